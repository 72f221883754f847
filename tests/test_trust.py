"""Issue 9, trust in every number: the determinacy gate (SPEC point 7), the
exclusion loop running to its end (point 6), no silent TCP (point 8) and
values no solver can use. The ABB quaternion writer is test_quat_writer.py.

Ground truth is synthetic (a known frame, known noise) and the gate's
prediction is checked against a Monte Carlo of the real estimator, not
against itself."""
from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st, HealthCheck
from scipy.spatial.transform import Rotation

from ucsio.method import horn, precision
from ucsio.cli import main
from ucsio.errors import UcsioError
from ucsio.method.solve import solve_points

REACH = 1000.0
THRESHOLD = 1.5
SETTINGS = settings(max_examples=40, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])


def fixture_points(seed, n, dims, line_ratio=None):
    """n laser points of a fixture (mm). ``line_ratio``: all points within that
    fraction of the length from one line (the nearly collinear case)."""
    rng = np.random.default_rng(seed)
    if line_ratio is None:
        return rng.uniform(-0.5, 0.5, size=(n, 3)) * np.asarray(dims, float)
    length = dims[0]
    along = np.linspace(-0.5, 0.5, n) * length
    across = rng.uniform(-1, 1, size=(n, 2)) * line_ratio * length
    pts = np.column_stack([along, across])
    return Rotation.random(random_state=seed + 1).apply(pts) + rng.uniform(-500, 500, 3)


def measure(laser, seed, noise):
    rng = np.random.default_rng(seed + 100)
    truth = Rotation.random(random_state=seed + 2)
    t = rng.uniform(-3000, 3000, 3)
    robot = truth.apply(laser) + t + rng.normal(0, noise, size=laser.shape)
    return robot, truth, t


def true_error_at_reach(sol, laser, truth, t, reach=REACH, n_dirs=400):
    """Largest displacement, over directions, of a point ``reach`` from the
    centroid between the fitted and the true frame (what the gate predicts)."""
    rng = np.random.default_rng(0)
    d = rng.normal(size=(n_dirs, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    p = laser.mean(axis=0) + reach * d
    R = np.array(sol.pose.matrix)
    fitted = p @ R.T + np.array(sol.pose.t)
    return float(np.linalg.norm(fitted - (truth.apply(p) + t), axis=1).max())


def names(n):
    return [f"P{i + 1}" for i in range(n)]


# ------------------------------------------------------------ the determinacy gate

def test_the_issues_nearly_collinear_fixture_is_rejected():
    """524 mm of fixture, points within 2.3 % of a line, 0.22 mm of noise: the
    fit looks fine (rms ~0.3 mm) but is degrees off about the line."""
    caught = 0
    for seed in range(10):
        laser = fixture_points(seed, 8, (524.0, 0, 0), line_ratio=0.023)
        robot, truth, t = measure(laser, seed, 0.22)
        sol = solve_points(names(8), laser, robot)
        assert sol.max < THRESHOLD                                  # the residuals hide it
        assert not sol.accepted
        assert "do not pin the orientation down" in sol.reason
        assert "spread the points" in sol.reason and "more points" in sol.reason
        assert sol.precision["at_reach"] > THRESHOLD
        caught += true_error_at_reach(sol, laser, truth, t) > THRESHOLD
    assert caught >= 5          # and the truth agrees that those frames were off


def test_json_and_table_carry_precision(tmp_path, capsys):
    laser = fixture_points(3, 8, (1200, 800, 300))
    robot, *_ = measure(laser, 3, 0.03)
    rows = ["point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c"]
    rows += [f"P{i},{l[0]},{l[1]},{l[2]},{r[0]},{r[1]},{r[2]},0,0,0"
             for i, (l, r) in enumerate(zip(laser, robot))]
    f = tmp_path / "m.csv"
    f.write_text("\n".join(rows) + "\n")
    assert main(["solve", str(f), "--tcp", "0,0,0", "--json"]) == 0
    p = json.loads(capsys.readouterr().out)["precision"]
    assert {"sigma", "angle_std", "reach", "at_reach"} <= set(p)
    assert p["reach"] == REACH and 0 < p["at_reach"] < THRESHOLD
    assert p["sigma"] == pytest.approx(np.hypot(0.015, 0.05))    # the stated noise: larger here
    assert main(["solve", str(f), "--tcp", "0,0,0", "--reach", "5000", "--json"]) in (0, 1)
    assert json.loads(capsys.readouterr().out)["precision"]["reach"] == 5000
    assert main(["solve", str(f), "--tcp", "0,0,0"]) == 0
    assert "precision: a point 1000 mm from the centroid within" in capsys.readouterr().out


@pytest.mark.parametrize("dims, n, noise", [((1500, 1000, 400), 8, 0.46),
                                            ((800, 600, 0.0), 7, 0.2),      # planar
                                            ((600, 40, 40), 8, 0.1),        # long and thin
                                            ((1200, 800, 300), 10, 0.05)])
def test_prediction_matches_the_estimators_real_scatter(dims, n, noise):
    """The first-order prediction vs a Monte Carlo of Horn's fit itself: the
    95th percentile of the worst displacement at 1 m, within 20 %."""
    laser = fixture_points(11, n, dims)
    robot0, truth, t = measure(laser, 11, 0.0)
    rng = np.random.default_rng(5)
    k = 600
    noisy = robot0 + rng.normal(0, noise, size=(k, n, 3))
    fits = horn.horn_batch(np.broadcast_to(laser, (k, n, 3)), noisy, np.ones((k, n)))
    dirs = rng.normal(size=(300, 3))
    dirs /= np.linalg.norm(dirs, axis=1)[:, None]
    p = laser.mean(axis=0) + REACH * dirs
    err = np.linalg.norm(fits.apply(np.broadcast_to(p, (k, 300, 3)))
                         - (truth.apply(p) + t), axis=2)                # (k, dirs)
    mc = np.percentile(err, 95, axis=0).max()
    R = truth.as_matrix()[None]
    pred = precision.predict(laser[None], np.ones((1, n)), R, [0.0], [n], [noise], [REACH])
    assert pred["at_reach"][0] == pytest.approx(mc, rel=0.2)


def test_quantile_of_the_norm_matches_exact_cases():
    """1-D: 1.96 sigma; isotropic 3-D: sqrt(chi2_3(0.95)) = 2.7955 sigma."""
    q1 = precision.quantile95_norm(np.diag([4.0, 0.0, 0.0])[None])[0]
    q3 = precision.quantile95_norm(np.eye(3)[None])[0]
    assert q1 == pytest.approx(2 * 1.959964, rel=0.015)
    assert q3 == pytest.approx(2.795483, rel=0.01)


@SETTINGS
@given(seed=st.integers(0, 10_000), n=st.integers(6, 10),
       dims=st.tuples(st.floats(600, 2000), st.floats(400, 1500), st.floats(0, 500)))
def test_well_spread_fixtures_are_accepted(seed, n, dims):
    """SPEC's default noise on a fixture spread across hundreds of mm: accepted."""
    laser = fixture_points(seed, n, dims)
    spread = horn.absolute_orientation(laser, laser).spread
    if spread[1] < 100:        # uniform draws can bunch up; the property is for spread points
        return
    robot, *_ = measure(laser, seed, 0.05)
    sol = solve_points(names(n), laser, robot)
    assert sol.accepted, sol.reason


@SETTINGS
@given(seed=st.integers(0, 10_000), n=st.integers(6, 10), length=st.floats(200, 1500),
       ratio=st.floats(0.012, 0.08), noise=st.floats(0.05, 0.5))
def test_nearly_collinear_noisy_fixtures_never_pass_unnoticed(seed, n, length, ratio, noise):
    """Whatever is accepted is within what the gate promised: the true error
    of a point 1 m away stays under twice the threshold (the prediction is
    a 95 % bound; twice it is practically certain)."""
    laser = fixture_points(seed, n, (length, 0, 0), line_ratio=ratio)
    robot, truth, t = measure(laser, seed, noise)
    try:
        sol = solve_points(names(n), laser, robot)
    except UcsioError:
        return                                          # refused outright as collinear
    if sol.accepted:
        assert true_error_at_reach(sol, laser, truth, t) <= 2 * THRESHOLD
    else:
        assert sol.reason


def test_gate_is_invariant_under_rigid_motion_of_either_side():
    laser = fixture_points(4, 8, (900, 500, 200))
    robot, *_ = measure(laser, 4, 0.3)
    base = solve_points(names(8), laser, robot).precision
    M = Rotation.from_euler("zyx", [33, -71, 120], degrees=True)
    for lz, rb in ((M.apply(laser) + [1e4, -3e3, 77], robot),
                   (laser, M.apply(robot) - [250, 5e3, 1e4])):
        p = solve_points(names(8), lz, rb).precision
        for k in ("sigma", "angle_std", "at_reach", "at_centroid"):
            assert p[k] == pytest.approx(base[k], rel=1e-7), k


def test_residual_noise_drives_the_gate_and_the_uncertainty(capsys, tmp_path):
    """Stated noise cannot make a fit look precise when its residuals are
    larger: the gate and --uncertainty both take the residuals' sigma."""
    laser = fixture_points(8, 8, (1200, 900, 300))
    robot, *_ = measure(laser, 8, 0.4)
    sol = solve_points(names(8), laser, robot)
    resid = np.array([p.residual for p in sol.points])
    assert sol.precision["sigma"] == pytest.approx(np.sqrt((resid ** 2).sum() / (3 * 8 - 6)))
    rows = ["point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c"]
    rows += [f"P{i},{l[0]},{l[1]},{l[2]},{r[0]},{r[1]},{r[2]},0,0,0"
             for i, (l, r) in enumerate(zip(laser, robot))]
    f = tmp_path / "m.csv"
    f.write_text("\n".join(rows) + "\n")
    main(["solve", str(f), "--tcp", "0,0,0", "--uncertainty", "3000", "--json"])
    d = json.loads(capsys.readouterr().out)
    u = d["uncertainty"]
    assert u["sigma_source"] == "residuals"
    assert u["sigma"] == pytest.approx(d["precision"]["sigma"], rel=1e-9)
    # the Monte Carlo angle then agrees with the gate's first-order angle
    assert u["std"]["angle"] == pytest.approx(d["precision"]["angle_std"], rel=0.1)


# ------------------------------------------------------------ the exclusion loop

def test_exclusion_runs_to_its_end_below_min_points():
    """Three blunders in 7 points, min 6: the loop used to stop at 5 points
    with the 7.7 mm blunder still used. It runs on; the set stays rejected."""
    laser = fixture_points(21, 7, (1200, 900, 300))
    robot, *_ = measure(laser, 21, 0.02)
    robot[1] += [12.0, 0, 0]
    robot[3] += [0, -10.0, 0]
    robot[5] += [0, 0, 7.7]
    sol = solve_points(names(7), laser, robot)
    by = {p.name: p for p in sol.points}
    assert not sol.accepted and "too few points" in sol.reason
    assert {"P2", "P4", "P6"} <= {n for n, p in by.items() if not p.used}
    assert by["P6"].excluded_by == "auto" and by["P6"].residual > 7.0
    assert sol.n_used < 6 and sol.max < THRESHOLD      # what is left is judged within


@SETTINGS
@given(seed=st.integers(0, 10_000), n=st.integers(4, 10), blunders=st.integers(0, 5),
       min_points=st.integers(3, 8))
def test_accept_and_reject_as_before(seed, n, blunders, min_points):
    """Running on below min_points changes what is listed, never the verdict:
    a set ending below min_points is rejected, and what is accepted ends with
    every used point within the threshold and at least min_points of them."""
    laser = fixture_points(seed, n, (1200, 900, 300))
    robot, *_ = measure(laser, seed, 0.03)
    rng = np.random.default_rng(seed)
    for k in rng.choice(n, size=min(blunders, n), replace=False):
        robot[k] += rng.normal(0, 6, 3)
    try:
        sol = solve_points(names(n), laser, robot, min_points=min_points)
    except UcsioError:
        return
    if sol.n_used < min_points:
        assert not sol.accepted
    if sol.accepted:
        assert sol.n_used >= min_points and sol.max <= THRESHOLD
    if sol.n_used >= 4:         # the loop ended because the refit judged every point within
        auto = [p for p in sol.points if p.excluded_by == "auto"]
        if auto:
            assert sol.max <= THRESHOLD or sol.n_used == 3


# ------------------------------------------------------------ no silent TCP

def test_solve_without_a_tcp_is_an_error(tmp_path, capsys):
    from conftest import FIXTURES
    meas = FIXTURES / "measurements" / "kuka_base3.csv"
    out_file = tmp_path / "s.json"
    assert main(["solve", str(meas), "-o", str(out_file)]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and not out_file.exists()
    assert "--tcp X,Y,Z" in err and "--tool FILE:NAME" in err and "--tcp solve" in err
    assert "--tcp 0,0,0" in err                    # and how to say "flange positions"
    from ucsio import api
    with pytest.raises(UcsioError, match="no TCP given"):
        api.solve(meas, None)


def test_batch_entry_without_a_tcp_is_reported_as_that_error(tmp_path, capsys):
    from conftest import FIXTURES
    import shutil
    shutil.copy(FIXTURES / "measurements" / "kuka_base3.csv", tmp_path / "m.csv")
    (tmp_path / "cell.mod").write_text(
        'MODULE cell\n  PERS wobjdata w:=[FALSE,TRUE,"",[[6125,2445,1169],[1,0,0,0]],'
        '[[0,0,0],[1,0,0,0]]];\nENDMODULE\n')
    (tmp_path / "m.toml").write_text(
        "[[entry]]\nname = 'with'\nmeasurement = 'm.csv'\ncontroller = 'cell.mod'\n"
        "frame = 'w'\ntcp = [-20.67, 89.73, 33.44]\n"
        "[[entry]]\nname = 'without'\nmeasurement = 'm.csv'\ncontroller = 'cell.mod'\n"
        "frame = 'w'\n")
    main(["batch", str(tmp_path / "m.toml"), "--json"])
    entries = json.loads(capsys.readouterr().out)["entries"]
    with_, without = entries
    assert with_["accepted"] and "error" not in with_
    assert "no TCP" in without["error"] and 'tool = "FILE:NAME"' in without["error"]
    assert 'tcp = "solve"' in without["error"]


# ------------------------------------------------------------ values no solver can use

@pytest.mark.parametrize("big", ["1e151", "-3e200", "1.7e308", "1e12"])
@pytest.mark.parametrize("column", [1, 4, 7, 10])
def test_huge_values_are_one_line_exit_2(tmp_path, capsys, big, column):
    rows = ["point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c,weight"]
    rng = np.random.default_rng(1)
    for i in range(8):
        v = list(rng.uniform(0, 1000, 6)) + [0, 0, 0, 1]
        rows.append(",".join([f"P{i}"] + [f"{x:.3f}" for x in v]))
    cells = rows[3].split(",")
    cells[column] = big
    rows[3] = ",".join(cells)
    f = tmp_path / "m.csv"
    f.write_text("\n".join(rows) + "\n")
    rc = main(["solve", str(f), "--tcp", "0,0,0"])
    out, err = capsys.readouterr()
    col = len(",".join(cells[:column])) + 2
    assert rc == 2 and err.count("\n") == 1 and f"{f}:4:{col}:" in err and "too large" in err
    assert "Warning" not in err and "Traceback" not in err


def test_huge_values_through_the_api_never_warn(recwarn):
    laser = fixture_points(1, 8, (1000, 800, 300))
    robot, *_ = measure(laser, 1, 0.02)
    robot[2] = [1e200, 0, 0]
    with pytest.raises(UcsioError, match="double precision"):
        solve_points(names(8), laser, robot)
    with pytest.raises(UcsioError):
        solve_points(names(8), laser, robot * np.nan)
    assert not [w for w in recwarn if issubclass(w.category, RuntimeWarning)]


def test_huge_tcp_is_refused(capsys):
    from conftest import FIXTURES
    rc = main(["solve", str(FIXTURES / "measurements" / "kuka_base3.csv"), "--tcp", "1e200,0,0"])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and "--tcp" in err


# ------------------------------------------------------------ the last resort

def test_an_unexpected_exception_is_one_line_not_a_traceback(monkeypatch, capsys):
    """A bug must still end in one line and exit 2, JSON with --json; with
    UCSIO_DEBUG set the traceback is there for whoever debugs it."""
    from ucsio.commands import frames as frames_cmd

    def boom(args):
        raise ZeroDivisionError("simulated bug")

    monkeypatch.setattr(frames_cmd, "run", boom)
    assert main(["frames", "x.mod"]) == 2
    out, err = capsys.readouterr()
    assert err.count("\n") == 1 and "internal error" in err and "ZeroDivisionError" in err
    assert main(["frames", "x.mod", "--json"]) == 2
    assert "internal error" in json.loads(capsys.readouterr().out)["error"]["message"]
    monkeypatch.setattr(frames_cmd, "run", lambda args: (_ for _ in ()).throw(RecursionError()))
    assert main(["frames", "x.mod"]) == 2
    assert "nested too deeply" in capsys.readouterr().err
    monkeypatch.setenv("UCSIO_DEBUG", "1")
    monkeypatch.setattr(frames_cmd, "run", boom)
    with pytest.raises(ZeroDivisionError):
        main(["frames", "x.mod"])
