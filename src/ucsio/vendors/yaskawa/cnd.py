"""Yaskawa Motoman condition files: UFRAME.CND (user frames) and TOOL.CND (tools).

Both are lists of blocks, one line per item (../shared/corpus/yaskawa/README.md):

- ``//UFRAME n``, then ``///NAME``, ``///TOOL t``, ``///GROUP`` (32 flags:
  which robot), ``///BASICFRM 1,k,m`` (what the frame is defined on),
  ``///BASEP`` (track position when taught), ``///PULSE`` and the taught
  points ``////RORG``/``////RXX``/``////RXY`` (joint pulses), and
  ``////BUSER x,y,z,rx,ry,rz``: the frame the controller computed. It is
  ``UFn``, its ``///NAME`` the label.
- ``//TOOL n``, then ``///CRC`` (YAS4.81 on), ``///NAME``, and the pose line
  ``x,y,z,rx,ry,rz`` in the flange, then centre of gravity, mass, inertia
  and one more line. It is ``UTn``.

x, y, z in mm, rx, ry, rz in degrees, R = Rz(rz)·Ry(ry)·Rx(rx): KUKA's
matrix with A = rz, B = ry, C = rx. The format is one item per line with
fixed keywords, so lines are matched one at a time with anchored patterns
(as the FANUC .dg reader does): linear in the file, and a line ucsio does
not know is kept as it is (an info), never an error. Every number read is
a span of the document, so a patch can replace exactly it.
"""
from __future__ import annotations

import math

from ...geometry.frames import UNKNOWN, Frame, Number, Pose, flange, frame_parent, robot, unit
from ...parsing import regex
from ...parsing.document import Document, Span, lf_lines
from ...parsing.model import ControllerFile

VENDOR = "yaskawa"
COMPONENTS = ("x", "y", "z", "rx", "ry", "rz")
# block keyword -> (frame type, name prefix, reference)
KINDS = {"UFRAME": ("UFRAME", "UF", "world"), "TOOL": ("TOOL", "UT", "flange")}
ANGLE_MAX = 180.0
# a checksum line (TOOL.CND from YAS4.81 on), in any spelling that may be one
CRC_LINE = ("///CRC", "////CRC")
# ///BASICFRM 1,k,m: what a user frame is defined on
ROBOT_BASE, ON_USER_FRAME, ON_MASTER_TOOL = 16, 19, 20

_N = r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)"
_NUMBER = regex.lazy(_N + r"\Z")
_BLOCK = regex.lazy(r"//(?P<kind>[A-Z]+)(?:[ \t]+(?P<number>[0-9]+))?[ \t]*\Z")
_ITEM = regex.lazy(r"(?P<slashes>/{3,4})(?P<key>[A-Z]+)(?:[ \t](?P<rest>[^\n]*))?\Z")
_INTS = regex.lazy(r"[0-9]+(?:,[0-9]+)*[ \t]*\Z")


def is_frame_name(name: str) -> bool:
    """Whether ``name`` has the form of a Yaskawa frame's name (UF2, ut0)."""
    import re
    return re.fullmatch(r"\s*u[ft]\s*[0-9]+\s*", name, re.I) is not None


def sniff(doc: Document) -> bool:
    """Whether a file begins like a UFRAME.CND or TOOL.CND (a git temporary
    file has no suffix to say so)."""
    head = doc.text[:64].lstrip("\ufeff \t\r\n")
    m = _BLOCK.match(head.split("\n", 1)[0].rstrip("\r"))
    return m is not None and m.group("kind") in KINDS


def _lines(doc: Document):
    """(offset, line without its ending) for each line of the document."""
    pos = 0
    for line in lf_lines(doc.text).split("\n"):
        yield pos, line[:-1] if line.endswith("\r") else line
        pos += len(line) + 1


class _Block:
    """One ``//UFRAME n`` or ``//TOOL n`` block as read so far."""

    __slots__ = ("kind", "number", "line", "end", "label", "numbers", "info", "group", "basicfrm")

    def __init__(self, kind: str, number: int, line: int, end: int):
        self.kind, self.number, self.line, self.end = kind, number, line, end
        self.label: str | None = None
        self.numbers: dict[str, Number] | None = None
        self.info: dict = {}
        self.group: int | None = None
        self.basicfrm: tuple[int, ...] | None = None


def parse(doc: Document, full: bool = False) -> ControllerFile:
    """A UFRAME.CND or TOOL.CND: its frames and lints. A line that breaks a
    block's layout (a number that is not one, a pose line of five values)
    is one error naming file:line:col."""
    cf = ControllerFile(document=doc, vendor=VENDOR)
    cf.name_form = is_frame_name
    blocks = _blocks(doc, cf)
    for block in blocks:
        if block.numbers is None:
            what = "////BUSER line" if block.kind == "UFRAME" else "pose line (x,y,z,rx,ry,rz)"
            raise doc.error(f"//{block.kind} {block.number} has no {what}", block.end)
        cf.frames.append(_frame(doc, block))
    _lint_blocks(cf, blocks)
    _lint_parents(cf, blocks)
    _lint_line_endings(cf, blocks)
    cf.extra["kind"] = "user frames" if blocks[0].kind == "UFRAME" else "tools"
    return cf


def _blocks(doc: Document, cf: ControllerFile) -> list[_Block]:
    blocks: list[_Block] = []
    block: _Block | None = None
    for pos, line in _lines(doc):
        if not blocks and line.strip() and not line.startswith("//"):
            raise _not_a_cnd(doc, pos)
        if line.startswith("//") and not line.startswith("///"):
            block = _open_block(doc, cf, pos, line, first=not blocks)
            if block is not None:
                blocks.append(block)
            continue
        if not line.strip():
            continue
        if line.startswith(CRC_LINE) and "crc_line" not in cf.extra:
            cf.extra["crc_line"] = doc.line_of(pos)     # a checksum: never written (write.py)
        if block is None:       # in a block ucsio does not read (reported at its head)
            continue
        block.end = pos + len(line)
        if block.kind == "UFRAME":
            _uframe_line(doc, cf, block, pos, line)
        else:
            _tool_line(doc, cf, block, pos, line)
    if not blocks:
        raise _not_a_cnd(doc, 0)
    return blocks


def _not_a_cnd(doc: Document, pos: int):
    return doc.error("not a UFRAME.CND or TOOL.CND: ucsio reads the Yaskawa condition files "
                     "that begin //UFRAME n or //TOOL n", pos)


def _open_block(doc: Document, cf: ControllerFile, pos: int, line: str,
                first: bool) -> _Block | None:
    """The block a ``//KIND n`` line opens; None (an info) for a kind ucsio
    does not read, which is kept as it is with its lines."""
    m = _BLOCK.match(line)
    if m is None or m.group("kind") not in KINDS:
        if first:
            raise _not_a_cnd(doc, pos)
        cf.lint(pos, "unknown-line", f"a block ucsio does not read ({line[:30]!r}), kept as it is",
                "info")
        return None
    if m.group("number") is None:
        raise doc.error(f"//{m.group('kind')} without its number", pos + m.end("kind"))
    number = doc.integer(m.group("number"), pos + m.start("number"), "frame number")
    return _Block(m.group("kind"), number, doc.line_of(pos), pos + len(line))


def _uframe_line(doc: Document, cf: ControllerFile, block: _Block, pos: int, line: str) -> None:
    m = _ITEM.match(line)
    key = m.group("key") if m is not None else None
    rest = (m.group("rest") or "") if m is not None else ""
    at = pos + m.start("rest") if m is not None and m.group("rest") is not None else pos + len(line)
    if key == "NAME":
        block.label = rest.strip() or None
    elif key == "TOOL":
        block.info["tool"] = _integers(doc, rest, at, 1, "///TOOL")[0]
    elif key == "GROUP":
        block.group = _group(doc, cf, rest, at)
    elif key == "BASICFRM":
        block.basicfrm = _integers(doc, rest, at, 3, "///BASICFRM")
    elif key == "BASEP":
        basep = _numbers(doc, rest, at, "///BASEP")
        if any(n.value != 0 for n in basep.values()):
            block.info["basep"] = [n.value + 0.0 for n in basep.values()]
            cf.lint(pos, "track-position", f"UF{block.number} was taught with the robot at a "
                    "track position (///BASEP is not zero)", "info")
    elif key == "BUSER" and m.group("slashes") == "////":
        block.numbers = _numbers(doc, rest, at, "////BUSER")
    elif key in ("PULSE", "RORG", "RXX", "RXY"):
        pass            # the taught points, in joint pulses: kept as they are
    elif line.strip():
        cf.lint(pos, "unknown-line", "a line of a user frame ucsio does not read, kept as it is",
                "info")


def _tool_line(doc: Document, cf: ControllerFile, block: _Block, pos: int, line: str) -> None:
    m = _ITEM.match(line)
    if m is not None:
        key = m.group("key")
        if key == "NAME":
            block.label = (m.group("rest") or "").strip() or None
        elif key == "CRC":
            block.info["crc"] = True    # a checksum ucsio cannot compute
        else:
            cf.lint(pos, "unknown-line", "a line of a tool ucsio does not read, kept as it is",
                    "info")
        return
    if block.numbers is None and line.strip():
        block.numbers = _numbers(doc, line, pos, "a tool's pose line")
    # the lines after it (centre of gravity, mass, inertia, ...) are kept as they are


def _integers(doc: Document, text: str, at: int, count: int, what: str) -> tuple[int, ...]:
    if _INTS.match(text) is None or text.count(",") != count - 1:
        raise doc.error(f"{what} is {count} integer{'s' if count > 1 else ''} separated by "
                        "commas", at)
    out, pos = [], at
    for field in text.rstrip(" \t").split(","):
        out.append(doc.integer(field, pos, what))
        pos += len(field) + 1
    return tuple(out)


def _numbers(doc: Document, text: str, at: int, what: str) -> dict[str, Number]:
    """The six numbers x,y,z,rx,ry,rz of ``text`` (at offset ``at``), each
    with its span; anything else is an error at the field that breaks it."""
    body = text.rstrip(" \t")
    fields = body.split(",")
    out: dict[str, Number] = {}
    pos = at
    for i, field in enumerate(fields):
        if i == len(COMPONENTS):
            raise doc.error(f"{what} is six numbers: x,y,z (mm), rx,ry,rz (deg); a seventh here",
                            pos)
        if _NUMBER.match(field) is None:
            raise doc.error(f"{what}: not a number: {field[:30]!r}" if field else
                            f"{what}: a number is missing here", pos)
        value = float(field)
        if not math.isfinite(value):    # 400 digits: no controller holds it, no pose is made of it
            raise doc.error(f"{what}: number out of range: {field[:30]!r}", pos)
        out[COMPONENTS[i]] = Number(Span(pos, pos + len(field)), field, value)
        pos += len(field) + 1
    if len(out) < len(COMPONENTS):
        raise doc.error(f"{what} is six numbers: x,y,z (mm), rx,ry,rz (deg); "
                        f"{len(out)} here", at + len(body))
    return out


def _group(doc: Document, cf: ControllerFile, text: str, at: int) -> int | None:
    """The robot a ``///GROUP`` line's flags name (flag k set: robot k); None,
    with a warning, where no flag or several are set."""
    flags = _integers(doc, text, at, text.count(",") + 1, "///GROUP")
    chosen = [k for k, flag in enumerate(flags, 1) if flag]
    if len(chosen) == 1:
        return chosen[0]
    cf.lint(at, "group-flags", "///GROUP names " + ("no robot" if not chosen else
            f"{len(chosen)} control groups") + ": the frame's robot is not known")
    return None


# -- frames -----------------------------------------------------------------------
def _frame(doc: Document, block: _Block) -> Frame:
    ftype, prefix, reference = KINDS[block.kind]
    values = {k: n.value for k, n in block.numbers.items()}
    x, y, z, rx, ry, rz = (values[k] for k in COMPONENTS)
    info = dict(block.info)
    info.update(rx=rx + 0.0, ry=ry + 0.0, rz=rz + 0.0)
    if block.kind == "UFRAME":
        info["group"] = block.group
        if block.basicfrm is not None:
            info["basicfrm"] = ",".join(str(v) for v in block.basicfrm)
    return Frame(name=f"{prefix}{block.number}", vendor=VENDOR, type=ftype,
                 pose=Pose.from_abc(x, y, z, rz, ry, rx), file=doc.path, line=block.line,
                 reference=reference if block.kind == "TOOL" else _reference(block),
                 label=block.label, numbers=block.numbers, info=info, document=doc,
                 parent=flange() if block.kind == "TOOL" else _parent(block))


def _parent(block: _Block):
    """What a user frame is relative to: ``///BASICFRM 1,16,0`` its robot's
    base, ``1,19,k`` user frame k, ``1,20,m`` the master robot's tool (which
    moves it: a unit of the tree); none given, the robot base."""
    kind = block.basicfrm[1] if block.basicfrm is not None and len(block.basicfrm) > 1 else None
    if kind is None or kind == ROBOT_BASE:
        return robot(block.group) if block.group is not None else UNKNOWN
    if kind == ON_USER_FRAME:
        return frame_parent(f"UF{block.basicfrm[2]}")
    if kind == ON_MASTER_TOOL:
        return unit("master robot's tool")
    return UNKNOWN


def _reference(block: _Block) -> str:
    parent = _parent(block)
    return {"robot": "world", "frame": "uframe", "unit": "machine"}.get(parent.kind, "unknown")


# -- lints ------------------------------------------------------------------------
def _lint_blocks(cf: ControllerFile, blocks: list[_Block]) -> None:
    doc = cf.document
    seen: dict[tuple[str, int], int] = {}
    for block, frame in zip(blocks, cf.frames):
        key = (block.kind, block.number)
        offset = doc.line_starts[block.line - 1]
        if key in seen:
            cf.lint(offset, "duplicate-block", f"{frame.name} is defined twice (line "
                    f"{seen[key]} and here): which one the controller loads is not known")
        seen.setdefault(key, block.line)
        for name in ("rx", "ry", "rz"):
            num = frame.numbers[name]
            if abs(num.value) > ANGLE_MAX:
                cf.lint(num.span.start, "angle-range", f"{frame.name}: {name} {num.text} is "
                        "outside [-180, 180]")
        if block.kind == "UFRAME" and block.basicfrm is not None and \
                (len(block.basicfrm) < 2 or block.basicfrm[1] not in
                 (ROBOT_BASE, ON_USER_FRAME, ON_MASTER_TOOL)):
            cf.lint(offset, "unknown-line", f"{frame.name}: ///BASICFRM "
                    f"{frame.info.get('basicfrm')} is a base ucsio does not know: parent unknown",
                    "info")


def _lint_parents(cf: ControllerFile, blocks: list[_Block]) -> None:
    """A user frame defined on a user frame (``///BASICFRM 1,19,k``) the
    file does not hold, or on itself through others: its parent is not
    known (the tree lists it as unknown, a measured frame is not written)."""
    on = {b.number: b.basicfrm[2] for b in blocks
          if b.kind == "UFRAME" and b.basicfrm is not None and len(b.basicfrm) > 2
          and b.basicfrm[1] == ON_USER_FRAME}
    held = {b.number for b in blocks if b.kind == "UFRAME"}
    for b in blocks:
        if b.number not in on or b.kind != "UFRAME":
            continue
        chain, k = [b.number], on[b.number]
        while k in on and k not in chain:
            chain.append(k)
            k = on[k]
        offset = cf.document.line_starts[b.line - 1]
        if k not in held:
            path = " on ".join(f"UF{n}" for n in chain[1:] + [k])
            cf.lint(offset, "basicfrm-parent", f"UF{b.number}: defined on {path} (///BASICFRM "
                    f"1,19,{on[b.number]}), which this file does not hold: its parent is not "
                    "known")
        elif k == b.number:
            circle = " on ".join(f"UF{n}" for n in chain + [k])
            cf.lint(offset, "basicfrm-parent", f"UF{b.number}: defined on user frames in a "
                    f"circle ({circle}): its parent is not known")


def _lint_line_endings(cf: ControllerFile, blocks: list[_Block]) -> None:
    """A UFRAME.CND without CRLF is reported to load on the controller as
    empty (git's text normalisation makes such copies)."""
    text = cf.document.text
    if any(b.kind == "UFRAME" for b in blocks) and "\n" in text and "\r\n" not in text:
        cf.lint(text.index("\n"), "lf-only", "LF line endings: a UFRAME.CND without CRLF is "
                "reported to load on the controller as empty (save it with CRLF)")
