"""The grammars that ship with ucsio, compiled by Lark, run by ucsio.parsing.lalr.

The grammars are data (grammars/*.lark at the top of the repository, copied
into the wheel as ucsio/grammars). Lark compiles each into LALR tables: when
the wheel is built (hatch_build.py ships them beside the grammars), or in a
source checkout once per machine (``tables`` keeps them in a disk cache);
marshal files keyed by the grammar's text. So a command that reads a file never
imports Lark. Only a syntax
error does: ``parse`` asks Lark itself for the positioned message, so what
the user reads is Lark's diagnosis of exactly the text we rejected.
"""
from __future__ import annotations

import functools
import os

from . import lalr
from .cache import cache_dir, write_cache

# pathlib and json cost a cold command 5-8 ms of imports: paths here are
# strings, and the tables are stored as marshal.


@functools.lru_cache(maxsize=None)
def grammar_dir() -> str:
    package = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))   # .../ucsio
    inside = os.path.join(package, "grammars")                               # installed wheel
    if os.path.isdir(inside):
        return inside
    return os.path.join(os.path.dirname(os.path.dirname(package)), "grammars")  # a checkout


class SyntaxFailure(Exception):
    """Text the grammar rejects; ``error`` is Lark's own exception for it
    (UnexpectedToken, UnexpectedCharacters, UnexpectedEOF), with position."""

    def __init__(self, error: Exception):
        super().__init__(str(error))
        self.error = error


@functools.lru_cache(maxsize=None)
def parser(name: str, start: tuple[str, ...]) -> lalr.Parser:
    """The run-time parser of grammars/NAME.lark with these start symbols."""
    return lalr.Parser(tables(name, start))


def parse(name: str, start: tuple[str, ...], text: str, symbol: str,
          lark_first: bool = False) -> lalr.Tree:
    """The tree of ``text`` from start symbol ``symbol``; SyntaxFailure,
    with Lark's positioned exception, where the grammar rejects it.
    ``lark_first``: the text is known to be rejected (the recogniser said
    so): go straight to Lark for the message."""
    if not lark_first:
        try:
            return parser(name, start).parse(text, symbol)
        except lalr.Rejected:
            pass
    from lark.exceptions import LarkError

    try:
        with lalr.paused_gc():
            tree = lark_parser(name, start).parse(text, start=symbol)
    except LarkError as exc:
        raise SyntaxFailure(exc) from None
    return from_lark(tree)      # not reached while the two agree (tests/test_lalr.py)


def tables(name: str, start: tuple[str, ...]) -> dict:
    """The LALR tables: shipped beside the grammars (an installed wheel), or
    from the disk cache, or (a source checkout's first run, a changed
    grammar) from Lark. Stored as marshal (format 4, which every Python since
    3.4 reads): it loads several times faster than JSON and needs no import.
    Each file holds the grammar text it was built from, and is used only for
    exactly that text (no hash to compute, nothing stale kept beside it). The
    cache is written atomically; where it cannot be written the tables are
    simply rebuilt next time."""
    import marshal

    grammar = _grammar_text(name)
    stem = _stem(name, start)
    shipped = os.path.join(grammar_dir(), f"{stem}.tables.marshal")
    cached = os.path.join(cache_dir(), f"{stem}.marshal")
    for path in (shipped, cached):
        try:
            with open(path, "rb") as fh:
                got = marshal.loads(fh.read())
            if isinstance(got, dict) and got.get("format") == lalr.FORMAT \
                    and got.get("grammar") == grammar:
                return got
        except (OSError, ValueError, EOFError, TypeError):
            pass
    data = _from_lark(name, start)
    write_cache(cached, marshal.dumps(data, 4))
    return data


def _grammar_text(name: str) -> str:
    with open(os.path.join(grammar_dir(), f"{name}.lark"), encoding="utf-8") as fh:
        return fh.read()


def _stem(name: str, start: tuple[str, ...]) -> str:
    """A parser's file name: the grammar and its start symbols."""
    return "-".join((name, *start))


def write_tables(folder, built) -> list[str]:
    """The tables of each parser in ``built`` ((grammar, start symbols): the
    registry's ``vendors.GRAMMARS``), built with Lark, written into ``folder``
    under the names ``tables`` looks for beside the grammars."""
    import marshal

    written = []
    for name, start in built:
        path = os.path.join(folder, f"{_stem(name, start)}.tables.marshal")
        with open(path, "wb") as fh:
            fh.write(marshal.dumps(_from_lark(name, start), 4))
        written.append(path)
    return written


def _from_lark(name: str, start: tuple[str, ...]) -> dict:
    """The tables as Lark builds them, in plain lists and dicts (through
    JSON: the same data whichever way it was stored)."""
    import json

    data = json.loads(json.dumps(lalr.tables_from_lark(lark_parser(name, start))))
    data["grammar"] = _grammar_text(name)      # what these tables are of
    return data


@functools.lru_cache(maxsize=None)
def lark_parser(name: str, start: tuple[str, ...]):
    """Lark's own LALR parser of the grammar: it compiles the tables and
    words the syntax errors."""
    from lark import Lark

    return Lark(_grammar_text(name), parser="lalr", lexer="contextual",
                start=list(start), propagate_positions=False, maybe_placeholders=False,
                cache=True)


def from_lark(tree) -> lalr.Tree:
    """A Lark tree as ucsio.parsing.lalr's Tree and Token (no recursion)."""
    from lark import Tree as LarkTree

    def convert(node):
        if isinstance(node, LarkTree):
            return lalr.Tree(str(node.data), list(node.children))
        return lalr.Token(node.type, node.value, node.start_pos, node.end_pos)

    root = convert(tree)
    stack = [root]
    while stack:
        node = stack.pop()
        node.children = [convert(c) for c in node.children]
        stack.extend(c for c in node.children if isinstance(c, lalr.Tree))
    return root
