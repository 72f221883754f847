"""Issue 20 points 2 and 3, after measuring: the predicted 95 % error at the
working points (solve --at, diff --points, batch at = "..."), the gate judged
there (--gate at, gate = "at"), and the noise check (consistency).

Truth is synthetic: a known frame, known noise; the predictions are checked
against the plan made before (the same covariance), against scipy's chi²,
and the plain-math path diff takes against numpy's."""
from __future__ import annotations

import contextlib
import csv
import io
import json
import shutil
import subprocess
import sys

import numpy as np
import pytest
from scipy import stats
from scipy.spatial.transform import Rotation

from conftest import FIXTURES
from ucsio.cli import main

TRUTH = Rotation.from_euler("ZYX", [30.5, -2.4, 1.0], degrees=True)
T = np.array([1501.0, -249.0, 600.5])


def run(*args) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in args])
    return code, out.getvalue(), err.getvalue()


def laser_points(seed=1, n=8, dims=(1200, 800, 300)):
    return np.random.default_rng(seed).uniform(-0.5, 0.5, (n, 3)) * dims + [600, 400, 150]


def write_measurement(path, laser, noise=0.02, seed=2):
    robot = TRUTH.apply(laser) + T + np.random.default_rng(seed).normal(0, noise, laser.shape)
    rows = ["point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c"]
    rows += [f"P{i + 1}," + ",".join(repr(float(v)) for v in (*p, *r)) + ",0,0,0"
             for i, (p, r) in enumerate(zip(laser, robot))]
    path.write_text("\n".join(rows) + "\n")
    return path


def write_points(path, xyz, prefix="W"):
    path.write_text("point,x,y,z\n" + "".join(
        f"{prefix}{i + 1},{p[0]!r},{p[1]!r},{p[2]!r}\n" for i, p in enumerate(np.asarray(xyz).tolist())))
    return path


WORK = np.array([[0, 0, 0], [2500, 0, 0], [0, 1800, 400], [600, 400, 1500], [-900, -700, 0.0]])


# ------------------------------------------------------------------ solve --at

def test_solve_at_gives_what_the_plan_predicted(tmp_path):
    """Before and after: with the stated noise setting σ, solve --at predicts
    at each working point what plan predicted from the planned points (the
    same covariance; the fit's geometry is the planned one)."""
    laser = laser_points()
    meas = write_measurement(tmp_path / "m.csv", laser)
    at = write_points(tmp_path / "at.csv", WORK)
    rc, out, _ = run("solve", meas, "--tcp", "0,0,0", "--at", at, "--json")
    sol = json.loads(out)
    assert rc == 0 and sol["accepted"] and sol["precision"]["sigma_source"] == "stated"
    plan = tmp_path / "plan.csv"
    plan.write_text("point,laser_x,laser_y,laser_z\n" + "".join(
        f"P{i + 1},{p[0]!r},{p[1]!r},{p[2]!r}\n" for i, p in enumerate(laser.tolist())))
    rc, out, _ = run("plan", plan, "--at", at, "--json", "--sigma-laser", "0.015",
                     "--sigma-robot", "0.05")                    # solve's stated noise
    planned = json.loads(out)
    got = {w["name"]: w["at_95"] for w in sol["working_points"]}
    want = {w["name"]: w["at_95"] for w in planned["working_points"]}
    assert got.keys() == want.keys() == {f"W{i + 1}" for i in range(len(WORK))}
    for k in got:
        assert got[k] == pytest.approx(want[k], rel=1e-3)
    worst = max(got, key=got.get)
    assert sol["worst"]["name"] == worst and sol["worst"]["at_95"] == max(got.values())
    assert got["W1"] < min(got[k] for k in got if k != "W1")     # the fixture's own corner
    assert sol["at"] == str(at) and sol["gate"] == "reach"
    # the table shows them, worst first
    rc, out, _ = run("solve", meas, "--tcp", "0,0,0", "--at", at)
    assert "working points from" in out and f"worst working point: {worst} within" in out
    assert out.index(f"\n{worst} ") < out.index("\nW1 ")


def test_gate_at_judges_the_worst_working_point(tmp_path):
    """A fixture the generic gate accepts fails where the robot works 4 m
    away; one whose generic point (--reach 6000) fails passes when its working
    points are near the fixture."""
    laser = laser_points(3, 6, (500, 350, 60))
    meas = write_measurement(tmp_path / "m.csv", laser, noise=0.05)
    far = write_points(tmp_path / "far.csv", [[4000, 3000, 0], [0, 0, 0]])
    near = write_points(tmp_path / "near.csv", [[500, 300, 100], [700, 500, 0]])
    assert run("solve", meas, "--tcp", "0,0,0")[0] == 0
    rc, out, _ = run("solve", meas, "--tcp", "0,0,0", "--at", far, "--gate", "at", "--json")
    d = json.loads(out)
    assert rc == 1 and not d["accepted"] and d["gate"] == "at"
    assert "where the robot works" in d["reason"] and "W1" in d["reason"]
    assert d["worst"]["at_95"] > 1.5 > d["precision"]["at_reach"]
    assert run("solve", meas, "--tcp", "0,0,0", "--reach", "6000")[0] == 1
    rc, out, _ = run("solve", meas, "--tcp", "0,0,0", "--reach", "6000", "--at", near, "--gate",
                     "at", "--json")
    d = json.loads(out)
    assert rc == 0 and d["accepted"] and d["precision"]["at_reach"] > 1.5
    # --gate at without working points is a usage error
    rc, _, err = run("solve", meas, "--tcp", "0,0,0", "--gate", "at")
    assert rc == 2 and "--at FILE" in err


def test_gate_at_with_a_solved_tcp(tmp_path):
    from test_tcp_solve import cell, csv_of

    meas, R, t = cell(4, 30)
    csv_path = csv_of(meas, tmp_path / "m.csv")
    far = write_points(tmp_path / "far.csv", [[20000, 0, 0]])
    rc, out, _ = run("solve", csv_path, "--tcp", "solve", "--at", far, "--json")
    d = json.loads(out)
    assert rc == 0 and d["worst"]["at_95"] > 1.5 and d["consistency"]["dof"] == 3 * 8 - 9
    assert d["tcp_at_95"] == d["tcp"]["at_95"] == d["precision"]["tcp_at_95"]
    assert d["orientation_span"] == d["precision"]["orientation_span"] > 30
    rc, out, _ = run("solve", csv_path, "--tcp", "solve", "--at", far, "--gate", "at", "--json")
    assert rc == 1 and "where the robot works" in json.loads(out)["reason"]
    # diff --points with that solution: the taught points' errors, the TCP's doubt and span
    sol = tmp_path / "sol.json"
    assert run("solve", csv_path, "--tcp", "solve", "-o", sol)[0] == 0
    shutil.copytree(FIXTURES / "taught" / "kuka" / "KRC", tmp_path / "KRC")
    config = next((tmp_path / "KRC").rglob("$config.dat"))
    rc, out, _ = run("diff", config, "--frame", "BASE_DATA[3]", "--measured", sol, "--points",
                     "--json", "--tolerance", "1e9")
    got = json.loads(out)
    assert rc == 0 and got["worst"]["at_95"] > 0 and got["tcp_at_95"] == d["tcp_at_95"]
    assert got["orientation_span"] == d["orientation_span"]


@pytest.mark.parametrize("body, where, words", [
    ("point,x,y,z\nW1,1,2,3\nW2,1,x2,3\n", ":3:6:", "y not a number"),
    ("point,x,y,z\nW1,1,2,3\nW2,1,2\n", ":3:7:", "expected 4 fields"),
    ("point;x;y;z\nW1;1;2;3\nW1;4,5;2;3\n", ":3:1:", "duplicate point name"),
    ("point,x,y,z\nW1,1,2,nan\n", ":2:8:", "not finite"),
    ("point,x,y,z\nW1,1,2,3,4\n", ":2:10:", "5 fields"),
    ("point,x,y\nW1,1,2\n", ":1:", "missing column z"),
])
@pytest.mark.parametrize("command", ["solve", "plan-at", "plan-candidates"])
def test_a_bad_working_point_or_candidate_file_names_its_line(tmp_path, body, where, words,
                                                              command):
    laser = laser_points()
    meas = write_measurement(tmp_path / "m.csv", laser)
    bad = tmp_path / "bad.csv"
    bad.write_text(body)
    args = {"solve": ["solve", meas, "--tcp", "0,0,0", "--at", bad],
            "plan-at": ["plan", meas, "--at", bad],
            "plan-candidates": ["plan", meas, "--candidates", bad]}[command]
    rc, out, err = run(*args)
    assert rc == 2 and out == "" and err.count("\n") == 1
    assert f"{bad}{where}" in err and words in err
    rc, out, _ = run(*args, "--json")
    assert rc == 2 and words in json.loads(out)["error"]["message"]


# ------------------------------------------------------------------ diff --points

def _kuka_cell(tmp_path):
    """The taught-points fixture's KRC tree (BASE_DATA[3] with E6POS), a
    measurement of it and its solution."""
    shutil.copytree(FIXTURES / "taught" / "kuka" / "KRC", tmp_path / "KRC")
    meas = write_measurement(tmp_path / "m.csv", laser_points(5, 8), noise=0.03)
    sol = tmp_path / "sol.json"
    assert run("solve", meas, "--tcp", "0,0,0", "-o", sol)[0] == 0
    config = next((tmp_path / "KRC").rglob("$config.dat"))
    return config, sol


def test_diff_points_gives_the_predicted_error_beside_the_displacement(tmp_path):
    from ucsio.method import working
    from ucsio.readers.points import Points

    config, sol = _kuka_cell(tmp_path)
    rc, out, _ = run("diff", config, "--frame", "BASE_DATA[3]", "--measured", sol, "--points",
                     "--json", "--tolerance", "1e6")
    d = json.loads(out)
    assert rc == 0 and d["points_moved"]["count"] > 0
    assert all(r["at_95"] > 0 for r in d["points"])
    wp = d["working_points"]
    assert len(wp) == len(d["points"]) and all("moved" in w and "file" in w for w in wp)
    assert d["worst"]["at_95"] == max(w["at_95"] for w in wp)
    # the plain-math numbers diff prints are numpy's
    data = json.loads(sol.read_text())
    pts = Points(None, [w["name"] for w in wp], [None] * len(wp),
                 np.array([[w["x"], w["y"], w["z"]] for w in wp]))
    rows, _ = working.predict(data["covariance"], np.array(data["frame"]["matrix"])[:3, :3], pts)
    assert [w["at_95"] for w in wp] == pytest.approx([r["at_95"] for r in rows], rel=1e-12)
    rc, out, _ = run("diff", config, "--frame", "BASE_DATA[3]", "--measured", sol, "--points",
                     "--tolerance", "1e6")
    assert "95 % mm" in out and "known within" in out
    # a solution without its covariance (older, or by hand): the displacements alone
    old = json.loads(sol.read_text())
    del old["covariance"]
    sol.write_text(json.dumps(old))
    rc, out, _ = run("diff", config, "--frame", "BASE_DATA[3]", "--measured", sol, "--points",
                     "--json", "--tolerance", "1e6")
    d = json.loads(out)
    assert rc == 0 and "worst" not in d and all("at_95" not in r for r in d["points"])


def test_diff_points_with_predictions_imports_no_numpy(tmp_path):
    config, sol = _kuka_cell(tmp_path)
    probe = ("import sys, io, contextlib\nfrom ucsio.cli import main\n"
             "with contextlib.redirect_stdout(io.StringIO()):\n    code = main(sys.argv[1:])\n"
             "print(code, 'numpy' in sys.modules)\n")
    res = subprocess.run([sys.executable, "-c", probe, "diff", str(config), "--frame",
                          "BASE_DATA[3]", "--measured", str(sol), "--points", "--tolerance",
                          "1e6"], capture_output=True, text=True, check=True)
    assert res.stdout.split() == ["0", "False"]


def test_abb_taught_points_are_working_points_in_the_user_frame(tmp_path):
    """A robtarget is in the object frame: as a working point of the user
    frame it goes through the object frame first (diff --points and plan
    --at-taught agree)."""
    root = FIXTURES / "taught" / "abb"
    mods = sorted(root.glob("*.mod"))
    from ucsio.parsing.controller import load
    from ucsio.taught import find_points, in_ucs
    for mod in mods:
        cf = load(mod)
        for frame in cf.frames:
            if frame.type != "wobjdata" or frame.info.get("component") == "oframe":
                continue
            found = find_points(cf, frame)
            if not found.points:
                continue
            of = cf.frame(frame.name + ".oframe").pose
            got = in_ucs(cf, frame, found)
            for p, q in zip(found.points, got):
                want = Rotation.from_quat(of.q, scalar_first=True).apply(p.xyz) + of.t
                assert q == pytest.approx(tuple(want), abs=1e-9)
            return
    pytest.skip("no wobj with taught points in fixtures/taught/abb")


# ------------------------------------------------------------------ batch

def test_batch_at_and_gate(tmp_path):
    shutil.copy(FIXTURES / "measurements" / "abb_wobj.csv", tmp_path / "m.csv")
    (tmp_path / "cell.mod").write_text(
        'MODULE cell\n  PERS wobjdata w:=[FALSE,TRUE,"",[[6125,2445,1169],[1,0,0,0]],'
        '[[0,0,0],[1,0,0,0]]];\nENDMODULE\n')
    write_points(tmp_path / "near.csv", [[100, 100, 0], [400, 300, 50]])
    write_points(tmp_path / "far.csv", [[30000, 0, 0], [0, 0, 0]])
    (tmp_path / "m.toml").write_text(
        "[defaults]\nmeasurement = 'm.csv'\ncontroller = 'cell.mod'\nframe = 'w'\n"
        "tcp = [1.5, -2, 182.3]\ntolerance = 1e6\n"
        "[[entry]]\nname = 'near'\nat = 'near.csv'\n"
        "[[entry]]\nname = 'far, reported'\nat = 'far.csv'\n"
        "[[entry]]\nname = 'far, gated'\nat = 'far.csv'\ngate = 'at'\n"
        "[[entry]]\nname = 'gate without at'\ngate = 'at'\n"
        "[[entry]]\nname = 'no such file'\nat = 'nope.csv'\n"
        "[[entry]]\nname = 'plain'\n")
    report = tmp_path / "r.html"
    out_csv = tmp_path / "out.csv"
    rc, out, _ = run("batch", tmp_path / "m.toml", "--json", "--report", report, "--csv", out_csv)
    near, far, gated, bad_gate, missing, plain = json.loads(out)["entries"]
    assert rc == 1
    assert near["accepted"] and near["worst"]["at_95"] < 1.5 and len(near["working_points"]) == 2
    assert far["accepted"] and far["worst"]["name"] == "W1" and far["worst"]["at_95"] > 1.5
    assert not gated["accepted"] and "where the robot works" in gated["reason"]
    assert gated["gate"] == "at" and far["gate"] == "reach"
    assert bad_gate["stage"] == "manifest" and "at = " in bad_gate["error"]
    assert missing["stage"] == "at" and "nope.csv" in missing["error"]
    assert "worst" not in plain and plain["consistency"]["dof"] == 3 * plain["n_used"] - 6
    # the table, the CSV and the report carry the worst working point
    rc, out, _ = run("batch", tmp_path / "m.toml")
    assert "worst working point (95 %)" in out and f"W1 {far['worst']['at_95']:.3f}" in out
    rows = {r["name"]: r for r in csv.DictReader(out_csv.open())}
    assert float(rows["far, reported"]["worst_at_95"]) == pytest.approx(far["worst"]["at_95"])
    assert rows["plain"]["worst_point"] == ""
    html = report.read_text().split('<script type="application/json"', 1)[0]
    assert "worst working point" in html and "working-points" in html
    assert f"{far['worst']['at_95']:.3f}" in html and "Where the robot works" in html
    # a bad gate value is the entry's error
    (tmp_path / "bad.toml").write_text(
        "[[entry]]\nname = 'x'\nmeasurement = 'm.csv'\ncontroller = 'cell.mod'\nframe = 'w'\n"
        "tcp = [0, 0, 0]\ngate = 'everywhere'\n")
    rc, out, _ = run("batch", tmp_path / "bad.toml", "--json")
    (x,) = json.loads(out)["entries"]
    assert "gate must be" in x["error"]


# ------------------------------------------------------------------ the noise check

def test_noise_check_compares_the_residuals_with_the_stated_noise(tmp_path):
    laser = laser_points(8, 8)
    loud = write_measurement(tmp_path / "loud.csv", laser, noise=0.3)
    quiet = write_measurement(tmp_path / "quiet.csv", laser, noise=0.03)
    rc, out, _ = run("solve", loud, "--tcp", "0,0,0", "--json", "--threshold", "3")
    d = json.loads(out)
    c = d["consistency"]
    r = np.array([p["residual"] for p in d["points"] if p["used"]])
    stated = np.hypot(0.015, 0.05)
    dof = 3 * len(r) - 6
    assert c["dof"] == dof
    assert c["ratio"] == pytest.approx(np.sqrt((r ** 2).sum() / dof) / stated)
    assert c["p"] == pytest.approx(stats.chi2.sf((r ** 2).sum() / stated ** 2, dof), rel=1e-9)
    assert c["p"] < 0.01 and "the tracker, the robot or the stated σ" in c["message"]
    rc, out, _ = run("solve", loud, "--tcp", "0,0,0", "--threshold", "3")
    assert "noise check: the residuals show" in out
    rc, out, _ = run("solve", quiet, "--tcp", "0,0,0", "--json")
    c = json.loads(out)["consistency"]
    assert c["p"] > 0.01 and "message" not in c
    assert "noise check" not in run("solve", quiet, "--tcp", "0,0,0")[1]
    # stated as the truth: p spread evenly, seldom below 0.01
    from ucsio.method.solve import solve_points
    ps = []
    for seed in range(200):
        rng = np.random.default_rng(seed)
        robot = TRUTH.apply(laser) + T + rng.normal(0, stated, laser.shape)
        ps.append(solve_points([f"P{i}" for i in range(8)], laser, robot,
                               no_exclusion=True).consistency["p"])
    assert 0.4 < np.mean(ps) < 0.6 and np.mean(np.array(ps) < 0.01) < 0.04


@pytest.mark.parametrize("ending", ["\n", "\r\n", "\r", "\r\r\n"])
def test_working_point_files_follow_the_one_rule_for_line_endings(tmp_path, ending):
    from ucsio.readers.points import read_points

    f = tmp_path / "at.csv"
    f.write_bytes(ending.join(["# where the robot works", "point;x;y;z", "A;1,5;2;3",
                               "B;4;5;6", ""]).encode())
    got = read_points(f)
    assert got.names == ["A", "B"] and got.lines == [3, 4] and got.xyz[0].tolist() == [1.5, 2, 3]
    f.write_bytes(ending.join(["point,x,y,z", "A,1,2,3", "B,4,5,6,7", ""]).encode())
    with pytest.raises(Exception, match=r":3:9: 5 fields"):
        read_points(f).names
