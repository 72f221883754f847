"""What every vendor's reader of robot positions (``solve --robot``) shares:
the poses it returns, and the helpers it builds them with.

``readers.robot`` picks a vendor's reader by the file's suffix (the vendor's
``robot_positions``) and reads SPEC's CSV itself; the readers import this
module, never that one.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...errors import UcsioError
from ...geometry.frames import Pose


@dataclass
class RobotPose:
    name: str                       # as written: 'XP1', 'pMeas3', 'P1'
    point: str                      # the name it pairs by: 'P1' for KUKA's XP1
    line: int | None
    col: int | None
    flange: np.ndarray | None       # (4, 4) flange pose in robot world
    problem: UcsioError | None = None
    note: str | None = None         # an assumption made, said once paired ("no FDAT ...")
    aliases: tuple[str, ...] = ()   # names it answers to after ``point`` (FANUC's P3 for P[3])
    written: np.ndarray | None = None   # a CSV's orientation columns as written


@dataclass
class RobotPoses:
    path: str
    format: str                     # 'csv', or the vendor whose file it is ('kuka', ...)
    poses: list[RobotPose]
    form: str                       # the orientation's vendor ('kuka', ...): its convention
    warnings: list[str] = field(default_factory=list)


def matrix(pose: Pose) -> np.ndarray:
    """A pose as a 4x4 homogeneous matrix."""
    T = np.eye(4)
    T[:3, :3] = pose.matrix
    T[:3, 3] = pose.t
    return T


def few_names(names: list[str], most: int = 8) -> str:
    """The first ``most`` names, and how many more."""
    shown = ", ".join(names[:most])
    return shown + (f" and {len(names) - most} more" if len(names) > most else "")
