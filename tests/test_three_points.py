"""Frames by their three points (SPEC, "Measurement programs and frames by
three points"): the pendant's 3-point frame from measured points beside the
best fit, and the three points that set the measured frame by hand."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from ucsio import api
from ucsio.cli import main
from ucsio.method import horn, three_points
from ucsio.readers.points import Points
from ucsio.vendors.yaskawa.program import frame_from_points   # the read-back's construction

TRUTH_R = Rotation.from_euler("ZYX", [63.0, -21.0, 8.0], degrees=True).as_matrix()
TRUTH_T = np.array([1520.0, -340.0, 780.0])
FIXTURE = np.array([[0, 0, 0], [900, 10, 5], [880, 610, -8], [15, 620, 12], [450, 300, 260],
                    [200, 90, 140], [700, 450, 90], [300, 500, -60]], dtype=float)


def measured(noise: float, seed: int):
    rng = np.random.default_rng(seed)
    laser = FIXTURE + rng.normal(0.0, noise, FIXTURE.shape)
    robot = FIXTURE @ TRUTH_R.T + TRUTH_T + rng.normal(0.0, noise, FIXTURE.shape)
    return laser, robot


def write_csv(folder, laser, robot):
    """The points as a measurement CSV (flange positions: orientation 0, --tcp 0,0,0)."""
    rows = ["point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c"]
    rows += [f"P{k + 1}," + ",".join(f"{v:.4f}" for v in (*laser[k], *robot[k])) + ",0,0,0"
             for k in range(len(laser))]
    meas = folder / "m.csv"
    meas.write_text("\n".join(rows) + "\n")
    return meas


def compare(laser, robot, at=None, reach=1000.0):
    fit = horn.absolute_orientation(laser, robot, np.ones(len(laser)))
    names = [f"P{k + 1}" for k in range(len(laser))]
    got = three_points.compare(names, laser, robot, np.ones(len(laser)),
                               np.ones(len(laser), bool), fit.R, fit.t, reach, at)
    return fit, got


def pose_matrix(d):
    R = Rotation.from_quat([*d["q"][1:], d["q"][0]]).as_matrix()   # scalar last for scipy
    return R, np.array([d["x"], d["y"], d["z"]])


def test_the_rule_picks_the_farthest_pair_and_the_largest_triangle():
    # P2-P4 farthest apart (P2 listed first: ORG), P3 farthest from that line
    pts = np.array([[100, 0, 0], [0, 0, 0], [500, 400, 0], [1000, 0, 0], [500, 50, 0]], float)
    assert three_points.pick_three(pts) == (1, 3, 2)
    assert three_points.pick_three(np.array([[0, 0, 0], [1, 1, 1], [2, 2, 2.0]])) is None


def brute_force_rule(pts):
    """The rule, pair by pair and triangle by triangle: the farthest pair
    (first listed: ORG), then the largest triangle on it."""
    n = len(pts)
    i, j = max(((a, b) for a in range(n) for b in range(a + 1, n)),
               key=lambda ab: np.linalg.norm(pts[ab[0]] - pts[ab[1]]))
    k = max(range(n), key=lambda c: np.linalg.norm(np.cross(pts[j] - pts[i], pts[c] - pts[i])))
    return [f"P{m + 1}" for m in (i, j, k)]


def test_three_point_frame_from_noise_free_points_is_the_truth():
    laser, robot = measured(0.0, 0)
    _, got = compare(laser, robot)
    R, t = pose_matrix(got["frame"])
    assert np.allclose(R, TRUTH_R, atol=1e-12) and np.allclose(t, TRUTH_T, atol=1e-9)
    assert [p["name"] for p in got["points"]] == brute_force_rule(laser)
    assert got["dist"] < 1e-9 and got["working_points"][0]["dist"] < 1e-9


def test_best_fit_beats_the_three_point_frame_on_average():
    """Monte Carlo over 40 seeds, 0.1 mm per axis on both sides: at the
    fixture's far corner and 1 m out, the best fit lands nearer the truth."""
    probe = np.array([[900.0, 600.0, 0.0], [1000.0, 1000.0, 500.0]])
    truth = probe @ TRUTH_R.T + TRUTH_T
    err_fit, err_three = [], []
    for seed in range(40):
        fit, got = compare(*measured(0.1, seed))
        R3, t3 = pose_matrix(got["frame"])
        err_fit.append(np.linalg.norm(probe @ fit.R.T + fit.t - truth, axis=1).max())
        err_three.append(np.linalg.norm(probe @ R3.T + t3 - truth, axis=1).max())
    assert np.mean(err_fit) < 0.75 * np.mean(err_three)


def test_the_difference_at_working_points_is_the_two_frames_apart_there():
    laser, robot = measured(0.3, 7)
    at = Points(names=["W1", "W2"], xyz=[(100.0, 200.0, 300.0), (-400.0, 1500.0, 0.0)],
                lines=[2, 3], path="at.csv")
    fit, got = compare(laser, robot, at)
    R3, t3 = pose_matrix(got["frame"])
    for row, p in zip(got["working_points"], np.array(at.xyz)):
        want = np.linalg.norm((fit.R @ p + fit.t) - (R3 @ p + t3))
        assert row["dist"] == pytest.approx(want, abs=1e-9)
    assert got["worst"]["name"] == max(got["working_points"], key=lambda r: r["dist"])["name"]


def test_the_generic_working_point_is_the_worst_at_reach():
    laser, robot = measured(0.3, 11)
    fit, got = compare(laser, robot, reach=1000.0)
    R3, t3 = pose_matrix(got["frame"])
    row = got["working_points"][0]
    p = np.array([row["x"], row["y"], row["z"]])
    centroid = laser.mean(axis=0)
    assert np.linalg.norm(p - centroid) == pytest.approx(1000.0)
    assert row["dist"] == pytest.approx(np.linalg.norm(fit.R @ p + fit.t - R3 @ p - t3))
    u = np.random.default_rng(0).normal(size=(200_000, 3))
    sphere = centroid + 1000.0 * u / np.linalg.norm(u, axis=1)[:, None]
    apart = np.linalg.norm(sphere @ (fit.R - R3).T + (fit.t - t3), axis=1)
    assert apart.max() <= row["dist"] + 1e-9 and apart.max() > row["dist"] * 0.999


def rebuilt(points):
    org, xx, xy = ((p["x"], p["y"], p["z"]) for p in points)
    pose = frame_from_points(org, xx, xy)
    return np.array(pose.matrix), np.array(pose.t)


def angle_deg(Ra, Rb):
    return math.degrees(Rotation.from_matrix(Ra.T @ Rb).magnitude())


def test_the_three_points_rebuild_the_measured_frame():
    got = three_points.setting(TRUTH_R, TRUTH_T, 200.0, (1.0, 2.0, 150.0), "tool7")
    R, t = rebuilt(got["points"])
    assert np.linalg.norm(t - TRUTH_T) < 1e-3 and angle_deg(R, TRUTH_R) < 1e-3
    assert got["tcp"] == {"x": 1.0, "y": 2.0, "z": 150.0, "tool": "tool7"}
    assert not got["moved"] and math.dist(*[(p["x"], p["y"], p["z"])
                                             for p in got["points"][:2]]) == pytest.approx(200)


def test_a_reach_box_moves_the_points_inside_and_states_the_offset():
    box = (1000.0, 1500.0, -600.0, 0.0, 500.0, 1000.0)       # the origin (x 1520) is outside
    got = three_points.setting(TRUTH_R, TRUTH_T, 200.0, (0, 0, 0), None, box)
    assert got["moved"]
    for p in got["points"]:
        for v, lo, hi in zip((p["x"], p["y"], p["z"]), box[0::2], box[1::2]):
            assert lo - 1e-6 <= v <= hi + 1e-6
    R, t = rebuilt(got["points"])
    assert angle_deg(R, TRUTH_R) < 1e-3                       # the orientation exactly
    o = got["offset"]
    back = t - TRUTH_R @ np.array([o["x"], o["y"], o["z"]])   # the origin taken back
    assert np.linalg.norm(back - TRUTH_T) < 1e-3


def test_solve_reports_both_and_keeps_its_keys(tmp_path):
    laser, robot = measured(0.02, 3)
    meas = write_csv(tmp_path, laser, robot)
    res = api.solve(str(meas), tcp=(0, 0, 0), three_point_distance=150)
    assert res.accepted and {"frame", "points", "precision"} <= set(res)
    assert [p["name"] for p in res["three_point_frame"]["points"]] == brute_force_rule(laser)
    R, t = rebuilt(res["three_points"]["points"])
    Rm, tm = pose_matrix(res["frame"])
    assert np.linalg.norm(t - tm) < 1e-3 and angle_deg(R, Rm) < 1e-3
    assert res["three_points"]["distance"] == 150


@pytest.mark.parametrize("opts, says", [
    (["--reach-box", "0,1,2"], "six numbers"),
    (["--reach-box", "0,10,5,1,0,9"], "below its maximum"),
    (["--reach-box", "0,100,0,100,0,100"], "fit nowhere inside the box"),
    (["--three-point-distance", "0"], "finite number > 0"),
])
def test_bad_three_point_options_exit_2_and_write_nothing(tmp_path, capsys, opts, says):
    meas = write_csv(tmp_path, *measured(0.0, 0))
    out = tmp_path / "solution.json"
    assert main(["solve", str(meas), "--tcp", "0,0,0", "-o", str(out), *opts]) == 2
    assert says in capsys.readouterr().err and not out.exists()


def test_many_points_pick_from_the_extremes_quickly():
    """Above EXACT_UP_TO used points the rule runs on the extremes (no n²
    distances): on a box's points the farthest pair is two opposite corners."""
    rng = np.random.default_rng(5)
    pts = rng.uniform(0.0, 1.0, (3 * three_points.EXACT_UP_TO, 3)) * [1000.0, 600.0, 300.0]
    corners = np.array([[0.0, 0, 0], [1000.0, 600, 300]])
    pts[[17, 1400]] = corners
    i, j, k = three_points.pick_three(pts)
    assert (i, j) == (17, 1400)
    off = np.linalg.norm(np.cross(pts - pts[i], pts[j] - pts[i]), axis=1)
    assert off[k] > 0.9 * off.max()          # the largest triangle among the extremes'


def test_the_reach_box_shift_is_the_shortest_one():
    """Against scipy's constrained minimiser: the shortest a, b, c that put
    ORG, XX and XY inside the box."""
    from scipy.optimize import minimize

    box = (1000.0, 1500.0, -600.0, 0.0, 500.0, 1000.0)
    got = three_points.setting(TRUTH_R, TRUTH_T, 200.0, (0, 0, 0), None, box)
    lo, hi = np.array(box[0::2]), np.array(box[1::2])
    steps = [np.zeros(3), 200.0 * TRUTH_R[:, 0], 200.0 * TRUTH_R[:, 1]]

    def inside(s):
        return np.concatenate([np.concatenate([hi - p, p - lo])
                               for p in (TRUTH_T + TRUTH_R @ s + st for st in steps)])
    best = minimize(lambda s: s @ s / 1e4, np.zeros(3), jac=lambda s: 2 * s / 1e4,
                    constraints=[{"type": "ineq", "fun": inside}], method="SLSQP",
                    options={"ftol": 1e-14, "maxiter": 500})
    o = np.array([got["offset"][k] for k in "xyz"])
    assert inside(best.x).min() > -1e-6 and inside(o).min() > -1e-6
    assert np.allclose(o, best.x, atol=1e-3)


def test_the_text_states_the_offset_to_take_back(tmp_path, capsys):
    meas = write_csv(tmp_path, *measured(0.0, 0))
    assert main(["solve", str(meas), "--tcp", "0,0,0",
                 "--reach-box", "1000,1500,-600,0,500,1000"]) == 0
    out = capsys.readouterr().out
    assert "three-point frame (a pendant's construction from" in out
    assert "moved into the reach box" in out and "take the origin back by" in out
