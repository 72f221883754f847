"""Horn's closed-form solution of absolute orientation with unit quaternions.

B. K. P. Horn, "Closed-form solution of absolute orientation using unit
quaternions", J. Opt. Soc. Am. A 4 (1987) 629-642.

Given points r_l,i measured in the "left" system (the laser tracker, aligned
to the fixture's nominal frame, the UCS) and the same points r_r,i in the
"right" system (robot world), find the rotation R and translation r_0 with

    r_r,i = R r_l,i + r_0

minimising sum_i w_i |r_r,i - R r_l,i - r_0|^2. Scale is fixed to 1: the
laser tracker and the robot both measure in millimetres.

The steps follow the paper, with its names:

- the translation: once the rotation is known, r_0 is the difference of the
  (weighted) centroids, r_0 = r̄_r - R r̄_l; so work with coordinates relative
  to the centroids, r'_l,i and r'_r,i;
- the sums of products S_xx = sum w_i x'_l,i x'_r,i, S_xy = sum w_i x'_l,i
  y'_r,i, ... (the entries of M = sum w_i r'_l,i r'_r,i^T);
- the symmetric 4x4 matrix N built from them (its trace is zero);
- the unit quaternion q = (q0, qx, qy, qz) that maximises q^T N q is the
  eigenvector of N's most positive eigenvalue;
- R from q, then r_0.

Everything is vectorised over a leading batch axis: inputs are (B, n, 3) and
one ``numpy.linalg.eigh`` call diagonalises the (B, 4, 4) stack. A single
solve is a batch of one (``absolute_orientation``), which raises
``UcsioError`` when the points cannot determine the frame.

Degeneracy (coplanar points are fine, as the paper shows; collinear ones are
not): the rotation about a line through collinear points is
undetermined, and then N's two largest eigenvalues coincide. We check the
laser points' scatter directly (principal RMS spreads s1 >= s2 >= s3 about
the weighted centroid) and, as a numerical safety net, the relative gap
between N's two largest eigenvalues.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import UcsioError

# Status codes, one per batch item.
OK = 0
TOO_FEW_POINTS = 1
COINCIDENT = 2
COLLINEAR = 3
AMBIGUOUS = 4

#: All points within this RMS distance (mm) of their centroid: coincident.
COINCIDENT_SPREAD = 1e-3
#: Second principal spread below this fraction of the first: the points lie
#: (nearly) on a line, and the rotation about it is undetermined (with a
#: typical 0.05 mm robot repeatability, 1 % of a 1 m line is 10 mm across,
#: already ~0.3 deg of doubt about the line).
NEAR_COLLINEAR_RATIO = 1e-2
#: Second principal spread below this (mm): collinear whatever the size.
COLLINEAR_SPREAD = 1e-3
#: Relative gap (lambda_1 - lambda_2) / (|lambda_1| + |lambda_4|) of N below
#: this: the maximising quaternion is not unique (numerical safety net).
MIN_EIGEN_GAP = 1e-9

REASONS = {
    OK: "ok",
    TOO_FEW_POINTS: "fewer than 3 points: a frame needs at least 3 points not on one line",
    COINCIDENT: "the laser points coincide: the rotation is undetermined",
    COLLINEAR: ("the laser points lie (nearly) on one line: the rotation about that line is "
                "undetermined; measure points spread across the fixture"),
    AMBIGUOUS: ("the point pairs do not determine one rotation (the two largest eigenvalues of "
                "Horn's matrix N coincide)"),
}


@dataclass
class HornBatch:
    """The fits of a batch. Arrays have the batch axis first."""

    q: np.ndarray            # (B, 4) unit quaternion (w, x, y, z), w >= 0
    R: np.ndarray            # (B, 3, 3) rotation, r_r = R r_l + r_0
    t: np.ndarray            # (B, 3) translation r_0
    eigenvalues: np.ndarray  # (B, 4) of N, ascending
    spread: np.ndarray       # (B, 3) principal RMS spreads of the laser points, descending (mm)
    status: np.ndarray       # (B,) int, OK or a degeneracy code

    @property
    def ok(self) -> np.ndarray:
        return self.status == OK

    def reason(self, i: int = 0) -> str:
        return REASONS[int(self.status[i])]

    def apply(self, points) -> np.ndarray:
        """R p + t for every set: points (B, m, 3) -> (B, m, 3)."""
        return np.einsum("bij,bmj->bmi", self.R, np.asarray(points, dtype=float)) + self.t[:, None, :]


@dataclass
class HornFit:
    """One fit: r_r = R r_l + t."""

    q: np.ndarray            # (4,) (w, x, y, z), w >= 0
    R: np.ndarray            # (3, 3)
    t: np.ndarray            # (3,)
    eigenvalues: np.ndarray  # (4,) of N, ascending
    spread: np.ndarray       # (3,) principal RMS spreads of the laser points (mm)

    def apply(self, points) -> np.ndarray:
        return np.asarray(points, dtype=float) @ self.R.T + self.t


def quat_to_matrix(q: np.ndarray) -> np.ndarray:
    """(..., 4) unit quaternions (w, x, y, z) -> (..., 3, 3) rotation matrices."""
    q0, qx, qy, qz = np.moveaxis(np.asarray(q, dtype=float), -1, 0)
    R = np.empty(q0.shape + (3, 3))
    R[..., 0, 0] = q0 * q0 + qx * qx - qy * qy - qz * qz
    R[..., 0, 1] = 2 * (qx * qy - q0 * qz)
    R[..., 0, 2] = 2 * (qx * qz + q0 * qy)
    R[..., 1, 0] = 2 * (qy * qx + q0 * qz)
    R[..., 1, 1] = q0 * q0 - qx * qx + qy * qy - qz * qz
    R[..., 1, 2] = 2 * (qy * qz - q0 * qx)
    R[..., 2, 0] = 2 * (qz * qx - q0 * qy)
    R[..., 2, 1] = 2 * (qz * qy + q0 * qx)
    R[..., 2, 2] = q0 * q0 - qx * qx - qy * qy + qz * qz
    return R


def horn_batch(r_l, r_r, w=None) -> HornBatch:
    """Fit every set of a batch: r_l, r_r (B, n, 3) laser and robot points,
    w (B, n) non-negative weights (default 1; a zero weight leaves a point
    out). Degenerate sets get a status code and a meaningless (but finite)
    result; check ``.ok`` / ``.status``."""
    r_l = np.asarray(r_l, dtype=float)
    r_r = np.asarray(r_r, dtype=float)
    if r_l.ndim != 3 or r_l.shape[-1] != 3 or r_r.shape != r_l.shape:
        raise ValueError(f"expected two (B, n, 3) arrays, got {r_l.shape} and {r_r.shape}")
    B, n, _ = r_l.shape
    w = np.ones((B, n)) if w is None else np.broadcast_to(np.asarray(w, dtype=float), (B, n))
    n_eff = np.count_nonzero(w > 0, axis=1)
    W = w.sum(axis=1)                                   # (B,)
    W_safe = np.where(W > 0, W, 1.0)[:, None, None]

    # Weighted centroids, and coordinates relative to them.
    rbar_l = (w[:, None, :] @ r_l) / W_safe             # (B, 1, 3)
    rbar_r = (w[:, None, :] @ r_r) / W_safe
    rp_l = r_l - rbar_l
    rp_r = r_r - rbar_r
    w_rp_l = rp_l * w[:, :, None]

    # M = sum_i w_i r'_l,i r'_r,i^T, whose entries are S_xx, S_xy, ...
    M = w_rp_l.transpose(0, 2, 1) @ rp_r
    S_xx, S_xy, S_xz = M[:, 0, 0], M[:, 0, 1], M[:, 0, 2]
    S_yx, S_yy, S_yz = M[:, 1, 0], M[:, 1, 1], M[:, 1, 2]
    S_zx, S_zy, S_zz = M[:, 2, 0], M[:, 2, 1], M[:, 2, 2]

    # The symmetric 4x4 matrix N.
    N = np.empty((B, 4, 4))
    N[:, 0, 0] = S_xx + S_yy + S_zz
    N[:, 0, 1] = N[:, 1, 0] = S_yz - S_zy
    N[:, 0, 2] = N[:, 2, 0] = S_zx - S_xz
    N[:, 0, 3] = N[:, 3, 0] = S_xy - S_yx
    N[:, 1, 1] = S_xx - S_yy - S_zz
    N[:, 1, 2] = N[:, 2, 1] = S_xy + S_yx
    N[:, 1, 3] = N[:, 3, 1] = S_zx + S_xz
    N[:, 2, 2] = -S_xx + S_yy - S_zz
    N[:, 2, 3] = N[:, 3, 2] = S_yz + S_zy
    N[:, 3, 3] = -S_xx - S_yy + S_zz

    # The unit quaternion maximising q^T N q is the eigenvector of the
    # most positive eigenvalue (eigh sorts ascending: the last column).
    eigenvalues, eigenvectors = np.linalg.eigh(N)
    q = eigenvectors[:, :, 3]
    q = np.where(q[:, :1] < 0, -q, q)                   # q and -q: same rotation; w >= 0
    q /= np.linalg.norm(q, axis=1, keepdims=True)

    # Rotation from the quaternion, then translation r_0 = r̄_r - R r̄_l.
    R = quat_to_matrix(q)
    t = (rbar_r - rbar_l @ R.transpose(0, 2, 1))[:, 0, :]

    # Degeneracy: principal spreads of the laser points about their centroid.
    C = (w_rp_l.transpose(0, 2, 1) @ rp_l) / W_safe
    spread = np.sqrt(_sym3_eigvals_desc(C))                # s1 >= s2 >= s3
    gap = (eigenvalues[:, 3] - eigenvalues[:, 2]) / np.maximum(
        np.abs(eigenvalues[:, 3]) + np.abs(eigenvalues[:, 0]), np.finfo(float).tiny)

    status = np.full(B, OK, dtype=np.int8)
    status[gap < MIN_EIGEN_GAP] = AMBIGUOUS
    status[(spread[:, 1] < COLLINEAR_SPREAD)
           | (spread[:, 1] < NEAR_COLLINEAR_RATIO * spread[:, 0])] = COLLINEAR
    status[spread[:, 0] < COINCIDENT_SPREAD] = COINCIDENT
    status[n_eff < 3] = TOO_FEW_POINTS
    return HornBatch(q=q, R=R, t=t, eigenvalues=eigenvalues, spread=spread, status=status)


def _sym3_eigvals_desc(C: np.ndarray) -> np.ndarray:
    """Eigenvalues (descending, clipped at 0) of positive semi-definite
    symmetric 3x3 matrices (B, 3, 3), in closed form (cheaper than a second
    LAPACK call per item). The largest comes from the trigonometric solution
    of the characteristic cubic, which is well conditioned for it; the other
    two from their sum (trace - l1) and product (det / l1), so a thin scatter
    (l2, l3 << l1) keeps its small eigenvalues to ~sqrt(eps) * l1 at worst,
    far below the collinearity ratio checked against them."""
    a, b, c = C[:, 0, 0], C[:, 1, 1], C[:, 2, 2]
    d, e, f = C[:, 0, 1], C[:, 1, 2], C[:, 0, 2]
    tr = a + b + c
    m = tr / 3.0
    p1 = d * d + e * e + f * f
    p2 = (a - m) ** 2 + (b - m) ** 2 + (c - m) ** 2 + 2.0 * p1
    p = np.sqrt(p2 / 6.0)
    p_safe = np.where(p > 0, p, 1.0)
    A, Bm, Cm = (a - m) / p_safe, (b - m) / p_safe, (c - m) / p_safe
    D, E, F = d / p_safe, e / p_safe, f / p_safe
    half_det = 0.5 * (A * (Bm * Cm - E * E) - D * (D * Cm - E * F) + F * (D * E - Bm * F))
    phi = np.arccos(np.clip(half_det, -1.0, 1.0)) / 3.0
    l1 = np.where(p > 0, m + 2.0 * p * np.cos(phi), m)
    det = a * (b * c - e * e) - d * (d * c - e * f) + f * (d * e - b * f)
    rest = np.clip(tr - l1, 0.0, None)                       # l2 + l3
    prod = np.clip(np.where(l1 > 0, det / np.where(l1 > 0, l1, 1.0), 0.0), 0.0, None)
    root = np.sqrt(np.clip(rest * rest - 4.0 * prod, 0.0, None))
    l2 = 0.5 * (rest + root)
    l3 = np.minimum(np.where(l2 > 0, prod / np.where(l2 > 0, l2, 1.0), 0.0), l2)
    return np.clip(np.stack([l1, l2, l3], axis=-1), 0.0, None)


def absolute_orientation(r_l, r_r, w=None) -> HornFit:
    """One fit of laser points r_l (n, 3) to robot points r_r (n, 3) with
    optional weights w (n,). Raises UcsioError when the points cannot
    determine the frame (fewer than 3, coincident, (nearly) collinear)."""
    r_l = np.asarray(r_l, dtype=float)
    r_r = np.asarray(r_r, dtype=float)
    if r_l.ndim != 2 or r_l.shape[-1] != 3 or r_r.shape != r_l.shape:
        raise ValueError(f"expected two (n, 3) arrays, got {r_l.shape} and {r_r.shape}")
    res = horn_batch(r_l[None], r_r[None], None if w is None else np.asarray(w, dtype=float)[None])
    if not res.ok[0]:
        raise UcsioError(res.reason(0))
    return HornFit(q=res.q[0], R=res.R[0], t=res.t[0], eigenvalues=res.eigenvalues[0],
                   spread=res.spread[0])


def rotation_angle_deg(R_a: np.ndarray, R_b: np.ndarray) -> np.ndarray:
    """Angle (deg) of the rotation between R_a (..., 3, 3) and R_b, accurate
    near 0 and 180 deg (atan2 of sine and cosine parts of R_a^T R_b)."""
    D = np.einsum("...ji,...jk->...ik", R_a, R_b)
    cos = (np.trace(D, axis1=-2, axis2=-1) - 1.0) / 2.0
    axis = np.stack([D[..., 2, 1] - D[..., 1, 2], D[..., 0, 2] - D[..., 2, 0],
                     D[..., 1, 0] - D[..., 0, 1]], axis=-1)
    sin = np.linalg.norm(axis, axis=-1) / 2.0
    return np.degrees(np.arctan2(sin, cos))
