"""``ucsio view`` without a browser: the scene's numbers against an
independent computation (scipy's Rotation), the SVG's circles, bad input
(exit 2 naming the file, nothing written), start-up without numpy."""
from __future__ import annotations

import contextlib
import io
import json
import re
import subprocess
import sys

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from ucsio.cli import main
from view_cases import matrix, write_case


def run(*args):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in args])
    return code, out.getvalue(), err.getvalue()


def scene_of(html: str) -> dict:
    m = re.search(r'<script type="application/json" id="ucsio-scene">(.*?)</script>', html, re.S)
    return json.loads(m.group(1))


@pytest.fixture(scope="module")
def case(tmp_path_factory):
    return write_case(tmp_path_factory.mktemp("view"), "blunder")


def test_kuka_matrix_of_the_cases_is_scipys():
    want = Rotation.from_euler("ZYX", [30, -2.5, 1.2], degrees=True).as_matrix()
    assert np.allclose(matrix(30, -2.5, 1.2), want, atol=1e-12)


def test_points_are_mapped_through_the_fit(case, tmp_path):
    out = tmp_path / "view.html"
    assert run("view", case["solution"], "-o", out)[0] == 0
    s = scene_of(out.read_text())
    sol = json.loads(case["solution"].read_text())
    f = sol["frame"]
    R = Rotation.from_quat([*f["q"][1:], f["q"][0]]).as_matrix()    # scipy: scalar last
    t = np.array([f["x"], f["y"], f["z"]])
    meas = np.genfromtxt(case["meas"], delimiter=",", skip_header=1)[:, 1:7]
    assert len(s["points"]) == len(sol["points"]) == 10
    for p, q, row in zip(s["points"], sol["points"], meas):
        assert p["name"] == q["name"]
        assert np.allclose(p["tracker"], R @ row[:3] + t, atol=1e-9)
        assert np.allclose(p["robot"], row[3:6], atol=1e-9)          # the CSV's flange, TCP 0
        assert p["residual"] == pytest.approx(q["residual"], abs=1e-9)
        assert p["used"] == q["used"]
    blunder = next(p for p in s["points"] if p["name"] == "P6")
    assert not blunder["used"] and blunder["residual"] > 3
    # the magnification is a round number, stated, and the drawn vector is d × it
    used = [p for p in s["points"] if p["used"]]
    assert s["magnify"] in {m * 10 ** k for m in (1, 2, 5) for k in range(8)}
    for p in used:
        assert np.allclose(p["drawn"], np.array(p["d"]) * s["magnify"])
    assert f"×{s['magnify']:g}" in out.read_text()


def test_the_simulated_frame_and_its_delta_are_diffs(case, tmp_path):
    out = tmp_path / "view.html"
    code, _, err = run("view", case["solution"], "--controller", case["config"],
                       "--frame", "BASE_DATA[3]", "-o", out)
    assert code == 0, err
    s = scene_of(out.read_text())
    sim = case["simulated"]
    assert np.allclose(s["simulated"]["origin"], [sim["x"], sim["y"], sim["z"]], atol=1e-9)
    want = Rotation.from_euler("ZYX", [sim["a"], sim["b"], sim["c"]], degrees=True).as_matrix()
    assert np.allclose(np.array(s["simulated"]["axes"]).T, want, atol=1e-9)
    code, d, _ = run("diff", case["config"], "--frame", "BASE_DATA[3]", "--measured",
                     case["solution"], "--json")
    d = json.loads(d)
    for k in ("dx", "dy", "dz", "angle", "dist", "dt_mean"):
        assert s["delta"][k] == pytest.approx(d[k], abs=1e-9)
    assert "Δ simulated → measured" in out.read_text()


def test_working_points_match_solve_at(case, tmp_path):
    out = tmp_path / "view.html"
    assert run("view", case["solution"], "--at", case["working"], "-o", out)[0] == 0
    s = scene_of(out.read_text())
    sol = json.loads(case["solution"].read_text())        # solve --at: numpy's numbers
    got = {w["name"]: w["at_95"] for w in s["working"]}
    for w in sol["working_points"]:
        assert got[w["name"]] == pytest.approx(w["at_95"], rel=1e-9)
    assert [w["name"] for w in s["working"] if w["worst"]] == [sol["worst"]["name"]]


def test_a_plan_draws_its_points(case, tmp_path):
    plan = tmp_path / "plan.json"
    code, text, _ = run("plan", case["meas"], "--tcp", "0,0,0", "--json")
    plan.write_text(text)
    out = tmp_path / "view.html"
    assert run("view", case["solution"], "--plan", plan, "-o", out)[0] == 0
    s = scene_of(out.read_text())
    doc = json.loads(text)
    assert [p["name"] for p in s["plan"]["points"]] == doc["points"]
    assert (s["plan"]["add"] is None) == ("add" not in (doc.get("suggest") or {}))


def test_each_projection_holds_one_circle_per_point(case, tmp_path):
    out = tmp_path / "view.html"
    run("view", case["solution"], "-o", out)
    html = out.read_text()
    for name in ("XY", "XZ", "YZ"):
        svg = re.search(rf'<svg id="svg-{name}".*?</svg>', html, re.S).group(0)
        assert svg.count("<circle") == 10
        assert len(re.findall(r'<circle class="point', svg)) == 10


def test_standard_output(case):
    code, out, _ = run("view", case["solution"], "-o", "-")
    assert code == 0 and out.startswith("<!DOCTYPE html>") and 'id="ucsio-scene"' in out


@pytest.mark.parametrize("content", ['{"x": 1}', "[1, 2]", "not json", '{"frame": {}, "points": []}'])
def test_not_a_solution_is_refused_and_nothing_written(tmp_path, content):
    bad = tmp_path / "bad.json"
    bad.write_text(content)
    out = tmp_path / "view.html"
    out.write_text("before")
    code, _, err = run("view", bad, "-o", out)
    assert code == 2
    assert str(bad) in err and err.count("\n") == 1
    assert out.read_text() == "before"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.json", "view.html"]


def test_a_solution_without_coordinates_says_solve_again(tmp_path, case):
    data = json.loads(case["solution"].read_text())
    for p in data["points"]:
        del p["laser"], p["robot"]
    old = tmp_path / "old.json"
    old.write_text(json.dumps(data))
    code, _, err = run("view", old, "-o", tmp_path / "v.html")
    assert code == 2 and "solve it again" in err and not (tmp_path / "v.html").exists()


def test_output_over_a_folder_or_in_a_missing_one_is_refused(tmp_path, case):
    folder = tmp_path / "dir"
    folder.mkdir()
    code, _, err = run("view", case["solution"], "-o", folder)
    assert code == 2 and "directory" in err and list(folder.iterdir()) == []
    code, _, err = run("view", case["solution"], "-o", tmp_path / "none" / "v.html")
    assert code == 2 and "does not exist" in err


def test_controller_without_frame_is_a_usage_error(case, tmp_path):
    code, _, err = run("view", case["solution"], "--controller", case["config"], "-o",
                       tmp_path / "v.html")
    assert code == 2 and "--frame" in err and not (tmp_path / "v.html").exists()


def test_view_imports_no_numpy_scipy_or_lark(case, tmp_path):
    """(--at reads its CSV with the working-point reader, which is numpy's.)"""
    probe = ("import sys, io, contextlib\nfrom ucsio.cli import main\n"
             "with contextlib.redirect_stderr(io.StringIO()):\n    code = main(sys.argv[1:])\n"
             "print(code, sorted(m for m in ('numpy', 'scipy', 'lark') if m in sys.modules))")
    res = subprocess.run([sys.executable, "-c", probe, "view", str(case["solution"]),
                          "--controller", str(case["config"]), "--frame", "BASE_DATA[3]",
                          "-o", str(tmp_path / "v.html")],
                         capture_output=True, text=True, check=True)
    assert res.stdout.split() == ["0", "[]"], res


def test_the_library_is_inlined_and_pinned(case, tmp_path):
    from ucsio.picture.page import three_version
    out = tmp_path / "v.html"
    run("view", case["solution"], "-o", out)
    html = out.read_text()
    assert f"three.js {three_version()}" in html and "var THREE=" in html
    assert not re.search(r'<script[^>]+src=|<link[^>]+href=|https?://(?!www\.w3\.org)', html)


def test_the_api_gives_the_scene_and_writes_the_page(case, tmp_path):
    from ucsio import api
    out = tmp_path / "v.html"
    s = api.view(case["solution"], controller=case["config"], frame="BASE_DATA[3]", output=out)
    assert scene_of(out.read_text()) == json.loads(json.dumps(s))
    assert s["delta"]["dist"] > 0 and len(s["points"]) == 10


def test_a_solved_tcp_gives_the_robot_points_it_found(tmp_path):
    """solve --tcp solve: each robot point is its flange pose applied to the
    solved TCP (scipy's rotation of the CSV's KUKA A, B, C)."""
    from conftest import FIXTURES
    meas = FIXTURES / "measurements" / "kuka_base3.csv"
    sol = tmp_path / "sol.json"
    run("solve", meas, "--tcp", "solve", "-o", sol)
    data = json.loads(sol.read_text())
    tcp = np.array([data["tcp"][k] for k in "xyz"])
    rows = np.genfromtxt(meas, delimiter=",", comments="#", skip_header=9)
    for p, row in zip(data["points"], rows):
        flange = Rotation.from_euler("ZYX", row[7:10], degrees=True).as_matrix()
        assert np.allclose(p["robot"], flange @ tcp + row[4:7], atol=1e-9)
        assert np.allclose(p["laser"], row[1:4], atol=1e-12)


def test_working_points_without_a_covariance_are_drawn_unknown(case, tmp_path):
    data = json.loads(case["solution"].read_text())
    del data["covariance"]
    sol = tmp_path / "sol.json"
    sol.write_text(json.dumps(data))
    out = tmp_path / "v.html"
    code, _, err = run("view", sol, "--at", case["working"], "-o", out)
    assert code == 0, err
    assert all(w["at_95"] is None for w in scene_of(out.read_text())["working"])
