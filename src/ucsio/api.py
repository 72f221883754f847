"""The Python API: what the commands do, as plain functions.

    from ucsio import api
    cell = api.load("R01/$config.dat")                    # ControllerFile
    api.frames("R01/$config.dat")                         # [Frame, ...]
    sol = api.solve("points.csv", tcp=(-20.67, 89.73, 33.44))
    d = api.diff_frame("R01/$config.dat", "BASE_DATA[3]", sol)       # SPEC's diff keys
    changes = api.diff_files("old/$config.dat", "new/$config.dat")  # changed/added/removed
    result = api.patch("R01/$config.dat", "BASE_DATA[3]", sol)     # nothing written yet
    print(result.diff)                                    # unified diff of the patch
    api.save(result)                                      # atomic, in place (or path=OUT)

Errors are ``ucsio.UcsioError`` (what the command line reports with exit 2).
A ``solution`` argument may be a ``Pose``, a solve result (anything with a
``.pose``), or the path of a SOLUTION.json written by ``ucsio solve -o``.
"""
from __future__ import annotations

import os
from typing import Any

from .errors import UcsioError
from .geometry.frames import Frame, Pose
from .method.solution import load_solution, pose_from_json
from .parsing.controller import ControllerFile
from .parsing.controller import load as _load
from .review.diff import DEFAULT_TOLERANCE
from .review.patch import PatchResult

PathLike = str | os.PathLike


def load(path: PathLike) -> ControllerFile:
    """Parse a controller file (ABB RAPID module or KUKA KRL data list)."""
    return _load(path)


def _cell(file: PathLike | ControllerFile) -> ControllerFile:
    return file if isinstance(file, ControllerFile) else _load(file)


def frames(path: PathLike | ControllerFile) -> list[Frame]:
    """Every frame of a controller file (``ucsio frames``)."""
    return list(_cell(path).frames)


def frame(path: PathLike | ControllerFile, name: str) -> Frame:
    """One frame by name (case-insensitive; KUKA labels too); ambiguous or
    unknown names raise UcsioError."""
    from .review.names import find_frame
    return find_frame(_cell(path), name)


def solve(csv: PathLike, tcp, **options):
    """Solve a measurement file (``ucsio solve``): returns the solver's
    Solution (``.pose``, ``.accepted``, ``.points``, ``.rms``, ``.precision``,
    ``.as_dict()``). ``tcp``: the reflector in flange coordinates (x, y, z) mm,
    no default (SPEC: never a silent 0,0,0), or ``"solve"`` to estimate it
    with the frame (``ucsio.method.tcp_solve``). ``options``: threshold,
    min_points, exclude, no_exclusion, reach, sigma_laser, sigma_robot, at
    (working points: a CSV path, or ``readers.points.Points``), gate
    ("reach" or "at")."""
    from .method.measurement import read_measurement
    from .method.solve import solve as _solve
    if isinstance(options.get("at"), (str, os.PathLike)):
        from .readers.points import read_points
        options["at"] = read_points(options["at"])
    if isinstance(tcp, str) and tcp.strip().casefold() == "solve":
        from .method.tcp_solve import solve_joint   # the TCP solved with the frame
        return solve_joint(read_measurement(csv), **options)
    return _solve(read_measurement(csv), tcp, **options)


def read_solution(path: PathLike, allow_rejected: bool = False) -> Pose:
    """The frame of a SOLUTION.json (``{"frame": {x, y, z, a, b, c, q}}``) or
    of a bare ``{x, y, z, a, b, c | q}`` object. A rejected dataset's
    solution is refused unless ``allow_rejected``."""
    return load_solution(path, allow_rejected=allow_rejected)


def as_pose(solution: Any) -> Pose:
    """A Pose from a Pose, a solve result (``.pose``), a SOLUTION.json path,
    or a mapping with x, y, z and a, b, c or q."""
    if isinstance(solution, Pose):
        return solution
    if hasattr(solution, "pose") and isinstance(solution.pose, Pose):
        if getattr(solution, "accepted", True) is False:
            if getattr(solution, "diagnosis", None):
                raise UcsioError(f"this solution's dataset was rejected: {solution.reason}")
            raise UcsioError("this solution's dataset was rejected: measure again")
        return solution.pose
    if isinstance(solution, (str, os.PathLike)):
        return read_solution(solution)
    if isinstance(solution, dict):
        return pose_from_json(solution)
    raise TypeError(f"not a pose or solution: {solution!r}")


def diff_frame(file: PathLike | ControllerFile, name: str, solution: Any,
               tolerance: float = DEFAULT_TOLERANCE, oframe: bool = False,
               points: bool = False) -> dict[str, Any]:
    """SPEC's one-frame diff (``ucsio diff FILE --frame NAME --measured``):
    name, simulated, measured, dx dy dz da db dc angle dist dt_mean, group, pass.
    ``points`` (``--points``) adds ``points``, ``points_moved`` and
    ``points_warnings``: how far each position taught in the frame moves;
    with a solution that keeps its covariance (a solve result, a
    SOLUTION.json), each point's ``at_95`` and ``working_points``, ``worst``."""
    from .review.patch import resolve_name
    from .review.compare import diff_frame as _diff_frame

    cell = _cell(file)
    pose = as_pose(solution)
    d = _diff_frame(cell, name, pose, tolerance, oframe=oframe)
    if points:
        from .taught import points_moved
        data = solution
        if hasattr(solution, "as_dict"):
            data = solution.as_dict()
        elif isinstance(solution, (str, os.PathLike)):
            from .method.solution import read_json
            data = read_json(os.fspath(solution))
        d.update(points_moved(cell, cell.frame(resolve_name(name, oframe)), pose,
                              solution=data if isinstance(data, dict) else None))
    return d


def plan(plan_csv: PathLike, *, at: Any = None, candidates: Any = None, tcp: Any = None,
         threshold: float = 1.5, reach: float = 1000.0, sigma_laser: float = 0.015,
         sigma_robot: float = 0.05, min_points: int = 6) -> dict[str, Any]:
    """Plan a measurement (``ucsio plan``): the predicted 95 % error at the
    working points ``at`` (a CSV path or ``readers.points.Points``; None: the
    generic point ``reach`` from the centroid), the verdict and ``suggest``
    (add, drop) from ``candidates`` (the same; None: the box's corners), as
    the JSON of ``plan --json``. ``tcp="solve"`` plans the TCP with the
    frame from the plan's robot_* columns."""
    from .commands.plan import read_plan
    from .method.plan import plan as _plan
    from .readers.points import read_points

    class _Args:                       # read_plan's options, as the command line gives them
        robot = config = map = None
        robot_tool, robot_wobj = "tool0", "wobj0"
    args = _Args()
    args.plan = os.fspath(plan_csv)
    joint = isinstance(tcp, str) and tcp.strip().casefold() == "solve"
    planned, warnings = read_plan(args, joint)
    at = read_points(at) if isinstance(at, (str, os.PathLike)) else at
    if isinstance(candidates, (str, os.PathLike)):
        candidates = read_points(candidates, "candidate file")
    out = _plan(planned, joint=joint, at=at, candidates=candidates, threshold=threshold,
                reach=reach, sigma_laser=sigma_laser, sigma_robot=sigma_robot,
                min_points=min_points)
    out["warnings"] = warnings + out["warnings"]
    return out


def diff_files(old: PathLike | ControllerFile | None,
               new: PathLike | ControllerFile | None) -> dict[str, Any]:
    """Every frame of two files matched by name (``ucsio diff OLD NEW``):
    ``changed``, ``added``, ``removed``, ``unchanged`` (a count). ``None``
    for a file that does not exist."""
    from .review.compare import diff_files as _diff_files
    return _diff_files(None if old is None else _cell(old), None if new is None else _cell(new))


def patch(file: PathLike | ControllerFile, name: str, solution: Any, *,
          measured: bool | None = None, force: bool = False, oframe: bool = False,
          check_siblings: bool = True) -> PatchResult:
    """Plan writing ``solution`` into frame ``name`` (``ucsio patch``). Nothing
    is written: the result has ``new_bytes``, ``diff`` (unified diff text),
    ``changes`` and ``changed``; pass it to ``save``.

    ``measured`` (default: True unless ``solution`` is a Pose) makes the
    frame's reference matter: a measured frame is in robot world."""
    from .review.patch import patch_frame
    if measured is None:
        measured = not isinstance(solution, Pose)
    return patch_frame(_cell(file), name, as_pose(solution), measured=measured, force=force,
                       oframe=oframe, check_siblings=check_siblings)


def save(result: PatchResult, path: PathLike | None = None, backup: bool = False) -> str:
    """Write a planned patch atomically: over the source file (``path`` None)
    or to ``path``; ``backup`` keeps FILE.bak. Refused if the source changed
    on disk since it was read. Returns the path written."""
    from .review.patch import save as _save
    return _save(result, path, backup=backup)


def textconv(file: PathLike | ControllerFile) -> str:
    """One stable line per frame, then the file's text (``ucsio diff --textconv``)."""
    from .review.compare import textconv as _textconv
    return _textconv(_cell(file))


def demo(out: PathLike | None = None) -> dict[str, Any]:
    """The shipped example cells end to end (``ucsio demo --json``)."""
    from .demo import run_demo
    return run_demo(out=out)


__all__ = ["load", "frames", "frame", "solve", "read_solution", "as_pose", "diff_frame",
           "diff_files", "patch", "save", "textconv", "demo", "PatchResult"]
