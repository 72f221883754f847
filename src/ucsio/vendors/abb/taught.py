"""ABB: the robtargets that instructions move to in a work object.

For every module of the file's folder (.mod .modx .sys .sysx .prg), the
outline scanner (ucsio.vendors.abb.rapid.outline with ``routines``) gives the routines
and the runs of declarations. A regex cuts those into statements at the
semicolons (strings and comments skipped, as the grammar's lexer does).

- A statement that names a work object (``\\WObj:=``) is parsed with the
  grammar's ``statements`` start symbol, all of a module's in one Lark call:
  only the instruction and its arguments matter.
- robtarget declarations (module level, and VAR/CONST inside routines) are
  parsed as data declarations, as the fast path parses frames.

An instruction's positional arguments that are robtargets are its points:
a robtarget by name (routine-local first, then the module, then a global
one of another module), an array element (``p{3}``), a literal target, and
``Offs(p, dx, dy, dz)`` / ``RelTool(p, dx, dy, dz)`` with literal offsets
(the offset point itself). Each point is counted once, at the line its
value is written. A target the folder does not declare (a routine
parameter, another task's data) is a warning, never a silent zero.
"""
from __future__ import annotations

import os
import re
from pathlib import Path

from ..common.taught import Found, TaughtPoint, files_around, is_same_file, same_folder
from ...errors import UcsioError
from ...geometry.frames import Frame, Number
from ...geometry.rotations import quat_to_matrix, matvec
from ...parsing import regex
from . import rapid
from .. import BY_NAME
from ...parsing.document import Document, Span
from ...parsing.lalr import Rejected, Token, Tree
from ...parsing.model import ControllerFile

# One statement: everything up to the next ';' outside strings and comments.
_STATEMENT = regex.lazy(r'(?:[^;"!]++|"[^"\r\n]*+"|![^\r\n]*+)*+;')
_STRINGS_COMMENTS = regex.lazy(r'"[^"\r\n]*+"|![^\r\n]*+')
_WOBJ = regex.lazy(r"\\\s*WObj\s*:=", re.I)
_WOBJ_NAMED = regex.lazy(r"\\\s*WObj\s*:=\s*([A-Za-z_]\w*(?:\s*\{[^}]*\})?)", re.I)
_GAP = r"(?:\s|![^\r\n]*+)*+"
_ROBTARGET_DECL = regex.lazy(_GAP + r"(?:(?:LOCAL|TASK)" + _GAP + r")?(?:PERS|CONST|VAR)"
                             + _GAP + r"robtarget\b" + _GAP + r"(?P<name>\w+)", re.I)
# a routine's head: [LOCAL] PROC name(params) | TRAP name | FUNC type name(params)
_LEAD = regex.lazy(_GAP)
_ROUTINE_HEAD = regex.lazy(_GAP + r"(?:LOCAL" + _GAP + r")?(?:PROC|TRAP|FUNC" + _GAP + r"\w+)"
                           + _GAP + r"\w+" + _GAP + r"(?:\([^)]*\))?", re.I)
_OFFSET_FUNCS = {"offs", "reltool"}
# A robtarget written out in the controller's own plain form (no comment or
# expression inside): a strict subset of what the grammar accepts, read
# without Lark, as a path module's thousands of targets need. Anything else
# goes through the grammar.
_S = r"[ \t\f\r\n]*"


def _num(k: int) -> str:
    """The k-th number of a literal target: its sign and its digits."""
    return (rf"(?P<sign{k}>[-+]?)" + _S
            + rf"(?P<digits{k}>(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)(?![\w.])")


_BARE = r"[-+]?" + _S + r"(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?(?![\w.])"


def _nums(first: int, k: int) -> str:
    """``[n, n, ...]``: k numbers, named from ``first`` on."""
    return r"\[" + _S + (_S + "," + _S).join(_num(i) for i in range(first, first + k)) + _S + r"\]"


_ANY_NUMS = r"\[" + _S + _BARE + r"(?:" + _S + "," + _S + _BARE + r")*" + _S + r"\]"
_LITERAL_TARGET = regex.lazy(
    _GAP + r"(?:(?P<scope>LOCAL|TASK)[ \t\f\r\n]+)?(?:PERS|CONST|VAR)[ \t\f\r\n]+robtarget[ \t\f\r\n]+"
    r"(?P<name>[A-Za-z_][A-Za-z0-9_]*)" + _S + ":=" + _S + r"\[" + _S + _nums(0, 3) + _S + ","
    + _S + _nums(3, 4) + _S + "," + _S + _ANY_NUMS + _S + "," + _S + _ANY_NUMS + _S + r"\]" + _S + r";\Z",
    re.I)
# instructions whose first argument is the cartesian target (not MoveAbsJ,
# MoveExtJ: joint targets; not SearchL: a signal comes first)
_CARTESIAN_MOVE = regex.lazy(r"(?:Move(?!AbsJ|ExtJ)|Trigg|Arc)\w*\Z", re.I)


def _modules(frame: Frame) -> list:
    """The modules of the file's folder (on disk, or in the same archive)."""
    return files_around(frame.file, same_folder, BY_NAME["abb"].suffixes)


def _wobj_name(frame: Frame) -> str:
    name = frame.name
    if frame.info.get("component") == "oframe":
        name = name[: -len(".oframe")]
    return name


class _LiteralTarget:
    """A robtarget declaration read by ``_LITERAL_TARGET``: what the rest of
    this module reads of a rapid.Decl (name, scope, start, dims, value)."""

    dims = None

    def __init__(self, m: re.Match, doc: Document):
        self.scope = m.group("scope").upper() if m.group("scope") else None
        self.name = m.group("name")
        nums = []
        for k in range(7):
            sign, digits = m.group(f"sign{k}"), m.group(f"digits{k}")
            start = m.start(f"sign{k}") if sign else m.start(f"digits{k}")
            end = m.end(f"digits{k}")
            value = float(digits) * (-1.0 if sign == "-" else 1.0)
            nums.append(Number(Span(start, end), doc.text[start:end], value))
        self.start = nums[0].span.start
        self.value = [nums[:3], nums[3:], [], []]


class _Module:
    """One module's robtarget declarations and \\WObj statements."""

    def __init__(self, doc: Document):
        self.doc = doc
        self.decls: list[rapid.Decl] = []
        self.routines: list[Span] = []
        self.statements = []            # (tree or None where unreadable, span)
        self.brackets: list[rapid.Region] = []              # MODULE ..., ENDMODULE
        self.targets: list[tuple[str, rapid.Region]] = []   # robtarget declarations, by name
        self.parsed: set[str] = set()   # names whose declarations are in ``decls``
        self.name = ""                  # MODULE name

    def parse_targets(self, names: set[str]) -> None:
        """Parse the robtarget declarations called one of ``names`` (casefolded),
        all in one Lark call, as the fast path parses frame declarations: a
        path module's thousand targets cost nothing unless a move uses them.
        Names parsed before (another frame of the same folder) are not again."""
        new = names - self.parsed
        self.parsed |= new
        keep = []
        text = self.doc.text
        for name, r in self.targets:
            if name not in new:
                continue
            m = _LITERAL_TARGET.match(text, r.span.start, r.span.end)
            if m is not None:
                self.decls.append(_LiteralTarget(m, self.doc))
            else:
                keep.append(r)
        if not keep:
            return
        regions = sorted(self.brackets + keep, key=lambda r: r.span.start)
        compact = rapid.Compact(self.doc, regions)
        tree = rapid.parse_tree(self.doc, compact.text, compact)
        compact.remap(tree)
        self.decls += [d for d in rapid.declarations(self.doc, tree)
                       if d.type.casefold() == "robtarget"]


def _read_module(doc: Document) -> _Module:
    mod = _Module(doc)
    text = doc.text
    regions = rapid.outline(doc, routines=True)
    moves = []              # spans of statements that name a work object
    for r in regions:
        if r.kind in ("module", "endmodule"):
            mod.brackets.append(r)
            head = _MODULE_NAME.match(text, r.span.start, r.span.end)
            if r.kind == "module" and head:
                mod.name = head.group(1)
            continue
        if r.kind not in ("decls", "routine"):
            continue
        pos, end = r.span.start, r.span.end
        if r.kind == "routine":
            mod.routines.append(r.span)
            head = _ROUTINE_HEAD.match(text, pos, end)
            if head:
                pos = head.end()
        # statements follow one another up to the last ';' (the recognised
        # routine's strings and comments are closed, so none fails midway);
        # match, not finditer: a search would retry every position of the
        # tail after the last ';', each up to the end (quadratic)
        while True:
            m = _STATEMENT.match(text, pos, end)
            if m is None:
                break
            pos = m.end()
            decl = _ROBTARGET_DECL.match(text, m.start(), m.end())
            if decl:
                mod.targets.append((decl.group("name").casefold(),
                                    rapid.Region("decl", Span(m.start(), m.end()))))
            elif r.kind == "routine":
                bare = _STRINGS_COMMENTS.sub(lambda x: " " * len(x.group()), m.group())
                if _WOBJ.search(bare):
                    start = _LEAD.match(text, m.start(), m.end()).end()   # at its first word
                    moves.append(rapid.Region("statement", Span(start, m.end())))
    if moves:
        mod.statements = _parse_statements(doc, moves)
    return mod


def _statement_parser():
    from ...parsing.grammar import parser
    return parser("rapid", ("statements",))


def _parse_statements(doc: Document, regions) -> list:
    """Every statement's tree, with positions in the file: one Lark call for
    all of them; where that fails, one call each, so the error names the
    statement."""
    compact = rapid.Compact(doc, regions)
    try:
        tree = _statement_parser().parse(compact.text, "statements")
    except Rejected:
        tree = None
    if tree is not None:
        compact.remap(tree)
        return [(st, r.span) for st, r in zip(tree.children, regions)]
    out = []
    for r in regions:
        one = rapid.Compact(doc, [r])
        try:
            t = _statement_parser().parse(one.text, "statements")
        except Rejected:
            out.append((None, r.span))
            continue
        one.remap(t)
        out.append((t.children[0], r.span))
    return out


def _text(node) -> str:
    """A name, element or component as written, without spaces: 'p10',
    'wobjs{2}', 'targets{i,2}', 'rec.p' (the tree drops the brackets)."""
    if isinstance(node, Token):
        return str(node)
    if node.data == "element":
        return _text(node.children[0]) + "{" + ",".join(_text(c) for c in node.children[1:]) + "}"
    if node.data == "component":
        return _text(node.children[0]) + "." + _text(node.children[1])
    return "".join(str(t) for t in node.scan_values(lambda v: isinstance(v, Token)))


class _Index:
    """Robtarget declarations by name: routine-local, module, global."""

    def __init__(self, modules: list[_Module]):
        self.local: dict[tuple[int, str], rapid.Decl] = {}   # (routine start, name)
        self.module: dict[tuple[int, str], rapid.Decl] = {}  # (module id, name)
        self.glob: dict[str, tuple[_Module, rapid.Decl]] = {}
        for mod in modules:
            for d in mod.decls:
                key = d.name.casefold()
                routine = next((s for s in mod.routines if s.start <= d.start < s.end), None)
                if routine is not None:
                    self.local.setdefault((id(mod), routine.start, key), d)
                    continue
                self.module.setdefault((id(mod), key), d)
                if d.scope != "LOCAL":
                    self.glob.setdefault(key, (mod, d))

    def lookup(self, mod: _Module, at: int, name: str):
        key = name.casefold()
        routine = next((s for s in mod.routines if s.start <= at < s.end), None)
        if routine is not None and (id(mod), routine.start, key) in self.local:
            return mod, self.local[(id(mod), routine.start, key)]
        if (id(mod), key) in self.module:
            return mod, self.module[(id(mod), key)]
        return self.glob.get(key, (None, None))


def _target(value) -> tuple[tuple[float, float, float], tuple] | None:
    """(trans, rot) of a robtarget value [[x,y,z],[q1..q4],conf,extax]."""
    if not (isinstance(value, list) and len(value) == 4):
        return None
    t, q = value[0], value[1]
    if not (isinstance(t, list) and len(t) == 3 and all(isinstance(c, Number) for c in t)):
        return None
    quat = None
    if isinstance(q, list) and len(q) == 4 and all(isinstance(c, Number) for c in q):
        quat = tuple(c.value for c in q)
    return tuple(c.value for c in t), quat


_MODULE_NAME = regex.lazy(r"\s*MODULE\s+(\w+)", re.IGNORECASE)


def _drop_copies(modules: list, frame: Frame, found: Found) -> None:
    """A module of the folder that has the frame's own MODULE name is a copy
    of its file (a patched copy, a backup): the controller never loads both,
    so its points are not counted twice."""
    own = str(frame.info.get("module") or "").casefold()
    copies = [m for m in modules if own and m.name.casefold() == own
              and not _same_path(m.doc.path, frame.file)]
    for m in copies:
        modules.remove(m)
        found.warnings.append(f"{m.doc.path} declares MODULE {m.name} too: a copy of "
                              f"{frame.file} (a patched copy or a backup), not a module loaded "
                              "beside it; its points are not counted (move the copy out of this "
                              "folder)")


def _same_path(a: str, b: str) -> bool:
    return os.path.normcase(os.path.abspath(a)) == os.path.normcase(os.path.abspath(b))


def _module(src, cf: ControllerFile, cache: dict | None) -> _Module:
    """A module of the folder, read once per run where ``cache`` is given."""
    key = ("abb", src.name)
    if cache is not None and key in cache:
        got = cache[key]
        if isinstance(got, UcsioError):
            raise got
        return got
    try:
        got = _read_module(cf.document if is_same_file(src, cf) else src.document())
    except UcsioError as exc:
        if cache is not None:
            cache[key] = exc
        raise
    if cache is not None:
        cache[key] = got
    return got


def find(cf: ControllerFile, frame: Frame, cache: dict | None = None) -> Found:
    found = Found()
    if frame.type != "wobjdata":
        found.warnings.append(f"{frame.name} is a {frame.type}, not a work object: no taught "
                              "points are stored in it")
        return found
    wobj = _wobj_name(frame).casefold()
    modules = []
    for src in _modules(frame) or [None]:
        try:
            modules.append(_read_module(cf.document) if src is None else _module(src, cf, cache))
        except UcsioError as exc:
            found.warnings.append(f"could not read {src.name if src else cf.path} ({exc}); "
                                  "its points are not counted")
    _drop_copies(modules, frame, found)
    wanted = {str(tok).casefold() for mod in modules for tree, _ in mod.statements
              if tree is not None for tok in _names_moved_to(tree, wobj)}
    for mod in list(modules):
        try:
            mod.parse_targets(wanted)
        except UcsioError as exc:
            found.warnings.append(f"could not read {mod.doc.path} ({exc}); its points are "
                                  "not counted")
            modules.remove(mod)
    index = _Index(modules)
    seen: set = set()
    for mod in modules:
        doc = mod.doc
        for tree, span in mod.statements:
            if tree is None:
                _unreadable(doc, span, wobj, found)
                continue
            _points_of(tree, mod, index, wobj, found, seen)
    return found


def chain(cf: ControllerFile, frame: Frame, measured) -> tuple[list, list]:
    """The poses a robtarget goes through to world, simulated and measured,
    innermost last: uframe * oframe (robtargets are in the object frame). A
    measured user frame replaces the uframe, a measured object frame (its
    pose in its user frame: ``measured``) the oframe."""
    wobj = _wobj_name(frame)
    uframe, oframe = cf.frame(wobj), cf.frame(wobj + ".oframe")
    for part in (uframe, oframe):
        if part.pose is None:
            raise UcsioError(f"{part.name}: the file gives no literal value; the taught points "
                             "cannot be placed in world", file=part.file, line=part.line)
    if frame is oframe:
        return [uframe.pose, oframe.pose], [uframe.pose, measured]
    return [uframe.pose, oframe.pose], [measured, oframe.pose]


def in_frame(cf: ControllerFile, frame: Frame, found: Found) -> list[tuple[float, float, float]]:
    """Each robtarget's position in ``frame``'s coordinates: a robtarget is
    in the object frame, so a user frame's points go through its object
    frame; an object frame's are as written."""
    if frame.info.get("component") == "oframe":
        return [p.xyz for p in found.points]
    oframe = cf.frame(frame.name + ".oframe")
    if oframe.pose is None:
        raise UcsioError(f"{oframe.name}: the file gives no literal value; the taught points "
                         "cannot be placed in the user frame", file=oframe.file, line=oframe.line)
    return [oframe.pose.apply(p.xyz) for p in found.points]


_ASSIGNMENT = regex.lazy(r"\s*[A-Za-z_][\w.{}, ]*:=")


def _unreadable(doc: Document, span: Span, wobj: str, found: Found) -> None:
    r"""A statement the grammar does not read: a warning where it may move to
    the work object (an assignment such as p := CRobT(\WObj:=w) reads a
    position, it does not move)."""
    bare = _STRINGS_COMMENTS.sub(lambda x: " " * len(x.group()), doc.text[span.start:span.end])
    head = _ROUTINE_HEAD.match(bare)
    names = {re.sub(r"\s", "", m.group(1)).casefold() for m in _WOBJ_NAMED.finditer(bare)}
    if wobj not in names or _ASSIGNMENT.match(bare, head.end() if head else 0):
        return
    start = span.start + len(bare) - len(bare.lstrip())
    line, col = doc.line_col(start)
    found.warnings.append(f"{doc.path}:{line}:{col}: could not read this instruction's "
                          "arguments; its points are not counted")


def _moving_in(statement, wobj: str):
    r"""The instruction of a statement that moves in work object ``wobj``
    (casefolded), else None (an assignment such as p := CRobT(\WObj:=w)
    reads a position, it does not move)."""
    instr = next((c for c in statement.children if isinstance(c, Tree)
                  and c.data == "instruction"), None)
    if instr is None:
        return None
    for o in instr.children:
        if isinstance(o, Tree) and o.data == "opt_arg" and len(o.children) > 1 \
                and str(o.children[0]).casefold() == "wobj":
            return instr if _text(o.children[1]).casefold() == wobj else None
    return None


def _names_moved_to(statement, wobj: str) -> list:
    """Every name in the arguments of an instruction moving in ``wobj``."""
    instr = _moving_in(statement, wobj)
    if instr is None:
        return []
    return [tok for arg in instr.children if isinstance(arg, Tree) and arg.data == "instr_arg"
            for tok in arg.scan_values(lambda v: isinstance(v, Token) and v.type == "NAME")]


def _points_of(statement, mod: _Module, index: _Index, wobj: str, found: Found, seen: set):
    instr = _moving_in(statement, wobj)
    if instr is None:
        return
    args = [c for c in instr.children if isinstance(c, Tree) and c.data == "instr_arg"]
    doc = mod.doc
    for k, arg in enumerate(args):
        node = arg.children[0]
        got = _resolve(node, mod, index, doc)
        if got is not None:
            key, point = got
            if key not in seen:
                seen.add(key)
                found.points.append(point)
        elif k == 0 and _CARTESIAN_MOVE.match(str(instr.children[0])):
            _not_counted(node, mod, index, found, seen)


def _not_counted(node, mod: _Module, index: _Index, found: Found, seen: set) -> None:
    """Say why the target of a cartesian move is not counted (once per name)."""
    if not (isinstance(node, Tree) and node.data in ("name", "element", "call")):
        return
    doc = mod.doc
    tok = next(node.scan_values(lambda v: isinstance(v, Token)))
    name = _text(node)
    key = ("not counted", doc.path, name.casefold())
    if key in seen:
        return
    seen.add(key)
    where = f"{doc.path}:{doc.line_of(tok.start_pos)}: {name}"
    if node.data == "call":
        found.warnings.append(f"{where}: a computed target: not counted")
        return
    base = node.children[0] if node.data == "element" else node
    _, decl = index.lookup(mod, tok.start_pos, _text(base))
    if decl is not None:
        found.warnings.append(f"{where}: the robtarget has no value in the file (set at run "
                              "time): not counted")
    else:
        found.warnings.append(f"{where}: not a robtarget declared in the modules of this "
                              "folder (a routine parameter, or another task's data): "
                              "not counted")


def _resolve(node, mod: _Module, index: _Index, doc: Document):
    """(dedup key, TaughtPoint) for an argument that is a robtarget, else None."""
    if not isinstance(node, Tree):
        return None
    kind = node.data
    if kind == "name":
        return _declared(_text(node), node.children[0].start_pos, mod, index)
    if kind == "element":
        base = node.children[0]
        if not (isinstance(base, Tree) and base.data == "name"):
            return None
        return _declared(_text(node), base.children[0].start_pos, mod, index,
                         array=_text(base))
    if kind == "aggregate":
        value = rapid._value(node)
        t = _target(value)
        if t is None:
            return None
        start = next(node.scan_values(lambda v: isinstance(v, Token))).start_pos
        line = doc.line_of(start)
        name = f"target at {Path(doc.path).name}:{line}"
        return (doc.path, start), TaughtPoint(name, doc.path, line, t[0], t[1])
    if kind == "call":
        fname = str(node.children[0]).casefold()
        if fname not in _OFFSET_FUNCS:
            return None
        args = [c for c in node.children[1:] if isinstance(c, Tree) and c.data == "arg"]
        if len(args) < 4 or any(len(a.children) != 1 for a in args[:4]):
            return None
        inner = _resolve(args[0].children[0], mod, index, doc)
        offsets = [rapid._value(a.children[0]) for a in args[1:4]]
        if inner is None or not all(isinstance(o, Number) for o in offsets):
            return inner      # the offset is computed: count the target it starts from
        (key, p), d = inner, tuple(o.value for o in offsets)
        if not any(d):
            return inner        # Offs(p, 0, 0, 0) is p
        if fname == "offs":     # in the object frame
            xyz = tuple(a + b for a, b in zip(p.xyz, d))
        else:                   # RelTool: along the target's own (tool) axes
            if p.q is None:
                return inner
            r = matvec(quat_to_matrix(p.q), d)
            xyz = tuple(a + b for a, b in zip(p.xyz, r))
        name = f"{node.children[0]}({p.name},{','.join(f'{v:g}' for v in d)})"
        return (key, fname, d), TaughtPoint(name, p.file, p.line, xyz)
    return None


def _declared(name: str, at: int, mod: _Module, index: _Index, array: str | None = None):
    owner, decl = index.lookup(mod, at, array or name)
    if decl is None:
        return None
    for ename, value in rapid._elements(decl.value, decl.dims, decl.name):
        if ename.casefold() != name.casefold().replace(" ", ""):
            continue
        t = _target(value)
        if t is None:
            return None
        start = rapid._start_of(value, decl.start)
        doc = owner.doc
        return (doc.path, start), TaughtPoint(ename, doc.path, doc.line_of(start), t[0], t[1])
    return None
