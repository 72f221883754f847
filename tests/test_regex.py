"""ucsio.parsing.regex: possessive quantifiers and atomic groups rewritten for
the CPython releases whose ``re`` runs them wrongly (3.11.0 to 3.11.4,
Debian 12's python3 among them), and the same matches everywhere."""
from __future__ import annotations

import importlib
import json
import os
import pkgutil
import re
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import ucsio
from ucsio.parsing import regex
from ucsio.parsing.regex import portable

CORPUS = Path(__file__).resolve().parents[1].parent / "shared" / "corpus"
SOUND_RE = sys.version_info >= (3, 11, 5)
needs_sound_re = pytest.mark.skipif(
    not SOUND_RE, reason=f"Python {sys.version.split()[0]}'s own re runs possessive quantifiers "
    "wrongly, so it is no reference here; the rest of the suite runs the rewritten patterns")

# the issue's own example: a RAPID routine
ROUTINE = (r'PROC\b(?:[^"!eE]++|"[^"\r\n]*+"|![^\r\n]*+|\B[eE]|[eE](?!NDPROC\b))*+ENDPROC\b')
ROUTINE_TEXT = "PROC m()\n  MoveL p, v200, fine, tool0;\nENDPROC"


def test_the_routine_of_the_issue_matches_on_this_python():
    assert regex.compile(ROUTINE, re.I).match(ROUTINE_TEXT).end() == len(ROUTINE_TEXT)
    # and the rewritten form, forced, on any Python
    assert re.compile(portable(ROUTINE), re.I).match(ROUTINE_TEXT).end() == len(ROUTINE_TEXT)


def test_the_rewritten_form_uses_no_possessive_or_atomic_syntax():
    pattern = ROUTINE + r"|(?>a|ab)c|x{2,3}+|[+*]++|\++|[?+]?+"
    out = portable(pattern)
    assert out != pattern and portable(out) == out


def test_possessive_semantics_are_kept():
    # a possessive loop never gives back: a++a cannot match, a+a can
    assert re.compile(portable("a++a")).match("aaa") is None
    assert re.compile(portable("(?>a|ab)c")).match("abc") is None
    assert re.compile(portable("(?:a|ab)c")).match("abc") is not None
    # a quantifier after a rewritten group applies to the whole group
    assert re.compile(portable("(?>ab)*c")).match("ababc").end() == 5
    assert re.compile(portable("x(?:a++b)*+c")).match("xaabaabc").end() == 8


def test_groups_are_named_where_the_pattern_is_rewritten():
    with pytest.raises(ValueError, match="names its capturing groups"):
        portable(r"(a)*+")
    with pytest.raises(ValueError, match="names its capturing groups"):
        portable(r"(?P<x>a)b++\1")
    assert portable(r"(a)b") == r"(a)b"              # nothing rewritten: numbering unchanged
    out = portable(r"(?P<_p1>a)b++")                # a name of ours already taken
    assert re.compile(out).match("abb").group("_p1") == "a"


def test_escapes_classes_and_flags_are_atoms():
    cases = [(r"\x41++B", "AAB"), (r"[]a]*+b", "]ab"), (r"[^]]++\]", "ab]"), (r"\101*+", "AA"),
             (r"(?i)a{2,3}+b", "AAb"), (r"a{,2}+b", "aab"), (r"\N{LATIN SMALL LETTER A}++", "aa"),
             (r"(?#note)a?+a", "a"), (r"(?-i:a)++", "aa"), (r"[\]\\]++", "]\\")]
    for pattern, text in cases:
        want = re.compile(pattern).match(text) if SOUND_RE else None
        got = re.compile(portable(pattern)).match(text)
        if SOUND_RE:
            assert (got and got.span()) == (want and want.span()), pattern


# -- random patterns: the rewritten form matches as the native one --------------
LEAVES = st.sampled_from(["a", "b", "[ab]", "[^a]", ".", r"\s", r"\b", r"\B", "x", "(?!a)",
                          "(?=b)", "A"])
QUANTS = st.sampled_from(["*", "+", "?", "{1,2}", "{2}", "{0,3}"])
MODES = st.sampled_from(["", "?", "+"])


def _node(children):
    return st.one_of(
        st.lists(children, min_size=1, max_size=3).map("".join),
        st.tuples(children, children).map(lambda t: f"(?:{t[0]}|{t[1]})"),
        children.map(lambda c: f"(?>{c})"),
        st.tuples(children, QUANTS, MODES).map(lambda t: f"(?:{t[0]}){t[1]}{t[2]}"),
        st.tuples(LEAVES, QUANTS, MODES).map(lambda t: f"{t[0]}{t[1]}{t[2]}"),
    )


PATTERNS = st.recursive(LEAVES, _node, max_leaves=8)


@needs_sound_re
@settings(max_examples=400, deadline=None)
@given(PATTERNS, st.text(alphabet="abAx \n", max_size=12), st.booleans())
def test_random_patterns_match_as_the_native_ones(pattern, text, ignorecase):
    flags = re.I if ignorecase else 0
    try:
        native = re.compile(pattern, flags)
    except re.error:
        return                                  # nothing to rewrite: re refuses it too
    rewritten = re.compile(portable(pattern), flags)
    for how in ("match", "search", "fullmatch"):
        a, b = getattr(native, how)(text), getattr(rewritten, how)(text)
        assert (a and a.span()) == (b and b.span()), (how, pattern, portable(pattern), text)


# -- ucsio's own patterns ---------------------------------------------------------
def _import_everything():
    for info in pkgutil.walk_packages(ucsio.__path__, "ucsio."):
        if not info.name.endswith("__main__"):          # that one runs the command line
            importlib.import_module(info.name)


def test_every_pattern_of_ucsio_can_be_rewritten():
    _import_everything()
    from ucsio.vendors.kuka import krl
    from ucsio.vendors.abb import rapid
    rapid._recognise("MODULE m\nENDMODULE\n")      # the shortcut patterns are built lazily
    krl._recognise("DEFDAT d\nENDDAT\n")
    assert len(regex.PATTERNS) > 10
    for pattern in regex.PATTERNS:
        re.compile(portable(pattern))


def test_the_grammar_terminals_need_no_rewriting():
    """Lark compiles the grammars' terminals itself (the lexer of a rejected
    file's message): they are written in the portable form."""
    from ucsio.parsing import grammar
    from ucsio.vendors import GRAMMARS

    for name, start in GRAMMARS:
        terminals = grammar.tables(name, start)["terminals"]
        assert terminals, name
        for terminal, pattern in terminals.items():
            assert portable(pattern) == pattern, (name, terminal)


@pytest.mark.skipif(not CORPUS.is_dir(), reason="../shared/corpus is absent")
def test_the_corpus_reads_the_same_with_the_rewritten_patterns(tmp_path):
    """Every corpus file checked and listed with the native patterns and, in a
    second process, with the rewritten ones (UCSIO_PORTABLE_REGEX=1), as on
    Debian 12's python3: the same frames, findings and errors."""
    files = sorted(str(p) for p in CORPUS.glob("*/*") if p.suffix.lower() in
                   (".mod", ".modx", ".sys", ".sysx", ".prg", ".dat", ".va", ".dg", ".ls"))
    assert len(files) > 40

    def run(portable_env: bool) -> dict:
        env = dict(os.environ, UCSIO_CACHE_DIR=str(tmp_path / "cache"))
        env.pop("UCSIO_PORTABLE_REGEX", None)
        if portable_env:
            env["UCSIO_PORTABLE_REGEX"] = "1"
        out = {}
        for command in ("check", "frames"):
            proc = subprocess.run([sys.executable, "-m", "ucsio", command, "--json", *files],
                                  capture_output=True, text=True, env=env, timeout=300)
            out[command] = json.loads(proc.stdout)
        return out

    assert run(True) == run(False)
