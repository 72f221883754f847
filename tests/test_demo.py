"""ucsio demo: the shipped example cells, end to end, from any folder."""
from __future__ import annotations

import json
import subprocess
import sys
from importlib import resources

import pytest

from ucsio.parsing.controller import load
from ucsio.demo import CELLS


def run(tmp_path, *args):
    return subprocess.run([sys.executable, "-m", "ucsio", "demo", *args], cwd=tmp_path,
                          capture_output=True, text=True, timeout=120)


def test_demo_data_is_package_data():
    root = resources.files("ucsio.demo").joinpath("data")
    for cell in CELLS:
        assert root.joinpath(cell.controller).is_file()
        assert root.joinpath(cell.measurement).is_file()


def test_demo_text(tmp_path):
    r = run(tmp_path)
    assert r.returncode == 0, r.stderr
    out = r.stdout
    for needle in ("cell R01 (KUKA)", "cell R02 (ABB)", "EXCLUDED (auto)", "accepted",
                   "group 1, PASS", "--- a/R01_kuka/$config.dat", "+BASE_DATA[3]={X 6125.",
                   "--- a/R02_abb/CellR02.mod", "cell R03 (KUKA)", "solved with the frame",
                   "+TOOL_DATA[2]={X 0.8", "+BASE_DATA[1]={X 3252.8",
                   "demo: 3 cells, every cell passes."):
        assert needle in out
    assert list(tmp_path.iterdir()) == []          # nothing written


def test_demo_json_and_out(tmp_path):
    r = run(tmp_path, "--json", "--out", "patched")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["ok"] is True and len(d["cells"]) == 3
    for cell in d["cells"]:
        assert cell["solve"]["accepted"] is True
        assert cell["solve"]["n_used"] == cell["solve"]["n_points"] - 1      # the blunder
        assert {"dx", "dy", "dz", "angle", "dt_mean", "group", "pass"} <= cell["diff"].keys()
        assert cell["diff"]["group"] == 1 and cell["diff"]["pass"] is True
        assert cell["patch"]["diff"].startswith("--- a/")
        written = tmp_path / cell["patch"]["written"]
        got = load(written).frame(cell["frame"]).pose
        m = cell["solve"]["frame"]
        assert abs(got.x - m["x"]) <= 5e-4 and abs(got.y - m["y"]) <= 5e-4 \
            and abs(got.z - m["z"]) <= 5e-4
    kuka = d["cells"][0]
    # SPEC's example cell: the simulated base of SPEC's diff, measured near SPEC's numbers
    assert kuka["diff"]["simulated"]["x"] == pytest.approx(6130.0)
    assert kuka["diff"]["dt_mean"] == pytest.approx(5.892, abs=0.05)


def test_demo_api():
    from ucsio import api
    d = api.demo()
    assert d["ok"] and [c["cell"] for c in d["cells"]] == ["R01", "R02", "R03"]


def test_demo_gate_and_bad_out(tmp_path):
    # a tolerance the shipped cells (dt_mean ~6 mm) cannot meet: the gate fails, exit 1
    res = run(tmp_path, "--tolerance", "5")
    assert res.returncode == 1 and "failed its gate" in res.stdout
    (tmp_path / "a_file").write_text("")
    res = run(tmp_path, "--out", str(tmp_path / "a_file"))
    assert res.returncode == 2 and res.stderr.count("\n") == 1 and "--out" in res.stderr


def test_demo_out_writes_inputs_and_a_replay_that_gives_the_same_results(tmp_path):
    """issue 11 point 7: the inputs beside the patched files, and every step
    replayable by hand: replay.sh's commands give the demo's own solution and
    patched file."""
    import os
    import shutil
    from pathlib import Path
    r = run(tmp_path, "--out", "out")
    assert r.returncode == 0, r.stderr
    assert "wrote" not in r.stdout and r.stderr.count("replay.sh") == len(CELLS)
    data = resources.files("ucsio.demo").joinpath("data")
    bindir = tmp_path / "bin"                     # `ucsio` as a user has it after pip install
    bindir.mkdir()
    shim = bindir / "ucsio"
    shim.write_text(f"#!/bin/sh\nexec {sys.executable} -m ucsio \"$@\"\n")
    shim.chmod(0o755)
    src = str(Path(__file__).resolve().parents[1] / "src")
    env = dict(os.environ, PATH=f"{bindir}{os.pathsep}{os.environ['PATH']}", PYTHONPATH=src)
    for cell in CELLS:
        folder = tmp_path / "out" / Path(cell.controller).parent.name
        ctl, meas = Path(cell.controller).name, Path(cell.measurement).name
        assert (folder / ctl).read_bytes() == data.joinpath(cell.controller).read_bytes()
        assert (folder / meas).read_bytes() == data.joinpath(cell.measurement).read_bytes()
        if cell.robot:
            robot = Path(cell.robot).name
            assert (folder / robot).read_bytes() == data.joinpath(cell.robot).read_bytes()
        demo_solution = json.loads((folder / "solution.json").read_text())
        demo_patched = (folder / "patched" / ctl).read_bytes()
        replay = shutil.copytree(folder, tmp_path / "replay" / folder.name)
        for p in (replay / "solution.json", replay / "patched" / ctl):
            p.unlink()
        res = subprocess.run(["sh", str(replay / "replay.sh")], capture_output=True, text=True,
                             env=env, timeout=120)
        assert res.returncode == 0, res.stderr
        assert json.loads((replay / "solution.json").read_text())["frame"] == demo_solution["frame"]
        assert (replay / "patched" / ctl).read_bytes() == demo_patched
        assert f"~ {cell.frame}" in res.stdout or "value changed" in res.stdout


def test_demo_third_cell_solves_the_tcp_and_patches_base_and_tool(tmp_path):
    """R03: a SpatialAnalyzer export and a KUKA measurement program; the true
    TCP (0.85, -1.40, 216.90, make_demo.py) 2.4 mm from the nominal one and
    the true base come back, and the patched copy carries both."""
    r = run(tmp_path, "--json", "--out", "out")
    assert r.returncode == 0, r.stderr
    cell = json.loads(r.stdout)["cells"][2]
    tcp = cell["solve"]["tcp"]
    assert tcp["solved"] is True
    assert [tcp[k] for k in "xyz"] == pytest.approx([0.85, -1.40, 216.90], abs=0.2)
    m = cell["solve"]["frame"]
    assert [m[k] for k in "xyz"] == pytest.approx([3252.84, -776.93, 641.72], abs=0.2)
    assert [p["name"] for p in cell["solve"]["points"] if not p["used"]] == ["P6"]
    patched = load(tmp_path / cell["patch"]["written"])
    assert patched.frame("SMR_adapter").pose.t == pytest.approx(
        (tcp["x"], tcp["y"], tcp["z"]), abs=5e-4)
    assert patched.frame("SMR_adapter").pose.abc == (0.0, 0.0, 0.0)
    assert {c["component"] for c in cell["patch"]["changes"]} >= {"x", "y", "z", "a"}
