"""The command line as a whole: subcommands, negative value lists, versions."""
from __future__ import annotations

import subprocess
import sys

import pytest

from conftest import FIXTURES


def run(*args):
    return subprocess.run([sys.executable, "-m", "ucsio", *map(str, args)],
                          capture_output=True, text=True)


def test_help_lists_every_command():
    res = run("--help")
    assert res.returncode == 0
    for name in ("frames", "check", "solve", "diff", "patch", "batch", "demo"):
        assert name in res.stdout


def test_version():
    res = run("--version")
    assert res.returncode == 0 and res.stdout.startswith("ucsio ")


def test_negative_value_lists_need_no_equals_sign(tmp_path):
    mod = FIXTURES / "abb" / "variants.mod"
    res = run("patch", mod, "--frame", "pShift", "--set", "-5,1,2,0,0,0")
    assert res.returncode == 0, res.stderr
    assert "+  LOCAL PERS pose pShift:=[[-5,1,2],[1,0,0,0]];" in res.stdout
    res = run("solve", FIXTURES / "measurements" / "kuka_base3.csv", "--tcp", "-20.67,89.73,33.44")
    assert res.returncode == 0, res.stderr
    assert "-20.670, 89.730, 33.440" in res.stdout


@pytest.mark.parametrize("args", [["frames"], ["solve", "x.csv", "--threshold", "abc"],
                                  ["patch", "f.mod", "--frame", "w", "--measured", "s.json",
                                   "--set-q", "1,2,3,1,0,0,0"], ["nonsense"]])
def test_usage_error_is_one_line_and_exits_2(args):
    res = run(*args)
    assert res.returncode == 2 and res.stdout == ""
    assert res.stderr.count("\n") == 1 and res.stderr.startswith("ucsio")
