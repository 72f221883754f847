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
followed: the values are those the lines above give.

Two ways through the grammar, as for the other languages: ``full=True``
(``check``) recognises every byte first; the fast path parses the program
with its /POS section blanked (a generated path program holds thousands of
points and no frame). ``positions(doc)`` reads /POS (the taught points,
with their UF, UT and CONFIG).

A ``.ls`` that is not a TP program (the controller's logs share the suffix:
``errall.ls``, ``logbook.ls``) is listed as such, with no frames: a file is
a program when it begins with ``/PROG``, or has a ``/MN``, ``/POS`` or
``/END`` line.
"""
from __future__ import annotations

import re

from ..geometry.frames import Number
from ..values import Value
from . import fanuc, regex
from .document import Document, Span, lf_lines, small_int
from .lalr import Rejected, Tree
from .model import ControllerFile

START = ("file",)
AXES = fanuc.COMPONENTS
_SECTION_LINE = regex.lazy(r"^[ \t\f\r]*/(?:PROG|MN|POS|END)(?![A-Za-z0-9_])", re.M)
_POS_LINE = regex.lazy(r"^[ \t\f\r]*/POS(?![A-Za-z0-9_])[^\n]*", re.M)
_END_LINE = regex.lazy(r"^[ \t\f\r]*/END(?![A-Za-z0-9_])", re.M)
_LITERAL_NUMBER = regex.lazy(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)")
# PR[8]=PR[8]-PR[8]: the register zeroed (the value's text, any comments)
_SELF_MINUS = regex.lazy(r"PR\[[ \t]*([0-9]+)[ \t]*(?::[^\]\n]*)?\][ \t]*-[ \t]*"
                         r"PR\[[ \t]*([0-9]+)[ \t]*(?::[^\]\n]*)?\][ \t]*;[ \t\f\r]*\Z")
_FRAME_HEAD = regex.lazy(r"U(?:FRAME|TOOL)[ \t]*\[")
_DEFAULT_GROUP = regex.lazy(r"DEFAULT_GROUP[ \t]*=[ \t]*([^;\n]*)")
ZERO = Number(Span(0, 0), "0", 0.0)     # a component LPOS-LPOS made 0: written nowhere


def is_program(text: str) -> bool:
    head = text.lstrip("\ufeff \t\f\r\n")
    return head.startswith("/PROG") or _SECTION_LINE.search(text) is not None


# -- parsing -----------------------------------------------------------------------
def _parser():
    from .grammar import parser
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
            _parser().recognise(text, "file")
        except Rejected:
            return _whole(doc, text, lark_first=True)
    return _interpret(doc, _parse(doc, _without_positions(text)))


def _without_positions(text: str) -> str:
    """``text`` with the lines between /POS and /END blanked (same length)."""
    pos = _POS_LINE.search(text)
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
    doc = cf.document
    regs: dict[tuple[int, int], _Register] = {}
    seen: dict[str, int] = {}
    for line in mn.children[1:]:
        if not isinstance(line, Tree):
            continue
        stmt = line.children[1] if len(line.children) > 1 else None
        if isinstance(stmt, Tree) and stmt.data == "pr_set":
            _pr_set(cf, stmt, regs, group)
        elif isinstance(stmt, Tree) and stmt.data == "frame_set":
            fr = _frame_set(cf, stmt, regs, group)
            key = fr.name.upper()
            if key in seen:
                cf.lint(stmt.children[0].start_pos, "duplicate-frame",
                        f"{fr.name} is set twice (lines {seen[key]} and {fr.line})")
            else:
                seen[key] = fr.line
            cf.frames.append(fr)
        elif stmt is not None and _FRAME_HEAD.match(stmt.value):
            cf.lint(stmt.start_pos, "unread-frame-set",
                    f"a frame assignment ucsio does not read: {stmt.value[:40]!r}")


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
    reg.values[component] = _literal(value) if value.type == "LITERAL" else None


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


def _literal(tok) -> Number:
    """The number inside a LITERAL token ((-1100.3), ((-29)), 770.299): its
    span without the parentheses, the sign included."""
    m = _LITERAL_NUMBER.search(tok.value)
    start = tok.start_pos + m.start()
    return Number(Span(start, start + len(m.group())), m.group(), float(m.group()))


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
    taught in, ``config`` ('N U T, 0, 0, 0', None for joints), ``values``
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
        from ..geometry.frames import Pose
        return Pose.from_wpr(*(self.values[k.upper()].value for k in AXES))


class Point(Value):
    """A position of /POS: ``P[12]`` with its comment and its groups
    ({group number: PointGroup}); ``at`` the offset of its ``P``."""

    __slots__ = ("number", "comment", "line", "groups", "at")

    def __init__(self, number, comment, line, groups, at=None):
        self.number, self.comment, self.line, self.groups = number, comment, line, groups
        self.at = at

    @property
    def name(self) -> str:
        return f"P[{self.number}]"


def positions(doc: Document) -> list[Point]:
    """The taught points of a program's /POS section, in order (the tree of
    every byte: a syntax error anywhere is file:line:col)."""
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
                comment = c.value[1:].strip()[1:-1]
        number = int(ch[1].value) if len(ch[1].value) < 10 else -1
        out.append(Point(number, comment, doc.line_of(ch[0].start_pos), groups,
                         ch[0].start_pos))
    return out


def _point_group(doc: Document, node: Tree) -> PointGroup:
    ch = node.children
    gp, uf, ut = ch[0], ch[1], ch[2]
    config = None
    values, units = {}, {}
    for c in ch[3:]:
        if c.data == "config":
            config = c.children[0].value[1:-1]
            continue
        axis, value, unit = c.children
        key = axis.value.upper()
        values[key] = (None if value.type == "STARS" else
                       Number(Span(value.start_pos, value.end_pos), value.value, float(value.value)))
        units[key] = unit.value
    group, uf_n, ut_n = (doc.integer(t.value[2:] if t is gp else t.value, t.start_pos, what)
                         for t, what in ((gp, "group"), (uf, "user frame"), (ut, "tool frame")))
    return PointGroup(group, uf_n, ut_n, config, values, units,
                      doc.line_of(gp.start_pos), gp.start_pos, uf.start_pos, ut.start_pos)
