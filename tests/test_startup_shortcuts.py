"""What the short commands do to start in a blink, each held against what it
stands in for (issue 18 point 10): the solution reader against json.loads,
re's cache primed with the standard library's patterns against re.compile,
argparse without gettext, float32 rounding against struct."""
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
from ucsio.review.patch import f32

JSON_VALUES = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False)
    | st.text(max_size=8),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=6), inner,
                                                                max_size=4),
    max_leaves=20)


@settings(max_examples=300, derandomize=True, deadline=None)
@given(JSON_VALUES, st.sampled_from(["", " ", "\n", "\r\n\t "]), st.booleans())
def test_the_solution_reader_reads_what_json_reads(value, space, indent):
    text = space + json.dumps(value, indent=2 if indent else None, ensure_ascii=False) + space
    got = solution.loads(text)
    assert got == json.loads(text)
    assert type(got) is type(json.loads(text))


@pytest.mark.parametrize("text", ['{"x": 1} {"y": 2}', '{"x": 1,}', "", "   ", '{"x": NaN}',
                                  '[Infinity, -Infinity]', '"\\ud800"', '{"x": 1}\x00',
                                  '{"a": "tab\there"}', "\ufeff{}", "[1, 2", "01"])
def test_the_solution_reader_fails_as_json_fails(text):
    try:
        want = json.loads(text)
    except json.JSONDecodeError as exc:
        with pytest.raises(json.JSONDecodeError) as got:
            solution.loads(text)
        assert (got.value.msg, got.value.pos) == (exc.msg, exc.pos)
    else:
        got = solution.loads(text)
        assert json.dumps(got) == json.dumps(want)      # NaN != NaN: compared as written


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


@pytest.mark.parametrize("source, flags", regex.STDLIB)
def test_each_primed_pattern_is_what_re_compiles(source, flags):
    # Pattern equality compares the pattern, its flags and its compiled code
    assert regex._compiled(source, flags) == re.compile(source, flags)


PROBE = """
import re, sys, io, contextlib
fresh = []
compile_ = re._compile
def spy(pattern, flags):
    key = (type(pattern), pattern, int(flags))
    if key not in re._cache and key not in getattr(re, "_cache2", {}):
        fresh.append(pattern)
    return compile_(pattern, flags)
re._compile = spy
from ucsio import cli
with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
    code = cli.main(sys.argv[1:])
print(code, "gettext" in sys.modules, "locale" in sys.modules, "json" in sys.modules,
      repr(sorted(set(p for p in fresh if isinstance(p, str)))))
"""


def test_a_short_command_compiles_none_of_the_standard_library_s_patterns(tmp_path):
    """diff and patch read a solution and print a diff: json, difflib and
    argparse are imported, and none of their patterns is compiled anew."""
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"), UCSIO_CACHE_DIR=str(tmp_path / "c"))
    sol = tmp_path / "S.json"
    sol.write_text(json.dumps({"frame": {"x": 1, "y": 2, "z": 3, "a": 0, "b": 0, "c": 0}}))
    dat = ROOT / "fixtures" / "kuka" / "cell_config.dat"
    runs = [["patch", str(dat), "--frame", "BASE_DATA[1]", "--measured", str(sol)],
            ["diff", str(dat), "--frame", "BASE_DATA[1]", "--measured", str(sol)]]
    for args in runs * 2:           # the second time from the compiled-pattern cache
        out = subprocess.run([sys.executable, "-c", PROBE, *args], env=env, capture_output=True,
                             text=True, check=True).stdout.split(None, 4)
    code, gettext, locale, json_, fresh = out
    assert code in ("0", "1") and gettext == locale == json_ == "False"
    stdlib = {s for s, _ in regex.STDLIB if isinstance(s, str)}
    assert not set(eval(fresh)) & stdlib, fresh         # noqa: S307 - our own repr


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
