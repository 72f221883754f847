"""The orientations a measurement program gives the reflector where the TCP
is solved with the frame (``--tcp solve``): the spread that pins it down.

A TCP is determined only where the flange turns between points, about at
least two axes (docs/method.md, "The reflector's TCP"). ``program --measure
--spread DEG`` and ``plan --tcp solve`` without planned flange poses share
one pattern, so that the plan predicts exactly the program it leads to:
point k (in the plan's order) holds the tool as the base orientation does,
then turned by DEG/2 about the tool's own x axis, its y axis, -x, -y, and
round again. The largest angle between two points' orientations (the
``orientation_span`` solve and plan report) is DEG from the fourth point on.
The reflector stays on the planned point: the flange moves round it.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import UcsioError

#: the tool's axis each point turns about, in turn (None: not turned)
AXES = (None, (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (-1.0, 0.0, 0.0), (0.0, -1.0, 0.0))
#: the spreads ``plan`` tries, least first, where none is given (deg)
STEPS = tuple(range(5, 95, 5))
MOST = 90.0         # beyond it a reflector faces too far from the tracker to be seen


def check(spread: float) -> float:
    """--spread as a pattern can hold it: more than 0, at most MOST deg."""
    if not (math.isfinite(spread) and 0 < spread <= MOST):
        raise UcsioError(f"--spread {spread:g}: a turn of more than 0 and at most {MOST:g} deg")
    return spread


def tilts(n: int, spread: float) -> np.ndarray:
    """(n, 3, 3): point k's turn of the tool, applied after the base
    orientation (base @ tilts[k])."""
    half = math.radians(spread) / 2.0
    out = np.empty((n, 3, 3))
    for k in range(n):
        axis = AXES[k % len(AXES)]
        out[k] = np.eye(3) if axis is None else _turn(np.asarray(axis), half)
    return out


def _turn(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues' rotation by ``angle`` (rad) about the unit ``axis``."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]],
                  [-axis[1], axis[0], 0.0]])
    return np.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * (k @ k)


def flanges(laser: np.ndarray, spread: float) -> np.ndarray:
    """(n, 4, 4) flange poses that stand in for a plan's where none are
    given: the UCS taken as world and the reflector on the flange (the TCP's
    value and the base orientation change no prediction: each is a common
    rotation or offset of every point's), each turned by the pattern."""
    laser = np.asarray(laser, dtype=float)
    out = np.tile(np.eye(4), (len(laser), 1, 1))
    out[:, :3, :3] = tilts(len(laser), spread)
    out[:, :3, 3] = laser
    return out
