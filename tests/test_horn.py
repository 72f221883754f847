"""Horn's absolute orientation: exact recovery, invariance, agreement with an
independent solver (scipy's Rotation.align_vectors, used only as a check),
batching, and the refusal of degenerate point sets."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from ucsio.geometry import arrays
from ucsio.method import horn
from ucsio.geometry import rotations as rot
from ucsio.errors import UcsioError


def fixture_points(rng, n=8, size=(1200.0, 800.0, 300.0)):
    return rng.uniform(0.0, 1.0, size=(n, 3)) * np.asarray(size)


def angle_deg(R1, R2):
    return float(arrays.rotation_angle_deg(np.asarray(R1), np.asarray(R2)))


def make_truth(rng, kind):
    t = rng.uniform(-5000, 5000, size=3)
    if kind == "random":
        return Rotation.random(random_state=int(rng.integers(1 << 30))), t
    if kind == "near180":
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        eps = rng.choice([0.0, 1e-9, 1e-6, 1e-3])
        return Rotation.from_rotvec(axis * np.radians(180.0 - eps)), t
    if kind == "gimbal":
        b = rng.choice([90.0, -90.0]) - rng.choice([0.0, 1e-9, 1e-5]) * rng.choice([1, -1])
        return Rotation.from_euler("ZYX", [rng.uniform(-180, 180), b, rng.uniform(-180, 180)],
                                   degrees=True), t
    raise ValueError(kind)


@pytest.mark.parametrize("kind", ["random", "near180", "gimbal"])
def test_exact_recovery(kind):
    rng = np.random.default_rng({"random": 1, "near180": 2, "gimbal": 3}[kind])
    for _ in range(100):
        truth, t = make_truth(rng, kind)
        laser = fixture_points(rng, int(rng.integers(3, 12)))
        robot = truth.apply(laser) + t
        fit = horn.absolute_orientation(laser, robot)
        assert np.abs(fit.t - t).max() <= 1e-6                        # mm
        assert angle_deg(fit.R, truth.as_matrix()) <= 1e-7              # deg
        assert np.abs(fit.apply(laser) - robot).max() <= 1e-6
        assert fit.q[0] >= 0 and abs(np.linalg.norm(fit.q) - 1) < 1e-14
        # the quaternion is the rotation's (up to sign at w = 0)
        qt = truth.as_quat(scalar_first=True)
        assert min(np.abs(fit.q - qt).max(), np.abs(fit.q + qt).max()) < 1e-9
        # and the solver's KUKA angles reproduce it
        abc = rot.matrix_to_abc(tuple(map(tuple, fit.R)))
        assert angle_deg(rot.abc_to_matrix(*abc), truth.as_matrix()) <= 1e-7


def test_exact_recovery_batched_matches_single():
    rng = np.random.default_rng(4)
    B, n = 50, 7
    truths = Rotation.random(B, random_state=5)
    t = rng.uniform(-3000, 3000, size=(B, 3))
    laser = rng.uniform(-600, 600, size=(B, n, 3))
    robot = np.einsum("bij,bmj->bmi", truths.as_matrix(), laser) + t[:, None]
    robot += rng.normal(0, 0.05, size=robot.shape)
    w = rng.uniform(0.5, 2.0, size=(B, n))
    res = horn.horn_batch(laser, robot, w)
    assert res.ok.all()
    for b in range(B):
        one = horn.absolute_orientation(laser[b], robot[b], w[b])
        np.testing.assert_allclose(res.R[b], one.R, atol=1e-12)
        np.testing.assert_allclose(res.t[b], one.t, atol=1e-9)
    np.testing.assert_allclose(res.apply(laser), np.einsum("bij,bmj->bmi", res.R, laser)
                               + res.t[:, None], atol=1e-9)


def test_invariance_under_rigid_motion_of_laser_points():
    """Moving the laser points by a rigid motion G moves the fit exactly:
    fit(G l) = fit(l) * G^-1."""
    rng = np.random.default_rng(6)
    for _ in range(30):
        laser = fixture_points(rng, 9)
        truth, t = make_truth(rng, "random")
        robot = truth.apply(laser) + t + rng.normal(0, 0.3, size=laser.shape)
        w = rng.uniform(0.2, 3.0, size=9)
        base = horn.absolute_orientation(laser, robot, w)
        G = Rotation.random(random_state=int(rng.integers(1 << 30))).as_matrix()
        g = rng.uniform(-1000, 1000, size=3)
        moved = horn.absolute_orientation(laser @ G.T + g, robot, w)
        np.testing.assert_allclose(moved.R, base.R @ G.T, atol=1e-12)
        np.testing.assert_allclose(moved.t, base.t - base.R @ G.T @ g, atol=1e-8)
        # and the residuals are the same
        np.testing.assert_allclose(moved.apply(laser @ G.T + g), base.apply(laser), atol=1e-8)
        # moving the robot points instead moves the fit the other way
        moved_r = horn.absolute_orientation(laser, robot @ G.T + g, w)
        np.testing.assert_allclose(moved_r.R, G @ base.R, atol=1e-12)
        np.testing.assert_allclose(moved_r.t, G @ base.t + g, atol=1e-8)


def test_agrees_with_scipy_align_vectors_on_noisy_data():
    rng = np.random.default_rng(7)
    for _ in range(200):
        n = int(rng.integers(4, 12))
        laser = fixture_points(rng, n)
        truth, t = make_truth(rng, "random")
        robot = truth.apply(laser) + t + rng.normal(0, 0.5, size=laser.shape)
        w = rng.uniform(0.1, 3.0, size=n)
        fit = horn.absolute_orientation(laser, robot, w)
        cl = np.average(laser, axis=0, weights=w)
        cr = np.average(robot, axis=0, weights=w)
        ref, _ = Rotation.align_vectors(robot - cr, laser - cl, weights=w)
        R_ref = ref.as_matrix()
        t_ref = cr - R_ref @ cl
        assert np.abs(fit.R - R_ref).max() <= 1e-9
        assert np.abs(fit.t - t_ref).max() <= 1e-9 * 5000     # 1e-9 relative to the coordinates
        assert angle_deg(fit.R, R_ref) <= 1e-9


def test_weights_zero_leave_points_out():
    rng = np.random.default_rng(8)
    laser = fixture_points(rng, 8)
    truth, t = make_truth(rng, "random")
    robot = truth.apply(laser) + t
    robot[3] += 50.0
    w = np.ones(8)
    w[3] = 0.0
    fit = horn.absolute_orientation(laser, robot, w)
    assert angle_deg(fit.R, truth.as_matrix()) < 1e-9
    np.testing.assert_allclose(fit.t, t, atol=1e-8)


def test_coplanar_points_are_fine():
    rng = np.random.default_rng(9)
    laser = fixture_points(rng, 6)
    laser[:, 2] = 0.0
    truth, t = make_truth(rng, "random")
    fit = horn.absolute_orientation(laser, truth.apply(laser) + t)
    assert angle_deg(fit.R, truth.as_matrix()) < 1e-9


# ------------------------------------------------------------------ degenerate sets

def degenerate_sets():
    rng = np.random.default_rng(10)
    truth, t = make_truth(rng, "random")
    d = rng.normal(size=3)
    d /= np.linalg.norm(d)
    line = np.outer(np.linspace(0, 1000, 6), d) + 100.0
    perp = np.cross(d, [0.0, 0.0, 1.0])
    perp /= np.linalg.norm(perp)
    nearly = line + np.outer([0, 0.5, -0.3, 0.2, 0.4, -0.1], perp)       # within 0.5 mm of a 1 m line
    two = fixture_points(rng, 2)
    same = np.tile([[120.0, 30.0, 5.0]], (5, 1)) + rng.normal(0, 1e-5, size=(5, 3))
    return truth, t, {
        "two points": (two, horn.TOO_FEW_POINTS, "fewer than 3"),
        "coincident": (same, horn.COINCIDENT, "coincide"),
        "collinear": (line, horn.COLLINEAR, "line"),
        "nearly collinear": (nearly, horn.COLLINEAR, "line"),
    }


@pytest.mark.parametrize("name", ["two points", "coincident", "collinear", "nearly collinear"])
def test_degenerate_refused(name):
    truth, t, sets = degenerate_sets()
    laser, code, words = sets[name]
    robot = truth.apply(laser) + t
    with pytest.raises(UcsioError, match=words) as info:
        horn.absolute_orientation(laser, robot)
    assert info.value.exit_code == 2
    if len(laser) >= 3:
        res = horn.horn_batch(laser[None], robot[None])
        assert res.status[0] == code and not res.ok[0]


def test_degenerate_flags_are_per_batch_item():
    truth, t, sets = degenerate_sets()
    rng = np.random.default_rng(11)
    good = fixture_points(rng, 6)
    lasers = [good, sets["collinear"][0], good * 0.5, sets["nearly collinear"][0],
              sets["coincident"][0][:1].repeat(6, 0)]
    laser = np.stack(lasers)
    robot = np.stack([truth.apply(x) + t for x in lasers])
    res = horn.horn_batch(laser, robot)
    assert res.status.tolist() == [horn.OK, horn.COLLINEAR, horn.OK, horn.COLLINEAR, horn.COINCIDENT]
    assert np.isfinite(res.R).all() and np.isfinite(res.t).all()
    # too few points with non-zero weight
    w = np.ones((1, 6))
    w[0, 2:] = 0
    assert horn.horn_batch(laser[:1], robot[:1], w).status[0] == horn.TOO_FEW_POINTS


def test_inconsistent_pairs_ambiguous_rotation():
    """Laser points spread out but robot points all identical: no rotation is
    preferred (N = 0): refused, not a silently arbitrary frame."""
    rng = np.random.default_rng(12)
    laser = fixture_points(rng, 6)
    robot = np.tile([[1000.0, 0.0, 500.0]], (6, 1))
    with pytest.raises(UcsioError, match="do not determine one rotation"):
        horn.absolute_orientation(laser, robot)


def test_spreads_are_principal_rms_extents():
    rng = np.random.default_rng(13)
    pts = rng.normal(size=(2000, 3)) * [300.0, 20.0, 2.0]
    R = Rotation.random(random_state=14).as_matrix()
    res = horn.horn_batch((pts @ R.T)[None], (pts @ R.T)[None])
    c = pts - pts.mean(0)
    ref = np.sqrt(np.linalg.eigvalsh(c.T @ c / len(c))[::-1])
    np.testing.assert_allclose(res.spread[0], ref, rtol=1e-9)


def test_quat_to_matrix_matches_scipy():
    r = Rotation.random(100, random_state=15)
    np.testing.assert_allclose(arrays.quat_to_matrix(r.as_quat(scalar_first=True)), r.as_matrix(),
                               atol=1e-15)


def test_rotation_angle_near_0_and_180():
    base = Rotation.random(random_state=16)
    for ang in [0.0, 1e-9, 1e-4, 33.0, 179.9999, 180.0]:
        d = Rotation.from_rotvec(np.radians(ang) * np.array([0.0, 0.8, 0.6]))
        got = angle_deg(base.as_matrix(), (base * d).as_matrix())
        assert got == pytest.approx(ang, abs=1e-9)


# ------------------------------------------------------------------ the closed form

def eigh_reference(laser, robot, w):
    """Horn's q from numpy's eigh on the same N: the method the closed form
    (quartic, Newton, adjugate) replaces."""
    s = horn.sums(laser, robot, w)
    S = s.M
    N = np.empty((len(S), 4, 4))
    N[:, 0] = np.stack([S[:, 0, 0] + S[:, 1, 1] + S[:, 2, 2], S[:, 1, 2] - S[:, 2, 1],
                        S[:, 2, 0] - S[:, 0, 2], S[:, 0, 1] - S[:, 1, 0]], -1)
    N[:, 1] = np.stack([S[:, 1, 2] - S[:, 2, 1], S[:, 0, 0] - S[:, 1, 1] - S[:, 2, 2],
                        S[:, 0, 1] + S[:, 1, 0], S[:, 2, 0] + S[:, 0, 2]], -1)
    N[:, 2] = np.stack([S[:, 2, 0] - S[:, 0, 2], S[:, 0, 1] + S[:, 1, 0],
                        -S[:, 0, 0] + S[:, 1, 1] - S[:, 2, 2], S[:, 1, 2] + S[:, 2, 1]], -1)
    N[:, 3] = np.stack([S[:, 0, 1] - S[:, 1, 0], S[:, 2, 0] + S[:, 0, 2],
                        S[:, 1, 2] + S[:, 2, 1], -S[:, 0, 0] - S[:, 1, 1] + S[:, 2, 2]], -1)
    values, vectors = np.linalg.eigh(N)
    return values, arrays.quat_to_matrix(vectors[:, :, 3])


@pytest.mark.parametrize("kind", ["random", "near180", "gimbal"])
def test_closed_form_eigenvector_equals_eigh(kind):
    """The largest eigenpair from the characteristic quartic and the adjugate
    gives the rotation eigh gives, within 1e-9 deg, on the property tests'
    kinds of rotation, with noise, weights, coplanar and 3-point sets."""
    rng = np.random.default_rng({"random": 20, "near180": 21, "gimbal": 22}[kind])
    for n in (3, 4, 8, 11):
        B = 300
        laser = rng.uniform(0.0, 1.0, size=(B, n, 3)) * [1200.0, 800.0, 300.0]
        laser[::3, :, 2] = 0.0                                        # coplanar
        truths = [make_truth(rng, kind) for _ in range(B)]
        R = np.stack([r.as_matrix() for r, _ in truths])
        t = np.stack([t for _, t in truths])
        robot = np.einsum("bij,bmj->bmi", R, laser) + t[:, None]
        robot += rng.normal(0, 1.0, size=(B, 1, 1)) ** 2 * rng.normal(size=robot.shape)
        w = rng.uniform(0.1, 3.0, size=(B, n))
        res = horn.horn_batch(laser, robot, w)
        values, R_ref = eigh_reference(laser, robot, w)
        ok = res.ok                                        # a few random triangles are slivers
        assert ok.sum() >= 0.95 * B and (res.status[~ok] == horn.COLLINEAR).all()
        assert arrays.rotation_angle_deg(res.R[ok], R_ref[ok]).max() <= 1e-9
        np.testing.assert_allclose(res.lambda_m, values[:, 3], rtol=1e-11)


def test_near_tie_falls_back_to_eigh(monkeypatch):
    """Robot points nearly on a line (laser points well spread): two
    rotations almost equally good, N's two largest eigenvalues a relative
    1e-8 apart - above the ambiguity limit, below the adjugate's. eigh
    decides there; every other set keeps the closed form."""
    rng = np.random.default_rng(23)
    laser = fixture_points(rng, 6)
    robot = np.outer(np.linspace(0, 1000, 6), [0.6, 0.8, 0.0]) + 300.0
    robot[:, 2] += rng.choice([-1.0, 1.0], size=6) * 1e-5
    good = fixture_points(rng, 6)
    L = np.stack([laser, good])
    R = np.stack([robot, good + 10.0])
    values, R_ref = eigh_reference(L, R, None)
    gap = (values[0, 3] - values[0, 2]) / (abs(values[0, 3]) + abs(values[0, 0]))
    assert horn.MIN_EIGEN_GAP < gap < horn.TIE_GAP
    decided = []
    real = np.linalg.eigh
    monkeypatch.setattr(np.linalg, "eigh", lambda N: decided.append(len(N)) or real(N))
    res = horn.horn_batch(L, R)
    assert decided == [1]                                  # the tied set only
    assert res.status.tolist() == [horn.OK, horn.OK]
    assert arrays.rotation_angle_deg(res.R, R_ref).max() <= 1e-9


def test_chunks_give_the_same_fits(monkeypatch):
    rng = np.random.default_rng(24)
    laser = rng.uniform(-500, 500, size=(50, 7, 3))
    robot = laser[:, :, ::-1] + rng.normal(0, 0.1, size=laser.shape)
    w = rng.uniform(0.5, 2.0, size=(50, 7))
    whole = horn.horn_batch(laser, robot, w)
    loo_whole, st_whole = horn.leave_one_out(laser, robot, w)
    monkeypatch.setattr(horn, "CHUNK_POINTS", 20)          # 2 sets, 2 leave-one-out fits at a time
    parts = horn.horn_batch(laser, robot, w)
    loo_parts, st_parts = horn.leave_one_out(laser, robot, w)
    np.testing.assert_allclose(parts.R, whole.R, atol=1e-14)   # summation order: last bits
    np.testing.assert_allclose(parts.t, whole.t, atol=1e-10)
    np.testing.assert_allclose(loo_parts, loo_whole, atol=1e-10)
    np.testing.assert_array_equal(st_parts, st_whole)


# ------------------------------------------------------------------ leave-one-out from the sums

def test_leave_one_out_from_sums_equals_explicit_refits():
    """Each point's terms taken out of its set's sums give the fit of the
    other points: equal to refitting them, to 1e-9 mm, with weights, zero
    weights and degenerate subsets."""
    rng = np.random.default_rng(25)
    B, n = 40, 7
    truths = Rotation.random(B, random_state=26)
    laser = rng.uniform(-600, 600, size=(B, n, 3))
    robot = np.einsum("bij,bmj->bmi", truths.as_matrix(), laser) + rng.uniform(-3000, 3000, (B, 1, 3))
    robot += rng.normal(0, 0.5, size=robot.shape)
    w = rng.uniform(0.2, 3.0, size=(B, n))
    w[0, 2] = 0.0                                          # a point already left out
    laser[1, :4] = np.outer(np.linspace(0, 900, 4), [1.0, 2.0, 2.0])   # 4 of 7 on a line
    laser[1, 4:] = laser[1, 0] + [[300, -200, 50], [0, 0, 0], [0, 0, 0]] * np.array([[1], [1e-9], [2e-9]])
    loo, status = horn.leave_one_out(laser, robot, w)
    for b in range(B):
        for j in range(n):
            keep = w[b] > 0
            keep[j] = False
            ref = horn.horn_batch(laser[b][keep][None], robot[b][keep][None], w[b][keep][None])
            assert status[b, j] == ref.status[0], (b, j)
            if ref.ok[0]:
                d = np.linalg.norm(robot[b, j] - ref.apply(laser[b, j][None, None])[0, 0])
                assert loo[b, j] == pytest.approx(d, abs=1e-9), (b, j)
    assert (status[1] != horn.OK).sum() >= 1              # leaving out the off-line point
    assert (status[np.arange(B) > 1] == horn.OK).all()


def large_set(rng, n):
    truth = Rotation.random(random_state=27)
    t = rng.uniform(-3000, 3000, size=3)
    laser = rng.uniform(0, 1, size=(n, 3)) * [1200.0, 800.0, 300.0]
    robot = truth.apply(laser) + t + rng.normal(0, 0.05, size=(n, 3))
    return laser, robot, truth, t


def test_large_set_solves_with_leave_one_out_in_linear_memory():
    """20,000 points (the benchmark runs 100,000): the fit, and every
    point's leave-one-out residual, without n x n anything (the old way
    needed 20,000^2 x 3 numbers: 9.6 GB)."""
    from ucsio.method.solve import solve_points
    rng = np.random.default_rng(28)
    n = 20_000
    laser, robot, truth, t = large_set(rng, n)
    robot[123] += [3.0, 0.0, 0.0]                          # one outlier
    sol = solve_points([f"P{i}" for i in range(n)], laser, robot)
    assert [p.name for p in sol.points if not p.used] == ["P123"]
    assert sol.points[123].excluded_by == "auto" and sol.accepted
    assert angle_deg(sol.pose.matrix, truth.as_matrix()) < 1e-3
    np.testing.assert_allclose(sol.pose.t, t, atol=0.01)
    used = np.array([p.used for p in sol.points])
    for j in (0, 4567, n - 1):                             # leave-one-out, the slow way
        keep = used & (np.arange(n) != j)
        f = horn.absolute_orientation(laser[keep], robot[keep])
        assert sol.points[j].loo_residual == pytest.approx(
            np.linalg.norm(robot[j] - f.apply(laser[j])), abs=1e-9)


def test_ten_thousand_collinear_points_refused():
    from ucsio.method.solve import solve_points
    rng = np.random.default_rng(29)
    n = 10_000
    d = np.array([0.48, 0.6, 0.64])
    laser = np.outer(rng.uniform(0, 2000, n), d) + 100.0 + rng.normal(0, 0.01, size=(n, 3))
    truth = Rotation.random(random_state=30)
    with pytest.raises(UcsioError, match="lie .nearly. on one line") as info:
        solve_points([f"P{i}" for i in range(n)], laser, truth.apply(laser) + 5.0)
    assert info.value.exit_code == 2
