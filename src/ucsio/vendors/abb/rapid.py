"""ABB RAPID: text -> frames, through grammars/rapid.lark.

Two ways through the same grammar:

- ``full=True`` (``ucsio check``): every byte of the file goes through the
  grammar's LALR table and lexer (ucsio.parsing.lalr's recogniser: Lark's tables,
  no tree), then the fast path below reads the frames, and every other
  declaration is listed from its words (its value parsed only if read).
  Where the recogniser rejects, ``parse_whole`` (the tree of every byte)
  gives the positioned error.
- the fast path (``ucsio frames``, ``diff``, ``patch``): an outline scanner
  (one regular expression, the same lexical rules as the grammar) walks the
  module's top-level items: comments, routines, records, declarations. Only
  the declarations of frame types are kept; every other character is replaced
  by a space, and the grammar parses that in one call; positions are mapped back
  of the original file, so every span points into the real document. A module
  with 20,000 robtargets thus costs one regex pass, not 20,000 parses.

Both paths give the same frames (tests/test_rapid.py checks it on the corpus),
and ``full=True`` shows what ``parse_whole`` shows (tests/test_lalr.py).
"""
from __future__ import annotations

import bisect
import os
import re

from ...errors import MAX_NESTING, TooDeep, UcsioError
from ...geometry.frames import Frame, Number, Parent, Pose, flange, frame_parent, unit
from ...values import Value
from ...parsing.document import Document, Span
from ...parsing import regex
from ...parsing.grammar import grammar_dir
from ...parsing.lalr import Rejected, Token, Tree
from ...parsing.model import ControllerFile

FRAME_TYPES = {"wobjdata", "tooldata", "pose"}
IDENT_MAX = 32          # RobotWare 5-7 identifier limit (the lexer does not enforce it)
# |sum q^2 - 1|: RobotWare's own backups hold up to 1.9e-5 (FORMATS 1.6), so a
# warning there would fail the controller's own files. Above NORM_WARN (the
# "1.0 +- 0.0001" reading) it is a warning; from NORM_INFO up, an info.
NORM_INFO = 1e-5
NORM_WARN = 1e-4
NUM_MAX = 3.4028235e38  # RAPID num is IEEE single precision

# -- the outline scanner -------------------------------------------------------
# Strings and comments are matched before anything can end inside them.
_STR = r'"[^"\r\n]*+"'


def _grammar_terminal(name: str) -> str:
    """A terminal's regex as grammars/rapid.lark writes it: the outline skips
    routines and records with the grammar's own patterns, so the two paths
    cannot drift apart."""
    with open(os.path.join(grammar_dir(), "rapid.lark"), encoding="utf-8") as fh:
        for line in fh:         # "ROUTINE.2: /.../i" (no regex: none compiled at start-up)
            head, sep, rest = line.rstrip("\r\n").partition(": /")
            if sep and head.split(".")[0] == name and rest.endswith("/i"):
                return rest[:-2]
    raise LookupError(f"rapid.lark has no terminal {name}")


# between keywords: whitespace and comments ("PERS ! shared\n  wobjdata w ...")
_GAP = r"(?:\s|![^\r\n]*+)++"
_DECL_HEAD = r"(?:(?:LOCAL|TASK)" + _GAP + r")?(?:PERS|CONST|VAR)" + _GAP
_PLACEHOLDER = r"<(?:TDN|DDN|RDN|PAR|ALT|DIM|SMT|VAR|EIT|CSE|EXP|ARG|ID)>"
_DECL_REST = r"(?:[^;\"!]++|" + _STR + r"|![^\r\n]*+)*+;"
# Whitespace and comments are folded into the item after them: one match per
# item keeps the Python loop short on modules with tens of thousands of targets.
_OUTLINE = regex.lazy(
    r"(?:\s++|![^\r\n]*+)*+(?:"
    r"(?P<frame_decl>" + _DECL_HEAD + r"(?:wobjdata|tooldata|pose)\b" + _DECL_REST + ")"
    # a run of other declarations (a path module's 20,000 robtargets) is one match
    r"|(?P<decls>" + _DECL_HEAD + r"(?:\w++|" + _PLACEHOLDER + ")" + _DECL_REST
    + r"(?:(?:\s++|![^\r\n]*+)*+" + _DECL_HEAD + r"(?!(?:wobjdata|tooldata|pose)\b)\w++"
    + _DECL_REST + r")*+)"
    r"|(?P<header>%%%[\s\S]*?%%%)"
    r"|(?P<module>MODULE\b(?:\s|![^\r\n]*+)*+\w*(?:[ \t]|![^\r\n]*+)*+(?:\([^)\r\n]*\))?)"
    r"|(?P<endmodule>ENDMODULE\b)"
    r"|(?P<routine>" + _grammar_terminal("ROUTINE") + ")"
    r"|(?P<record>" + _grammar_terminal("RECORD_DEF") + ")"
    r"|(?P<alias>ALIAS\b[^;]*;)"
    r"|(?P<placeholder>" + _PLACEHOLDER + ")"
    r"|(?P<eof>\Z))",
    re.IGNORECASE,
)
_TRIVIA = regex.lazy(r"(?:\s++|![^\r\n]*+)*+")
_BAD_NUMBER = regex.lazy(
    r"\d(?:[A-DF-Za-df-z_]|[eE](?![+-]?\d)|[eE][+-]?\d++[.A-Za-z_]"
    r"|\.\d*+(?:[.A-DF-Za-df-z_]|[eE](?![+-]?\d)|[eE][+-]?\d++[.A-Za-z_]))")
_NUMBER_RUN = regex.lazy(r"(?:[eE][+-]|[\w.])*+")
_RADIX = regex.lazy(r"0(?:[xX][0-9A-Fa-f]+|[oO][0-7]+|[bB][01]+|[dD][0-9]+)(?![\w.])")


class Region(Value):
    __slots__ = ("kind", "span")

    def __init__(self, kind: str, span: Span):
        self.kind, self.span = kind, span


def outline(doc: Document, routines: bool = False) -> list[Region]:
    """Module brackets, header and frame declarations, in order; with
    ``routines`` also every routine and every run of other declarations
    (what ``diff --points`` reads: move instructions and robtargets).

    Walks every top-level item (contiguity is checked, so nothing is skipped
    unseen) and raises a positioned error for anything that is not RAPID at
    this level: text outside MODULE ... ENDMODULE, an unterminated
    declaration or routine, unbalanced brackets, a bad number, a missing
    ENDMODULE.
    """
    text = doc.text
    regions: list[Region] = []
    append = regions.append
    pos = 0
    in_module = False
    seen_module = False
    match = _OUTLINE.match       # match, not finditer: a search past a failed item would
    while True:                  # retry every later position, each up to the end (quadratic)
        m = match(text, pos)
        if m is None:
            break
        pos = m.end()
        kind = m.lastgroup
        if kind == "decls" or kind == "frame_decl":
            start = m.start(kind)
            if not in_module:
                raise doc.error("declaration outside MODULE ... ENDMODULE", start)
            if not _balanced(m.group(kind)):
                raise doc.error("unbalanced [ ] in declaration", _unbalanced_decl(text, start, pos))
            if kind == "frame_decl" or routines:
                append(Region(kind, Span(start, pos)))
            continue
        if kind == "eof":
            break
        start = m.start(kind)
        if kind == "placeholder":   # <DDN> where a declaration will go: legal, nothing to list
            if not in_module:
                raise doc.error("placeholder outside MODULE ... ENDMODULE", start)
            continue
        if kind == "module":
            if in_module:
                raise doc.error("MODULE inside a module (ENDMODULE missing above)", start)
            in_module = seen_module = True
            append(Region("module", Span(start, pos)))
        elif kind == "endmodule":
            if not in_module:
                raise doc.error("ENDMODULE without MODULE", start)
            in_module = False
            append(Region("endmodule", Span(start, pos)))
        elif kind == "header":
            if seen_module or regions:
                raise doc.error("%%% header after the start of the file", start)
            append(Region("header", Span(start, pos)))
        elif not in_module:
            raise doc.error(f"{kind} outside MODULE ... ENDMODULE", start)
        elif routines and kind == "routine":
            append(Region("routine", Span(start, pos)))
    if pos != len(text):
        item = _TRIVIA.match(text, pos).end()  # point at the item, not the blank before it
        raise doc.error(_explain(text, item), item)
    if in_module:
        raise doc.error("module is not closed: ENDMODULE missing at end of file", len(text))
    if not seen_module:
        raise doc.error("no MODULE in file", 0)
    return regions


def _balanced(chunk: str) -> bool:
    """As many [ as ] outside strings and comments (a run of declarations
    holds the comment lines between them: "! PERS wobjdata x := [")."""
    if '"' in chunk or "!" in chunk:
        chunk = _STRINGS_AND_COMMENTS.sub("", chunk)
    return chunk.count("[") == chunk.count("]")


_ONE_DECL = regex.lazy(r"(?:\s++|![^\r\n]*+)*+(?P<decl>" + _DECL_HEAD + r"\w++" + _DECL_REST + ")", re.IGNORECASE)


def _unbalanced_decl(text: str, start: int, end: int) -> int:
    """Offset of the first unbalanced declaration in a run of them."""
    pos = start
    while pos < end:
        m = _ONE_DECL.match(text, pos, end)
        if m is None:
            break
        if not _balanced(m.group("decl")):
            return m.start("decl")
        pos = m.end()
    return start



def _check_numbers(doc: Document) -> None:
    """A number run straight into a letter or a second dot ("1.2.3", "3e",
    "12ab") is bad wherever it stands in live code. The regex only finds
    candidates; digits inside names (p10, tool0.tframe) are skipped here.
    This costs a pass over every digit, so only ``check`` runs it on the whole
    file; the fast path's parse checks the numbers of frame data.

    Linear on any text: strings and comments are blanked in one pass (not
    looked up per candidate), and a run of digits and dots is judged once,
    however many candidates it holds."""
    text = doc.text
    live = _STRINGS_AND_COMMENTS.sub(_blank, text) if ('"' in text or "!" in text) else text
    judged = 0                  # candidates before this lie in a run already judged
    for m in _BAD_NUMBER.finditer(live):
        if m.start() < judged:
            continue
        i = m.start()
        while i > 0 and (live[i - 1].isdigit() or live[i - 1] == "."):
            i -= 1
        judged = _DIGITS_DOTS.match(live, i).end()
        if i > 0 and (live[i - 1].isalnum() or live[i - 1] == "_"):
            continue  # digits inside a name
        if live[i] == "." and i > 0 and live[i - 1] in ")}]":
            continue
        if _RADIX.match(live, i):
            continue
        raise doc.error(f"bad number {_NUMBER_RUN.match(text, i, i + 40).group()!r}", i)


# Strings and comments never span lines in RAPID; "" inside a string reads as
# two strings back to back, which blanks the same characters. A string not
# closed on its line runs to the line's end.
_STRINGS_AND_COMMENTS = regex.lazy(r'"[^"\r\n]*+"?|![^\r\n]*+')
_DIGITS_DOTS = regex.lazy(r"[\d.]*")


def _blank(m: re.Match) -> str:
    return " " * (m.end() - m.start())


def _explain(text: str, pos: int) -> str:
    rest = text[pos:pos + 40]
    word = re.match(r"\w+", rest)
    head = rest.split("\n", 1)[0].strip()
    if word and word.group().upper() in ("PERS", "CONST", "VAR", "LOCAL", "TASK"):
        return "declaration not terminated by ';'"
    if word and word.group().upper() in ("PROC", "FUNC", "TRAP", "RECORD"):
        return f"{word.group()} without its END{word.group().upper()}"
    if rest.startswith('"'):
        return "string not closed on its line"
    return f"unexpected text {head[:30]!r}"


class Compact:
    """Only the regions the parser must see, joined by line breaks (a region may
    end in a comment: "MODULE m ! note" must not comment out what follows),
    and the map from a position in that text back to the file. The parser then
    reads a few kilobytes instead of a module of robtargets; positions are
    mapped back once, so every span in the tree points into the real
    document."""

    def __init__(self, doc: Document, regions: list[Region]):
        text = doc.text
        parts: list[str] = []
        self.starts: list[int] = []     # where each region starts in the compact text
        self.origins: list[int] = []    # ... and in the file
        n = 0
        for r in regions:
            self.starts.append(n)
            self.origins.append(r.span.start)
            parts.append(text[r.span.start:r.span.end])
            parts.append("\n")
            n += r.span.end - r.span.start + 1
        self.text = "".join(parts)

    def __call__(self, pos: int) -> int:
        i = bisect.bisect_right(self.starts, pos) - 1
        return self.origins[i] + pos - self.starts[i] if i >= 0 else pos

    def remap(self, tree) -> None:
        for sub in tree.iter_subtrees():
            for tok in sub.children:
                if isinstance(tok, Token) and tok.start_pos is not None:
                    tok.start_pos = self(tok.start_pos)
                    tok.end_pos = self(tok.end_pos)


# -- the grammar --------------------------------------------------------------------
START = ("file", "data_decl")


def _parser():
    from ...parsing import grammar
    return grammar.parser("rapid", START)


def parse_tree(doc: Document, source: str, locate=lambda pos: pos, lark_first: bool = False):
    from ...parsing.grammar import SyntaxFailure, parse

    try:
        return parse("rapid", START, source, "file", lark_first)
    except SyntaxFailure as failure:
        exc = failure.error
    from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedToken

    if isinstance(exc, UnexpectedEOF):
        raise doc.error("unexpected end of file", len(doc.text)) from None
    if isinstance(exc, UnexpectedToken):
        tok = exc.token
        pos = locate(tok.start_pos) if tok.start_pos is not None else len(doc.text)
        if tok.type == "$END":
            raise doc.error("unexpected end of file", len(doc.text)) from None
        want = sorted(exc.accepts or exc.expected)
        hint = f"; expected {_nice(want)}" if want else ""
        raise doc.error(f"unexpected {str(tok)[:30]!r}{hint}", pos) from None
    if isinstance(exc, UnexpectedCharacters):
        raise doc.error(f"unexpected character {source[exc.pos_in_stream]!r}",
                        locate(exc.pos_in_stream)) from None
    # pragma: no cover - other Lark errors
    raise doc.error(str(exc).splitlines()[0], locate(getattr(exc, "pos_in_stream", 0))) from None


_PUNCT = {"SEMICOLON": "';'", "COMMA": "','", "RSQB": "']'", "LSQB": "'['", "RBRACE": "'}'",
          "RPAR": "')'", "__ANON_0": "':='", "NUMBER": "a number", "NAME": "a name"}


def _nice(names: list[str]) -> str:
    shown = [_PUNCT.get(n, n.lower()) for n in names[:6]]
    return " or ".join(shown) + (" ..." if len(names) > 6 else "")


# -- declarations -> frames ---------------------------------------------------------
class Decl(Value):
    """A module-level data declaration; ``value`` is the converted value tree
    (Number, bool, str, list, or _Expr for anything computed) and ``dims``
    the array dimensions. Both are converted when first read: frames need
    only the frame declarations' values, so a path module's robtargets (or a
    record nested 10,000 deep, which the grammar accepts) cost nothing here,
    and ``check`` and the fast path agree on what they accept."""

    __slots__ = ("scope", "storage", "type", "name", "start", "end", "module", "_nodes",
                 "_converted", "_doc")
    _compare = ("scope", "storage", "type", "name", "start", "end", "module")

    def __init__(self, scope, storage, type, name, nodes, start, end, module, doc):
        self.scope, self.storage, self.type, self.name = scope, storage, type, name
        self.start, self.end, self.module = start, end, module
        self._nodes, self._converted, self._doc = nodes, None, doc

    def _convert(self) -> tuple:
        if self._converted is None:
            dims_node, value_node = self._nodes
            try:
                dims = None if dims_node is None else [_value(d) for d in dims_node.children]
                value = None if value_node is None else _value(value_node)
            except TooDeep as exc:
                raise self._doc.error(f"{self.name}: value nested more than {MAX_NESTING} levels "
                                      "deep", exc.pos) from None
            self._converted = (dims, value)
        return self._converted

    @property
    def dims(self):
        return self._convert()[0]

    @property
    def value(self):
        return self._convert()[1]


class _LazyDecl(Decl):
    """A declaration known from its words; its dims and value are parsed
    (the grammar, start ``data_decl``, over its own text) only when read, as
    reading a measurement program's robtargets does."""

    __slots__ = ()

    def _convert(self) -> tuple:
        if self._converted is None:
            from ...parsing.grammar import SyntaxFailure, parse

            doc = self._doc
            own = Compact(doc, [Region("decl", Span(self.start, self.end))])
            try:
                tree = parse("rapid", START, own.text, "data_decl")
            except SyntaxFailure:   # pragma: no cover - the recogniser accepted the file
                raise doc.error(f"{self.name}: declaration not understood", self.start) from None
            own.remap(tree)
            self._nodes = _decl_parts(tree)[4:]
        return Decl._convert(self)


class _Expr:
    """A value that is not a literal (a name, a call, arithmetic)."""

    def __init__(self, start: int, end: int):
        self.start, self.end = start, end


class _Placeholder(_Expr):
    """An editor placeholder (<EXP>, ...) where a value should be."""


def _placeholder_in(v) -> _Placeholder | None:
    if isinstance(v, _Placeholder):
        return v
    if isinstance(v, list):
        for x in v:
            found = _placeholder_in(x)
            if found is not None:
                return found
    return None


def _value(node, depth: int = 0):
    """Subtree -> Number | bool | str | list | _Expr. Deeper than
    MAX_NESTING raises TooDeep (a clear error, not Python's RecursionError)."""
    if depth > MAX_NESTING:
        raise TooDeep(_extent(node)[0])
    if isinstance(node, Token):
        return _Expr(node.start_pos, node.end_pos)
    kind = node.data
    if kind == "number":
        tok = node.children[0]
        return Number(Span(tok.start_pos, tok.end_pos), str(tok), _num(str(tok)))
    if kind == "neg" or kind == "pos":
        sign_token, operand = node.children
        inner = _value(operand, depth + 1)
        if isinstance(inner, Number):  # the sign joins the span in _with_text, if it may
            sign = -1.0 if kind == "neg" else 1.0
            return Number(inner.span, None, sign * inner.value,  # type: ignore[arg-type]
                          (Span(sign_token.start_pos, sign_token.end_pos),) + inner.signs)
        return _Expr(*_extent(node))
    if kind == "placeholder":
        return _Placeholder(*_extent(node))
    if kind == "bool":
        return str(node.children[0]).upper() == "TRUE"
    if kind == "string":
        raw = str(node.children[0])[1:-1]
        return raw.replace('""', '"')
    if kind == "aggregate":
        return [_value(c, depth + 1) for c in node.children
                if isinstance(c, Tree) or c.type != "COMMA"]
    return _Expr(*_extent(node))


def _extent(tree) -> tuple[int, int]:
    """First and last token positions of a subtree (rule nodes carry none);
    without recursion, however deep the tree."""
    first, last = _edge_token(tree, 0), _edge_token(tree, -1)
    return (first.start_pos, last.end_pos) if first is not None else (0, 0)


def _edge_token(tree, side: int):
    """The first (side 0) or last (side -1) token under ``tree``."""
    stack = [tree]
    while stack:
        node = stack.pop()
        if not isinstance(node, Tree):
            return node
        # children pushed so that the wanted edge is popped first
        stack.extend(node.children if side == -1 else reversed(node.children))
    return None


def _num(text: str) -> float:
    """A literal's value; one too large for a float is inf (the caller
    refuses it where it matters: a frame's numbers, a dimension)."""
    t = text.lower()
    if t.startswith(("0x", "0o", "0b")) and len(t) > 2:
        try:
            return float(int(t[2:], {"x": 16, "o": 8, "b": 2}[t[1]]))
        except OverflowError:
            return float("inf")
    if t.startswith("0d") and len(t) > 2 and not t.startswith("0d."):
        return float(t[2:])     # float(), not int(): no limit on the number of digits
    return float(text)


def declarations(doc: Document, tree) -> list[Decl]:
    out: list[Decl] = []
    for module in tree.children:
        if not isinstance(module, Tree) or module.data != "module":
            continue
        module_name = str(module.children[0])
        for item in module.children[1:]:
            if not isinstance(item, Tree) or item.data != "data_decl":
                continue
            scope, storage, type_name, name, dims_node, value_node = _decl_parts(item)
            start, end = _extent(item)
            out.append(Decl(scope, storage, type_name, name, (dims_node, value_node), start, end,
                            module_name, doc))
    return out


def _decl_parts(item) -> tuple:
    """A data_decl node's scope, storage, type, name, dims node, value node."""
    ch = item.children
    i = 0
    scope = None
    if isinstance(ch[0], Tree) and ch[0].data == "scope":
        scope = str(ch[0].children[0]).upper()
        i = 1
    storage = str(ch[i].children[0]).upper()
    dims_node = value_node = None
    for r in ch[i + 3:]:
        if isinstance(r, Tree) and r.data == "dims":
            dims_node = r
        else:
            value_node = r
    return scope, storage, str(ch[i + 1]), str(ch[i + 2]), dims_node, value_node


def _nums(v, n: int) -> list[Number] | None:
    if isinstance(v, list) and len(v) == n and all(isinstance(x, Number) for x in v):
        return v
    return None


def _pose(v) -> tuple[dict[str, Number], tuple] | None:
    """[[x,y,z],[q1,q2,q3,q4]] -> ({'x': Number, ...}, (x,y,z,q))."""
    if not (isinstance(v, list) and len(v) == 2):
        return None
    trans, rot = _nums(v[0], 3), _nums(v[1], 4)
    if trans is None or rot is None:
        return None
    numbers = dict(zip(("x", "y", "z", "q1", "q2", "q3", "q4"), trans + rot))
    return numbers, (tuple(n.value for n in trans), tuple(n.value for n in rot))


def _elements(value, dims: list | None, name: str):
    """Yield (display name, element value) for scalars and arrays."""
    if not dims:
        yield name, value
        return

    def walk(v, depth, index):
        if depth == len(dims):
            yield f"{name}{{{','.join(map(str, index))}}}", v
            return
        if not isinstance(v, list):
            return
        for k, item in enumerate(v, 1):
            yield from walk(item, depth + 1, index + [k])

    yield from walk(value, 0, [])


def _loaddata(v) -> dict | None:
    if not (isinstance(v, list) and len(v) == 6):
        return None
    mass, cog, aom, ix, iy, iz = v
    cog_n, aom_n = _nums(cog, 3), _nums(aom, 4)
    if not all(isinstance(x, Number) for x in (mass, ix, iy, iz)) or cog_n is None or aom_n is None:
        return None
    return {"mass": mass.value, "cog": [n.value for n in cog_n], "aom": [n.value for n in aom_n],
            "ix": ix.value, "iy": iy.value, "iz": iz.value}


def _make_frame(cf: ControllerFile, decl: Decl, name: str, type_: str, pose_value,
                reference: str, info: dict, at: int, parent: Parent | None = None) -> Frame:
    doc = cf.document
    at = _start_of(pose_value, at)  # a multi-line wobj: the oframe's line is its own
    parsed = _pose(pose_value)
    pose = None
    numbers: dict[str, Number] = {}
    if parsed is None:
        if _is_literal(pose_value) and not info.get("incomplete"):
            # written out, but not [[x, y, z], [q1, q2, q3, q4]]: the controller refuses it
            cf.lint(at, "bad-shape", f"{name}: a pose is [[x, y, z], [q1, q2, q3, q4]]; "
                    "this value is not (not patchable)")
        elif decl.value is not None and not info.get("bad_shape"):  # no value: linted once, above
            cf.lint(at, "not-literal", f"{name}: not a literal pose; listed without numbers, "
                    "not patchable", severity="info")
        info = dict(info, value=None)
    else:
        numbers, (t, q) = parsed
        numbers = {k: _with_text(doc, n) for k, n in numbers.items()}
        for n in numbers.values():
            if not abs(n.value) <= NUM_MAX:
                raise doc.error(f"number {_short(n.written)} is out of range for a RAPID num "
                                "(float32)",
                                n.span.start)
        norm2 = sum(c * c for c in q)
        if norm2 == 0.0:
            cf.lint(numbers["q1"].span.start, "zero-quaternion", f"{name}: orientation is all zeros")
        else:
            err = abs(norm2 - 1.0)
            if err > NORM_WARN:
                cf.lint(numbers["q1"].span.start, "unnormalized-quaternion",
                        f"{name}: quaternion is not normalised (|sum q^2 - 1| = {err:.2e}, "
                        f"above {NORM_WARN:g})")
            elif err > NORM_INFO:
                cf.lint(numbers["q1"].span.start, "quaternion-rounding",
                        f"{name}: |sum q^2 - 1| = {err:.2e}: rounded as RobotWare writes it "
                        f"(warned above {NORM_WARN:g})", severity="info")
            pose = Pose.from_quat(*t, q)
    line = doc.line_of(at)
    return Frame(name=name, vendor="abb", type=type_, pose=pose, file=doc.path, line=line,
                 reference=reference, numbers=numbers, info=info, document=doc, parent=parent)


def _is_literal(v) -> bool:
    """A value written out in full (numbers, booleans, strings, aggregates of
    them), as opposed to one that names or computes something."""
    if isinstance(v, list):
        return all(_is_literal(x) for x in v)
    return isinstance(v, (Number, bool, str))


_BLANKS = regex.lazy(r"[ \t]*")


def _with_text(doc: Document, n: Number) -> Number:
    """The number with its text, and its signs joined to its span where only
    blanks part them from the digits ("-0.5", "- 430.25"): a patch rewrites
    those whole. A sign behind a comment or a line break stays detached
    (``Number.signs``), and so do the signs outside it: what stands between a
    sign and its digits is not the number's to replace."""
    if n.text is not None:
        return n
    text = doc.text
    start = n.span.start
    signs = list(n.signs)
    while signs and _BLANKS.fullmatch(text, signs[-1].end, start):
        start = signs.pop().start
    span = Span(start, n.span.end)
    return Number(span, doc.slice(span), n.value, tuple(signs),
                  "".join(text[s.start:s.end] for s in signs))


RECORD_SIZES = {"tooldata": 3, "wobjdata": 5}


def frames_from(cf: ControllerFile, decls: list[Decl]) -> None:
    seen: dict[tuple[str, str], Decl] = {}
    for d in decls:
        if len(d.name) > IDENT_MAX:
            cf.lint(d.start, "long-name", f"{d.name}: identifier longer than {IDENT_MAX} characters")
        key = (d.module.casefold(), d.name.casefold())
        if key in seen:
            cf.lint(d.start, "duplicate", f"{d.name}: declared twice in module {d.module} "
                    f"(first at line {cf.document.line_of(seen[key].start)})")
        seen.setdefault(key, d)
        kind = d.type.casefold()
        if kind not in FRAME_TYPES:
            continue
        _check_array_size(cf, d)
        storage = " ".join(x for x in (d.scope, d.storage) if x)
        base_info = {"storage": storage, "module": d.module}
        ph = _placeholder_in(d.value)
        if ph is not None:
            # FORMATS 1.2: an unfinished declaration is listed, never patched
            cf.lint(ph.start, "incomplete", f"{d.name}: contains the placeholder "
                    f"{cf.document.text[ph.start:ph.end]}; incomplete, not patchable")
            base_info["incomplete"] = True
        if d.value is None:
            cf.lint(d.start, "no-value", f"{d.name}: declared without a value (legal: another "
                    "module or the default gives it); not patchable here", severity="info")
        for name, v in _elements(d.value, d.dims, d.name):
            at = _start_of(v, d.start)
            size = RECORD_SIZES.get(kind)
            element_info = base_info
            if size and isinstance(v, list) and len(v) != size and not base_info.get("incomplete"):
                cf.lint(at, "bad-shape", f"{name}: a {kind} has {size} components, this value "
                        f"has {len(v)} (not patchable)")
                element_info = dict(base_info, bad_shape=True)   # said once, not per component
            if kind == "pose":
                cf.frames.append(_make_frame(cf, d, name, "pose", v, "unknown", dict(element_info), at))
            elif kind == "tooldata":
                robhold = v[0] if isinstance(v, list) and len(v) == 3 and isinstance(v[0], bool) else None
                tframe = v[1] if robhold is not None else None
                load = _loaddata(v[2]) if robhold is not None else None
                info = dict(element_info, robhold=robhold, load=load)
                ref = "flange" if robhold is not False else "world"
                cf.frames.append(_make_frame(cf, d, name, "tooldata", tframe, ref, info, at))
                if robhold and load is not None and load["mass"] <= 0:
                    cf.lint(at, "tool-mass", f"{name}: robot-held tool with load mass {load['mass']:g} kg (must be > 0)")
            elif kind == "wobjdata":
                ok = (isinstance(v, list) and len(v) == 5 and isinstance(v[0], bool)
                      and isinstance(v[1], bool) and isinstance(v[2], str))
                robhold, ufprog, ufmec = (v[0], v[1], v[2]) if ok else (None, None, None)
                info = dict(element_info, robhold=robhold, ufprog=ufprog, ufmec=ufmec)
                # uframe is in world with a robot-held tool; with a stationary
                # tool (wobj robhold TRUE) the robot holds the work object.
                uref = "wrist" if robhold else "world"
                uparent = flange() if robhold else None        # the wrist is tool0: the flange
                if ufprog is False:
                    uref = f"mechanical unit {ufmec}" if ufmec else "moving"
                    uparent = unit(ufmec)
                    cf.lint(at, "moving-uframe",
                            f"{name}: moving user frame (ufprog FALSE, ufmec {ufmec!r}): not patchable")
                cf.frames.append(_make_frame(cf, d, name, "wobjdata", v[3] if ok else None, uref,
                                             dict(info, component="uframe"), at, uparent))
                cf.frames.append(_make_frame(cf, d, f"{name}.oframe", "wobjdata",
                                             v[4] if ok else None, "uframe",
                                             dict(info, component="oframe"), at,
                                             frame_parent(name)))


def _check_array_size(cf: ControllerFile, d: Decl) -> None:
    """{3} initialised with 2 elements: the controller refuses the module."""
    if not d.dims or not isinstance(d.value, list):
        return
    level = [d.value]
    for depth, dim in enumerate(d.dims):
        if not isinstance(dim, Number):
            return            # a dimension named by a CONST: not evaluated here
        if not abs(dim.value) <= DIM_MAX:
            raise cf.document.error(f"{d.name}: array dimension {_short(_written(cf, dim))} is "
                                    "not a size the controller accepts", _start_of(dim, d.start))
        for v in level:
            if not isinstance(v, list):
                return
            if len(v) != int(dim.value):
                cf.lint(_start_of(v, d.start), "array-size",
                        f"{d.name}: dimension {depth + 1} is {int(dim.value)}, the value has "
                        f"{len(v)} elements")
                return
        level = [x for v in level for x in v]


DIM_MAX = 2 ** 31 - 1


def _written(cf: ControllerFile, n: Number) -> str:
    return n.text if n.text is not None else cf.document.text[_start_of(n, 0):n.span.end]


def _short(s: str, limit: int = 30) -> str:
    return s if len(s) <= limit else s[:limit] + "..."


def _start_of(v, default: int) -> int:
    if isinstance(v, Number):
        return v.signs[0].start if v.signs else v.span.start
    if isinstance(v, list):
        for x in v:
            s = _start_of(x, -1)
            if s >= 0:
                return s
    if isinstance(v, _Expr):
        return v.start
    return default


def parse(doc: Document, full: bool = False) -> ControllerFile:
    """Frames and lints of a module. ``full`` (``check``): every byte through
    the grammar as well, and every declaration listed (``declarations``;
    values other than frames' are parsed when first read)."""
    regions = outline(doc, routines=full)  # structure errors read best from the outline
    if full:
        _check_numbers(doc)
        try:
            _recognise(doc.text)
        except Rejected:
            # Lark first: its positioned message (or, were the two to differ,
            # the tree); the outline and the number scan above have run
            tree = parse_tree(doc, doc.text, lark_first=True)
            return _interpret(doc, declarations(doc, tree))
    frame_regions = [r for r in regions if r.kind not in ("decls", "routine")]
    compact = Compact(doc, frame_regions)
    try:
        tree = parse_tree(doc, compact.text, compact)
    except UcsioError:
        _check_numbers(doc)  # "bad number '1.2.3'" says more than Lark's token error
        raise
    compact.remap(tree)
    decls = declarations(doc, tree)
    if full:
        decls = sorted(decls + _other_declarations(doc, regions), key=lambda d: d.start)
    return _interpret(doc, decls)


def parse_whole(doc: Document) -> ControllerFile:
    """``parse(doc, full=True)`` from the tree of every byte (ucsio.parsing.lalr
    shaped as Lark shapes it): the reference the recogniser is tested
    against."""
    outline(doc)
    _check_numbers(doc)
    return _interpret(doc, declarations(doc, parse_tree(doc, doc.text)))


def _interpret(doc: Document, decls: list["Decl"]) -> ControllerFile:
    cf = ControllerFile(document=doc, vendor="abb")
    cf.extra["declarations"] = decls
    frames_from(cf, decls)
    return cf


# -- check: the recogniser and the declarations the fast path leaves out -----------
def _recognise(text: str) -> None:
    """Every byte through the grammar (ucsio.parsing.lalr.Parser.recognise);
    Rejected if not RAPID."""
    global _SHORTCUTS
    parser = _parser()
    if _SHORTCUTS is None:
        from ...parsing.lalr import atomic, bracketed

        tp = parser.terminals
        gap = f"(?:{atomic(tp['WS'])}|{atomic(tp['COMMENT'])})*+"
        # a literal number (signs are unary operators), string or boolean
        element = (f"(?:[+-]{gap})*+{atomic(tp['NUMBER'])}|{atomic(tp['STRING'])}"
                   f"|{atomic(tp['BOOL'])}")
        aggregate = bracketed(r"\[", r"\]", element, gap)
        for _ in range(3):          # robtarget arrays: [[[x, y, z], [q1, ...], ...], ...]
            aggregate = bracketed(r"\[", r"\]", f"{aggregate}|{element}", gap)
        # atom: NUMBER | aggregate: the parser moves on alike after either
        _SHORTCUTS = {"LSQB": (regex.compile(aggregate), "NUMBER")}
    parser.recognise(text, "file", _SHORTCUTS)


_SHORTCUTS = None
# one declaration at the head of a run the outline found (`decls`): its words
_DECL_WORDS = regex.lazy(
    r"(?:\s++|![^\r\n]*+)*+(?P<decl>(?:(?P<scope>LOCAL|TASK)" + _GAP + r")?(?P<storage>PERS|CONST|VAR)"
    + _GAP + r"(?P<type>\w++|" + _PLACEHOLDER + r")(?:\s|![^\r\n]*+)*+(?P<name>\w++|" + _PLACEHOLDER
    + r")" + _DECL_REST + ")", re.IGNORECASE)
_MODULE_NAME = regex.lazy(r"MODULE\b(?:\s|![^\r\n]*+)*+(?P<name>\w*)", re.IGNORECASE)


def _other_declarations(doc: Document, regions: list[Region]) -> list["Decl"]:
    """The declarations in the outline's runs (every one but the frames'),
    from their words; the recogniser has accepted the file, so each is a
    data_decl of the grammar. A value is parsed only if read."""
    text = doc.text
    out = []
    module = ""
    for r in regions:
        if r.kind == "module":
            module = _MODULE_NAME.match(text, r.span.start).group("name")
            continue
        if r.kind != "decls":
            continue
        pos, end = r.span.start, r.span.end
        while pos < end:
            m = _DECL_WORDS.match(text, pos, end)
            if m is None:       # pragma: no cover - the outline matched this run
                raise doc.error("declaration not understood", pos)
            storage, scope = m.group("storage").upper(), m.group("scope")
            out.append(_LazyDecl(scope.upper() if scope else None, storage, m.group("type"),
                                 m.group("name"), None, m.start("decl"), m.end(), module, doc))
            pos = m.end()
    return out


# -- taught positions (robtargets) ---------------------------------------------------
class Target(Value):
    """A module-level ``robtarget``: the pose of the TCP of the tool it is
    taught with, in the object frame of its work object (both named where
    the target is used, not in the data). ``pose`` is None, with
    ``problem``, where the value is not a literal [[x,y,z],[q1..q4],...]."""

    __slots__ = ("name", "pose", "line", "col", "module", "problem")

    def __init__(self, name, pose, line, col, module, problem=None):
        self.name, self.pose, self.line, self.col = name, pose, line, col
        self.module, self.problem = module, problem


def robtargets(cf: ControllerFile) -> list[Target]:
    """The robtargets of a module parsed with ``full=True`` (the fast path
    leaves them out), in file order; arrays are skipped."""
    doc = cf.document
    out = []
    for d in cf.extra.get("declarations", ()):
        if d.type.casefold() != "robtarget" or d.dims:
            continue
        line, col = doc.line_col(d.start)
        v = d.value
        parsed = _pose(v[:2]) if isinstance(v, list) and len(v) == 4 else None
        if parsed is None:
            problem = doc.error(f"{d.name}: not a literal robtarget [[x, y, z], [q1, q2, q3, q4], "
                                "[cf1, cf4, cf6, cfx], [eax_a, ...]]", _start_of(v, d.start))
            out.append(Target(d.name, None, line, col, d.module, problem))
            continue
        _, (t, q) = parsed
        if sum(c * c for c in q) == 0.0:
            out.append(Target(d.name, None, line, col, d.module,
                              doc.error(f"{d.name}: orientation is all zeros", d.start)))
            continue
        out.append(Target(d.name, Pose.from_quat(*t, q), line, col, d.module))
    return out
