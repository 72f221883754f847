"""The determinacy gate (SPEC, "The method", point 7): how well do the used
points pin the fitted frame down?

A fit can have small residuals and still be far off: points near a line leave
the rotation about that line to the noise, and the residuals cannot show it.
So, from the fitted geometry alone, predict how far a point ``reach`` mm from
the points' centroid may be displaced (95 %) and reject the dataset when that
exceeds the threshold.

First-order covariance of the weighted least-squares fit, linearised about it
in coordinates centred on the weighted centroid (p_i = R (l_i - c)):

    robot_i = exp([dθ]x) R l_i + t + dt  ->  J_i = [I3, -[p_i]x]  for (dt, dθ)
    H = Σ w_i J_i^T J_i,   G = Σ w_i² J_i^T J_i,   cov = σ² H⁻¹ G H⁻¹

where σ, the per-axis noise of a point, is the larger of the stated noise
√(σ_laser² + σ_robot²) and the residuals' own estimate √(Σ|e_i|² / (3n − 6))
(3n numbers, 6 parameters): stated noise cannot make a fit whose residuals
say otherwise look precise.

A point at p = c + r·u moves by dt − r [u]x dθ. The worst direction u is the
one across which the orientation is least certain (the eigenvector of the
smallest eigenvalue of cov_θ: every other rotation axis then swings p);
both signs of u are tried. The 95 % quantile of |displacement| for that 3x3
covariance is the Satterthwaite scaled χ² (matching mean and variance of
|d|²) with the Wilson–Hilferty quantile: within about 1 % of the exact value
from one to three dimensions.

Everything is batched over a leading axis (``batch`` judges a fleet at once).
"""
from __future__ import annotations

import math

import numpy as np

Z95 = 1.6448536269514722      # one-sided standard normal quantile at 0.95


def skew(v: np.ndarray) -> np.ndarray:
    """(..., 3) -> (..., 3, 3) cross-product matrices [v]x."""
    x, y, z = np.moveaxis(v, -1, 0)
    o = np.zeros_like(x)
    return np.stack([np.stack([o, -z, y], -1), np.stack([z, o, -x], -1),
                     np.stack([-y, x, o], -1)], axis=-2)


def quantile95_norm(cov: np.ndarray) -> np.ndarray:
    """(..., 3, 3) covariances -> the 95 % quantile of |d|, d ~ N(0, cov)."""
    mean = np.trace(cov, axis1=-2, axis2=-1)
    var = 2.0 * np.einsum("...ij,...ji->...", cov, cov)
    with np.errstate(divide="ignore", invalid="ignore"):
        g = var / (2.0 * mean)
        k = 2.0 * mean * mean / var
        h = 2.0 / (9.0 * k)
        q = g * k * (1.0 - h + Z95 * np.sqrt(h)) ** 3
    return np.sqrt(np.where(mean > 0, q, 0.0))


def at_reach95(cov: np.ndarray, reach) -> np.ndarray:
    """(B, 6, 6) covariances of (dt at the centroid, dθ) -> the 95 % displacement
    (B,) of a point ``reach`` mm from the centroid, in the worst direction
    (module docstring). Also used for the joint TCP model's frame block."""
    ctt, ctq, cqq = cov[:, :3, :3], cov[:, :3, 3:], cov[:, 3:, 3:]
    evals, evecs = np.linalg.eigh(cqq)
    u = evecs[:, :, 0]                                           # least-doubt axis
    r = np.asarray(reach, dtype=float).reshape(-1)[:, None, None]
    worst = np.zeros(len(cov))
    for sgn in (1.0, -1.0):
        U = skew(sgn * u)
        cp = ctt - r * (ctq @ np.swapaxes(U, 1, 2)) - r * (U @ np.swapaxes(ctq, 1, 2)) \
            + r * r * (U @ cqq @ np.swapaxes(U, 1, 2))
        worst = np.maximum(worst, quantile95_norm(cp))
    return worst


def residual_sigma(sum_e2, n_used, params: int = 6):
    """Per-axis noise the residuals show: √(Σ|e_i|² / (3n − params)) (3n
    numbers, ``params`` fitted: 6 for a frame, 9 for a frame and a TCP).
    Scalars or arrays alike."""
    dof = np.maximum(3.0 * np.asarray(n_used, dtype=float) - params, 1.0)
    return np.sqrt(np.asarray(sum_e2, dtype=float) / dof)


def fit_covariance(p, w) -> np.ndarray:
    """H⁻¹ G H⁻¹ (B, 6, 6) for (dt, dθ) of weighted fits whose points, in
    robot axes about the origin the translation is taken at, are p (B, n, 3)
    with weights w (B, n): J_i = [I3, -[p_i]x], H = Σ w_i J_i^T J_i, G = Σ w_i²
    J_i^T J_i. Times σ² it is the fit's first-order covariance."""
    p = np.asarray(p, dtype=float)
    w = np.asarray(w, dtype=float)
    # J_i^T J_i = [[I, -[p]x], [[p]x, |p|² I - p p^T]], summed with w and w².
    P = skew(p)                                                 # (B, n, 3, 3)
    inner = (np.einsum("bni,bni->bn", p, p)[..., None, None] * np.eye(3)
             - np.einsum("bni,bnj->bnij", p, p))

    def moment(v):
        M = np.zeros(p.shape[:1] + (6, 6))
        M[:, :3, :3] = v.sum(axis=1)[:, None, None] * np.eye(3)
        M[:, :3, 3:] = -np.einsum("bn,bnij->bij", v, P)
        M[:, 3:, :3] = np.einsum("bn,bnij->bij", v, P)
        M[:, 3:, 3:] = np.einsum("bn,bnij->bij", v, inner)
        return M

    with np.errstate(all="ignore"):
        Hinv = np.linalg.pinv(moment(w), hermitian=True)
        return Hinv @ moment(w * w) @ Hinv


def predict(laser, weights, R, sum_e2, n_used, sigma_stated, reach) -> dict[str, np.ndarray]:
    """The gate's numbers for a batch of fits.

    laser (B, n, 3) and weights (B, n) (0 for unused or padded points), R
    (B, 3, 3) the fitted rotations, sum_e2 (B,) Σ|e_i|² over the used points,
    n_used (B,), sigma_stated (B,) √(σ_laser² + σ_robot²), reach (B,) mm.
    Returns arrays (B,): ``sigma`` (mm), ``angle_std`` (deg, √trace cov_θ),
    ``at_reach`` (mm, 95 %), ``at_centroid`` (mm, 95 %, the translation alone)
    and ``spread`` (B, 3) principal RMS spreads of the used laser points (mm).
    """
    L = np.asarray(laser, dtype=float)
    w = np.asarray(weights, dtype=float)
    R = np.asarray(R, dtype=float)
    wsum = w.sum(axis=1)
    c = np.einsum("bn,bni->bi", w, L) / wsum[:, None]
    p = np.einsum("bij,bnj->bni", R, L - c[:, None, :])          # centred, robot axes
    sigma = np.maximum(np.asarray(sigma_stated, dtype=float), residual_sigma(sum_e2, n_used))
    cov = (sigma ** 2)[:, None, None] * fit_covariance(p, w)
    ctt, cqq = cov[:, :3, :3], cov[:, 3:, 3:]
    worst = at_reach95(cov, reach)
    C = np.einsum("bn,bni,bnj->bij", w, p, p) / wsum[:, None, None]
    spread = np.sqrt(np.clip(np.linalg.eigvalsh(C)[:, ::-1], 0.0, None))
    return {"sigma": sigma,
            "angle_std": np.degrees(np.sqrt(np.clip(np.trace(cqq, axis1=1, axis2=2), 0, None))),
            "at_reach": worst, "at_centroid": quantile95_norm(ctt), "spread": spread}


def reason(at_reach: float, at_centroid: float, reach: float, threshold: float,
           sigma: float, angle_std: float, spread) -> str:
    """Why a dataset fails the gate, and what the engineer can change."""
    s1, s2, s3 = (float(v) for v in spread)
    head = (f"the points do not pin the orientation down: a point {reach:g} mm from their "
            f"centroid is known only to {at_reach:.2f} mm (95 %), over the {threshold:g} mm "
            f"threshold (orientation ±{angle_std:.3f} deg at noise {sigma:.3f} mm per axis; "
            f"the points spread {s1:.0f} x {s2:.0f} x {s3:.0f} mm)")
    if at_centroid >= threshold:
        return head + "; the noise alone is too large for the threshold: measure more points" \
                      " or find the source of the scatter"
    # The orientation's share scales with 1/spread²: the spread that would do.
    k = math.sqrt(max(at_reach ** 2 - at_centroid ** 2, 0.0) /
                  max(threshold ** 2 - at_centroid ** 2, 1e-300))
    return head + (f"; spread the points about {k:.1f} times wider across the fixture, or "
                   "measure more points")
