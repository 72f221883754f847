"""The grammars' parsers at run time: Lark's LALR tables, driven by a small loop.

Lark compiles grammars/*.lark: its LALR analysis gives the parse table, its
contextual lexer a regular expression per parser state, and its tree
builder the shape of each rule's node (which tokens are kept, which
``_rule`` children are spliced in, which ``?rule`` nodes stand for their
only child). ``tables_from_lark`` copies exactly that into plain data, which
the wheel ships (ucsio.parsing.grammar builds and caches it in a source
checkout); this module runs it without importing Lark (a command that reads
one file starts in a blink), two ways:

- ``parse``: tokens and a tree shaped as Lark shapes it (Tree.data,
  .children; Token, a str with .type, .value, .start_pos, .end_pos);
- ``recognise`` (``check``): the same moves keeping only the state stack, no
  token or node made; a literal robtarget/E6POS value can be fed as one
  NUMBER (``shortcuts``, see ucsio.vendors.abb.rapid and ucsio.vendors.kuka.krl).

Either says only *whether* a text is in the language: on rejection the
caller asks Lark itself for the positioned error (ucsio.parsing.grammar), so
messages stay Lark's. tests/test_lalr.py checks that trees, acceptance and
rejection are Lark's, on the corpus and on generated and mutated files.
"""
from __future__ import annotations

import gc

from . import regex

FORMAT = 2          # bump when the shape of the tables changes (the disk cache keys on it)


class Rejected(Exception):
    """The text is not in the language (or a token needs a closer look)."""

    def __init__(self, pos: int):
        super().__init__(pos)
        self.pos = pos


class Token(str):
    """A token: its text (the str), terminal name, and offsets in the text parsed."""

    def __new__(cls, type_: str, value: str, start_pos: int, end_pos: int):
        self = str.__new__(cls, value)
        self.type = type_
        self.value = value
        self.start_pos = start_pos
        self.end_pos = end_pos
        return self

    def __reduce__(self):
        return Token, (self.type, self.value, self.start_pos, self.end_pos)

    def __repr__(self) -> str:
        return f"Token({self.type!r}, {self.value!r})"


class Tree:
    """A rule's node: ``data`` the rule (or alias) name, ``children`` the
    kept tokens and subtrees."""

    __slots__ = ("data", "children")

    def __init__(self, data: str, children: list):
        self.data = data
        self.children = children

    def __repr__(self) -> str:
        return f"Tree({self.data!r}, {self.children!r})"

    def iter_subtrees(self):
        """Every node of the tree (this one too); no recursion, any depth."""
        stack = [self]
        while stack:
            node = stack.pop()
            yield node
            stack.extend(c for c in node.children if isinstance(c, Tree))

    def scan_values(self, pred):
        """The tokens below this node, left to right, for which ``pred`` holds."""
        stack = [self]
        while stack:
            node = stack.pop()
            if isinstance(node, Tree):
                stack.extend(reversed(node.children))
            elif pred(node):
                yield node


# -- the tables, from Lark (ucsio.parsing.grammar calls this when its cache is cold) -----------
def tables_from_lark(lark) -> dict:
    """Plain data (dicts, lists, strings, ints: marshal-able) with everything
    a Parser needs, read from a Lark object built with parser="lalr",
    lexer="contextual", maybe_placeholders=False."""
    from lark.parse_tree_builder import _should_expand
    from lark.parsers.lalr_analysis import Shift

    frontend = lark.parser
    table = frontend.parser._parse_table
    rule_index: dict = {}
    states = []
    for state in range(len(table.states)):
        row = {}
        for sym, (action, arg) in table.states[state].items():
            row[sym] = arg if action is Shift else ~rule_index.setdefault(arg, len(rule_index))
        states.append(row)
    rules = [None] * len(rule_index)
    for rule, i in rule_index.items():
        opts = rule.options
        keep = [(k, _should_expand(sym)) for k, sym in enumerate(rule.expansion)
                if opts.keep_all_tokens or not (sym.is_term and sym.filter_out)]
        plain = len(keep) == len(rule.expansion) and not any(x for _, x in keep)
        rules[i] = (len(rule.expansion), rule.origin.name,
                    rule.alias or opts.template_source or rule.origin.name,
                    bool(opts.expand1 and not rule.alias),
                    None if plain else [[k, x] for k, x in keep])
    lexers: list = []
    lexer_of: list = []
    seen: dict[int, int] = {}
    for state in range(len(table.states)):
        lexer = frontend.lexer.lexers[state]
        if id(lexer) not in seen:
            seen[id(lexer)] = len(lexers)
            lexers.append(_lexer_spec(lexer))
        lexer_of.append(seen[id(lexer)])
    return {"format": FORMAT, "states": states, "rules": rules, "lexers": lexers,
            "root": _lexer_spec(frontend.lexer.root_lexer),
            "lexer_of": lexer_of, "start": dict(table.start_states),
            "end": dict(table.end_states),
            "terminals": {t.name: t.pattern.to_regexp() for t in lark.terminals}}


def _lexer_spec(lexer) -> list:
    """One of Lark's lexers as data: its regular expression (one named group
    per terminal, in Lark's priority order), flags, ignored terminals, the
    keyword retyping of its terminals ({terminal: [(regex, flags)]}, Lark's
    UnlessCallback), and what it can produce ({terminal: [the terminal and
    the keywords it is retyped to]})."""
    scanner = lexer.scanner             # built on first use
    if len(scanner._mres) != 1:         # pragma: no cover - over 100 terminals in one state
        raise ValueError("a lexer state needs more than one regular expression")
    keywords = {t: [(s.pattern, s.flags) for s in cb.scanner._mres]
                for t, cb in lexer.callback.items()}
    produces = {t.name: [t.name] for t in scanner.terminals}
    for t, cb in lexer.callback.items():
        produces.setdefault(t, [t]).extend(sorted(k.name for k in cb.scanner.terminals))
    return [scanner._mres[0].pattern, scanner._mres[0].flags, sorted(lexer.ignore_types),
            keywords, produces]


# -- the run-time parser ------------------------------------------------------------
class Parser:
    """One grammar's tables, for any of its start symbols."""

    def __init__(self, tables: dict):
        if tables.get("format") != FORMAT:
            raise ValueError("tables of another format")
        self.actions: list[dict[str, int]] = tables["states"]
        self.rules = [(size, origin) for size, origin, *_ in tables["rules"]]
        self.builders = [_builder(name, expand1, keep)
                         for _, _, name, expand1, keep in tables["rules"]]
        self._lexer_specs = tables["lexers"]
        self._lexer_of = tables["lexer_of"]
        self._compiled: list = [None] * len(self._lexer_specs)
        # lexers[state]: (match, ignored terminals, keyword retyping), filled
        # the first time the state lexes without the root lexer (below)
        self.lexers: list = [None] * len(self.actions)
        # The root lexer, every terminal in one regular expression, lexes
        # first in every state; where what it reads is not what the state's
        # own lexer would read (a terminal the state does not take, a keyword
        # it does not know), that lexer reads again. Each state's lexer is a
        # regular expression of its own: compiling one is 0.3-1.5 ms of pure
        # Python, and a short file visits a dozen of them, where the root
        # lexer is compiled once. The two agree: Lark orders every lexer's
        # terminals by one key, so the first of the root's terminals to
        # match, if the state has it, is the first of the state's too.
        self._root_spec = tables["root"]
        self._root = None
        specs = [(frozenset(ignore), {t: frozenset(kinds) for t, kinds in produces.items()})
                 for _, _, ignore, _, produces in self._lexer_specs]
        # per state: (ignored terminals, {terminal: what the state reads it as})
        self.reads = [specs[i] for i in self._lexer_of]
        self.start_states = tables["start"]
        self.end_states = tables["end"]
        self.terminals: dict[str, str] = tables["terminals"]

    def _lexer(self, state: int):
        i = self._lexer_of[state]
        got = self._compiled[i]
        if got is None:
            pattern, flags, ignore, keywords, _ = self._lexer_specs[i]
            kw = {t: _fullmatcher(specs) for t, specs in keywords.items()}
            got = self._compiled[i] = (regex.compile(pattern, flags).match, frozenset(ignore), kw)
        self.lexers[state] = got
        return got

    def _root_lexer(self):
        if self._root is None:
            pattern, flags, _, keywords, _ = self._root_spec
            self._root = (regex.compile(pattern, flags).match,
                          {t: _fullmatcher(specs) for t, specs in keywords.items()})
        return self._root

    def _state_lex(self, text: str, pos: int, state: int):
        """(terminal, match) of the token at ``pos`` as ``state``'s own
        lexer reads it (where the root lexer read something else); None
        where nothing matches."""
        match, _, keywords = self.lexers[state] or self._lexer(state)
        m = match(text, pos)
        if m is None:
            return None
        kind = m.lastgroup
        if keywords and kind in keywords:
            kind = keywords[kind](m.group()) or kind
        return kind, m

    def parse(self, text: str, start: str) -> Tree:
        """The tree of ``text``, as Lark shapes it; Rejected(pos) if ``text``
        is not in the language."""
        with paused_gc():
            return self._parse(text, start)

    def _parse(self, text: str, start: str) -> Tree:
        actions, rules, builders, reads = self.actions, self.rules, self.builders, self.reads
        root_match, root_keywords = self._root or self._root_lexer()
        state = self.start_states[start]
        states = [state]
        values: list = []
        push, keep = states.append, values.append
        pos = 0
        n = len(text)
        kind = None
        while True:
            if pos < n:
                m = root_match(text, pos)
                if m is None:
                    raise Rejected(pos)         # no terminal at all matches here
                kind = alt = m.lastgroup
                if alt in root_keywords:
                    kind = root_keywords[alt](m.group()) or alt
                ignore, reads_as = reads[state]
                if kind not in reads_as.get(alt, ()):
                    got = self._state_lex(text, pos, state)
                    if got is None:
                        raise Rejected(pos)
                    kind, m = got
                end = m.end()
                if kind in ignore:
                    pos = end
                    continue
                token = Token(kind, m.group(), pos, end)
                pos = end
            else:
                kind = "$END"
                token = None
            row = actions[state]
            while True:
                act = row.get(kind)
                if act is None:
                    raise Rejected(token.start_pos if token is not None else n)
                if act >= 0:
                    if token is None:
                        raise Rejected(n)
                    state = act
                    push(act)
                    keep(token)
                    break
                size, origin = rules[~act]
                if size:
                    children = values[-size:]
                    del states[-size:]
                    del values[-size:]
                else:
                    children = []
                node = builders[~act](children)
                state = actions[states[-1]][origin]
                if token is None and state == self.end_states[start]:
                    return node
                push(state)
                keep(node)
                row = actions[state]

    def recognise(self, text: str, start: str, shortcuts: dict | None = None,
                  suspects: dict | None = None) -> None:
        """Return if ``text`` is in the language, else raise Rejected: the
        moves of ``parse`` with only the state stack kept.

        ``shortcuts``: {terminal: (compiled regex, terminal fed instead)},
        tried where the lexer reads ``terminal`` and the parser can take it.
        ``suspects``: {terminal: predicate(text)}: a token for which the
        predicate holds rejects (the caller's full parse looks at it)."""
        actions, rules, reads = self.actions, self.rules, self.reads
        root_match, root_keywords = self._root or self._root_lexer()
        shortcuts, suspects = shortcuts or {}, suspects or {}
        state = self.start_states[start]
        stack = [state]
        push = stack.append
        pos = 0
        n = len(text)
        while pos < n:
            m = root_match(text, pos)
            if m is None:
                raise Rejected(pos)
            kind = alt = m.lastgroup
            if alt in root_keywords:
                kind = root_keywords[alt](m.group()) or alt
            ignore, reads_as = reads[state]
            if kind not in reads_as.get(alt, ()):
                got = self._state_lex(text, pos, state)
                if got is None:
                    raise Rejected(pos)
                kind, m = got
            end = m.end()
            if kind in ignore:
                pos = end
                continue
            row = actions[state]
            if kind in shortcuts and kind in row:
                pattern, instead = shortcuts[kind]
                whole = pattern.match(text, pos)
                if whole is not None:
                    kind, end = instead, whole.end()
            elif kind in suspects and suspects[kind](m.group()):
                raise Rejected(pos)
            token_pos, pos = pos, end
            while True:
                act = row.get(kind)
                if act is None:
                    raise Rejected(token_pos)
                if act >= 0:
                    state = act
                    push(act)
                    break
                size, origin = rules[~act]
                if size:
                    del stack[-size:]
                state = actions[stack[-1]][origin]
                push(state)
                row = actions[state]
        end_state = self.end_states[start]
        while True:     # end of input: reduce until the start symbol is complete
            act = actions[state].get("$END")
            if act is None or act >= 0:
                raise Rejected(n)
            size, origin = rules[~act]
            if size:
                del stack[-size:]
            state = actions[stack[-1]][origin]
            push(state)
            if state == end_state:
                return


class paused_gc:
    """Python's cyclic garbage collector off while a tree is built: the
    tree has no cycles, and the collector's passes over a growing heap of
    nodes made a module of 20,000 robtargets several times slower."""

    def __enter__(self):
        self.was = gc.isenabled()
        gc.disable()

    def __exit__(self, *exc):
        if self.was:
            gc.enable()


def _fullmatcher(specs):
    """Lark's keyword callback: a NAME spelt as a keyword becomes it."""
    compiled = [regex.compile(p, f) for p, f in specs]

    def retype(value: str):
        for c in compiled:
            m = c.fullmatch(value)
            if m:
                return m.lastgroup
        return None
    return retype


def _builder(name: str, expand1: bool, keep):
    """A rule's node builder, as Lark's tree builder shapes it: the kept
    children (anonymous tokens dropped, ``_rule`` nodes spliced in), and a
    ``?rule`` with one child stands for that child."""
    if keep is None:
        if expand1:
            return lambda children: children[0] if len(children) == 1 else Tree(name, children)
        return lambda children: Tree(name, children)
    keep = [(k, bool(x)) for k, x in keep]

    def build(children):
        out: list = []
        for k, splice in keep:
            if splice:
                if out:
                    out += children[k].children
                else:
                    # a left-recursive list (_item* ...) grows by one child per
                    # reduction: take its list over, never copy it (as Lark's
                    # tree builder does), or a data list of n lines costs n²
                    out = children[k].children
            else:
                out.append(children[k])
        if expand1 and len(out) == 1:
            return out[0]
        return Tree(name, out)
    return build


# -- shortcut patterns ---------------------------------------------------------------
def atomic(pattern: str) -> str:
    """A token's pattern as an atomic group: matched as the lexer matches it,
    never given back to let a longer pattern around it succeed. Its groups
    are made non-capturing: nothing reads them, CPython 3.11's re
    reports "The span of capturing group is wrong" for capturing groups
    inside possessive repeats, and ucsio.parsing.regex rewrites only
    patterns whose groups are named."""
    return f"(?>{noncapturing(pattern)})"


def noncapturing(pattern: str) -> str:
    """``pattern`` with every capturing group ``(`` turned into ``(?:``."""
    out = []
    escaped = in_class = False
    for i, c in enumerate(pattern):
        out.append(c)
        if escaped:
            escaped = False
        elif c == "\\":
            escaped = True
        elif in_class:
            in_class = c != "]" or pattern[i - 1] == "["
        elif c == "[":
            in_class = True
        elif c == "(" and not pattern.startswith("?", i + 1):
            out.append("?:")
    return "".join(out)


def bracketed(open_: str, close: str, item: str, gap: str) -> str:
    """``open [item (, item)*] close`` with ``gap`` (ignored text) between
    tokens; possessive, so a literal that does not close fails at once."""
    return f"{open_}{gap}(?:(?:{item})(?:{gap},{gap}(?:{item}))*+)?+{gap}{close}"
