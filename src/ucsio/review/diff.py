"""Differences between frames: simulated vs measured, and old vs new files.

Definitions are SPEC's: delta = measured - simulated; da, db, dc wrapped to
(-180, 180]; ``angle`` the single rotation between the orientations; ``dist``
|t_measured - t_simulated|; ``dt_mean`` (|dx| + |dy| + |dz|) / 3; groups by
dt_mean (1 below 10 mm, 2 below 25, 3 below 50, 4 below 100, 5 from 100 on);
a frame passes when dt_mean is below the tolerance.
"""
from __future__ import annotations

import math

from .. import defaults
from ..geometry.frames import Pose
from ..geometry.rotations import abc_in_range, nearest_abc, quat_angle, wrap180

DEFAULT_TOLERANCE = defaults.TOLERANCE
GROUP_BOUNDS = (10.0, 25.0, 50.0, 100.0)   # mm; group k is below GROUP_BOUNDS[k-1]
# deg: a quarter of KUKA's written step (a vendor's same_rotation_tolerance)
SAME_ROTATION = 2.5e-5


def group_of(dt_mean: float) -> int:
    for k, bound in enumerate(GROUP_BOUNDS, 1):
        if dt_mean < bound:
            return k
    return len(GROUP_BOUNDS) + 1


def frame_delta(simulated: Pose, measured: Pose, tolerance: float = DEFAULT_TOLERANCE,
                same_rotation: float = SAME_ROTATION) -> dict:
    """SPEC's delta. da, db, dc are between the simulated angles in SPEC's
    ranges (a file that writes A 200, B 100, C -181 must not show +180 deg
    on two axes) and the measured rotation's triple nearest them, as patch
    writes it (``rotations.nearest_abc``, within ``same_rotation`` deg: at
    B = +-90, a 0.01 deg correction is a 0.01 deg delta, not a 175 deg
    rewrite of A and C)."""
    dx, dy, dz = measured.x - simulated.x, measured.y - simulated.y, measured.z - simulated.z
    old = abc_in_range(simulated.abc, simulated.q)
    new = nearest_abc(measured.q, old, same_rotation)
    da, db, dc = (wrap180(m - s) for m, s in zip(new, old))
    dt_mean = (abs(dx) + abs(dy) + abs(dz)) / 3.0
    return {
        "simulated": simulated.as_dict(),
        "measured": measured.as_dict(),
        "dx": dx, "dy": dy, "dz": dz,
        "da": da, "db": db, "dc": dc,
        "angle": quat_angle(simulated.q, measured.q),
        "dist": math.sqrt(dx * dx + dy * dy + dz * dz),
        "dt_mean": dt_mean,
        "group": group_of(dt_mean),
        "pass": dt_mean < tolerance,
        "tolerance": tolerance,
    }
