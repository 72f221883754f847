"""The grammars that ship with ucsio, compiled by Lark, run by ucsio.parsing.lalr.

The grammars are data (grammars/*.lark at the top of the repository, copied
into the wheel as ucsio/grammars). Lark compiles each into LALR tables: when
the wheel is built (hatch_build.py ships them beside the grammars), or in a
source checkout once per machine (``tables`` keeps them in a disk cache);
JSON keyed by the grammar's text. So a command that reads a file never
imports Lark. Only a syntax
error does: ``parse`` asks Lark itself for the positioned message, so what
the user reads is Lark's diagnosis of exactly the text we rejected.
"""
from __future__ import annotations

import functools
import json
import os
import zlib
from pathlib import Path

from . import lalr


def grammar_dir() -> Path:
    package = Path(__file__).resolve().parent.parent     # .../ucsio
    inside = package / "grammars"                        # installed wheel
    if inside.is_dir():
        return inside
    return package.parent.parent / "grammars"            # source checkout / editable install


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


# The parsers ucsio runs: (grammar, start symbols). A wheel ships their
# tables beside the grammars (hatch_build.py calls write_tables).
BUILT = (("rapid", ("file", "data_decl")), ("rapid", ("statements",)), ("krl", ("file",)))


def tables(name: str, start: tuple[str, ...]) -> dict:
    """The LALR tables: shipped beside the grammars (an installed wheel), or
    from the disk cache, or (a source checkout's first run, a changed
    grammar) from Lark. The cache is written atomically; where it cannot be
    written the tables are simply rebuilt next time."""
    key = _key(name, start)
    shipped = grammar_dir() / f"{name}-{key}.tables.json"
    cached = cache_dir() / f"{name}-{key}.json"
    for path in (shipped, cached):
        try:
            got = json.loads(path.read_bytes())
            if got.get("format") == lalr.FORMAT:
                return got
        except (OSError, ValueError, AttributeError):
            pass
    data = _from_lark(name, start)
    _write_cache(cached, data.encode())
    return json.loads(data)         # as read back from disk: tuples are lists


def _key(name: str, start: tuple[str, ...]) -> str:
    """What the tables depend on: their format, the start symbols and the
    grammar's text. (hashlib would cost a cold start 6 ms, it loads OpenSSL;
    a CRC and the length tell an edited grammar from the one tabled.)"""
    text = (grammar_dir() / f"{name}.lark").read_text(encoding="utf-8")
    data = f"{lalr.FORMAT}\0{','.join(start)}\0{text}".encode()
    return f"{zlib.crc32(data):08x}{len(data):x}"


def write_tables(folder: Path) -> list[Path]:
    """Every parser's tables, built with Lark, written into ``folder`` under
    the names ``tables`` looks for beside the grammars."""
    written = []
    for name, start in BUILT:
        path = Path(folder) / f"{name}-{_key(name, start)}.tables.json"
        path.write_text(_from_lark(name, start), encoding="utf-8")
        written.append(path)
    return written


def _from_lark(name: str, start: tuple[str, ...]) -> str:
    """The tables as Lark builds them, as the JSON text stored on disk."""
    return json.dumps(lalr.tables_from_lark(lark_parser(name, start)), separators=(",", ":"))


def cache_dir() -> Path:
    where = os.environ.get("UCSIO_CACHE_DIR")
    if where:
        return Path(where)
    base = os.environ.get("XDG_CACHE_HOME")
    if not base:
        home = os.path.expanduser("~")
        if home.startswith("~"):        # no home to expand: never a "~" folder in the cwd
            import tempfile
            user = os.getuid() if hasattr(os, "getuid") else "user"
            return Path(tempfile.gettempdir()) / f"ucsio-cache-{user}"
        base = os.path.join(home, ".cache")
    return Path(base) / "ucsio"


def _write_cache(path: Path, data: bytes) -> None:
    import tempfile

    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(data)
            os.replace(tmp, path)
        except BaseException:
            os.unlink(tmp)
            raise
    except OSError:
        pass            # a read-only home: correct, only slower


@functools.lru_cache(maxsize=None)
def lark_parser(name: str, start: tuple[str, ...]):
    """Lark's own LALR parser of the grammar: it compiles the tables and
    words the syntax errors."""
    from lark import Lark

    path = grammar_dir() / f"{name}.lark"
    return Lark(path.read_text(encoding="utf-8"), parser="lalr", lexer="contextual",
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
