"""Pairing the two sides by point name (SPEC: Measurements where they live).

Names match case-insensitively. A robot position also answers to its point
name (KUKA's ``XP1`` to ``P1``; a FANUC ``P[3]`` to its comment), then to
its aliases (FANUC's ``P3``, ``PR16``), but its own name wins, and a point
name wins over an alias. ``--map FILE`` is a
CSV of ``laser,robot`` name pairs (a header row ``laser,robot`` is allowed)
for anything else; mapped names take part in nothing else. Unpaired names
on either side are warnings; fewer than three pairs is an error. The result
is the ``Measurement`` a merged CSV of the same numbers gives, in the laser
file's order.
"""
from __future__ import annotations

import os

import numpy as np

from ..errors import UcsioError
from ..vendors.common.robot import RobotPoses, few_names
from .laser import LaserPoints
from .text import content_lines, read_text, split

MIN_PAIRS = 3


def read_map(path: str | os.PathLike) -> list[tuple[str, str, int]]:
    """(laser name, robot name, line) from a --map CSV."""
    path = os.fspath(path)
    rows = content_lines(read_text(path, "map file"))
    out = []
    for k, (lineno, line) in enumerate(rows):
        sep = ";" if ";" in line else ("\t" if "\t" in line else ",")
        fields = split(line, sep)
        if k == 0 and [f.casefold() for f, _ in fields[:2]] == ["laser", "robot"]:
            continue
        if len(fields) != 2 or not fields[0][0] or not fields[1][0]:
            raise UcsioError("expected two names: laser,robot", file=path, line=lineno)
        out.append((fields[0][0], fields[1][0], lineno))
    return out


def pair(laser: LaserPoints, robot: RobotPoses, mapping=(), map_path: str | None = None):
    """(Measurement, warnings)."""
    from ..method.measurement import Measurement

    by_name: dict[str, list[int]] = {}
    by_point: dict[str, list[int]] = {}
    by_alias: dict[str, list[int]] = {}
    for k, rp in enumerate(robot.poses):
        by_name.setdefault(rp.name.casefold(), []).append(k)
        by_point.setdefault(rp.point.casefold(), []).append(k)
        for alias in rp.aliases:
            by_alias.setdefault(alias.casefold(), []).append(k)

    def robot_index(name: str, where: dict) -> int | None:
        for table in (by_name, by_point, by_alias):
            hits = table.get(name.casefold(), [])
            if len(hits) > 1:
                which = ", ".join(f"{robot.poses[k].name} (line {robot.poses[k].line})"
                                  for k in hits)
                raise UcsioError(f"point {name!r} matches several robot positions: {which}; "
                                 "pair it with --map", **where)
            if hits:
                return hits[0]
        return None

    laser_index = {n.casefold(): i for i, n in enumerate(laser.names)}
    partner: dict[int, int] = {}       # laser index -> robot index
    taken: dict[int, int] = {}         # robot index -> laser index
    for lname, rname, lineno in mapping:
        where = {"file": map_path, "line": lineno}
        i = laser_index.get(lname.casefold())
        if i is None:
            raise UcsioError(f"--map: no laser point {lname!r} in {laser.path}", **where)
        k = robot_index(rname, where)
        if k is None:
            raise UcsioError(f"--map: no robot position {rname!r} in {robot.path}", **where)
        if i in partner or k in taken:
            raise UcsioError(f"--map: {lname if i in partner else rname!r} is paired twice",
                             **where)
        partner[i], taken[k] = k, i
    mapped_robot = set(taken)
    for i, name in enumerate(laser.names):
        if i in partner:
            continue
        k = robot_index(name, {"file": laser.path, "line": laser.lines[i]})
        if k is None or k in mapped_robot:
            continue
        if k in taken:
            other = laser.names[taken[k]]
            raise UcsioError(f"laser points {other!r} and {name!r} both pair with robot "
                             f"position {robot.poses[k].name}; pair them with --map",
                             file=laser.path, line=laser.lines[i])
        partner[i], taken[k] = k, i

    warnings = list(laser.warnings) + list(robot.warnings)
    lone_laser = [n for i, n in enumerate(laser.names) if i not in partner]
    lone_robot = [rp.name for k, rp in enumerate(robot.poses) if k not in taken]
    if lone_laser:
        warnings.append(f"laser points without a robot position: {few_names(lone_laser)}")
    if lone_robot:
        warnings.append(f"robot positions without a laser point: {few_names(lone_robot)}")
    if len(partner) < MIN_PAIRS:
        raise UcsioError(f"only {len(partner)} point{'s' if len(partner) != 1 else ''} pair by "
                         f"name between {laser.path} ({few_names(laser.names, 5)}) and "
                         f"{robot.path} "
                         f"({few_names([p.name for p in robot.poses], 5)}); at least {MIN_PAIRS} "
                         "needed (--map FILE pairs other names)")
    order = sorted(partner)
    flange = []
    notes: dict[str, list[str]] = {}
    for i in order:
        rp = robot.poses[partner[i]]
        if rp.problem is not None:
            raise rp.problem
        flange.append(rp.flange)
        if rp.note:
            notes.setdefault(rp.note, []).append(rp.name)
    warnings.extend(f"{', '.join(names)}: {note}" for note, names in notes.items())
    written = [robot.poses[partner[i]].written for i in order]
    orientation = (np.array(written) if all(w is not None for w in written)
                   else np.empty((len(order), 0)))       # a controller's file: as it says
    meas = Measurement(path=laser.path, names=[laser.names[i] for i in order],
                       lines=[laser.lines[i] for i in order], laser=laser.xyz[order].copy(),
                       flange=np.array(flange, dtype=float), weights=laser.weights[order].copy(),
                       form=robot.form, orientation=orientation)
    return meas, warnings
