"""Stäubli's robot positions for ``solve --robot``: a .dtx's points.

A point (s7/CS9 ``pointRx``, CS8 ``<point>`` with ``<tpValue>``) is a
Cartesian position: the pose of a tool's TCP in its father frame
(``fatherId``, ``pFather``: world or a frame of the file, itself on world
or on other frames). The file does not say which tool was active when it
was taught, so ucsio assumes the one ``--robot-tool`` names (a tool of the
same .dtx; the default ``tool0`` is the flange itself), and says so beside
the pairing. The flange in world is then father * point * tool^-1, the
frames and tools composed up the file's tree. Orientations rest on ucsio's
reading of rx, ry, rz (``convention``: R = Rx·Ry·Rz, not proved);
positions with the flange as the tool do not. A point that cannot be
resolved carries its problem, raised only if the point is paired.
"""
from __future__ import annotations

from ...errors import UcsioError
from ...geometry.frames import Pose
from ..common.robot import RobotPose, RobotPoses, few_names, matrix
from .convention import READING, xyz_to_quat
from .dtx import shown
from .entries import father_parent

FLANGE_NAMES = ("tool0", "flange")


def read(vendor, path: str, config, tool: str, wobj: str, load) -> RobotPoses:
    if wobj.strip().casefold() != "wobj0":
        raise UcsioError("--robot-wobj names ABB's work object; a Stäubli point names its own "
                         "father frame (fatherId, pFather)", file=path)
    cf = load(path)
    if cf.vendor != vendor.name:
        raise UcsioError("not a Stäubli .dtx: --robot takes a VAL3 data file", file=path)
    frames = {f.name: f for f in cf.frames}
    tcp, said = _tool(cf, frames, tool, path)
    note = (f"each point is taken as the TCP of {said} in its father frame (a .dtx does not say "
            f"which tool taught it); rx, ry, rz read as {READING}")
    poses = []
    doc = cf.document
    for e in cf.extra["points"]:
        line, col = doc.line_col(e.at)
        rp = RobotPose(e.name, e.name, line, col, None, note=note)
        poses.append(rp)
        try:
            x, y, z, rx, ry, rz = e.values()
            point = Pose.from_quat(x, y, z, xyz_to_quat(rx, ry, rz))
            rp.flange = matrix(_in_world(cf, frames, e).compose(point).compose(tcp.inverse()))
        except UcsioError as exc:
            rp.problem = exc
    return RobotPoses(path, vendor.name, poses, vendor.name)


def _tool(cf, frames, tool: str, path: str) -> tuple[Pose, str]:
    """The TCP in the flange of ``--robot-tool`` (a tool of the file, up its
    fathers), and how the note names it."""
    name = tool.strip()
    if name.casefold() in FLANGE_NAMES:
        return Pose.from_quat(0, 0, 0, (1.0, 0.0, 0.0, 0.0)), "the flange (--robot-tool tool0)"
    frame = frames.get(name)
    if frame is None or frame.type != "tool":
        held = [f.name for f in cf.frames if f.type == "tool"]
        raise UcsioError(f"--robot-tool {name}: not a tool of this file (its tools: "
                         f"{few_names(held) or 'none'}; tool0 is the flange)", file=path)
    return _chain(cf, frames, frame, "flange"), f"tool {name}"


def _in_world(cf, frames, e) -> Pose:
    """The father frame of point ``e`` in world."""
    parent = father_parent(e, frames)
    if parent.kind == "world":
        return Pose.from_quat(0, 0, 0, (1.0, 0.0, 0.0, 0.0))
    frame = frames.get(parent.name) if parent.kind == "frame" else None
    if frame is None or frame.type != "frame":
        raise cf.document.error(f"{shown(e.name)}: its father {shown(parent.name)} is not a "
                                "frame of this file: where the point is in world is not known",
                                e.at)
    return _chain(cf, frames, frame, "world")


def _chain(cf, frames, frame, root: str) -> Pose:
    """``frame`` in ``root`` (world or the flange), through its fathers."""
    pose, seen = frame.pose, [frame.name]
    parent = frame.parent
    while parent.kind == "frame":
        up = frames.get(parent.name)
        if up is None or parent.name in seen:
            raise cf.document.error(f"{shown(frame.name)}: its fathers do not reach {root} "
                                    f"({shown(' on '.join(seen), 120)})",
                                    cf.document.line_starts[frame.line - 1])
        seen.append(up.name)
        pose = up.pose.compose(pose)
        parent = up.parent
    if parent.kind != root:
        raise cf.document.error(f"{shown(frame.name)}: hangs from {shown(parent.name)}, not "
                                f"{root}",
                                cf.document.line_starts[frame.line - 1])
    return pose
