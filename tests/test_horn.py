"""Horn's absolute orientation: exact recovery, invariance, agreement with an
independent solver (scipy's Rotation.align_vectors, used only as a check),
batching, and the refusal of degenerate point sets."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from ucsio import horn
from ucsio import rotations as rot
from ucsio.errors import UcsioError


def fixture_points(rng, n=8, size=(1200.0, 800.0, 300.0)):
    return rng.uniform(0.0, 1.0, size=(n, 3)) * np.asarray(size)


def angle_deg(R1, R2):
    return float(horn.rotation_angle_deg(np.asarray(R1), np.asarray(R2)))


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
    np.testing.assert_allclose(horn.quat_to_matrix(r.as_quat(scalar_first=True)), r.as_matrix(),
                               atol=1e-15)


def test_rotation_angle_near_0_and_180():
    base = Rotation.random(random_state=16)
    for ang in [0.0, 1e-9, 1e-4, 33.0, 179.9999, 180.0]:
        d = Rotation.from_rotvec(np.radians(ang) * np.array([0.0, 0.8, 0.6]))
        got = angle_deg(base.as_matrix(), (base * d).as_matrix())
        assert got == pytest.approx(ang, abs=1e-9)
