"""FANUC's robot positions for ``solve --robot``.

- ``program``: a TP program's /POS positions (.ls). Each Cartesian position
  is the TCP of tool frame UT[t] in user frame UF[u], as its GP1 says
  (``UF : u, UT : t``): the flange in world is UF[u] * P * UT[t]^-1, with
  group 1's frames read from ``--config sysframe.va`` (needed where u or t
  is not 0; UF 0 is world, UT 0 the faceplate). Named ``P[3]``; it also
  pairs by its comment, then as ``P3``.
- ``registers``: posreg.va's Cartesian position registers of group 1
  (``PR[16]``, pairing also by comment, then ``PR16``). A register does not
  record the frames it was taken in: UF and UT are ``--robot-wobj UFk`` and
  ``--robot-tool UTk`` (default UF 0 and UT 0: the flange in world, said
  once paired), read as for a program. Uninitialized registers are left out.

The positions go through the TP and .va readers: the same grammars as
``frames``. A position that cannot be resolved carries its problem, raised
only if the point is paired. ``load`` (passed in by the front) reads
``--config``, which must be a FANUC file.
"""
from __future__ import annotations

import numpy as np

from ...errors import UcsioError
from ...geometry import rotations as rot
from ...geometry.arrays import flange_matrices
from ...geometry.frames import Pose
from ...parsing.document import Document
from ..common.robot import RobotPose, RobotPoses, few_names, matrix


def read(vendor, path: str, config: str | None, tool: str, wobj: str, load) -> RobotPoses:
    """A TP program's positions, or posreg.va's registers, as flange poses in
    world, in ``vendor``'s convention (the package's VENDOR, handed in: this
    module does not import its package back)."""
    import os
    reader = program if os.path.splitext(path)[1].lower() == ".ls" else registers
    return reader(vendor, path, config, tool, wobj, load)


def program(vendor, path: str, config: str | None, tool: str, wobj: str, load) -> RobotPoses:
    from array import array

    from .tp import iter_positions

    if tool.strip().casefold() not in ("tool0", "ut0") or \
            wobj.strip().casefold() not in ("wobj0", "uf0"):
        raise UcsioError("--robot-tool and --robot-wobj name the frames of posreg.va's "
                         "registers (or ABB's); a TP program's positions give their own UF "
                         "and UT", file=path)
    doc = Document.read(path)
    frames = _FanucFrames(config, load, vendor.name)
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
    _fanuc_flanges(vendor.angles, taught, values)
    return RobotPoses(path, vendor.name, poses, vendor.name)


def _fanuc_flanges(angles, taught: list, values) -> None:
    """``_fanuc_flange`` of every position at once, as arrays: a path
    program has 100,000 positions, and Pose algebra per position took 10 s.
    ``taught``: (RobotPose, UF pose or None, UT pose or None), the same pose
    objects for the positions that share a frame; ``values``: their X Y Z W
    P R, six floats each (an array('d'): no float objects kept)."""
    if not taught:
        return
    xyzwpr = np.frombuffer(values, dtype=float).reshape(-1, 6)
    flanges = flange_matrices(angles, xyzwpr[:, 3:], xyzwpr[:, :3])
    by_frames: dict = {}
    for i, (_, user, tool) in enumerate(taught):
        by_frames.setdefault((id(user), id(tool)), (user, tool, []))[2].append(i)
    for user, tool, rows in by_frames.values():
        if user is None and tool is None:
            continue
        left = np.eye(4) if user is None else matrix(user)
        right = np.eye(4) if tool is None else matrix(tool.inverse())
        for start in range(0, len(rows), 10_000):      # bounded temporaries
            chunk = rows[start:start + 10_000]
            flanges[chunk] = left @ flanges[chunk] @ right
    for (rp, _, _), flange in zip(taught, flanges):
        rp.flange = flange


def registers(vendor, path: str, config: str | None, tool: str, wobj: str, load) -> RobotPoses:
    from .va import register_list

    doc = Document.read(path)
    regs = register_list(doc)
    if not regs:
        raise UcsioError("no position registers ($POSREG): --robot takes a FANUC posreg.va or "
                         "TP program (.ls)", file=path)
    uf = _frame_number(wobj, "wobj0", "UF", "--robot-wobj", "user frame")
    ut = _frame_number(tool, "tool0", "UT", "--robot-tool", "tool frame")
    frames = _FanucFrames(config, load, vendor.name)
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
        rp.flange = _fanuc_flange(vendor.angles, xyzwpr, user, tool_pose)
    return RobotPoses(path, vendor.name, poses, vendor.name)


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

    def __init__(self, config: str | None, load, vendor: str):
        self.config, self.load, self.vendor = config, load, vendor
        self.cf = None
        self.found: dict = {}           # (UF or UT, n): the pose, once found

    def _load(self):
        if self.cf is None:
            cf = self.load(self.config)
            if cf.vendor != self.vendor:
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
                        f"{'user' if kind == 'UF' else 'tool'} frames: "
                        f"{few_names(held) or 'none'})")
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
    return all(abs(u - v) <= 1e-6 for u, v in zip(a.t, b.t)) and \
        rot.quat_angle(a.q, b.q) <= 1e-6


def _fanuc_flange(angles, xyzwpr, user: Pose | None, tool: Pose | None) -> np.ndarray:
    """UF * P * UT^-1 as a 4x4 matrix (None: world, the faceplate)."""
    x, y, z, w, p, r = xyzwpr
    if user is None and tool is None:
        # the numbers as written, through the same conversion as the CSV's robot_w/p/r
        return flange_matrices(angles, np.array([[w, p, r]]), np.array([[x, y, z]]))[0]
    flange = Pose.from_wpr(x, y, z, w, p, r)
    if user is not None:
        flange = user.compose(flange)
    if tool is not None:
        flange = flange.compose(tool.inverse())
    return matrix(flange)
