"""Issue 20 point 4: a 95 % prediction is missed 5 % of the time.

Where the residuals set the noise, σ is an estimate from 3n − 6 numbers (3n −
9 with a solved TCP), and used as if known, a 95 % prediction is missed about
8-10 % of the time on fixtures of 5 to 7 points. The prediction now takes the
quantile for an estimated scale (``ucsio.method.quantile``: the F quantile,
Student's t in several dimensions). These tests draw seeded random fixtures
with a known frame (and TCP), fit them with the product's own code, and count
how often the true error exceeds the prediction: for the frame (the gate's
point at --reach), for working points, and for the solved TCP, each within 5 ±
1.5 %. The same fits judged with the old plug-in quantile miss more than 6.5 %,
so the tests tell the two apart.

The stated noise is set far below the true one, so the residuals set σ (where
the stated σ is right and larger, the prediction uses it and is conservative).
The fixtures are spread and the noise moderate, so the gate and the exclusion
rule seldom bind: a gate that rejects many fits keeps those whose residuals
happened to be small, and no quantile undoes that selection.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats
from scipy.spatial.transform import Rotation

from ucsio.method import precision, tcp_solve, working
from ucsio.method.quantile import INF, chi2_sf, norm95_sq
from ucsio.method.solve import Dataset, solve_many
from ucsio.readers.points import Points

FIXTURES = 2000
STATED = 0.001          # mm: far below the true noise, so the residuals set σ
LOW, HIGH = 3.5, 6.5    # % : 5 ± 1.5


# ------------------------------------------------------------------ the quantiles

@pytest.mark.parametrize("k", [1, 1.5, 2, 3])
@pytest.mark.parametrize("dof", [3, 4, 6, 9, 12, 24, 60, INF])
def test_quantile_for_an_estimated_noise_matches_scipy(k, dof):
    """|d|²/s² ≈ k F(k, ν) (χ²_k for a known noise): Paulson's approximation
    within 1.3 % of scipy's exact quantile of |d| from ν = 4, 3.1 % at 3."""
    q = math.sqrt(norm95_sq(k, 2.0 * k, dof))          # isotropic in k dimensions, unit noise
    exact = math.sqrt(k * stats.f.ppf(0.95, k, dof) if dof != INF else stats.chi2.ppf(0.95, k))
    assert q == pytest.approx(exact, rel=0.013 if dof >= 4 else 0.031)


@pytest.mark.parametrize("x, dof", [(3, 3), (30, 12), (100, 21), (0.1, 3), (21, 21), (60, 12),
                                    (500, 30), (1e-6, 6), (8.5, 9)])
def test_chi2_tail_matches_scipy(x, dof):
    assert chi2_sf(x, dof) == pytest.approx(stats.chi2.sf(x, dof), rel=1e-9, abs=1e-300)


# ------------------------------------------------------------------ the frame

def _frames(seed: int):
    """FIXTURES random fixtures of 5-7 points, 0.03-0.12 mm of noise, four
    working points each, 200-2000 mm from the centroid: solved with
    ``solve_many`` as ``batch`` solves them."""
    rng = np.random.default_rng(seed)
    data, truth = [], []
    for _ in range(FIXTURES):
        n = int(rng.integers(5, 8))
        laser = rng.uniform(-0.5, 0.5, (n, 3)) * rng.uniform([800, 600, 0], [1600, 1200, 400])
        R = Rotation.random(random_state=rng.integers(1 << 31))
        t = rng.uniform(-3000, 3000, 3)
        robot = R.apply(laser) + t + rng.normal(0, rng.uniform(0.03, 0.12), (n, 3))
        d = rng.normal(size=(4, 3))
        at = laser.mean(0) + d / np.linalg.norm(d, axis=1)[:, None] * rng.uniform(200, 2000, (4, 1))
        data.append(Dataset(names=[f"P{i}" for i in range(n)], laser=laser, robot=robot,
                            weights=np.ones(n), min_points=5, sigma_stated=STATED,
                            at=Points(None, list("abcd"), [None] * 4, at)))
        truth.append((R.as_matrix(), t, at))
    return solve_many(data), truth


def test_the_frame_and_its_working_points_are_calibrated():
    sols, truth = _frames(2026)
    reach, reach_plug, wp, wp_plug = [], [], [], []
    for sol, (R_true, t_true, at) in zip(sols, truth):
        if not sol.accepted:
            continue
        R, t, cov = np.array(sol.pose.matrix), np.array(sol.pose.t), sol.covariance
        K, c = np.array(cov["frame"]), np.array(cov["about"])
        # the gate's point: 1000 mm from the centroid across the least certain axis
        u = np.linalg.eigh(K[3:, 3:])[1][:, 0]
        ends = c + np.array([u, -u]) @ R * 1000.0               # UCS
        pts = np.vstack([ends, at])
        err = np.linalg.norm(pts @ R.T + t - (pts @ R_true.T + t_true), axis=1)
        P = (pts - c) @ R.T
        q = precision.at_points95(K[None], P, cov["sigma_stated"], cov["sigma_residual"],
                                  cov["dof"])[0]
        plug = precision.at_points95(K[None], P, cov["sigma_residual"])[0]
        j = int(np.argmax(q[:2]))
        assert q[j] == pytest.approx(sol.precision["at_reach"], rel=1e-9)
        assert q[2:] == pytest.approx([w["at_95"] for w in sol.working_points], rel=1e-9)
        reach.append(err[j] > q[j])
        reach_plug.append(err[j] > plug[j])
        wp.extend(err[2:] > q[2:])
        wp_plug.extend(err[2:] > plug[2:])
    assert len(reach) > 0.95 * FIXTURES                        # the gate seldom binds here
    for name, miss, old in (("reach", reach, reach_plug), ("working points", wp, wp_plug)):
        rate, before = 100 * np.mean(miss), 100 * np.mean(old)
        assert LOW <= rate <= HIGH, (name, rate)
        assert before > HIGH, (name, before)                  # the plug-in quantile misses more


# ------------------------------------------------------------------ the TCP

GEOMETRIES, DRAWS = 200, 10


def test_the_solved_tcp_and_its_frame_are_calibrated():
    """The joint model: 200 random cells of 6-8 points (flange turned ±30°),
    10 noisy measurements each, refitted by the product's Gauss-Newton in one
    batch per cell; the prediction as ``solve_joint`` makes it."""
    rng = np.random.default_rng(7)
    tcp_miss, tcp_plug, wp_miss = [], [], []
    for _ in range(GEOMETRIES):
        n = int(rng.integers(6, 9))
        R_ucs = Rotation.from_euler("ZYX", rng.uniform(-60, 60, 3), degrees=True)
        t_ucs = rng.uniform(-1500, 1500, 3) + [2000, 0, 500]
        x_true = rng.uniform(-50, 50, 3) + [0, 0, 150]
        laser = rng.uniform(0, 1, (n, 3)) * [1000, 700, 250]
        world = R_ucs.apply(laser) + t_ucs
        Rf = np.array([(Rotation.from_euler("ZYX", [180, 0, 180], degrees=True)
                        * Rotation.from_euler("ZYX", rng.uniform(-30, 30, 3), degrees=True))
                       .as_matrix() for _ in range(n)])
        tf = world - np.einsum("nij,j->ni", Rf, x_true)
        sigma = rng.uniform(0.03, 0.12)
        noisy_l = laser + rng.normal(0, sigma / 3, (DRAWS, n, 3))
        noisy_t = tf + rng.normal(0, sigma, (DRAWS, n, 3))
        w = np.ones(n)
        R, t, x = tcp_solve.gauss_newton(noisy_l, Rf, noisy_t, np.ones((DRAWS, n)),
                                         np.repeat(R_ucs.as_matrix()[None], DRAWS, 0),
                                         np.repeat(t_ucs[None], DRAWS, 0),
                                         np.repeat(x_true[None], DRAWS, 0))
        e = tcp_solve.residuals(noisy_l, Rf, noisy_t, R, t, x)
        s = precision.residual_sigma((e ** 2).sum(axis=(1, 2)), n, params=9)
        dof = float(precision.dof_of(n, params=9))
        at = Points(None, list("abcd"), [None] * 4, laser.mean(0) + rng.normal(0, 800, (4, 3)))
        for d in range(DRAWS):
            K = tcp_solve.covariance(noisy_l[d], Rf, R[d], w, 1.0)
            q = precision.q95(K[None, 6:, 6:], STATED, s[d], dof)[0]
            err = np.linalg.norm(x[d] - x_true)
            tcp_miss.append(err > q)
            tcp_plug.append(err > precision.q95(K[None, 6:, 6:], s[d])[0])
            c = noisy_l[d].mean(0)
            cov = working.covariance_json(K[:6, :6], c, STATED, s[d], dof)
            rows, _ = working.predict(cov, R[d], at)
            true_at = at.xyz @ R_ucs.as_matrix().T + t_ucs
            fit_at = at.xyz @ R[d].T + t[d]
            wp_miss.extend(np.linalg.norm(fit_at - true_at, axis=1) > [r["at_95"] for r in rows])
    rate, before, wrate = (100 * np.mean(v) for v in (tcp_miss, tcp_plug, wp_miss))
    assert LOW <= rate <= HIGH, rate
    assert LOW <= wrate <= HIGH, wrate
    assert before > HIGH, before


def test_the_harness_predicts_what_solve_joint_reports():
    """The TCP test above computes the prediction as solve_joint does: the
    same numbers for a measured cell."""
    from test_tcp_solve import cell

    meas, _, _ = cell(3, 30)
    meas.flange[:, :3, 3] += np.random.default_rng(1).normal(0, 0.2, (8, 3))    # residuals set σ
    sol = tcp_solve.solve_joint(meas, sigma_laser=STATED, sigma_robot=0.0, threshold=5.0)
    R = np.array(sol.pose.matrix)
    K = tcp_solve.covariance(meas.laser, meas.flange[:, :3, :3], R, np.ones(8), 1.0)
    r = np.array([p.residual for p in sol.points])
    s = precision.residual_sigma((r ** 2).sum(), 8, params=9)
    assert sol.precision["sigma_source"] == "residuals"
    assert sol.tcp_solved["at_95"] == pytest.approx(
        precision.q95(K[None, 6:, 6:], STATED, s, 15.0)[0], rel=1e-9)
    assert sol.consistency["dof"] == 15 and sol.consistency["p"] < 0.01


# ------------------------------------------------------------------ the paper's example

def test_the_papers_example_stays_accepted():
    """SPEC, the method, 7: Table 2 with P5 excluded, σ ≈ 0.46 mm from the
    residuals, about 1.1 mm at 1000 mm with the noise taken as known, and
    accepted. The table's numbers could not be found; this is a synthetic
    fixture built to match that description: ten points over 1.4 x 0.9 x 0.35
    m with a 6 mm blunder at P5, the noise scaled so the used residuals give
    0.46 mm and the layout so the known-noise prediction is 1.1 mm. The
    quantile for an estimated noise (24 degrees of freedom) raises it by
    about 10 %: still within 1.5 mm."""
    from ucsio.method.solve import solve_points

    rng = np.random.default_rng(5)
    base = rng.uniform(-0.5, 0.5, (10, 3)) * [1400, 900, 350]
    noise = rng.normal(size=(10, 3))
    R = Rotation.from_euler("ZYX", [30, -10, 5], degrees=True)

    def fit(scale, amplitude):
        laser = base * scale
        robot = R.apply(laser) + [4000, 1000, 800] + amplitude * noise
        robot[4] += [6.0, 0, 0]
        return solve_points([f"P{i + 1}" for i in range(10)], laser, robot)

    amplitude = 0.46
    for _ in range(3):                              # residuals of 0.46 mm exactly
        sol = fit(1.0, amplitude)
        amplitude *= 0.46 / sol.precision["sigma"]
    lo, hi = 0.2, 3.0                               # the layout giving 1.1 mm as known noise
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        sol = fit(mid, amplitude)
        K = np.array(sol.covariance["frame"])
        known = float(precision.at_reach95(K[None], 1000.0, sol.precision["sigma"])[0])
        lo, hi = (mid, hi) if known > 1.1 else (lo, mid)
    assert [pt.name for pt in sol.points if not pt.used] == ["P5"]
    assert sol.precision["sigma"] == pytest.approx(0.46, rel=0.01)
    assert known == pytest.approx(1.1, rel=0.01)
    assert sol.precision["dof"] == 3 * 9 - 6
    assert sol.precision["sigma_source"] == "residuals"
    assert 1.1 < sol.precision["at_reach"] < 1.5 and sol.accepted
