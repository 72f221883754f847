"""What the short commands do to start in a blink, each held against what it
stands in for (issue 18 point 10, issue 25 points 12-13): the compiled-pattern
cache against re.compile, and its one fallback where this Python's _sre
takes other arguments; argparse without gettext, and the stand-in handing
other names to the real gettext; float32 rounding against struct. Nothing
here reaches into json's or re's private caches any more."""
from __future__ import annotations

import json
import math
import os
import re
import struct
import subprocess
import sys

import pytest
from hypothesis import given, settings, strategies as st

from conftest import ROOT
from ucsio.errors import UcsioError
from ucsio.method import solution
from ucsio.parsing import regex
from ucsio.vendors.common.write import f32


def test_a_bad_solution_file_names_its_line_and_column(tmp_path):
    text = '{\n  "frame": {"x": 1,\n  }\n}\n'
    path = tmp_path / "S.json"
    path.write_text(text)
    with pytest.raises(json.JSONDecodeError) as want:     # where this Python's json says
        json.loads(text)                                  # (3.13 names the trailing comma)
    with pytest.raises(UcsioError) as exc:
        solution.read_json(str(path))
    assert (exc.value.line, exc.value.col) == (want.value.lineno, want.value.colno)
    assert exc.value.line in (2, 3)
    assert exc.value.message == f"not valid JSON: {want.value.msg}"


def test_no_private_json_or_re_cache_is_touched():
    """A future _json or re cache must not turn a diff into an internal
    error: the source names neither."""
    for path in (ROOT / "src" / "ucsio").rglob("*.py"):
        text = path.read_text()
        assert "_json import" not in text and "make_scanner" not in text, path
        assert "re._cache" not in text and '"_cache"' not in text, path


PATTERNS = [r"(?P<a>x+)y", r"\s*(?:#\s*)?$", r"[A-Z_]\w*", r"(?i)BASE_DATA\[(?P<n>\d+)\]"]


@pytest.mark.parametrize("source", PATTERNS)
def test_each_cached_pattern_is_what_re_compiles(source, tmp_path, monkeypatch):
    # Pattern equality compares the pattern, its flags and its compiled code
    monkeypatch.setenv("UCSIO_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(regex, "_store", None)
    assert regex._compiled(source, 0) == re.compile(source)
    assert (source, 0) in regex._store                  # kept for the next run
    assert regex._compiled(source, 0) == re.compile(source)     # from the kept opcodes


FALLBACK = """
import _sre, re, sys
from ucsio.parsing import regex

native = _sre.compile
ours = []
def changed(*args):
    # a Python whose _sre.compile takes other arguments: its own re is built
    # for them (simulated: re's compiler gets through), ucsio's cache is not
    if sys._getframe(1).f_globals.get("__name__") == "re._compiler":
        return native(*args)
    ours.append(args[0])
    raise TypeError("compile() takes other arguments")
_sre.compile = changed

parsed = []
parse = re._parser.parse
def counting(source, flags=0, *rest):
    parsed.append(source)
    return parse(source, flags, *rest)
re._parser.parse = counting

sources = [rf"(?P<n{i}>\\d+)x{i}" for i in range(20)]
got = [regex._compiled(s, 0) for s in sources]
_sre.compile = native
assert got == [re.compile(s) for s in sources]
print(len(ours), parsed.count(sources[0]), max(parsed.count(s) for s in sources[1:]),
      len(regex._store))
"""


def test_a_changed_sre_compile_costs_one_attempt_not_every_pattern_twice(tmp_path):
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"), UCSIO_CACHE_DIR=str(tmp_path))
    out = subprocess.run([sys.executable, "-c", FALLBACK], env=env, capture_output=True,
                         text=True)
    assert out.returncode == 0, out.stderr
    attempts, first, later, kept = map(int, out.stdout.split())
    assert attempts == 1        # the first pattern's; every later one goes straight to re
    assert first == 2           # the one that found out: ours, then re's
    assert later == 1           # no other pattern parsed twice
    assert kept == 0            # nothing stored that this Python cannot load


def test_the_gettext_stand_in_hands_other_names_to_the_real_module(monkeypatch):
    from ucsio.cli import gettext_stand_in

    stand_in = gettext_stand_in()
    monkeypatch.setitem(sys.modules, "gettext", stand_in)
    assert stand_in.gettext("x") == "x" and stand_in.ngettext("a", "b", 2) == "b"
    from gettext import dgettext, translation       # names the stand-in does not define
    import gettext as real
    assert real is not stand_in and dgettext is real.dgettext
    assert translation is real.translation
    assert dgettext("no-such-domain", "words") == "words"


def test_argparse_speaks_as_before_without_gettext(tmp_path):
    """In a fresh process (argparse not yet imported: the stand-in is used)
    usage errors and help read as argparse writes them."""
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))

    def ucsio(*args):
        return subprocess.run([sys.executable, "-c", "import sys; from ucsio.cli import main; "
                               "r = main(sys.argv[1:]); print('gettext' in sys.modules); "
                               "sys.exit(r)", *args], env=env, capture_output=True, text=True)
    res = ucsio("frames")
    assert res.returncode == 2 and res.stdout.strip() == "False"
    assert "the following arguments are required: FILE" in res.stderr
    res = ucsio("frames", "x.mod", "--no-such-option")
    assert res.returncode == 2 and "unrecognized arguments: --no-such-option" in res.stderr
    res = ucsio("solve", "--tcp")
    assert res.returncode == 2 and "expected one argument" in res.stderr
    res = ucsio("patch", "--help")
    assert res.returncode == 0 and res.stdout.startswith("usage: ucsio patch")
    assert "options:" in res.stdout


@settings(max_examples=300, derandomize=True, deadline=None)
@given(st.floats(allow_nan=True, allow_infinity=True) | st.sampled_from(
    [3.4028235e38, 3.4028236e38, 1e39, -1e39, 1e-46, -0.0, 1.1]))
def test_float32_rounding_is_struct_s(v):
    try:
        want = struct.unpack("f", struct.pack("f", v))[0]
    except OverflowError:
        want = v
    got = f32(v)
    assert (math.isnan(got) and math.isnan(want)) or (got == want and
                                                       math.copysign(1, got) == math.copysign(1, want))
