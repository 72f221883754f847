"""ABB's robot positions for ``solve --robot``: a module's robtargets.

Each is the pose of the TCP of ``--robot-tool`` (default tool0) in the
object frame of ``--robot-wobj`` (default wobj0): flange in world = uframe *
oframe * target * tframe^-1. The tool and work object are looked up in the
module, then in the modules of its folder, then in ``--config FILE``; tool0
and wobj0 are the controller's predefined identities where no file declares
them. The targets go through ``rapid.robtargets``: the same grammar as
``frames``; a target that cannot be resolved carries its problem, raised
only if the point is paired. ``load`` (passed in by the front) reads the
module and the files it searches, of any vendor, as every command does.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ... import vendors
from ...errors import UcsioError
from ...geometry.arrays import flange_matrices
from ...geometry.frames import Pose
from ..common.robot import RobotPose, RobotPoses, matrix
from .rapid import robtargets


def read(vendor, path: str, config: str | None, tool: str, wobj: str, load) -> RobotPoses:
    """A module's robtargets as flange poses in world, in ``vendor``'s
    convention (the package's VENDOR, handed in: this module does not import
    its package back)."""
    cf = load(path, full=True)
    targets = robtargets(cf)
    lookup = _AbbLookup(cf, config, load, vendors.BY_NAME[vendor.name].suffixes)
    tool_pose = lookup.tool(tool)
    uframe, oframe = lookup.wobj(wobj)
    identity = tool_pose is None and uframe is None and oframe is None
    poses = []
    for t in targets:
        rp = RobotPose(t.name, t.name, t.line, t.col, None, t.problem)
        poses.append(rp)
        if t.pose is None:
            continue
        if identity:     # tool0 in wobj0: the numbers as written, as the CSV reads them
            rp.flange = flange_matrices(vendor.angles, np.array([t.pose.q]),
                                        np.array([t.pose.t]))[0]
            continue
        flange = t.pose
        for outer in (oframe, uframe):
            if outer is not None:
                flange = outer.compose(flange)
        if tool_pose is not None:
            flange = flange.compose(tool_pose.inverse())
        rp.flange = matrix(flange)
    return RobotPoses(path, vendor.name, poses, vendor.name, lookup.warnings)


class _AbbLookup:
    """tooldata and wobjdata by name: the module, its folder, --config."""

    def __init__(self, cf, config: str | None, load, modules: tuple[str, ...]):
        self.cf = cf
        self.config, self.load = config, load
        self.modules = modules          # the suffixes of the modules beside it
        self.warnings: list[str] = []
        self._files = None

    def _sources(self):
        if self._files is None:
            load = self.load
            here = Path(self.cf.path)
            files = [self.cf]
            try:
                siblings = sorted(p for p in here.parent.iterdir()
                                  if p.suffix.lower() in self.modules and p.is_file()
                                  and p.resolve() != here.resolve())
            except OSError:
                siblings = []
            for p in siblings:
                try:
                    files.append(load(p))
                except UcsioError as exc:
                    self.warnings.append(f"could not read {p.name} while looking for the tool "
                                         f"and work object: {exc.message}")
            if self.config is not None:
                files.append(load(self.config))
            self._files = files
        return self._files

    def _find(self, name: str, type_: str):
        for cf in self._sources():
            found = [f for f in cf.frames if f.name.casefold() == name.casefold()
                     and f.type == type_]
            if found:
                return found[0]
        return None

    def tool(self, name: str) -> Pose | None:
        f = self._find(name, "tooldata")
        if f is None:
            if name.casefold() == "tool0":
                return None
            raise UcsioError(f"--robot-tool {name}: no tooldata of that name in {self.cf.path}, "
                             "the modules of its folder" + (f" or {self.config}" if self.config
                                                            else " (--config FILE names another)"))
        if f.info.get("robhold") is False:
            raise UcsioError(f"--robot-tool {name}: a stationary tool (robhold FALSE); its "
                             "robtargets are not flange poses", file=f.file, line=f.line)
        if f.pose is None:
            raise UcsioError(f"--robot-tool {name}: no literal value", file=f.file, line=f.line)
        return f.pose

    def wobj(self, name: str) -> tuple[Pose | None, Pose | None]:
        f = self._find(name, "wobjdata")
        if f is None:
            if name.casefold() == "wobj0":
                return None, None
            raise UcsioError(f"--robot-wobj {name}: no wobjdata of that name in {self.cf.path}, "
                             "the modules of its folder" + (f" or {self.config}" if self.config
                                                            else " (--config FILE names another)"))
        o = self._find(name + ".oframe", "wobjdata")
        if f.info.get("robhold"):
            raise UcsioError(f"--robot-wobj {name}: held by the robot (robhold TRUE); its "
                             "robtargets are not flange poses in world", file=f.file, line=f.line)
        if f.info.get("ufprog") is False:
            raise UcsioError(f"--robot-wobj {name}: a moving user frame (ufprog FALSE)",
                             file=f.file, line=f.line)
        if f.pose is None or o is None or o.pose is None:
            raise UcsioError(f"--robot-wobj {name}: no literal value", file=f.file, line=f.line)
        return f.pose, o.pose
