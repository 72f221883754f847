"""Yaskawa's VAR.DAT: the controller's global variables as they are now.

The file (../shared/corpus/yaskawa/README.md) begins ``//VAR``, then header
items (``///PFNUM``, ``///SHARE``) and one section per variable type, each a
``///X`` line followed by its rows: ``///B`` bytes, ``///I`` integers,
``///D`` double integers, ``///R`` reals, ``///S`` strings, ``///P`` robot
positions, ``///BP`` base positions, ``///EX`` station positions.

What ucsio reads is the ``///P`` section: one row per position variable,
P000, P001, ... in order::

    "RECTAN"0,0,4,000000000000000000000000,0,16,x,y,z,rx,ry,rz,0.0000,0.0000
    "PULSE"0,0,3,000000000000000000000000,0,0,s,l,u,r,b,t,0,0
    "UNUSED"

A P variable is a position, not a frame: the file lists no frames. What it
tells is which P variables the cell uses (a row that is not ``"UNUSED"``),
so that a generated job (``ucsio program ... -o SETUF2.JBI``) loads its
points into free ones. Every other section and line is kept as it is; each
number of a P row is a span of the document. Read line by line with
anchored patterns, as the condition files are (``cnd``).
"""
from __future__ import annotations

import math

from ...geometry.frames import Number
from ...parsing import regex
from ...parsing.document import Document, Span, lf_lines
from ...parsing.model import ControllerFile

VENDOR = "yaskawa"
HEAD = "//VAR"
UNUSED = "UNUSED"
# a P row: its kind in quotes, then its comma-separated fields
_ROW = regex.lazy(r'"(?P<kind>[A-Z]*)"(?P<rest>[^\n]*)\Z')
_SECTION = regex.lazy(r"///(?P<name>[A-Z]+)(?P<rest>[ \t][^\n]*)?\Z")
_NUMBER = regex.lazy(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)\Z")
# the fields before a position's values: two flags, the tool, the 24 RCONF
# flags, one more flag, the coordinate system (16 the robot base)
LEADING = 6
VALUES = 6


class PVariable:
    """One row of the ``///P`` section: P``number``, its ``kind`` (RECTAN,
    PULSE, UNUSED; None for a row ucsio does not know), its ``line``, the
    ``tool`` and coordinate code of a position, and ``values``: the six
    numbers (x, y, z, rx, ry, rz or the six axes' pulses), each with its span."""

    __slots__ = ("number", "kind", "line", "tool", "coordinate", "values")

    def __init__(self, number: int, kind: str | None, line: int):
        self.number, self.kind, self.line = number, kind, line
        self.tool: int | None = None
        self.coordinate: int | None = None
        self.values: list[Number] = []

    @property
    def name(self) -> str:
        return f"P{self.number:03d}"

    @property
    def in_use(self) -> bool:
        """Not "UNUSED": a row ucsio does not know counts as in use (never
        taken for a generated job)."""
        return self.kind != UNUSED

    def as_dict(self) -> dict:
        return {"name": self.name, "kind": self.kind, "line": self.line, "tool": self.tool,
                "values": [n.value for n in self.values]}


def sniff(doc: Document) -> bool:
    """Whether a file begins ``//VAR`` (a git temporary file has no name to say so)."""
    first = doc.text[:64].lstrip("\ufeff \t\r\n").split("\n", 1)[0].rstrip("\r \t")
    return first == HEAD


def _lines(doc: Document):
    """(offset, line without its ending) for each line of the document."""
    pos = 0
    for line in lf_lines(doc.text).split("\n"):
        yield pos, line[:-1] if line.endswith("\r") else line
        pos += len(line) + 1


def parse(doc: Document, full: bool = False) -> ControllerFile:
    """A VAR.DAT: no frames; ``cf.extra["p_variables"]`` its ``///P`` rows.
    A P row that breaks its layout (a number that is not one) is one error
    naming file:line:col; a line ucsio does not know is an info, kept."""
    cf = ControllerFile(document=doc, vendor=VENDOR)
    rows: list[PVariable] = []
    section = None
    for index, (pos, line) in enumerate(_lines(doc)):
        if index == 0:
            if line.lstrip("\ufeff").rstrip(" \t") != HEAD:
                raise doc.error("not a VAR.DAT: ucsio reads the Yaskawa variable file that "
                                "begins //VAR", pos)
            continue
        m = _SECTION.match(line)
        if m is not None:
            if m.group("rest") is None:
                section = m.group("name")
            continue                # a header item (///PFNUM, ///SHARE): kept as it is
        if section == "P":
            rows.append(_p_row(doc, cf, len(rows), pos, line))
    cf.extra["kind"] = "global variables"
    cf.extra["p_variables"] = rows
    used = sum(r.in_use for r in rows)
    cf.extra["holds"] = (f"global variables: {len(rows)} position variables (P), {used} in use; "
                         "positions, not frames")
    return cf


def _p_row(doc: Document, cf: ControllerFile, number: int, pos: int, line: str) -> PVariable:
    row = PVariable(number, None, doc.line_of(pos))
    m = _ROW.match(line)
    if m is None:
        cf.lint(pos, "unknown-line", f"P{number:03d}: a row ucsio does not read, kept as it is "
                "(counted as in use)", "info")
        return row
    row.kind = m.group("kind")
    rest, at = m.group("rest"), pos + m.start("rest")
    if row.kind == UNUSED and not rest.strip():
        return row
    if row.kind not in ("RECTAN", "PULSE"):
        cf.lint(pos, "unknown-line", f"{row.name}: a {row.kind!r} row ucsio does not read, kept "
                "as it is (counted as in use)", "info")
        return row
    fields = rest.rstrip(" \t").split(",")
    if len(fields) < LEADING + VALUES:
        raise doc.error(f"{row.name}: a {row.kind} row is {LEADING} flags and at least "
                        f"{VALUES} numbers separated by commas; {len(fields)} fields here",
                        at + len(rest.rstrip(" \t")))
    starts = _field_starts(fields, at)
    row.tool = _integer(doc, fields[2], starts[2], f"{row.name}'s tool")
    row.coordinate = _integer(doc, fields[5], starts[5], f"{row.name}'s coordinate system")
    row.values = [_number(doc, row, f, s)
                  for f, s in zip(fields[LEADING:LEADING + VALUES], starts[LEADING:])]
    return row


def _field_starts(fields: list[str], at: int) -> list[int]:
    starts, pos = [], at
    for field in fields:
        starts.append(pos)
        pos += len(field) + 1
    return starts


def _integer(doc: Document, field: str, at: int, what: str) -> int:
    if not field.isdigit():
        raise doc.error(f"{what} is an integer; {field[:30]!r} here", at)
    return doc.integer(field, at, what)


def _number(doc: Document, row: PVariable, field: str, at: int) -> Number:
    if _NUMBER.match(field) is None:
        raise doc.error(f"{row.name}: not a number: {field[:30]!r}" if field else
                        f"{row.name}: a number is missing here", at)
    value = float(field)
    if not math.isfinite(value):
        raise doc.error(f"{row.name}: number out of range: {field[:30]!r}", at)
    return Number(Span(at, at + len(field)), field, value)


def in_use(cf: ControllerFile) -> list[int]:
    """The numbers of the P variables a VAR.DAT shows in use (every row
    that is not "UNUSED"), in order."""
    return [r.number for r in cf.extra["p_variables"] if r.in_use]


def p_count(cf: ControllerFile) -> int:
    """How many P variables the controller has: the rows of ``///P``."""
    return len(cf.extra["p_variables"])
