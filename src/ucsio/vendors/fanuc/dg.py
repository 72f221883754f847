"""FANUC diagnostic listings (.dg): what ucsio reads of them.

The controller prints these for people, not for loading back; two matter here:

- ``frame.dg``: the frame tables (``Tool Frame``, ``Jog Frame``, ``User
  Frame``), one row per frame: six values with one decimal, then the frame's
  comment (``  -1.3  -1090.6   764.6  -180.0     0.0   -90.0 SSW``). Row k of
  the Tool Frame table is UT k, of the User Frame table UF k; a table that
  comes again is the next motion group's (an assumption: the corpus has one
  group). The values are too coarse for anything but names: ucsio takes the
  comments as the frames' labels (``frame_labels``) and lists no frame.
- ``curpos.dg``: the robot's position at one instant, per motion group: the
  joints, then the pose in the current user frame (``Frame #: u  Tool #: t``)
  and in world, each X Y Z W P R with two decimals and its ``CFG:`` line
  (``current_positions``). A group whose pose the controller cannot compute
  says so (``Cartesian position cannot be calculated``).

Any other ``.dg`` (iostate.dg, summary.dg, ...) is a listing ucsio does not
read: it is listed, without frames. Lines are matched one at a time with
anchored patterns: linear in the file, whatever it holds.
"""
from __future__ import annotations

from ...geometry.frames import Number, Pose
from ...values import Value
from ...parsing import regex
from . import base as fanuc
from ...parsing.document import Document, Span, lf_lines
from ...parsing.model import ControllerFile

_N = r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)"
_TABLES = {"tool frame": "UTOOL", "jog frame": None, "user frame": "UFRAME"}
_ROW = regex.lazy(r"[ \t\f\r]*(" + _N + r"|\*+)[ \t]+(" + _N + r"|\*+)[ \t]+(" + _N + r"|\*+)"
                  r"[ \t]+(" + _N + r"|\*+)[ \t]+(" + _N + r"|\*+)[ \t]+(" + _N + r"|\*+)"
                  r"(?:[ \t]([^\n]*))?\Z")
_CURRENT = "CURRENT ROBOT POSITION"
_GROUP = regex.lazy(r"[ \t]*Group[ \t]*#:[ \t]*([0-9]+)[ \t\f\r]*\Z")
_JOINT = regex.lazy(r"[ \t]*Joint[ \t]+([0-9]+)[ \t]*:[ \t]*([^\s]*)[ \t\f\r]*\Z")
_FRAME_TOOL = regex.lazy(r"[ \t]*Frame[ \t]*#:[ \t]*([0-9]+)[ \t]+Tool[ \t]*#:[ \t]*([0-9]+)"
                         r"[ \t\f\r]*\Z")
_TOOL = regex.lazy(r"[ \t]*Tool[ \t]*#:[ \t]*([0-9]+)[ \t\f\r]*\Z")
_VALUE = regex.lazy(r"[ \t]*([XYZWPR])[ \t]*:[ \t]*([^\s]*)[ \t\f\r]*\Z")
_CFG = regex.lazy(r"[ \t]*CFG[ \t]*:([^\n]*)\Z")
_NUMBER = regex.lazy(_N + r"\Z")


def _lines(doc: Document):
    """(offset, line without its ending) for each line of the document."""
    text = lf_lines(doc.text)
    pos = 0
    for line in text.split("\n"):
        yield pos, line
        pos += len(line) + 1


def parse(doc: Document, full: bool = False) -> ControllerFile:
    """A .dg file: frame.dg and curpos.dg are read (and refused, with
    file:line:col, where their lines break the layout); any other listing
    is listed as such."""
    cf = fanuc.controller_file(doc)
    text = doc.text
    if not text.strip():
        raise doc.error("empty file: no FANUC listing", 0)
    if _CURRENT in text:
        cf.extra["kind"] = "current position"
        cf.extra["current"] = current_positions(doc)
    elif any(line.strip().lower() in _TABLES for _, line in _lines(doc)):
        cf.extra["kind"] = "frame comments"
        cf.extra["labels"] = frame_labels(doc)
    else:
        cf.extra["kind"] = "diagnostics"
    return cf


# -- frame.dg -------------------------------------------------------------------------
def frame_labels(doc: Document) -> dict:
    """{(type, n, group): comment} from frame.dg's Tool Frame and User Frame
    tables (rows without a comment give none)."""
    out = {}
    table = None
    seen: dict[str, int] = {}
    row = 0
    for pos, line in _lines(doc):
        title = line.strip().lower()
        if title in _TABLES:
            table = title
            seen[table] = seen.get(table, 0) + 1
            row = 0
            continue
        if not line.strip():
            table = None
            continue
        if table is None:
            continue
        m = _ROW.match(line)
        if m is None:
            col = len(line) - len(line.lstrip(" \t\f\r"))
            raise doc.error(f"a row of the {title_case(table)} table is six numbers and a "
                            "comment", pos + col)
        row += 1
        ftype = _TABLES[table]
        comment = (m.group(7) or "").strip()
        if ftype is not None and comment:
            out[(ftype, row, seen[table])] = comment
    return out


def title_case(table: str) -> str:
    return " ".join(w.capitalize() for w in table.split())


# -- curpos.dg -------------------------------------------------------------------------
class CurrentPosition(Value):
    """One motion group of curpos.dg: ``joints`` {k: Number}; the pose in
    user frame ``uf`` with tool ``ut`` (``user``: {x..r: Number}, None where
    the controller could not compute it) and in world (``world``, with tool
    ``world_tool``); each with its configuration string and line."""

    __slots__ = ("group", "line", "joints", "uf", "ut", "user", "user_config", "user_line",
                 "world_tool", "world", "world_config", "world_line")

    def __init__(self, group: int, line: int):
        self.group, self.line = group, line
        self.joints: dict = {}
        self.uf = self.ut = self.world_tool = None
        self.user = self.world = self.user_config = self.world_config = None
        self.user_line = self.world_line = None

    @staticmethod
    def _pose(values) -> Pose | None:
        if values is None or any(k not in values for k in fanuc.COMPONENTS):
            return None
        return Pose.from_wpr(*(values[k].value for k in fanuc.COMPONENTS))

    @property
    def user_pose(self) -> Pose | None:
        return self._pose(self.user)

    @property
    def world_pose(self) -> Pose | None:
        return self._pose(self.world)


def current_positions(doc: Document) -> list[CurrentPosition]:
    """Every group of a curpos.dg, in order. A value that is not a number
    is an error naming its line and column."""
    out: list[CurrentPosition] = []
    cur = None
    section = None
    pending_tool = None
    for pos, line in _lines(doc):
        lineno = doc.line_of(pos)
        m = _GROUP.match(line)
        if m is not None:
            cur = CurrentPosition(doc.integer(m.group(1), pos + m.start(1), "group"), lineno)
            out.append(cur)
            section = None
            continue
        if cur is None:
            continue
        stripped = line.strip()
        if stripped.startswith("CURRENT USER FRAME POSITION"):
            section = "user"
            cur.user, cur.user_line = {}, lineno
            continue
        if stripped.startswith("CURRENT WORLD POSITION"):
            section = "world"
            cur.world, cur.world_line = {}, lineno
            cur.world_tool = pending_tool
            continue
        if stripped.startswith("CURRENT JOINT POSITION"):
            section = "joints"
            continue
        if stripped.startswith("Cartesian position cannot be calculated"):
            if section == "user":
                cur.user = None
            elif section == "world":
                cur.world = None
            continue
        m = _FRAME_TOOL.match(line)
        if m is not None:
            cur.uf = doc.integer(m.group(1), pos + m.start(1), "frame number")
            cur.ut = doc.integer(m.group(2), pos + m.start(2), "tool number")
            continue
        m = _TOOL.match(line)
        if m is not None:
            pending_tool = doc.integer(m.group(1), pos + m.start(1), "tool number")
            continue
        m = _JOINT.match(line)
        if m is not None:
            cur.joints[doc.integer(m.group(1), pos + m.start(1), "joint")] = _number(doc, m, 2, pos)
            continue
        m = _CFG.match(line)
        if m is not None and section in ("user", "world"):
            setattr(cur, f"{section}_config", m.group(1).strip())
            continue
        m = _VALUE.match(line)
        if m is not None and section in ("user", "world"):
            values = getattr(cur, section)
            if values is not None:
                values[m.group(1).lower()] = _number(doc, m, 2, pos)
    return out


def _number(doc: Document, m, group: int, pos: int) -> Number:
    text = m.group(group)
    start = pos + m.start(group)
    if not _NUMBER.match(text):
        raise doc.error(f"not a number: {text[:30]!r}" if text else "a number is missing here",
                        start)
    return Number(Span(start, start + len(text)), text, float(text))
