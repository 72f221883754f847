"""Yaskawa Motoman jobs (.JBI): the positions of ``//POS``.

A job is one item per line (../shared/corpus/yaskawa/README.md):

- ``/JOB``, ``//NAME name``, ``//POS``, ``///NPOS C,BC,EC,P,BP,EX`` (how
  many positions of each kind follow);
- then groups of positions, each line changing what holds for the lines
  after it: ``///TOOL n`` (may change between points), ``///USER n``,
  ``///POSTYPE PULSE|BASE|ROBOT|TOOL|USER|MTOOL``, ``///PULSE`` or
  ``///RECTAN`` with ``///RCONF ...`` (the robot's configuration flags:
  opaque, kept as they are);
- the positions ``Cnnnnn=`` (the job's points), ``Pnnn=`` (snapshots of
  global position variables), and ``BCnnnnn``, ``ECnnnnn``, ``BPnnn``,
  ``EXnnn`` (base and station axes): joint pulses (integers) or, for a
  robot, x,y,z (mm), rx,ry,rz (deg) in the frame its POSTYPE names;
- ``//INST`` (``///DATE``, ``///ATTR``, ``///FRAME``, ``///GROUP1``, NOP ...
  END): the program, kept as it is.

A job defines no frame: ``frames`` lists none and ``check`` reads every
line. Every number of a position is a span of the document; a line ucsio
does not know is kept verbatim (an info), a malformed position is one error
at file:line:col. The reader is plain string work (no numpy, no grammar):
``diff --points`` reads every job of a backup.
"""
from __future__ import annotations

import math

from ...geometry.frames import Number
from ...parsing import regex
from ...parsing.document import Document, Span
from ...parsing.model import ControllerFile
from .cnd import COMPONENTS, _lines

VENDOR = "yaskawa"
# ///NPOS's six counts, in its order
KINDS = ("C", "BC", "EC", "P", "BP", "EX")
ROBOT_KINDS = ("C", "P")            # the robot's own positions; the others are axes of a unit
POSTYPES = ("PULSE", "BASE", "ROBOT", "TOOL", "USER", "MTOOL")
# a Cartesian robot position: x,y,z,rx,ry,rz, and a 7-axis arm's elbow angle re
RECTAN_COUNTS = (6, 7)

_POSITION = regex.lazy(r"(?P<kind>BC|EC|BP|EX|C|P)(?P<number>[0-9]+)=")
_ITEM = regex.lazy(r"(?P<slashes>/{1,3})(?P<key>[A-Z]+[0-9]*)(?:[ \t]+(?P<rest>[^\n]*))?\Z")
_INT = regex.lazy(r"[+-]?[0-9]+\Z")
_HEAD = regex.lazy(r"[\ufeff \t\r\n]*+/JOB(?![^ \t\r\n])")
_NUMBER = regex.lazy(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)\Z")


class Position:
    """One position line: ``kind`` C, P, BC, EC, BP or EX and its number;
    the group it is in (``tool``, ``user``, ``postype``); ``values`` each a
    Number (x..rz, and re, for a Cartesian one; j1.. for pulses);
    ``line`` and ``at`` (the offset of its first value)."""

    __slots__ = ("name", "kind", "number", "line", "at", "tool", "user", "postype", "pulse",
                 "values")

    def __init__(self, name: str, kind: str, number: int, line: int, at: int, tool, user,
                 postype: str | None, pulse: bool, values: dict[str, Number]):
        self.name, self.kind, self.number, self.line, self.at = name, kind, number, line, at
        self.tool, self.user, self.postype, self.pulse = tool, user, postype, pulse
        self.values = values

    @property
    def point(self) -> str:
        """The name INFORM gives it without leading zeros: C0, P105."""
        return f"{self.kind}{self.number}"

    @property
    def cartesian(self) -> bool:
        return not self.pulse

    def xyzabc(self) -> tuple[float, ...]:
        """x, y, z, rx, ry, rz of a Cartesian position."""
        return tuple(self.values[k].value + 0.0 for k in COMPONENTS)


class _Group:
    """What the ``///`` lines before a position have set."""

    __slots__ = ("tool", "user", "postype", "form")

    def __init__(self):
        self.tool: int | None = None
        self.user: int | None = None
        self.postype: str | None = None
        self.form: str | None = None        # PULSE or RECTAN, as its line says


def sniff(doc: Document) -> bool:
    """Whether a file begins ``/JOB`` (a git temporary file has no suffix),
    after blank lines of any length, as ``positions`` reads it."""
    return _HEAD.match(doc.text) is not None


def parse(doc: Document, full: bool = False) -> ControllerFile:
    """A job's lints, its name and its positions (``extra["positions"]``);
    no frames."""
    cf = ControllerFile(document=doc, vendor=VENDOR)
    cf.extra["kind"] = "job"
    found = cf.extra["positions"] = positions(doc, cf)
    cf.extra["holds"] = holds(found)
    return cf


def holds(found: list[Position]) -> str:
    """What a job holds instead of frames, for ``frames``: "6 positions
    (1 BASE, 5 USER in UF1)"."""
    kinds: dict[str, int] = {}
    for p in found:
        what = "PULSE" if p.pulse else (p.postype or "RECTAN")
        if p.kind not in ROBOT_KINDS:
            what = f"{p.kind} axes"
        elif what == "USER":
            what = f"USER in UF{p.user}" if p.user is not None else "USER (no ///USER)"
        kinds[what] = kinds.get(what, 0) + 1
    shown = ", ".join(f"{n} {k}" for k, n in kinds.items())
    return (f"a job: {len(found)} position{'s' if len(found) != 1 else ''}"
            + (f" ({shown})" if shown else "") + "; the frames it uses are UFRAME.CND's "
            "and TOOL.CND's")


def positions(doc: Document, cf: ControllerFile | None = None) -> list[Position]:
    """Every position of the job's ``//POS``, in file order. ``cf`` gets the
    lints (None: read for their positions only, as ``solve`` and ``diff
    --points`` do)."""
    lint = cf.lint if cf is not None else (lambda *a, **k: None)
    out: list[Position] = []
    group = _Group()
    section = None
    npos = None
    for pos, line in _lines(doc):
        if section is None:
            if line.strip():
                if not sniff_line(line):
                    raise doc.error("not a Yaskawa job: a job begins /JOB", pos)
                section = "JOB"
            continue
        if section == "INST":
            continue                    # the program: kept as it is
        m = _ITEM.match(line)
        if m is not None and len(m.group("slashes")) == 2:
            section = m.group("key")    # NAME, POS, INST, ... (kept as they are)
            if section == "NAME" and cf is not None:
                cf.extra["name"] = (m.group("rest") or "").strip()
            continue
        if section != "POS":
            if line.strip():
                lint(pos, "unknown-line", "a line of a job ucsio does not read, kept as it is",
                     "info")
            continue
        if m is not None and len(m.group("slashes")) == 3:
            rest = m.group("rest") or ""
            at = pos + m.start("rest") if m.group("rest") is not None else pos + len(line)
            if m.group("key") == "NPOS":
                npos = (_npos(doc, rest, at), pos)
            elif not _group_line(doc, group, m.group("key"), rest, at) and line.strip():
                lint(pos, "unknown-line", "a line of a job's //POS ucsio does not read, kept "
                     "as it is", "info")
            continue
        p = _POSITION.match(line)
        if p is not None:
            out.append(_position(doc, group, pos, line, p))
        elif line.strip():
            lint(pos, "unknown-line", "a line of a job's //POS ucsio does not read, kept as it "
                 "is", "info")
    if section is None:
        raise doc.error("not a Yaskawa job: a job begins /JOB", 0)
    if npos is not None and cf is not None:
        _lint_counts(cf, npos, out)
    return out


_MOVE = regex.lazy(r"[ \t]*S?MOV[JLCS][ \t]+(?P<name>(?:BC|EC|BP|EX|C|P)[0-9]+)\b")
_COMMENT = regex.lazy(r"[ \t]*'(?P<text>[^\r\n]*)\Z")


def names_by_comment(doc: Document) -> dict[str, str]:
    """The name each position is given by a comment line directly before a
    move to it (``'M3`` then ``MOVL C00002 V=100.0``), as a pendant shows
    the job: C00002 -> "M3". A job's positions carry no names of their own;
    this is how ``program --measure`` names its points for ``solve`` to pair.
    Where a position is commented with two names, or a name comments two
    positions, neither is used (a taught job's "'APPROACH" names nothing)."""
    names: dict[str, set[str]] = {}
    before = None
    section = None
    for _, line in _lines(doc):
        m = _ITEM.match(line)
        if m is not None and len(m.group("slashes")) == 2:
            section = m.group("key")
            continue
        if section != "INST":
            continue
        move = _MOVE.match(line)
        if move is not None and before:
            names.setdefault(move.group("name"), set()).add(before)
        comment = _COMMENT.match(line)
        before = comment.group("text").strip() if comment is not None else None
    once = {k: next(iter(v)) for k, v in names.items() if len(v) == 1}
    counts: dict[str, int] = {}
    for text in once.values():
        counts[text.casefold()] = counts.get(text.casefold(), 0) + 1
    return {k: text for k, text in once.items() if counts[text.casefold()] == 1}


def sniff_line(line: str) -> bool:
    return line.lstrip("\ufeff \t").rstrip(" \t") == "/JOB"


def _npos(doc: Document, text: str, at: int) -> tuple[int, ...]:
    fields = text.rstrip(" \t").split(",")
    if len(fields) != len(KINDS) or not all(_INT.match(f) for f in fields):
        raise doc.error("///NPOS is six counts C,BC,EC,P,BP,EX separated by commas", at)
    out, pos = [], at
    for field in fields:
        out.append(doc.integer(field, pos, "///NPOS count"))
        pos += len(field) + 1
    return tuple(out)


def _group_line(doc: Document, group: _Group, key: str, rest: str, at: int) -> bool:
    """Apply a ``///KEY rest`` line of //POS to ``group``; False where it is
    not one ucsio reads."""
    word = rest.strip()
    if key in ("TOOL", "USER"):
        if _INT.match(word) is None or word.startswith(("+", "-")):
            raise doc.error(f"///{key} is a number: {word[:30]!r}", at)
        setattr(group, key.lower(), doc.integer(word, at, f"///{key} number"))
    elif key == "POSTYPE":
        if word not in POSTYPES:
            raise doc.error(f"///POSTYPE is one of {', '.join(POSTYPES)}: {word[:30]!r}", at)
        group.postype = word
    elif key in ("PULSE", "RECTAN"):
        group.form = key
    elif key != "RCONF":                # the configuration flags: kept as they are
        return False
    return True


def _position(doc: Document, group: _Group, pos: int, line: str, m) -> Position:
    kind = m.group("kind")
    at = pos + m.end()
    number = doc.integer(m.group("number"), pos + m.start("number"), "position number")
    pulse = _is_pulse(group, kind)
    body = line[m.end():].rstrip(" \t")
    values = _values(doc, body, at, pulse, kind, line[:m.end() - 1])
    return Position(line[:m.end() - 1], kind, number, doc.line_of(pos), at, group.tool,
                    group.user, group.postype, pulse, values)


def _is_pulse(group: _Group, kind: str) -> bool:
    """Joint pulses or x..rz: as the last ///PULSE or ///RECTAN says, else
    as ///POSTYPE does (PULSE, or a Cartesian type)."""
    if group.form is not None:
        return group.form == "PULSE"
    return group.postype in (None, "PULSE")


def _values(doc: Document, body: str, at: int, pulse: bool, kind: str,
            name: str) -> dict[str, Number]:
    """The numbers of a position line, each at its span; integers for pulses,
    six (or seven) numbers for a Cartesian robot position."""
    fields = body.split(",")
    keys = _keys(pulse, kind, len(fields))
    what = "joint pulses (integers)" if pulse else "x,y,z (mm), rx,ry,rz (deg)"
    out: dict[str, Number] = {}
    pos = at
    for key, field in zip(keys, fields):
        ok = (_INT if pulse else _NUMBER).match(field) is not None
        if not ok:
            raise doc.error(f"{name}: not a number: {field[:30]!r} ({what})" if field else
                            f"{name}: a number is missing here ({what})", pos)
        value = float(field)
        if not math.isfinite(value):
            raise doc.error(f"{name}: number out of range: {field[:30]!r}", pos)
        out[key] = Number(Span(pos, pos + len(field)), field, value)
        pos += len(field) + 1
    if len(fields) != len(keys):        # where the seventh-or-more starts, or at the end
        raise doc.error(f"{name}: a Cartesian position is x,y,z,rx,ry,rz (and re): "
                        f"{len(fields)} values here", min(pos, at + len(body)))
    return out


def _keys(pulse: bool, kind: str, count: int) -> list[str]:
    """The names of a position's values: j1.. for pulses or a unit's axes,
    x..rz (and re) for a Cartesian robot position, too few or too many of
    which the caller reports."""
    if pulse or kind not in ROBOT_KINDS:
        return [f"j{i}" for i in range(1, count + 1)]
    if count in RECTAN_COUNTS:
        return list(COMPONENTS) + ["re"][:count - len(COMPONENTS)]
    if count < len(COMPONENTS):
        return list(COMPONENTS)         # zip stops at the fields: "missing" at the end
    return list(COMPONENTS) + ["re"]


def _lint_counts(cf: ControllerFile, npos: tuple, found: list[Position]) -> None:
    """///NPOS against the positions that follow: a controller checks it on
    loading a job."""
    counts, at = npos
    have = {k: 0 for k in KINDS}
    for p in found:
        have[p.kind] += 1
    wrong = [f"{k} {n} (///NPOS says {c})" for k, c, n in zip(KINDS, counts, have.values())
             if c != n]
    if wrong:
        cf.lint(at, "npos-count", "///NPOS does not count the positions that follow: "
                + ", ".join(wrong))
