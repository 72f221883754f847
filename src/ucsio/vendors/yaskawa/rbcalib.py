"""Yaskawa's robot-to-robot calibration, RBCALIB.DAT.

One block per pair of robots (../shared/corpus/yaskawa/README.md):

- ``//RBCALIB n``;
- ``///MTOOL t``, ``///MGROUP`` (32 flags: the master robot), ``///MPULSE``
  and ``////MRBC1``..``3``: three points taught with the master robot, in
  its joint pulses;
- ``///STOOL``, ``///SGROUP`` (the slave robot), ``///SPULSE``,
  ``////SRBC1``..``3``: the same three physical points in the slave's pulses;
- ``////SRANG x,y,z,rx,ry,rz``: the slave robot's base in the master
  robot's base (mm, deg, R = Rz(rz)·Ry(ry)·Rx(rx), as UFRAME.CND's BUSER).

SRANG is the frame ``RBCALIBn``: its parent is the master robot's base, its
label names both robots ("R2 base in R1 base"). The taught points are joint
pulses: checking that they give SRANG needs the robots' kinematics, which
ucsio does not have, so they are kept as they are, never interpreted. Read
line by line as cnd.py reads the condition files (its helpers), every
number a span.
"""
from __future__ import annotations

from ...geometry.frames import UNKNOWN, Frame, Number, Pose, robot
from ...parsing import regex
from ...parsing.document import Document
from ...parsing.model import ControllerFile
from .cnd import (ANGLE_MAX, COMPONENTS, VENDOR, _BLOCK, _ITEM, _group, _integers, _lines,
                  _numbers)

HEAD = "//RBCALIB"
# the taught points (joint pulses) and their heads: kept verbatim
_PULSES = regex.lazy(r"///[MS]PULSE[ \t]*\Z|////[MS]RBC[0-9]+[ \t]")


def sniff(doc: Document) -> bool:
    """Whether a file begins ``//RBCALIB`` (a git temporary file has no name
    to say so)."""
    head = doc.text[:64].lstrip("\ufeff \t\r\n")
    return head.startswith(HEAD) and not head[len(HEAD):len(HEAD) + 1].isalnum()


def is_frame_name(name: str) -> bool:
    import re
    return re.fullmatch(r"\s*rbcalib\s*[0-9]+\s*", name, re.I) is not None


def robot_name(group: int | None) -> str:
    """How the pendant names a control group's robot: flag k is Rk."""
    return f"R{group}" if group is not None else "an unknown robot"


class _Block:
    __slots__ = ("number", "line", "end", "numbers", "groups", "tools")

    def __init__(self, number: int, line: int, end: int):
        self.number, self.line, self.end = number, line, end
        self.numbers: dict[str, Number] | None = None
        self.groups: dict[str, int | None] = {}     # "M"/"S" -> control group
        self.tools: dict[str, int] = {}             # "M"/"S" -> tool number


def parse(doc: Document, full: bool = False) -> ControllerFile:
    """An RBCALIB.DAT: one frame per block (its SRANG) and the lints. A line
    that breaks a block's layout is one error naming file:line:col."""
    cf = ControllerFile(document=doc, vendor=VENDOR)
    cf.name_form = is_frame_name
    blocks = _blocks(doc, cf)
    seen: dict[int, int] = {}
    for block in blocks:
        if block.numbers is None:
            raise doc.error(f"//RBCALIB {block.number} has no ////SRANG line", block.end)
        cf.frames.append(_frame(doc, block))
        _lint_angles(cf, cf.frames[-1])
        if block.number in seen:
            cf.lint(doc.line_starts[block.line - 1], "duplicate-block", f"RBCALIB{block.number} "
                    f"is defined twice (line {seen[block.number]} and here): which one the "
                    "controller loads is not known")
        seen.setdefault(block.number, block.line)
    cf.extra["kind"] = "robot-to-robot calibration"
    return cf


def _not_rbcalib(doc: Document, pos: int):
    return doc.error("not an RBCALIB.DAT: it begins //RBCALIB n", pos)


def _blocks(doc: Document, cf: ControllerFile) -> list[_Block]:
    blocks: list[_Block] = []
    for pos, line in _lines(doc):
        if not line.strip():
            continue
        if line.startswith("//") and not line.startswith("///"):
            blocks.append(_open_block(doc, pos, line))
        elif not blocks:
            raise _not_rbcalib(doc, pos)
        else:
            blocks[-1].end = pos + len(line)
            _item(doc, cf, blocks[-1], pos, line)
    if not blocks:
        raise _not_rbcalib(doc, 0)
    return blocks


def _open_block(doc: Document, pos: int, line: str) -> _Block:
    m = _BLOCK.match(line)
    if m is None or m.group("kind") != "RBCALIB":
        raise _not_rbcalib(doc, pos)
    if m.group("number") is None:
        raise doc.error("//RBCALIB without its number", pos + m.end("kind"))
    number = doc.integer(m.group("number"), pos + m.start("number"), "calibration number")
    return _Block(number, doc.line_of(pos), pos + len(line))


def _item(doc: Document, cf: ControllerFile, block: _Block, pos: int, line: str) -> None:
    if _PULSES.match(line):
        return
    m = _ITEM.match(line)
    key = m.group("key") if m is not None else None
    rest = (m.group("rest") or "") if m is not None else ""
    at = pos + m.start("rest") if m is not None and m.group("rest") is not None else pos + len(line)
    if key in ("MTOOL", "STOOL"):
        block.tools[key[0]] = _integers(doc, rest, at, 1, f"///{key}")[0]
    elif key in ("MGROUP", "SGROUP"):
        block.groups[key[0]] = _group(doc, cf, rest, at)
    elif key == "SRANG" and m.group("slashes") == "////":
        block.numbers = _numbers(doc, rest, at, "////SRANG")
    else:
        cf.lint(pos, "unknown-line", "a line of RBCALIB.DAT ucsio does not read, kept as it is",
                "info")


def _frame(doc: Document, block: _Block) -> Frame:
    values = {k: n.value for k, n in block.numbers.items()}
    x, y, z, rx, ry, rz = (values[k] for k in COMPONENTS)
    master, slave = block.groups.get("M"), block.groups.get("S")
    info = {"master": robot_name(master), "slave": robot_name(slave),
            "master_group": master, "slave_group": slave,
            "master_tool": block.tools.get("M"), "slave_tool": block.tools.get("S"),
            "rx": rx + 0.0, "ry": ry + 0.0, "rz": rz + 0.0}
    return Frame(name=f"RBCALIB{block.number}", vendor=VENDOR, type="RBCALIB",
                 pose=Pose.from_abc(x, y, z, rz, ry, rx), file=doc.path, line=block.line,
                 reference="world" if master is not None else "unknown",
                 label=f"{robot_name(slave)} base in {robot_name(master)} base",
                 numbers=block.numbers, info=info, document=doc,
                 parent=robot(master) if master is not None else UNKNOWN)


def _lint_angles(cf: ControllerFile, frame: Frame) -> None:
    for name in ("rx", "ry", "rz"):
        num = frame.numbers[name]
        if abs(num.value) > ANGLE_MAX:
            cf.lint(num.span.start, "angle-range", f"{frame.name}: {name} {num.text} is "
                    "outside [-180, 180]")
