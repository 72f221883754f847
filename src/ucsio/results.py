"""What ``ucsio.api`` returns: each command's ``--json`` document as an object.

A result *is* the document: a ``dict`` whose keys are the ``--json`` keys
(``json.dumps(result)`` prints what ``ucsio COMMAND --json`` prints, with
``schema_version``), and whose keys are attributes too (``sol.rms`` is
``sol["rms"]``). Nested objects are results as well (``sol.frame.x``,
``sol.points[0].residual``). The classes below declare the keys scripts rely
on, with their types, for mypy and editors; a declared key that a document
leaves out reads as None, an undeclared one is still there by ``[key]`` and
by attribute (SPEC: more keys are welcome). The keys are described in
docs/json.md and fixed by the JSON Schemas in docs/schema/.

Units and frames, everywhere: millimetres and degrees; a pose of frame F in
parent P is ``x y z`` (mm) and a rotation R with p_P = R·p_F + t, given as
KUKA ``a b c`` (R = Rz(a)·Ry(b)·Rx(c), deg), ABB ``q`` ([q1, q2, q3, q4],
q1 the real part) and, for a measured frame, FANUC ``w p r`` (the same matrix,
w = c, p = b, r = a). A measured user frame is the UCS in robot world.

``pass`` is a Python keyword: read it as ``d["pass"]`` or ``d.passed``.
"""
from __future__ import annotations

import typing
from typing import Any, Mapping

from .geometry.frames import Pose


class Result(dict[str, Any]):
    """A JSON object with its keys as attributes (see the module's doc)."""

    def __init__(self, data: Mapping[str, Any] | None = None) -> None:
        super().__init__()
        hints = _fields(type(self))
        for key, value in (data or {}).items():
            self[key] = _wrap(value, hints.get(key))

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        try:
            return self[name]
        except KeyError:
            if name in _fields(type(self)):
                return None             # a declared key this document leaves out
            raise AttributeError(f"{type(self).__name__} has no key {name!r}") from None

    def __dir__(self) -> list[str]:
        return sorted(set(super().__dir__()) | {k for k in self if k.isidentifier()})

    def __repr__(self) -> str:
        return f"{type(self).__name__}({dict.__repr__(self)})"

    def as_dict(self) -> dict[str, Any]:
        """The document as plain dicts and lists."""
        return _plain(self)  # type: ignore[no-any-return]


def _plain(v: Any) -> Any:
    if isinstance(v, dict):
        return {k: _plain(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_plain(x) for x in v]
    return v


_FIELDS: dict[type, dict[str, type[Result] | None]] = {}


def _fields(cls: type) -> dict[str, type[Result] | None]:
    """Each declared key of ``cls`` -> the Result class its objects become."""
    got = _FIELDS.get(cls)
    if got is None:
        hints = typing.get_type_hints(cls) if cls is not Result else {}
        got = {k: _result_class(h) for k, h in hints.items()
               if typing.get_origin(h) is not typing.ClassVar}
        _FIELDS[cls] = got
    return got


def _result_class(hint: Any) -> type[Result] | None:
    if isinstance(hint, type) and issubclass(hint, Result):
        return hint
    for arg in typing.get_args(hint):
        found = _result_class(arg)
        if found is not None:
            return found
    return None


def _wrap(value: Any, cls: type[Result] | None) -> Any:
    if isinstance(value, dict):
        return (cls or Result)(value)
    if isinstance(value, list):
        return [_wrap(v, cls) for v in value]
    return value


class _Passes(Result):
    @property
    def passed(self) -> bool:
        """The ``pass`` key: dt_mean below the tolerance."""
        return bool(self["pass"])


# ------------------------------------------------------------------ shared pieces

class PoseValues(Result):
    """A pose: ``x y z`` (mm), ``a b c`` (deg, KUKA: R = Rz(a)·Ry(b)·Rx(c)),
    ``q`` (ABB quaternion, q1 real)."""
    x: float
    y: float
    z: float
    a: float
    b: float
    c: float
    q: list[float]


class ErrorInfo(Result):
    """A file that could not be read: where (``line``, ``col`` 1-based, None
    where the error has no place) and why."""
    file: str | None
    line: int | None
    col: int | None
    message: str
    code: str | None        # check: syntax-error or unreadable


class XYZ(Result):
    """Three components, mm (or deg where the key says angle)."""
    x: float
    y: float
    z: float


class WorkingPoint(Result):
    """A working point: ``x y z`` in the UCS (mm) and ``at_95``, the measured
    frame's predicted 95 % error there (mm, in robot world). A taught point
    also has ``file``, ``line`` and ``moved``."""
    name: str
    x: float
    y: float
    z: float
    at_95: float | None
    file: str | None
    line: int | None
    moved: float | None


class Worst(Result):
    """The working point predicted worst: ``name``, ``at_95`` (mm)."""
    name: str
    at_95: float | None
    file: str | None
    line: int | None


# ------------------------------------------------------------------ frames

class NotRead(Result):
    """A file listed but not read (a FANUC backup's binary .tp .sv .vr and
    its .DAT files, another controller's files)."""
    file: str
    reason: str


class FrameItem(Result):
    """One frame of a controller file: where (``file``, ``line``), what
    (``vendor`` abb, kuka or fanuc, ``type`` wobjdata, tooldata, BASE_DATA,
    UFRAME, ..., ``reference`` the frame it is relative to: world, flange, a
    uframe; ``parent`` the same as a node of the frame tree: 'world',
    'robot', 'flange', 'robot@2', another frame's name, a unit's name, or
    'unknown', ``parent_kind`` which of those), its pose (``x y z`` mm,
    ``a b c`` deg, ``q``; None where the
    file gives no literal value), ``label`` where the file names it, ``set``
    (False for an unset KUKA or FANUC entry); FANUC's ``group`` and ``w p r``
    (deg; w = c, p = b, r = a)."""
    name: str
    file: str
    line: int
    vendor: str
    type: str
    reference: str | None
    parent: str
    parent_kind: str
    x: float | None
    y: float | None
    z: float | None
    a: float | None
    b: float | None
    c: float | None
    q: list[float] | None
    label: str | None
    set: bool
    group: int | None
    w: float | None
    p: float | None
    r: float | None


class FramesResult(Result):
    """``ucsio frames --json``: every frame of the files read, the files read,
    the files that could not be read, and those listed as not read."""
    schema_version: int
    frames: list[FrameItem]
    files: list[str]
    errors: list[ErrorInfo]
    not_read: list[NotRead]


# ------------------------------------------------------------------ check

class Lint(Result):
    """A lint: where (1-based ``line``, ``col`` in characters), ``code``,
    ``severity`` (warning or info) and ``message``."""
    line: int | None
    col: int | None
    code: str
    severity: str
    message: str


class CheckedFile(Result):
    """One file checked: ``vendor``, ``encoding``, the number of ``frames``,
    whether the byte-exact ``round_trip`` holds, and its ``lints``."""
    file: str
    vendor: str
    kind: str | None            # FANUC: program, frame comments, ...
    encoding: str
    frames: int
    round_trip: bool
    lints: list[Lint]


class Finding(Result):
    """One finding, as ``check --output-format json-lines`` prints it: a lint,
    a failed round trip or a file not read (codes round-trip, syntax-error,
    unreadable); ``line``/``col`` None for the whole file; ``fingerprint``
    stays when lines move."""
    file: str
    line: int | None
    col: int | None
    code: str
    severity: str
    message: str
    fingerprint: str


class CheckResult(Result):
    """``ucsio check --json``: each file read and the files not read; ``ok``
    when nothing fails the check (exit 0). ``findings`` (not a key) is the
    same as one list, as ``--output-format json-lines`` prints it."""
    schema_version: int
    files: list[CheckedFile]
    errors: list[ErrorInfo]
    not_read: list[NotRead]
    ok: bool

    @property
    def findings(self) -> list[Finding]:
        from types import SimpleNamespace

        from .findings import collect, json_lines
        errors = [SimpleNamespace(**e) for e in self.errors]
        return [Finding(f) for f in json_lines(collect(self.files, errors))]


# ------------------------------------------------------------------ solve

class SolvedFrame(PoseValues):
    """The measured frame (the UCS in robot world): SPEC's ``x y z a b c q``,
    FANUC ``w p r`` (deg) and the 4x4 ``matrix`` (mm)."""
    w: float
    p: float
    r: float
    matrix: list[list[float]]


class SolvePoint(Result):
    """A measured point: ``residual`` (its distance to the fitted frame, mm),
    ``loo_residual`` (to the frame fitted from the other used points; None
    where undetermined), ``used``, ``excluded_by`` (auto, hand or None),
    ``dx dy dz`` (robot − fitted, robot world, mm), its ``weight`` and ``line``."""
    name: str
    residual: float
    loo_residual: float | None
    used: bool
    excluded_by: str | None
    dx: float
    dy: float
    dz: float
    weight: float
    line: int | None


class Tcp(Result):
    """The TCP (the reflector in flange coordinates, mm): ``solved`` True with
    ``--tcp solve``, then ``std`` (mm per axis) and ``at_95`` (mm)."""
    x: float
    y: float
    z: float
    solved: bool
    std: XYZ | None
    at_95: float | None


class Precision(Result):
    """The determinacy gate: ``sigma`` (noise per axis, mm), ``angle_std``
    (deg), ``reach`` and ``at_reach`` (mm: the 95 % displacement of a point
    ``reach`` mm from the centroid), ``sigma_source`` (stated or residuals)."""
    sigma: float
    angle_std: float
    reach: float
    at_reach: float
    sigma_source: str | None


class Spread(Result):
    """Per axis of the frame's origin in robot world (``x y z``, mm) and of
    its orientation (``angle``, deg)."""
    x: float | None
    y: float | None
    z: float | None
    angle: float | None


class Uncertainty(Result):
    """``--uncertainty N``: ``samples``; ``std`` and ``ci95`` (``x y z`` mm of
    the frame's origin in robot world, ``angle`` deg; ``ci95`` as [low,
    high]) from N Monte Carlo copies of the measurement."""
    samples: int
    std: Spread
    ci95: dict[str, list[float]]


class Consistency(Result):
    """The noise check: ``ratio`` (residual σ / stated σ), ``p`` of the χ²
    test with ``dof`` degrees of freedom."""
    ratio: float | None
    p: float | None
    dof: int


class Solve(Result):
    """``ucsio solve --json`` (and SOLUTION.json): the measured ``frame``,
    each point, the counts, ``rms mean max`` of the used residuals (mm),
    ``accepted`` and why not (``reason``), the gate's ``precision``, the
    ``tcp``, and where asked ``uncertainty``, ``working_points``/``worst``
    (``--at``), ``consistency``, ``covariance`` (6x6 per unit noise, mm² and
    rad², about ``covariance.about`` in the UCS, robot world axes)."""
    frame: SolvedFrame
    points: list[SolvePoint]
    n_points: int
    n_used: int
    rms: float
    mean: float
    max: float
    accepted: bool
    reason: str | None
    warnings: list[str]
    precision: Precision | None
    tcp: Tcp
    settings: dict[str, Any]
    uncertainty: Uncertainty | None
    diagnosis: dict[str, Any] | None
    consistency: Consistency | None
    tcp_at_95: float | None
    orientation_span: float | None
    working_points: list[WorkingPoint] | None
    worst: Worst | None
    gate: str | None
    at: str | None
    covariance: dict[str, Any] | None

    @property
    def pose(self) -> Pose:
        """The measured frame as a ``ucsio.Pose`` (robot world)."""
        sol = self.__dict__.get("solution")
        if sol is not None:
            return sol.pose  # type: ignore[no-any-return]
        from .method.solution import pose_from_json
        return pose_from_json(self, allow_rejected=True)


class SolveResult(Solve):
    """``ucsio solve --json``. ``solution`` (not a key): the solver's own
    object, where the result was just solved."""
    schema_version: int


# ------------------------------------------------------------------ diff

class PointsMoved(Result):
    """How far the taught points move in world (mm): ``count``, ``max``,
    ``mean``, ``worst`` (the name of the one that moves most)."""
    count: int
    max: float | None
    mean: float | None
    worst: str | None


class TaughtPoint(Result):
    """A position taught in the frame: where it is written and ``moved``, how
    far it moves in world (mm) when the measured frame replaces the
    simulated one; ``at_95`` the measured frame's predicted 95 % error there
    (mm) where the solution keeps its covariance."""
    name: str
    file: str
    line: int
    moved: float
    at_95: float | None


class TaughtPoints(Result):
    """``diff --points``' keys (``api.taught_points``): ``points`` (worst
    first), ``points_moved``, ``points_warnings``, ``points_skipped`` (the
    positions taught in the frame that do not move with it: FANUC joint
    positions); with the solution's covariance ``working_points`` and
    ``worst``."""
    schema_version: int
    points: list[TaughtPoint]
    points_moved: PointsMoved
    points_warnings: list[str]
    points_skipped: int
    working_points: list[WorkingPoint] | None
    worst: Worst | None
    tcp_at_95: float | None
    orientation_span: float | None


class Delta(_Passes):
    """Δ = measured − simulated: ``dx dy dz`` (mm), ``da db dc`` (deg, each
    wrapped to (−180, 180]), ``angle`` (deg, the one rotation between the
    two), ``dist`` (mm), ``dt_mean`` = (|dx| + |dy| + |dz|) / 3 (mm),
    ``group`` (1–5 by dt_mean), ``pass``."""
    dx: float
    dy: float
    dz: float
    da: float
    db: float
    dc: float
    angle: float
    dist: float
    dt_mean: float
    group: int


class FrameDiff(Delta):
    """Δ = measured − simulated for one frame, in the frame's reference
    (``Delta``'s keys), the two poses, and ``pass`` (dt_mean below
    ``tolerance``)."""
    name: str
    simulated: PoseValues
    measured: PoseValues
    tolerance: float | None


class Diff(FrameDiff):
    """One frame against a measurement: the frame (``file``, ``line``,
    ``vendor``, ``type``, ``reference``, ``label``), its Δ, ``set``, a
    ``warning``; with ``--points`` the taught points' keys (``TaughtPoints``)."""
    file: str
    line: int
    vendor: str
    type: str
    reference: str | None
    label: str | None
    set: bool
    warning: str | None
    points: list[TaughtPoint] | None
    points_moved: PointsMoved | None
    points_warnings: list[str] | None
    points_skipped: int | None
    working_points: list[WorkingPoint] | None
    worst: Worst | None


class DiffResult(Diff):
    """``ucsio diff FILE --frame NAME --measured SOLUTION.json --json``."""
    schema_version: int


class FrameChange(FrameDiff):
    """A frame in both files whose value, label or other data changed:
    ``changes`` says what; ``old``/``new`` the two frames; where both have a
    value, the Δ new − old (``simulated`` = old, ``measured`` = new)."""
    vendor: str
    type: str
    changes: list[str]
    old: FrameItem
    new: FrameItem
    path: str | None


class FilesDiff(Result):
    """``ucsio diff OLD NEW --json`` (two files): frames ``changed``,
    ``added``, ``removed`` (matched by name), and how many are
    ``unchanged``."""
    schema_version: int
    old: str | None
    new: str | None
    changed: list[FrameChange]
    added: list[FrameItem]
    removed: list[FrameItem]
    unchanged: int


class FileListed(Result):
    """A file added or removed: its ``path`` inside the backup, the ``file``
    as named, its ``frames`` (names)."""
    path: str
    file: str
    frames: list[str]
    not_read: str | None        # why a binary file is not read


class FileChanged(Result):
    """A file in both backups whose bytes differ: counts of its frames
    changed, added, removed (None where it could not be read, then
    ``error``), and whether ``other_lines`` changed."""
    path: str
    old_file: str
    file: str
    frames_changed: int | None
    frames_added: int | None
    frames_removed: int | None
    other_lines: bool | None
    error: str | None
    not_read: str | None


class BackupsDiff(Result):
    """``ucsio diff OLD NEW --json`` (two backups): files added, removed,
    changed (paired by path), and every frame changed, added, removed in
    the files present in both (each with its ``path``); files not read in
    ``errors``."""
    schema_version: int
    old: str
    new: str
    files_added: list[FileListed]
    files_removed: list[FileListed]
    files_changed: list[FileChanged]
    files_unchanged: int
    changed: list[FrameChange]
    added: list[FrameItem]
    removed: list[FrameItem]
    errors: list[ErrorInfo]


# ------------------------------------------------------------------ patch

class Change(Result):
    """One number replaced: its ``component`` (x, y, z, a, b, c, q1..q4), the
    ``old`` and ``new`` text as written, and their values."""
    component: str
    old: str
    new: str
    old_value: float
    new_value: float


class PatchInfo(Result):
    """The patch of one frame: ``old`` and ``new`` pose in the frame's own
    reference, whether the file ``changed``, each ``changes``, the unified
    ``diff``, ``warnings``, and where it was ``written`` (None until saved)."""
    file: str
    frame: str
    type: str
    vendor: str
    line: int
    reference: str | None
    old: PoseValues | None
    new: PoseValues
    changed: bool
    changes: list[Change]
    diff: str
    warnings: list[str]
    written: str | None
    backup: str | None


class PatchOutput(Result):
    """``ucsio patch --json``: ``patch``. Not keys: ``diff``, ``new_bytes``,
    ``changed``, ``warnings`` of the planned patch, and ``planned`` itself
    (``review.result.PatchResult``), which ``api.save`` writes."""
    schema_version: int
    patch: PatchInfo

    @property
    def planned(self) -> Any:
        return self.__dict__["planned"]

    @property
    def diff(self) -> str:
        return self.patch.diff

    @property
    def new_bytes(self) -> bytes:
        return self.planned.new_bytes  # type: ignore[no-any-return]

    @property
    def changed(self) -> bool:
        return self.patch.changed

    @property
    def warnings(self) -> list[str]:
        return self.patch.warnings


class ProgramValues(Result):
    """The frame as the program sets it: ``x y z`` (mm), FANUC ``w p r`` or
    Yaskawa ``rx ry rz`` (deg)."""
    x: float
    y: float
    z: float
    w: float
    p: float
    r: float
    rx: float
    ry: float
    rz: float


class ProgramInfo(Result):
    """A program that sets a frame: its ``text`` (CRLF), ``name``
    (/PROG, //NAME), the ``frame`` (UF3, UT2, UF3@2) with its ``type`` (UFRAME,
    UTOOL), ``number`` and ``group``; FANUC: the register ``pr`` and ``pr_from``
    ("--pr" or the posreg.va it was found unused in), the ``comment``;
    Yaskawa: the P variables ``p`` and ``p_from`` ("--p" or the VAR.DAT); the
    ``pose`` it reads back as (``x y z w p r``), ``warnings``, and the ``file`` written
    (None on standard output)."""
    file: str | None
    name: str
    frame: str
    type: str
    number: int
    group: int
    pr: int
    pr_from: str
    p: list[int]
    p_from: str
    comment: str | None
    pose: ProgramValues
    warnings: list[str]
    text: str


class ProgramOutput(Result):
    """``ucsio program --json``: ``program``; ``text`` is the program."""
    schema_version: int
    program: ProgramInfo

    @property
    def text(self) -> str:
        return self.program.text


class MeasurementProgramFile(Result):
    """One file of a measurement program: the ``file`` written (None: not
    written) and its ``text``."""
    file: str | None
    text: str


class MeasurementProgramInfo(Result):
    """A measurement program: its ``text`` (CRLF), ``name``, ``vendor``, the
    ``frame`` and ``tool`` it moves in, the plan's ``points`` in the
    program's order and the ``positions`` that reach them (FANUC ``P[1]``,
    Yaskawa ``C00000``, KUKA ``XP1``), ``warnings``, the ``file`` written
    (None on standard output), and ``files``: every file, the main one
    first (KUKA's .src, then its .dat)."""
    file: str | None
    name: str
    vendor: str
    frame: str
    tool: str
    points: list[str]
    positions: list[str]
    warnings: list[str]
    text: str
    files: list[MeasurementProgramFile]


class MeasurementProgramOutput(Result):
    """``ucsio program --measure --json``: ``measurement_program``."""
    schema_version: int
    measurement_program: MeasurementProgramInfo

    @property
    def text(self) -> str:
        return self.measurement_program.text


# ------------------------------------------------------------------ batch

class BatchDelta(Delta):
    """An entry's Δ measured − simulated (mm, deg), as ``diff``'s."""


class BatchEntry(_Passes):
    """One manifest entry: ``status`` (pass, over_tolerance, rejected,
    error), ``accepted``, ``e`` (the mean residual of its used points, mm),
    ``dt_mean`` (mm), ``group``, ``pass``, the measured ``frame`` (robot
    world) and, where it failed, ``error`` and the ``stage``."""
    name: str
    status: str
    accepted: bool
    e: float | None
    dt_mean: float | None
    group: int | None
    reason: str | None
    frame: PoseValues | None
    error: str | None
    stage: str | None
    simulated: PoseValues | None
    diff: BatchDelta | None
    points_moved: PointsMoved | None
    worst: Worst | None


class BatchGroup(Result):
    """A Table-4 group: dt_mean in ``range`` (mm), ``count``, ``percent`` of
    the total, ``mean_e`` and ``std_e`` (mm) of its entries."""
    group: int
    range: list[float | None]
    count: int
    percent: float | None
    mean_e: float | None
    std_e: float | None


class BatchSummary(Result):
    """``total``, ``passed``, ``rejected`` (too few points), ``errors``,
    ``success_rate`` (passed / total) and the five ``groups``."""
    total: int
    passed: int
    rejected: int
    errors: int
    over_tolerance: int
    success_rate: float | None
    groups: list[BatchGroup]


class BatchOutput(Result):
    """``ucsio batch --json``: every entry and the summary. ``result`` (not a
    key): ``fleet.batch.BatchResult``, for the report and the CSV."""
    schema_version: int
    manifest: str
    entries: list[BatchEntry]
    summary: BatchSummary


# ------------------------------------------------------------------ plan

class Nearest(Result):
    """Where a suggested point lies from the nearest planned point: its
    ``name``, the ``distance`` (mm) and the ``offset`` [dx, dy, dz] (mm, UCS)."""
    name: str
    distance: float
    offset: list[float]


class SuggestAdd(Result):
    """The candidate (``x y z`` in the UCS, mm) whose point most lowers the
    worst working point's error, and that error then (mm); ``from``
    ("candidates" or "near planned points") and ``nearest``."""
    name: str
    x: float
    y: float
    z: float
    worst_after: float | None
    nearest: Nearest


class PlanNoise(Result):
    """The noise a plan assumes (``sigma``, mm per axis) and its ``source``:
    "default" (an uncalibrated robot), "stated" (``sigma_laser``,
    ``sigma_robot``) or "history" (``history``, ``datasets``, their residual
    σ's ``mean`` and ``std``)."""
    sigma: float
    source: str
    sigma_laser: float | None
    sigma_robot: float | None
    history: str | None
    datasets: int | None
    mean: float | None
    std: float | None


class SuggestDrop(Result):
    """The planned point that costs least to drop, and the worst error then (mm)."""
    name: str
    worst_after: float | None


class Suggest(Result):
    add: SuggestAdd | None
    drop: SuggestDrop | None


class PlanResult(Result):
    """``ucsio plan --json``: each working point's predicted 95 % error
    (mm), the ``worst``, the ``verdict`` (pass or fail against
    ``threshold``), ``reason`` and ``advice``, and what to change
    (``suggest``); with ``--tcp solve`` ``tcp_at_95`` (mm) and
    ``orientation_span`` (deg), and where the plan gives no flange poses
    the ``spread`` (deg) of ``program --measure --spread`` it takes."""
    schema_version: int
    planned: int
    sigma: float
    noise: PlanNoise
    threshold: float
    working_points: list[WorkingPoint]
    worst: Worst
    verdict: str
    reason: str | None
    advice: str | None
    suggest: Suggest
    tcp_at_95: float | None
    orientation_span: float | None
    spread: float | None
    warnings: list[str]
    source: str
    at: str | None


# ------------------------------------------------------------------ demo

class DemoCell(Result):
    """One shipped cell: its ``solve`` document, the ``diff`` of its frame and
    the ``patch`` preview; ``ok`` when accepted and within tolerance."""
    cell: str
    vendor: str
    controller: str
    frame: str
    solve: Solve
    diff: Diff
    patch: dict[str, Any]
    folder: str | None
    ok: bool


class DemoResult(Result):
    """``ucsio demo --json``: every cell, ``ok`` when all pass, ``out``."""
    schema_version: int
    cells: list[DemoCell]
    ok: bool
    out: str | None


__all__ = ["Result", "PoseValues", "ErrorInfo", "NotRead", "FrameItem", "FramesResult", "CheckResult",
           "CheckedFile", "Lint", "Finding", "SolveResult", "Solve", "SolvedFrame", "SolvePoint",
           "Tcp", "Precision", "Uncertainty", "Spread", "Consistency", "WorkingPoint", "Worst",
           "DiffResult", "Diff", "Delta", "FrameDiff", "TaughtPoints", "TaughtPoint", "PointsMoved",
           "FilesDiff", "FrameChange", "BackupsDiff", "FileListed", "FileChanged",
           "PatchOutput", "PatchInfo", "Change", "BatchOutput", "BatchEntry", "BatchSummary",
           "BatchGroup", "BatchDelta", "PlanResult", "Suggest", "SuggestAdd", "SuggestDrop",
           "DemoResult", "DemoCell", "XYZ"]
