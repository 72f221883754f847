"""FANUC variable listings (.va): text -> frames, through grammars/va.lark.

``sysframe.va`` lists the frames: ``$MNUFRAME`` (user frames, relative to
world) and ``$MNUTOOL`` (tool frames, relative to the faceplate), arrays of
POSITION sized [groups, frames] by each record's head (seen: [2,32],
[4,20], [4,29]), one element per frame:

    [*SYSTEM*]$MNUFRAME  Storage: SHADOW  Access: RW  : ARRAY[2,32] OF POSITION
        [1,1] =
      Group: 1   Config: N U T, 0, 0, 0
      X:  3495.600   Y:  5813.000   Z: -1166.400
      W:      .140   P:      .080   R:   -90.040

Every other listing (posreg.va, FRAMEVAR.VA, numreg.va, system.va, ...)
reads with the same grammar; it gives no frames. Two ways through it, as
for KRL (ucsio.vendors.kuka.krl):

- ``full=True`` (``ucsio check``): every byte through the grammar's tables
  (ucsio.parsing.lalr's recogniser: no tree), then the fast path for the
  frames; where the recogniser rejects, the tree of every byte gives Lark's
  positioned error (``parse_whole``).
- the fast path (``frames``, ``diff``): an outline (one regular expression)
  finds the records' head lines; the grammar parses the text with every
  line blanked except the heads, the first line and the frame records (the
  offsets and line numbers stay the file's). An element whose value and
  lines repeat an earlier one's text exactly (the unset frames, all 0, that
  fill most of a sysframe.va) is blanked too: its line up to the "=" is
  what the grammar's INDEX and "=" read (the outline's pattern is theirs),
  the rest is text the grammar read once already; it shares that element's
  reading, moved to its own offsets. An element written as the controller
  writes one (``_PLAIN``: a comment, the Group/Config line, X Y Z and W P R
  lines of plain numbers) is blanked too and read from its words, as the
  grammar would read it; any other (a comment over a line end, stars,
  units, glued tokens) goes through the grammar. A 100 KB sysframe.va costs
  one regular expression per distinct element, not 3,000 lines of parsing.

Both paths give the same frames and lints (tests/test_fanuc.py checks it on
the corpus, tests/test_va_listings.py on generated and mutated listings).
"""
from __future__ import annotations

import bisect
import re

from ...errors import UcsioError
from ...geometry.frames import Frame, Number, ShiftedNumbers
from ...parsing import regex
from . import base as fanuc
from ...parsing.document import Document, Span, lf_lines, masked, small_int
from ...parsing.lalr import Rejected, Tree
from ...parsing.model import ControllerFile

START = ("file",)
FRAME_RECORDS = {"$MNUFRAME": "UFRAME", "$MNUTOOL": "UTOOL"}
AXES = ("X", "Y", "Z", "W", "P", "R")
# FRAMEVAR.VA: SETUP_DATA[group, kind, n].$COMMENT; kind 1 the tool frames, 3
# the user frames (2: jog frames), as frame.dg orders its tables. In the corpus
# backup kjbvtu411450r01 the comments of kind 1 stand at n = 1, 2, 4, the tool
# frames its SYSFRAME.VA sets.
SETUP_KINDS = {1: "UTOOL", 3: "UFRAME"}

# -- the outline ---------------------------------------------------------------------
# a record's head line: its tag and name as the grammar's HEAD reads them
# (searched in "\n" + text: offsets one more than in the text)
_HEAD_LINE = regex.lazy(r"\n[ \t\f\r]*\[[^\]\n0-9 ,][^\]\n]*\]([^\s]+)")
_FIRST = regex.lazy(r"[^\s]")
# an element's line up to its "=": the grammar's WS? INDEX WS? "=" (searched
# in "\n" + text; group 1 the INDEX)
_ELEMENT = regex.lazy(r"\n[ \t\f\r]*(\[[0-9 ,]*\])[ \t\f\r]*=")
# A frame element as the controller writes it, from its INDEX to the next
# element (fullmatch from the INDEX's line start; the grammar's terminals,
# WS between them, each line's end and the blank lines after it its _NL):
#     [1,1] =   'FIXTURE'
#   Group: 1   Config: N U T, 0, 0, 0
#   X:  3495.600   Y:  5813.000   Z: -1166.400
#   W:      .140   P:      .080   R:   -90.040
# The fast path reads such an element from these groups instead of the
# grammar; anything else (a comment over a line end, an inline group, units,
# stars, glued tokens) goes to the grammar as before.
_B = r"[ \t\f\r]"                        # WS
_NUM = r"([+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)"
_COORDS = "".join(rf"{_B}*({axis})[ \t]*:{_B}*{_NUM}" + (rf"{_B}*\n[ \t\f\r\n]*" if axis in "ZR"
                                                           else rf"{_B}+")
                  for axis in "XYZWPR")
_PLAIN = regex.lazy(rf"{_B}*\[[0-9 ,]*\]{_B}*={_B}*(?:('[^'\n]*'){_B}*)?\n[ \t\f\r\n]*"
                    rf"(Group)[ \t]*:{_B}*([0-9]+){_B}*Config[ \t]*:{_B}*"
                    rf"([^\s](?:[^\n]*[^\s])?)?{_B}*\n[ \t\f\r\n]*{_COORDS}")
# FRAMEVAR.VA: a SETUP_DATA comment that is not empty
# (its string on the line, or on the next: a long one)
_COMMENT_FIELD = regex.lazy(r"\n[ \t\f\r]*Field:[ \t\f\r]+SETUP_DATA\[[^\n]*\$COMMENT[^\n=]*="
                            r"[ \t\f\r]*(?:\n[ \t\f\r]*)?'[^'\n]")
# a record's type, from its DESC: ... : ARRAY[2,32] OF POSITION
_ARRAY = regex.lazy(r"ARRAY\[([0-9 ,]*)\][ \t]+OF[ \t]+(.+)\Z")
_PATH_INDEX = regex.lazy(r"SETUP_DATA\[([0-9]+),([0-9]+),([0-9]+)\]\.\$COMMENT\Z", re.I)


def _records(nl: str):
    """(offset of the head line's start, name upper-case, end) of each
    record of ``nl`` ("\n" + the text), in text offsets: a record runs to
    the next head line."""
    heads = [(m.start(), m.group(1).upper()) for m in _HEAD_LINE.finditer(nl)]
    out = []
    for i, (start, name) in enumerate(heads):
        end = heads[i + 1][0] if i + 1 < len(heads) else len(nl) - 1
        out.append((start, name, end))
    return out


def _line_end(text: str, pos: int) -> int:
    end = text.find("\n", pos)
    return len(text) if end < 0 else end


def _kept_end(text: str, pos: int) -> int:
    """Where the line at ``pos`` ends, or the line its last string ends on
    where that string runs over the line end (a listing's strings hold no
    quote: an odd count leaves one open)."""
    end = _line_end(text, pos)
    while text.count("'", pos, end) % 2:
        close = text.find("'", end)
        if close < 0:
            return len(text)
        pos, end = close + 1, _line_end(text, close)
    return end


def outline(text: str, wanted) -> tuple[list[tuple[int, int]], dict, dict]:
    """The spans the fast path keeps: every record's head line, the file's
    first line, and where ``wanted(name)`` says "record" the whole record
    (its repeated elements blanked: see the module's doc) or "comments" its
    SETUP_DATA comment lines. Returns (spans, shared, plain), ``shared``
    mapping the INDEX offset of an element left out to (its INDEX text, the
    INDEX offset of the first element with its text, the offset from that
    one's "=" to this one's), ``plain`` the INDEX offset of an element read
    from its words (``_PLAIN``) to (its INDEX text, its Entry)."""
    spans = []
    shared: dict[int, tuple[str, int, int]] = {}
    plain: dict[int, tuple[str, Entry]] = {}
    seen: dict[str, tuple[int, int]] = {}
    extent: dict[int, tuple[int, int]] = {}     # a left-out element's text (INDEX offset ->)
    first = _FIRST.search(text)
    if first is not None:
        s = text.rfind("\n", 0, first.start()) + 1
        spans.append((s, _kept_end(text, s)))
    nl = "\n" + text           # the line patterns start with the "\n" before a line
    for start, name, end in _records(nl):
        head_end = _kept_end(text, start)
        how = wanted(name)
        if how == "record":
            spans += _record_spans(text, nl, start, end, seen, shared, plain, extent)
        else:
            spans.append((start, head_end))
            if how == "comments":
                for m in _COMMENT_FIELD.finditer(nl, head_end + 1, end + 1):
                    s = m.start()           # the "\n" in nl: the line's start in text
                    spans.append((s, _kept_end(text, m.end() - 3)))    # from its quote on
    merged = _merged(spans)
    # A kept span may run over an element left out (a head whose string runs over its
    # line end keeps the text up to where the string closes): the grammar reads such an
    # element, so it is not read from its words or shared as well (it would be listed
    # twice). Kept whole, and the spans merged again, until none is left half read.
    while True:
        starts = [s for s, _ in merged]
        covered = []
        for index, (s, e) in extent.items():
            i = bisect.bisect_right(starts, e - 1) - 1      # the last span starting before e
            if i >= 0 and merged[i][1] > s:
                covered.append(index)
        if not covered:
            return merged, shared, plain
        for index in covered:
            merged.append(extent.pop(index))
            shared.pop(index, None)
            plain.pop(index, None)
        merged = _merged(merged)


def _merged(spans: list[tuple[int, int]]) -> list[tuple[int, int]]:
    """Spans sorted, those that overlap or touch made one."""
    merged: list[tuple[int, int]] = []
    for s, e in sorted(spans):              # the first line is a record's head, say
        if merged and s <= merged[-1][1]:
            merged[-1] = (merged[-1][0], max(merged[-1][1], e))
        else:
            merged.append((s, e))
    return merged


def _record_spans(text: str, nl: str, start: int, end: int, seen: dict,
                  shared: dict, plain: dict, extent: dict) -> list[tuple[int, int]]:
    """A frame record's text as spans, each element left out where an
    earlier element of the file wrote exactly the same after its "="
    (``seen``: that text -> (INDEX offset, offset after the "=") of the
    first; ``shared`` gets the later ones), or where it is written as the
    controller writes one (``_PLAIN``: ``plain`` gets its Entry); ``extent``
    gets each left-out element's text (line start, end). ``nl``: "\n" +
    ``text``."""
    fullmatch = _PLAIN.fullmatch
    # (line start, INDEX offset, INDEX text, offset after the "="), in text offsets
    marks = [(m.start(), m.start(1) - 1, m.group(1), m.end() - 1)
             for m in _ELEMENT.finditer(nl, start + 1, end + 1)]
    if not marks:
        return [(start, end)]
    spans = []
    pos = start
    for i, (line, index, key, eq) in enumerate(marks):
        tail_end = marks[i + 1][0] if i + 1 < len(marks) else end
        src = seen.setdefault(text[eq:tail_end], (index, eq))
        if src[0] != index:
            shared[index] = (key, src[0], eq - src[1])
        else:
            m = fullmatch(text, line, tail_end)
            if m is None:
                continue                # the grammar reads it
            plain[index] = (key, _plain_entry(m))
        extent[index] = (line, tail_end)
        spans.append((pos, line))
        pos = tail_end
    spans.append((pos, end))
    return [s for s in spans if s[0] < s[1]]


# -- parsing -----------------------------------------------------------------------
def _parser():
    from ...parsing.grammar import parser
    return parser("va", START)


_READABLE = {"_NL": "end of line", "HEAD": "a record ([*SYSTEM*]$NAME ...)",
             "INDEX": "an element ([g,n] = ...)", "FIELD": "Field:", "GROUP": "Group:",
             "CONFIG": "Config:", "AXIS": "a coordinate (X:, W:, J1 =)",
             "NUMBER": "a number", "STARS": "a number", "INT": "an integer",
             "STRING": "a 'comment'", "UNINIT": "Uninitialized", "SCALAR": "a value",
             "DESC": "its type", "PATH": "a name", "UNIT": "mm or deg",
             "CONFIG_TEXT": "a configuration", "EQUAL": "'='", "COLON": "':'", "$END":
             "end of file"}


def _parse(doc: Document, text: str, lark_first: bool = False) -> Tree:
    return fanuc.tree("va", doc, text, _READABLE, "not a FANUC variable listing", lark_first)


def _lines(doc: Document) -> str:
    """The text the grammar reads: every line ends at LF (a bare CR made an
    LF, same length: Document.line_starts' rule)."""
    text = lf_lines(doc.text)
    if not text.strip():
        raise doc.error("empty file: no FANUC variable listing", 0)
    return text


def parse(doc: Document, full: bool = False, beside: bool = True) -> ControllerFile:
    """The frames of a variable listing (none unless it is a sysframe.va);
    ``full`` (``check``): every byte through the grammar first; ``beside``:
    label the frames from frame.dg / FRAMEVAR.VA beside the file."""
    text = _lines(doc)
    if full:
        try:
            _parser().recognise(text, "file")
        except Rejected:
            return _whole(doc, text, lark_first=True, beside=beside)
    spans, shared, plain = outline(text, _frames_wanted)
    try:
        return _interpret(doc, _parse(doc, masked(text, spans)), shared, beside, plain)
    except (UcsioError, _Unshared):
        # The outline reads strings as the grammar does in every listing a controller
        # writes; in a damaged one it may close a string elsewhere, and the blanked text
        # then reads otherwise than the whole (an error where there is none, or an
        # element that repeats one the grammar never read). The whole text says what
        # is right: its frames, or its error.
        return _whole(doc, text, beside=beside)


def _frames_wanted(name: str):
    return "record" if name in FRAME_RECORDS else None


def parse_whole(doc: Document, beside: bool = True) -> ControllerFile:
    """``parse(doc, full=True)`` from the tree of every byte: the reference
    the fast path is tested against."""
    return _whole(doc, _lines(doc), beside=beside)


def _whole(doc: Document, text: str, lark_first: bool = False,
           beside: bool = True) -> ControllerFile:
    return _interpret(doc, _parse(doc, text, lark_first), {}, beside)


# -- the tree, read -------------------------------------------------------------------
class Entry:
    """What a member's line and the lines below it say (an element, a field,
    or the record's own value): ``comment`` ('@Home'), ``group``, ``config``,
    ``uninit``, ``scalar`` (any other value), ``coords`` {axis (X, W, J1,
    EXT1): Number, or None for ********}, ``joints`` (a joint position),
    ``dups`` (axes given twice, with offsets). Offsets are where the
    entry was parsed; a Member says how far its own text is from there."""

    __slots__ = ("comment", "comment_pos", "group", "group_pos", "config", "uninit", "scalar",
                 "coords", "axis_pos", "joints", "dups")


class Member:
    """A record's element (``key`` its index, [1,2]) or field (``key`` its
    path), at ``pos``; ``entry`` read ``delta`` characters before (0 but for
    an element that repeats an earlier one's text: the fast path reads
    that once)."""

    __slots__ = ("kind", "key", "pos", "entry", "delta")

    def __init__(self, kind: str, key: str, pos: int, entry: Entry, delta: int = 0):
        self.kind, self.key, self.pos, self.entry, self.delta = kind, key, pos, entry, delta


def _entry(children) -> Entry:
    """An Entry from a member's children after its INDEX/PATH/DESC."""
    e = Entry.__new__(Entry)
    e.comment = e.comment_pos = e.group = e.group_pos = e.config = e.scalar = None
    e.uninit = e.joints = False
    e.coords, e.axis_pos, e.dups = {}, {}, []
    for c in children:
        if isinstance(c, Tree):
            d = c.data
            if d == "group":
                _group(e, c)
            elif d == "xyz" or d == "joints":
                e.joints = e.joints or d == "joints"
                for ax in c.children:
                    name = ax.children[0]
                    key = name.value.upper()
                    if key in e.coords:
                        e.dups.append((key, name.start_pos))
                        continue
                    v = ax.children[1]
                    e.axis_pos[key] = name.start_pos
                    e.coords[key] = (None if v.type == "STARS" else
                                     Number(Span(v.start_pos, v.end_pos), v.value, float(v.value)))
            continue
        t = c.type
        if t == "STRING":       # '@Home', the comment of `1  'Chip 1'`, a string's value
            e.comment, e.comment_pos = c.value[1:-1], c.start_pos
        elif t == "UNINIT":
            e.uninit = True
        elif t == "SCALAR":
            e.scalar = c.value
    return e


def _plain_entry(m) -> Entry:
    """The Entry the grammar reads from an element ``_PLAIN`` matched."""
    e = Entry.__new__(Entry)
    e.scalar = None
    e.uninit = e.joints = False
    e.dups = []
    comment = m.group(1)
    e.comment, e.comment_pos = (comment[1:-1], m.start(1)) if comment else (None, None)
    e.group_pos = m.start(2)
    e.group = int(m.group(3)) if len(m.group(3)) < 10 else -1
    e.config = m.group(4) or ""
    e.coords, e.axis_pos = {}, {}
    for i in range(5, 17, 2):
        axis, number = m.group(i), m.group(i + 1)
        e.axis_pos[axis] = m.start(i)
        e.coords[axis] = Number(Span(m.start(i + 1), m.end(i + 1)), number, float(number))
    return e


def _group(e: Entry, node: Tree) -> None:
    ch = node.children
    e.group_pos = ch[0].start_pos
    e.group = int(ch[1].value) if len(ch[1].value) < 10 else -1
    e.config = ch[3].value if len(ch) > 3 else ("" if len(ch) > 2 else None)


class Record:
    """A record: ``name`` ($MNUFRAME), its ``tag`` (*SYSTEM*), what its head
    declares (``desc``; ``dims`` and ``elem_type`` of an array), its own
    ``value`` (an Entry) and its ``members`` (Member)."""

    __slots__ = ("name", "tag", "head_pos", "line", "desc", "dims", "elem_type", "value",
                 "members")


def records(tree: Tree, doc: Document, shared: dict | None = None,
            plain: dict | None = None) -> list[Record]:
    """The records of a tree, read; the fast path's elements left out of
    it: ``shared`` those that repeat an earlier one, which take its Entry,
    ``plain`` those read from their words (``outline``)."""
    read: dict[int, Entry] = {pos: entry for pos, (_key, entry) in (plain or {}).items()}
    out = []
    for node in tree.children:
        if not isinstance(node, Tree) or node.data != "record":
            continue
        ch = node.children
        head = ch[0]
        r = Record.__new__(Record)
        close = head.value.index("]")
        r.tag, r.name = head.value[1:close], head.value[close + 1:]
        r.head_pos, r.line = head.start_pos, doc.line_of(head.start_pos)
        r.desc = ch[1].value if len(ch) > 1 and getattr(ch[1], "type", None) == "DESC" else ""
        r.dims, r.elem_type = _type_of(r.desc)
        r.value = _entry([c for c in ch[1:] if not (isinstance(c, Tree) and c.data in
                                                     ("element", "field"))
                          and getattr(c, "type", None) != "DESC"])
        r.members = []
        for m in ch:
            if not isinstance(m, Tree) or m.data not in ("element", "field"):
                continue
            mc = m.children
            if m.data == "element":
                key_tok, rest = mc[0], mc[1:]
            else:
                key_tok = mc[1]
                rest = [c for c in mc[2:] if getattr(c, "type", None) != "DESC"]
            pos = key_tok.start_pos
            e = read[pos] = _entry(rest)
            r.members.append(Member(m.data, key_tok.value, pos, e))
        out.append(r)
    if shared or plain:
        _rejoin(out, shared or {}, plain or {}, read)
    return out


class _Unshared(Exception):
    """An element the fast path left out repeats one the grammar did not
    read as an element (a string over a line end swallowed it): there is no
    reading to share, and the whole text is read instead (``parse``)."""


def _rejoin(recs: list[Record], shared: dict, plain: dict, read: dict) -> None:
    """Put the elements the fast path left out back into their records, in
    file order: each read from its words with its Entry, each repeating an
    earlier one with that one's Entry."""
    import bisect
    heads = [r.head_pos for r in recs]
    touched = set()
    left_out = [(pos, key, read[pos], 0) for pos, (key, _e) in plain.items()]
    for pos, (key, src, delta) in shared.items():
        if src not in read:     # the element it repeats is no element to the grammar
            raise _Unshared
        left_out.append((pos, key, read[src], delta))
    for pos, key, entry, delta in left_out:
        i = bisect.bisect_right(heads, pos) - 1
        recs[i].members.append(Member("element", key, pos, entry, delta))
        touched.add(i)
    for i in touched:
        recs[i].members.sort(key=lambda m: m.pos)


def _type_of(desc: str):
    """(dims, element type) of ``... : ARRAY[2,32] OF POSITION``; (None,
    type) for a scalar (``... : POSITION``, ``... : INTEGER``)."""
    typ = desc.rpartition(":")[2].strip() if ":" in desc else desc.strip()
    m = _ARRAY.search(typ)
    if m is None:
        return None, typ
    dims = tuple(small_int(d) if d.strip() else None for d in m.group(1).split(","))
    return (() if None in dims else dims), m.group(2).strip()


def _index(text: str):
    """[1,2] -> (1, 2); None for anything else."""
    g, comma, n = text[1:-1].partition(",")
    if comma and g.isdecimal() and n.isdecimal() and len(g) < 10 and len(n) < 10:
        return int(g), int(n)           # the usual [g,n], without the general split
    parts = text[1:-1].split(",")
    if len(text) > 20 and any(len(p.strip()) >= 10 for p in parts):
        return None         # a 10-digit index: not a frame's (and no huge int() below)
    try:
        return tuple(map(int, parts))
    except ValueError:
        return None


def _moved(numbers: dict, delta: int):
    """``numbers`` (component -> Number) ``delta`` characters further on,
    made only when a span is asked for (``ShiftedNumbers``)."""
    if not delta:
        return dict(numbers)
    return ShiftedNumbers(numbers, delta)


# -- frames ---------------------------------------------------------------------------
def _interpret(doc: Document, tree: Tree, shared: dict, beside: bool = True,
               plain: dict | None = None) -> ControllerFile:
    cf = fanuc.controller_file(doc)
    recs = records(tree, doc, shared, plain)
    names = {r.name.upper() for r in recs}
    cf.extra["records"] = [r.name for r in recs]
    frame_recs = [r for r in recs if r.name.upper() in FRAME_RECORDS]
    cf.extra["kind"] = ("sysframe" if frame_recs else "posreg" if "$POSREG" in names
                        else "framevar" if "SETUP_DATA" in names else "variables")
    if frame_recs:
        labels, errors = _labels_beside(doc.path) if beside else ({}, [])
        for exc in errors:
            cf.lint(0, "label-source", f"{_where(exc)} could not be read ({exc.message}): "
                                       "frames listed without its comments", severity="info")
        seen: dict[str, int] = {}
        made: dict[int, tuple] = {}
        for r in frame_recs:
            _frames_of(cf, r, labels, seen, made)
    return cf


def _where(exc: UcsioError) -> str:
    import os
    return os.path.basename(exc.file or "") or "a file beside it"


def _labels_beside(path: str) -> tuple[dict, list]:
    from . import dg
    return fanuc.labels_beside(path, {"framevar.va": frame_comments, "frame.dg": dg.frame_labels})


def _frames_of(cf: ControllerFile, r: Record, labels: dict, seen: dict, made: dict) -> None:
    """The frames of a $MNUFRAME or $MNUTOOL record. ``made``: the numbers
    and pose of each Entry already read without a finding, by id: an element
    that repeats it (the fast path's shared ones) moves them to its offsets."""
    doc = cf.document
    ftype = FRAME_RECORDS[r.name.upper()]
    reference = fanuc.KINDS[ftype][1]
    dims = r.dims
    if dims is None or len(dims) != 2 or r.elem_type.upper() != "POSITION":
        cf.lint(r.head_pos, "not-a-frame-array",
                f"{r.name} is {r.desc.rpartition(':')[2].strip() or 'untyped'}: expected "
                "ARRAY[groups,frames] OF POSITION; no frames read from it")
        return
    import bisect
    starts = doc.line_starts        # a frame's line: hundreds of them, one bisect each
    for m in r.members:
        if m.kind != "element":
            cf.lint(m.pos, "not-a-frame-array", f"{r.name}: a Field in an array of frames")
            continue
        index = _index(m.key)
        if index is None or len(index) != 2:
            cf.lint(m.pos, "index-out-of-range",
                    f"{r.name}{m.key}: a frame's index is [group,frame]")
            continue
        g, n = index
        line = bisect.bisect_right(starts, m.pos)
        if not (1 <= g <= dims[0] and 1 <= n <= dims[1]):
            cf.lint(m.pos, "index-out-of-range",
                    f"{r.name}{m.key} is outside the declared size [{dims[0]},{dims[1]}]")
        e, delta = m.entry, m.delta
        name = fanuc.frame_name(ftype, n, g)
        if e.group is not None and e.group != g:
            cf.lint(e.group_pos + delta, "group-mismatch",
                    f"{name}: the element [{g},{n}] says Group: {e.group}")
        # the element's own comment ([1,1] =   'FIXTURE'), else the one beside it
        label = (e.comment or "").strip() or labels.get((ftype, n, g))
        got = made.get(id(e))
        if got is None:
            before = len(cf.lints)
            numbers = _frame_numbers(cf, r.name + m.key, e, m.pos, delta)   # at e's offsets
            info = {"config": (e.config.strip() or None) if e.config is not None else None}
            fr = fanuc.make_frame(doc, ftype, n, g, line, numbers and _moved(numbers, delta),
                                  label=label, info=info)
            if len(cf.lints) == before:
                made[id(e)] = (numbers, fr)
        else:                            # as the element it repeats, at its own place
            numbers, like = got
            info = dict(like.info)
            info["group"] = g
            fr = Frame(name, fanuc.VENDOR, ftype, like.pose, doc.path, line, reference, label,
                       numbers and _moved(numbers, delta), info, doc, fanuc.parent(ftype, g))
        key = name.upper()
        if key in seen:
            cf.lint(m.pos, "duplicate-frame",
                    f"{name} is listed twice (lines {seen[key]} and {line})")
        else:
            seen[key] = line
        cf.frames.append(fr)


def _frame_numbers(cf: ControllerFile, what: str, e: Entry, pos: int, delta: int):
    """The six numbers of a frame element (at the offsets ``e`` was read at),
    or None (with a lint) where it has no complete X Y Z W P R."""
    if e.uninit:
        cf.lint(pos, "no-value", f"{what} is Uninitialized: listed without a value",
                severity="info")
        return None
    if e.joints:
        cf.lint(pos, "not-a-frame", f"{what} holds joint values, not X Y Z W P R")
        return None
    if not e.coords:
        cf.lint(pos, "missing-component", f"{what} has no X Y Z W P R: listed without a value")
        return None
    for key, at in e.dups:
        cf.lint(at + delta, "duplicate-component", f"{what}: {key} given twice")
    nums = {}
    complete = True
    for key, n in e.coords.items():
        at = e.axis_pos[key] + delta
        if key not in AXES:
            cf.lint(at, "unknown-component", f"{what}: a frame has no component {key}")
            continue
        if n is None:
            cf.lint(at, "not-a-number", f"{what}: {key} is not a number (********)")
            complete = False
            continue
        if not abs(n.value) <= fanuc.REAL_MAX:
            raise cf.document.error(f"number {n.text[:30]} is out of range for a FANUC REAL "
                                    "(float32)", n.span.start + delta)
        why = fanuc.range_problem(key.lower(), n.value)
        if why:
            cf.lint(n.span.start + delta, "out-of-range", f"{what}: {why}")
        nums[key.lower()] = n
    missing = [k for k in AXES if k not in e.coords]
    if missing:
        cf.lint(pos, "missing-component",
                f"{what}: {' '.join(missing)} missing: listed without a value")
        return None
    if not complete:
        return None
    return {k: nums[k] for k in fanuc.COMPONENTS}


# -- the other listings, for the readers that need them --------------------------------
def frame_comments(doc: Document) -> dict:
    """FRAMEVAR.VA's frame comments: {(type, n, group): comment} from the
    SETUP_DATA[g,1,n] (tool frames) and [g,3,n] (user frames) comments that
    are not blank, read through the grammar (the record's head and those
    lines; the rest blanked)."""
    text = _lines(doc)
    spans, _, _ = outline(text, lambda name: "comments" if name == "SETUP_DATA" else None)
    tree = _parse(doc, masked(text, spans))
    return comments_of(records(tree, doc))


def comments_of(recs: list[Record]) -> dict:
    out = {}
    for r in recs:
        if r.name.upper() != "SETUP_DATA":
            continue
        for member in r.members:
            e = member.entry
            m = _PATH_INDEX.search(member.key) if member.kind == "field" else None
            if m is None or e.comment is None or not e.comment.strip():
                continue
            g, k, n = map(small_int, m.groups())      # None: beyond 32 bits, no frame's
            if k in SETUP_KINDS and None not in (g, n):
                out[(SETUP_KINDS[k], n, g)] = e.comment.strip()
    return out


def position_registers(doc: Document) -> dict:
    """posreg.va's registers: {(group, n): Entry} for every $POSREG element
    (comment, group, config, coords: X..R or J1..; ``uninit``), from the
    tree of every byte."""
    return {(g, n): e for g, n, _pos, e in register_list(doc)}


def register_list(doc: Document) -> list[tuple[int, int, int, Entry]]:
    """posreg.va's $POSREG elements in file order: (group, n, the offset of
    the element's ``[g,n]``, its Entry), from the tree of every byte."""
    tree = _parse(doc, _lines(doc))
    out = []
    for r in records(tree, doc):
        if r.name.upper() != "$POSREG":
            continue
        for member in r.members:
            index = _index(member.key) if member.kind == "element" else None
            if index is not None and len(index) == 2:
                out.append((index[0], index[1], member.pos, member.entry))
    return out
