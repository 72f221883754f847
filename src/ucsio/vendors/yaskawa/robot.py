"""Yaskawa's robot positions for ``solve --robot``: a job's (.JBI) positions.

Each Cartesian position of the robot (``C`` and ``P`` rows under
``///RECTAN``) is the pose of the TCP of the tool its group names
(``///TOOL n``: ``UTn`` of TOOL.CND) in the frame its ``///POSTYPE`` names:

- ``BASE`` or ``ROBOT``: the robot's base. They differ only on a robot
  that rides a traveling base (a track), where BASE is the track's frame:
  ucsio takes both as the robot base, which holds for a robot without one;
- ``USER``: user frame ``///USER k`` (``UFk`` of UFRAME.CND, itself in the
  robot base, or on another user frame it names);
- ``TOOL`` and ``MTOOL`` (a tool's or the master robot's tool's frame),
  and joint pulses (``///PULSE``): refused where the measurement pairs them,
  with why (pulses need the robot's kinematics, which ucsio does not have).

The flange in the robot base is frame * position * tool^-1, with the tools
and user frames read from ``--config TOOL.CND`` and ``--config UFRAME.CND``
(Yaskawa's every tool, UT0 too, is a row of TOOL.CND: the file is needed for
any Cartesian position). A position that cannot be resolved carries its
problem, raised only if the point is paired: a job's other points do not
stop a measurement. The positions are read by ``job.positions``, the
reader ``frames`` and ``check`` use.
"""
from __future__ import annotations

import re

from ...errors import UcsioError
from ...geometry.frames import Pose
from ...parsing.document import Document
from ...parsing.model import ControllerFile
from ..common.robot import RobotPose, RobotPoses, few_names, matrix
from . import job

_GROUP1 = re.compile(r"^///GROUP1[ \t]+RB([0-9]+)\b", re.M)
_GROUP2 = re.compile(r"^///GROUP2\b", re.M)

# what each ///POSTYPE a job writes is in, where ucsio takes it
IN_BASE = ("BASE", "ROBOT")
NOT_A_FLANGE = {
    "TOOL": "a position in a tool's frame (///POSTYPE TOOL): an offset from the TCP, not "
            "where the robot was",
    "MTOOL": "a position in the master robot's tool (///POSTYPE MTOOL): it moves with the other "
             "robot, not a pose of this robot's flange",
}
PULSES = ("joint pulses (///PULSE): a flange pose from pulses needs the robot's kinematics, "
          "which ucsio does not have: record the point as a Cartesian position "
          "(///POSTYPE BASE or ROBOT)")


def read(vendor, path: str, configs, tool: str, wobj: str, load) -> RobotPoses:
    """A job's robot positions as flange poses in the robot base. ``configs``:
    the --config files (a TOOL.CND, and a UFRAME.CND for USER positions);
    ``tool`` and ``wobj`` are not asked: each group names its own."""
    if tool.strip().casefold() != "tool0" or wobj.strip().casefold() != "wobj0":
        raise UcsioError("--robot-tool and --robot-wobj name the frames of ABB's robtargets and "
                         "FANUC's registers; a Yaskawa job's positions name their own "
                         "(///TOOL n, ///USER k)", file=path)
    # read as check reads it: a binary, foreign or damaged file is refused alike
    cf = load(path)
    if cf.vendor != vendor.name or cf.extra.get("kind") != "job":
        raise UcsioError("not a Yaskawa job: --robot takes a job (.JBI) that begins /JOB",
                         file=path, line=1, col=1)
    doc = cf.document
    frames = _Frames(configs or (), load, vendor.name, job_robot(doc))
    poses = []
    named = job.names_by_comment(doc)
    for p in cf.extra["positions"]:
        if p.kind not in job.ROBOT_KINDS:
            continue                    # a base's or station's axes: not the robot's flange
        line, col = doc.line_col(p.at)
        if p.name in named:             # its comment names it; C00002 and C2 still pair
            rp = RobotPose(p.name, named[p.name], line, col, None, aliases=(p.name, p.point))
        else:
            rp = RobotPose(p.name, p.point, line, col, None, aliases=(p.name,))
        poses.append(rp)
        try:
            rp.flange = matrix(_flange(doc, p, frames))
        except UcsioError as exc:
            rp.problem = exc
    return RobotPoses(path, vendor.name, poses, vendor.name)


def _flange(doc: Document, p: job.Position, frames: "_Frames") -> Pose:
    """frame * position * tool^-1, or why not (an error at the position)."""
    if p.pulse:
        raise doc.error(f"{p.name}: {PULSES}", p.at)
    if p.postype in NOT_A_FLANGE:
        raise doc.error(f"{p.name}: {NOT_A_FLANGE[p.postype]}", p.at)
    x, y, z, rx, ry, rz = p.xyzabc()
    tcp = Pose.from_abc(x, y, z, rz, ry, rx)
    if p.postype == "USER":
        if p.user is None:
            raise doc.error(f"{p.name}: ///POSTYPE USER without a ///USER k before it: the "
                            "user frame it is in is not known", p.at)
        tcp = frames.user(p.user, doc, p).compose(tcp)
    elif p.postype not in IN_BASE:
        raise doc.error(f"{p.name}: no ///POSTYPE before it: the frame it is in is not known",
                        p.at)
    if p.tool is None:
        raise doc.error(f"{p.name}: no ///TOOL n before it: the tool it was taught with is not "
                        "known", p.at)
    return tcp.compose(frames.tool(p.tool, doc, p).inverse())


def job_robot(doc: Document) -> int | None:
    """The robot a job moves (``///GROUP1 RBn`` of its //INST); None where
    it names none or several groups move (``///GROUP2``)."""
    found = _GROUP1.findall(doc.text)
    if len(found) != 1 or _GROUP2.search(doc.text):
        return None
    return int(found[0])


class _Frames:
    """The tools (TOOL.CND) and user frames (UFRAME.CND) of ``--config``,
    each file loaded when first needed."""

    KINDS = {"UT": ("tools", "TOOL.CND", "tool"), "UF": ("user frames", "UFRAME.CND",
                                                        "user frame")}

    def __init__(self, configs, load, vendor: str, robot: int | None = None):
        self.configs, self.load, self.vendor = tuple(configs), load, vendor
        self.robot = robot          # the job's robot: a user frame of another is not its
        self.files: dict[str, ControllerFile] | None = None
        self.found: dict[str, Pose] = {}

    def _by_kind(self) -> dict[str, ControllerFile]:
        if self.files is None:
            self.files = {}
            for path in self.configs:
                cf = self.load(path)
                kind = cf.extra.get("kind") if cf.vendor == self.vendor else None
                if kind not in ("tools", "user frames"):
                    what = f"a {kind}" if kind else f"a {cf.vendor.upper()} file"
                    raise UcsioError("--config: a Yaskawa job's positions take TOOL.CND (its "
                                     f"tools) and UFRAME.CND (its user frames); this is {what}",
                                     file=path)
                if kind in self.files:
                    raise UcsioError(f"--config: two files of {kind} ({self.files[kind].path} "
                                     "and this one): give one", file=path)
                self.files[kind] = cf
        return self.files

    def tool(self, n: int, doc: Document, p: job.Position) -> Pose:
        return self._pose("UT", n, doc, p, f"///TOOL {n}")

    def user(self, k: int, doc: Document, p: job.Position) -> Pose:
        return self._pose("UF", k, doc, p, f"///USER {k}")

    def _pose(self, prefix: str, n: int, doc: Document, p: job.Position, said: str,
              through: tuple[str, ...] = ()) -> Pose:
        """UTn or UFn in the flange or the robot base (a user frame on another
        one through it: ``through`` the frames on the way, a cycle refused)."""
        name = f"{prefix}{n}"
        if name in self.found:
            return self.found[name]
        if name in through:
            raise doc.error(f"{p.name}: {said}: user frames defined on each other in a "
                            f"circle ({' on '.join(through + (name,))})", p.at)
        kind, file, what = self.KINDS[prefix]
        cf = self._by_kind().get(kind)
        if cf is None:
            raise doc.error(f"{p.name}: {said}: give --config {file}, the controller's {kind}",
                            p.at)
        frame = next((f for f in cf.frames if f.name == name), None)
        if frame is None:
            held = [f.name for f in cf.frames]
            raise doc.error(f"{p.name}: {said}, but {cf.path} does not hold {name} (its {kind}: "
                            f"{few_names(held) or 'none'})", p.at)
        pose = frame.pose
        parent = frame.parent
        if prefix == "UF" and parent.kind == "frame":        # a frame on another user frame
            pose = self._pose("UF", int(parent.name[2:]), doc, p, said,
                              through + (name,)).compose(pose)
        elif prefix == "UF" and parent.kind != "robot":
            raise doc.error(f"{p.name}: {said}, but {name} ({cf.path}:{frame.line}) is defined "
                            f"on the {parent.name} (///BASICFRM "
                            f"{frame.info.get('basicfrm')}), not on this robot's base",
                            p.at)
        elif prefix == "UF" and self.robot not in (None, frame.info.get("group", self.robot)):
            raise doc.error(f"{p.name}: {said}, but {name} ({cf.path}:{frame.line}) is robot "
                            f"{frame.info['group']}'s user frame (///GROUP) and this job moves "
                            f"RB{self.robot} (///GROUP1): its positions are not in that "
                            "robot's base", p.at)
        self.found[name] = pose
        return pose
