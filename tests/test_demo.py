"""ucsio demo: the shipped example cells, end to end, from any folder."""
from __future__ import annotations

import json
import subprocess
import sys
from importlib import resources

import pytest

from ucsio.parsing.controller import load
from ucsio.demo import CELLS


def not_run() -> list[str]:
    """The cells whose robot side this ucsio cannot read yet (R05 until
    Yaskawa's jobs are read): the demo lists them apart."""
    from ucsio.demo import data_root, robot_side_missing
    from pathlib import Path
    with resources.as_file(data_root()) as root:
        return [c.name for c in CELLS if robot_side_missing(c, Path(root))]


# the cells whose vendor refuses to patch its files, for a stated reason (Stäubli's
# rotation order, not proved): their patch step is reported as not run
REFUSED = ("R06",)

# the date a generated Yaskawa job carries: the same in the demo and in its replay
EPOCH = {"SOURCE_DATE_EPOCH": "1764763200"}


def refused(cell: dict) -> str | None:
    """Why the cell's patch step did not run (its vendor refuses to patch its files)."""
    return next((s["why"] for s in cell["skipped"] if s["step"] == "patch"), None)


def run(tmp_path, *args):
    import os
    return subprocess.run([sys.executable, "-m", "ucsio", "demo", *args], cwd=tmp_path,
                          capture_output=True, text=True, timeout=120,
                          env=dict(os.environ, **EPOCH))


def test_demo_data_is_package_data():
    root = resources.files("ucsio.demo").joinpath("data")
    for cell in CELLS:
        for rel in (cell.controller, cell.config, cell.measurement, cell.robot, *cell.extra):
            assert rel is None or root.joinpath(rel).is_file()


def test_demo_text(tmp_path):
    r = run(tmp_path)
    assert r.returncode == 0, r.stderr
    out = r.stdout
    for needle in ("cell R01 (KUKA)", "cell R02 (ABB)", "EXCLUDED (auto)", "accepted",
                   "group 1, PASS", "--- a/R01_kuka/$config.dat", "+BASE_DATA[3]={X 6125.",
                   "--- a/R02_abb/CellR02.mod", "cell R03 (KUKA)", "solved with the frame",
                   "+TOOL_DATA[2]={X 0.8", "+BASE_DATA[1]={X 3252.8",
                   "cell R04 (FANUC)", "UFRAME[1:PALLET]=PR[20] ;", "+  X:  2104.6",
                   "taught points in UF1: 6, moved in world by max",
                   "R04_fanuc/PALLET.LS:46", "cell R05 (Yaskawa)",
                   "cell R06 (Stäubli)", "3. patch: not run: Stäubli's rotation order",
                   "cell R07 (Universal Robots)", "--- a/R07_ur/cell.installation",
                   '+            <toolPosition value="0.5234'):
        assert needle in out
    if not_run() == ["R05"]:
        assert ("1. solve: not run: Yaskawa has no reader of robot positions yet: MEASURE.JBI "
                "is a Yaskawa Motoman job (JBI)") in out
        assert f"demo: {len(CELLS) - 1} of {len(CELLS)} cells run, every cell passes; not run " \
            "yet: R05" in out
    else:
        assert not_run() == [] and f"demo: {len(CELLS)} cells, every cell passes." in out
    assert list(tmp_path.iterdir()) == []          # nothing written


def test_demo_json_and_out(tmp_path):
    r = run(tmp_path, "--json", "--out", "patched")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["ok"] is True and len(CELLS) == 7
    assert [c["cell"] for c in d["not_run"]] == not_run()
    assert len(d["cells"]) + len(d["not_run"]) == len(CELLS)
    for cell in d["cells"]:
        assert cell["solve"]["accepted"] is True
        assert cell["solve"]["n_used"] == cell["solve"]["n_points"] - 1      # the blunder
        assert {"dx", "dy", "dz", "angle", "dt_mean", "group", "pass"} <= cell["diff"].keys()
        assert cell["diff"]["group"] == 1 and cell["diff"]["pass"] is True
        if refused(cell):           # the vendor's stated reason, and no patched copy
            assert cell["patch"] is None
            assert not (tmp_path / cell["folder"] / "patched").exists()
            continue
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
    assert d["ok"] and [c["cell"] for c in d["cells"]] == \
        [c for c in ["R01", "R02", "R03", "R04", "R05", "R06", "R07"] if c not in not_run()]


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
    env = dict(os.environ, PATH=f"{bindir}{os.pathsep}{os.environ['PATH']}", PYTHONPATH=src,
               **EPOCH)
    for cell in CELLS:
        folder = tmp_path / "out" / Path(cell.controller).parent.name
        ctl, meas = Path(cell.controller).name, Path(cell.measurement).name
        assert (folder / ctl).read_bytes() == data.joinpath(cell.controller).read_bytes()
        assert (folder / meas).read_bytes() == data.joinpath(cell.measurement).read_bytes()
        for rel in (cell.config, cell.robot, *cell.extra):
            if rel:
                assert (folder / Path(rel).name).read_bytes() == data.joinpath(rel).read_bytes()
        if cell.name in not_run():      # tests/test_demo_yaskawa.py: its replay runs nothing
            assert not (folder / "solution.json").exists()
            continue
        demo_solution = json.loads((folder / "solution.json").read_text())
        if cell.name in REFUSED:        # no patched copy: the replay solves and diffs
            assert not (folder / "patched").exists()
            replay = shutil.copytree(folder, tmp_path / "replay" / folder.name)
            (replay / "solution.json").unlink()
            res = subprocess.run(["sh", str(replay / "replay.sh")], capture_output=True,
                                 text=True, env=env, timeout=120)
            assert res.returncode == 0, res.stderr
            assert json.loads((replay / "solution.json").read_text())["frame"] == \
                demo_solution["frame"]
            assert not (replay / "patched").exists() and "PASS" in res.stdout
            continue
        demo_patched = (folder / "patched" / ctl).read_bytes()
        made = [Path("solution.json"), Path("patched") / ctl]
        if cell.program_file and (folder / cell.program_file).exists():
            made.append(Path(cell.program_file))
        demo_made = {m: (folder / m).read_bytes() for m in made}
        replay = shutil.copytree(folder, tmp_path / "replay" / folder.name)
        for m in made:
            (replay / m).unlink()
        res = subprocess.run(["sh", str(replay / "replay.sh")], capture_output=True, text=True,
                             env=env, timeout=120)
        assert res.returncode == 0, res.stderr
        assert json.loads((replay / "solution.json").read_text())["frame"] == demo_solution["frame"]
        assert (replay / "patched" / ctl).read_bytes() == demo_patched
        for m in made[1:]:                  # the patched copy, the program: byte for byte
            assert (replay / m).read_bytes() == demo_made[m], m
        # step 0, the measurement program, into ../measure: the demo's, byte for byte
        if cell.measure_file and (tmp_path / "out" / "measure" / cell.measure_file).exists():
            again = tmp_path / "replay" / "measure" / cell.measure_file
            assert again.read_bytes() == \
                (tmp_path / "out" / "measure" / cell.measure_file).read_bytes()
        assert f"~ {cell.frame}" in res.stdout or "value changed" in res.stdout


def test_demo_out_writes_each_cells_measurement_program(tmp_path):
    """issue 28 point 4: OUT/measure holds each cell's measurement program
    where its vendor has a writer (else the cell says why in ``skipped``):
    read back through the robot reader and solved against the cell's laser
    points, it gives the simulated frame (the program moves in it), every
    point paired by its name."""
    from pathlib import Path

    from ucsio import api, vendors
    r = run(tmp_path, "--out", "out", "--json")
    doc = json.loads(r.stdout)
    data = resources.files("ucsio.demo").joinpath("data")
    written = 0
    for cell, got in zip(CELLS, doc["cells"]):
        m = got.get("measurement_program")
        if cell.measure_file is None:       # no measurement program in the cell (R06, R07)
            assert m is None and all(s["step"] != "measure" for s in got["skipped"])
            continue
        if vendors.get(cell.vendor).measurement_program is None:
            assert m is None and any(s["step"] == "measure" and "no measurement program "
                                     "writer" in s["why"] for s in got["skipped"])
            continue
        out = tmp_path / "out" / "measure" / cell.measure_file
        assert m["written"] == str(Path("out") / "measure" / cell.measure_file) or \
            Path(m["written"]).resolve() == out.resolve()
        side = m["read_back"]                   # how solve reads it: the program says
        with resources.as_file(data) as root:
            solved = api.solve(laser=Path(root) / cell.measurement,
                               robot=out.parent / Path(side["robot"]).name,
                               config=[str(Path(root) / f) for f in side["config"]],
                               tool=str(Path(root) / side["tool"]),
                               robot_tool=side.get("robot_tool", "tool0"),
                               robot_wobj=side.get("robot_wobj", "wobj0"),
                               no_exclusion=True).as_dict()
            sim = load(Path(root) / cell.controller).frame(cell.frame).pose
        assert solved["n_used"] == solved["n_points"] == len(m["points"])
        f = solved["frame"]
        assert abs(f["x"] - sim.t[0]) < 2e-3 and abs(f["y"] - sim.t[1]) < 2e-3 \
            and abs(f["z"] - sim.t[2]) < 2e-3
        written += 1
    assert written >= 2                             # FANUC and Yaskawa at least


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


def test_demo_fanuc_cell_end_to_end(tmp_path):
    """R04 (issue 19 point 8): the tracker's point table and the measurement
    program MEASURE.LS (positions taught with the reflector UT2 in world);
    the true UF1 of make_demo.py comes back, the blunder M6 is excluded, the
    generated program sets UF1 from a register POSREG.VA shows unused, keeps
    the frame's comment, and reads back as the solution; the listing's copy
    changes that frame alone; the replay's diff --points moves the six
    Cartesian positions of PALLET.LS and skips its joint one."""
    import os
    from pathlib import Path

    from ucsio.parsing.controller import load as load_file
    r = run(tmp_path, "--json", "--out", "out")
    assert r.returncode == 0, r.stderr
    cell = json.loads(r.stdout)["cells"][3]
    assert (cell["cell"], cell["vendor"], cell["frame"], cell["label"]) == \
        ("R04", "fanuc", "UF1", "PALLET")
    m = cell["solve"]["frame"]
    true = (2104.650, -652.380, 418.910, 0.210, -0.140, 90.380)     # make_demo.R04_TRUE_UF
    assert [m[k] for k in "xyz"] == pytest.approx(true[:3], abs=0.15)
    assert [m[k] for k in ("w", "p", "r")] == pytest.approx(true[3:], abs=0.02)
    assert [p["name"] for p in cell["solve"]["points"] if not p["used"]] == ["M6"]
    prog = cell["program"]
    assert (prog["name"], prog["pr"], prog["pr_from"]) == ("SET_UF1", 20, "POSREG.VA")
    folder = tmp_path / "out" / "R04_fanuc"
    written = folder / "SET_UF1.LS"
    assert written.read_bytes() == prog["text"].encode("ascii") and b"\r\n/END\r\n" in \
        written.read_bytes()
    (uf1,) = load_file(written).frames
    assert (uf1.name, uf1.label) == ("UF1", "PALLET")
    assert [uf1.pose.x, uf1.pose.y, uf1.pose.z] == pytest.approx([m["x"], m["y"], m["z"]],
                                                                 abs=5e-4)
    original = (folder / "SYSFRAME.VA").read_bytes().split(b"\r\n")
    copy = (folder / "patched" / "SYSFRAME.VA").read_bytes().split(b"\r\n")
    assert len(original) == len(copy)
    assert [k for k, (a, b) in enumerate(zip(original, copy)) if a != b] == [3, 4]
    bindir = tmp_path / "bin"
    bindir.mkdir()
    (bindir / "ucsio").write_text(f"#!/bin/sh\nexec {sys.executable} -m ucsio \"$@\"\n")
    (bindir / "ucsio").chmod(0o755)
    env = dict(os.environ, PATH=f"{bindir}{os.pathsep}{os.environ['PATH']}",
               PYTHONPATH=str(Path(__file__).resolve().parents[1] / "src"))
    res = subprocess.run([sys.executable, "-m", "ucsio", "diff", "SYSFRAME.VA", "--frame", "UF1",
                          "--measured", "solution.json", "--points", "--json"], cwd=folder,
                         env=env, capture_output=True, text=True)
    d = json.loads(res.stdout)
    assert d["points_moved"]["count"] == 6 and d["points_skipped"] == 1
    assert {p["file"] for p in d["points"]} == {"PALLET.LS"}
