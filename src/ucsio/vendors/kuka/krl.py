"""KUKA KRL data lists ($config.dat, program .dat): text -> frames, through
grammars/krl.lark.

KRL data lists are line-oriented: one declaration or element initialisation
per line, no terminator, ``;`` starts a comment. Two ways through the same
grammar:

- ``full=True`` (``ucsio check``): every byte of the file goes through the
  grammar (start symbol ``file``) first, so a syntax error anywhere is found:
  the recogniser (ucsio.parsing.lalr: the grammar's LALR table and lexer, no
  tree), then the fast path below for the frames. Where the recogniser
  rejects, ``parse_whole`` (the tree of every byte) gives the positioned
  error.
- the fast path (``ucsio frames``, ``diff``, ``patch``): a line-oriented
  outline (a few regular expressions, one pass each) picks the lines that
  matter for frames: FRAME declarations, element lines of FRAME arrays,
  the TOOL/BASE name and type tables, LOAD_DATA, the MAX_* sizes, and the
  MACHINE_FRAME_DAT entries that tie a base to an external kinematic (with
  the MACHINE_DEF entries they name); and the lines that make the file's
  layout (``_layout_lines``: the ``&`` header lines, the DEFDAT and ENDDAT
  lines, the first statement line, the first one after ENDDAT). Every other
  character is replaced by a space (newlines kept), so offsets and line
  numbers are those of the real file, and the grammar parses that masked text in
  one call, with the same start symbol ``file``: a layout ``check`` rejects
  (text after ENDDAT, a second or malformed DEFDAT, a header or a statement
  before DEFDAT where it cannot be, no ENDDAT) fails the fast path too, with
  the same message at the same place. A value repeated on several element lines (zero frames, unset
  loads) is parsed once: the later copies become a placeholder and
  share the first one's tree, moved to their own offsets. A 120 KB
  $config.dat costs about 200 short lines and 1,800 tokens, not
  3,000 lines.

Both paths feed the same interpretation, which only looks at those
statements, so they give identical frames and lints (tests/test_krl.py checks
that on the whole corpus).

Frames: ``TOOL_DATA[n]`` (relative to the flange; TOOL_TYPE gives the role:
tool, or robot-guided workpiece for #TCP), ``BASE_DATA[n]`` (relative to world,
or to an external kinematic when ``MACHINE_FRAME_DAT[n].MACH_DEF_INDEX`` is not
0; BASE_TYPE #TCP marks an external, fixed TCP), labelled from
``TOOL_NAME[n,]``/``BASE_NAME[n,]``; and every other FRAME variable or FRAME
array element, under its declared spelling (``gfBaseShift[2]``), reference
``unknown`` since KRL does not say. E6POS/POS points are not frames.
"""
from __future__ import annotations

import re

from ...errors import MAX_NESTING, TooDeep, UcsioError
from ...geometry.frames import Frame, Number, Pose, unit
from ...values import Value
from ...parsing import regex
from ...parsing.document import Document, Span, lf_lines, masked
from ...parsing.lalr import Rejected, Token, Tree, paused_gc
from ...parsing.model import ControllerFile
from ...parsing.numbers import bad_number

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from typing import Any

VENDOR = "kuka"
START = ("file",)
# What TOOL_TYPE[n] / BASE_TYPE[n] (ENUM IPO_M_T: the interpolation mode the
# entry is used with) say. FORMATS.md 2.7 [M] read TOOL_TYPE #BASE as "external
# TCP, relative to world" and BASE_TYPE #TCP as "relative to the flange". The
# corpus contradicts it: six of the seven real $config.dat with named tools have
# TOOL_TYPE[1]=#BASE for plainly robot-held tools (GripperBP2, VENTOSA_SACOS,
# gripperFingers, Spindle, cutters), and Zinkerreka's BASE_TYPE[2]=#TCP entry is
# named "laserTCP", a fixed tool. That is KUKA's $IPO_MODE: #BASE = normal
# (robot-held tool, fixed base), #TCP = external TCP. KSS stores a fixed tool in
# the BASE table and a robot-guided workpiece in the TOOL table, so TOOL_DATA is
# always relative to the flange and BASE_DATA to world (or to an external
# kinematic, MACHINE_FRAME_DAT); the type only gives the role.
TOOL_ROLES = {"#NONE": "tool", "#BASE": "tool", "#TCP": "workpiece"}
BASE_ROLES = {"#NONE": "base", "#BASE": "base", "#TCP": "external_tcp"}
LABEL_MAX = 24                      # TOOL_NAME/BASE_NAME are CHAR [n,24]
REAL_MAX = 3.4028235e38             # KRL REAL is float32
COMPONENTS = ("x", "y", "z", "a", "b", "c")

# $config.dat tables read besides the FRAME arrays themselves. MACHINE_FRAME_DAT
# and MACHINE_DEF (external kinematics) only matter for a base tied to one: the
# interpretation ignores a MACHINE_FRAME_DAT[n] whose MACH_DEF_INDEX is 0 (or
# missing) and reads MACHINE_DEF[k] only through such an index, so the fast
# path reads just the MACHINE_FRAME_DAT lines whose index may not be 0 and the
# MACHINE_DEF lines they may point at.
TABLES = ("TOOL_DATA", "BASE_DATA", "TOOL_NAME", "BASE_NAME", "TOOL_TYPE", "BASE_TYPE",
          "LOAD_DATA")
MACHINE_TABLES = ("MACHINE_FRAME_DAT", "MACHINE_DEF")

# -- the outline (fast path) --------------------------------------------------
# Whitespace is the grammar's WS, [ \t\f\r]; a line is what ends at "\n". The
# line patterns start with the "\n" before the line (searched in "\n" + text):
# a literal first character lets the regex engine skip to the next newline
# instead of trying every position, as ^ with re.M would (4x faster).
_WS = r"[ \t\f\r]"
_MODS = _WS + r"*(?:(?:DECL|GLOBAL|CONST)" + _WS + r"+)*"
# FRAME declarations (group 2 set) and INT MAX_* sizes
_DECL_LINE = regex.lazy(r"\n(" + _MODS + r"(?:(FRAME)" + _WS + r"|INT" + _WS + r"+MAX_)[^\n]*)",
                        re.I)
_DEFDAT = regex.lazy(r"^[ \t\f\r]*DEFDAT[ \t\f\r]+([A-Za-z_$][\w$]*)(?:[ \t\f\r]+(PUBLIC)\b)?", re.I | re.M)
# the layout lines: `&` headers (group 1 unset) and lines that start with the
# word DEFDAT or ENDDAT as the grammar's NAME would end it (group 1 "E" for
# ENDDAT); and statement lines: not blank, not a comment, not a header
_LAYOUT_LINE = regex.lazy(r"\n[ \t\f\r]*(?:&|(?:DEF|(END))DAT(?![A-Za-z0-9_$]))", re.I)
_PROGRAM = regex.lazy(r"^[ \t\f\r]*DEF[ \t]", re.I | re.M)
_STATEMENT_LINE = regex.lazy(r"\n[ \t\f\r]*[^ \t\f\r\n;&]")
_IDENT = regex.lazy(r"[A-Za-z_$][\w$]*")
_BRACED = regex.lazy(r"\{[^}\n]*\}?|\"[^\"\n]*\"?")
# the left-hand side of an element line: NAME, NAME[...]
_ASSIGN_LHS = regex.lazy(r"[ \t\f\r]*[A-Za-z_$][\w$]*[ \t\f\r]*(?:\[[^\]]*\][ \t\f\r]*)?\Z")
# error reporting only: compiled when needed
_STATEMENT_BEFORE = r"^[ \t\f\r]*[^\s;&]"
# the field and the NUMBER token the grammar reads as its value
_MACH_DEF_INDEX = regex.lazy(r"MACH_DEF_INDEX[ \t\f\r]*(?:\[[ \t\f\r]*\][ \t\f\r]*)?"
                             r"([+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)",
                             re.I)


# An element line ``NAME[...]=...`` / ``NAME=...`` of any table: group 2 the
# name, group 3 "[" or "=", group 4 the first index if so written. Which
# names matter is decided in Python with a set: an alternation of every
# declared name (thousands in a program .dat) made each line cost as many
# tries as there are names, quadratic in the file.
_ELEMENT_LINE = regex.lazy(r"\n(" + _WS + r"*([A-Za-z_$][\w$]*)" + _WS + r"*([\[=])(?:" + _WS +
                           r"*([0-9]+))?[^\n]*)")


def outline(text: str, nl_text: str | None = None,
            layout: list[tuple[int, int]] | None = None) -> list[tuple[int, int]]:
    """Spans (start, end) of the lines the frames depend on, in order; each
    span is a line's content without its newline. ``nl_text`` ("\n" +
    text) and ``layout`` (``_layout_lines``) where the caller has them."""
    spans = []
    names = set(TABLES)
    if nl_text is None:
        nl_text = "\n" + text       # offsets in nl_text are one more than in text
    for m in _DECL_LINE.finditer(nl_text):
        spans.append((m.start(1) - 1, m.end(1) - 1))
        if m.group(2) is not None:
            # every identifier on a FRAME line outside {...}, "..." and the
            # comment: a superset of the declared names, all the filter needs.
            rest = _BRACED.sub(" ", m.group(1)).split(";", 1)[0]
            names.update(n.upper() for n in _IDENT.findall(rest))
    # MACHINE_FRAME_DAT and MACHINE_DEF, unless declared as FRAMEs (then every
    # element line is a frame)
    machine = names.isdisjoint(MACHINE_TABLES)
    if not machine:
        names.update(MACHINE_TABLES)
    mframes = []
    mdefs = []
    # most element lines are of no table read here: the name decides first.
    # Group 1 starts right after the match's "\n" and ends with the match, so
    # the line's span in text is (m.start(), m.end() - 1).
    append = spans.append
    for m in _ELEMENT_LINE.finditer(nl_text):
        name = m[2].upper()
        if name in names:           # never a MACHINE_* name where ``machine``
            s, e = m.span()
            append((s, e - 1))
        elif machine and name == "MACHINE_FRAME_DAT":
            s, e = m.span()
            mframes.append(((s, e - 1), m[1]))
        elif machine and name == "MACHINE_DEF":
            s, e = m.span()
            mdefs.append(((s, e - 1), m[3] == "[" and m[4]))
    if mframes:
        spans += _machine_lines(mframes, mdefs)
    spans += _layout_lines(text, nl_text) if layout is None else layout
    return sorted(set(spans))


def _layout_lines(text: str, nl_text: str) -> list[tuple[int, int]]:
    """The lines that decide whether the file's layout is what the grammar's
    ``file`` accepts, as spans: every ``&`` header line, every line that
    starts with the word DEFDAT or ENDDAT, the first statement line (what
    comes first after the headers: DEFDAT, or a fragment's first statement)
    and the first statement line after each ENDDAT line (the grammar allows
    only blank and comment lines there). Statement lines are independent of
    each other, so with these lines kept, the masked text breaks the layout
    exactly where the file does; the lines left out can only hold errors
    within a statement, which ``check`` finds."""
    spans = []
    n = len(text)

    def line(m) -> tuple[int, int]:
        start = m.start()               # nl_text offset of the "\n" = text offset of the line
        end = text.find("\n", start)
        return start, n if end < 0 else end

    first = _STATEMENT_LINE.search(nl_text)
    if first is not None:
        spans.append(line(first))
    for m in _LAYOUT_LINE.finditer(nl_text):
        span = line(m)
        spans.append(span)
        if m.group(1) is not None:     # ENDDAT: what follows it
            after = _STATEMENT_LINE.search(nl_text, span[1] + 1)
            if after is not None:
                spans.append(line(after))
    return spans


def _machine_lines(mframes, mdefs) -> list[tuple[int, int]]:
    """The MACHINE_FRAME_DAT lines that may tie a base to an external kinematic
    (a MACH_DEF_INDEX that is not 0) and the MACHINE_DEF lines they may refer
    to: a superset of what the interpretation reads from those tables.
    ``mframes``: (span, line); ``mdefs``: (span, first index as written or
    a false value)."""
    spans = []
    refs: set[int] = set()
    every = False                   # an index too large to tell: keep all of MACHINE_DEF
    for span, line in mframes:
        keep = False
        for n in _MACH_DEF_INDEX.findall(line):
            v = float(n)
            if abs(v) >= 1:         # int(v) != 0, as the interpretation reads it
                keep = True
                try:
                    refs.add(int(v))
                except OverflowError:
                    every = True
        if keep:
            spans.append(span)
    if spans:
        # MACHINE_DEF[k]...: k is the entry; any other shape, keep the line
        spans += [span for span, k in mdefs
                  if every or not k or len(k) > 10 or int(k) in refs]
    return spans


def _shared_values(text: str, spans: list[tuple[int, int]]):
    """Lines ``NAME...=VALUE`` whose VALUE text (all after the first "=") an
    earlier line has too: a config file repeats a few values (zero frames,
    unset loads) many times, and the parser need read each only once.

    Returns (placeholders, shared): ``placeholders`` (start, end) of the later
    values, each to be written as a 0 padded with spaces; ``shared`` maps the
    statement start of such a line to (statement start of the first line with
    that value, offset from there to here, start of the placeholder)."""
    first: dict[str, tuple[int, int]] = {}     # value text -> (statement start, value start)
    placeholders = []
    shared: dict[int, tuple[int, int, int]] = {}
    end = 0
    for s, e in spans:
        if s < end:                  # a line matched twice
            continue
        end = e
        line = text[s:e]
        i = line.find("=")
        if i <= 0 or i == len(line) - 1 or not _ASSIGN_LHS.match(line, 0, i):
            continue
        start = s + len(line) - len(line.lstrip(" \t\f\r"))
        pos = s + i + 1
        src, src_pos = first.setdefault(line[i + 1:], (start, pos))
        if src != start:
            placeholders.append((pos, e))
            shared[start] = (src, pos - src_pos, pos)
    return placeholders, shared


# An element line as KSS writes it: NAME[n]= or NAME[n,]= and a flat
# structure of numbers, a string or an #ENUM value, then at most a comment.
# Most of a $config.dat is such lines (32 bases, their names and types, 16
# tools...): read straight from their words, as the grammar reads them, they
# cost a regular-expression match instead of twenty tokens through the
# parser. Anything else (nested structures, blanks inside brackets, other
# value kinds, a line the grammar would refuse) goes through the parser.
_B = r"[ \t\f\r]*+"
_PLAIN_NUMBER = r"[+-]?+(?:[0-9]++(?:\.[0-9]*+)?+|\.[0-9]++)(?:[eE][+-]?+[0-9]++)?+"
_PLAIN_FIELD = r"[A-Za-z_$][A-Za-z0-9_$]*[ \t\f\r]+" + _PLAIN_NUMBER
_PLAIN_LINE = regex.lazy(
    _B + r"(?P<name>[A-Za-z_$][A-Za-z0-9_$]*)\[(?P<index>[0-9]{1,9}),?\]" + _B + "=" + _B
    + r"(?P<value>\{" + _B + _PLAIN_FIELD + "(?:" + _B + "," + _B + _PLAIN_FIELD + ")*" + _B
    + r"\}|\"[^\"\n]*\"|#" + _B + r"[A-Za-z_$][A-Za-z0-9_$]*)" + _B + r"(?:;[^\n]*)?\Z")
_PLAIN_FIELDS = regex.lazy(r"(?P<key>[A-Za-z_$][A-Za-z0-9_$]*)[ \t\f\r]+(?P<number>" + _PLAIN_NUMBER + ")")


def _plain_statements(doc: Document, text: str, spans, layout=None, line_of=None):
    """(statements read from their words, the spans left for the parser):
    the outline's element lines that _PLAIN_LINE matches, each made into
    the statement and value the parser would give. ``layout``: the set of
    ``_layout_lines`` where the caller has it; ``line_of``: a _Lines of
    ``text``, or doc.line_of."""
    made: list[_Stmt] = []
    rest = []
    match = _PLAIN_LINE.match
    fields_in = _PLAIN_FIELDS.finditer
    structs: dict[str, _Val] = {}  # value text -> the first line's _Val
    if line_of is None:
        line_of = doc.line_of
    for s, e in spans:
        m = match(text, s, e)
        if m is None or m.group("name").upper() in _KEYWORDS:
            rest.append((s, e))
            continue
        if layout is None:          # never a line that decides the file's layout
            layout = set(_layout_lines(text, "\n" + text))
        if (s, e) in layout:
            rest.append((s, e))
            continue
        start = m.start("name")
        st = _Stmt()
        st.kind, st.delta, st.start, st.line = "assign", 0, start, line_of(start)
        st.name = Token("NAME", m.group("name"), start, m.end("name"))
        st.index = [int(m.group("index"))]
        vs, ve = m.span("value")
        first = text[vs]
        if first == "{" and text[vs:ve] in structs:
            # a value an earlier line has too (a config file's unset frames):
            # its fields, moved here
            v0 = structs[text[vs:ve]]
            d = vs - v0.start
            st.value = _Val("struct", {key: (_Name(n.value, n.start_pos + d),
                                             _Val("number", fv.value, fv.start + d, fv.end + d,
                                                  fv.text))
                                       for key, (n, fv) in v0.value.items()}, vs, ve)
            st.value.dups = [(key, at + d) for key, at in v0.dups]
        elif first == "{":
            fields: dict[str, Any] = {}
            dups = []
            for f in fields_in(text, vs, ve):
                word, number = f.group("key", "number")
                key = word.upper()
                at = f.start()
                if key in fields:
                    dups.append((key, at))
                ns, ne = f.span("number")
                fields[key] = (_Name(word, at), _Val("number", float(number), ns, ne, number))
            st.value = _Val("struct", fields, vs, ve)
            st.value.dups = dups
            structs[text[vs:ve]] = st.value
        elif first == '"':
            st.value = _Val("string", text[vs + 1:ve - 1], vs, ve)
        else:
            st.value = _Val("enum", "#" + text[vs + 1:ve].strip().upper(), vs, ve)
        made.append(st)
    return made, rest


def _shared_parse(doc: Document, text: str, spans, layout=None, lines=None):
    """(statements, tree) of the masked text, the parser reading each repeated
    value once (_shared_values); None when that is not possible here (a
    syntax error, or a shared value not read as an assignment): the caller
    then parses the masked text as it is, with its exact error.

    A later line with a repeated value whose left-hand side is a plain
    ``NAME[n]`` or ``NAME[n,]`` (a config file's 32 unset bases) is not
    parsed at all: its statement is made here from its words, the value the
    first line's; others are parsed with the value as a placeholder 0.
    ``layout``: the set of ``_layout_lines`` where the caller has it;
    ``lines``: a _Lines of ``text``, or doc.line_of."""
    placeholders, shared = _shared_values(text, spans)
    if not shared:
        return None
    if lines is None:
        lines = doc.line_of
    if layout is None:
        layout = set(_layout_lines(text, "\n" + text))
    line_of = {s: (s, e) for s, e in spans}
    made: list[_Stmt] = []
    blank: list[tuple[int, int]] = []
    for s, e in spans:
        if (s, e) in layout:
            continue
        first = text[s:e].lstrip(" \t\f\r")
        start = e - len(first)
        if start not in shared:
            continue
        m = _PLAIN_LHS.match(text, start, e)
        if m is None or m.group("name").upper() in _KEYWORDS:
            continue
        src, delta, pos = shared[start]
        if m.end() != pos:
            continue
        st = _Stmt()
        st.kind, st.delta, st.start, st.line = "assign", delta, start, lines(start)
        st.name = Token("NAME", m.group("name"), start, m.end("name"))
        st.index = None if m.group("index") is None else [int(m.group("index"))]
        st.value = src              # the first line's statement start, resolved below
        made.append(st)
        blank.append(line_of[s])
        del shared[start]
    skip = set(blank)
    mtext = masked(text, [sp for sp in spans if sp not in skip])
    pieces = []
    pos = 0
    for s, e in placeholders:
        if s < pos or s >= len(mtext) or mtext[s:e] != text[s:e]:
            continue                # its line was blanked (made above)
        pieces.append(mtext[pos:s])
        pieces.append("0".ljust(e - s))
        pos = e
    pieces.append(mtext[pos:])
    try:
        tree = _parser().parse("".join(pieces), "file")
        stmts = _statements(tree, doc, lines)
    except (Rejected, UcsioError):
        return None
    assigns = {st.start: st for st in stmts if st.kind == "assign"}
    for start, (src, delta, pos) in shared.items():
        st = assigns.get(start)
        first = assigns.get(src)
        if st is None or first is None or not isinstance(st.value, Token) \
                or st.value.start_pos != pos or st.value.value != "0":
            return None
        st.value = first.value
        st.delta = delta
    for st in made:
        first = assigns.get(st.value)
        if first is None:
            return None
        st.value = first.value
    if made:
        stmts = sorted(stmts + made, key=lambda st: st.start)
    return stmts, tree


# a later line's left-hand side made into a statement without the parser
# (_shared_parse): NAME, NAME[n], NAME[n,] and the "=", as the grammar reads them
_PLAIN_LHS = regex.lazy(r"(?P<name>[A-Za-z_$][A-Za-z0-9_$]*)(?:\[(?P<index>[0-9]{1,9}),?\])?[ \t\f\r]*=")
# words the grammar reads as keywords, never as an assignment's name
_KEYWORDS = {"DECL", "GLOBAL", "CONST", "STRUC", "ENUM", "SIGNAL", "EXT", "EXTP", "EXTFCT",
             "EXTFCTP", "CHANNEL", "IMPORT", "DEFDAT", "ENDDAT", "PUBLIC", "TRUE", "FALSE"}


# -- parsing -------------------------------------------------------------------
def _parser():
    from ...parsing.grammar import parser
    return parser("krl", START)


def _raise_syntax(doc: Document, text: str, exc: Exception):
    from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedToken

    if isinstance(exc, UnexpectedCharacters):
        pos = exc.pos_in_stream
        bad = bad_number(text, pos)
        if bad:
            return doc.error(f"malformed number {_short(text[bad[0]:bad[1]])!r}", bad[0])
        ch = text[pos]
        if ch == '"':
            return doc.error("unterminated string: missing '\"' before the end of the line", pos)
        if ch == "'":
            return doc.error("unterminated character literal: missing \"'\"", pos)
        return doc.error(f"syntax error: unexpected character {ch!r}", pos)
    if isinstance(exc, UnexpectedEOF):
        return doc.error("unexpected end of file", len(text))
    if isinstance(exc, UnexpectedToken):
        tok = exc.token
        expected = set(exc.expected or ())
        if tok.type == "$END":
            pos = len(text)
            if "ENDDAT" in expected:
                return doc.error("missing ENDDAT: the DEFDAT data list is never closed", pos)
            return doc.error("unexpected end of file" + _expecting(expected), pos)
        pos = tok.start_pos
        bad = bad_number(text, pos)
        if bad:
            return doc.error(f"malformed number {_short(text[bad[0]:bad[1]])!r}", bad[0])
        if tok.type == "_NL":
            if "RBRACE" in expected:
                return doc.error("unterminated structure: missing '}' before the end of the line",
                                 pos)
            if "RSQB" in expected:
                return doc.error("unterminated index: missing ']' before the end of the line", pos)
            return doc.error("unexpected end of line" + _expecting(expected), pos)
        if expected == {"_NL", "$END"}:     # only after ENDDAT
            return doc.error(f"unexpected {_short(tok.value)!r} after ENDDAT: only blank and comment "
                             f"lines may follow the data list", pos)
        if tok.type == "ENDDAT" or tok.type == "DEFDAT":
            return doc.error(f"unexpected {tok.value}" + _expecting(expected), pos)
        return doc.error(f"syntax error: unexpected {_short(tok.value)!r}" + _expecting(expected), pos)
    raise exc


_READABLE = {"_NL": "end of line", "NAME": "a name", "NUMBER": "a number", "INT": "an integer",
             "STRING": "a string", "CHARLIT": "a character literal", "ENUMVAL": "#VALUE",
             "HEADER": "an & header", "$END": "end of file", "LBRACE": "'{'", "RBRACE": "'}'",
             "LSQB": "'['", "RSQB": "']'", "COMMA": "','", "EQUAL": "'='", "COLON": "':'",
             "LPAR": "'('", "RPAR": "')'"}


INT_MAX = 2 ** 31 - 1               # KRL INT is 32 bit


def _int(doc: Document, tok) -> int:
    """An INT token (an index, a dimension) as a number; beyond 32 bits the
    controller refuses it, and so does ucsio, naming where (Python would
    otherwise refuse to convert a 5,000-digit string, with a traceback)."""
    text = tok.value
    value = int(text) if len(text) <= 10 else INT_MAX + 1
    if value > INT_MAX:
        raise doc.error(f"integer {_short(text)} is out of range for a KRL INT (32 bit)",
                        tok.start_pos)
    return value


def _short(s: str, limit: int = 30) -> str:
    """Quoted input in a message: one readable line, not a megabyte."""
    return s if len(s) <= limit else s[:limit] + "..."


def _expecting(expected: set) -> str:
    words = sorted({_READABLE.get(e, e if not e.startswith("__") else "a keyword")
                    for e in expected})
    if not words or len(words) > 6:
        return ""
    return "; expected " + " or ".join(words)


def _parse(doc: Document, text: str, start: str, lark_first: bool = False):
    from ...parsing.grammar import SyntaxFailure, parse

    try:
        return parse("krl", START, text, start, lark_first)
    except SyntaxFailure as failure:
        if start == "file":
            m = _DEFDAT.search(text)
            if m is not None and re.compile(_STATEMENT_BEFORE, re.M).search(text, 0, m.start()):
                raise doc.error("DEFDAT must come first, after the & header lines",
                                m.start() + len(m.group()) - len(m.group().lstrip())) from None
        raise _raise_syntax(doc, text, failure.error) from None


# -- interpretation --------------------------------------------------------------
class _Val:
    """A value from the tree: kind ('number', 'string', 'enum', 'bool',
    'char', 'name', 'struct'), python value, span, for numbers the text as
    written, for structs the fields given twice."""

    __slots__ = ("kind", "value", "start", "end", "text", "dups")

    def __init__(self, kind, value, start, end, text=None):
        self.kind, self.value, self.start, self.end, self.text = kind, value, start, end, text
        self.dups = ()


class _Name:
    """A field name moved by a shared value's offset (see _shared_values):
    what the interpretation reads of a NAME token."""

    __slots__ = ("value", "start_pos")

    def __init__(self, value, start_pos):
        self.value, self.start_pos = value, start_pos


def _value(node, delta: int = 0, depth: int = 0) -> _Val:
    """The value ``node`` as a _Val; positions moved by ``delta`` (a value
    parsed once for several lines with the same text, see _shared_values).
    Deeper than MAX_NESTING raises TooDeep (a clear error, not Python's
    RecursionError)."""
    if isinstance(node, _Val):          # read without the parser (_plain_statements)
        return node
    if depth > MAX_NESTING:
        raise TooDeep((node.start_pos if isinstance(node, str) else node.children[0].start_pos)
                       + delta)
    if isinstance(node, str):           # a lark Token (a str); else a struct Tree
        t = node.type
        v = node.value
        start = node.start_pos + delta
        end = node.end_pos + delta
        if t == "NUMBER":
            return _Val("number", float(v), start, end, v)
        if t == "STRING":
            return _Val("string", v[1:-1], start, end)
        if t == "ENUMVAL":
            return _Val("enum", "#" + v[1:].strip().upper(), start, end)
        if t == "TRUE" or t == "FALSE":
            return _Val("bool", t == "TRUE", start, end)
        if t == "CHARLIT":
            return _Val("char", v[1:-1], start, end)
        return _Val("name", v, start, end)
    # struct: {KEY: (field name token, _Val)} in source order; duplicates kept.
    # Children: LBRACE, the fields, RBRACE (rule nodes carry no positions).
    fields: dict[str, Any] = {}
    dups = []
    children = node.children
    for i in range(1, len(children) - 1):
        ch = children[i].children
        if not isinstance(ch[0], str):     # Type: prefix
            ch = ch[1:]
        name = ch[0]
        if delta:
            name = _Name(name.value, name.start_pos + delta)
        key = name.value.upper()
        if key in fields:
            dups.append((key, name.start_pos))
        fields[key] = (name, _value(ch[-1], delta, depth + 1))
    val = _Val("struct", fields, children[0].start_pos + delta, children[-1].end_pos + delta)
    val.dups = dups
    return val


class _Lines:
    """The 1-based line of an offset in the grammar's copy of a file (_lines:
    an LF ends every line, where Document.line_starts finds one, so the two
    agree), counted on from the offset asked before: offsets asked in
    ascending order cost one pass over the text."""

    __slots__ = ("text", "pos", "line")

    def __init__(self, text: str):
        self.text, self.pos, self.line = text, 0, 1

    def __call__(self, offset: int) -> int:
        if offset < self.pos:
            self.pos, self.line = 0, 1
        self.line += self.text.count("\n", self.pos, offset)
        self.pos = offset
        return self.line


class _Stmt:
    # delta: offset from where ``value`` was parsed to this line (_shared_values)
    __slots__ = ("kind", "line", "start", "mods", "type", "vars", "name", "index", "value",
                 "delta")


_RESERVED = {"DEFDAT", "ENDDAT", "DEF", "END", "DEFFCT", "ENDFCT"}


def _statements(tree, doc: Document, line_of=None):
    """decl and assign statements of the tree, simplified, in order.
    ``line_of``: a _Lines of the text parsed, or doc.line_of."""
    if line_of is None:
        line_of = doc.line_of
    out = []
    for st in tree.children:        # file: headers, then defdat or the statements

        if not isinstance(st, Tree):
            continue
        d = st.data
        if d == "decl":
            ch = st.children
            i = 0
            mods = []
            while ch[i].type in ("DECL", "GLOBAL", "CONST"):
                mods.append(ch[i].type)
                i += 1
            s = _Stmt()
            s.kind = "decl"
            s.delta = 0
            s.line = line_of(ch[0].start_pos)
            s.start = ch[0].start_pos
            s.mods = mods
            s.type = ch[i].value.upper()
            if s.type in _RESERVED:     # the contextual lexer took it for a type name
                raise doc.error(f"unexpected {ch[i].value}: " + (
                    "DEFDAT must come first, after the & header lines" if s.type == "DEFDAT"
                    else "not allowed in a data list"), ch[i].start_pos)
            s.vars = []
            for v in ch[i + 1:]:
                vch = v.children
                name = vch[0]
                dims = None
                val = None
                for c in vch[1:]:
                    if isinstance(c, Tree) and c.data == "dims":
                        dims = [_int(doc, t) if t.type == "INT" else t.value for t in c.children]
                    else:
                        val = c
                s.vars.append((name, dims, val))
            out.append(s)
        elif d == "assign":
            ch = st.children
            s = _Stmt()
            s.kind = "assign"
            s.delta = 0
            s.line = line_of(ch[0].start_pos)
            s.start = ch[0].start_pos
            s.name = ch[0]
            s.index = None
            if len(ch) == 3:
                s.index = [_int(doc, t) for t in ch[1].children]
            s.value = ch[-1]
            out.append(s)
        elif d in ("defdat", "program"):
            out.extend(_statements(st, doc, line_of))
    return out


def _defdat(tree):
    for body in tree.children:
        if getattr(body, "data", None) == "defdat":
            ch = body.children
            return {"name": ch[1].value, "public": any(getattr(c, "type", None) == "PUBLIC"
                                                       for c in ch[2:4])}
    return None


def parse(doc: Document, full: bool = False) -> ControllerFile:
    """Parse a KRL data list into frames, lints and tables. ``full``
    (``check``): every byte through the grammar first."""
    text = _lines(doc)
    if _PROGRAM.search(text):
        # a program (.src): short, and its layout is not a data list's,
        # which the fast path's masking knows
        return _whole(doc, text)
    if full:
        try:
            _recognise(text)
        except Rejected:
            # Lark first: its positioned message (or, were the two to differ, the tree)
            return _whole(doc, text, lark_first=True)
    # the frame lines and the layout lines (outline), the rest blanked out
    nl_text = "\n" + text
    layout = _layout_lines(text, nl_text)
    spans = outline(text, nl_text, layout)
    layout_set = set(layout)
    # line numbers counted in text, not from doc.line_starts (a list of
    # every line's start, which only a lint or an error needs)
    line_of = _Lines(text)
    plain, rest = _plain_statements(doc, text, spans, layout_set, line_of)
    got = _shared_parse(doc, text, rest, layout_set, line_of)
    if got is None:
        tree = _parse(doc, masked(text, rest), "file")
        stmts = _statements(tree, doc, line_of)
    else:
        stmts, tree = got
    if plain:
        stmts = sorted(stmts + plain, key=lambda st: st.start)
    return _interpret(doc, stmts, tree)


def _lines(doc: Document) -> str:
    """The text the grammar reads: lines end at LF."""
    # A bare CR ends a line (CR-only files from some KRC tools, mixed ones
    # from conversion scripts), as Document.line_starts counts lines: the
    # grammar, whose lines end at LF, reads a copy with LF for each bare CR;
    # same length, so every offset holds.
    text = lf_lines(doc.text)
    if not text.strip():
        # a fragment may hold any statements, but none at all is a failed transfer
        raise doc.error("empty file: no KRL data (DEFDAT ... ENDDAT or declarations)", 0)
    return text


def _interpret(doc: Document, stmts, tree) -> ControllerFile:
    cf = ControllerFile(document=doc, vendor=VENDOR)
    try:
        _Interpreter(doc, cf).run(stmts)
    except TooDeep as exc:
        raise doc.error(f"value nested more than {MAX_NESTING} levels deep", exc.pos) from None
    cf.extra["defdat"] = _defdat(tree)
    return cf


def parse_whole(doc: Document) -> ControllerFile:
    """``parse(doc, full=True)`` from the tree of every byte (ucsio.parsing.lalr
    shaped as Lark shapes it): the reference the recogniser is tested
    against."""
    return _whole(doc, _lines(doc))


def _whole(doc: Document, text: str, lark_first: bool = False) -> ControllerFile:
    """The tree of every byte of ``text`` (the grammar's copy of the file),
    interpreted; ``lark_first`` where the recogniser has rejected it."""
    tree = _parse(doc, text, "file", lark_first=lark_first)
    return _interpret(doc, _statements(tree, doc), tree)


def _recognise(text: str) -> None:
    """Every byte through the grammar (ucsio.parsing.lalr.Parser.recognise), a
    structure literal read in one step; Rejected if not KRL. Tokens the
    interpretation of the whole tree would refuse (an INT beyond 32 bits, a
    reserved word as a type name) reject too: the whole tree says where."""
    global _SHORTCUTS
    parser = _parser()
    if _SHORTCUTS is None:
        from ...parsing.lalr import atomic, bracketed

        tp = parser.terminals
        gap = f"{atomic(tp['WS'])}?+"
        name = atomic(tp["NAME"])
        value = "|".join(atomic(tp[t]) for t in ("NUMBER", "STRING", "CHARLIT", "ENUMVAL", "NAME"))
        struct = None
        for _ in range(3):          # {X 1,...}, {FRAME: {X ..},...}, one more level
            item = value if struct is None else f"{struct}|{value}"
            field = f"(?:{name}{gap}:{gap})?+{name}{gap}(?:\\[{gap}\\]{gap})?+(?:{item})"
            struct = bracketed(r"\{", r"\}", field, gap)
        # value: NUMBER | struct: the parser moves on alike after either
        _SHORTCUTS = {"LBRACE": (regex.compile(struct), "NUMBER")}
    parser.recognise(text, "file", _SHORTCUTS, _SUSPECTS)


_SUSPECTS = {"INT": lambda v: len(v) > 9, "NAME": lambda v: v.upper() in _RESERVED}
_SHORTCUTS = None


class _Interpreter:
    def __init__(self, doc: Document, cf: ControllerFile):
        self.doc = doc
        self.cf = cf
        self.poses: dict[tuple, Pose] = {}     # X..C -> Pose.from_abc of them

    # -- helpers --
    def int_value(self, value: float, text: str, pos: int) -> int:
        """A number where KRL wants an INT (MAX_* sizes, MACH_DEF_INDEX): the
        controller converts a REAL in range and refuses anything beyond 32 bits."""
        if not abs(value) <= INT_MAX:
            raise self.doc.error(f"{_short(text)} is out of range for a KRL INT (32 bit)", pos)
        return int(value)

    def lint(self, offset: int, code: str, message: str, severity: str = "warning") -> None:
        self.cf.lint(offset, code, message, severity)

    def run(self, stmts) -> None:
        frame_arrays: dict[str, tuple[str, list]] = {}     # KEY -> (spelling, dims)
        frame_scalars: dict[str, str] = {}                 # KEY -> spelling
        frame_decls = []                                   # (stmt, name tok, value node)
        uninitialised = []
        maxima: dict[str, int] = {}
        for s in stmts:
            if s.kind != "decl":
                continue
            if s.type == "FRAME":
                for name, dims, val in s.vars:
                    key = name.value.upper()
                    if dims is not None:
                        frame_arrays[key] = (name.value, dims)
                    else:
                        frame_scalars[key] = name.value
                        if val is None:
                            uninitialised.append((s, name))
                        else:
                            frame_decls.append((s, name, val))
            elif s.type == "INT" and s.vars and s.vars[0][0].value.upper().startswith("MAX_"):
                for name, dims, val in s.vars:
                    key = name.value.upper()
                    if key.startswith("MAX_") and dims is None and val is not None \
                            and getattr(val, "type", None) == "NUMBER":
                        maxima[key] = self.int_value(float(val.value), val.value,
                                                     val.start_pos)

        # element lines, by table
        labels: dict[tuple[str, int], tuple[str, int]] = {}   # (TOOL|BASE, n) -> (label, offset)
        types: dict[tuple[str, int], tuple[str, int]] = {}
        loads: dict[int, dict] = {}
        mframes: dict[int, dict] = {}
        machines: dict[int, dict] = {}
        elements = []          # (stmt, key) for FRAME elements / FRAME scalar assignments
        load_of: dict[int, Any] = {}    # id(value node) -> _load of it (None: not a struct)
        for s in stmts:
            if s.kind != "assign":
                continue
            key = s.name.value.upper()
            idx = s.index
            one = idx[0] if idx and len(idx) >= 1 else None
            if key in ("TOOL_DATA", "BASE_DATA") or key in frame_arrays \
                    or (key in frame_scalars and not idx):
                elements.append((s, key))
            elif key in ("TOOL_NAME", "BASE_NAME") and one is not None:
                v = _value(s.value, s.delta)
                if v.kind != "string":
                    self.lint(v.start, "bad-label", f"{s.name.value}[{one},] is not a string")
                    continue
                labels[(key[:4], one)] = (self.cf.document.readable(v.value), v.start)
            elif key in ("TOOL_TYPE", "BASE_TYPE") and one is not None:
                v = _value(s.value, s.delta)
                if v.kind != "enum":
                    self.lint(v.start, "bad-type", f"{s.name.value}[{one}] is not an #ENUM value")
                    continue
                types[(key[:4], one)] = (v.value, v.start)
            elif key == "LOAD_DATA" and one is not None:
                # a value shared by several lines (_shared_parse: the unset
                # loads) is one node: _load reads no position, so read it once
                got = load_of.get(id(s.value), load_of)
                if got is load_of:
                    v = _value(s.value, s.delta)
                    got = load_of[id(s.value)] = _load(v) if v.kind == "struct" else None
                if got is not None:
                    loads[one] = {k: dict(x) if isinstance(x, dict) else x
                                  for k, x in got.items()}
            elif key == "MACHINE_FRAME_DAT" and one is not None:
                v = _value(s.value, s.delta)
                if v.kind == "struct":
                    f = v.value
                    idxv = f.get("MACH_DEF_INDEX")
                    index = self.int_value(idxv[1].value, idxv[1].text, idxv[1].start) \
                        if idxv and idxv[1].kind == "number" else 0
                    if not index:     # not tied to a kinematic: the fast path skips the line
                        continue
                    par = f.get("PARENT")
                    mframes[one] = {
                        "index": index,
                        "parent": par[1].value.rstrip() if par and par[1].kind == "string"
                        else None}
            elif key == "MACHINE_DEF" and one is not None:
                v = _value(s.value, s.delta)
                if v.kind == "struct":
                    f = v.value
                    mach = {k.lower(): (f[k][1].value.rstrip() if f[k][1].kind == "string"
                                        else f[k][1].value)
                            for k in ("NAME", "PARENT", "MECH_TYPE") if k in f}
                    root = f.get("ROOT")
                    if root and root[1].kind == "struct":
                        r = root[1].value
                        mach["root"] = {c: r[c.upper()][1].value for c in COMPONENTS
                                        if c.upper() in r and r[c.upper()][1].kind == "number"}
                    machines[one] = mach

        # frames in document order; a FRAME declared without a value and never
        # assigned is listed too (as ABB's PERS without a value is), without numbers
        assigned = {key for s, key in elements if key in frame_scalars and not s.index}
        items = [(s.start, s, name, val) for s, name, val in frame_decls]
        items += [(s.start, s, None, None) for s, _ in elements]
        items += [(s.start, s, name, None) for s, name in uninitialised
                  if name.value.upper() not in assigned]
        items.sort(key=lambda it: it[0])
        frames = self.cf.frames
        seen: dict[str, Frame] = {}
        for _, s, name_tok, val in items:
            if name_tok is not None and val is None:          # DECL FRAME x
                fr = Frame(name=name_tok.value, vendor=VENDOR, type="FRAME", pose=None,
                           file=self.doc.path, line=s.line, document=self.doc)
                fr.reference = "unknown"
                fr.info.update(_mods_info(s.mods))
                fr.info["value"] = None
                self.lint(name_tok.start_pos, "no-value",
                          f"{fr.name}: declared without a value (legal: the program assigns "
                          "it); listed, not patchable", severity="info")
            elif name_tok is not None:                        # FRAME x={...}
                fr = self.frame(name_tok.value, "FRAME", s, val)
                fr.reference = "unknown"
                fr.info.update(_mods_info(s.mods))
            else:
                key = s.name.value.upper()
                idx = s.index or []
                sub = "[" + ",".join(str(i) for i in idx) + "]" if idx else ""
                if key in ("TOOL_DATA", "BASE_DATA") and len(idx) == 1:
                    fr = self.frame(key + sub, key, s, s.value)
                    self.table_entry(fr, key, idx[0], labels, types, loads, mframes, machines)
                else:
                    spelling = frame_arrays[key][0] if key in frame_arrays else \
                        frame_scalars.get(key, s.name.value)
                    if key in ("TOOL_DATA", "BASE_DATA") and key not in frame_arrays:
                        spelling = key
                    fr = self.frame(spelling + sub, "FRAME", s, s.value)
                    fr.reference = "unknown"
                dims = frame_arrays.get(key, (None, None))[1]
                if dims and idx and len(idx) == len(dims) and \
                        any(isinstance(d, int) and (i < 1 or i > d) for i, d in zip(idx, dims)):
                    self.lint(s.start, "index-out-of-range",
                              f"{fr.name} is outside the declared size "
                              f"[{','.join(str(d) for d in dims)}]")
            k = fr.name.upper()
            if k in seen:
                self.lint(s.start, "duplicate-frame",
                          f"{fr.name} is initialised twice (lines {seen[k].line} and {fr.line})")
            else:
                seen[k] = fr
            frames.append(fr)

        self.duplicate_names()
        extra = self.cf.extra
        extra["tables"] = dict(sorted(maxima.items()))
        extra["arrays"] = {sp: dims for sp, dims in frame_arrays.values()}
        extra["uninitialised"] = [name.value for _, name in uninitialised]
        extra["loads"] = loads

    def frame(self, name: str, ftype: str, s, val_node) -> Frame:
        doc = self.doc
        fr = Frame(name=name, vendor=VENDOR, type=ftype, pose=None, file=doc.path,
                   line=s.line, document=doc)
        v = _value(val_node, s.delta)
        if v.kind != "struct":
            self.lint(v.start, "not-a-frame", f"{name}: a FRAME value is written {{X ..,Y ..,"
                                              f"Z ..,A ..,B ..,C ..}}")
            return fr
        for key, pos in v.dups:
            self.lint(pos, "duplicate-component", f"{name}: component {key} given twice")
        nums = {}
        for key, (tok, fv) in v.value.items():
            comp = key.lower()
            if comp not in COMPONENTS:
                self.lint(tok.start_pos, "unknown-component",
                          f"{name}: a FRAME has no component {tok.value}")
                continue
            if fv.kind != "number":
                self.lint(fv.start, "not-a-number", f"{name}: component {tok.value} is not a number")
                continue
            if not (abs(fv.value) <= REAL_MAX):
                raise doc.error(f"number {_short(fv.text)} is out of range for a KRL REAL "
                                "(float32)",
                                fv.start)
            nums[comp] = Number(Span(fv.start, fv.end), fv.text, fv.value)
        fr.numbers = {c: nums[c] for c in COMPONENTS if c in nums}
        missing = [c.upper() for c in COMPONENTS if c not in nums]
        if missing:
            plural = "s" if len(missing) > 1 else ""
            if name.upper().startswith(("TOOL_DATA[", "BASE_DATA[")):
                self.lint(v.start, "missing-component",
                          f"{name}: component{plural} {', '.join(missing)} missing: the frame "
                          "has no complete value")
            else:
                # legal in a declaration (they stay undefined): KSS's own
                # $custom.dat has FRAME $SINGUL_ERR_PRO={A 0.0,B 0.0,C 0.0}
                self.lint(v.start, "missing-component",
                          f"{name}: component{plural} {', '.join(missing)} not given (undefined "
                          "until set); listed without numbers, not patchable", severity="info")
        else:
            # one Pose for each distinct value (a config file's many unset
            # frames): a Pose is never changed once made. -0.0 and 0.0 are
            # one key, and from_abc makes the same Pose of both (its + 0.0)
            key = tuple([nums[c].value for c in COMPONENTS])
            pose = self.poses.get(key)
            if pose is None:
                pose = self.poses[key] = Pose.from_abc(*key)
            fr.pose = pose
        return fr

    def table_entry(self, fr: Frame, key: str, n: int, labels, types, loads, mframes,
                    machines) -> None:
        kind = key[:4]                       # TOOL | BASE
        lab = labels.get((kind, n))
        if lab is not None:
            label, pos = lab
            if len(label) > LABEL_MAX:
                self.lint(pos, "label-too-long",
                          f"{kind}_NAME[{n},] is {len(label)} characters; the controller "
                          f"keeps {LABEL_MAX}")
            if '"' in label:
                self.lint(pos, "label-quote", f'{kind}_NAME[{n},] contains \'"\'')
            # both sides: the controller pads with spaces, and names given
            # on the command line are matched stripped
            label = label.strip()
            fr.label = label or None
            fr.info["label_offset"] = pos
        t = types.get((kind, n))
        tv = t[0] if t else None
        roles = TOOL_ROLES if kind == "TOOL" else BASE_ROLES
        if tv is not None and tv not in roles:
            self.lint(t[1], "unknown-type", f"{kind}_TYPE[{n}]={tv}: expected "
                                            f"{', '.join(sorted(roles))}")
        fr.info[kind.lower() + "_type"] = tv
        fr.info["role"] = roles.get(tv, "unknown") if tv is not None else roles["#NONE"]
        known = tv is None or tv in roles   # an unknown type value: reference unknown too
        if kind == "TOOL":
            fr.reference = "flange" if known else "unknown"
            if n in loads:
                fr.info["load"] = dict(loads[n])
            return
        fr.reference = "world" if known else "unknown"
        mach = mframes.get(n)
        if mach and mach["index"] and fr.reference == "world":
            fr.reference = "machine"
            fr.parent = unit(f"MACHINE_DEF[{mach['index']}]")   # the kinematic that moves it
            fr.info["machine"] = dict(mach)
            if mach["index"] in machines:
                fr.info["machine"]["definition"] = machines[mach["index"]]
        if fr.reference == "machine":
            where = _kinematic(n, mach, machines.get(mach["index"]))
        elif fr.reference != "world":
            where = "an unknown frame"
        if fr.reference != "world":
            self.lint(self._line_offset(fr), "base-not-world",
                      f"{fr.name} is relative to {where}, not to world")

    def _line_offset(self, fr: Frame) -> int:
        return self.doc.line_starts[fr.line - 1]

    def duplicate_names(self) -> None:
        by_name: dict[str, list[Frame]] = {}
        for fr in self.cf.frames:
            for n in {fr.name.casefold(), *([fr.label.casefold()] if fr.label else [])}:
                by_name.setdefault(n, []).append(fr)
        for key, frs in by_name.items():
            labelled = [f for f in frs if f.label and f.label.casefold() == key]
            if len(frs) < 2 or not labelled:
                continue
            later = frs[-1]
            pos = later.info.get("label_offset", self._line_offset(later))
            which = " and ".join(f.name for f in frs)
            shown = labelled[0].label
            self.lint(pos, "duplicate-label",
                      f"label {shown!r} names {which}: refer to them by entry name")
        for fr in self.cf.frames:
            fr.info.pop("label_offset", None)


def _kinematic(n: int, mach: dict, definition) -> str:
    """'external kinematic 2 "DKP-400" (MACHINE_FRAME_DAT[3]: MACH_DEF_INDEX 2,
    parent DKP-400)': the kinematic is MACHINE_DEF[index], named by its NAME
    when the file has it; PARENT is the frame the base hangs from."""
    k = mach["index"]
    name = (definition or {}).get("name")
    named = f' "{name}"' if isinstance(name, str) and name.strip() else ""
    parent = mach.get("parent")
    par = f", parent {parent.strip()}" if parent and parent.strip() else ""
    return (f"external kinematic {k}{named} (MACHINE_FRAME_DAT[{n}]: MACH_DEF_INDEX {k}"
            f"{par})")


def _mods_info(mods) -> dict:
    info = {}
    if "GLOBAL" in mods:
        info["global"] = True
    if "CONST" in mods:
        info["const"] = True
    return info


def _load(v: _Val) -> dict:
    """LOAD {M m,CM {X..C},J {X,Y,Z}} as a plain dict; M -1 means 'not set'."""
    f = v.value
    out: dict[str, Any] = {}
    m = f.get("M")
    mass = m[1].value if m and m[1].kind == "number" else None
    out["m"] = None if mass is None or mass < 0 else mass
    out["load_set"] = mass is not None and mass >= 0
    for key, comps in (("CM", COMPONENTS), ("J", ("x", "y", "z"))):
        sub = f.get(key)
        if sub and sub[1].kind == "struct":
            sv = sub[1].value
            out[key.lower()] = {c: (sv[c.upper()][1].value if c.upper() in sv
                                    and sv[c.upper()][1].kind == "number" else None)
                                for c in comps}
    return out


# -- taught positions (a measurement program's .dat) ------------------------------
POSITION_TYPES = ("E6POS", "POS", "FRAME")


class Position(Value):
    """A position declared in a data list (``DECL E6POS XP1={...}``) with the
    motion data of its inline form (``DECL FDAT FP1={TOOL_NO 1,BASE_NO 2,
    IPO_FRAME #BASE}``): the pose of ``$TOOL`` in ``$BASE``. ``fdat`` is None
    where the file declares no FDAT for it; ``tool_no``/``base_no`` are
    None where the FDAT leaves them out."""

    __slots__ = ("name", "type", "pose", "line", "col", "fdat", "tool_no", "base_no",
                 "ipo_frame", "problem")

    def __init__(self, name, type, pose, line, col, fdat=None, tool_no=None, base_no=None,
                 ipo_frame=None):
        self.name, self.type, self.pose, self.line, self.col = name, type, pose, line, col
        self.fdat, self.tool_no, self.base_no, self.ipo_frame = fdat, tool_no, base_no, ipo_frame
        self.problem = None      # UcsioError: why ``pose`` is None (raised where it is used)

    @property
    def point(self) -> str:
        """The point's name as the inline form shows it: XP1 -> P1."""
        return self.name[1:] if self.name[:1] in "Xx" and len(self.name) > 1 else self.name


# the declaration lines positions() needs on the fast path
_POSITION_LINE = regex.lazy(r"\n(" + _MODS + r"(?:E6POS|POS|FRAME|FDAT)" + _WS + r"[^\n]*)", re.I)


def positions(doc: Document, full: bool = True) -> list[Position]:
    """Every E6POS, POS and FRAME declared with a value, in file order, each
    with its FDAT (``X<name>`` pairs with ``F<name>``, the inline forms'
    naming). By default the whole file goes through the grammar (``check``'s
    path): a measurement program is short, and a syntax error anywhere must
    not go unseen. ``full=False`` is the fast path's way (``diff --points``
    reading every .dat of a controller's tree): only the position and FDAT
    lines and the layout lines, the rest blanked. A position whose X, Y, Z,
    A, B or C is missing or not a number has no pose and a ``problem``
    (file:line:col) for whoever needs it."""
    with paused_gc():
        return _positions(doc, full)


def _positions(doc: Document, full: bool) -> list[Position]:
    text = lf_lines(doc.text)
    if full:
        tree = _parse(doc, text, "file")
    else:
        nl_text = "\n" + text
        spans = [(m.start(1) - 1, m.end(1) - 1) for m in _POSITION_LINE.finditer(nl_text)]
        if not spans:
            return []
        spans += _layout_lines(text, nl_text)
        tree = _parse(doc, masked(text, sorted(set(spans))), "file")
    found: list[tuple[str, str, Any, int]] = []
    fdats: dict[str, tuple[dict, int]] = {}
    for s in _statements(tree, doc):
        if s.kind != "decl" or s.type not in POSITION_TYPES + ("FDAT",):
            continue
        for name, dims, val in s.vars:
            if dims is not None or val is None:
                continue
            v = _value(val)
            if s.type == "FDAT":
                if v.kind == "struct":
                    fdats[name.value.upper()] = (v.value, v.start)
                continue
            found.append((name.value, s.type, v, name.start_pos))
    out = []
    for name, ptype, v, pos in found:
        line, col = doc.line_col(pos)
        pose, problem = _position_pose(name, ptype, v)
        p = Position(name, ptype, pose, line, col)
        if problem is not None:
            p.problem = doc.error(*problem)
        key = name.upper()
        fd = fdats.get("F" + key[1:]) if key.startswith("X") else None
        if fd is not None:
            fields, _ = fd
            p.fdat = "F" + name[1:]

            def field(k, kind):
                got = fields.get(k)
                return got[1].value if got is not None and got[1].kind == kind else None

            tool, base = field("TOOL_NO", "number"), field("BASE_NO", "number")
            p.tool_no, p.base_no = _int_or_none(tool), _int_or_none(base)
            if (tool is None) != (p.tool_no is None) or (base is None) != (p.base_no is None):
                p.pose, p.problem = None, doc.error(f"{p.fdat}: TOOL_NO or BASE_NO is out of "
                                                    "range for a KRL INT (32 bit)", fd[1])
            p.ipo_frame = field("IPO_FRAME", "enum")
        out.append(p)
    return out


def _int_or_none(value: float | None) -> int | None:
    """A number where KRL wants an INT, or None (none given, or beyond 32 bits)."""
    return None if value is None or not abs(value) <= INT_MAX else int(value)


def _position_pose(name: str, ptype: str, v: _Val):
    """(Pose, None), or (None, (message, offset)) where the value is not a
    complete X, Y, Z, A, B, C."""
    if v.kind != "struct":
        return None, (f"{name}: a {ptype} value is written {{X ..,Y ..,Z ..,A ..,B ..,C ..}}",
                      v.start)
    comps = {}
    for c in COMPONENTS:
        got = v.value.get(c.upper())
        if got is None:
            return None, (f"{name}: component {c.upper()} missing", v.start)
        if got[1].kind != "number":
            return None, (f"{name}: component {c.upper()} is not a number", got[1].start)
        if not abs(got[1].value) <= REAL_MAX:
            return None, (f"{name}: component {c.upper()} is out of range for a KRL REAL "
                          "(float32)", got[1].start)
        comps[c] = got[1].value
    return Pose.from_abc(*(comps[c] for c in COMPONENTS)), None
