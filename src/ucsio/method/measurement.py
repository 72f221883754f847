"""A measurement: laser tracker points paired with robot flange poses, as
the method takes it. ``readers.measurement`` reads SPEC's CSV into one; the
other readers (tracker exports with the robot's own positions) pair theirs
into the same."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def spec_orientation(convention, orientation: np.ndarray, angle_units: str = "deg",
                     quaternion_order: str = "wxyz") -> np.ndarray:
    """The orientation columns as written in ``convention`` (a
    ``geometry.angles.AngleColumns``) -> SPEC's reading: degrees, and
    quaternions with the real part first."""
    if convention.quaternion:
        return orientation[:, [3, 0, 1, 2]] if quaternion_order == "xyzw" else orientation
    return np.degrees(orientation) if angle_units == "rad" else orientation


@dataclass
class Measurement:
    """n point pairs. ``flange`` holds the flange poses as (n, 4, 4)
    homogeneous matrices in robot world."""

    path: str
    names: list[str]
    lines: list[int]
    laser: np.ndarray        # (n, 3) mm, in the UCS (None: a robot-side file)
    flange: np.ndarray       # (n, 4, 4) flange pose in robot world (None: a laser-side file)
    weights: np.ndarray      # (n,)
    form: str                # the orientation's vendor (its name: 'kuka', ...; 'none': laser only)
    orientation: np.ndarray  # (n, 3) or (n, 4) as written ((n, 0): not from a CSV)

    def __len__(self) -> int:
        return len(self.names)

    def robot_points(self, tcp=(0.0, 0.0, 0.0)) -> np.ndarray:
        """(n, 3): each flange pose applied to the TCP (reflector) offset,
        given in flange coordinates."""
        tcp = np.asarray(tcp, dtype=float).reshape(3)
        return self.flange[:, :3, :3] @ tcp + self.flange[:, :3, 3]
