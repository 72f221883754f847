"""FANUC TP programs (.ls): text -> the frames a program sets, through
grammars/tp.lark.

A program sets a frame from a position register:

    1:  PR[16]=LPOS    ;
    2:  PR[16,1]=(-.4)    ;
    ...
    7:  PR[16,6]=(-90)    ;
    8:  UTOOL[1:SSW]=PR[16] ;

``frames prog.ls`` lists UT1 (label SSW) with the values PR[16] holds at
that line, read from the /MN lines above it in program order: ``PR[n,i]=``
with a literal sets component i (the spans of those numbers are the frame's
numbers, on their own lines); ``PR[n]=LPOS`` or ``JPOS`` leaves all six
unknown (the robot's position when it runs), ``PR[n]=LPOS-LPOS`` and
``PR[n]=PR[n]-PR[n]`` make them 0; any other value, or an assignment
through an indirect index (``PR[R[3]]=``, any register then), unknown. A
frame whose six values are not all known is listed without them, with the
``not-literal`` lint; so is one set through an indirect index
(``UFRAME[R[9]]=PR[16]``), named ``UF[R[9]]``. Jumps and calls are not
followed: the values are those the lines above give. Any other /MN line
is kept as it is (a motion's options and attached logic, a generated line
without its number, a line ucsio does not understand): only the header,
/POS and the assignments must parse. A frame set again is how a program
computes it: ``duplicate-frame`` warns only for two literal values that
differ. A literal no FANUC REAL holds is refused, file:line:col.

Two ways through the grammar, as for the other languages: ``full=True``
(``check``) recognises every byte first; the fast path parses the program
with its /POS section blanked (a generated path program holds thousands of
points and no frame). ``positions(doc)`` reads /POS (the taught points,
with their UF, UT and CONFIG; an untaught one with neither, ``UF : F``)
position by position with patterns made of the grammar's terminals, no
tree; ``positions_whole`` is the grammar's reading it is held to.

A ``.ls`` that is not a TP program (the controller's logs share the suffix:
``errall.ls``, ``logbook.ls``) is listed as such, with no frames: a file is
a program when it begins with ``/PROG``, or has a ``/MN``, ``/POS`` or
``/END`` line.
"""
from __future__ import annotations

import re

from ...errors import UcsioError
from ...geometry.frames import Number
from ...values import Value
from ...parsing import regex
from . import base as fanuc
from ...parsing.document import Document, Span, lf_lines, small_int
from ...parsing.lalr import Rejected, Tree
from ...parsing.model import ControllerFile

START = ("file",)
AXES = fanuc.COMPONENTS
_SECTION_LINE = regex.lazy(r"^[ \t\f\r]*/(?:PROG|MN|POS|END)(?![A-Za-z0-9_])", re.M)
_MN_LINE = regex.lazy(r"^[ \t\f\r]*/MN(?![A-Za-z0-9_])", re.M)
_POS_LINE = regex.lazy(r"^[ \t\f\r]*/POS(?![A-Za-z0-9_])[^\n]*", re.M)
_END_LINE = regex.lazy(r"^[ \t\f\r]*/END(?![A-Za-z0-9_])", re.M)
_LITERAL_NUMBER = regex.lazy(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)")
# a number with an exponent, in parentheses or not, ending the statement: 1e39 ;  (-4E+40) ;
_EXPONENT_NUMBER = regex.lazy(r"[( \t]*([+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)[eE][+-]?[0-9]+)"
                              r"[) \t]*;[ \t\f\r]*\Z")
# PR[8]=PR[8]-PR[8]: the register zeroed (the value's text, any comments)
_SELF_MINUS = regex.lazy(r"PR\[[ \t]*([0-9]+)[ \t]*(?::[^\]\n]*)?\][ \t]*-[ \t]*"
                         r"PR\[[ \t]*([0-9]+)[ \t]*(?::[^\]\n]*)?\][ \t]*;[ \t\f\r]*\Z")
_FRAME_HEAD = regex.lazy(r"U(?:FRAME|TOOL)[ \t]*\[")
# the end of a motion's attached logic: ------ ;
_SEPARATOR = regex.lazy(r"-+[ \t]*;\Z")
_DEFAULT_GROUP = regex.lazy(r"DEFAULT_GROUP[ \t]*=[ \t]*([^;\n]*)")
ZERO = Number(Span(0, 0), "0", 0.0)     # a component LPOS-LPOS made 0: written nowhere


def is_program(text: str) -> bool:
    head = text.lstrip("\ufeff \t\f\r\n")
    return head.startswith("/PROG") or _SECTION_LINE.search(text) is not None


# -- parsing -----------------------------------------------------------------------
def _parser():
    from ...parsing.grammar import parser
    return parser("tp", START)


_READABLE = {"_NL": "end of line", "PROG": "/PROG", "MN": "/MN", "POS": "/POS", "END": "/END",
             "SECTION": "a section (/ATTR)", "LINE": "a line", "LINENO": "a line number",
             "COLON": "':'", "REST": "an instruction", "CONT": "a continued line",
             "FRAME_SET": "UFRAME/UTOOL", "PR_SET": "PR[...]", "PR_REF": "PR[...]",
             "LITERAL": "a number", "CURRENT": "LPOS or JPOS", "INT": "an integer",
             "REGISTER": "R[...]", "COMMENT": "':comment'", "LSQB": "'['", "RSQB": "']'",
             "EQUAL": "'='", "SEMICOLON": "';'", "COMMA": "','", "LBRACE": "'{'",
             "RBRACE": "'}'", "P": "P[...]", "GP": "GP1:", "POINT_COMMENT": "':\"comment\"'",
             "CONFIG_STRING": "'N U T, 0, 0, 0'", "AXIS": "a coordinate (X =, J1 =)",
             "NUMBER": "a number", "STARS": "a number", "UNIT": "mm or deg",
             "GROUP_PREFIX": "GP1:", "$END": "end of file", "UF": "UF", "UT": "UT",
             "CONFIG": "CONFIG"}


def _parse(doc: Document, text: str, lark_first: bool = False) -> Tree:
    return fanuc.tree("tp", doc, text, _READABLE, "not a FANUC TP program", lark_first)


def _lines(doc: Document) -> str:
    text = lf_lines(doc.text)
    if not text.strip():
        raise doc.error("empty file: no FANUC TP program", 0)
    return text


def parse(doc: Document, full: bool = False) -> ControllerFile:
    """The frames a TP program sets; ``full`` (``check``): every byte
    through the grammar first."""
    text = _lines(doc)
    if not is_program(text):
        cf = fanuc.controller_file(doc)
        cf.extra["kind"] = "listing"
        return cf
    if full:
        try:
            _recognise(text)
        except Rejected:
            return _whole(doc, text, lark_first=True)
        for _ in _read_positions(doc, text):    # a number no REAL holds is refused there
            pass
    return _interpret(doc, _parse(doc, _without_positions(text)))


def _recognise(text: str) -> None:
    """Every byte of ``text`` through the grammar, without a tree; a run of
    plain statement lines (``n:`` and an instruction that is no PR or frame
    assignment: a path program's motion lines) goes in as one TEXT line,
    which the parser takes alike. Rejected if not a TP program."""
    global _SHORTCUTS
    if _SHORTCUTS is None:
        plain = r"[0-9]+[ \t\f\r]*:(?![ \t\f\r]*[UP])[^\n]*+"
        _SHORTCUTS = {"LINENO": (regex.compile(f"{plain}(?:\\n[ \\t\\f\\r\\n]*+{plain})*+"),
                                 "TEXT")}
    _parser().recognise(text, "file", _SHORTCUTS)


_SHORTCUTS = None


def _pos_line(text: str):
    """The match of the /POS line that opens the positions: the first after
    /MN (a header section may be named /POS, and /MN's lines never begin
    with it)."""
    mn = _MN_LINE.search(text)
    return _POS_LINE.search(text, mn.end()) if mn is not None else None


def _without_position_lines(text: str) -> str:
    """``text`` without the lines between /POS and /END (its offsets are
    not the file's: for recognition only)."""
    pos = _pos_line(text)
    if pos is None:
        return text
    end = _END_LINE.search(text, pos.end())
    return text[:pos.end()] + "\n" + (text[end.start():] if end is not None else "")


def _without_positions(text: str) -> str:
    """``text`` with the lines between /POS and /END blanked (same length)."""
    pos = _pos_line(text)
    if pos is None:
        return text
    end = _END_LINE.search(text, pos.end())
    stop = end.start() if end is not None else len(text)
    body = text[pos.end():stop]
    return text[:pos.end()] + "\n".join(" " * len(p) for p in body.split("\n")) + text[stop:]


def parse_whole(doc: Document) -> ControllerFile:
    """``parse(doc, full=True)`` from the tree of every byte."""
    text = _lines(doc)
    if not is_program(text):
        return parse(doc)
    return _whole(doc, text)


def _whole(doc: Document, text: str, lark_first: bool = False) -> ControllerFile:
    return _interpret(doc, _parse(doc, text, lark_first))


# -- /MN: the frames --------------------------------------------------------------------
class _Register:
    """What the program has put in a position register so far: ``values``
    {component 1..6: Number (ZERO where LPOS-LPOS made it 0) or None
    (unknown)}; ``joint`` where it holds joint values (JPOS)."""

    __slots__ = ("values", "joint")

    def __init__(self, values: dict, joint: bool):
        self.values, self.joint = values, joint


def _interpret(doc: Document, tree: Tree) -> ControllerFile:
    cf = fanuc.controller_file(doc)
    cf.extra["kind"] = "program"
    group = 1
    for node in tree.children:
        if not isinstance(node, Tree):
            continue
        if node.data == "prog":
            cf.extra["program"] = node.children[1].value.split()[0]
        elif node.data == "section":
            for tok in node.children[1:]:
                m = _DEFAULT_GROUP.match(tok.value)
                if m is not None:
                    group = _default_group(m.group(1))
        elif node.data == "mn":
            _main(cf, node, group)
        elif node.data == "pos":
            _positions(doc, node)           # a number no REAL holds is refused there
    if tree.children and getattr(tree.children[-1], "type", None) == "LINE":
        tok = tree.children[-1]
        cf.lint(tok.start_pos, "after-end", f"text after /END on its line ({tok.value[:30]!r}): "
                                            "ignored", severity="info")
    cf.extra["group"] = group
    return cf


def _default_group(text: str) -> int:
    """DEFAULT_GROUP = 1,*,*,*,*: the first group the program moves (1)."""
    for i, g in enumerate(text.split(","), 1):
        if g.strip() == "1":
            return i
    return 1


def _main(cf: ControllerFile, mn: Tree, group: int) -> None:
    regs: dict[tuple[int, int], _Register] = {}
    seen: dict = {}                     # the frame's name: where it was set last
    for line in mn.children[1:]:
        if not isinstance(line, Tree):
            continue
        if line.data == "text_line":
            _text_line(cf, line.children[0])
            continue
        stmt = _statement(line)
        if isinstance(stmt, Tree) and stmt.data == "pr_set":
            _pr_set(cf, stmt, regs, group)
        elif isinstance(stmt, Tree) and stmt.data == "frame_set":
            fr = _frame_set(cf, stmt, regs, group)
            _set_again(cf, stmt.children[0].start_pos, fr, seen.get(fr.name.upper()))
            seen[fr.name.upper()] = fr
            cf.frames.append(fr)
        elif stmt is not None and _FRAME_HEAD.match(stmt.value):
            cf.lint(stmt.start_pos, "unread-frame-set",
                    f"a frame assignment ucsio does not read: {stmt.value[:40]!r}")


def _statement(line: Tree):
    """The statement of ``[n]: statement``: a frame_set or pr_set node, a
    REST token, or None (an empty line)."""
    for child in line.children:
        if isinstance(child, Tree) or child.type == "REST":
            return child
    return None


def _text_line(cf: ControllerFile, tok) -> None:
    """A /MN line that is no statement: a motion's logic ends at a line of
    dashes; any other is kept as it is, and said (a frame assignment there
    would not be read)."""
    if _SEPARATOR.match(tok.value):
        return
    if _FRAME_HEAD.match(tok.value):
        cf.lint(tok.start_pos, "unread-frame-set",
                f"a frame assignment ucsio does not read (no line number): {tok.value[:40]!r}")
        return
    cf.lint(tok.start_pos, "unread-line", f"a /MN line that is no numbered statement, kept as "
                                          f"it is: {tok.value[:40]!r}", severity="info")


def _set_again(cf: ControllerFile, at: int, frame, before) -> None:
    """A frame the program sets a second time: a TP program computes frames
    so (a register zeroed, then PR[n]=LPOS), so only two literal values
    that differ warn."""
    if before is None:
        return
    differ = frame.pose is not None and before.pose is not None and frame.pose != before.pose
    cf.lint(at, "duplicate-frame", f"{frame.name} is set twice (lines {before.line} and "
                                   f"{frame.line})" + ("" if differ else
                                                       ": not both literal values that differ"),
            severity="warning" if differ else "info")


def _pr_set(cf: ControllerFile, stmt: Tree, regs: dict, group: int) -> None:
    ch = stmt.children
    i = 1
    gp = group
    if getattr(ch[i], "type", None) == "GROUP_PREFIX":
        gp = cf.document.integer(ch[i].value[2:].rstrip(" \t:"), ch[i].start_pos, "group")
        i += 1
    index = ch[i]
    number = _literal_index(index)
    i += 1
    component = None
    if i < len(ch) and getattr(ch[i], "type", None) == "INT":
        component = int(ch[i].value) if len(ch[i].value) < 10 else -1
        i += 1
    if i < len(ch) and getattr(ch[i], "type", None) == "COMMENT":
        i += 1
    value = ch[i]
    if number is None:                  # PR[R[3]]=...: any register, unknown now
        for reg in regs.values():
            reg.values = dict.fromkeys(reg.values)
        return
    key = (number, gp)
    if component is None:
        regs[key] = _whole_value(value, number)
        return
    reg = regs.get(key)
    if reg is None:                     # the rest is what the controller holds
        reg = regs[key] = _Register(dict.fromkeys(range(1, 7)), False)
    if value.type == "REST":
        _refuse_huge(cf.document, value)
    reg.values[component] = _literal(cf.document, value) if value.type == "LITERAL" else None


def _whole_value(value, number: int) -> _Register:
    """PR[n]=VALUE: LPOS/JPOS (unknown), LPOS-LPOS or PR[n]-PR[n] (zeros),
    anything else (unknown)."""
    text = value.value
    if value.type == "CURRENT":
        words = text.replace(" ", "").replace("\t", "").upper()
        joint = words.startswith("JPOS")
        zero = "-" in words
        return _Register(dict.fromkeys(range(1, 7), ZERO if zero else None), joint)
    m = _SELF_MINUS.match(text) if value.type == "REST" else None
    if m is not None and small_int(m.group(1)) == number == small_int(m.group(2)):
        return _Register(dict.fromkeys(range(1, 7), ZERO), False)
    return _Register(dict.fromkeys(range(1, 7)), False)


def _literal(doc: Document, tok) -> Number:
    """The number inside a LITERAL token ((-1100.3), ((-29)), 770.299): its
    span without the parentheses, the sign included."""
    m = _LITERAL_NUMBER.search(tok.value)
    return _number(doc, m.group(), tok.start_pos + m.start())


def _number(doc: Document, text: str, start: int) -> Number:
    """A number the program writes; one beyond what a FANUC REAL (float32)
    holds is refused, as the controller would (400 digits read as inf)."""
    value = float(text)
    if not abs(value) <= fanuc.REAL_MAX:
        raise doc.error(f"number {text[:30]} is out of range for a FANUC REAL (float32)", start)
    return Number(Span(start, start + len(text)), text, value)


def _refuse_huge(doc: Document, tok) -> None:
    """A value the LITERAL terminal leaves to REST (``1e39``, ``(-4E+40)``):
    not read, but refused where no REAL holds it."""
    m = _EXPONENT_NUMBER.match(tok.value)
    if m is not None:
        _number(doc, m.group(1), tok.start_pos + m.start(1))


def _literal_index(index: Tree):
    """The number of ``k`` / ``k:comment``; None for ``R[k]``."""
    first = index.children[0]
    if isinstance(first, Tree) or len(first.value) >= 10:
        return None
    return int(first.value)


def _index(index: Tree) -> tuple[str, str | None]:
    """(the number as written, "1" or "R[9]" or "R[9:count]"; the comment
    after it, or None)."""
    first = index.children[0]
    comment = index.children[1].value[1:].strip() if len(index.children) > 1 else ""
    if isinstance(first, Tree):                 # register: R [ INT [COMMENT] ]
        first = f"R[{first.children[1].value}]"
    else:
        first = first.value
    return first, comment or None


def _frame_set(cf: ControllerFile, stmt: Tree, regs: dict, group: int):
    doc = cf.document
    ch = stmt.children
    head, index, source = ch[0], ch[1], ch[2]
    ftype = head.value.upper()
    line = doc.line_of(head.start_pos)
    literal = _literal_index(index)
    number_text, label = _index(index)
    what = fanuc.frame_name(ftype, literal if literal is not None else number_text, group)
    info: dict = {}
    numbers = None
    values = None
    why = None
    if isinstance(source, Tree):            # pr_ref
        pr = _literal_index(source.children[1])
        info["set_from"] = f"PR[{_index(source.children[1])[0]}]"
        reg = regs.get((pr, group)) if pr is not None else None
        if pr is None:
            why = f"the register is {info['set_from'][3:-1]}, known only when the program runs"
        elif reg is None:
            why = (f"PR[{pr}] is not given values in this program before line {line}: it holds "
                   "what the controller has when the program runs")
        elif reg.joint:
            why = f"PR[{pr}] holds joint values (JPOS), not X Y Z W P R"
        elif any(reg.values.get(i) is None for i in range(1, 7)):
            unknown = [AXES[i - 1].upper() for i in range(1, 7) if reg.values.get(i) is None]
            why = (f"PR[{pr}] {' '.join(unknown)} {'is' if len(unknown) == 1 else 'are'} not "
                   f"given literal values in this program before line {line}")
        else:
            comps = [reg.values.get(i) for i in range(1, 7)]
            values = {k: v.value for k, v in zip(AXES, comps)}
            numbers = {k: v for k, v in zip(AXES, comps) if v is not ZERO}
            for k, v in numbers.items():
                problem = fanuc.range_problem(k, v.value)
                if problem:
                    cf.lint(v.span.start, "out-of-range", f"{what}: {problem}")
    else:
        info["set_from"] = source.value.rstrip(" \t;")
        why = f"set from {info['set_from'][:40]!r}, not from a position register"
    if literal is None:
        why = (f"the frame number is {number_text}, known only when the program runs"
               + (f"; {why}" if why else ""))
    if why:
        cf.lint(head.start_pos, "not-literal", f"{what}: {why}; listed without values"
                if values is None else f"{what}: {why}", severity="info")
    return fanuc.make_frame(doc, ftype, literal if literal is not None else number_text, group,
                            line, numbers, values=values, label=label, info=info)


# -- /POS: the taught points ------------------------------------------------------------
class PointGroup(Value):
    """One motion group of a taught point: ``uf``/``ut`` the frames it was
    taught in (None for F: never taught, ``untaught``), ``config`` ('N U T, 0, 0, 0', None for joints), ``values``
    {axis (X..R, J1.., E1..): Number, or None for ********} and their
    ``units`` (mm, deg); ``at``, ``uf_at``, ``ut_at``: the offsets of its
    ``GPn``, and of the UF and UT numbers (for file:line:col)."""

    __slots__ = ("group", "uf", "ut", "config", "values", "units", "line", "at", "uf_at",
                 "ut_at")

    def __init__(self, group, uf, ut, config, values, units, line, at=None, uf_at=None,
                 ut_at=None):
        self.group, self.uf, self.ut, self.config = group, uf, ut, config
        self.values, self.units, self.line = values, units, line
        self.at, self.uf_at, self.ut_at = at, uf_at, ut_at

    @property
    def untaught(self) -> bool:
        """A position that exists and was never taught: ``UF : F, UT : F``
        (its values ``********``)."""
        return self.uf is None or self.ut is None

    @property
    def joint(self) -> bool:
        """Joint values (J1 = ...), not X Y Z W P R."""
        return any(k.startswith("J") for k in self.values)

    @property
    def cartesian(self) -> bool:
        return all(self.values.get(k.upper()) is not None for k in AXES)

    @property
    def pose(self):
        """The point as a Pose (its TCP in user frame ``uf``), or None for
        joint values."""
        if not self.cartesian:
            return None
        from ...geometry.frames import Pose
        return Pose.from_wpr(*(self.values[k.upper()].value for k in AXES))


class Point(Value):
    """A position of /POS: ``P[12]`` with its comment and its groups
    ({group number: PointGroup}); ``at`` the offset of its ``P``, ``col``
    its column on ``line``."""

    __slots__ = ("number", "comment", "line", "groups", "at", "col")

    def __init__(self, number, comment, line, groups, at=None, col=None):
        self.number, self.comment, self.line, self.groups = number, comment, line, groups
        self.at, self.col = at, col

    @property
    def name(self) -> str:
        return f"P[{self.number}]"


def positions(doc: Document) -> list[Point]:
    """The taught points of a program's /POS section, in order
    (``iter_positions``)."""
    return list(iter_positions(doc))


def iter_positions(doc: Document):
    """The taught points of a program's /POS section, one at a time (a
    reader that keeps only what it needs of each holds no list of 100,000).
    The program without /POS goes through the grammar first (a syntax error
    anywhere is file:line:col); /POS is read position by position with
    patterns made of the grammar's own terminals, with no tree. A position
    the patterns do not take leaves the file to the grammar
    (``positions_whole``), which reads it alike or says where it is wrong."""
    text = _lines(doc)
    if not is_program(text):
        return
    try:
        _recognise(_without_position_lines(text))
    except Rejected:
        yield from positions_whole(doc)
        return
    yield from _read_positions(doc, text)


def _read_positions(doc: Document, text: str):
    """/POS of a program whose other sections the grammar has taken."""
    done = 0
    try:
        for point in _PositionScanner(doc, text).read():
            yield point
            done += 1
    except (_NotPlain, UcsioError):
        # the same points, or the grammar's first error (a syntax error
        # after a number no REAL holds is the one the tree reports)
        yield from positions_whole(doc)[done:]


def positions_whole(doc: Document) -> list[Point]:
    """``positions`` from the tree of every byte: the reference the fast
    reader is held to (tests/test_tp_lines.py)."""
    text = _lines(doc)
    if not is_program(text):
        return []
    for node in _parse(doc, text).children:
        if isinstance(node, Tree) and node.data == "pos":
            return _positions(doc, node)
    return []


def _positions(doc: Document, pos: Tree) -> list[Point]:
    out = []
    for p in pos.children[1:]:
        ch = p.children
        comment = None
        groups = {}
        for c in ch[2:]:
            if isinstance(c, Tree):
                g = _point_group(doc, c)
                groups[g.group] = g
            elif c.type == "POINT_COMMENT":
                comment = _point_comment(c.value)
        number = _index_number(doc, ch[1].value, ch[1].start_pos)
        at = ch[0].start_pos
        line, col = doc.line_col(at)
        out.append(Point(number, comment, line, groups, at, col))
    return out


def _point_group(doc: Document, node: Tree) -> PointGroup:
    ch = node.children
    gp, uf, ut = ch[0], ch[1], ch[2]
    config = None
    values, units = {}, {}
    for c in ch[3:]:
        if c.data == "config":
            config = c.children[1].value[1:-1]
            continue
        axis, value, unit = c.children
        key = axis.value.upper()
        values[key] = None if value.type == "STARS" else _number(doc, value.value, value.start_pos)
        units[key] = unit.value
    return PointGroup(_index_number(doc, gp.value[2:], gp.start_pos + 2),
                      _frame_number(doc, uf.value, uf.start_pos),
                      _frame_number(doc, ut.value, ut.start_pos), config, values, units,
                      doc.line_of(gp.start_pos), gp.start_pos, uf.start_pos, ut.start_pos)


def _point_comment(text: str) -> str:
    """``:"App"`` -> App."""
    return text[1:].strip()[1:-1]


def _index_number(doc: Document, digits: str, at: int) -> int:
    """A point's or group's number as written; digits no controller
    numbers by (more than 9 digits) are refused, naming the place; judged by
    ``small_int``, as every integer a reader takes from a file."""
    value = small_int(digits, 999_999_999)
    if value is None:
        raise doc.error(f"number {digits[:30]}... has {len(digits)} digits: not a FANUC index", at)
    return value


def _frame_number(doc: Document, text: str, at: int) -> int | None:
    """The UF or UT a position was taught in; None for F (untaught)."""
    return None if text == "F" else _index_number(doc, text, at)


class _NotPlain(Exception):
    """Text the fast /POS reader does not take: the grammar decides."""


class _PositionScanner:
    """/POS read position by position, each token matched with the
    grammar's own terminal patterns (``_position_patterns``) as its lexer
    would match it, so what this reads is what the tree gives; anything
    else raises _NotPlain."""

    def __init__(self, doc: Document, text: str):
        self.doc, self.text = doc, text
        self.p = _position_patterns()
        self.counted = (0, 1)           # (offset, its line): lines counted as the reader goes

    def line(self, at: int) -> int:
        """The line of ``at`` (offsets only grow): the LFs of the grammar's
        copy of the text are the document's line ends, and the document's
        table of 800,000 line starts is not built."""
        offset, line = self.counted
        line += self.text.count("\n", offset, at)
        self.counted = (at, line)
        return line

    def col(self, at: int) -> int:
        return at - self.text.rfind("\n", 0, at)

    def read(self):
        text = self.text
        pos = _pos_line(text)
        if pos is None:
            return
        end = _END_LINE.search(text, pos.end())
        stop = text.index("/END", end.start())
        at = self._need(self.p.newline, pos.end()).end()
        while at < stop:
            m = self.p.plain.match(text, at)
            point, at = self._plain(m) if m is not None else self._point(at)
            yield point
        if at != stop:          # pragma: no cover - a newline ends at a non-blank
            raise _NotPlain

    def _plain(self, m) -> tuple[Point, int]:
        """A position of one group with X Y Z W P R and nothing else, the
        way a controller writes most: one match (``_Patterns.plain``)."""
        doc = self.doc
        p_at = m.start("p")
        p_line, p_col = self.line(p_at), self.col(p_at)
        values, units = {}, {}
        for key in _CARTESIAN:
            value = m.group(key)
            values[key] = None if value[0] == "*" else _number(doc, value, m.start(key))
            units[key] = _UNITS[m.group(key + "u")]
        gp_at, config, comment = m.start("gp"), m.group("config"), m.group("comment")
        group = PointGroup(_index_number(doc, m.group("gp")[2:], gp_at + 2),
                           _frame_number(doc, m.group("uf"), m.start("uf")),
                           _frame_number(doc, m.group("ut"), m.start("ut")),
                           None if config is None else config[1:-1], values, units,
                           self.line(gp_at), gp_at, m.start("uf"), m.start("ut"))
        return Point(_index_number(doc, m.group("number"), m.start("number")),
                     None if comment is None else _point_comment(comment), p_line,
                     {group.group: group}, p_at, p_col), m.end()

    def _need(self, pattern, at: int):
        m = pattern.match(self.text, at)
        if m is None:
            raise _NotPlain
        return m

    def _point(self, at: int) -> tuple[Point, int]:
        doc, p = self.doc, self.p
        head = self._need(p.head, at)
        p_at = head.start("p")
        p_line, p_col = self.line(p_at), self.col(p_at)
        number = _index_number(doc, head.group("number"), head.start("number"))
        comment = head.group("comment")
        groups = {}
        at = head.end()
        while True:
            g = p.group.match(self.text, at)
            if g is None:
                break
            group, at = self._group(g)
            groups[group.group] = group
        if not groups:
            raise _NotPlain
        at = self._need(p.tail, at).end()
        return Point(number, None if comment is None else _point_comment(comment),
                     p_line, groups, p_at, p_col), at

    def _group(self, g) -> tuple[PointGroup, int]:
        doc, p, text = self.doc, self.p, self.text
        values, units = {}, {}
        at = g.end()
        c = p.component.match(text, at)
        while c is not None:
            value, key = c.group("value"), c.group("axis").upper()
            values[key] = None if value[0] == "*" else _number(doc, value, c.start("value"))
            units[key] = c.group("unit")
            sep = p.comma.match(text, c.end())
            if sep is None:         # the last one, without a trailing ","
                at = p.newline_maybe.match(text, c.end()).end()
                break
            at = sep.end()          # "," and a line end: another component, or none
            c = p.component.match(text, at)
        config = g.group("config")
        gp_at = g.start("gp")
        group = PointGroup(_index_number(doc, g.group("gp")[2:], gp_at + 2),
                           _frame_number(doc, g.group("uf"), g.start("uf")),
                           _frame_number(doc, g.group("ut"), g.start("ut")),
                           None if config is None else config[1:-1], values, units,
                           self.line(gp_at), gp_at, g.start("uf"), g.start("ut"))
        return group, at


_CARTESIAN = ("X", "Y", "Z", "W", "P", "R")
_UNITS = {"mm": "mm", "deg": "deg"}     # one string each, however many points


class _Patterns:
    __slots__ = ("newline", "newline_maybe", "head", "group", "component", "comma", "tail",
                 "plain")


_PATTERNS = None


def _position_patterns() -> _Patterns:
    """The tokens of a /POS position, from grammars/tp.lark's terminals,
    each atomic (matched as the lexer matches it, never given back), WS
    between any two, _NL only where the grammar has it."""
    global _PATTERNS
    if _PATTERNS is None:
        from ...parsing.lalr import atomic
        t = _parser().terminals
        gap = f"{atomic(t['WS'])}?+"
        nl = f"(?:{gap}{atomic(t['_NL'])})?+"

        def tokens(*parts: str) -> str:
            return gap.join(parts)
        frame_no = f"{atomic(t['INT'])}|{atomic(t['UNTAUGHT'])}"
        p = _Patterns()
        p.newline = regex.compile(atomic(t["_NL"]))
        head = tokens(f"(?P<p>{atomic(t['P'])})", r"\[", f"(?P<number>{atomic(t['INT'])})",
                      f"(?P<comment>{atomic(t['POINT_COMMENT'])})?+", r"\]", r"\{") + nl
        p.head = regex.compile(head)
        group = (gap + tokens(f"(?P<gp>{atomic(t['GP'])})", ":") + nl
                 + gap + tokens("UF", ":", f"(?P<uf>{frame_no})", ",") + nl
                 + gap + tokens("UT", ":", f"(?P<ut>{frame_no})", ",") + nl
                 + f"(?:{gap}" + tokens(atomic(t["CONFIG_WORD"]), ":",
                                        f"(?P<config>{atomic(t['CONFIG_STRING'])})", ",") + nl
                 + ")?+")
        p.group = regex.compile(group)
        p.component = regex.compile(gap + tokens(
            f"(?P<axis>{atomic(t['AXIS'])})", "=",
            f"(?P<value>{atomic(t['NUMBER'])}|{atomic(t['STARS'])})",
            f"(?P<unit>{atomic(t['UNIT'])})"))
        p.comma = regex.compile(gap + "," + nl)
        p.newline_maybe = regex.compile(nl)
        tail = gap + tokens(r"\}", ";") + gap + atomic(t["_NL"])
        p.tail = regex.compile(tail)
        # the common position in one match: one group, X Y Z W P R in order
        cartesian = (gap + f",{nl}{gap}").join(
            tokens(f"{axis}(?=[ \t]*=)", "=", f"(?P<{axis}>{atomic(t['NUMBER'])}|"
                   f"{atomic(t['STARS'])})", f"(?P<{axis}u>{atomic(t['UNIT'])})")
            for axis in _CARTESIAN)
        p.plain = regex.compile(head + group + gap + cartesian + f"(?:{gap},)?+" + nl
                                + tail)
        _PATTERNS = p
    return _PATTERNS
