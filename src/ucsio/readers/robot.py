"""The robot side: where the flange was at each point, in robot world.

A controller's file goes to its vendor's reader of robot positions (the
vendor's ``robot_positions``, for the suffixes it lists in
``robot_suffixes``: ``vendors/<name>/robot.py`` says what each reads and
how); any other file is SPEC's CSV with ``point`` and the ``robot_*``
columns, read by ``measurement.py`` itself. A position that cannot be
resolved carries its problem, raised only if the point is paired: a
program's other data do not stop a measurement. The records are
``vendors.common.robot``'s.
"""
from __future__ import annotations

import os
from pathlib import Path

from .. import vendors
from ..errors import UcsioError
from ..vendors.common.robot import RobotPose, RobotPoses


def read_robot(path: str | os.PathLike, *, config: str | None = None, tool: str = "tool0",
               wobj: str = "wobj0", angle_units: str = "deg",
               quaternion_order: str = "wxyz") -> RobotPoses:
    """The robot side, by the file's kind: a KUKA .dat, an ABB module, a
    FANUC TP program (.ls) or posreg.va, else SPEC's CSV. Only a CSV can be
    written in radians or with the quaternion's real part last: a
    controller's own files say how they are written."""
    path = os.fspath(path)
    vendor = _positions_vendor(Path(path).suffix.lower())
    if vendor is not None:
        from ..parsing.controller import load
        return vendor.robot_positions(path, config=_configs(vendor, config), tool=tool,
                                      wobj=wobj, load=load)
    return spec_csv(path, angle_units=angle_units, quaternion_order=quaternion_order)


def _configs(vendor, config):
    """``--config`` as the vendor's reader takes it: one path (or None), or,
    where it takes several (Yaskawa's TOOL.CND and UFRAME.CND), a tuple."""
    given = [] if config is None else [config] if isinstance(config, (str, os.PathLike)) \
        else list(config)
    given = [os.fspath(c) for c in given]
    if vendor.robot_configs > 1:
        return tuple(given)
    if len(given) > 1:
        raise UcsioError(f"--config given {len(given)} times: {vendor.title}'s positions take "
                         "one file")
    return given[0] if given else None


def _positions_vendor(suffix: str):
    """The vendor whose reader of robot positions takes files ending so, or None."""
    for entry in vendors.VENDORS:
        if suffix in entry.suffixes:
            vendor = vendors.get(entry.name)
            if vendor.robot_positions is not None and suffix in vendor.robot_suffixes:
                return vendor
    return None


# ---------------------------------------------------------------- CSV

def spec_csv(path: str, **reading) -> RobotPoses:
    from .measurement import read_measurement

    m = read_measurement(path, sides=("robot",), what="robot file", **reading)
    poses = [RobotPose(n, n, ln, None, m.flange[i], written=m.orientation[i])
             for i, (n, ln) in enumerate(zip(m.names, m.lines))]
    return RobotPoses(path, "csv", poses, m.form)
