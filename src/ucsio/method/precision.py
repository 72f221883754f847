"""The determinacy gate (SPEC, "The method", point 7): how well do the used
points pin the fitted frame down? And, with the same covariance, how well at
the points where the robot works (SPEC, "Planning and working points").

A fit can have small residuals and still be far off: points near a line leave
the rotation about that line to the noise, and the residuals cannot show it.
So, from the fitted geometry alone, predict how far a point ``reach`` mm from
the points' centroid may be displaced (95 %) and reject the dataset when that
exceeds the threshold.

First-order covariance of the weighted least-squares fit, linearised about it
in coordinates centred on the weighted centroid (p_i = R (l_i - c)):

    robot_i = exp([dθ]x) R l_i + t + dt  ->  J_i = [I3, -[p_i]x]  for (dt, dθ)
    H = Σ w_i J_i^T J_i,   G = Σ w_i² J_i^T J_i,   cov = σ² H⁻¹ G H⁻¹

K = H⁻¹ G H⁻¹ is the covariance per unit noise; ``moments`` gives H and G,
so ``ucsio plan`` can add or take away a point's term without refitting.

The noise σ per axis: the stated √(σ_laser² + σ_robot²), or the residuals'
own estimate s = √(Σ|e_i|² / (3n − 6)) (3n numbers, 6 parameters) where
that says more: stated noise cannot make a fit whose residuals say otherwise
look precise. An estimate from a few residuals is not a known σ: where s
sets the prediction, the quantile is the one for an estimated scale
(``quantile.norm95_sq`` with ν = 3n − 6, Student's t in several dimensions),
so that 95 % means 95 % (tests/test_plan.py, the calibration). A prediction
is the larger of the two: σ_stated · q(K) and s · q_ν(K).

A point at p = c + r·u moves by dt − r [u]x dθ. The worst direction u is the
one across which the orientation is least certain (the eigenvector of the
smallest eigenvalue of cov_θ: every other rotation axis then swings p);
both signs of u are tried. At a working point w the displacement is
J_w (dt, dθ) with J_w = [I, -[R (w - c)]x]; its 3x3 covariance S is
quadratic in w, and the quantile needs only tr S and tr S² (degree 2 and 4
in w), so ``at_points95`` evaluates many covariances (candidate plans) at
many points as two matrix products of coefficients and monomials.

Everything is batched over a leading axis (``batch`` judges a fleet at once).
"""
from __future__ import annotations

import math

import numpy as np

from .quantile import INF, Z95, norm95_sq  # noqa: F401  (Z95 re-exported)


def skew(v: np.ndarray) -> np.ndarray:
    """(..., 3) -> (..., 3, 3) cross-product matrices [v]x."""
    x, y, z = np.moveaxis(v, -1, 0)
    o = np.zeros_like(x)
    return np.stack([np.stack([o, -z, y], -1), np.stack([z, o, -x], -1),
                     np.stack([-y, x, o], -1)], axis=-2)


def _q95(mean, var, dof=INF):
    """√norm95_sq on arrays; 0 where the covariance is 0."""
    with np.errstate(divide="ignore", invalid="ignore"):
        q = norm95_sq(mean, var, dof)
    return np.sqrt(np.where(mean > 0, q, 0.0))


def quantile95_norm(cov: np.ndarray, dof=INF) -> np.ndarray:
    """(..., 3, 3) covariances -> the 95 % quantile of |d|, d ~ N(0, cov);
    with ``dof`` finite, cov's scale estimated from that many degrees of
    freedom (``quantile``)."""
    mean = np.trace(cov, axis1=-2, axis2=-1)
    var = 2.0 * np.einsum("...ij,...ji->...", cov, cov)
    return _q95(mean, var, dof)


def q95(cov: np.ndarray, sigma_stated=1.0, sigma_residual=0.0, dof=INF) -> np.ndarray:
    """(B, 3, 3) covariances per unit noise -> the 95 % displacement (B,):
    max(σ_stated q(K), s q_ν(K)) (module docstring)."""
    sigma_stated = np.broadcast_to(np.asarray(sigma_stated, float), cov.shape[:1])
    sigma_residual = np.broadcast_to(np.asarray(sigma_residual, float), cov.shape[:1])
    dof = np.broadcast_to(np.asarray(dof, float), cov.shape[:1])
    return np.maximum(sigma_stated * quantile95_norm(cov),
                      sigma_residual * quantile95_norm(cov, dof))


def at_reach95(cov: np.ndarray, reach, sigma_stated=1.0, sigma_residual=0.0,
               dof=INF) -> np.ndarray:
    """(B, 6, 6) covariances of (dt at the centroid, dθ) -> the 95 % displacement
    (B,) of a point ``reach`` mm from the centroid, in the worst direction
    (module docstring). ``cov`` is per unit noise with the noise given
    (``q95``), or already scaled (the defaults). Also used for the joint
    TCP model's frame block."""
    ctt, ctq, cqq = cov[:, :3, :3], cov[:, :3, 3:], cov[:, 3:, 3:]
    evals, evecs = np.linalg.eigh(cqq)
    u = evecs[:, :, 0]                                           # least-doubt axis
    r = np.asarray(reach, dtype=float).reshape(-1)[:, None, None]
    worst = np.zeros(len(cov))
    for sgn in (1.0, -1.0):
        U = skew(sgn * u)
        cp = ctt - r * (ctq @ np.swapaxes(U, 1, 2)) - r * (U @ np.swapaxes(ctq, 1, 2)) \
            + r * r * (U @ cqq @ np.swapaxes(U, 1, 2))
        worst = np.maximum(worst, q95(cp, sigma_stated, sigma_residual, dof))
    return worst


def residual_sigma(sum_e2, n_used, params: int = 6):
    """Per-axis noise the residuals show: √(Σ|e_i|² / (3n − params)) (3n
    numbers, ``params`` fitted: 6 for a frame, 9 for a frame and a TCP).
    Scalars or arrays alike."""
    dof = np.maximum(3.0 * np.asarray(n_used, dtype=float) - params, 1.0)
    return np.sqrt(np.asarray(sum_e2, dtype=float) / dof)


def dof_of(n_used, params: int = 6):
    """The residuals' degrees of freedom, 3n − params (at least 1)."""
    return np.maximum(3.0 * np.asarray(n_used, dtype=float) - params, 1.0)


def point_terms(p, w) -> np.ndarray:
    """w_i J_i^T J_i (..., n, 6, 6) for points p (..., n, 3) and weights
    w (..., n): J_i = [I3, -[p_i]x]."""
    p = np.asarray(p, dtype=float)
    w = np.asarray(w, dtype=float)
    # J^T J = [[I, -[p]x], [[p]x, |p|² I - p p^T]]
    P = skew(p)
    M = np.zeros(p.shape[:-1] + (6, 6))
    M[..., :3, :3] = np.eye(3)
    M[..., :3, 3:] = -P
    M[..., 3:, :3] = P
    M[..., 3:, 3:] = (np.einsum("...i,...i->...", p, p)[..., None, None] * np.eye(3)
                      - p[..., :, None] * p[..., None, :])
    return w[..., None, None] * M


def moments(p, w) -> tuple[np.ndarray, np.ndarray]:
    """H = Σ w_i J_i^T J_i and G = Σ w_i² J_i^T J_i (B, 6, 6) for weighted fits
    whose points, in robot axes about the origin the translation is taken
    at, are p (B, n, 3) with weights w (B, n)."""
    p = np.asarray(p, dtype=float)
    w = np.asarray(w, dtype=float)
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

    return moment(w), moment(w * w)


def sandwich(H: np.ndarray, G: np.ndarray) -> np.ndarray:
    """H⁻¹ G H⁻¹ (batched; a pseudo-inverse, so an undetermined direction
    gives a finite number the degeneracy checks judge, not an exception)."""
    with np.errstate(all="ignore"):
        Hinv = np.linalg.pinv(H, hermitian=True)
        return Hinv @ G @ Hinv


def fit_covariance(p, w) -> np.ndarray:
    """H⁻¹ G H⁻¹ (B, 6, 6) for (dt, dθ) of weighted fits whose points, in
    robot axes about the origin the translation is taken at, are p (B, n, 3)
    with weights w (B, n). Times σ² it is the fit's first-order covariance."""
    return sandwich(*moments(p, w))


def shift(cov: np.ndarray, delta) -> np.ndarray:
    """(B, k, k) covariances whose first six are (dt at a point o, dθ) -> the
    same with dt at o + delta (robot axes, (B, 3)): dt' = dt − [delta]x dθ."""
    delta = np.asarray(delta, dtype=float)
    T = np.broadcast_to(np.eye(cov.shape[-1]), cov.shape).copy()
    T[:, :3, 3:6] = -skew(delta)
    return T @ cov @ np.swapaxes(T, 1, 2)


# ---------------------------------------------------------------- working points

# J(p) = [I, -[p]x] = A[0] + p_x A[1] + p_y A[2] + p_z A[3], so the covariance
# at p, S(p) = J K Jᵀ, is Σ over the 10 products p_k p_m (p_0 = 1) of fixed
# 3x3 matrices S_km; the quantile needs only tr S (degree 2 in p: 10
# monomials) and tr S² (degree 4: 35 monomials), each a dot product of
# per-covariance coefficients with the point's monomials.
_A = np.zeros((4, 3, 6))
_A[0, :, :3] = np.eye(3)
for _k in range(3):
    _A[1 + _k, :, 3:] = -skew(np.eye(3)[_k])
_PAIRS = [(k, m) for k in range(4) for m in range(k, 4)]


def _exponents(pair) -> tuple[int, int, int]:
    e = [0, 0, 0]
    for k in pair:
        if k:
            e[k - 1] += 1
    return tuple(e)


_DEG2 = [_exponents(p) for p in _PAIRS]
_DEG4 = sorted({tuple(a + b for a, b in zip(e, f)) for e in _DEG2 for f in _DEG2},
               key=lambda e: (sum(e), e))
_PRODUCT = np.zeros((len(_DEG2) ** 2, len(_DEG4)))      # (i, j) -> the monomial of their product
for _i, _e in enumerate(_DEG2):
    for _j, _f in enumerate(_DEG2):
        _PRODUCT[_i * len(_DEG2) + _j, _DEG4.index(tuple(a + b for a, b in zip(_e, _f)))] = 1.0


def trace_coefficients(cov: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(B, 6, 6) covariances -> coefficients (B, 10) of tr S(p) and (B, 35)
    of tr S(p)², S(p) the 3x3 covariance at a point p (robot axes, about the
    translation's origin): tr S = c2 · monomials(p, 2), tr S² = c4 ·
    monomials(p, 4)."""
    AC = np.einsum("kij,bjl->bkil", _A, cov)                    # (B, 4, 3, 6)
    S = np.einsum("bkil,mjl->bkmij", AC, _A)                    # A_k C A_mᵀ (B, 4, 4, 3, 3)
    S = np.stack([S[:, k, m] if k == m else S[:, k, m] + S[:, m, k] for k, m in _PAIRS], axis=1)
    c2 = np.einsum("nixx->ni", S)
    c4 = np.einsum("nk,kj->nj", np.einsum("nixy,njyx->nij", S, S).reshape(len(cov), -1),
                   _PRODUCT)
    return c2, c4


def monomials(p, degree: int = 2) -> np.ndarray:
    """(W, 3) points -> (10, W) or, degree 4, (35, W): the monomials of
    ``trace_coefficients``, in its order."""
    p = np.asarray(p, dtype=float)
    powers = [np.ones((3, len(p))), p.T]              # powers[k][axis] = p_axis ** k
    for k in range(2, degree + 1):
        powers.append(powers[-1] * p.T)
    return np.stack([powers[e[0]][0] * powers[e[1]][1] * powers[e[2]][2]
                     for e in (_DEG2 if degree == 2 else _DEG4)])


def _quantile(mean, tr2, sigma_stated, sigma_residual, dof) -> np.ndarray:
    """(B, W) tr S and tr S² per unit noise -> 95 % displacements."""
    var = 2.0 * tr2
    q = np.asarray(sigma_stated, float).reshape(-1, 1) * _q95(mean, var)
    s_res = np.asarray(sigma_residual, float).reshape(-1, 1)
    if np.any(s_res > 0):
        q = np.maximum(q, s_res * _q95(mean, var, np.asarray(dof, float).reshape(-1, 1)))
    return q


def at_points95(cov: np.ndarray, p, sigma_stated=1.0, sigma_residual=0.0,
                dof=INF) -> np.ndarray:
    """The 95 % displacement (B, W) at the points p (W, 3) (robot axes,
    relative to the translation's origin) of B covariances (B, 6, 6) per
    unit noise."""
    c2, c4 = trace_coefficients(cov)
    return _quantile(c2 @ monomials(p, 2), c4 @ monomials(p, 4), sigma_stated, sigma_residual,
                     dof)


#: (covariances x points) evaluated at once: a few arrays of this many
#: floats live at a time, a few MB each
_CHUNK = 250_000


def _cube(h):
    return (1.0 - h + Z95 * math.sqrt(h)) ** 3


#: q² / tr S lies between these (tr S² between (tr S)²/3 and (tr S)², so h =
#: 2 tr S² / 9 (tr S)² between 2/27 and 2/9, where (1 - h + z√h)³ rises):
#: a point whose trace is below KEEP times the largest cannot be the worst
KEEP = _cube(2.0 / 27.0) / _cube(2.0 / 9.0) * (1.0 - 1e-9)


def worst_at_points95(cov: np.ndarray, p, sigma_stated=1.0) -> tuple[np.ndarray, np.ndarray]:
    """(largest 95 % displacement (B,), index of its point (B,)) over the
    points p (W, 3) for each of B covariances with a known noise, in chunks
    of covariances, never the whole (B, W) at once. Per chunk: tr S at every
    point (one matrix product); tr S² only at the points whose trace can
    still make them the worst (``KEEP``; a few percent of a cell's working
    points); q²/σ² = m (1 - h + z√h)³ (``quantile.norm95_sq`` with h = 2 tr
    S² / 9 m²) ranks them, the square root taken of the worst alone."""
    c2, c4 = trace_coefficients(cov)
    m2, m4 = monomials(p, 2), monomials(p, 4)
    B, W = len(cov), m2.shape[1]
    step = max(1, _CHUNK // max(W, 1))
    where = np.empty(B, dtype=np.intp)
    rank = np.empty(B)
    with np.errstate(divide="ignore", invalid="ignore"):
        for a in range(0, B, step):
            b = min(B, a + step)
            m = np.einsum("bk,kw->bw", c2[a:b], m2)
            cols = np.flatnonzero((m >= KEEP * m.max(axis=1, keepdims=True)).any(axis=0))
            m = m[:, cols]
            h = np.einsum("bk,kw->bw", c4[a:b], m4[:, cols])
            h *= 2.0 / 9.0
            h /= m
            h /= m
            f = np.sqrt(h)
            f *= Z95
            f -= h
            f += 1.0
            h = f * f
            h *= f
            h *= m                                              # q² per unit noise
            j = np.argmax(h, axis=1)
            where[a:b] = cols[j]
            rank[a:b] = h[np.arange(b - a), j]
    worst = np.asarray(sigma_stated, float) * np.sqrt(np.where(rank > 0, rank, 0.0))
    return worst, where


# ---------------------------------------------------------------- the gate

def predict(laser, weights, R, sum_e2, n_used, sigma_stated, reach) -> dict[str, np.ndarray]:
    """The gate's numbers for a batch of fits.

    laser (B, n, 3) and weights (B, n) (0 for unused or padded points), R
    (B, 3, 3) the fitted rotations, sum_e2 (B,) Σ|e_i|² over the used points,
    n_used (B,), sigma_stated (B,) √(σ_laser² + σ_robot²), reach (B,) mm.
    Returns arrays (B,): ``sigma`` (mm, the larger of the stated and the
    residuals' noise), ``sigma_residual`` (s), ``dof`` (3n − 6),
    ``angle_std`` (deg, σ √trace cov_θ), ``at_reach`` (mm, 95 %),
    ``at_centroid`` (mm, 95 %, the translation alone), ``sigma_source``
    ('stated' or 'residuals': which bound sets at_reach), ``spread`` (B, 3)
    principal RMS spreads of the used laser points (mm), and for the working
    points ``K`` (B, 6, 6) per unit noise, in robot axes about ``centroid``
    (B, 3, in the UCS).
    """
    L = np.asarray(laser, dtype=float)
    w = np.asarray(weights, dtype=float)
    R = np.asarray(R, dtype=float)
    wsum = w.sum(axis=1)
    c = np.einsum("bn,bni->bi", w, L) / wsum[:, None]
    p = np.einsum("bij,bnj->bni", R, L - c[:, None, :])          # centred, robot axes
    stated = np.asarray(sigma_stated, dtype=float)
    s = residual_sigma(sum_e2, n_used)
    dof = dof_of(n_used)
    sigma = np.maximum(stated, s)
    K = fit_covariance(p, w)
    worst = at_reach95(K, reach, stated, s, dof)
    from_stated = at_reach95(K, reach, stated)
    C = np.einsum("bn,bni,bnj->bij", w, p, p) / wsum[:, None, None]
    spread = np.sqrt(np.clip(np.linalg.eigvalsh(C)[:, ::-1], 0.0, None))
    return {"sigma": sigma, "sigma_residual": s, "dof": dof,
            "angle_std": np.degrees(sigma * np.sqrt(np.clip(np.trace(K[:, 3:, 3:], axis1=1,
                                                                      axis2=2), 0, None))),
            "at_reach": worst, "at_centroid": q95(K[:, :3, :3], stated, s, dof),
            "sigma_source": np.where(worst > from_stated, "residuals", "stated"),
            "spread": spread, "K": K, "centroid": c}


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


def at_reason(name: str, at_95: float, threshold: float, sigma: float) -> str:
    """Why a dataset fails the gate judged at the working points (--gate at)."""
    return (f"the points do not pin the frame down where the robot works: working point "
            f"{name} is known only to {at_95:.2f} mm (95 %), over the {threshold:g} mm "
            f"threshold (noise {sigma:.3f} mm per axis); spread the points toward the working "
            "points or measure more points (ucsio plan says where)")
