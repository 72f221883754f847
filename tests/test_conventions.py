"""The command line behaves like git and ruff (SPEC: Many files and whole
backups; issue 11 point 6): no abbreviated options, suggestions for typos,
JSON errors with --json, stderr for messages and stdout for data, colour only
on a terminal."""
from __future__ import annotations

import json
import shutil
import subprocess
import sys

import pytest

from conftest import FIXTURES, ROOT

SRC = str(ROOT / "src")


def run(*args, stdin=None, env=None):
    import os
    e = dict(os.environ, PYTHONPATH=SRC)
    e.pop("NO_COLOR", None)
    e.update(env or {})
    return subprocess.run([sys.executable, "-m", "ucsio", *map(str, args)], input=stdin,
                          capture_output=True, text=True, env=e)


def test_abbreviated_option_is_refused_and_writes_nothing(tmp_path):
    mod = tmp_path / "variants.mod"
    shutil.copy(FIXTURES / "abb" / "variants.mod", mod)
    before = mod.read_bytes()
    res = run("patch", mod, "--frame", "pShift", "--set", "1,2,3,0,0,0", "--in-plac")
    assert res.returncode == 2 and res.stdout == ""
    assert res.stderr.count("\n") == 1
    assert "--in-plac" in res.stderr and "did you mean '--in-place'" in res.stderr
    assert mod.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["variants.mod"]


@pytest.mark.parametrize("args", [["frames", "--jso", "x.mod"], ["solve", "m.csv", "--thresh", "2"],
                                  ["diff", "a", "b", "--exit"]])
def test_no_command_takes_an_abbreviation(args):
    res = run(*args)
    assert res.returncode == 2 and "unrecognized arguments" in res.stderr


def test_mistyped_subcommand_gets_the_nearest():
    res = run("frmes", "x.mod")
    assert res.returncode == 2 and res.stdout == ""
    assert "did you mean 'frames'" in res.stderr and res.stderr.count("\n") == 1


def test_json_error_is_json_on_stdout_and_a_line_on_stderr(tmp_path):
    bad = tmp_path / "bad.mod"
    bad.write_text("MODULE m\n  PERS wobjdata w:=[FALSE,TRUE,\"\",[[0,0,0],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n"
                   "  PERS num x:=[1,2;\nENDMODULE\n")
    for args in (["patch", bad, "--frame", "w", "--set", "1,2,3,0,0,0"],
                 ["diff", bad, "--frame", "w", "--measured", tmp_path / "none.json"]):
        res = run(*args, "--json")
        assert res.returncode == 2
        err = json.loads(res.stdout)["error"]
        assert set(err) == {"file", "line", "col", "message"}
        assert err["file"] and err["message"]
        assert res.stderr.count("\n") == 1 and err["message"] in res.stderr
    # a usage error too
    res = run("patch", bad, "--frame", "w", "--json")
    assert res.returncode == 2
    assert "required" in json.loads(res.stdout)["error"]["message"]


def test_textconv_with_json_is_a_usage_error():
    mod = FIXTURES / "abb" / "variants.mod"
    res = run("diff", "--textconv", mod, "--json")
    assert res.returncode == 2
    assert "--json" in json.loads(res.stdout)["error"]["message"]
    assert res.stderr.count("\n") == 1 and "textconv" in res.stderr
