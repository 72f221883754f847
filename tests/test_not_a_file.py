"""Inputs that are not regular files (issue 18, point 11).

A named pipe opened for reading blocks until something writes to it, and a
device like /dev/zero never ends: ucsio must not wait on either. Anything
that is not a regular file (after following links) gets one line naming it
and exit 2; a folder walk lists it as an error beside the other files, and a
batch entry that names one fails alone. Every command runs in a subprocess
with a timeout, so a regression fails here instead of hanging the suite.
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import FIXTURES

pytestmark = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes on this OS")

KUKA = FIXTURES / "kuka" / "cell_config.dat"
MEAS = FIXTURES / "measurements" / "kuka_base3.csv"
TCP = "-20.67,89.73,33.44"


def run(*args, cwd=None):
    try:
        return subprocess.run([sys.executable, "-m", "ucsio", *map(str, args)],
                              capture_output=True, text=True, timeout=20, cwd=cwd,
                              stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        pytest.fail(f"ucsio {' '.join(map(str, args))} still ran after 20 s: it waits on a "
                    "file that is not a regular file")


def fifo(path: Path) -> Path:
    os.mkfifo(path)
    return path


def one_error_line(res, name: str) -> str:
    assert res.returncode == 2, (res.stdout, res.stderr)
    assert res.stderr.count("\n") == 1, res.stderr
    assert name in res.stderr and "not a regular file" in res.stderr, res.stderr
    return res.stderr


def test_controller_file_that_is_a_pipe(tmp_path):
    p = fifo(tmp_path / "$config.dat")
    one_error_line(run("frames", p), str(p))
    one_error_line(run("check", p), str(p))
    one_error_line(run("diff", p, KUKA), str(p))
    one_error_line(run("diff", "--textconv", p), str(p))
    one_error_line(run("patch", p, "--frame", "BASE_DATA[1]", "--set", "1,2,3,0,0,0"), str(p))
    # through a symbolic link too
    link = tmp_path / "linked.dat"
    link.symlink_to(p)
    one_error_line(run("frames", link), str(link))
    res = run("frames", p, "--json")
    err = json.loads(res.stdout)["error"]
    assert err["file"] == str(p) and "not a regular file" in err["message"]


def test_a_device_is_not_read_either(tmp_path):
    if not os.path.exists("/dev/zero"):
        pytest.skip("no /dev/zero")
    one_error_line(run("frames", "/dev/zero"), "/dev/zero")
    one_error_line(run("solve", "/dev/zero", "--tcp", TCP), "/dev/zero")


def test_measurement_solution_and_side_files_that_are_pipes(tmp_path):
    p = fifo(tmp_path / "points.csv")
    one_error_line(run("solve", p, "--tcp", TCP), str(p))
    one_error_line(run("solve", "--laser", p, "--robot", MEAS, "--tcp", TCP), str(p))
    one_error_line(run("solve", "--laser", MEAS, "--robot", p, "--tcp", TCP), str(p))
    robot = fifo(tmp_path / "MEASURE.dat")
    one_error_line(run("solve", "--laser", MEAS, "--robot", robot, "--tcp", TCP), str(robot))
    one_error_line(run("solve", MEAS, "--tool", f"{p}:TOOL_DATA[1]"), str(p))
    one_error_line(run("solve", "--laser", MEAS, "--robot", MEAS, "--map", p, "--tcp", TCP),
                   str(p))
    sol = fifo(tmp_path / "solution.json")
    one_error_line(run("diff", KUKA, "--frame", "BASE_DATA[1]", "--measured", sol), str(sol))
    one_error_line(run("patch", KUKA, "--frame", "BASE_DATA[1]", "--measured", sol), str(sol))


def test_a_pipe_in_a_backup_folder_is_listed_and_the_rest_read(tmp_path):
    old, new = tmp_path / "old", tmp_path / "new"
    for d in (old, new):
        (d / "KRC" / "R1" / "System").mkdir(parents=True)
        shutil.copy(KUKA, d / "KRC" / "R1" / "System" / "$config.dat")
        fifo(d / "KRC" / "R1" / "System" / "pipe.dat")
    (new / "KRC" / "R1" / "System" / "$config.dat").write_text(
        KUKA.read_text().replace("BASE_DATA[1]={X 1000.0", "BASE_DATA[1]={X 1000.5"))
    pipe = str(old / "KRC" / "R1" / "System" / "pipe.dat")
    for cmd in (["frames", old], ["check", old]):
        res = run(*cmd)
        assert res.returncode == 2, res.stderr
        assert pipe in res.stderr and "not a regular file" in res.stderr
        if cmd[0] == "frames":
            assert "BASE_DATA[1]" in res.stdout          # the good file is still listed
    res = run("frames", old, "--json")
    data = json.loads(res.stdout)
    assert any(f["name"] == "BASE_DATA[1]" for f in data["frames"])
    assert [e["file"] for e in data["errors"]] == [pipe]
    res = run("diff", old, new)
    assert res.returncode == 2, res.stderr
    assert "BASE_DATA[1]" in res.stdout and "not a regular file" in res.stdout + res.stderr


def test_a_pipe_in_one_batch_entry_fails_that_entry_only(tmp_path):
    shutil.copy(KUKA, tmp_path / "$config.dat")
    shutil.copy(MEAS, tmp_path / "good.csv")
    fifo(tmp_path / "pipe.csv")
    (tmp_path / "station.toml").write_text(
        f'[defaults]\ncontroller = "$config.dat"\nframe = "BASE_DATA[1]"\n'
        f'tcp = [{TCP}]\ntolerance = 100000.0\n'
        '[[entry]]\nname = "piped"\nmeasurement = "pipe.csv"\n'
        '[[entry]]\nname = "good"\nmeasurement = "good.csv"\n')
    res = run("batch", tmp_path / "station.toml", "--json")
    assert res.returncode == 1, res.stderr
    piped, good = json.loads(res.stdout)["entries"]
    assert piped["status"] == "error" and "not a regular file" in piped["error"]
    assert good["status"] == "pass"
    # the manifest itself
    m = fifo(tmp_path / "pipe.toml")
    one_error_line(run("batch", m), str(m))
