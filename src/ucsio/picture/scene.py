"""A solution as the numbers of its picture, in the solution's coordinates
(robot world: the measured frame's parent). Plain math, no numpy.

- ``points``: each measured point's tracker position mapped through the fit
  (R·laser + t), the robot's position, the residual robot − fit;
- ``measured``/``simulated``: frames as origin and axes (columns of R);
- ``working``: working points (UCS) mapped through the fit, with their
  predicted 95 % error; ``plan``: planned points, the suggested one, the one
  plan would drop.
"""
from __future__ import annotations

import math

from ..errors import UcsioError

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any


def nice(x: float) -> float:
    """The round number (1, 2 or 5 × 10^k) at or below ``x``."""
    if not x > 0 or not math.isfinite(x):
        return 1.0
    k = math.floor(math.log10(x))
    for m in (5, 2, 1):
        if m * 10 ** k <= x:
            return float(m * 10 ** k)
    return float(10 ** k)


def _vec(v: Any, what: str, path: str | None) -> list[float]:
    if (not isinstance(v, list) or len(v) != 3
            or not all(isinstance(c, (int, float)) and not isinstance(c, bool)
                       and math.isfinite(c) for c in v)):
        raise UcsioError(f"{what}: expected [x, y, z], three finite numbers", file=path)
    return [float(c) for c in v]


def _apply(R, t, p) -> list[float]:
    return [sum(R[i][j] * p[j] for j in range(3)) + t[i] for i in range(3)]


def frame_of(pose) -> dict[str, Any]:
    """A Pose as the picture draws it: origin, axes (R's columns) and its numbers."""
    R = pose.matrix
    d = pose.as_dict()
    d["origin"] = list(pose.t)
    d["axes"] = [[R[0][k], R[1][k], R[2][k]] for k in range(3)]
    return d


def measured_points(data: dict, pose, path: str | None) -> list[dict[str, Any]]:
    """The solution's points: tracker (fit-mapped), robot, residual, used."""
    pts = data.get("points")
    if not isinstance(pts, list) or not pts:
        raise UcsioError("the solution has no 'points' list (is it a SOLUTION.json written by "
                         "`ucsio solve -o`?)", file=path)
    R, t = pose.matrix, pose.t
    out = []
    for i, p in enumerate(pts):
        if not isinstance(p, dict) or "laser" not in p:
            raise UcsioError(f"points[{i}] has no 'laser' coordinates: solve it again with this "
                             "ucsio (solve -o writes them)", file=path)
        name = p.get("name") if isinstance(p.get("name"), str) else f"P{i + 1}"
        laser = _vec(p.get("laser"), f"points[{i}] ({name}) laser", path)
        tracker = _apply(R, t, laser)
        robot = (_vec(p["robot"], f"points[{i}] ({name}) robot", path) if "robot" in p
                 else tracker)
        d = [robot[k] - tracker[k] for k in range(3)]
        out.append({"name": name, "laser": laser, "tracker": tracker, "robot": robot,
                    "d": d, "residual": math.sqrt(sum(c * c for c in d)),
                    "used": p.get("used") is not False, "excluded_by": p.get("excluded_by")})
    return out


def working_points(rows, pose, worst) -> list[dict[str, Any]]:
    """Working points (UCS x y z, at_95) where the fit puts them in world."""
    R, t = pose.matrix, pose.t
    out = []
    for w in rows or ():
        at = _apply(R, t, [w["x"], w["y"], w["z"]])
        out.append({"name": w["name"], "at": at, "at_95": w.get("at_95"),
                    "worst": worst is not None and w["name"] == worst.get("name")})
    return out


def plan_points(plan: dict, pose, path: str | None) -> dict[str, Any]:
    """A plan's points, its suggested point and the point it would drop, in world."""
    places = plan.get("planned_points")
    if not isinstance(places, list):
        raise UcsioError("not a plan: no 'planned_points' (written by `ucsio plan --json` of "
                         "this ucsio)", file=path)
    R, t = pose.matrix, pose.t
    pts = [{"name": str(p.get("name")),
            "at": _apply(R, t, _vec([p.get("x"), p.get("y"), p.get("z")],
                                    f"planned_points[{i}]", path))}
           for i, p in enumerate(places)]
    suggest = plan.get("suggest") or {}
    add = suggest.get("add")
    drop = suggest.get("drop")
    return {"points": pts,
            "add": ({"name": add.get("name", "suggested"),
                     "at": _apply(R, t, _vec([add.get("x"), add.get("y"), add.get("z")],
                                             "suggest.add", path)),
                     "worst_after": add.get("worst_after")} if isinstance(add, dict) else None),
            "drop": drop.get("name") if isinstance(drop, dict) else None,
            "verdict": plan.get("verdict")}


def _extent(xyz: list[list[float]]) -> tuple[list[float], float]:
    lo = [min(p[k] for p in xyz) for k in range(3)]
    hi = [max(p[k] for p in xyz) for k in range(3)]
    size = max(hi[k] - lo[k] for k in range(3))
    return [(lo[k] + hi[k]) / 2 for k in range(3)], (size if size > 0 else 100.0)


def magnification(points: list[dict], size: float) -> float:
    """A round factor that draws the largest used residual about a tenth of
    the scene (an excluded blunder would shrink every other one to nothing)."""
    worst = max((p["residual"] for p in points if p["used"]), default=0.0) or \
        max((p["residual"] for p in points), default=0.0)
    if not worst > 0:
        return 1.0
    return max(1.0, nice(0.1 * size / worst))


def scene(solution: dict, *, simulated: dict | None = None, working: list | None = None,
          worst: dict | None = None, plan: dict | None = None, source: str | None = None,
          path: str | None = None) -> dict[str, Any]:
    """The picture's numbers. ``simulated``: ``diff``'s one-frame document
    (its ``simulated`` pose is mapped into the solution's coordinates through
    the same parent basis as its ``measured``). ``working``/``worst``: rows as
    ``solve --at`` gives them (UCS); default the solution's own."""
    from ..method.solution import pose_from_json

    pose = pose_from_json(solution, path, allow_rejected=True)
    points = measured_points(solution, pose, path)
    if working is None:
        working, worst = solution.get("working_points"), solution.get("worst")
    s: dict[str, Any] = {
        "title": source or "solution", "units": "mm",
        "coordinates": "robot world (the measured frame's parent)",
        "accepted": solution.get("accepted"), "reason": solution.get("reason"),
        "rms": solution.get("rms"), "max": solution.get("max"),
        "points": points, "measured": frame_of(pose), "simulated": None, "delta": None,
        "working": working_points(working, pose, worst), "plan": None}
    if simulated is not None:
        s["simulated"], s["delta"] = simulated_in_world(simulated, pose)
    if plan is not None:
        s["plan"] = plan_points(plan, pose, path)
    xyz = [p["tracker"] for p in points] + [p["robot"] for p in points]
    xyz += [w["at"] for w in s["working"]] + [pose.t]
    if s["simulated"]:
        xyz.append(s["simulated"]["origin"])
    if s["plan"]:
        xyz += [p["at"] for p in s["plan"]["points"]]
        if s["plan"]["add"]:
            xyz.append(s["plan"]["add"]["at"])
    center, size = _extent(xyz)
    s.update(center=center, size=size, magnify=magnification(points, size),
             axis_length=nice(0.35 * size), scale_bar=nice(0.25 * size),
             marker=marker_radius([p["tracker"] for p in points], size))
    for p in points:
        p["drawn"], p["clipped"] = drawn(p["d"], s["magnify"], 0.4 * size)
    return s


def marker_radius(xyz: list[list[float]], size: float) -> float:
    """A point's marker radius (mm): a small part of the scene, and small
    enough that the two closest points stay apart (points bunched in a
    corner of a large scene). Up to 200 points are compared pairwise."""
    r = 0.012 * size
    if len(xyz) <= 200:
        closest = min((math.dist(a, b) for i, a in enumerate(xyz) for b in xyz[i + 1:]),
                      default=math.inf)
        if closest > 0:
            r = min(r, 0.25 * closest)
    return r


def drawn(d: list[float], magnify: float, longest: float) -> tuple[list[float], bool]:
    """The residual vector as drawn: magnified, and shortened to ``longest``
    where an excluded blunder would leave the picture (its label says so)."""
    v = [c * magnify for c in d]
    n = math.sqrt(sum(c * c for c in v))
    if n <= longest:
        return v, False
    return [c * longest / n for c in v], True


def simulated_in_world(d: dict, measured) -> tuple[dict, dict]:
    """``diff``'s simulated frame in the solution's coordinates, and its Δ.

    ``diff`` compares in the frame's parent (an ABB object frame in its user
    frame): the measured pose there is ``d["measured"]``; the rigid map that
    takes it to the solution's pose takes the simulated one along."""
    from ..geometry.frames import Pose

    def pose(p):
        return Pose.from_quat(p["x"], p["y"], p["z"], p["q"])

    basis = measured.compose(pose(d["measured"]).inverse())
    sim = frame_of(basis.compose(pose(d["simulated"])))
    sim.update(name=d.get("name"), file=d.get("file"), line=d.get("line"))
    delta = {k: d.get(k) for k in ("dx", "dy", "dz", "da", "db", "dc", "angle", "dist",
                                   "dt_mean", "group", "pass")}
    return sim, delta
