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
  eigenvector e_m of N's most positive eigenvalue lambda_m (Section 4.B):
  lambda_m is the largest root of the characteristic quartic
  lambda^4 + c2 lambda^2 + c1 lambda + c0 with c2 = -2 Tr(M^T M),
  c1 = -8 det(M), c0 = det(N), found here by Newton's method, and e_m solves
  (N - lambda_m I) e_m = 0: any non-zero column of the adjugate of
  N - lambda_m I. Where the two largest eigenvalues nearly tie, that column
  is poorly determined and ``numpy.linalg.eigh`` decides instead;
- R from q, then r_0.

Everything is vectorised over a leading batch axis: inputs are (B, n, 3),
processed in chunks so that the working memory stays a small multiple of one
chunk, whatever B. A single solve is a batch of one
(``absolute_orientation``), which raises ``UcsioError`` when the points cannot
determine the frame.

Everything Horn's method needs of a point set is a few weighted sums (the
``Sums``: total weight, centroids, M, and the scatter of each side). Taking
one point out of a set changes them by that point's own terms, so the
leave-one-out fits of every point (``leave_one_out``) cost O(n) memory and
time, not n refits of n - 1 points.

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

from ..errors import UcsioError
from ..geometry.arrays import quat_to_matrix

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
#: Relative gap below which the eigenvector is taken from ``eigh`` rather
#: than from the adjugate (whose column then loses digits as 1 / gap).
TIE_GAP = 1e-6
#: Newton steps on the quartic before an item is handed to ``eigh``.
NEWTON_STEPS = 30
#: Points per chunk of a batch (about 3 MB per (chunk, 3) array).
CHUNK_POINTS = 1 << 17

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
    lambda_m: np.ndarray     # (B,) N's most positive eigenvalue, q^T N q
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

    @classmethod
    def empty(cls, B: int) -> "HornBatch":
        return cls(q=np.empty((B, 4)), R=np.empty((B, 3, 3)), t=np.empty((B, 3)),
                   lambda_m=np.empty(B), spread=np.empty((B, 3)),
                   status=np.empty(B, dtype=np.int8))

    def fill(self, where: slice, part: "HornBatch") -> None:
        for name in ("q", "R", "t", "lambda_m", "spread", "status"):
            getattr(self, name)[where] = getattr(part, name)


@dataclass
class HornFit:
    """One fit: r_r = R r_l + t."""

    q: np.ndarray            # (4,) (w, x, y, z), w >= 0
    R: np.ndarray            # (3, 3)
    t: np.ndarray            # (3,)
    lambda_m: float          # N's most positive eigenvalue
    spread: np.ndarray       # (3,) principal RMS spreads of the laser points (mm)

    def apply(self, points) -> np.ndarray:
        return np.asarray(points, dtype=float) @ self.R.T + self.t


@dataclass
class Sums:
    """What Horn's method needs of each point set of a batch (batch axis
    first): the weighted sums, taken about the weighted centroids."""

    n: np.ndarray            # (B,) points with a positive weight
    W: np.ndarray            # (B,) sum of the weights
    rbar_l: np.ndarray       # (B, 3) weighted centroids
    rbar_r: np.ndarray       # (B, 3)
    M: np.ndarray            # (B, 3, 3) sum w_i r'_l,i r'_r,i^T: S_xx, S_xy, ...
    C_l: np.ndarray          # (B, 3, 3) sum w_i r'_l,i r'_l,i^T: the laser points' scatter
    G_r: np.ndarray          # (B,) sum w_i |r'_r,i|^2

    def __getitem__(self, index) -> "Sums":
        return Sums(self.n[index], self.W[index], self.rbar_l[index], self.rbar_r[index],
                    self.M[index], self.C_l[index], self.G_r[index])

    def without(self, r_l, r_r, w) -> "Sums":
        """The sums of each set with one of its points taken out: r_l, r_r
        (K, 3) and w (K,) are that point, self the sums of its set (K).

        With W' = W - w and d the point's offset from its set's centroid,
        the centroid moves by -(w / W') d and every sum of products about
        the centroid loses (w W / W') d_a d_b^T: that point's own term plus
        the shift of the centroid. O(K), whatever the sets' sizes."""
        W_rest = self.W - w
        alone = W_rest <= 0
        W_safe = np.where(alone, 1.0, W_rest)
        d_l = r_l - self.rbar_l
        d_r = r_r - self.rbar_r
        shift = np.where(alone, 0.0, w / W_safe)[:, None]
        g = np.where(alone, 0.0, w * self.W / W_safe)[:, None, None]
        return Sums(n=self.n - (w > 0), W=W_rest,
                    rbar_l=self.rbar_l - shift * d_l, rbar_r=self.rbar_r - shift * d_r,
                    M=self.M - g * d_l[:, :, None] * d_r[:, None, :],
                    C_l=self.C_l - g * d_l[:, :, None] * d_l[:, None, :],
                    G_r=self.G_r - g[:, 0, 0] * np.einsum("ki,ki->k", d_r, d_r))


def _points_and_weights(r_l, r_r, w):
    r_l = np.asarray(r_l, dtype=float)
    r_r = np.asarray(r_r, dtype=float)
    if r_l.ndim != 3 or r_l.shape[-1] != 3 or r_r.shape != r_l.shape:
        raise ValueError(f"expected two (B, n, 3) arrays, got {r_l.shape} and {r_r.shape}")
    B, n, _ = r_l.shape
    if w is not None:
        w = np.broadcast_to(np.asarray(w, dtype=float), (B, n))
    return r_l, r_r, w


def _chunks(B: int, n: int):
    """Slices of whole sets with about CHUNK_POINTS points each."""
    step = max(1, CHUNK_POINTS // max(n, 1))
    for start in range(0, B, step):
        yield slice(start, min(start + step, B))


def sums(r_l, r_r, w=None) -> Sums:
    """The sums of each set: r_l, r_r (B, n, 3), w (B, n) or None (all 1)."""
    r_l, r_r, w = _points_and_weights(r_l, r_r, w)
    B, n, _ = r_l.shape
    if w is None:
        w = np.ones((B, n))
    W = w.sum(axis=1)                                   # (B,)
    W_safe = np.where(W > 0, W, 1.0)[:, None]
    # Laser and robot coordinates side by side (B, n, 6): one pass gives the
    # weighted centroids, then the coordinates relative to them, r'.
    r = np.concatenate([r_l, r_r], axis=2)
    rbar = np.einsum("bn,bni->bi", w, r) / W_safe
    r -= rbar[:, None, :]
    # All sums of products of r' at once: sum w_i r'_i r'_i^T (B, 6, 6);
    # its upper right block is M, the upper left the laser scatter.
    P = np.matmul((r * w[:, :, None]).transpose(0, 2, 1), r)
    return Sums(n=np.count_nonzero(w > 0, axis=1), W=W, rbar_l=rbar[:, :3], rbar_r=rbar[:, 3:],
                M=P[:, :3, 3:], C_l=P[:, :3, :3], G_r=np.einsum("bii->b", P[:, 3:, 3:]))


def horn_from_sums(s: Sums) -> HornBatch:
    """Horn's method on the sums of each set (any number of sets, all at
    once: callers chunk). Degenerate sets get a status code and a
    meaningless (but finite) result."""
    B = len(s.W)
    M = s.M
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

    # The unit quaternion maximising q^T N q is the eigenvector e_m of the
    # most positive eigenvalue lambda_m.
    G_l = np.trace(s.C_l, axis1=1, axis2=2)
    lambda_m, q, gap = _largest_eigenpair(N, M, upper=0.5 * (G_l + s.G_r))
    q = np.where(q[:, :1] < 0, -q, q)                   # q and -q: same rotation; w >= 0

    # Rotation from the quaternion, then translation r_0 = r̄_r - R r̄_l.
    R = quat_to_matrix(q)
    t = s.rbar_r - np.einsum("bij,bj->bi", R, s.rbar_l)

    # Degeneracy: principal spreads of the laser points about their centroid.
    W_safe = np.where(s.W > 0, s.W, 1.0)[:, None, None]
    spread = np.sqrt(_sym3_eigvals_desc(s.C_l / W_safe))   # s1 >= s2 >= s3

    status = np.full(B, OK, dtype=np.int8)
    status[gap < MIN_EIGEN_GAP] = AMBIGUOUS
    status[(spread[:, 1] < COLLINEAR_SPREAD)
           | (spread[:, 1] < NEAR_COLLINEAR_RATIO * spread[:, 0])] = COLLINEAR
    status[spread[:, 0] < COINCIDENT_SPREAD] = COINCIDENT
    status[s.n < 3] = TOO_FEW_POINTS
    return HornBatch(q=q, R=R, t=t, lambda_m=lambda_m, spread=spread, status=status)


def _largest_eigenpair(N: np.ndarray, M: np.ndarray, upper: np.ndarray):
    """N's most positive eigenvalue lambda_m (B,), its unit eigenvector
    (B, 4), and a lower bound on the relative gap (lambda_1 - lambda_2) /
    (|lambda_1| + |lambda_4|) (exact where ``eigh`` decided).

    The characteristic polynomial of N is lambda^4 + c2 lambda^2 + c1 lambda
    + c0 (Horn, Section 4.B). Newton's method starts from ``upper`` =
    (sum w |r'_l|^2 + sum w |r'_r|^2) / 2, which is never below lambda_m
    (q^T N q = sum w r'_r . R r'_l) and exceeds it by half the residual sum
    of squares: for good data a step or two. Right of its largest root the
    quartic is increasing and convex, so the steps go down monotonically to
    lambda_m."""
    c2 = -2.0 * np.einsum("bij,bij->b", M, M)
    c1 = -8.0 * _det3(M)
    c0 = _det4(N)
    norm_N = np.sqrt(-2.0 * c2)                           # ||N||_F = sqrt(sum lambda^2) >= lambda_m
    lam = np.clip(upper, 0.0, norm_N)
    tol = 4.0 * np.finfo(float).eps * np.maximum(norm_N, np.finfo(float).tiny)
    converged = np.zeros(len(lam), dtype=bool)
    dp = np.zeros_like(lam)
    todo = np.arange(len(lam))                            # items still stepping
    with np.errstate(divide="ignore", invalid="ignore"):
        for _ in range(NEWTON_STEPS):
            x, a2, a1, a0 = lam[todo], c2[todo], c1[todo], c0[todo]
            p = ((x * x + a2) * x + a1) * x + a0
            slope = (4.0 * x * x + 2.0 * a2) * x + a1
            step = np.where(slope > 0, p / slope, 0.0)
            lam[todo] = x - step
            dp[todo] = slope
            done = np.abs(step) <= tol[todo]
            converged[todo[done]] = True
            todo = todo[~done]
            if not len(todo):
                break
        # dp = (l1 - l2)(l1 - l3)(l1 - l4) <= gap * (l1 - l4)^2 and every
        # |l_i - l_j| <= 2 ||N||_F: a lower bound on the relative gap.
        gap = dp / (2.0 * norm_N) ** 3
        # e_m from the adjugate of N - lambda_m I: every column is a multiple
        # of e_m; the one on the largest diagonal entry is the longest. An
        # error d in lambda_m leaves a part d / gap of the next eigenvector
        # in it; the adjugate applied once more squares that part away (it
        # is (N - lambda_m I)^-1 times det: one step of inverse iteration).
        adj = _adjugate4(N - lam[:, None, None] * np.eye(4))
        k = np.argmax(np.abs(np.einsum("bii->bi", adj)), axis=1)
        e = adj[np.arange(len(lam)), :, k]
        e /= np.linalg.norm(e, axis=1, keepdims=True)
        e = np.einsum("bij,bj->bi", adj, e)
        e /= np.linalg.norm(e, axis=1, keepdims=True)
    tie = ~(converged & (gap >= TIE_GAP) & np.isfinite(e).all(axis=1))
    if tie.any():
        values, vectors = np.linalg.eigh(N[tie])          # ascending: the last one
        lam[tie] = values[:, 3]
        e[tie] = vectors[:, :, 3]
        gap[tie] = (values[:, 3] - values[:, 2]) / np.maximum(
            np.abs(values[:, 3]) + np.abs(values[:, 0]), np.finfo(float).tiny)
    return lam, e, gap


def _det3(M: np.ndarray) -> np.ndarray:
    """Determinants of (B, 3, 3) matrices (cheaper than LAPACK for tiny ones)."""
    return (M[:, 0, 0] * (M[:, 1, 1] * M[:, 2, 2] - M[:, 1, 2] * M[:, 2, 1])
            - M[:, 0, 1] * (M[:, 1, 0] * M[:, 2, 2] - M[:, 1, 2] * M[:, 2, 0])
            + M[:, 0, 2] * (M[:, 1, 0] * M[:, 2, 1] - M[:, 1, 1] * M[:, 2, 0]))


def _minors2(A: np.ndarray):
    """The 2x2 minors of rows (0, 1) and of rows (2, 3) of (B, 4, 4) A."""
    a = [[A[:, i, j] for j in range(4)] for i in range(4)]
    s = [a[0][0] * a[1][1] - a[1][0] * a[0][1], a[0][0] * a[1][2] - a[1][0] * a[0][2],
         a[0][0] * a[1][3] - a[1][0] * a[0][3], a[0][1] * a[1][2] - a[1][1] * a[0][2],
         a[0][1] * a[1][3] - a[1][1] * a[0][3], a[0][2] * a[1][3] - a[1][2] * a[0][3]]
    c = [a[2][0] * a[3][1] - a[3][0] * a[2][1], a[2][0] * a[3][2] - a[3][0] * a[2][2],
         a[2][0] * a[3][3] - a[3][0] * a[2][3], a[2][1] * a[3][2] - a[3][1] * a[2][2],
         a[2][1] * a[3][3] - a[3][1] * a[2][3], a[2][2] * a[3][3] - a[3][2] * a[2][3]]
    return a, s, c


def _det4(A: np.ndarray) -> np.ndarray:
    """Determinants of (B, 4, 4) matrices (Laplace expansion by 2x2 minors)."""
    _, s, c = _minors2(A)
    return s[0] * c[5] - s[1] * c[4] + s[2] * c[3] + s[3] * c[2] - s[4] * c[1] + s[5] * c[0]


def _adjugate4(A: np.ndarray) -> np.ndarray:
    """Adjugates (transposed cofactor matrices) of (B, 4, 4) matrices."""
    a, s, c = _minors2(A)
    adj = np.empty_like(A)
    adj[:, 0, 0] = a[1][1] * c[5] - a[1][2] * c[4] + a[1][3] * c[3]
    adj[:, 0, 1] = -a[0][1] * c[5] + a[0][2] * c[4] - a[0][3] * c[3]
    adj[:, 0, 2] = a[3][1] * s[5] - a[3][2] * s[4] + a[3][3] * s[3]
    adj[:, 0, 3] = -a[2][1] * s[5] + a[2][2] * s[4] - a[2][3] * s[3]
    adj[:, 1, 0] = -a[1][0] * c[5] + a[1][2] * c[2] - a[1][3] * c[1]
    adj[:, 1, 1] = a[0][0] * c[5] - a[0][2] * c[2] + a[0][3] * c[1]
    adj[:, 1, 2] = -a[3][0] * s[5] + a[3][2] * s[2] - a[3][3] * s[1]
    adj[:, 1, 3] = a[2][0] * s[5] - a[2][2] * s[2] + a[2][3] * s[1]
    adj[:, 2, 0] = a[1][0] * c[4] - a[1][1] * c[2] + a[1][3] * c[0]
    adj[:, 2, 1] = -a[0][0] * c[4] + a[0][1] * c[2] - a[0][3] * c[0]
    adj[:, 2, 2] = a[3][0] * s[4] - a[3][1] * s[2] + a[3][3] * s[0]
    adj[:, 2, 3] = -a[2][0] * s[4] + a[2][1] * s[2] - a[2][3] * s[0]
    adj[:, 3, 0] = -a[1][0] * c[3] + a[1][1] * c[1] - a[1][2] * c[0]
    adj[:, 3, 1] = a[0][0] * c[3] - a[0][1] * c[1] + a[0][2] * c[0]
    adj[:, 3, 2] = -a[3][0] * s[3] + a[3][1] * s[1] - a[3][2] * s[0]
    adj[:, 3, 3] = a[2][0] * s[3] - a[2][1] * s[1] + a[2][2] * s[0]
    return adj


def horn_batch(r_l, r_r, w=None) -> HornBatch:
    """Fit every set of a batch: r_l, r_r (B, n, 3) laser and robot points,
    w (B, n) non-negative weights (default 1; a zero weight leaves a point
    out). Degenerate sets get a status code and a meaningless (but finite)
    result; check ``.ok`` / ``.status``. Works through the batch in chunks,
    so memory beyond the inputs is the outputs and one chunk's work."""
    r_l, r_r, w = _points_and_weights(r_l, r_r, w)
    B, n, _ = r_l.shape
    out = HornBatch.empty(B)
    for part in _chunks(B, n):
        out.fill(part, horn_from_sums(sums(r_l[part], r_r[part], None if w is None else w[part])))
    return out


def leave_one_out(r_l, r_r, w=None):
    """Each point against the frame fitted from the other points of its set:
    r_l, r_r (B, n, 3), w (B, n) as for ``horn_batch``. Returns the distance
    |r_r,j - (R_-j r_l,j + r_0,-j)| (B, n) and the status of each
    leave-one-out fit (B, n). The sums of each set lose the point's own
    terms (``Sums.without``): O(B n) memory and time."""
    r_l, r_r, w = _points_and_weights(r_l, r_r, w)
    B, n, _ = r_l.shape
    residual = np.empty((B, n))
    status = np.empty((B, n), dtype=np.int8)
    step = max(1, CHUNK_POINTS // 8)                    # leave-one-out fits at once
    for part in _chunks(B, n):
        full = sums(r_l[part], r_r[part], None if w is None else w[part])
        L, R_, Wp = r_l[part].reshape(-1, 3), r_r[part].reshape(-1, 3), None
        if w is not None:
            Wp = w[part].reshape(-1)
        res_part = residual[part].reshape(-1)           # views: part is a slice of whole sets
        st_part = status[part].reshape(-1)
        for k0 in range(0, len(L), step):
            k = slice(k0, min(k0 + step, len(L)))
            owner = np.arange(k.start, k.stop) // n
            w_j = np.ones(k.stop - k.start) if Wp is None else Wp[k]
            fit = horn_from_sums(full[owner].without(L[k], R_[k], w_j))
            pred = np.einsum("kij,kj->ki", fit.R, L[k]) + fit.t
            res_part[k] = np.linalg.norm(R_[k] - pred, axis=1)
            st_part[k] = fit.status
    return residual, status


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
    return HornFit(q=res.q[0], R=res.R[0], t=res.t[0], lambda_m=float(res.lambda_m[0]),
                   spread=res.spread[0])
