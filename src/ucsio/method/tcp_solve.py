"""The TCP solved with the frame (SPEC: ``solve --tcp solve``).

With one reflector on the flange whose offset x (flange coordinates) is not
known, point i gives

    R_Y l_i + t_Y = R_i x + t_i        (l_i laser, (R_i, t_i) flange pose i)

with unknowns R_Y, t_Y (the UCS in robot world) and x: the hand-eye problem
with 3D position data (Wu & Ren, "Finding the kinematic base frame of a robot
by hand-eye calibration using 3D position data", IEEE T-ASE).

1. Linear first solution. Writing l_i = c + B a_i (c the centroid, B the
   principal axes along which the laser points spread: three, or two for a
   flat fixture), R_Y l_i + t_Y = p + N a_i with p = R_Y c + t_Y and N = R_Y B,
   so p + N a_i - R_i x = t_i is linear in (p, N, x): least squares gives x;
   Horn's method (``horn``) then fits R_Y, t_Y to the robot points R_i x + t_i.
2. Gauss-Newton on all nine unknowns (rotation updates exp([dθ]x) R_Y), from
   that start, batched: the full fit and the n leave-one-out fits (each point's
   weight zeroed, started from the full fit) are one array computation.
3. Residuals, leave-one-out residuals and exclusion use the joint model, with
   the rule of ``solve`` (while the largest leave-one-out residual exceeds the
   threshold, exclude that point and refit; stop when every used point's
   residual is within it; run to the end; ``--exclude``, ``--no-exclusion``);
   acceptance by ``solve.acceptance``.
4. The gates. The first-order covariance of the nine unknowns (per-axis
   noise σ the larger of the stated √(σ_laser² + σ_robot²) and the residuals'
   √(Σ|e_i|² / (3n − 9))) gives the TCP's 95 % doubt (``precision.
   quantile95_norm`` of its 3x3 block): over the threshold, the dataset is
   rejected, naming the flange orientations' spread and the spread that would
   do (the doubt falls as 1/spread). The frame's 6x6 block gives ``precision``
   as for a fixed TCP (``precision.at_reach95``).

``diagnose`` is the other direction: a fixed-TCP solve rejected for its
residuals, where the joint model explains them, names the TCP that fits.
"""
from __future__ import annotations

import math
from typing import Any, Iterable

import numpy as np

from . import horn
from .. import defaults
from ..errors import UcsioError
from ..geometry.arrays import rotation_angle_deg, rotvecs_to_matrices
from ..geometry.frames import Pose
from .precision import residual_sigma, skew

MAX_ITERATIONS = 50
STEP_MM = 1e-9              # a Gauss-Newton step this small (mm, rad) has converged
STEP_ROT = 1e-12
MIN_POINTS_JOINT = 4        # nine unknowns; 3 points fit exactly and show nothing
#: principal spread (relative to the largest) below which the linear first
#: solution treats the laser points as flat (the rotation's third column is
#: then left to Horn's fit)
FLAT_RATIO = 0.05


# ---------------------------------------------------------------- the fit

def linear_tcp(laser: np.ndarray, Rf: np.ndarray, tf: np.ndarray, w: np.ndarray) -> np.ndarray:
    """The linear first solution's x (3,) from points with weight w > 0."""
    keep = w > 0
    L, Rk, tk, wk = laser[keep], Rf[keep], tf[keep], w[keep]
    c = (wk[:, None] * L).sum(axis=0) / wk.sum()
    A = L - c
    scatter = (wk[:, None, None] * A[:, :, None] * A[:, None, :]).sum(axis=0) / wk.sum()
    evals, evecs = np.linalg.eigh(scatter)
    spreads = np.sqrt(np.clip(evals, 0.0, None))[::-1]
    basis = evecs[:, ::-1]
    k = max(2, int(np.count_nonzero(spreads > FLAT_RATIO * spreads[0])))
    a = A @ basis[:, :k]                                     # (m, k)
    m = len(L)
    D = np.zeros((m, 3, 6 + 3 * k))
    D[:, :, :3] = np.eye(3)                                  # p
    for j in range(k):                                       # N's columns
        D[:, :, 3 + 3 * j:6 + 3 * j] = a[:, j, None, None] * np.eye(3)
    D[:, :, 3 + 3 * k:] = -Rk                                # x
    sw = np.sqrt(wk)[:, None, None]
    sol, *_ = np.linalg.lstsq((sw * D).reshape(3 * m, -1), (sw[:, :, 0] * tk).reshape(-1),
                              rcond=None)
    return sol[-3:]


def _per_set(a, S: int) -> np.ndarray:
    """(n, 3) shared by every set, or (S, n, 3) one per set (Monte Carlo)."""
    a = np.asarray(a, dtype=float)
    return a if a.ndim == 3 else np.broadcast_to(a, (S,) + a.shape)


def residuals(laser, Rf, tf, R, t, x) -> np.ndarray:
    """e = (R_i x + t_i) - (R_Y l_i + t_Y): (S, n, 3) for (S,) parameter sets;
    laser and tf (n, 3) shared, or (S, n, 3) per set."""
    S = len(R)
    return (np.einsum("nij,sj->sni", Rf, x) + _per_set(tf, S)
            - np.einsum("sij,snj->sni", R, _per_set(laser, S)) - t[:, None, :])


def gauss_newton(laser, Rf, tf, W, R, t, x):
    """Refine (S,) parameter sets, each against the points weighted by its
    row of W (S, n): R (S, 3, 3), t (S, 3), x (S, 3). Returns R, t, x."""
    R, t, x = R.copy(), t.copy(), x.copy()
    S, n = W.shape
    J = np.empty((S, n, 3, 9))
    J[:, :, :, 3:6] = -np.eye(3)
    J[:, :, :, 6:] = Rf[None]
    L = _per_set(laser, S)
    for _ in range(MAX_ITERATIONS):
        Rl = np.einsum("sij,snj->sni", R, L)
        e = residuals(laser, Rf, tf, R, t, x)
        J[:, :, :, :3] = skew(Rl)                           # d e / d theta = [R l]x
        H = np.einsum("sn,snki,snkj->sij", W, J, J)
        g = np.einsum("sn,snki,snk->si", W, J, e)
        step = -np.einsum("sij,sj->si", np.linalg.pinv(H, hermitian=True), g)
        R = rotvecs_to_matrices(step[:, :3]) @ R
        t = t + step[:, 3:6]
        x = x + step[:, 6:]
        if np.all(np.abs(step[:, :3]) <= STEP_ROT) and np.all(np.abs(step[:, 3:]) <= STEP_MM):
            break
    return R, t, x


def first_solution(laser, Rf, tf, w):
    """Linear x, then Horn for R_Y, t_Y: (R, t, x) or a UcsioError."""
    x = linear_tcp(laser, Rf, tf, w)
    robot = Rf @ x + tf
    fit = horn.horn_batch(laser[None], robot[None], w[None])
    if not fit.ok[0]:
        raise UcsioError(f"cannot fit a frame: {fit.reason(0)}")
    return fit.R[0], fit.t[0], x


# ---------------------------------------------------------------- the gate

def joint_terms(p, Rf, w) -> np.ndarray:
    """w_i J_i^T J_i (..., n, 9, 9) for (dt, dθ, dx): J_i = [I, -[p_i]x, -R_i],
    p_i the laser points in robot axes about the translation's origin, R_i
    the flange orientations."""
    p = np.asarray(p, dtype=float)
    J = np.zeros(p.shape[:-1] + (3, 9))
    J[..., :3] = np.eye(3)
    J[..., 3:6] = -skew(p)
    J[..., 6:] = -np.asarray(Rf, dtype=float)
    return np.asarray(w, dtype=float)[..., None, None] * np.einsum("...ki,...kj->...ij", J, J)


def moments(laser, Rf, R, w, centred: bool = True):
    """H = Σ w_i J_i^T J_i and G = Σ w_i² J_i^T J_i (9, 9), and the point the
    translation is taken at (UCS): the weighted centroid, or with
    ``centred`` False the frame's origin."""
    w = np.asarray(w, dtype=float)
    c = (w[:, None] * laser).sum(axis=0) / w.sum() if centred else np.zeros(3)
    p = (laser - c) @ R.T
    T = joint_terms(p, Rf, np.ones_like(w))
    return np.einsum("n,nij->ij", w, T), np.einsum("n,nij->ij", w * w, T), c


def covariance(laser, Rf, R, w, sigma: float, centred: bool = True) -> np.ndarray:
    """First-order covariance (9, 9) of (dt, dθ, dx): dt at the centroid (the
    frame's first six in precision.py's coordinates), or with ``centred``
    False at the frame's origin (the fitted translation's own doubt). inf
    where some direction is undetermined."""
    H, G, _c = moments(laser, Rf, R, w, centred)
    ev = np.linalg.eigvalsh(H)
    if ev[0] <= 1e-12 * max(ev[-1], 1e-300):
        return np.full((9, 9), np.inf)                       # some direction undetermined
    Hinv = np.linalg.inv(H)
    return sigma ** 2 * Hinv @ G @ Hinv


def orientation_span(Rf: np.ndarray) -> float:
    """The largest angle (deg) between two of the flange orientations."""
    if len(Rf) < 2:
        return 0.0
    i, j = np.triu_indices(len(Rf), 1)
    return float(np.max(rotation_angle_deg(Rf[i], Rf[j])))


def tcp_reason(doubt: float, span: float, threshold: float) -> str:
    head = (f"the flange orientations do not vary enough to pin the TCP down: they span "
            f"{span:.1f} deg (the largest angle between two used points)")
    if not math.isfinite(doubt):
        return (head + ", about fewer than two axes, so part of the TCP is not determined at "
                "all; tilt the flange about two axes between points, or give the TCP "
                "(--tcp X,Y,Z or --tool)")
    need = span * doubt / threshold
    return (head + f", which leaves the TCP known only to {doubt:.2f} mm (95 %), over the "
            f"{threshold:g} mm threshold; turn the flange by about {math.ceil(need)} deg or more "
            "between points (about at least two axes), or give the TCP (--tcp X,Y,Z or --tool)")


# ---------------------------------------------------------------- the method

def solve_joint(measurement, *, threshold: float = defaults.THRESHOLD,
                min_points: int = defaults.MIN_POINTS, exclude: Iterable[str] = (),
                no_exclusion: bool = False, reach: float = defaults.REACH,
                sigma_laser: float = defaults.SIGMA_LASER,
                sigma_robot: float = defaults.SIGMA_ROBOT, at=None, gate: str = "reach"):
    """The method with the TCP among the unknowns: a ``solve.Solution`` whose
    ``tcp`` is the solved offset and ``tcp_solved`` its JSON (x, y, z,
    solved, std, at_95). ``at``, ``gate``: working points, as ``solve``."""
    from . import noise, working
    from . import precision as prec
    from .solve import (PointResult, Solution, acceptance, check_gate, check_sigmas,
                        hand_marks, judge, next_exclusion)

    if not threshold > 0:
        raise UcsioError(f"threshold must be positive, got {threshold}")
    if min_points < 3:
        raise UcsioError(f"min-points must be at least 3, got {min_points}")
    check_sigmas(sigma_laser, sigma_robot)
    check_gate(gate, at)
    path = measurement.path
    names = list(measurement.names)
    laser = np.asarray(measurement.laser, dtype=float)
    Rf = np.asarray(measurement.flange, dtype=float)[:, :3, :3]
    tf = np.asarray(measurement.flange, dtype=float)[:, :3, 3]
    weights = np.asarray(measurement.weights, dtype=float)
    n = len(names)
    marks = hand_marks(names, exclude, path)
    used = np.array([m is None for m in marks])
    if used.sum() < MIN_POINTS_JOINT:
        raise UcsioError(f"the TCP solved with the frame needs at least {MIN_POINTS_JOINT} "
                         f"points, {int(used.sum())} given", file=path)

    with np.errstate(all="ignore"):
        try:
            R, t, x = first_solution(laser, Rf, tf, weights * used)
        except UcsioError as exc:
            raise UcsioError(exc.message, file=path) from None
        R, t, x = (a[0] for a in gauss_newton(laser, Rf, tf, (weights * used)[None], R[None],
                                              t[None], x[None]))
        first = True
        while True:
            resid = np.linalg.norm(residuals(laser, Rf, tf, R[None], t[None], x[None])[0], axis=1)
            loo = _leave_one_out(laser, Rf, tf, weights, used, R, t, x)
            worst = next_exclusion(used, resid, loo, first=first, threshold=threshold,
                                   no_exclusion=no_exclusion, fewest=MIN_POINTS_JOINT)
            first = False
            if worst is None:
                break
            used[worst] = False
            marks[worst] = "auto"
            R, t, x = (a[0] for a in gauss_newton(laser, Rf, tf, (weights * used)[None],
                                                  R[None], t[None], x[None]))

        e = residuals(laser, Rf, tf, R[None], t[None], x[None])[0]
        r_used = resid[used]
        n_used = int(used.sum())
        accepted, reason = acceptance(n_used, float(r_used.max()), threshold=threshold,
                                      min_points=min_points, no_exclusion=no_exclusion,
                                      n_auto=marks.count("auto"))
        # the gates, from the used points' geometry: per unit noise, then the
        # larger of the stated noise's quantile and the residuals' (3n - 9 dof)
        stated = math.hypot(sigma_laser, sigma_robot)
        e2 = float(np.sum(r_used ** 2))
        s_res = float(residual_sigma(e2, n_used, params=9))
        dof = float(prec.dof_of(n_used, params=9))
        sigma = max(stated, s_res)
        wu = weights * used
        K = covariance(laser[used], Rf[used], R, wu[used], 1.0)
        finite = bool(np.all(np.isfinite(K)))
        span = orientation_span(Rf[used])
        lu = laser[used]
        cen = (wu[used][:, None] * lu).sum(axis=0) / wu[used].sum()
        C = np.einsum("n,ni,nj->ij", wu[used], lu - cen, lu - cen) / wu[used].sum()
        spread = np.sqrt(np.clip(np.linalg.eigvalsh(C)[::-1], 0.0, None))
        if finite:
            doubt = float(prec.q95(K[None, 6:, 6:], stated, s_res, dof)[0])
            tcp_std = sigma * np.sqrt(np.clip(np.diag(K)[6:], 0.0, None))
            at_reach = float(prec.at_reach95(K[None, :6, :6], reach, stated, s_res, dof)[0])
            source = ("residuals" if at_reach > float(prec.at_reach95(K[None, :6, :6], reach,
                                                                        stated)[0])
                      else "stated")
            at_centroid = float(prec.q95(K[None, :3, :3], stated, s_res, dof)[0])
            angle_std = float(np.degrees(sigma * np.sqrt(max(np.trace(K[3:6, 3:6]), 0.0))))
            cov_json = working.covariance_json(K[:6, :6], cen, stated, s_res, dof)
        else:
            doubt = at_reach = at_centroid = angle_std = math.inf
            tcp_std = np.full(3, np.inf)
            source, cov_json = "stated", None
    precision = {"sigma": sigma, "angle_std": angle_std, "reach": float(reach),
                 "at_reach": at_reach, "at_centroid": at_centroid,
                 "spread": [float(v) for v in spread], "sigma_source": source, "dof": dof,
                 "tcp_at_95": doubt, "orientation_span": span}
    wp = worst = None
    if at is not None and cov_json is not None:
        wp, worst = working.predict(cov_json, R, at)
    elif at is not None:           # the frame undetermined: nothing is known anywhere
        wp, worst = working.describe(at.names, at.xyz, [math.inf] * len(at))
    if accepted and not doubt <= threshold:
        accepted, reason = False, tcp_reason(doubt, span, threshold)
    elif accepted and not at_reach <= threshold and gate != "at":
        accepted, reason = False, prec.reason(at_reach, at_centroid, reach, threshold, sigma,
                                              angle_std, spread)
    else:
        accepted, reason = judge(accepted, reason, dict(precision), worst, gate, threshold)
    if accepted and s_res > 0 and finite:
        # the gates passed on these residuals: the TCP's 95 % for such fits
        judged = selected_doubt(K, stated, s_res, dof, threshold, gate, reach, cov_json, R, at)
        tcp_std = tcp_std * (judged / doubt)
        doubt = precision["tcp_at_95"] = judged
    robot = laser @ R.T + t + e      # the reflector in world with the solved TCP
    points = [PointResult(name=names[k], residual=float(resid[k]),
                          loo_residual=float(loo[k] if used[k] else resid[k]), used=bool(used[k]),
                          dx=float(e[k, 0]), dy=float(e[k, 1]), dz=float(e[k, 2]),
                          excluded_by=marks[k], weight=float(weights[k]),
                          line=measurement.lines[k] if measurement.lines else None,
                          laser=laser[k].tolist(), robot=robot[k].tolist())
              for k in range(n)]
    pose = Pose.from_matrix(tuple(map(tuple, R.tolist())), t.tolist())
    tcp = tuple(float(v) for v in x)
    sol = Solution(pose=pose, points=points, n_points=n, n_used=n_used,
                   rms=float(np.sqrt(np.mean(r_used ** 2))), mean=float(np.mean(r_used)),
                   max=float(np.max(r_used)), accepted=accepted, reason=reason,
                   tcp=tcp, threshold=float(threshold), min_points=int(min_points), source=path,
                   no_exclusion=bool(no_exclusion), precision=precision, covariance=cov_json,
                   consistency=noise.consistency(e2, n_used, 9, stated), working_points=wp,
                   worst=worst, gate=gate)
    sol.tcp_solved = {"x": tcp[0], "y": tcp[1], "z": tcp[2], "solved": True,
                      "std": {k: float(v) for k, v in zip("xyz", tcp_std)}, "at_95": doubt}
    return sol


def selected_doubt(K, stated: float, s_res: float, dof: float, threshold: float, gate: str,
                   reach: float, cov_json, R, at) -> float:
    """The TCP's 95 % doubt of a fit the gates accepted (``selected``): the
    gates judged the same residual σ s, so the residual side is the quantile
    given that they passed; the stated noise's side as before."""
    from . import precision as prec
    from .selected import accepted_q95

    unit = {"sigma_stated": 0.0, "sigma_residual": 1.0}
    per_s = float(prec.q95(K[None, 6:, 6:], 0.0, 1.0, dof)[0])
    if gate == "at" and at is not None:
        from . import working
        _, w = working.predict(dict(cov_json, **unit), R, at)
        per_s = max(per_s, w["at_95"])
    else:
        per_s = max(per_s, float(prec.at_reach95(K[None, :6, :6], reach, 0.0, 1.0, dof)[0]))
    return max(float(prec.q95(K[None, 6:, 6:], stated)[0]),
               accepted_q95(K[6:, 6:], s_res, dof, threshold, per_s))


def _leave_one_out(laser, Rf, tf, weights, used, R, t, x) -> np.ndarray:
    """(n,) each used point's distance to the joint fit of the other used
    points (nan where fewer than MIN_POINTS_JOINT remain, or not used)."""
    n = len(laser)
    idx = np.flatnonzero(used)
    out = np.full(n, np.nan)
    if len(idx) - 1 < MIN_POINTS_JOINT:
        return out
    W = np.repeat((weights * used)[None], len(idx), axis=0)
    W[np.arange(len(idx)), idx] = 0.0
    S = len(idx)
    Rs, ts, xs = gauss_newton(laser, Rf, tf, W, np.repeat(R[None], S, 0),
                              np.repeat(t[None], S, 0), np.repeat(x[None], S, 0))
    e = residuals(laser, Rf, tf, Rs, ts, xs)                 # (S, n, 3)
    out[idx] = np.linalg.norm(e[np.arange(S), idx], axis=1)
    return out


# ---------------------------------------------------------------- uncertainty

def uncertainty(measurement, sol, n_samples: int = 10000,
                sigma_laser: float = defaults.SIGMA_LASER,
                sigma_robot: float = defaults.SIGMA_ROBOT, seed: int = 0) -> dict[str, Any]:
    """``solve --uncertainty N`` for the joint model: N copies of the used
    points with Gaussian noise per axis (``sigma_laser`` on the laser points,
    ``sigma_robot`` on the flange positions), each refitted by Gauss-Newton
    from the solution, in one batch. The keys of ``solve.uncertainty`` (x, y,
    z, angle of the frame; the noise scaled up to the residuals' where they
    show more, √(Σ|e|² / (3n − 9))), plus ``tcp``: ``std`` and ``ci95`` of
    the solved TCP. ``analytical_std``: the first-order numbers alongside."""
    from .solve import check_sigmas

    check_sigmas(sigma_laser, sigma_robot)
    if n_samples < 2:
        raise UcsioError("--uncertainty needs at least 2 samples")
    used = np.array([p.used for p in sol.points])
    L = np.asarray(measurement.laser, dtype=float)[used]
    F = np.asarray(measurement.flange, dtype=float)[used]
    w = np.asarray(measurement.weights, dtype=float)[used]
    Rf, tf = F[:, :3, :3], F[:, :3, 3]
    n = len(L)
    r = np.array([p.residual for p in sol.points])[used]
    stated = math.hypot(sigma_laser, sigma_robot)
    residual = float(residual_sigma(np.sum(r ** 2), n, params=9))
    source = "stated"
    if residual > stated:
        source = "residuals"
        if stated > 0:
            sigma_laser, sigma_robot = sigma_laser * residual / stated, sigma_robot * residual / stated
        else:
            sigma_robot = residual
    R0 = np.array(sol.pose.matrix, dtype=float)
    t0 = np.array(sol.pose.t, dtype=float)
    x0 = np.array(sol.tcp, dtype=float)
    rng = np.random.default_rng(seed)
    noisy_l = L + rng.normal(0.0, sigma_laser, size=(n_samples, n, 3))
    noisy_t = tf + rng.normal(0.0, sigma_robot, size=(n_samples, n, 3))
    S = n_samples
    with np.errstate(all="ignore"):
        R, t, x = gauss_newton(noisy_l, Rf, noisy_t, np.broadcast_to(w, (S, n)),
                               np.repeat(R0[None], S, 0), np.repeat(t0[None], S, 0),
                               np.repeat(x0[None], S, 0))
    angle = rotation_angle_deg(R0[None], R)

    def stats(v):
        lo, hi = np.percentile(v, [2.5, 97.5], axis=0)
        return ({k: float(np.std(v[:, j], ddof=1)) for j, k in enumerate("xyz")},
                {k: [float(lo[j]), float(hi[j])] for j, k in enumerate("xyz")})

    std, ci95 = stats(t)
    std["angle"] = float(np.sqrt(np.mean(angle ** 2)))
    ci95["angle"] = [0.0, float(np.percentile(angle, 95.0))]
    tcp_std, tcp_ci = stats(x)
    cov = covariance(L, Rf, R0, w, 1.0, centred=False) * (sigma_laser ** 2 + sigma_robot ** 2)
    finite = bool(np.all(np.isfinite(cov)))
    d = np.sqrt(np.clip(np.diag(cov), 0.0, None)) if finite else np.full(9, np.inf)
    analytical = {"x": float(d[0]), "y": float(d[1]), "z": float(d[2]),
                  "angle": float(np.degrees(np.sqrt(max(np.trace(cov[3:6, 3:6]), 0.0))))
                  if finite else math.inf}
    return {"samples": int(n_samples), "sigma_laser": float(sigma_laser),
            "sigma_robot": float(sigma_robot), "sigma": float(math.hypot(sigma_laser, sigma_robot)),
            "sigma_source": source, "seed": int(seed), "std": std, "ci95": ci95,
            "tcp": {"std": tcp_std, "ci95": tcp_ci,
                    "analytical_std": {k: float(v) for k, v in zip("xyz", d[6:])}},
            "analytical_std": analytical}


# ---------------------------------------------------------------- diagnosis

#: what the diagnosis tells a command-line user to do (``batch`` names its keys)
DIAGNOSIS_ADVICE = "check --tool / --tcp, or solve the TCP with the frame (--tcp solve)"


def diagnose(measurement, sol, *, advice: str = DIAGNOSIS_ADVICE,
             **settings) -> dict[str, Any] | None:
    """For a rejected fixed-TCP solve: the joint model's fit, where it is
    accepted with the same settings and its TCP is more than the threshold
    away from the one given (a wrong TCP, not a bad measurement), else None.
    Returns ``tcp`` (x, y, z), ``distance`` (mm from the given TCP),
    ``n_used``, ``rms``, ``max`` and ``message`` (ending with ``advice``:
    what to check instead of measuring again)."""
    if sol.accepted or len(measurement.names) < MIN_POINTS_JOINT:
        return None
    hand = [p.name for p in sol.points if p.excluded_by == "hand"]
    try:
        joint = solve_joint(measurement, exclude=hand, **settings)
    except UcsioError:
        return None
    if not joint.accepted:
        return None
    dist = math.dist(joint.tcp, sol.tcp)
    if dist <= joint.threshold:
        return None
    x, y, z = joint.tcp
    msg = (f"the residuals are what a wrong TCP gives: a TCP of {x:.3f}, {y:.3f}, {z:.3f} mm "
           f"(flange), {dist:.2f} mm from the one given, fits {joint.n_used} of "
           f"{joint.n_points} points within {joint.max:.3f} mm; {advice}")
    return {"tcp": [x, y, z], "distance": dist, "n_used": joint.n_used, "rms": joint.rms,
            "max": joint.max, "message": msg}
