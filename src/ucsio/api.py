"""The Python API: what each command does, as a function that returns its
``--json`` document.

    from ucsio import api
    sol = api.solve("points.csv", tool="$config.dat:SMR_reflector")
    sol.accepted, sol.rms, sol.frame.x, sol.points[0].residual   # solve --json's keys
    api.save_solution(sol, "solution.json")                      # as solve -o writes it
    d = api.diff_frame("$config.dat", "BASE_DATA[3]", sol)        # d.dt_mean, d["pass"]
    out = api.patch("$config.dat", "BASE_DATA[3]", sol)           # nothing written yet
    print(out.diff)                                               # the unified diff
    api.save(out, "patched/$config.dat")                          # atomic; in place without a path

Each function runs the command's own code (``ucsio.commands``): the same
checks, the same numbers, the same errors. Each returns a ``ucsio.results``
object: the document as a dict whose keys are attributes too, so
``json.dumps(result)`` is what ``ucsio COMMAND --json`` prints
(``schema_version`` included) and ``result.key`` is typed for mypy. Units and
frames: millimetres and degrees; poses are ``x y z`` with KUKA ``a b c``
(R = Rz(a)·Ry(b)·Rx(c)) and ABB ``q`` (q1 real); a measured frame is the UCS
in robot world. docs/python-api.md walks through it; docs/json.md and
docs/schema/ define the keys.

Bad input raises ``ucsio.UcsioError`` (what the command reports with exit 2:
``exc.as_dict()`` is the ``error`` object); a rejected dataset or a frame
over tolerance is a result (``accepted``, ``pass``), not an exception.
A ``solution`` argument may be a ``solve`` result, a ``Pose``, the path of
a SOLUTION.json, or its data as a dict.
"""
from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Sequence
from typing import Any, TypeVar, Union

from . import defaults
from .errors import UcsioError
from .geometry.frames import Frame, Pose
from .method.solution import load_solution, pose_from_json
from .output import _clean, versioned
from .parsing.controller import load as _load
from .parsing.model import ControllerFile
from .results import (BackupsDiff, BatchOutput, CheckResult, DemoResult, DiffResult, FilesDiff,
                      FramesResult, MeasurementProgramOutput, PatchOutput, PlanResult,
                      ProgramOutput, Result, SolveResult, TaughtPoints)
from .review.result import PatchResult

PathLike = Union[str, "os.PathLike[str]"]
Paths = Union[PathLike, Sequence[PathLike]]
#: A TCP: three numbers (mm, the reflector in flange coordinates), "X,Y,Z", or "solve".
TcpLike = Union[str, Sequence[float]]


R = TypeVar("R", bound=Result)


def _document(cls: type[R], doc: dict[str, Any]) -> R:
    """The command's document as ``cls``: with schema_version, NaN and inf as
    null (as emit_json prints it)."""
    return cls(_clean(versioned(doc)))


def _paths(paths: Paths) -> list[str]:
    if isinstance(paths, (str, os.PathLike)):
        return [os.fspath(paths)]
    return [os.fspath(p) for p in paths]


def _cell(file: PathLike | ControllerFile) -> ControllerFile:
    """A parsed file, or a path to parse (an ``ARCHIVE.zip!member`` too)."""
    if isinstance(file, ControllerFile):
        return file
    from .parsing.backup import load_one
    return load_one(os.fspath(file))


def load(path: PathLike) -> ControllerFile:
    """Parse a controller file (ABB RAPID module or KUKA KRL data list)."""
    return _load(path)


def frame(path: PathLike | ControllerFile, name: str) -> Frame:
    """One frame by name (case-insensitive; KUKA labels too) as a ``Frame``
    (``.pose`` in the frame's reference, mm and deg); ambiguous or unknown
    names raise UcsioError."""
    from .review.names import find_frame
    return find_frame(_cell(path), name)


def frames(paths: Paths | ControllerFile) -> FramesResult:
    """``ucsio frames --json``: every frame of controller files, backup
    folders or .zip archives (``frames``: ``name file line vendor type
    reference parent parent_kind x y z a b c q label set``; poses in each frame's own
    reference, mm and deg). One plain file that cannot be read raises; of
    many, the unreadable ones are listed in ``errors``."""
    from .commands import frames as command
    if isinstance(paths, ControllerFile):
        parsed, errors, not_read = [(None, paths)], [], []
    else:
        from .commands import load_inputs
        parsed, errors, not_read = load_inputs(_paths(paths))
    return _document(FramesResult, command.document(parsed, errors, not_read))


def check(paths: Paths, ignore: Iterable[str] = ()) -> CheckResult:
    """``ucsio check --json``: parse every byte, prove the byte-exact round
    trip, lint. ``files`` (each ``round_trip``, ``lints``), ``errors`` (files
    not read), ``ok`` (nothing that fails the check); ``.findings`` the same
    as one list, as ``--output-format json-lines`` prints it. ``ignore``:
    lint codes to silence (an unknown code raises, with the nearest one)."""
    from .commands import check as command
    codes = command.ignored_codes([ignore] if isinstance(ignore, str) else list(ignore))
    results, errors, not_read, status = command.check_files(_paths(paths), codes, "json")
    return _document(CheckResult, command.document(results, errors, not_read, status))


def solve(measurement: PathLike | None = None, tcp: TcpLike | None = None, *,
          tool: str | None = None, laser: PathLike | None = None,
          robot: PathLike | None = None, config: PathLike | list[PathLike] | None = None,
          map: PathLike | None = None, laser_units: str = "mm", robot_tool: str = "tool0",
          robot_wobj: str = "wobj0", threshold: float = defaults.THRESHOLD,
          min_points: int = defaults.MIN_POINTS, exclude: Iterable[str] = (),
          no_exclusion: bool = False, reach: float = defaults.REACH, at: Any = None,
          gate: str = "reach", uncertainty: int = 0,
          sigma_laser: float = defaults.SIGMA_LASER, sigma_robot: float = defaults.SIGMA_ROBOT,
          seed: int = 0, angle_units: str = "deg",
          quaternion_order: str = "wxyz", three_point_distance: float = 200.0,
          reach_box: str | Iterable[float] | None = None) -> SolveResult:
    """``ucsio solve --json``: the measured UCS in robot world (Horn's
    method, leave-one-out outlier exclusion, the determinacy gate).

    The measurement: ``measurement`` (the SPEC CSV; "-" is standard input),
    or where it lives: ``laser`` (CSV, SpatialAnalyzer export or a name x y z
    table, in ``laser_units``) and ``robot`` (CSV, KUKA .dat with its
    ``config`` $config.dat, ABB module with ``robot_tool``/``robot_wobj``,
    FANUC .ls or posreg.va with its ``config`` sysframe.va, Yaskawa .JBI
    with ``config`` a list: its TOOL.CND and UFRAME.CND), paired by name (``map``: a CSV of laser,robot name pairs).
    The TCP (the reflector in flange coordinates, mm; no default): ``tcp``
    as three numbers or "X,Y,Z", ``tcp="solve"`` to solve it with the frame,
    or ``tool="FILE:NAME"``. ``threshold`` (mm), ``min_points``,
    ``exclude`` (names), ``no_exclusion``, ``reach`` (mm), ``at`` (working
    points: a CSV of point, x, y, z in the UCS, mm, or
    ``readers.points.Points``), ``gate`` ("reach" or "at"), ``uncertainty``
    (Monte Carlo samples), ``sigma_laser``/``sigma_robot`` (mm per axis),
    ``seed``, ``angle_units`` ("deg" or "rad": a CSV's robot_a/b/c or
    robot_w/p/r), ``quaternion_order`` ("wxyz" or "xyzw": a CSV's
    robot_q1..q4): as the options of those names. ``three_point_distance``
    (mm) and ``reach_box`` ("XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX" or six numbers,
    robot base mm): the three points that set the frame by hand
    (``three_points``, beside ``three_point_frame``).

    A rejected dataset is a result with ``accepted`` False and ``reason``;
    one a unit or order mistake explains is a UcsioError that names it.
    ``.pose`` is the frame as a ``Pose``; ``.solution`` the solver's object."""
    from .commands import solve as command
    sol, doc, _warnings = command.solve(
        measurement, laser=laser, robot=robot, laser_units=laser_units, config=config,
        robot_tool=robot_tool, robot_wobj=robot_wobj, map=map, tcp=tcp, tool=tool,
        threshold=threshold, min_points=min_points, exclude=list(exclude),
        no_exclusion=no_exclusion, reach=reach, at=at, gate=gate, uncertainty=uncertainty,
        sigma_laser=sigma_laser, sigma_robot=sigma_robot, seed=seed, angle_units=angle_units,
        quaternion_order=quaternion_order, three_point_distance=three_point_distance,
        reach_box=reach_box)
    result = _document(SolveResult, doc)
    result.__dict__["solution"] = sol
    return result


def save_solution(result: SolveResult | dict[str, Any], path: PathLike) -> str:
    """Write a solve result as ``solve -o`` writes SOLUTION.json (atomically,
    with ``schema_version``); returns the path."""
    from .files import atomic_write_text
    from .method.solution import solution_text
    path = os.fspath(path)
    atomic_write_text(path, solution_text(dict(result)))
    return path


def read_solution(path: PathLike, allow_rejected: bool = False) -> Pose:
    """The frame of a SOLUTION.json (``{"frame": {x, y, z, a, b, c, q}}``) or
    of a bare ``{x, y, z, a, b, c | q}`` object. A rejected dataset's
    solution is refused unless ``allow_rejected``; so is one written with a
    newer ``schema_version``."""
    return load_solution(path, allow_rejected=allow_rejected)


def as_pose(solution: Any) -> Pose:
    """A Pose from a Pose, a solve result (``.pose``), a SOLUTION.json path,
    or a mapping with x, y, z and a, b, c or q. A rejected dataset raises."""
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


def _measured(solution: Any, allow_rejected: bool = False) -> tuple[Pose, dict[str, Any] | None,
                                                                     str | None]:
    """(pose, the solution's JSON data or None, its path or None), read as
    the commands read a SOLUTION.json: the same refusals (a rejected
    dataset unless ``allow_rejected``, a newer schema_version)."""
    if isinstance(solution, Pose):
        return solution, None, None
    if isinstance(solution, (str, os.PathLike)):
        from .method.solution import read_json
        path = os.fspath(solution)
        data = read_json(path)
        return pose_from_json(data, path, allow_rejected), data, path
    data = solution if isinstance(solution, dict) else None
    if data is None and hasattr(solution, "as_dict"):       # the solver's own Solution
        data = solution.as_dict()
    if not isinstance(data, dict):
        raise TypeError(f"not a pose or solution: {solution!r}")
    return pose_from_json(data, None, allow_rejected), data, None


def diff_frame(file: PathLike | ControllerFile, name: str, solution: Any,
               tolerance: float | None = None, oframe: bool = False,
               points: bool = False) -> DiffResult:
    """``ucsio diff FILE --frame NAME --measured SOLUTION.json --json``: Δ =
    measured − simulated in the frame's reference (``dx dy dz`` mm, ``da db
    dc`` and ``angle`` deg, ``dist``, ``dt_mean`` mm, ``group``, ``pass``
    against ``tolerance``, default 100 mm). ``oframe``: an ABB wobj's object
    frame. ``points`` (``--points``): also ``taught_points``' keys."""
    from .commands import diff as command
    pose, data, _path = _measured(solution)
    doc = command.one_frame(_cell(file), name, pose, data, tolerance=tolerance, oframe=oframe,
                            points=points)
    return _document(DiffResult, doc)


def taught_points(file: PathLike | ControllerFile, frame: str, solution: Any,
                  oframe: bool = False) -> TaughtPoints:
    """What ``diff --points`` adds: the positions taught in ``frame`` (KUKA
    E6POS/POS with its BASE_NO in the controller's tree, ABB robtargets
    moved to with ``\\WObj``, FANUC /POS positions with ``UF : k`` in the
    backup's .ls programs), each with ``moved`` (mm, in world, when the
    measured frame replaces the simulated one), worst first;
    ``points_moved`` (``count max mean worst``); ``points_warnings``;
    ``points_skipped`` (FANUC joint positions, Yaskawa pulses and base
    positions: they do not move); with a solution that keeps its
    covariance (a solve result, a SOLUTION.json) each point's ``at_95`` (mm) and ``working_points``/``worst``."""
    from .commands import diff as command
    pose, data, _path = _measured(solution)
    doc = command.taught_points(_cell(file), frame, pose, data, oframe=oframe)
    return _document(TaughtPoints, doc)


def diff_files(old: PathLike | ControllerFile | None,
               new: PathLike | ControllerFile | None) -> FilesDiff:
    """``ucsio diff OLD NEW --json`` for two files: every frame matched by
    name, ``changed`` (with ``changes``, ``old``, ``new`` and the Δ new −
    old), ``added``, ``removed``, ``unchanged`` (a count). ``None`` for a
    file that does not exist."""
    from .review.compare import diff_files as _diff_files
    doc = _diff_files(None if old is None else _cell(old), None if new is None else _cell(new))
    return _document(FilesDiff, doc)


def diff_backups(old: PathLike, new: PathLike) -> BackupsDiff:
    """``ucsio diff OLD NEW --json`` for two backups (folders or .zip
    archives): files paired by path, ``files_added``, ``files_removed``,
    ``files_changed``, ``files_unchanged``; the frames ``changed``,
    ``added``, ``removed`` in files present in both (each with its
    ``path``); files that changed but could not be read in ``errors``."""
    from .commands import diff as command
    from .review.backup_diff import as_json
    return _document(BackupsDiff, as_json(command.backups(old, new)))


def patch(file: PathLike | ControllerFile, name: str, solution: Any, *,
          measured: bool | None = None, force: bool = False, oframe: bool = False,
          check_siblings: bool = True) -> PatchOutput:
    """``ucsio patch --json``: plan writing ``solution`` into frame ``name``
    in the vendor's native form, only that frame's numbers changing. Nothing
    is written: ``out.diff`` is the unified diff, ``out.patch`` the
    document's ``patch``; ``save(out)`` writes it.

    ``measured`` (default: True unless ``solution`` is a Pose) says the
    values are a measured frame in robot world (then written relative to
    the frame's reference); a Pose with ``measured=False`` is written as
    given. For a robot-held tool, a solution whose TCP was solved writes
    that TCP's x, y, z. ``force``: as ``--force``."""
    from .commands import patch as command
    if measured is None:
        measured = not isinstance(solution, Pose)
    pose, data, path = _measured(solution, allow_rejected=force)
    if isinstance(file, ControllerFile):
        cf = file
    else:
        from .parsing.backup import refuse_member
        refuse_member(os.fspath(file))
        cf = _load(file)
    planned = command.plan_patch(cf, name, pose, measured=measured,
                                 solution=data if measured else None, path=path, force=force,
                                 oframe=oframe, check_siblings=check_siblings)
    out = _document(PatchOutput, command.document(planned))
    out.__dict__["planned"] = planned
    return out


def save(result: PatchOutput | PatchResult, path: PathLike | None = None,
         backup: bool = False) -> str:
    """Write a planned patch atomically: over the source file (``path`` None)
    or to ``path``; ``backup`` keeps FILE.bak (never overwriting one).
    Refused if the source changed on disk since it was read. Returns the
    path written; a ``patch`` result's ``written``/``backup`` keys say it."""
    from .review.save import save as _save
    planned = result.planned if isinstance(result, PatchOutput) else result
    written = _save(planned, path, backup=backup)
    if isinstance(result, PatchOutput):
        result.patch["written"], result.patch["backup"] = planned.written, planned.backup
    return written


def program(solution: Any, frame: str, *, group: int | None = None, pr: int | None = None,
            posreg: PathLike | None = None, comment: str | None = None,
            wpr: str | Sequence[float] | None = None, p: int | None = None,
            var: PathLike | None = None, vendor: str | None = None,
            output: PathLike | None = None) -> ProgramOutput:
    """``ucsio program --json``: a program that sets ``frame`` to a measured
    ``solution`` (a solve result, a SOLUTION.json's path, or its data): a
    FANUC TP program (``UF3``, ``UT2``, ``UF3@2``; ``UTk``: its solved TCP,
    with the tool's ``wpr``, default 0, 0, 0; ``pr``: the position register,
    else the highest one ``posreg`` (a posreg.va) shows unused; ``comment``:
    ``UFRAME[k:comment]``) or a Yaskawa job (``UFk``; ``p``: its first P
    variable, else three that ``var`` (a VAR.DAT) and the jobs beside it do
    not use). ``vendor`` names whose, else ``output``'s suffix (.LS, .JBI),
    else FANUC. The program is read back before it is returned (``out.text``,
    CRLF); with ``output`` it is also written there (atomically; its file
    name is the program's name)."""
    from .commands import program as command
    if isinstance(solution, (str, os.PathLike)):
        data: Any = os.fspath(solution)
    elif isinstance(solution, dict):
        data = solution
    elif hasattr(solution, "as_dict"):
        data = solution.as_dict()
    else:
        raise TypeError(f"not a solution: {solution!r}")
    angles = None if wpr is None else wpr if isinstance(wpr, str) else tuple(wpr)
    made = command.make(data, frame, group=group, pr=pr,
                        posreg=None if posreg is None else os.fspath(posreg), comment=comment,
                        wpr=angles, p=p, var=None if var is None else os.fspath(var),
                        vendor=vendor, output=None if output is None else os.fspath(output))
    if output is not None:
        command.save(made, os.fspath(output))
    return _document(ProgramOutput, command.document(made))


def measurement_program(plan: PathLike, controller: PathLike, frame: str, *,
                        tool: str | None = None, tcp: TcpLike | None = None,
                        approach: float = 100.0, approach_dir: Sequence[float] | None = None,
                        orientation: Sequence[float] | None = None,
                        spread: float | None = None, speed: float = 100.0,
                        dwell: float | None = None,
                        output: PathLike | None = None) -> MeasurementProgramOutput:
    """``ucsio program --measure --json``: the measurement program that moves
    the reflector (``tool``, a tool of ``controller`` or "FILE:NAME"; or
    ``tcp`` on the flange) to each point of ``plan`` in ``controller``'s
    ``frame``, in the controller's language (ABB .mod, FANUC .LS, KUKA .src
    and .dat, Yaskawa .JBI), read back before it is returned; with ``output``
    also written there (KUKA: its .dat beside it), which must not exist.
    ``spread`` (deg) turns the tool point by point for a TCP solved with the
    frame (``plan(tcp="solve")`` says how much)."""
    from .programs import measure
    made = measure.make(os.fspath(plan), os.fspath(controller), frame, tool=tool, tcp=tcp,
                        approach=approach, approach_dir=approach_dir, orientation=orientation,
                        spread=spread, speed=speed, dwell=dwell,
                        output=None if output is None else os.fspath(output))
    if output is not None:
        measure.save(made, os.fspath(output))
    return _document(MeasurementProgramOutput, {"measurement_program": made.as_dict()})


def batch(manifest: PathLike, *, uncertainty: int = 0,
          sigma_laser: float = defaults.SIGMA_LASER, sigma_robot: float = defaults.SIGMA_ROBOT,
          seed: int = 0, patch_dir: PathLike | None = None, csv: PathLike | None = None,
          report: PathLike | None = None,
          progress: Callable[[str, int, int], None] | None = None) -> BatchOutput:
    """``ucsio batch MANIFEST.toml --json``: every entry solved and diffed
    (``entries``: ``name status accepted e dt_mean group pass frame``,
    ``error`` where it failed; mm and deg, frames in robot world) and the
    ``summary`` (``total passed rejected errors success_rate groups``).
    ``patch_dir``, ``csv``, ``report`` write what the options of those names
    write; ``progress(stage, done, total)`` is called as entries go.
    ``.result`` is ``fleet.batch.BatchResult``."""
    from .commands import batch as command
    result = command.batch(manifest, uncertainty=uncertainty, sigma_laser=sigma_laser,
                           sigma_robot=sigma_robot, seed=seed, patch_dir=patch_dir, csv=csv,
                           report=report, progress=progress)
    out = _document(BatchOutput, result.as_dict())
    out.__dict__["result"] = result
    return out


def plan(plan: PathLike, *, at: Any = None, at_taught: PathLike | None = None,
         frame: str | None = None, candidates: Any = None, tcp: TcpLike | None = None,
         tool: str | None = None, robot: PathLike | None = None,
         config: PathLike | None = None, map: PathLike | None = None,
         robot_tool: str = "tool0", robot_wobj: str = "wobj0",
         threshold: float = defaults.THRESHOLD, reach: float = defaults.REACH,
         sigma_laser: float | None = None, sigma_robot: float | None = None,
         history: PathLike | None = None, min_points: int = defaults.MIN_POINTS,
         margin: float = defaults.MARGIN, laser_units: str = "mm",
         spread: float | None = None) -> PlanResult:
    """``ucsio plan --json``: from the planned points alone (``plan``: point,
    laser_x/y/z in the UCS, mm; robot_* or ``robot`` for the planned flange
    poses), the fitted frame's predicted 95 % error (mm) at the working
    points ``at`` (a CSV of point, x, y, z in the UCS, or
    ``readers.points.Points``; or ``at_taught`` CONTROLLER with ``frame``;
    none: the generic point ``reach`` mm from the centroid), the ``worst``,
    the ``verdict`` against ``threshold`` and ``suggest`` (add from
    ``candidates``, else locations within ``margin`` mm of a planned point;
    drop). ``tcp="solve"`` plans the TCP with the frame (with no flange
    poses planned: at the ``spread`` of ``measurement_program``, default
    the least that holds the threshold). The noise: the
    stated ``sigma_laser``/``sigma_robot``, the fleet's own from ``history``
    (a batch --json result or a folder of solutions), else an uncalibrated
    robot's (``defaults.PLAN_SIGMA_ROBOT``)."""
    from .commands import plan as command
    doc = command.plan_measurement(
        plan, robot=robot, config=config, map=map, robot_tool=robot_tool,
        robot_wobj=robot_wobj, tcp=tcp, tool=tool, at=at, at_taught=at_taught, frame=frame,
        candidates=candidates, threshold=threshold, reach=reach, min_points=min_points,
        sigma_laser=sigma_laser, sigma_robot=sigma_robot, history=history, margin=margin,
        laser_units=laser_units, spread=spread)
    return _document(PlanResult, doc)


def view(solution: PathLike, *, controller: PathLike | None = None, frame: str | None = None,
         at: PathLike | None = None, plan: PathLike | None = None,
         output: PathLike | None = None) -> dict[str, Any]:
    """``ucsio view``: the picture of a SOLUTION.json as its scene (the numbers
    the page draws: ``points``, ``measured``, ``simulated`` with ``delta``
    where ``controller`` and ``frame`` name the simulated frame, ``working``
    from ``at``, ``plan`` from a ``plan --json`` file, ``magnify``); with
    ``output``, the self-contained HTML page written there (atomically)."""
    from .commands import view as command
    scene, html = command.view(os.fspath(solution),
                               controller=None if controller is None else os.fspath(controller),
                               frame=frame, at=None if at is None else os.fspath(at),
                               plan=None if plan is None else os.fspath(plan))
    if output is not None:
        from .files import atomic_write_text
        atomic_write_text(output, html)
    return scene


def textconv(file: PathLike | ControllerFile) -> str:
    """One stable line per frame, then the file's text (``ucsio diff --textconv``)."""
    from .review.compare import textconv as _textconv
    return _textconv(_cell(file))


def demo(out: PathLike | None = None, tolerance: float | None = None) -> DemoResult:
    """``ucsio demo --json``: the shipped example cells end to end (solve,
    diff, patch preview); ``out`` writes each cell's inputs, solution.json,
    patched copy and replay.sh there."""
    from .demo import run_demo
    return _document(DemoResult, run_demo(out=out, tolerance=tolerance))


__all__ = ["load", "frame", "frames", "check", "solve", "save_solution", "read_solution",
           "as_pose", "diff_frame", "taught_points", "diff_files", "diff_backups", "patch",
           "program", "measurement_program",
           "save", "batch", "plan", "view", "textconv", "demo", "PatchResult"]
