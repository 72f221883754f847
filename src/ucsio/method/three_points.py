"""Frames by their three points (SPEC, "Measurement programs and frames by
three points").

Every pendant defines a user frame from three taught points: the origin
ORG, a point XX on +X, a point XY in the XY plane on the +Y side. The
construction: x along ORG->XX, z = x × (XY - ORG) normalised, y = z × x.

``compare``: the frame that construction gives from three of the measured
points, beside the best fit over all the used points. The three are the
pair of used points farthest apart (ORG the one listed first, XX the other)
and the used point farthest from the line through them (the largest
triangle), judged on the laser side (the UCS); ties go to the point listed
first. The construction runs on both sides of the same three physical
points: F_L on their laser coordinates (UCS), F_R on the robot's TCP
positions (robot base); the UCS in robot world is then F_R·F_L⁻¹. When the
three points are the fixture's own origin, +X and XY points, F_L is the
identity and this is exactly the pendant's frame.

``setting``: the three points that set the measured frame by hand:
ORG = the origin, XX = ORG + d·x̂, XY = ORG + d·ŷ in robot base. XY lies on
the Y axis itself, so a pendant that puts the origin at the foot of XY on
the line ORG-XX gives the same frame as one that puts it at ORG. With a
reach box, the three points move together by the smallest offset
s = a·x̂ + b·ŷ + c·ẑ that puts all three inside it: the construction then
gives the measured orientation exactly and the origin at ORG + s, which the
user must take back by (-a, -b, -c) along the frame's own axes.
"""
from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np

from ..errors import UcsioError
from ..geometry.frames import Pose

DEFAULT_DISTANCE = 200.0
RULE = ("the pair of used points farthest apart (origin: the one listed first, +X: the other) "
        "and the used point farthest from the line through them (XY), on the laser side")


def construct(org, xx, xy) -> tuple[np.ndarray, np.ndarray]:
    """(R, t) of the 3-point construction: R's columns x̂, ŷ, ẑ, t = ORG."""
    org, xx, xy = (np.asarray(p, dtype=float) for p in (org, xx, xy))
    x = (xx - org) / np.linalg.norm(xx - org)
    z = np.cross(x, xy - org)
    z = z / np.linalg.norm(z)
    return np.column_stack([x, np.cross(z, x), z]), org


def pick_three(points: np.ndarray) -> tuple[int, int, int] | None:
    """Indices (ORG, XX, XY) into ``points`` (n, 3) by the rule in RULE;
    None where no three of them span a triangle."""
    n = len(points)
    if n < 3:
        return None
    if n > EXACT_UP_TO:             # the farthest pair is on the hull: its extremes
        keep = _extremes(points)
        got = pick_three(points[keep])
        return None if got is None else tuple(int(keep[m]) for m in got)
    d = np.linalg.norm(points[:, None, :] - points[None, :, :], axis=2)
    i, j = divmod(int(np.argmax(np.triu(d, 1))), n)   # the first of equals: i < j
    axis = points[j] - points[i]
    off = np.linalg.norm(np.cross(points - points[i], axis), axis=1) / np.linalg.norm(axis)
    k = int(np.argmax(off))
    if not off[k] > 1e-9 * max(d[i, j], 1.0):
        return None
    return i, j, k


#: more used points than this: the rule runs on the points extreme along 13
#: directions (axes, face and space diagonals) and the farthest from their
#: mean, not on every pair (n² distances)
EXACT_UP_TO = 500


def _extremes(points: np.ndarray) -> np.ndarray:
    dirs = np.array([v for v in itertools.product((-1, 0, 1), repeat=3) if v > (0, 0, 0)],
                    dtype=float)
    proj = points @ dirs.T
    far = np.linalg.norm(points - points.mean(axis=0), axis=1)
    return np.unique(np.concatenate([proj.argmin(axis=0), proj.argmax(axis=0),
                                     [int(far.argmax())]]))


def _pose_dict(R: np.ndarray, t: np.ndarray) -> dict[str, Any]:
    pose = Pose.from_matrix(tuple(map(tuple, R.tolist())), t.tolist())
    d = pose.as_dict()
    w, p, r = pose.wpr
    d.update({"w": w, "p": p, "r": r})
    return d


def worst_at_reach(R1, t1, R2, t2, centroid, reach: float) -> tuple[np.ndarray, float]:
    """The UCS point ``reach`` mm from ``centroid`` where the two frames
    differ most, and that difference (mm). d(c + r·u) = a + r·M·u with
    M = R1 - R2 of rank 2 (singular values s, s, 0): the points r·M·u fill a
    disc of radius r·s, so the farthest is a's own direction in the disc's
    plane (any direction there when a is normal to it)."""
    M = np.asarray(R1) - np.asarray(R2)
    a = M @ centroid + (np.asarray(t1) - np.asarray(t2))
    U, S, Vt = np.linalg.svd(M)
    if not S[0] > 1e-15:                          # one rotation: the same everywhere
        return centroid + reach * Vt[0], float(np.linalg.norm(a))
    in_plane = U[:, :2] @ (U[:, :2].T @ a)
    size = np.linalg.norm(in_plane)
    direction = in_plane / size if size > 1e-12 * max(np.linalg.norm(a), 1.0) else U[:, 0]
    u = Vt[:2].T @ ((U[:, :2].T @ direction) / S[:2])  # M u ∥ direction
    u = u / np.linalg.norm(u)
    p = centroid + reach * u
    return p, float(np.linalg.norm(M @ p + np.asarray(t1) - np.asarray(t2)))


def compare(names, laser, robot, weights, used, R, t, reach: float, at=None
            ) -> dict[str, Any] | None:
    """``three_point_frame``: the 3-point frame from the used points (the
    rule in RULE) beside the best fit (R, t), and how far apart they put
    each working point (``at``: readers.points.Points, else the point
    ``reach`` mm from the used points' weighted centroid where they differ
    most). None where the used points span no triangle."""
    idx = np.flatnonzero(used)
    three = pick_three(laser[idx])
    if three is None:
        return None
    i, j, k = (int(idx[m]) for m in three)
    RL, tL = construct(laser[i], laser[j], laser[k])
    RR, tR = construct(robot[i], robot[j], robot[k])
    R3 = RR @ RL.T                                # F_R · F_L⁻¹
    t3 = tR - R3 @ tL
    rel = np.clip((np.trace(R3.T @ R) - 1.0) / 2.0, -1.0, 1.0)
    out: dict[str, Any] = {
        "rule": RULE,
        "points": [{"role": role, "name": names[m], "laser": laser[m].tolist(),
                    "robot": robot[m].tolist()}
                   for role, m in (("ORG", i), ("XX", j), ("XY", k))],
        "frame": _pose_dict(R3, t3),
        "dist": float(np.linalg.norm(t3 - t)), "angle": math.degrees(math.acos(rel)),
    }
    if at is not None:
        xyz = np.asarray(at.xyz, dtype=float).reshape(-1, 3)
        moved = np.linalg.norm(xyz @ (R - R3).T + (t - t3), axis=1)
        rows = [{"name": nm, "x": float(p[0]), "y": float(p[1]), "z": float(p[2]),
                 "dist": float(m)} for nm, p, m in zip(at.names, xyz, moved.tolist())]
    else:
        w = np.asarray(weights, dtype=float)[idx]
        centroid = (w[:, None] * laser[idx]).sum(axis=0) / w.sum()
        p, m = worst_at_reach(R, t, R3, t3, centroid, reach)
        rows = [{"name": f"reach {reach:g} mm", "x": float(p[0]), "y": float(p[1]),
                 "z": float(p[2]), "dist": m}]
    out["working_points"] = rows
    worst = max(rows, key=lambda r: r["dist"]) if rows else None
    out["worst"] = None if worst is None else {"name": worst["name"], "dist": worst["dist"]}
    return out


# ------------------------------------------------------------ setting by hand

def parse_box(text: str | None) -> tuple[float, ...] | None:
    """--reach-box XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX (mm) -> six floats."""
    if text is None:
        return None
    if not isinstance(text, str):
        vals = list(text)
    else:
        vals = [s.strip() for s in text.split(",")]
    try:
        box = tuple(float(v) for v in vals)
    except (TypeError, ValueError):
        box = ()
    if len(box) != 6 or not all(math.isfinite(v) for v in box):
        raise UcsioError(f"--reach-box {text!r}: expected six numbers "
                         "XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX (mm, robot base)")
    if not all(box[2 * k] < box[2 * k + 1] for k in range(3)):
        raise UcsioError(f"--reach-box {text!r}: each minimum must be below its maximum")
    return box


def check_distance(distance: float) -> float:
    distance = float(distance)
    if not (math.isfinite(distance) and distance > 0):
        raise UcsioError(f"--three-point-distance {distance}: a distance must be a finite "
                         "number > 0 (mm)")
    return distance


def smallest_shift(A: np.ndarray, b: np.ndarray) -> np.ndarray | None:
    """The shortest s with A s <= b (a handful of constraints in 3 unknowns):
    the minimum-norm point of a polyhedron is the projection of 0 onto the
    affine hull of at most three of its constraints; try every such set."""
    tol = 1e-9 * max(1.0, float(np.abs(b).max()))
    if np.all(b >= 0.0):
        return np.zeros(3)
    best = None
    for size in (1, 2, 3):
        for rows in itertools.combinations(range(len(A)), size):
            As, bs = A[list(rows)], b[list(rows)]
            gram = As @ As.T
            if abs(np.linalg.det(gram)) < 1e-12:
                continue
            s = As.T @ np.linalg.solve(gram, bs)
            if np.all(A @ s <= b + tol) and (best is None or s @ s < best @ best):
                best = s
    return best


def setting(R, t, distance: float, tcp, tool: str | None, box=None) -> dict[str, Any]:
    """``three_points``: ORG, XX, XY (robot base, mm) that set the frame
    (R, t) by the construction, with the TCP they are positions of; inside
    ``box`` by the smallest shift along the frame's axes (module docstring)."""
    R, t = np.asarray(R, dtype=float), np.asarray(t, dtype=float)
    steps = np.array([[0.0, 0.0, 0.0], distance * R[:, 0], distance * R[:, 1]])
    shift = np.zeros(3)
    if box is not None:
        lo, hi = np.array(box[0::2]), np.array(box[1::2])
        # P_k + R s within [lo, hi] for the three points P_k = t + steps[k]
        A = np.vstack([np.vstack([R, -R]) for _ in steps])
        b = np.concatenate([np.concatenate([hi - (t + s), (t + s) - lo]) for s in steps])
        found = smallest_shift(A, b)
        if found is None:
            raise UcsioError(f"--reach-box: the three points {distance:g} mm apart along the "
                             "frame's axes fit nowhere inside the box; give a smaller "
                             "--three-point-distance or a larger box")
        shift = found
    org = t + R @ shift
    pts = {"ORG": org, "XX": org + steps[1], "XY": org + steps[2]}
    a, b, c = shift.tolist()
    out: dict[str, Any] = {
        "distance": float(distance),
        "points": [{"role": k, "x": float(v[0]), "y": float(v[1]), "z": float(v[2])}
                   for k, v in pts.items()],
        "tcp": {"x": float(tcp[0]), "y": float(tcp[1]), "z": float(tcp[2]), "tool": tool},
        "reach_box": None if box is None else list(box),
        "offset": {"x": a, "y": b, "z": c},
        "moved": bool(np.any(shift != 0.0)),
    }
    return out
