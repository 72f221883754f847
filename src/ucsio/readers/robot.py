"""The robot side: where the flange was at each point, in robot world.

- ``spec_csv``: SPEC's CSV with ``point`` and the ``robot_*`` columns, read
  by ``measurement.py`` itself.
- ``kuka_dat``: a program ``.dat`` (the measurement program's data list).
  Each E6POS/POS/FRAME is the pose of ``$TOOL`` in ``$BASE``, named by its
  FDAT's TOOL_NO and BASE_NO; the flange in world is base * position *
  tool^-1, with TOOL_DATA[n] and BASE_DATA[n] read from ``--config
  $config.dat`` (needed where either number is not 0; 0 is the flange, and
  the world).
- ``fanuc_program``: a TP program's /POS positions (.ls). Each Cartesian
  position is the TCP of tool frame UT[t] in user frame UF[u], as its GP1
  says (``UF : u, UT : t``): the flange in world is UF[u] * P * UT[t]^-1,
  with group 1's frames read from ``--config sysframe.va`` (needed where u
  or t is not 0; UF 0 is world, UT 0 the faceplate). Named ``P[3]``; it
  also pairs by its comment, then as ``P3``.
- ``fanuc_registers``: posreg.va's Cartesian position registers of group 1
  (``PR[16]``, pairing also by comment, then ``PR16``). A register does not
  record the frames it was taken in: UF and UT are ``--robot-wobj UFk`` and
  ``--robot-tool UTk`` (default UF 0 and UT 0: the flange in world, said
  once paired), read as for a program. Uninitialized registers are left
  out.
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
from ..vendors import BY_NAME

KUKA_SUFFIXES = {".dat"}
FANUC_SUFFIXES = {".ls", ".va"}


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
    format: str                     # 'csv' | 'kuka' | 'abb' | 'fanuc'
    poses: list[RobotPose]
    form: str                       # orientation form: 'kuka' | 'abb' | 'fanuc'
    warnings: list[str] = field(default_factory=list)


def read_robot(path: str | os.PathLike, *, config: str | None = None, tool: str = "tool0",
               wobj: str = "wobj0", angle_units: str = "deg",
               quaternion_order: str = "wxyz") -> RobotPoses:
    """The robot side, by the file's kind: a KUKA .dat, an ABB module, a
    FANUC TP program (.ls) or posreg.va, else SPEC's CSV. Only a CSV can be
    written in radians or with the quaternion's real part last: a
    controller's own files say how they are written."""
    path = os.fspath(path)
    suffix = Path(path).suffix.lower()
    if suffix in KUKA_SUFFIXES:
        return kuka_dat(path, config)
    if suffix == ".ls":
        return fanuc_program(path, config, tool, wobj)
    if suffix == ".va":
        return fanuc_registers(path, config, tool, wobj)
    if suffix in BY_NAME["abb"].suffixes:
        return abb_module(path, tool, wobj, config)
    return spec_csv(path, angle_units=angle_units, quaternion_order=quaternion_order)


def _matrix(pose: Pose) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = pose.matrix
    T[:3, 3] = pose.t
    return T


# ---------------------------------------------------------------- CSV

def spec_csv(path: str, **reading) -> RobotPoses:
    from .measurement import read_measurement

    m = read_measurement(path, sides=("robot",), what="robot file", **reading)
    poses = [RobotPose(n, n, ln, None, m.flange[i], written=m.orientation[i])
             for i, (n, ln) in enumerate(zip(m.names, m.lines))]
    return RobotPoses(path, "csv", poses, m.form)


# ---------------------------------------------------------------- KUKA

def kuka_dat(path: str, config: str | None) -> RobotPoses:
    from ..parsing.controller import load
    from ..parsing.document import Document
    from ..vendors.kuka.krl import positions
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


# ---------------------------------------------------------------- FANUC

def fanuc_program(path: str, config: str | None, tool: str = "tool0",
                  wobj: str = "wobj0") -> RobotPoses:
    from ..parsing.document import Document
    from array import array

    from ..vendors.fanuc.tp import iter_positions

    if tool.strip().casefold() not in ("tool0", "ut0") or \
            wobj.strip().casefold() not in ("wobj0", "uf0"):
        raise UcsioError("--robot-tool and --robot-wobj name the frames of posreg.va's "
                         "registers (or ABB's); a TP program's positions give their own UF "
                         "and UT", file=path)
    doc = Document.read(path)
    frames = _FanucFrames(config)
    poses = []
    taught = []                         # (pose, UF, UT): the flanges are made at once
    values = array("d")                 # their X Y Z W P R
    for p in iter_positions(doc):       # one at a time: a path program has 100,000
        rp = RobotPose(p.name, p.comment or f"P{p.number}", p.line, p.col, None,
                       aliases=(f"P{p.number}",) if p.comment else ())
        poses.append(rp)
        g = p.groups.get(1)
        if g is None:
            others = ", ".join(f"GP{k}" for k in sorted(p.groups)) or "no group"
            rp.problem = doc.error(f"{p.name}: no group 1 (GP1) position ({others}): not a "
                                   "pose of the robot's flange", p.at)
            continue
        why = ("never taught (UF : F, UT : F): the position has no values" if g.untaught
               else _not_cartesian(g.values, g.joint))
        if why:
            rp.problem = doc.error(f"{p.name}: {why}", g.at)
            continue
        xyzwpr = [g.values[k].value for k in ("X", "Y", "Z", "W", "P", "R")]
        try:
            user = frames.pose("UF", g.uf, doc, p.name, g.uf_at)
            tool_pose = frames.pose("UT", g.ut, doc, p.name, g.ut_at)
        except UcsioError as exc:
            rp.problem = exc
            continue
        taught.append((rp, user, tool_pose))
        values.extend(xyzwpr)
    _fanuc_flanges(taught, values)
    return RobotPoses(path, "fanuc", poses, "fanuc")


def _fanuc_flanges(taught: list, values) -> None:
    """``_fanuc_flange`` of every position at once, as arrays: a path
    program has 100,000 positions, and Pose algebra per position took 10 s.
    ``taught``: (RobotPose, UF pose or None, UT pose or None), the same pose
    objects for the positions that share a frame; ``values``: their X Y Z W
    P R, six floats each (an array('d'): no float objects kept)."""
    if not taught:
        return
    from ..geometry.arrays import flange_matrices
    xyzwpr = np.frombuffer(values, dtype=float).reshape(-1, 6)
    flanges = flange_matrices("fanuc", xyzwpr[:, 3:], xyzwpr[:, :3])
    by_frames: dict = {}
    for i, (_, user, tool) in enumerate(taught):
        by_frames.setdefault((id(user), id(tool)), (user, tool, []))[2].append(i)
    for user, tool, rows in by_frames.values():
        if user is None and tool is None:
            continue
        left = np.eye(4) if user is None else _matrix(user)
        right = np.eye(4) if tool is None else _matrix(tool.inverse())
        for start in range(0, len(rows), 10_000):      # bounded temporaries
            chunk = rows[start:start + 10_000]
            flanges[chunk] = left @ flanges[chunk] @ right
    for (rp, _, _), flange in zip(taught, flanges):
        rp.flange = flange


def fanuc_registers(path: str, config: str | None, tool: str = "tool0",
                    wobj: str = "wobj0") -> RobotPoses:
    from ..parsing.document import Document
    from ..vendors.fanuc.va import register_list

    doc = Document.read(path)
    regs = register_list(doc)
    if not regs:
        raise UcsioError("no position registers ($POSREG): --robot takes a FANUC posreg.va or "
                         "TP program (.ls)", file=path)
    uf = _frame_number(wobj, "wobj0", "UF", "--robot-wobj", "user frame")
    ut = _frame_number(tool, "tool0", "UT", "--robot-tool", "tool frame")
    frames = _FanucFrames(config)
    user = frames.pose("UF", uf, None, "--robot-wobj", 0)
    tool_pose = frames.pose("UT", ut, None, "--robot-tool", 0)
    note = None
    if not uf and not ut:
        note = ("posreg.va does not record the frames a register was taken in: taken as the "
                "flange in world (UF 0, UT 0); --robot-wobj UFk and --robot-tool UTk name others")
    poses = []
    for g, n, pos, e in regs:
        if g != 1 or e.uninit:
            continue
        comment = (e.comment or "").strip()
        line, col = doc.line_col(pos)
        name = f"PR[{n}]"
        rp = RobotPose(name, comment or f"PR{n}", line, col, None, note=note,
                       aliases=(f"PR{n}",) if comment else ())
        poses.append(rp)
        values = e.coords
        why = _not_cartesian(values, e.joints)
        if why:
            rp.problem = doc.error(f"{name}: {why}", pos)
            continue
        xyzwpr = [values[k].value for k in ("X", "Y", "Z", "W", "P", "R")]
        rp.flange = _fanuc_flange(xyzwpr, user, tool_pose)
    return RobotPoses(path, "fanuc", poses, "fanuc")


def _not_cartesian(values: dict, joint: bool) -> str | None:
    """Why a FANUC position is not X Y Z W P R, or None."""
    if joint:
        return ("a joint position (J1 ...), not X Y Z W P R: a measurement needs the flange's "
                "Cartesian pose (record it as a Cartesian position)")
    missing = [k for k in ("X", "Y", "Z", "W", "P", "R") if values.get(k) is None]
    if missing:
        stars = [k for k in missing if k in values]
        return (f"{' '.join(stars)} not a number (********)" if stars else
                f"{' '.join(missing)} missing") + ": not a complete X Y Z W P R"
    return None


def _frame_number(text: str, default: str, prefix: str, opt: str, what: str) -> int:
    """--robot-wobj UF2 -> 2 (the default tool0/wobj0, UF0, UT0 -> 0)."""
    t = text.strip()
    if t.casefold() == default:
        return 0
    head, digits = t[:2], t[2:]
    if head.upper() == prefix and digits.isdigit() and len(digits) < 6:
        return int(digits)
    zero = "world" if prefix == "UF" else "the faceplate"
    raise UcsioError(f"{opt} {text}: for a FANUC posreg.va, the {what} the registers were "
                     f"taken in, {prefix}k ({prefix}0: {zero})")


class _FanucFrames:
    """Group 1's user and tool frames from ``--config`` (a sysframe.va, or
    any FANUC file listing them), loaded when first needed."""

    def __init__(self, config: str | None):
        self.config = config
        self.cf = None
        self.found: dict = {}           # (UF or UT, n): the pose, once found

    def _load(self):
        if self.cf is None:
            from ..parsing.controller import load
            cf = load(self.config)
            if cf.vendor != "fanuc":
                raise UcsioError(f"--config {self.config}: a {cf.vendor.upper()} file; the UF "
                                 "and UT of FANUC positions come from a sysframe.va",
                                 file=self.config)
            self.cf = cf
        return self.cf

    def pose(self, kind: str, n: int, doc, who: str, at: int) -> Pose | None:
        """UFn or UTn of group 1 (None for 0: world, the faceplate). ``doc``
        and ``at``: the position that names it, for the error (None: an
        option names it, ``who``)."""
        if n == 0:
            return None
        if (kind, n) in self.found:         # one look-up per frame, not per position
            return self.found[kind, n]
        name = f"{kind}{n}"
        field = f"{kind} : {n}" if doc is not None else name

        def error(message: str) -> UcsioError:
            return doc.error(message, at) if doc is not None else UcsioError(message)

        if self.config is None:
            raise error(f"{who}: {field}: give --config sysframe.va, the controller's user and "
                        "tool frames")
        cf = self._load()
        found = [f for f in cf.frames if f.name.upper() == name]
        if not found:
            held = [f.name for f in cf.frames if f.name.upper().startswith(kind)
                    and "@" not in f.name and f.pose is not None]
            raise error(f"{who}: {field}, but {self.config} does not hold {name} (its group 1 "
                        f"{'user' if kind == 'UF' else 'tool'} frames: {_names(held) or 'none'})")
        f = found[0]
        if f.pose is None:
            raise error(f"{who}: {field}, but {name} ({f.file}:{f.line}) has no value")
        for g in found[1:]:         # a program that sets it twice: alike, or not known
            if g.pose is None or not _same_pose(g.pose, f.pose):
                raise error(f"{who}: {field}, but {self.config} sets {name} twice with "
                            f"different values (lines {f.line} and {g.line}): which one the "
                            "position was taught in is not known")
        self.found[kind, n] = f.pose
        return f.pose


def _same_pose(a: Pose, b: Pose) -> bool:
    """Equal at a FANUC file's written precision (0.001 mm, 0.001 deg)."""
    from ..geometry import rotations as rot
    return all(abs(u - v) <= 1e-6 for u, v in zip(a.t, b.t)) and \
        rot.quat_angle(a.q, b.q) <= 1e-6


def _fanuc_flange(xyzwpr, user: Pose | None, tool: Pose | None) -> np.ndarray:
    """UF * P * UT^-1 as a 4x4 matrix (None: world, the faceplate)."""
    x, y, z, w, p, r = xyzwpr
    if user is None and tool is None:
        # the numbers as written, through the same conversion as the CSV's robot_w/p/r
        from ..geometry.arrays import flange_matrices
        return flange_matrices("fanuc", np.array([[w, p, r]]), np.array([[x, y, z]]))[0]
    flange = Pose.from_wpr(x, y, z, w, p, r)
    if user is not None:
        flange = user.compose(flange)
    if tool is not None:
        flange = flange.compose(tool.inverse())
    return _matrix(flange)


# ---------------------------------------------------------------- ABB

def abb_module(path: str, tool: str, wobj: str, config: str | None) -> RobotPoses:
    from ..parsing.controller import parse
    from ..parsing.document import Document
    from ..geometry.arrays import flange_matrices
    from ..vendors.abb.rapid import robtargets

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
                                  if p.suffix.lower() in BY_NAME["abb"].suffixes and p.is_file()
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
