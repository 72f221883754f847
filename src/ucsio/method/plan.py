"""Planning a measurement before it is taken (``ucsio plan``; SPEC,
"Planning and working points").

Moving a reflector costs minutes; measuring again costs a shift. Before the
tracker is set up, the planned points (the fixture's nominal references and,
for a TCP solved with the frame, the planned flange poses) already fix the
fit's first-order covariance: it does not depend on the measured values,
only on where the points are (``precision``, ``tcp_solve``: the same
covariance the determinacy gate uses after the fit, with the stated noise).
From it:

- the predicted 95 % error at every working point (``--at``, the taught
  points of a frame, or the gate's generic point ``--reach`` mm from the
  centroid), the worst, and with ``--tcp solve`` the TCP's 95 % doubt and
  the flange orientations' span; the verdict against the threshold;
- ``suggest.add``: of the candidate locations (a file, or a grid of
  locations within ``margin`` mm of a planned point: a further reflector
  goes on the fixture, near the ones planned), the one whose point most
  lowers the worst working-point error, and where it lies from the nearest
  planned point;
- ``suggest.drop``: the planned point whose removal raises it least.

A point's share of the fit is one term J_iᵀJ_i of H and G, so a candidate is
H + J_aᵀJ_a and a drop H − w_i J_iᵀJ_i: every candidate's covariance is one
batched inverse, and every candidate's worst working point one matrix
product of its covariance's coefficients with the working points' monomials
(``precision.worst_at_points95``), in chunks. No loop per candidate in
Python (benchmarks/bench_plan.py).

With ``--tcp solve`` a candidate is taken with the flange orientation of the
planned point nearest to it (the robot reaching there can hold a similar
one), and the verdict also needs the TCP's doubt within the threshold (a
solve would reject it otherwise).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from . import horn
from .. import defaults
from . import precision as prec
from ..errors import UcsioError

MIN_FIXED = 3           # points a frame needs
MIN_JOINT = 4           # and a frame with its TCP (tcp_solve.MIN_POINTS_JOINT)


@dataclass
class Planned:
    """The planned points: names, UCS positions, weights; flange poses
    (n, 4, 4) in robot world where planned (None otherwise)."""

    path: str | None
    names: list[str]
    lines: list[int | None]
    laser: np.ndarray
    weights: np.ndarray
    flange: np.ndarray | None = None


@dataclass
class Model:
    """The planned fit's geometry: each point's terms of H and G, about the
    planned points' weighted centroid ``c`` (UCS), in axes R (world from UCS;
    the identity for a known TCP, whose error's length does not depend on
    them)."""

    joint: bool
    laser: np.ndarray        # (n, 3) the planned points, UCS
    weights: np.ndarray      # (n,)
    R: np.ndarray
    c: np.ndarray
    terms: np.ndarray        # (n, k, k) w_i J_iᵀJ_i
    terms2: np.ndarray       # (n, k, k) w_i² J_iᵀJ_i
    Rf: np.ndarray | None    # (n, 3, 3) flange orientations (joint)


def model(planned: Planned, joint: bool) -> Model:
    """The Model of a plan (UcsioError where the points cannot fix a frame)."""
    L, w = planned.laser, planned.weights
    need = MIN_JOINT if joint else MIN_FIXED
    if len(L) < need:
        raise UcsioError(f"{len(L)} planned point{'s' if len(L) != 1 else ''}: a frame"
                         f"{' with its TCP' if joint else ''} needs at least {need}",
                         file=planned.path)
    fit = horn.horn_batch(L[None], L[None], w[None])
    if not fit.ok[0]:
        raise UcsioError(f"the planned points cannot fix a frame: {fit.reason(0)}",
                         file=planned.path)
    c = (w[:, None] * L).sum(axis=0) / w.sum()
    if not joint:
        p = L - c
        return Model(False, L, w, np.eye(3), c, prec.point_terms(p, w),
                     prec.point_terms(p, w * w), None)
    from . import tcp_solve

    if planned.flange is None:
        raise UcsioError("--tcp solve plans the TCP with the frame: it needs the planned flange "
                         "poses (robot_* columns in the plan, or --robot FILE)",
                         file=planned.path)
    Rf, tf = planned.flange[:, :3, :3], planned.flange[:, :3, 3]
    with np.errstate(all="ignore"):
        try:        # the UCS in world as the planned poses place it
            R, t, x = tcp_solve.first_solution(L, Rf, tf, w)
        except UcsioError as exc:
            raise UcsioError(exc.message, file=planned.path) from None
        R = tcp_solve.gauss_newton(L, Rf, tf, w[None], R[None], t[None], x[None])[0][0]
    p = (L - c) @ R.T
    return Model(True, L, w, R, c, tcp_solve.joint_terms(p, Rf, w),
                 tcp_solve.joint_terms(p, Rf, w * w), Rf)


def candidate_terms(m: Model, xyz: np.ndarray) -> np.ndarray:
    """J_aᵀJ_a (B, k, k) of a point of weight 1 at each location (UCS); with
    a solved TCP, held with the flange orientation of the nearest planned
    point."""
    xyz = np.asarray(xyz, dtype=float)
    p = (xyz - m.c) @ m.R.T
    if not m.joint:
        return prec.point_terms(p, np.ones(len(p)))
    from . import tcp_solve

    return tcp_solve.joint_terms(p, m.Rf[nearest(m.laser, xyz)], np.ones(len(p)))


def nearest(points: np.ndarray, xyz: np.ndarray) -> np.ndarray:
    """For each location, the index of the nearest of ``points``."""
    d2 = (np.einsum("bi,bi->b", xyz, xyz)[:, None] - 2.0 * xyz @ points.T
          + np.einsum("ni,ni->n", points, points)[None])
    return np.argmin(d2, axis=1)


def covariances(H: np.ndarray, G: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """H⁻¹ G H⁻¹ per unit noise for (B, k, k) moments, and which of them are
    determined (where some direction is not, the covariance is left as the
    identity and ``ok`` is False: its errors are infinite)."""
    with np.errstate(all="ignore"):
        ev = np.linalg.eigvalsh(H)
        ok = ev[:, 0] > 1e-12 * np.maximum(ev[:, -1], 1e-300)
        eye = np.eye(H.shape[-1])
        Hinv = np.linalg.inv(np.where(ok[:, None, None], H, eye))
        K = np.where(ok[:, None, None], Hinv @ G @ Hinv, eye)
    return K, ok


def worst_error(m: Model, K: np.ndarray, ok: np.ndarray, sigma: float, at, reach: float,
                centroids: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The worst working point's 95 % error (B,) of B covariances and its
    index (-1: the generic point at ``reach`` from ``centroids`` (B, 3), each
    configuration's own weighted centroid, as the gate takes it)."""
    frame = K[:, :6, :6]
    if at is not None:
        P = (np.asarray(at.xyz, dtype=float) - m.c) @ m.R.T
        worst, where = prec.worst_at_points95(frame, P, sigma)
    else:
        frame = prec.shift(frame, (centroids - m.c) @ m.R.T)
        worst, where = prec.at_reach95(frame, reach, sigma), np.full(len(K), -1)
    return np.where(ok, worst, np.inf), where


def reach_point(m: Model, K: np.ndarray, reach: float, sigma: float):
    """The generic working point: (UCS position, 95 % error) of the point
    ``reach`` mm from the centroid across the least certain rotation axis,
    on the worse side (``precision.at_reach95``'s point)."""
    u = np.linalg.eigh(K[3:6, 3:6])[1][:, 0]
    p = np.array([u, -u]) * reach                              # world axes, about c
    q = prec.at_points95(K[None, :6, :6], p, sigma)[0]
    k = int(np.argmax(q))
    return m.c + m.R.T @ p[k], float(q[k])


DEFAULT_FROM = "near planned points"     # suggest.add.from of a default candidate
#: grid steps along the longest side of the default candidates' box, at most
GRID = 16


def default_candidates(planned: Planned, margin: float) -> tuple[list[str], np.ndarray]:
    """Locations within ``margin`` mm of a planned point, named after it: a
    grid over the planned points' box widened by the margin (at most GRID
    steps along its longest side, none coarser than half the margin), and the
    six points ``margin`` away along each axis from every planned point
    (the farthest a reflector may go, where its lever is longest)."""
    L = planned.laser
    lo, hi = L.min(axis=0) - margin, L.max(axis=0) + margin
    step = max(margin / 2.0, float((hi - lo).max()) / GRID)
    axes = [np.arange(a, b + step / 2.0, step) for a, b in zip(lo, hi)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    offsets = np.vstack([np.eye(3), -np.eye(3)]) * margin
    xyz = np.vstack([grid, (L[:, None, :] + offsets[None]).reshape(-1, 3)])
    near = nearest(L, xyz)
    dist = np.linalg.norm(xyz - L[near], axis=1)
    keep = (dist > 1e-9 * margin) & (dist <= margin * (1.0 + 1e-9))
    return [f"near {planned.names[i]}" for i in near[keep]], xyz[keep] + 0.0     # no -0.0


def relative_to_planned(planned: Planned, xyz) -> dict[str, Any]:
    """Where a location lies from the nearest planned point: its ``name``,
    the ``distance`` (mm) and the ``offset`` [dx, dy, dz] (mm, UCS axes)."""
    xyz = np.asarray(xyz, dtype=float)
    i = int(nearest(planned.laser, xyz[None])[0])
    d = xyz - planned.laser[i]
    return {"name": planned.names[i], "distance": float(np.linalg.norm(d)),
            "offset": [float(v) for v in d]}


def plan(planned: Planned, *, joint: bool = False, at=None, candidates=None,
         threshold: float, reach: float, sigma_laser: float, sigma_robot: float,
         min_points: int, margin: float = defaults.MARGIN) -> dict[str, Any]:
    """The plan's JSON (SPEC: working_points, worst, tcp_at_95,
    orientation_span, verdict, suggest), with ``reason`` where it fails and
    ``warnings``."""
    from . import working

    sigma = math.hypot(sigma_laser, sigma_robot)
    m = model(planned, joint)
    H, G = m.terms.sum(axis=0), m.terms2.sum(axis=0)
    K0, ok0 = covariances(H[None], G[None])
    n = len(planned.names)
    wsum = float(planned.weights.sum())
    wl = (planned.weights[:, None] * planned.laser).sum(axis=0)

    if at is not None:
        if ok0[0]:
            P = (at.xyz - m.c) @ m.R.T
            q = prec.at_points95(K0[:, :6, :6], P, sigma)[0]
        else:
            q = np.full(len(at), np.inf)
        rows, worst = working.describe(at.names, at.xyz, q.tolist(), at_extra(at))
    else:
        if ok0[0]:
            xyz, q = reach_point(m, K0[0], reach, sigma)
        else:
            xyz, q = m.c, math.inf
        rows, worst = working.describe([f"reach {reach:g} mm"], [xyz], [q])
        rows[0]["reach"] = float(reach)
    # the planned points' places beside their names: what `ucsio view` draws
    places = [{"name": name, "x": x, "y": y, "z": z}
              for name, (x, y, z) in zip(planned.names, np.asarray(planned.laser).tolist())]
    out: dict[str, Any] = {"planned": n, "points": list(planned.names), "sigma": sigma,
                           "planned_points": places,
                           "threshold": float(threshold), "reach": float(reach),
                           "working_points": rows, "worst": worst}
    fails = []
    if joint:
        from .tcp_solve import orientation_span, tcp_reason

        doubt = float(prec.q95(K0[:, 6:, 6:], sigma)[0]) if ok0[0] else math.inf
        span = orientation_span(m.Rf)
        out.update(tcp_at_95=doubt, orientation_span=span)
        if not doubt <= threshold:
            fails.append(tcp_reason(doubt, span, threshold))
    if not worst["at_95"] <= threshold:
        fails.append(at_risk(worst, threshold, sigma, m))
    out["verdict"] = "fail" if fails else "pass"
    out["reason"] = "; ".join(fails) if fails else None

    # what to change: one point added at a candidate location, one dropped
    if candidates is not None:
        cnames, cxyz = candidates.names, np.asarray(candidates.xyz, dtype=float)
    else:
        cnames, cxyz = default_candidates(planned, margin)
    T = candidate_terms(m, cxyz)
    Kc, okc = covariances(H + T, G + T)
    worst_c, _ = worst_error(m, Kc, okc, sigma, at, reach, (wl + cxyz) / (wsum + 1.0))
    add = None
    if len(cxyz):
        b = int(np.argmin(worst_c))
        add = {"name": cnames[b], "x": float(cxyz[b, 0]), "y": float(cxyz[b, 1]),
               "z": float(cxyz[b, 2]), "worst_after": float(worst_c[b]),
               "from": "candidates" if candidates is not None else DEFAULT_FROM,
               "nearest": relative_to_planned(planned, cxyz[b])}
        if joint:
            add["tcp_at_95_after"] = float(prec.q95(Kc[b:b + 1, 6:, 6:], sigma)[0]) \
                if okc[b] else math.inf
            add["orientation_from"] = planned.names[int(nearest(m.laser, cxyz[b:b + 1])[0])]
    drop = None
    fewest = max(MIN_JOINT if joint else MIN_FIXED, int(min_points))
    if n - 1 >= fewest:
        Kd, okd = covariances(H - m.terms, G - m.terms2)
        wd = wsum - planned.weights
        cen = (wl - planned.weights[:, None] * planned.laser) / wd[:, None]
        worst_d, _ = worst_error(m, Kd, okd, sigma, at, reach, cen)
        if np.isfinite(worst_d).any():
            i = int(np.argmin(worst_d))
            drop = {"name": planned.names[i], "worst_after": float(worst_d[i])}
            if joint:
                drop["tcp_at_95_after"] = float(prec.q95(Kd[i:i + 1, 6:, 6:], sigma)[0]) \
                    if okd[i] else math.inf
    out["suggest"] = {"add": add, "drop": drop}
    out["advice"] = advice(out, add)
    warnings = []
    if n < min_points:
        warnings.append(f"{n} points planned: solve rejects fewer than {min_points} "
                        "(--min-points); plan more")
    out["warnings"] = warnings
    return out


def advice(out: dict[str, Any], add: dict[str, Any] | None) -> str | None:
    """What to change where the working points fail (the TCP's reason
    carries its own)."""
    if out["worst"]["at_95"] <= out["threshold"] or add is None:
        return None
    where = f"{location(add)}, {from_nearest(add)}"
    if add["worst_after"] <= out["threshold"]:
        return (f"add a point at {where}: the worst working point is then predicted within "
                f"{add['worst_after']:.2f} mm; plan again with it")
    return (f"one more point is not enough (at best {add['worst_after']:.2f} mm, at {where}): "
            "add it, spread the others toward the working points, and plan again")


def location(add: dict[str, Any]) -> str:
    """'C3 (1200.0, 800.0, 0.0)', or the coordinates alone for a default
    candidate (its name is the nearest planned point's, said next)."""
    xyz = f"({add['x']:.1f}, {add['y']:.1f}, {add['z']:.1f})"
    return xyz if add["from"] == DEFAULT_FROM else f"{add['name']} {xyz}"


def from_nearest(add: dict[str, Any]) -> str:
    """'212.1 mm from M3 (+150.0, +150.0, +0.0)': where a suggested point
    lies from the nearest planned one."""
    near = add["nearest"]
    dx, dy, dz = near["offset"]
    return f"{near['distance']:.1f} mm from {near['name']} ({dx:+.1f}, {dy:+.1f}, {dz:+.1f})"


def at_extra(at) -> list[dict[str, Any]] | None:
    """Per working point, the file and line a taught point was read from."""
    files = getattr(at, "files", None)
    if files is None:
        return None
    return [{"file": f, "line": ln} for f, ln in zip(files, at.lines)]


def at_risk(worst: dict[str, Any], threshold: float, sigma: float, m: Model) -> str:
    spread = np.sqrt(np.clip(np.linalg.eigvalsh(np.cov(m.laser.T, bias=True))[::-1], 0, None))
    return (f"the planned points do not pin the frame down where the robot works: "
            f"{worst['name']} is predicted within {worst['at_95']:.2f} mm (95 %), over the "
            f"{threshold:g} mm threshold (noise {sigma:.3f} mm per axis; the points spread "
            f"{spread[0]:.0f} x {spread[1]:.0f} x {spread[2]:.0f} mm)")


def least_spread(planned: Planned, *, at, threshold: float, reach: float,
                 sigma_laser: float, sigma_robot: float) -> float:
    """For a TCP solved with the frame where the plan gives no flange poses:
    the least spread of ``program --measure``'s pattern (``spread.STEPS``)
    at which the TCP and the worst working point are both predicted within
    the threshold; the largest tried where none is (the plan then fails,
    saying why)."""
    from dataclasses import replace

    from . import spread

    sigma = math.hypot(sigma_laser, sigma_robot)
    for deg in spread.STEPS:
        m = model(replace(planned, flange=spread.flanges(planned.laser, deg)), True)
        K, ok = covariances(m.terms.sum(axis=0)[None], m.terms2.sum(axis=0)[None])
        if not ok[0] or not prec.q95(K[:, 6:, 6:], sigma)[0] <= threshold:
            continue
        if at is not None:
            worst = float(prec.at_points95(K[:, :6, :6], (at.xyz - m.c) @ m.R.T, sigma).max())
        else:
            worst = reach_point(m, K[0], reach, sigma)[1]
        if worst <= threshold:
            return float(deg)
    return float(spread.STEPS[-1])
