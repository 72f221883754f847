"""Issue 20 points 1 and 5: ``ucsio plan``, before measuring.

Every prediction is checked against a Monte Carlo of the fit itself (Horn's
batched fit for a known TCP, the joint Gauss-Newton for a solved one) on
noisy copies of the planned measurement, over well- and badly-spread plans:
within 10 %. The suggestions are checked against a plain recomputation of
every candidate plan; the clustered plan of the issue is refused, and the
advice, followed, passes."""
from __future__ import annotations

import contextlib
import io
import json
import shutil

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from conftest import FIXTURES, ROOT
from ucsio.cli import main
from ucsio.method import horn, tcp_solve

SIGMA_LASER, SIGMA_ROBOT = 0.015, 0.05
DEMO = ROOT / "src" / "ucsio" / "demo" / "data"
UCS = Rotation.from_euler("ZYX", [35, -12, 4], degrees=True)
T_UCS = np.array([2500.0, 300.0, 700.0])
SAMPLES = 3000


def run(*args) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in args])
    return code, out.getvalue(), err.getvalue()


def plan_json(*args):
    """plan --json with the noise the Monte Carlos draw, unless ``args`` state one."""
    if not any(str(a).startswith(("--sigma-", "--history")) for a in args):
        args += ("--sigma-laser", SIGMA_LASER, "--sigma-robot", SIGMA_ROBOT)
    rc, out, err = run("plan", *args, "--json")
    assert rc in (0, 1), err
    return rc, json.loads(out)


def write_plan(path, laser, flange=None):
    """PLAN.csv: point, laser_*; with ``flange`` (n, 4, 4) the planned poses
    as robot_* (KUKA A, B, C)."""
    head = "point,laser_x,laser_y,laser_z"
    rows = []
    for i, p in enumerate(np.asarray(laser).tolist()):
        cells = [f"P{i + 1}"] + [repr(v) for v in p]
        if flange is not None:
            T = flange[i]
            abc = Rotation.from_matrix(T[:3, :3]).as_euler("ZYX", degrees=True)
            cells += [repr(float(v)) for v in (*T[:3, 3], *abc)]
        rows.append(",".join(cells))
    if flange is not None:
        head += ",robot_x,robot_y,robot_z,robot_a,robot_b,robot_c"
    path.write_text(head + "\n" + "\n".join(rows) + "\n")
    return path


def write_points(path, xyz, prefix="W"):
    path.write_text("point,x,y,z\n" + "".join(
        f"{prefix}{i + 1},{p[0]!r},{p[1]!r},{p[2]!r}\n"
        for i, p in enumerate(np.asarray(xyz, float).tolist())))
    return path


def mc_fixed(laser, work, samples=SAMPLES, seed=3):
    """95th percentile of |error| at each working point over Horn fits of
    noisy copies of the planned measurement (a known TCP)."""
    rng = np.random.default_rng(seed)
    n = len(laser)
    robot = UCS.apply(laser) + T_UCS
    nl = laser + rng.normal(0, SIGMA_LASER, (samples, n, 3))
    nr = robot + rng.normal(0, SIGMA_ROBOT, (samples, n, 3))
    fit = horn.horn_batch(nl, nr, np.ones((samples, n)))
    err = np.linalg.norm(fit.apply(np.broadcast_to(work, (samples,) + work.shape))
                         - (UCS.apply(work) + T_UCS), axis=2)
    return np.percentile(err, 95, axis=0)


PLANS = {   # name: (points, dims): well spread, flat, long and thin, a small cluster
    "spread": (8, (1200, 800, 300)),
    "flat": (6, (900, 600, 0)),
    "thin": (7, (1000, 60, 40)),
    "cluster": (5, (250, 180, 60)),
}


@pytest.mark.parametrize("name", PLANS)
def test_working_points_match_a_monte_carlo_of_the_fit(tmp_path, name):
    n, dims = PLANS[name]
    rng = np.random.default_rng(len(name))
    laser = rng.uniform(-0.5, 0.5, (n, 3)) * dims
    work = laser.mean(0) + rng.normal(0, 1, (12, 3)) * [900, 700, 300]
    _, got = plan_json(write_plan(tmp_path / "p.csv", laser), "--at",
                       write_points(tmp_path / "at.csv", work), "--threshold", "1000")
    pred = np.array([w["at_95"] for w in got["working_points"]])
    assert pred == pytest.approx(mc_fixed(laser, work), rel=0.10)
    # the generic point --reach from the centroid, as the gate takes it
    _, got = plan_json(tmp_path / "p.csv", "--threshold", "1000")
    (reach,) = got["working_points"]
    xyz = np.array([[reach["x"], reach["y"], reach["z"]]])
    assert np.linalg.norm(xyz - laser.mean(0)) == pytest.approx(1000.0)
    assert reach["at_95"] == pytest.approx(mc_fixed(laser, xyz)[0], rel=0.10)


def cell(seed, spread_deg, n=8, dims=(1000, 700, 250), tcp=(10.0, -25.0, 160.0)):
    """A planned cell with a solved TCP: laser points and flange poses (a
    downward flange turned up to ±spread_deg about each axis)."""
    rng = np.random.default_rng(seed)
    laser = rng.uniform(0, 1, (n, 3)) * dims
    world = UCS.apply(laser) + T_UCS
    flange = np.tile(np.eye(4), (n, 1, 1))
    for i in range(n):
        R = Rotation.from_euler("ZYX", [180, 0, 180], degrees=True) * Rotation.from_euler(
            "ZYX", rng.uniform(-spread_deg, spread_deg, 3), degrees=True)
        flange[i, :3, :3] = R.as_matrix()
        flange[i, :3, 3] = world[i] - R.apply(tcp)
    return laser, flange, np.array(tcp)


def mc_joint(laser, flange, tcp, work, samples=SAMPLES, seed=4):
    rng = np.random.default_rng(seed)
    n = len(laser)
    Rf, tf = flange[:, :3, :3], flange[:, :3, 3]
    nl = laser + rng.normal(0, SIGMA_LASER, (samples, n, 3))
    nt = tf + rng.normal(0, SIGMA_ROBOT, (samples, n, 3))
    R, t, x = tcp_solve.gauss_newton(nl, Rf, nt, np.ones((samples, n)),
                                     np.repeat(UCS.as_matrix()[None], samples, 0),
                                     np.repeat(T_UCS[None], samples, 0),
                                     np.repeat(tcp[None], samples, 0))
    fit = np.einsum("sij,wj->swi", R, work) + t[:, None, :]
    err = np.linalg.norm(fit - (UCS.apply(work) + T_UCS), axis=2)
    return np.percentile(err, 95, axis=0), np.percentile(np.linalg.norm(x - tcp, axis=1), 95)


@pytest.mark.parametrize("spread_deg, dims", [(30, (1000, 700, 250)), (8, (1000, 700, 250)),
                                              (25, (400, 300, 0))])
def test_a_solved_tcp_matches_a_monte_carlo_of_the_joint_fit(tmp_path, spread_deg, dims):
    laser, flange, tcp = cell(2, spread_deg, dims=dims)
    work = laser.mean(0) + np.random.default_rng(9).normal(0, 1, (8, 3)) * [900, 700, 300]
    _, got = plan_json(write_plan(tmp_path / "p.csv", laser, flange), "--tcp", "solve", "--at",
                       write_points(tmp_path / "at.csv", work), "--threshold", "1000")
    at95, tcp95 = mc_joint(laser, flange, tcp, work)
    assert [w["at_95"] for w in got["working_points"]] == pytest.approx(at95, rel=0.10)
    assert got["tcp_at_95"] == pytest.approx(tcp95, rel=0.10)
    spans = [np.degrees(np.linalg.norm(Rotation.from_matrix(a[:3, :3].T @ b[:3, :3]).as_rotvec()))
             for a in flange for b in flange]
    assert got["orientation_span"] == pytest.approx(max(spans), abs=1e-6)
    # a known TCP is a smaller problem: its working points are known better
    _, fixed = plan_json(tmp_path / "p.csv", "--at", tmp_path / "at.csv", "--threshold", "1000")
    assert fixed["worst"]["at_95"] < got["worst"]["at_95"] and "tcp_at_95" not in fixed


# ------------------------------------------------------------------ the verdict and advice

def test_the_clustered_plan_is_refused_and_the_advice_passes(tmp_path):
    """4 points in 200 x 150 mm, a working point 1.5 m away (robot noise 0.1
    mm): refused, with the point to add; added, the plan passes, and the fit
    of that plan, simulated, agrees."""
    laser = np.array([[0, 0, 0], [200, 0, 5], [200, 150, 0], [0, 150, 8.0]])
    work = np.array([[1500.0, 75.0, 0.0]])
    plan, at = write_plan(tmp_path / "p.csv", laser), write_points(tmp_path / "at.csv", work)
    args = ("--at", at, "--sigma-robot", "0.1")
    rc, got = plan_json(plan, *args)
    assert rc == 1 and got["verdict"] == "fail" and got["worst"]["at_95"] > 1.5
    assert "where the robot works" in got["reason"] and got["advice"].startswith("add a point")
    add = got["suggest"]["add"]
    assert add["worst_after"] <= 1.5 and add["from"] == "near planned points"
    assert 0 < add["nearest"]["distance"] <= 250.0                 # --margin's default
    rc, text, _ = run("plan", plan, *args)
    where = f"({add['x']:.1f}, {add['y']:.1f}, {add['z']:.1f})"
    assert rc == 1 and "FAIL" in text and f"add a point at {where}" in text
    followed = write_plan(tmp_path / "followed.csv",
                          np.vstack([laser, [add["x"], add["y"], add["z"]]]))
    rc, after = plan_json(followed, *args)
    assert rc == 0 and after["verdict"] == "pass"
    assert after["worst"]["at_95"] == pytest.approx(add["worst_after"], rel=1e-9)
    global SIGMA_ROBOT
    keep, SIGMA_ROBOT = SIGMA_ROBOT, 0.1
    try:
        assert after["worst"]["at_95"] == pytest.approx(
            mc_fixed(followed_laser := np.vstack([laser, [add["x"], add["y"], add["z"]]]),
                     work)[0], rel=0.10)
        assert got["worst"]["at_95"] == pytest.approx(mc_fixed(laser, work)[0], rel=0.10)
    finally:
        SIGMA_ROBOT = keep
    assert len(followed_laser) == 5


def _brute_force(planned, at, candidates, tcp=None, **kw):
    """The worst working point of every one-point-added and one-point-dropped
    plan, each computed from scratch (no shared H, G). With a solved TCP the
    added point's flange takes the nearest planned point's orientation and
    the position that puts the TCP on the candidate."""
    from ucsio.method.plan import Planned, plan

    adds = []
    for c in candidates:
        flange = None
        if planned.flange is not None:
            F = planned.flange[_nearest(planned.laser, c)].copy()
            F[:3, 3] = UCS.apply(c) + T_UCS - F[:3, :3] @ tcp
            flange = np.concatenate([planned.flange, F[None]])
        p = Planned(None, planned.names + ["new"], planned.lines + [None],
                    np.vstack([planned.laser, c]), np.append(planned.weights, 1.0), flange)
        adds.append(plan(p, at=at, candidates=None, **kw))
    drops = []
    for i in range(len(planned.names)):
        keep = np.arange(len(planned.names)) != i
        p = Planned(None, [n for k, n in enumerate(planned.names) if keep[k]], [None] * keep.sum(),
                    planned.laser[keep], planned.weights[keep],
                    None if planned.flange is None else planned.flange[keep])
        drops.append(plan(p, at=at, candidates=None, **kw))
    return adds, drops


def _nearest(points, c):
    return int(np.argmin(np.linalg.norm(points - c, axis=1)))


@pytest.mark.parametrize("joint", [False, True])
@pytest.mark.parametrize("with_at", [True, False])
def test_suggestions_are_the_best_of_every_candidate_plan(joint, with_at):
    """suggest.add and suggest.drop (one batched update of H and G) are the
    best of the candidate plans recomputed one by one."""
    from ucsio.method.plan import Planned, plan
    from ucsio.readers.points import Points

    laser, flange, tcp = cell(5, 25, n=7)
    w = np.array([1, 1, 2, 1, 1, 0.5, 1.0])
    planned = Planned(None, [f"P{i + 1}" for i in range(7)], [None] * 7, laser, w,
                      flange if joint else None)
    rng = np.random.default_rng(2)
    at = (Points(None, [f"W{i}" for i in range(30)], [None] * 30,
                 laser.mean(0) + rng.normal(0, 900, (30, 3))) if with_at else None)
    cand = laser.mean(0) + rng.normal(0, 700, (25, 3))
    kw = dict(joint=joint, threshold=1.5, reach=1000.0, sigma_laser=SIGMA_LASER,
              sigma_robot=SIGMA_ROBOT, min_points=4)
    got = plan(planned, at=at, candidates=Points(None, [f"C{i}" for i in range(25)], [None] * 25,
                                                  cand), **kw)
    adds, drops = _brute_force(planned, at, cand, tcp, **kw)
    worst_add = [a["worst"]["at_95"] for a in adds]
    worst_drop = [d["worst"]["at_95"] for d in drops]
    add, drop = got["suggest"]["add"], got["suggest"]["drop"]
    assert add["name"] == f"C{int(np.argmin(worst_add))}"
    assert add["worst_after"] == pytest.approx(min(worst_add), rel=1e-6)
    assert drop["name"] == f"P{int(np.argmin(worst_drop)) + 1}"
    assert drop["worst_after"] == pytest.approx(min(worst_drop), rel=1e-6)
    if joint:
        assert add["tcp_at_95_after"] == pytest.approx(adds[int(np.argmin(worst_add))]["tcp_at_95"],
                                                       rel=1e-6)
    # never below --min-points
    kw["min_points"] = 7
    assert plan(planned, at=at, **kw)["suggest"]["drop"] is None


# ------------------------------------------------------------------ inputs

def test_plan_from_the_measurement_programs_dat(tmp_path):
    """--robot FILE: the demo cell R03's MEASURE.dat (E6POS with FDAT, TOOL_NO
    through $config.dat), paired by name with a plan of the jig's points,
    as solve --robot pairs them."""
    plan = tmp_path / "plan.csv"
    shutil.copy(DEMO / "R03_kuka" / "jig_points.txt", plan)
    rc, got = plan_json(plan, "--robot", DEMO / "R03_kuka" / "MEASURE.dat", "--config",
                        DEMO / "R03_kuka" / "$config.dat", "--tcp", "solve")
    assert got["planned"] == 10 and 0 < got["tcp_at_95"] < 1.5 and got["orientation_span"] > 30
    assert rc == 0 and got["verdict"] == "pass"
    # the same poses as robot_* columns in the plan: the same numbers
    from ucsio.readers import laser, pairing, robot
    m, _ = pairing.pair(laser.read_laser(plan), robot.read_robot(
        DEMO / "R03_kuka" / "MEASURE.dat", config=str(DEMO / "R03_kuka" / "$config.dat")))
    rc, same = plan_json(write_plan(tmp_path / "p.csv", m.laser, m.flange), "--tcp", "solve")
    assert same["tcp_at_95"] == pytest.approx(got["tcp_at_95"], rel=1e-6)
    assert same["worst"]["at_95"] == pytest.approx(got["worst"]["at_95"], rel=1e-6)
    # without --tcp solve the poses are not needed, and said so
    rc, out, err = run("plan", plan, "--robot", DEMO / "R03_kuka" / "MEASURE.dat",
                       "--sigma-robot", SIGMA_ROBOT)
    assert rc == 0 and "matter only with --tcp solve" in err


def test_tcp_solve_needs_poses_that_turn(tmp_path):
    laser, flange, _ = cell(1, 30)
    # without planned poses the plan takes program --measure's turns, and says which
    # (tests/test_measure_spread.py)
    rc, out, err = run("plan", write_plan(tmp_path / "p.csv", laser), "--tcp", "solve")
    assert rc in (0, 1) and "spread: the orientations of program --measure --spread" in out
    # turned about one axis only: the TCP is not determined
    one = flange.copy()
    rng = np.random.default_rng(3)
    for i in range(len(one)):
        R = Rotation.from_euler("ZYX", [180, 0, 180], degrees=True) * Rotation.from_euler(
            "Z", rng.uniform(-40, 40), degrees=True)
        one[i, :3, 3] = one[i, :3, 3] + one[i, :3, :3] @ [10.0, -25.0, 160.0] \
            - R.apply([10.0, -25.0, 160.0])
        one[i, :3, :3] = R.as_matrix()
    rc, got = plan_json(write_plan(tmp_path / "one.csv", laser, one), "--tcp", "solve")
    assert rc == 1 and "fewer than two axes" in got["reason"]
    # turned 3 deg: refused with the turn that would do
    laser, flange, _ = cell(1, 3)
    rc, got = plan_json(write_plan(tmp_path / "small.csv", laser, flange), "--tcp", "solve")
    assert rc == 1 and got["tcp_at_95"] > 1.5 and "turn the flange" in got["reason"]


def test_at_taught_takes_the_frames_taught_points(tmp_path):
    """--at-taught: the positions diff --points finds, in the frame (demo
    cell R02: pPick and its Offs, moved to in wobjTable)."""
    rc, got = plan_json(DEMO / "R02_abb" / "table_points.csv", "--at-taught",
                        DEMO / "R02_abb" / "CellR02.mod", "--frame", "wobjTable")
    names = {w["name"]: w for w in got["working_points"]}
    assert set(names) == {"pPick", "Offs(pPick,0,0,100)"} and rc == 0
    assert (names["pPick"]["x"], names["pPick"]["y"], names["pPick"]["z"]) == (400, 250, 120)
    assert names["Offs(pPick,0,0,100)"]["z"] == 220 and names["pPick"]["file"].endswith(
        "CellR02.mod")
    # KUKA: the E6POS of BASE_DATA[3] in the controller's tree
    shutil.copytree(FIXTURES / "taught" / "kuka" / "KRC", tmp_path / "KRC")
    config = next((tmp_path / "KRC").rglob("$config.dat"))
    rc, got = plan_json(DEMO / "R01_kuka" / "base3_points.csv", "--at-taught", config,
                        "--frame", "BASE_DATA[3]")
    assert len(got["working_points"]) > 3
    text = config.read_text()
    config.write_text(text.replace("BASE_DATA[3]=", "BASE_DATA[2]={X 1.0,Y 0.0,Z 0.0,A 0.0,B 0.0,"
                                                   "C 0.0}\nBASE_DATA[3]=", 1))
    for args, words in ((("--at-taught", config), "needs --frame"),
                        (("--frame", "BASE_DATA[3]"), "goes with --at-taught"),
                        (("--at-taught", config, "--frame", "BASE_DATA[2]"), "no positions")):
        rc, out, err = run("plan", DEMO / "R01_kuka" / "base3_points.csv", *args)
        assert rc == 2 and words in err, err


@pytest.mark.parametrize("body, words", [
    ("point,laser_x,laser_y\nP1,0,0\n", "missing column"),
    ("point,laser_x,laser_y,laser_z\nP1,0,0,0\nP2,100,0,0\n", "at least 3"),
    ("point,laser_x,laser_y,laser_z\nP1,0,0,0\nP2,100,0,0\nP3,200,0,0\nP4,300,0,0\n", "line"),
    ("point,laser_x,laser_y,laser_z\nP1,0,0,0\nP2,100,x,0\n", "not a"),
])
def test_a_bad_plan_is_exit_2(tmp_path, body, words):
    f = tmp_path / "p.csv"
    f.write_text(body)
    rc, out, err = run("plan", f)
    assert rc == 2 and out == "" and err.count("\n") == 1 and str(f) in err and words in err


def test_threshold_and_options(tmp_path):
    laser = np.random.default_rng(1).uniform(-0.5, 0.5, (8, 3)) * (1200, 800, 300)
    plan = write_plan(tmp_path / "p.csv", laser)
    rc, got = plan_json(plan)
    assert rc == 0 and got["worst"]["at_95"] < 1.5 and got["suggest"]["drop"] is not None
    worst = got["worst"]["at_95"]
    assert plan_json(plan, "--threshold", f"{worst * 0.99}")[0] == 1
    assert plan_json(plan, "--threshold", f"{worst * 1.01}")[0] == 0
    # the noise scales every prediction
    _, loud = plan_json(plan, "--sigma-laser", "0.03", "--sigma-robot", "0.1")
    assert loud["worst"]["at_95"] == pytest.approx(2 * worst, rel=1e-9)
    rc, text, _ = run("plan", plan, "--sigma-robot", SIGMA_ROBOT)
    assert "generic one 1000 mm from the centroid" in text and "PASS" in text
    for bad in (["--threshold", "0"], ["--reach", "-1"], ["--sigma-robot", "-1"],
                ["--min-points", "2"], ["--tcp", "1,2"]):
        assert run("plan", plan, *bad)[0] == 2, bad


# ------------------------------------------------------------------ the batched evaluation

@settings(max_examples=25, deadline=None, derandomize=True)
@given(seed=st.integers(0, 10_000), thin=st.floats(0.005, 1.0), far=st.floats(10, 5000))
def test_the_batched_worst_is_the_worst_of_every_point(seed, thin, far):
    """precision.worst_at_points95 (traces by matrix products, most points
    pruned by the bound on q²/tr S) against each point's 3x3 covariance
    J K Jᵀ built one by one and precision.quantile95_norm."""
    from ucsio.method import precision

    rng = np.random.default_rng(seed)
    laser = rng.uniform(-0.5, 0.5, (6, 8, 3)) * [1000, 1000 * thin, 300 * thin]
    K = precision.fit_covariance(laser - laser.mean(1, keepdims=True), np.ones((6, 8)))
    pts = rng.normal(0, 1, (400, 3)) * far
    J = np.zeros((400, 3, 6))
    J[:, :, :3] = np.eye(3)
    J[:, :, 3:] = -precision.skew(pts)
    direct = np.array([precision.quantile95_norm(J @ k @ np.swapaxes(J, 1, 2)) for k in K]) * 0.05
    worst, where = precision.worst_at_points95(K, pts, 0.05)
    assert worst == pytest.approx(direct.max(axis=1), rel=1e-9)
    assert direct[np.arange(6), where] == pytest.approx(direct.max(axis=1), rel=1e-9)
    assert precision.at_points95(K, pts, 0.05) == pytest.approx(direct, rel=1e-9)


def test_the_python_api_plans_and_predicts(tmp_path):
    from ucsio import api

    laser = np.random.default_rng(1).uniform(-0.5, 0.5, (8, 3)) * (1200, 800, 300)
    plan = write_plan(tmp_path / "p.csv", laser)
    at = write_points(tmp_path / "at.csv", [[2000, 0, 0], [0, 1500, 200]])
    got = api.plan(plan, at=at, threshold=0.2, sigma_laser=SIGMA_LASER, sigma_robot=SIGMA_ROBOT)
    rc, cli = plan_json(plan, "--at", at, "--threshold", "0.2")
    assert got["worst"] == cli["worst"] and got["verdict"] == cli["verdict"]
    assert got["suggest"] == cli["suggest"]
