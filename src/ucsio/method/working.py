"""Working points: the predicted 95 % error of a fitted frame where the robot
works (SPEC, "Planning and working points").

Small residuals do not prove a frame: the residuals at the measured points
say nothing about the error at the points the robot goes to (Fitzpatrick &
West, IEEE TMI 2001). The fit's first-order covariance does: a solution
keeps it per unit noise (``covariance_json``: the 6x6 of dt at the used
points' centroid and dθ, in robot world axes, with the stated noise, the
residuals' and their degrees of freedom), and the error at a UCS point w is
the 95 % length of J_w (dt, dθ), J_w = [I, -[R (w - c)]x] (``precision``).

``predict`` evaluates it with numpy (solve, batch); ``predict_plain`` in
plain math from a SOLUTION.json (``diff --points``, which imports no numpy).
"""
from __future__ import annotations

TYPE_CHECKING = False      # typing costs a cold start; annotations are strings
if TYPE_CHECKING:
    from typing import Any


def covariance_json(K, centroid, sigma_stated: float, sigma_residual: float,
                    dof: float) -> dict[str, Any]:
    """What a solution keeps of its covariance: ``frame`` (6x6 per unit
    noise, mm² and rad², dt at ``about`` then dθ, robot world axes),
    ``about`` (the UCS point, mm), ``sigma_stated``, ``sigma_residual``
    (mm per axis) and ``dof`` (the residuals' degrees of freedom)."""
    return {"frame": K.tolist(), "about": [float(v) for v in centroid],
            "axes": "robot world", "sigma_stated": float(sigma_stated),
            "sigma_residual": float(sigma_residual), "dof": float(dof)}


def describe(names, xyz, at95, extra=None) -> tuple[list[dict[str, Any]], dict[str, Any] | None]:
    """SPEC's ``working_points`` (each ``name``, ``x y z``, ``at_95``) and
    ``worst`` (``name``, ``at_95``; the first of equals). ``extra``: per point,
    more keys (a taught point's file and line)."""
    rows = []
    for k, (name, p, q) in enumerate(zip(names, xyz, at95)):
        row = {"name": name, "x": float(p[0]), "y": float(p[1]), "z": float(p[2]),
               "at_95": float(q)}
        if extra is not None:
            row.update(extra[k])
        rows.append(row)
    if not rows:
        return rows, None
    worst = max(rows, key=lambda r: r["at_95"])
    return rows, {k: worst[k] for k in ("name", "at_95", "file", "line") if k in worst}


def predict(cov: dict[str, Any], R, points, extra=None):
    """(working_points, worst) of ``points`` (``readers.points.Points``) for a
    fit with rotation R and ``covariance_json`` ``cov``."""
    import numpy as np

    from .precision import at_points95

    K = np.asarray(cov["frame"], dtype=float)[None]
    P = (np.asarray(points.xyz, dtype=float) - np.asarray(cov["about"])) @ np.asarray(R).T
    q = at_points95(K, P, cov["sigma_stated"], cov["sigma_residual"], cov["dof"])[0]
    return describe(points.names, points.xyz, q.tolist(), extra)


def predict_plain(cov: dict[str, Any], R, xyz) -> list[float]:
    """The 95 % errors (mm) at the UCS points ``xyz`` in plain math
    (``quantile.at_point95``): the same numbers as ``predict``."""
    from .quantile import at_point95

    K, c = cov["frame"], cov["about"]
    args = (cov["sigma_stated"], cov["sigma_residual"], cov["dof"])
    return [at_point95(K, c, R, w, *args) for w in xyz]


def from_solution(data: Any) -> dict[str, Any] | None:
    """A SOLUTION.json's ``covariance``, checked, or None where it has none
    (written before solutions kept it, or by hand)."""
    import math

    cov = data.get("covariance") if isinstance(data, dict) else None
    if not isinstance(cov, dict):
        return None

    def finite(v):
        return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)

    K, c = cov.get("frame"), cov.get("about")
    if not (isinstance(K, list) and len(K) == 6
            and all(isinstance(r, list) and len(r) == 6 and all(map(finite, r)) for r in K)
            and isinstance(c, list) and len(c) == 3 and all(map(finite, c))
            and all(finite(cov.get(k)) for k in ("sigma_stated", "sigma_residual", "dof"))):
        return None
    return cov
