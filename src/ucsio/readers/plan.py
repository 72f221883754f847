"""A plan's points (``plan`` and ``program --measure`` read them alike):
PLAN.csv's names and laser positions, and the planned flange poses where
it or ``--robot`` gives them (``method.plan.Planned``)."""
from __future__ import annotations

import os

from ..errors import UcsioError


def read_plan(plan, joint: bool, *, robot=None, config=None, map=None,
              robot_tool: str = "tool0", robot_wobj: str = "wobj0", laser_units: str = "mm"):
    """(method.plan.Planned, warnings) from PLAN.csv and --robot, the laser
    coordinates in mm."""
    import numpy as np

    from ..method.plan import Planned
    from .text import content_lines, read_text

    plan = os.fspath(plan)
    text = read_text(plan, "plan file")
    has_robot = any("robot_x" in line.lower() for _, line in content_lines(text)[:2])
    warnings: list[str] = []
    if has_robot and robot is not None:
        raise UcsioError("the plan has robot_* columns and --robot is given: plan the flange "
                         "poses once", file=plan)
    for opt, given in (("--config", config), ("--map", map)):
        if given is not None and robot is None:
            raise UcsioError(f"{opt} goes with --robot")
    from ..defaults import LENGTH_UNITS
    from . import laser
    if laser_units not in LENGTH_UNITS:
        raise UcsioError(f"--laser-units {laser_units!r}: expected one of "
                         f"{', '.join(LENGTH_UNITS)}")
    if has_robot:
        from .measurement import parse_measurement
        m = parse_measurement(text, plan)
        return (Planned(plan, m.names, m.lines, m.laser * LENGTH_UNITS[laser_units], m.weights,
                        m.flange), warnings)
    lp = laser.read_laser(plan, laser_units)
    if robot is None:
        return Planned(plan, lp.names, lp.lines, lp.xyz, lp.weights), list(lp.warnings)
    if not joint:
        warnings.append("--robot: the planned flange poses matter only with --tcp solve (a "
                        "known TCP's frame error does not depend on them); not read")
        return Planned(plan, lp.names, lp.lines, lp.xyz, lp.weights), warnings
    from . import pairing, robot as robots
    rp = robots.read_robot(robot, config=config, tool=robot_tool, wobj=robot_wobj)
    mapping = pairing.read_map(map) if map else ()
    m, more = pairing.pair(lp, rp, mapping, map)
    return (Planned(plan, m.names, m.lines, m.laser, m.weights,
                    np.asarray(m.flange, dtype=float)), warnings + more)
