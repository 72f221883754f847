"""Issue 25 point 3: the solved TCP's 95 % holds for the fits the gates accept.

The gates and the TCP's prediction judge the same residual σ s, so accepted
fits are those whose s came out small, and the plain quantile s · q_ν was
missed 6.2-6.9 % of the time on them. ``method.selected`` takes the quantile
given that the gates passed. Here:

- the conditional quantile, against a Monte Carlo of its own model (d ~
  N(0, σ² K) independent of s² ~ σ² χ²_ν / ν, kept where s <= u σ): missed
  5 % of the time within three binomial standard errors and the cube-root
  approximations' own 0.4 points, where the plain quantile misses more than
  that (so the test tells them apart);
- ``solve --tcp solve`` reports it: a fit accepted near the gate states the
  selected quantile (and scales the TCP's std with it), a fit far from the
  gate the plain one.

The whole product over 2,000 and more accepted cells is
benchmarks/calibrate_tcp.py (too slow for the suite); docs/method.md quotes it.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from test_tcp_solve import cell
from ucsio.method import precision, tcp_solve
from ucsio.method.quantile import norm95_sq
from ucsio.method.selected import conditional_q95

DRAWS = 200_000
#: the cube-root tails' own error in a miss rate (the quantiles are within about
#: 1 % of the exact ones, tests/test_calibration.py)
APPROX = 0.004


@pytest.mark.parametrize("dof, u", [(9, 0.8), (15, 0.9), (15, 1.1), (3, 0.9), (21, 1.0)])
def test_the_selected_quantile_is_missed_5_percent_of_the_accepted_fits(dof, u):
    rng = np.random.default_rng(dof * 100 + int(u * 10))
    A = rng.normal(size=(3, 3)) * [1.0, 0.5, 0.2]
    K = A @ A.T
    mean, var = float(np.trace(K)), 2.0 * float(np.trace(K @ K))
    d = np.linalg.norm(rng.normal(size=(DRAWS, 3)) @ np.linalg.cholesky(K).T, axis=1)
    s = np.sqrt(rng.chisquare(dof, DRAWS) / dof)
    kept = s <= u
    n = int(kept.sum())
    se = math.sqrt(0.05 * 0.95 / n)
    k = conditional_q95(mean, var, dof, u)
    rate = float(np.mean(d[kept] > k * s[kept]))
    assert abs(rate - 0.05) < APPROX + 3 * se, (rate, n)
    plain = math.sqrt(norm95_sq(mean, var, dof))
    before = float(np.mean(d[kept] > plain * s[kept]))
    assert before > 0.05 + APPROX + 3 * se, before                        # the selection bites
    # far from the gate: the plain quantile
    assert conditional_q95(mean, var, dof, 50.0) == pytest.approx(plain, rel=1e-12)


def _joint(threshold):
    meas, _, _ = cell(3, 30)
    meas.flange[:, :3, 3] += np.random.default_rng(1).normal(0, 0.2, (8, 3))   # residuals set σ
    return meas, tcp_solve.solve_joint(meas, threshold=threshold)


def test_solve_reports_the_selected_doubt_near_the_gate():
    meas, far = _joint(threshold=50.0)
    assert far.accepted and far.precision["sigma_source"] == "residuals"
    R = np.array(far.pose.matrix)
    K = tcp_solve.covariance(meas.laser, meas.flange[:, :3, :3], R, np.ones(8), 1.0)
    s, dof = far.consistency["sigma_residual"], 15.0
    plain = float(precision.q95(K[None, 6:, 6:], far.consistency["sigma_stated"], s, dof)[0])
    assert far.tcp_solved["at_95"] == pytest.approx(plain, rel=1e-9)       # far: as before
    # a threshold just above what the gates saw: accepted, and near the gate
    gate = max(plain, far.precision["at_reach"])
    _, near = _joint(threshold=gate * 1.02)
    assert near.accepted
    ratio = near.tcp_solved["at_95"] / plain
    assert 1.1 < ratio < 2.0 and near.precision["tcp_at_95"] == near.tcp_solved["at_95"]
    for axis in "xyz":
        assert near.tcp_solved["std"][axis] == pytest.approx(far.tcp_solved["std"][axis] * ratio,
                                                             rel=1e-9)
    # below it: rejected, with the doubt the gate judged
    _, rejected = _joint(threshold=gate * 0.98)
    assert not rejected.accepted and rejected.tcp_solved["at_95"] == pytest.approx(plain,
                                                                                   rel=1e-9)
