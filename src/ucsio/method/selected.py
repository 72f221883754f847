"""A 95 % that holds for the fits the gates accept (issue 25 point 3).

Where the residuals set the noise, a prediction is s · q_ν: s the residuals'
σ, q_ν the quantile of |d|/s (``quantile``, Student's t in several
dimensions). Over all fits it is missed 5 % of the time. But the gates judge
the same s: a fit passes only where s · a <= threshold (a, per unit noise,
the largest of the gates' factors), so the accepted fits are those whose
residuals happened to understate the noise, and a solved TCP's 95 % was
missed 6.2-6.9 % of the time on them.

Given that the gate passed, s is drawn below s_max = threshold / a. In units
of σ, with W = s²/σ² ~ χ²_ν/ν independent of the error d (least squares),
the quantile k that the accepted fits miss 5 % of the time solves

    ∫_0^u² P(|d|²/σ² > k² w) f_W(w) dw = 0.05 · F_W(u²),   u = s_max / σ

(|d|²/σ²'s tail by Wilson and Hilferty's cube root, the integral by
Gauss-Legendre). σ is not known: it is taken at the residuals' 90 % upper
bound, s √(ν / χ²_ν(0.10)), a noise the residuals do not rule out (at s
itself the correction is too small where the gates reject many fits).
Far from the gate (u large) k is the plain q_ν; it is never below it. The
Monte Carlo in benchmarks/calibrate_tcp.py measures the result over 2,000
and more accepted cells (docs/method.md, "Calibrated").
"""
from __future__ import annotations

import math

import numpy as np

from .quantile import INF, chi2_sf, norm95_sq

MISS = 0.05
#: the residuals' upper bound on σ at which the gate's truncation is judged
UPPER = 0.10
_Z_UPPER = -1.2815515655446004          # the standard normal quantile at UPPER
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(64)
_erfc = np.frompyfunc(math.erfc, 1, 1)


def chi2_quantile(p: float, dof: float) -> float:
    """χ²_dof's p quantile by Wilson and Hilferty's cube root (z the normal
    quantile at p; here only p = UPPER)."""
    h = 2.0 / (9.0 * dof)
    return dof * max(1.0 - h + _Z_UPPER * math.sqrt(h), 1e-6) ** 3


def _tail(y, mean: float, h: float):
    """P(|d|² > y) for |d|² of ``mean`` and cube-root variance h (units of σ²)."""
    z = (np.cbrt(np.asarray(y, dtype=float) / mean) - (1.0 - h)) / math.sqrt(h)
    return 0.5 * _erfc(z / math.sqrt(2.0)).astype(float)


def conditional_q95(mean: float, var: float, dof: float, u: float) -> float:
    """k (per unit s) with P(|d| > k s | s <= u σ) = 5 %, for |d|² of ``mean``
    and ``var`` in units of σ² and s² ~ σ² χ²_dof / dof. Never below the
    unconditional q_ν."""
    plain = math.sqrt(norm95_sq(mean, var, dof))
    if not (mean > 0 and math.isfinite(dof) and u > 0):
        return plain
    # where W = χ²_ν/ν has (almost) no mass the integrand is 0: stop there
    hi = min(u * u, 1.0 + 12.0 * math.sqrt(2.0 / dof) + 60.0 / dof)
    w = (_NODES + 1.0) * (hi / 2.0)
    a = dof / 2.0
    log_f = (a - 1.0) * np.log(dof * w) - dof * w / 2.0 - math.lgamma(a) - a * math.log(2.0)
    fw = np.exp(log_f) * dof * _WEIGHTS * (hi / 2.0)
    accepted = 1.0 - chi2_sf(dof * u * u, dof)
    if not accepted > 1e-12:
        return plain
    h = var / (9.0 * mean * mean)

    def miss(k: float) -> float:
        return float((fw * _tail(k * k * w, mean, h)).sum()) / accepted

    lo, hi_k = plain, plain
    while miss(hi_k) > MISS and hi_k < 1e3 * plain:
        lo, hi_k = hi_k, hi_k * 1.5
    if lo == hi_k:
        return plain
    for _ in range(40):                         # bisection to a relative 1e-9
        mid = 0.5 * (lo + hi_k)
        lo, hi_k = (mid, hi_k) if miss(mid) > MISS else (lo, mid)
        if hi_k - lo <= 1e-9 * hi_k:
            break
    return max(plain, hi_k)


def accepted_q95(cov, s: float, dof: float, threshold: float, gate_per_s: float) -> float:
    """The 95 % displacement (mm) of a (3, 3) covariance per unit noise, for
    a fit the gates accepted: s the residuals' σ, ``gate_per_s`` the gates'
    largest residual-side value per unit s (the fit passed because s times
    it is within ``threshold``)."""
    cov = np.asarray(cov, dtype=float)
    mean = float(np.trace(cov))
    var = 2.0 * float(np.einsum("ij,ji->", cov, cov))
    if not (s > 0 and gate_per_s > 0 and mean > 0) or dof == INF:
        return s * math.sqrt(norm95_sq(mean, var, dof)) if mean > 0 else 0.0
    sigma_upper = s * math.sqrt(dof / chi2_quantile(UPPER, dof))
    u = threshold / gate_per_s / sigma_upper
    return s * conditional_q95(mean, var, dof, u)
