"""95 % quantiles of a displacement's length, and the χ² tail: plain math.

Written with arithmetic operators only, so ``norm95_sq`` takes floats or
numpy arrays alike: ``precision`` calls it on arrays, ``diff --points``
(which imports no numpy) on floats, through ``at_point95``.

The length of a Gaussian displacement d ~ N(0, σ² K) (K 3x3): |d|² has mean
m = σ² tr K and variance v = 2 σ⁴ tr K². Satterthwaite matches them with g
χ²_k (g = v / 2m, k = 2m² / v, g k = m).

- σ known (the stated noise): the 95 % quantile of χ²_k / k by Wilson and
  Hilferty's cube root, (1 − h + z √h)³ with h = 2 / 9k.
- σ estimated from ν degrees of freedom (the residuals', s² ~ σ² χ²_ν / ν,
  independent of the fit's parameters in a least-squares fit): |d|² / s² ≈
  g k F(k, ν) with s in place of σ, the multivariate form of Student's t
  (k = 1: |d| / s ~ |t_ν|). F's 95 % quantile by Paulson's cube-root
  approximation (Paulson 1942; Johnson, Kotz & Balakrishnan, Continuous
  Univariate Distributions 2, 27.5), which is Wilson–Hilferty's as ν → ∞.
  Within about 1.2 % of the exact quantile of |d| for ν ≥ 4, 3 % at ν = 3
  (conservative; tests/test_plan.py holds it to scipy).
"""
from __future__ import annotations

import math

Z95 = 1.6448536269514722      # one-sided standard normal quantile at 0.95
INF = math.inf


def norm95_sq(mean, var, dof=INF):
    """q² with P(|d|² <= q²) = 0.95, from |d|²'s ``mean`` (> 0) and ``var``
    in units of the noise variance, and the noise's degrees of freedom
    (INF: known). Floats or arrays."""
    ha = var / (9.0 * mean * mean)           # 2 / 9k
    hb = 2.0 / (9.0 * dof)                   # 2 / 9ν (0 for a known noise)
    a, b = 1.0 - hb, 1.0 - ha
    # Paulson: z = (a y − b) / √(hb y² + ha) with y = F^(1/3); the larger root
    y = (a * b + Z95 * (a * a * ha + hb * b * b - Z95 * Z95 * ha * hb) ** 0.5) / (
        a * a - Z95 * Z95 * hb)
    return mean * y * y * y


def at_point95(K, c, R, w, sigma_stated: float, sigma_residual: float = 0.0,
               dof: float = INF) -> float:
    """The 95 % displacement (mm) of the point ``w`` (UCS, mm) of a frame
    whose first-order covariance per unit noise is K (6x6 nested lists: dt
    at the UCS point ``c``, dθ, in robot world axes) and rotation R (3x3):
    the larger of the stated noise's quantile and the residuals' (σ
    estimated from ``dof``). ``precision.at_points95`` is the same, batched."""
    d = [w[0] - c[0], w[1] - c[1], w[2] - c[2]]
    p = [sum(R[i][j] * d[j] for j in range(3)) for i in range(3)]
    # J = [I, -[p]x]: the displacement dt + dθ x p
    J = [[1.0, 0.0, 0.0, 0.0, p[2], -p[1]],
         [0.0, 1.0, 0.0, -p[2], 0.0, p[0]],
         [0.0, 0.0, 1.0, p[1], -p[0], 0.0]]
    JK = [[sum(J[a][i] * K[i][j] for i in range(6)) for j in range(6)] for a in range(3)]
    S = [[sum(JK[a][j] * J[b][j] for j in range(6)) for b in range(3)] for a in range(3)]
    mean = S[0][0] + S[1][1] + S[2][2]
    if not mean > 0:
        return 0.0
    var = 2.0 * sum(S[a][b] * S[b][a] for a in range(3) for b in range(3))
    q = sigma_stated * math.sqrt(norm95_sq(mean, var))
    if sigma_residual > 0:
        q = max(q, sigma_residual * math.sqrt(norm95_sq(mean, var, dof)))
    return q


def chi2_sf(x: float, dof: float) -> float:
    """P(χ²_dof >= x): the regularised upper incomplete gamma Q(dof/2, x/2),
    by its series below a + 1 and its continued fraction above (Numerical
    Recipes, 6.2)."""
    if not x > 0:
        return 1.0
    a, x = 0.5 * dof, 0.5 * x
    log_front = a * math.log(x) - x - math.lgamma(a)
    if x < a + 1.0:                      # P by the series, Q = 1 - P
        term = total = 1.0 / a
        ap = a
        for _ in range(10_000):
            ap += 1.0
            term *= x / ap
            total += term
            if abs(term) < abs(total) * 1e-16:
                break
        return max(0.0, 1.0 - total * math.exp(log_front))
    tiny = 1e-300                        # Q by Lentz's continued fraction
    b = x + 1.0 - a
    c = 1.0 / tiny
    d = 1.0 / b
    h = d
    for i in range(1, 10_000):
        an = -i * (i - a)
        b += 2.0
        d = an * d + b
        d = tiny if abs(d) < tiny else d
        c = b + an / c
        c = tiny if abs(c) < tiny else c
        d = 1.0 / d
        delta = d * c
        h *= delta
        if abs(delta - 1.0) < 1e-16:
            break
    return min(1.0, math.exp(log_front) * h)
