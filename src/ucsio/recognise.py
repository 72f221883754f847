"""Does a whole file belong to the grammar? Lark's own tables, driven fast.

``check`` must put every byte of a file through the grammar, but it needs no
tree of it: the frames come from the fast path, which parses only their
declarations. Lark builds a Token object per token and a tree node per rule,
which is nine tenths of its time. A Recogniser runs the same LALR table and
the same contextual lexer (Lark's per-state regular expressions, its keyword
callbacks, its ignored terminals) in a loop that keeps only the state stack,
so a file is accepted exactly when Lark would accept it.

Shortcuts: most of a controller file's bytes are literal data, a robtarget's
``[[x,y,z],[q1,q2,q3,q4],...]`` or an E6POS's ``{X 1.0,Y 2.0,...}``. Where
the grammar reads such a literal as one value whose alternatives are a
NUMBER or the literal (``atom: NUMBER | aggregate``, ``value: NUMBER |
struct``), the parser's moves after it are the same for both. A shortcut is
a regular expression, built from the grammar's own terminals, that matches
only literals made of tokens the lexer reads one way (atomic groups: no
split the lexer would not make); where it matches, the literal is fed to
the parser as one NUMBER. Anything it does not match goes token by token.
tests/test_recognise.py checks that the recogniser and Lark accept and
reject the same files, with and without shortcuts.

On rejection the caller parses with Lark for the positioned message: the
recogniser says only *whether*, never *why*.
"""
from __future__ import annotations

import re


class Rejected(Exception):
    """The text is not in the grammar (or a token needs a closer look)."""

    def __init__(self, pos: int):
        super().__init__(pos)
        self.pos = pos


class Recogniser:
    """An LALR recogniser for one start symbol of a Lark parser built with
    ``parser="lalr", lexer="contextual"``.

    ``shortcuts``: {terminal: (compiled regex, terminal fed instead)}; tried
    where the lexer reads ``terminal`` and the parser can take it.
    ``suspects``: {terminal: predicate(text)}; a token for which the
    predicate is true rejects (the caller's full parse looks at it)."""

    def __init__(self, lark, start: str, shortcuts: dict | None = None,
                 suspects: dict | None = None):
        from lark.parsers.lalr_analysis import Shift

        frontend = lark.parser
        table = frontend.parser._parse_table
        rules: dict = {}
        self.actions: dict[int, dict[str, int]] = {}
        # shift to state s -> s; reduce by rule r -> ~index(r) (negative);
        # nonterminals (gotos) share the dict: their names are lower case.
        for state, acts in table.states.items():
            row = {}
            for sym, (action, arg) in acts.items():
                if action is Shift:
                    row[sym] = arg
                else:
                    row[sym] = ~rules.setdefault(arg, len(rules))
            self.actions[state] = row
        self.rules = [None] * len(rules)
        for rule, i in rules.items():
            self.rules[i] = (len(rule.expansion), rule.origin.name)
        self.start_state = table.start_states[start]
        self.end_state = table.end_states[start]

        self.lexers: dict[int, tuple] = {}
        built: dict[int, tuple] = {}
        for state, lexer in frontend.lexer.lexers.items():
            key = id(lexer)
            if key not in built:
                scanner = lexer.scanner              # built on first use
                if len(scanner._mres) != 1:          # pragma: no cover - > 100 terminals
                    raise ValueError("a lexer state with more than one regex")
                keywords = {t: cb.scanner.fullmatch for t, cb in lexer.callback.items()}
                built[key] = (scanner._mres[0].match, frozenset(lexer.ignore_types), keywords)
            self.lexers[state] = built[key]
        self.shortcuts = shortcuts or {}
        self.suspects = suspects or {}

    def check(self, text: str) -> None:
        """Return if ``text`` is in the language, raise Rejected if not."""
        actions, rules, lexers = self.actions, self.rules, self.lexers
        shortcuts, suspects = self.shortcuts, self.suspects
        state = self.start_state
        stack = [state]
        push = stack.append
        pos = 0
        n = len(text)
        while pos < n:
            match, ignore, keywords = lexers[state]
            m = match(text, pos)
            if m is None:
                raise Rejected(pos)
            kind = m.lastgroup
            end = m.end()
            if kind in ignore:
                pos = end
                continue
            if keywords and kind in keywords:
                kind = keywords[kind](m.group()) or kind
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
        # end of input: reduce until the start symbol is complete
        while True:
            act = actions[state].get("$END")
            if act is None or act >= 0:
                raise Rejected(n)
            size, origin = rules[~act]
            if size:
                del stack[-size:]
            state = actions[stack[-1]][origin]
            push(state)
            if state == self.end_state:
                return


class LarkOnly:
    """Stands in where this Lark's internals are not what Recogniser reads
    (another major version): every file then goes to Lark's own parser,
    slower, never wrong."""

    def check(self, text: str) -> None:
        raise Rejected(0)


def build(lark, start: str, shortcuts: dict | None = None, suspects: dict | None = None):
    """A Recogniser, or LarkOnly if it cannot be built from this Lark."""
    try:
        return Recogniser(lark, start, shortcuts, suspects)
    except (AttributeError, KeyError, TypeError, ValueError, ImportError):
        return LarkOnly()


def atomic(pattern: str) -> str:
    """A token's pattern as an atomic group: matched as the lexer matches it,
    never given back to let a longer pattern around it succeed. Its groups
    are made non-capturing: nothing reads them, and CPython 3.11's re
    reports "The span of capturing group is wrong" for capturing groups
    inside possessive repeats."""
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


def terminal_pattern(lark, name: str) -> str:
    """The regular expression Lark matches terminal ``name`` with."""
    for t in lark.terminals:
        if t.name == name:
            return t.pattern.to_regexp()
    raise KeyError(name)


def bracketed(open_: str, close: str, item: str, gap: str) -> str:
    """``open [item (, item)*] close`` with ``gap`` (ignored text) between
    tokens; possessive, so a literal that does not close fails at once."""
    return f"{open_}{gap}(?:(?:{item})(?:{gap},{gap}(?:{item}))*+)?+{gap}{close}"
