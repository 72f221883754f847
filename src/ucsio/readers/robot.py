"""The robot side: where the flange was at each point, in robot world.

- ``spec_csv``: SPEC's CSV with ``point`` and the ``robot_*`` columns, read
  by ``measurement.py`` itself.
- ``kuka_dat``: a program ``.dat`` (the measurement program's data list).
  Each E6POS/POS/FRAME is the pose of ``$TOOL`` in ``$BASE``, named by its
  FDAT's TOOL_NO and BASE_NO; the flange in world is base * position *
  tool^-1, with TOOL_DATA[n] and BASE_DATA[n] read from ``--config
  $config.dat`` (needed where either number is not 0; 0 is the flange, and
  the world).
- ``abb_module``: a module's robtargets, each the pose of the TCP of
  ``--robot-tool`` (default tool0) in the object frame of ``--robot-wobj``
  (default wobj0): flange in world = uframe * oframe * target * tframe^-1.
  The tool and work object are looked up in the module, then in the modules
  of its folder, then in ``--config FILE``; tool0 and wobj0 are the
  controller's predefined identities where no file declares them.

Controller files go through ``krl.positions`` and ``rapid.robtargets``: the
same grammars as ``frames``. Pose algebra is ``frames.Pose``'s. A position
that cannot be resolved (its tool or base unknown or not a plain one, a value
that is not literal) carries its problem, raised only if the point is paired:
a program's other data do not stop a measurement.
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import UcsioError
from ..geometry.frames import Pose
from ..parsing.controller import ABB_SUFFIXES

KUKA_SUFFIXES = {".dat"}


@dataclass
class RobotPose:
    name: str                       # as written: 'XP1', 'pMeas3', 'P1'
    point: str                      # the name it pairs by: 'P1' for KUKA's XP1
    line: int | None
    col: int | None
    flange: np.ndarray | None       # (4, 4) flange pose in robot world
    problem: UcsioError | None = None
    note: str | None = None         # an assumption made, said once paired ("no FDAT ...")


@dataclass
class RobotPoses:
    path: str
    format: str                     # 'csv' | 'kuka' | 'abb'
    poses: list[RobotPose]
    form: str                       # orientation form: 'kuka' | 'abb' | 'fanuc'
    warnings: list[str] = field(default_factory=list)


def read_robot(path: str | os.PathLike, *, config: str | None = None, tool: str = "tool0",
               wobj: str = "wobj0") -> RobotPoses:
    """The robot side, by the file's kind: a KUKA .dat, an ABB module, else
    SPEC's CSV."""
    path = os.fspath(path)
    suffix = Path(path).suffix.lower()
    if suffix in KUKA_SUFFIXES:
        return kuka_dat(path, config)
    if suffix in ABB_SUFFIXES:
        return abb_module(path, tool, wobj, config)
    return spec_csv(path)


def _matrix(pose: Pose) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = pose.matrix
    T[:3, 3] = pose.t
    return T


# ---------------------------------------------------------------- CSV

def spec_csv(path: str) -> RobotPoses:
    from ..method.measurement import read_measurement

    m = read_measurement(path, sides=("robot",), what="robot file")
    poses = [RobotPose(n, n, ln, None, m.flange[i]) for i, (n, ln) in
             enumerate(zip(m.names, m.lines))]
    return RobotPoses(path, "csv", poses, m.form)


# ---------------------------------------------------------------- KUKA

def kuka_dat(path: str, config: str | None) -> RobotPoses:
    from ..parsing.controller import load
    from ..parsing.document import Document
    from ..parsing.krl import positions
    from ..geometry.arrays import flange_matrices

    doc = Document.read(path)
    cfg = None
    poses = []
    warnings: list[str] = []
    for p in positions(doc):
        rp = RobotPose(p.name, p.point, p.line, p.col, None)
        poses.append(rp)
        if p.pose is None:
            rp.problem = p.problem
            continue
        if p.fdat is None:
            rp.note = "no FDAT: taken as the flange in world (TOOL_NO 0, BASE_NO 0)"
        where = {"file": path, "line": p.line, "col": p.col}
        if p.ipo_frame == "#TCP":
            rp.problem = UcsioError(f"{p.name}: IPO_FRAME #TCP in {p.fdat}: taught with an "
                                    "external (fixed) TCP, not a flange pose", **where)
            continue
        tool_no, base_no = p.tool_no or 0, p.base_no or 0
        if not tool_no and not base_no:
            x, y, z = p.pose.t
            # the numbers as written, through the same conversion as the CSV
            rp.flange = flange_matrices("kuka", np.array([p.pose.abc]), np.array([[x, y, z]]))[0]
            continue
        if config is None:
            rp.problem = UcsioError(f"{p.name}: TOOL_NO {tool_no}, BASE_NO {base_no} in "
                                    f"{p.fdat}: give --config $config.dat, the controller's "
                                    "TOOL_DATA and BASE_DATA", **where)
            continue
        if cfg is None:
            cfg = load(config)
        try:
            flange = p.pose
            if base_no:
                flange = _kuka_entry(cfg, "BASE", base_no, p.name).compose(flange)
            if tool_no:
                flange = flange.compose(_kuka_entry(cfg, "TOOL", tool_no, p.name).inverse())
        except UcsioError as exc:
            rp.problem = UcsioError(exc.message, **where)
            continue
        rp.flange = _matrix(flange)
    return RobotPoses(path, "kuka", poses, "kuka", warnings)


def _kuka_entry(cfg, kind: str, n: int, who: str) -> Pose:
    """TOOL_DATA[n] (in the flange) or BASE_DATA[n] (in world) of $config.dat,
    refused where it is not that: an external TCP, a base on an external
    kinematic, an entry without a value."""
    name = f"{kind}_DATA[{n}]"
    found = [f for f in cfg.frames if f.name.upper() == name]
    if not found:
        raise UcsioError(f"{who}: {kind}_NO {n}, but {cfg.path} has no {name}")
    f = found[0]
    want = "flange" if kind == "TOOL" else "world"
    if f.reference != want or f.info.get("role") not in ("tool", "base"):
        raise UcsioError(f"{who}: {kind}_NO {n}: {name} ({cfg.path}:{f.line}) is "
                         f"{f.info.get('role') or f.reference} relative to {f.reference}, not a "
                         f"plain {'robot-held tool' if kind == 'TOOL' else 'base in world'}")
    if f.pose is None:
        raise UcsioError(f"{who}: {kind}_NO {n}: {name} ({cfg.path}:{f.line}) has no complete "
                         "value")
    return f.pose


def _names(names: list[str], most: int = 8) -> str:
    shown = ", ".join(names[:most])
    return shown + (f" and {len(names) - most} more" if len(names) > most else "")


# ---------------------------------------------------------------- ABB

def abb_module(path: str, tool: str, wobj: str, config: str | None) -> RobotPoses:
    from ..parsing.controller import parse
    from ..parsing.document import Document
    from ..geometry.arrays import flange_matrices
    from ..parsing.rapid import robtargets

    cf = parse(Document.read(path), full=True)
    targets = robtargets(cf)
    lookup = _AbbLookup(cf, config)
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
            rp.flange = flange_matrices("abb", np.array([t.pose.q]), np.array([t.pose.t]))[0]
            continue
        flange = t.pose
        for outer in (oframe, uframe):
            if outer is not None:
                flange = outer.compose(flange)
        if tool_pose is not None:
            flange = flange.compose(tool_pose.inverse())
        rp.flange = _matrix(flange)
    return RobotPoses(path, "abb", poses, "abb", lookup.warnings)


class _AbbLookup:
    """tooldata and wobjdata by name: the module, its folder, --config."""

    def __init__(self, cf, config: str | None):
        self.cf = cf
        self.config = config
        self.warnings: list[str] = []
        self._files = None

    def _sources(self):
        if self._files is None:
            from ..parsing.controller import load

            here = Path(self.cf.path)
            files = [self.cf]
            try:
                siblings = sorted(p for p in here.parent.iterdir()
                                  if p.suffix.lower() in ABB_SUFFIXES and p.is_file()
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
