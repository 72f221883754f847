"""Possessive quantifiers and atomic groups on every CPython ucsio supports.

ucsio's scanners stay linear on hostile text because their loops never
give back what they matched: ``X*+``, ``X++``, ``X?+``, ``X{m,n}+`` and
``(?>X)``, new in Python 3.11's ``re``. Before 3.11.5 those match wrongly
where the repeated group has alternatives (gh-106052, gh-100061): on Debian
12's own python3 (3.11.2) every RAPID routine went unrecognised.

``compile`` therefore hands such a Python the same pattern in the older
spelling of an atomic group, which every ``re`` has always run correctly:
a lookahead (atomic in ``re``: never re-entered on backtracking) captures
what ``X`` matches, and a backreference consumes exactly that:

    (?>X)   ->  (?:(?=(?P<_pN>X))(?-i:(?P=_pN)))
    X*+     ->  (?:(?=(?P<_pN>X*))(?-i:(?P=_pN)))

The backreference is compared case-sensitively: it is the same text, and a
case-folding comparison is twice as slow. Where ``re`` is sound the pattern
is compiled as written (the lookahead form costs about 1.3x).

A pattern given to ``compile`` names its capturing groups (``(?P<kind>…)``):
the rewriting adds groups, which would renumber unnamed ones.
"""
from __future__ import annotations

import os
import re
import sys

NATIVE = sys.version_info >= (3, 11, 5) and not os.environ.get("UCSIO_PORTABLE_REGEX")
"""Whether this Python's ``re`` runs possessive quantifiers and atomic groups
correctly (CPython 3.11.5 and later). UCSIO_PORTABLE_REGEX=1 takes the
rewritten patterns anyway (the tests run them on every Python)."""

PATTERNS: list[str] = []
"""Every pattern given to ``compile`` (tests rewrite each and compare)."""


def compile(pattern: str, flags: int = 0) -> re.Pattern:
    """``re.compile``, with possessive quantifiers and atomic groups rewritten
    where this Python's ``re`` gets them wrong, through the compiled-pattern
    cache (below)."""
    PATTERNS.append(pattern)
    return _compiled(pattern if NATIVE else portable(pattern), flags)


# -- compiled patterns, cached -------------------------------------------------------
# re compiles a pattern in pure Python (its parser and code generator), and
# the C engine then runs a list of opcodes. For a command that lists one
# file's frames, compiling the outline scanner and the grammar's lexer was a
# quarter of all it did. The opcodes depend only on the pattern, its flags
# and the Python that compiled them (_sre.MAGIC, the version): they are kept
# in the disk cache, one file per Python, and given back to _sre.compile,
# which validates them. Where any of this is not as expected (another
# Python, another re), patterns are simply compiled by re.
_store: dict | None = None
_dirty = False
_native_ok = True
"""False once this Python's ``_sre.compile`` has refused opcodes that its own
``re`` made: from then on every pattern goes to ``re.compile`` at once, so a
changed ``re`` costs one failed attempt per run, never every pattern twice."""


def _store_path() -> str | None:
    import _sre

    from .cache import cache_dir

    tag = getattr(sys.implementation, "cache_tag", None)
    if sys.implementation.name != "cpython" or not tag or not hasattr(_sre, "compile") \
            or _sre.CODESIZE != 4:
        return None
    return os.path.join(cache_dir(), f"re2-{tag}-{sys.version_info[2]}-{_sre.MAGIC}.marshal")


def _load_store() -> dict:
    global _store
    import marshal

    _store = {}
    try:
        path = _store_path()
        if path is not None:
            with open(path, "rb") as fh:
                got = marshal.loads(fh.read())
            if isinstance(got, dict):
                _store = got
    except (OSError, ValueError, EOFError, TypeError):
        pass
    return _store


def _compiled(source, flags: int) -> re.Pattern:
    if not _native_ok:
        return re.compile(source, flags)
    store = _load_store() if _store is None else _store
    got = store.get((source, int(flags)))
    if got is not None:
        import _sre
        try:
            flags2, code, groups, groupindex, indexgroup = got
            # the opcodes are kept as bytes (unsigned 32-bit words): marshal
            # reads a whole file of them as fast as it copies it, and only
            # the patterns this command uses become lists of ints
            return _sre.compile(source, flags2, memoryview(code).cast("I").tolist(), groups,
                                groupindex, indexgroup)
        except Exception:       # noqa: BLE001 - a stale or damaged entry: compile anew
            pass
    return _compile_and_keep(store, source, flags)


def _compile_and_keep(store: dict, source, flags: int) -> re.Pattern:
    """Compile as ``re`` does, keeping the opcodes for the next run; where
    this Python's ``re`` is not built as expected, give up the cache for the
    rest of the run and let ``re.compile`` do it all."""
    global _dirty, _native_ok
    try:
        import _sre
        from re import _compiler, _parser

        parsed = _parser.parse(source, flags)
        code = _compiler._code(parsed, flags)
    except Exception:           # noqa: BLE001 - not this re's internals
        _native_ok = False
        return re.compile(source, flags)
    groupindex = dict(parsed.state.groupdict)
    indexgroup = [None] * parsed.state.groups
    for name, i in groupindex.items():
        indexgroup[i] = name
    all_flags = int(flags | parsed.state.flags)
    try:
        compiled = _sre.compile(source, all_flags, code, parsed.state.groups - 1, groupindex,
                                tuple(indexgroup))
    except Exception:           # noqa: BLE001 - _sre.compile takes other arguments now
        _native_ok = False
        return re.compile(source, flags)
    import array
    store[(source, int(flags))] = (all_flags, array.array("I", code).tobytes(),
                                   parsed.state.groups - 1, groupindex, tuple(indexgroup))
    if not _dirty:
        import atexit
        atexit.register(save_cache)     # the command line saves before its os._exit
    _dirty = True
    return compiled


def save_cache() -> None:
    """Write the compiled patterns learned in this run (the command line
    calls this before it exits; ``atexit`` for everyone else)."""
    global _dirty
    if not _dirty or _store is None:
        return
    _dirty = False
    import marshal

    from .cache import write_cache

    try:
        path = _store_path()
        if path is not None:
            write_cache(path, marshal.dumps(_store, 4))
    except (OSError, ValueError):
        pass


class lazy:
    """A module's pattern, compiled (by ``compile``) when first used: ``re``
    compiles in pure Python, 0.2-5 ms a pattern, and a command that lists one
    file's frames needs a few of the many patterns a module holds."""

    __slots__ = ("_source", "_flags", "_compiled")

    def __init__(self, pattern: str, flags: int = 0):
        self._source, self._flags, self._compiled = pattern, flags, None
        PATTERNS.append(pattern)

    def __getattr__(self, name: str):
        compiled = self._compiled
        if compiled is None:
            compiled = self._compiled = _compiled(
                self._source if NATIVE else portable(self._source), self._flags)
        return getattr(compiled, name)


class _Rewriter:
    def __init__(self, pattern: str):
        self.p = pattern
        self.n = 0
        self.used = set(re.findall(r"\(\?P<(\w+)>", pattern))     # names taken
        self.numbered = False       # an unnamed group or a backreference by number


    def name(self) -> str:
        while True:
            self.n += 1
            name = f"_p{self.n}"
            if name not in self.used:
                return name

    def once(self, body: str) -> str:
        name = self.name()
        return f"(?:(?=(?P<{name}>{body}))(?-i:(?P={name})))"

    # -- one sequence: atoms, each maybe quantified, until ``)`` or the end ----
    def sequence(self, i: int) -> tuple[str, int]:
        p = self.p
        out: list[str] = []
        while i < len(p) and p[i] != ")":
            c = p[i]
            if c == "|":
                out.append(c)
                i += 1
                continue
            atom, i = self.atom(i)
            quant, i = _quantifier(p, i)
            if quant and i < len(p) and p[i] == "+":      # possessive
                out.append(self.once(atom + quant))
                i += 1
            else:
                if quant and i < len(p) and p[i] == "?":  # lazy
                    quant += "?"
                    i += 1
                out.append(atom + quant)
        return "".join(out), i

    def atom(self, i: int) -> tuple[str, int]:
        p = self.p
        c = p[i]
        if c == "\\":
            end = _escape_end(p, i)
            if p[i + 1] in "123456789" and end - i <= 3:
                self.numbered = True                     # a backreference by number
            return p[i:end], end
        if c == "[":
            end = _class_end(p, i)
            return p[i:end], end
        if c == "(":
            return self.group(i)
        return c, i + 1

    def group(self, i: int) -> tuple[str, int]:
        p = self.p
        if p.startswith("(?#", i):                         # comment
            end = p.index(")", i) + 1
            return p[i:end], end
        if p.startswith("(?P=", i):                        # named backreference
            end = p.index(")", i) + 1
            return p[i:end], end
        m = _own.group_head.match(p, i)
        if m is None:
            raise ValueError(f"unsupported group at {i}: {p[i:i + 10]!r}")
        head = m.group()
        if head.endswith(")"):
            return head, m.end()                           # (?i): flags for the whole pattern
        if head == "(":
            self.numbered = True
        body, j = self.sequence(m.end())
        if j >= len(p) or p[j] != ")":
            raise ValueError(f"unbalanced parenthesis at {i}")
        if head == "(?>":
            return self.once(body), j + 1
        return f"{head}{body})", j + 1


# (?:  (?P<name>  (?=  (?!  (?<=  (?<!  (?>  (?flags:  (?flags)  (
class _Own:
    """The rewriter's own patterns (plain re, compiled when first rewriting)."""

    def __getattr__(self, name: str):
        value = re.compile(_OWN[name])
        setattr(self, name, value)
        return value


_OWN = {"group_head": r"\((?:\?(?::|P<\w+>|=|!|<=|<!|>|[aiLmsux]*(?:-[imsx]+)?[:)]))?",
        "quant": r"[*+?]|\{(?:\d+(?:,\d*)?|,\d+)\}"}
_own = _Own()


def _quantifier(p: str, i: int) -> tuple[str, int]:
    m = _own.quant.match(p, i)
    return (m.group(), m.end()) if m else ("", i)


def _escape_end(p: str, i: int) -> int:
    """End of the escape at p[i] == '\\' (re's rules: \\0 and up to two
    octal digits; three octal digits; else \\1 .. \\99, a backreference)."""
    c = p[i + 1]
    if c in "xuU":
        return i + {"x": 4, "u": 6, "U": 10}[c]
    if c == "N":
        return p.index("}", i) + 1
    if c == "0":
        j = i + 2
        while j < len(p) and j < i + 4 and p[j] in "01234567":
            j += 1
        return j
    if c.isdigit():
        if c in "01234567" and len(p) >= i + 4 and all(d in "01234567" for d in p[i + 2:i + 4]):
            return i + 4
        return i + 3 if i + 2 < len(p) and p[i + 2].isdigit() else i + 2
    return i + 2


def _class_end(p: str, i: int) -> int:
    """End of the character class starting at p[i] == '['."""
    j = i + 1
    if j < len(p) and p[j] == "^":
        j += 1
    if j < len(p) and p[j] == "]":       # a ] first is a literal
        j += 1
    while p[j] != "]":
        j += 2 if p[j] == "\\" else 1
    return j + 1


def portable(pattern: str) -> str:
    """``pattern`` with every possessive quantifier and atomic group written
    as a capturing lookahead and a backreference (see the module's doc);
    ValueError for a pattern that cannot be rewritten safely (an unnamed
    capturing group, a numbered backreference)."""
    rewriter = _Rewriter(pattern)
    out, i = rewriter.sequence(0)
    if i != len(pattern):
        raise ValueError(f"unbalanced parenthesis at {i}")
    if rewriter.n and rewriter.numbered:
        raise ValueError("a pattern with possessive quantifiers or atomic groups names its "
                         "capturing groups (?P<name>...) and backreferences (?P=name): "
                         "the rewriting adds groups, which would renumber the others")
    return out
