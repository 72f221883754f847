"""The picture's inputs read from files: a SOLUTION.json, the simulated frame
of a controller file (as ``diff --measured`` compares it), working points, a
plan's JSON. Every error names its file."""
from __future__ import annotations

import math

from ..errors import UcsioError


def read_scene(solution: str, *, controller: str | None = None, frame: str | None = None,
               at: str | None = None, plan: str | None = None) -> dict:
    from ..method.solution import pose_from_json, read_json
    from .scene import scene

    data = read_json(solution)
    if not isinstance(data, dict) or "frame" not in data or "points" not in data:
        raise UcsioError("not a SOLUTION.json: expected the object `ucsio solve -o` writes "
                         "(with 'frame' and 'points')", file=solution)
    pose = pose_from_json(data, solution, allow_rejected=True)
    simulated = None
    if controller is not None:
        from ..parsing.backup import load_one
        from ..review.compare import diff_frame
        simulated = diff_frame(load_one(controller), frame, pose)
    working = worst = None
    if at is not None:
        working, worst = _working(data, pose, at)
    plan_data = None
    if plan is not None:
        plan_data = read_json(plan)
        if not isinstance(plan_data, dict) or "planned_points" not in plan_data:
            raise UcsioError("not a plan: expected `ucsio plan --json`'s document (with "
                             "'planned_points')", file=plan)
    return scene(data, simulated=simulated, working=working, worst=worst, plan=plan_data,
                 source=solution, path=solution)


def _working(data: dict, pose, at: str):
    """Working points from ``--at``, each with its predicted 95 % error from
    the solution's covariance (plain math: no numpy for a picture)."""
    from ..method.working import describe, from_solution, predict_plain
    from ..readers.points import read_points

    pts = read_points(at)
    cov = from_solution(data)
    xyz = [list(p) for p in pts.xyz]
    q = predict_plain(cov, pose.matrix, xyz) if cov is not None else [math.inf] * len(xyz)
    return describe(list(pts.names), xyz, q)
