"""Many datasets at once: a TOML manifest of stations, solved and diffed in
batch, with a summary by group (../shared/SPEC.md, "Many robots at once").

The flow, each step callable on its own:

- ``read_manifest(path)``: the manifest, checked (``UcsioError``, exit 2, for
  anything wrong with the manifest as a whole: bad TOML, a bad [defaults], no
  entries, a missing or duplicate name; a bad key or value inside one
  [[entry]] is that entry's ``problem``, reported as its error).
- ``run_batch(manifest)``: per entry, read the measurement and the
  controller's simulated frame (each file parsed once, cached by path), solve
  every dataset (``solve_many``: the method of ``ucsio.method.solve``, batched: one
  Horn call per exclusion round for all entries together, each entry's full
  fit and its leave-one-out fits stacked in it), diff against the simulated
  frame; optionally the Monte Carlo uncertainty and patched copies of the
  controller files. A failing entry (missing file, bad CSV, unknown frame,
  degenerate points) gets its ``error`` and the run goes on.
- ``summarize(results)``: total, passed, rejected, errors, success rate, the
  five groups (count, percent of total, mean and standard deviation of the
  measurement error e over the *accepted* entries of the group) and the
  Pearson correlation of simulated vs measured x, y, z over passing entries.

Statistics conventions: ``std_e`` is the sample standard deviation (n - 1
in the denominator) and is ``null`` for a group with fewer than 2 accepted
entries; ``mean_e`` is ``null`` for an empty group; a correlation is ``null``
with fewer than 2 passing entries or when either side does not vary.
"""
from __future__ import annotations

import math
import os
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Sequence

import numpy as np

from ..defaults import MIN_POINTS, REACH, SIGMA_LASER, SIGMA_ROBOT, THRESHOLD
from ..errors import UcsioError
from ..files import atomic_write_text, read_bytes
from ..geometry.frames import Pose, tool_tcp
from ..review.diff import DEFAULT_TOLERANCE, GROUP_BOUNDS, frame_delta
from ..method.solve import Dataset, solve_many  # noqa: F401  (re-exported: batch is where fleets are solved)

N_GROUPS = len(GROUP_BOUNDS) + 1
# folders that name a part of a backup, not a station (a station's default name is above them)
_BACKUP_FOLDER = re.compile(r"(?:KRC|R\d|SYSTEM|PROGRAM|RAPID|TASK\d+|PROGMOD|SYSMOD|HOME)\Z",
                            re.I)
#: the two sides of a measurement where they live, instead of ``measurement``
#: (``solve --laser/--robot``; paths resolved like the others)
SOURCE_KEYS = ("laser", "robot", "config", "map")
SOURCE_OPTIONS = ("laser_units", "robot_tool", "robot_wobj", "angle_units", "quaternion_order")
#: how a measurement's numbers are written (solve's options of those names), for either kind
READING_KEYS = ("laser_units", "angle_units", "quaternion_order")
ENTRY_KEYS = ("name", "measurement", *SOURCE_KEYS, *SOURCE_OPTIONS, "controller", "frame", "tcp",
              "tool", "threshold", "min_points", "tolerance", "exclude", "no_exclusion", "reach",
              "points", "station", "at", "gate", "pr", "posreg")
DEFAULT_KEYS = tuple(k for k in ENTRY_KEYS if k != "name")
REQUIRED = ("controller", "frame")

Progress = Callable[[str, int, int], None]


# ---------------------------------------------------------------- manifest

@dataclass(frozen=True)
class Entry:
    index: int                        # 0-based position in the manifest
    name: str
    measurement: str | None           # paths resolved against the manifest's folder
    controller: str | None            # (None only in an entry with a problem)
    frame: str | None
    tcp: tuple[float, float, float] | None
    tool: str | None                  # "FILE:NAME", FILE resolved
    threshold: float = THRESHOLD
    min_points: int = MIN_POINTS
    tolerance: float = DEFAULT_TOLERANCE
    exclude: tuple[str, ...] = ()
    no_exclusion: bool = False
    reach: float = REACH
    points: bool = False              # also how far the frame's taught points move
    station: str | None = None        # the report's roll-up (default: the controller's folder)
    problem: str | None = None        # why this entry cannot run (a bad value in its table)
    solve_tcp: bool = False           # tcp = "solve": the TCP estimated with the frame
    tcp_tool: str | None = None       # tcp = "solve" with tool = "FILE:NAME": the solved TCP goes
                                      # there (--patch-dir), FILE resolved
    sources: dict | None = None       # laser, robot, config, map, laser_units, robot_tool, robot_wobj
    at: str | None = None             # working points (CSV of point, x, y, z in the UCS), resolved
    gate: str = "reach"               # "at": the determinacy gate judges the worst working point
    reading: tuple = ()               # (key, value) of READING_KEYS the manifest gives
    pr: int | None = None             # --patch-dir, a listing's frame: the program's register ...
    posreg: str | None = None         # ... or the posreg.va to take an unused one from, resolved


@dataclass
class Manifest:
    path: str
    entries: list[Entry]


def _number(value, key: str, where: str, path: str, *, positive=False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise UcsioError(f"{where}: {key} must be a number, got {value!r}", file=path)
    if positive and not value > 0:
        raise UcsioError(f"{where}: {key} must be positive, got {value!r}", file=path)
    return float(value)


def _resolve(base: Path, rel: str) -> str:
    p = Path(rel).expanduser()
    return os.path.normpath(p if p.is_absolute() else base / p)


def _check_table(table: dict, where: str, allowed: Sequence[str], path: str) -> dict:
    unknown = [k for k in table if k not in allowed]
    if unknown:
        from ..errors import did_you_mean
        raise UcsioError(f"{where}: unknown key{'s' if len(unknown) > 1 else ''} "
                         f"{', '.join(map(repr, unknown))}{did_you_mean(unknown[0], allowed)} "
                         f"(allowed: {', '.join(allowed)})", file=path)
    if "tcp" in table and "tool" in table and table["tcp"] != "solve":
        raise UcsioError(f"{where}: give either tcp or tool, not both (tool goes with tcp only "
                         "as tcp = \"solve\": the solved TCP is then written into that tool "
                         "by --patch-dir)", file=path)
    return table


def _check_values(table: dict, where: str, path: str) -> None:
    """The type and range of every value a table gives (UcsioError)."""
    if "pr" in table and (isinstance(table["pr"], bool) or not isinstance(table["pr"], int)
                          or not 1 <= table["pr"] <= 9999):
        raise UcsioError(f"{where}: pr must be a position register number, 1 to 9999, got "
                         f"{table['pr']!r}", file=path)
    for k in REQUIRED + ("measurement", "at", "posreg") + SOURCE_KEYS + SOURCE_OPTIONS:
        if k in table and (not isinstance(table[k], str) or not table[k].strip()):
            raise UcsioError(f"{where}: {k} must be a non-empty string, got {table[k]!r}",
                             file=path)
    if "tool" in table:
        spec = table["tool"]
        file, sep, tname = spec.rpartition(":") if isinstance(spec, str) else ("", "", "")
        if not sep or not file or not tname:
            raise UcsioError(f"{where}: tool must be \"FILE:NAME\", got {spec!r}", file=path)
    if "laser_units" in table and table["laser_units"] not in ("mm", "m", "in"):
        raise UcsioError(f"{where}: laser_units must be \"mm\", \"m\" or \"in\", got "
                         f"{table['laser_units']!r}", file=path)
    for key, allowed in (("angle_units", ("deg", "rad")), ("quaternion_order", ("wxyz", "xyzw"))):
        if key in table and table[key] not in allowed:
            raise UcsioError(f"{where}: {key} must be \"{allowed[0]}\" or \"{allowed[1]}\", "
                             f"got {table[key]!r}", file=path)
    if "tcp" in table and table["tcp"] != "solve":
        v = table["tcp"]
        if not isinstance(v, list) or len(v) != 3:
            raise UcsioError(f"{where}: tcp must be a list of three numbers [x, y, z] or "
                             f"\"solve\", got {v!r}", file=path)
        for c in v:
            _number(c, "tcp", where, path)
    for k in ("threshold", "tolerance", "reach"):
        if k in table:
            _number(table[k], k, where, path, positive=True)
    if "min_points" in table:
        mp = table["min_points"]
        if isinstance(mp, bool) or not isinstance(mp, int) or mp < 3:
            raise UcsioError(f"{where}: min_points must be an integer >= 3, got {mp!r}", file=path)
    if "exclude" in table:
        ex = table["exclude"]
        if isinstance(ex, str):
            ex = [ex]
        if not isinstance(ex, list) or not all(isinstance(x, str) for x in ex):
            raise UcsioError(f"{where}: exclude must be a list of point names", file=path)
    for k in ("no_exclusion", "points"):
        if k in table and not isinstance(table[k], bool):
            raise UcsioError(f"{where}: {k} must be true or false", file=path)
    if "gate" in table and table["gate"] not in ("reach", "at"):
        raise UcsioError(f"{where}: gate must be \"reach\" or \"at\", got {table['gate']!r}",
                         file=path)
    if "station" in table and (not isinstance(table["station"], str)
                               or not table["station"].strip()):
        raise UcsioError(f"{where}: station must be a non-empty string", file=path)


def _entry(i: int, name: str, raw: dict, defaults: dict, label: str, base: Path,
           path: str) -> Entry:
    """One checked entry; UcsioError for anything wrong with it."""
    _check_table(raw, label, ENTRY_KEYS, path)
    merged = dict(defaults)
    if "tcp" in raw or "tool" in raw:          # the entry's own TCP source wins
        merged.pop("tcp", None)
        merged.pop("tool", None)
    merged.update(raw)
    # the measurement: one merged file, or the laser and robot sides
    if "measurement" in raw and ("laser" in raw or "robot" in raw):
        raise UcsioError(f"{label}: give measurement, or laser and robot, not both", file=path)
    if "measurement" in raw:                   # the entry's own kind of measurement wins
        merged.pop("laser", None)
        merged.pop("robot", None)
    elif "laser" in raw or "robot" in raw:
        merged.pop("measurement", None)
    if "measurement" not in merged:
        if "laser" not in merged or "robot" not in merged:
            raise UcsioError(f"{label}: needs measurement (a merged CSV), or laser and robot",
                             file=path)
    elif "laser" in merged or "robot" in merged:
        raise UcsioError(f"{label}: give measurement, or laser and robot, not both", file=path)
    for k in REQUIRED:
        if not isinstance(merged.get(k), str) or not merged[k].strip():
            raise UcsioError(f"{label}: needs {k} (a string)", file=path)
    _check_values(merged, label, path)
    sources = None
    if "measurement" not in merged:
        sources = {k: _resolve(base, merged[k]) for k in SOURCE_KEYS if k in merged}
        sources.update({k: merged[k] for k in SOURCE_OPTIONS if k in merged})
    tcp = None
    tool = None
    tcp_tool = None
    solve_tcp = False
    if "tool" in merged:
        file, _, tname = merged["tool"].rpartition(":")
        if merged.get("tcp") == "solve":    # solve the TCP; --patch-dir writes it into the tool
            solve_tcp = True
            tcp_tool = f"{_resolve(base, file)}:{tname}"
        else:                               # the TCP read from the tool
            tool = f"{_resolve(base, file)}:{tname}"
    elif merged.get("tcp") == "solve":
        solve_tcp = True
    elif "tcp" in merged:
        tcp = tuple(float(c) for c in merged["tcp"])
    else:       # SPEC point 8: never a silent 0,0,0
        raise UcsioError(f"{label}: no TCP: give tcp = [x, y, z] (mm, in flange coordinates; "
                         "[0, 0, 0] says the points are flange positions), tool = "
                         "\"FILE:NAME\" or tcp = \"solve\", in the entry or in [defaults]",
                         file=path)
    ex = merged.get("exclude", [])
    if isinstance(ex, str):
        ex = [ex]
    gate = merged.get("gate", "reach")
    if gate == "at" and "at" not in merged:
        raise UcsioError(f"{label}: gate = \"at\" judges the working points: give them with "
                         "at = \"FILE\"", file=path)
    measurement = (_resolve(base, merged["measurement"]) if sources is None
                   else sources["laser"])
    return Entry(index=i, name=name, measurement=measurement,
                 controller=_resolve(base, merged["controller"]), frame=merged["frame"],
                 tcp=tcp, tool=tool, threshold=float(merged.get("threshold", THRESHOLD)),
                 min_points=merged.get("min_points", MIN_POINTS),
                 tolerance=float(merged.get("tolerance", DEFAULT_TOLERANCE)),
                 exclude=tuple(ex), no_exclusion=merged.get("no_exclusion", False),
                 reach=float(merged.get("reach", REACH)),
                 points=merged.get("points", False), station=merged.get("station"),
                 solve_tcp=solve_tcp, tcp_tool=tcp_tool, sources=sources,
                 at=_resolve(base, merged["at"]) if "at" in merged else None, gate=gate,
                 reading=tuple((k, merged[k]) for k in READING_KEYS if k in merged),
                 pr=merged.get("pr"),
                 posreg=_resolve(base, merged["posreg"]) if "posreg" in merged else None)


def _broken_entry(i: int, name: str, raw: dict, defaults: dict, base: Path,
                  problem: str) -> Entry:
    """An entry that cannot run: what can be told of it, and why."""
    def path_of(k):
        v = raw.get(k, defaults.get(k))
        return _resolve(base, v) if isinstance(v, str) and v.strip() else None

    frame = raw.get("frame", defaults.get("frame"))
    station = raw.get("station", defaults.get("station"))
    return Entry(index=i, name=name, measurement=path_of("measurement"),
                 controller=path_of("controller"),
                 frame=frame if isinstance(frame, str) else None, tcp=None, tool=None,
                 station=station if isinstance(station, str) and station.strip() else None,
                 problem=problem)


def read_manifest(path: str | os.PathLike) -> Manifest:
    """Read and check a batch manifest.

    UcsioError (exit 2) for anything wrong with the manifest as a whole: not
    readable, not UTF-8, not TOML, unknown top-level keys, a bad [defaults],
    no entries, an entry without a name or a duplicate name. A problem inside one named
    [[entry]] (an unknown key, a missing frame, a mistyped value) only makes
    that entry fail: its ``problem``, reported as its error by run_batch."""
    path = os.fspath(path)
    raw = read_bytes(path, "manifest")
    try:
        text = raw.decode("utf-8")      # TOML is UTF-8 (tomllib would raise UnicodeDecodeError)
    except UnicodeDecodeError as exc:
        raise UcsioError(f"not UTF-8 text: byte 0x{raw[exc.start]:02x} at offset {exc.start} "
                         "cannot be decoded (a TOML manifest is UTF-8; save it as UTF-8)",
                         file=path, line=raw[:exc.start].count(b"\n") + 1) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise UcsioError(f"not valid TOML: {exc}", file=path) from None
    base = Path(path).resolve().parent
    top_unknown = [k for k in data if k not in ("defaults", "entry")]
    if top_unknown:
        from ..errors import did_you_mean
        raise UcsioError(f"unknown top-level key(s) {', '.join(map(repr, top_unknown))}"
                         f"{did_you_mean(top_unknown[0], ('defaults', 'entry'))} "
                         "(a manifest has [defaults] and [[entry]] tables)", file=path)
    defaults = data.get("defaults", {})
    if not isinstance(defaults, dict):
        raise UcsioError("[defaults] must be a table", file=path)
    _check_table(defaults, "[defaults]", DEFAULT_KEYS, path)
    _check_values(defaults, "[defaults]", path)
    raw_entries = data.get("entry", [])
    if not isinstance(raw_entries, list) or not all(isinstance(e, dict) for e in raw_entries):
        raise UcsioError("entries must be [[entry]] tables", file=path)
    if not raw_entries:
        raise UcsioError("no [[entry]] tables: nothing to do", file=path)

    entries: list[Entry] = []
    seen: dict[str, int] = {}
    for i, raw in enumerate(raw_entries):
        name = raw.get("name")
        label = f"entry {i + 1}" + (f" ({name!r})" if isinstance(name, str) else "")
        if not isinstance(name, str) or not name.strip():
            raise UcsioError(f"{label}: needs a name (a non-empty string)", file=path)
        key = name.strip().casefold()
        if key in seen:
            raise UcsioError(f"duplicate entry name {name!r} (entries {seen[key] + 1} and {i + 1});"
                             " names must be unique", file=path)
        seen[key] = i
        try:
            entries.append(_entry(i, name, raw, defaults, label, base, path))
        except UcsioError as exc:
            entries.append(_broken_entry(i, name, raw, defaults, base, str(exc)))
    return Manifest(path=path, entries=entries)


# ---------------------------------------------------------------- the run

@dataclass
class EntryResult:
    entry: Entry
    solution: Any = None              # ucsio.method.solve.Solution
    simulated: Pose | None = None
    measured: Pose | None = None      # in the frame's own parent (differs from the fit for oframe)
    delta: dict | None = None
    error: str | None = None
    stage: str | None = None          # where it failed: manifest, controller, tool, measurement, solve, diff
    vendor: str | None = None
    frame_file: str | None = None
    frame_line: int | None = None
    patched: str | None = None        # the patched copy (--patch-dir)
    patch_error: str | None = None    # why no patched copy was written
    uncertainty_axes: str | None = None   # "world", or "uframe" (an ABB object frame)
    uncertainty_error: str | None = None  # why --uncertainty gave nothing for this entry
    points_moved: dict | None = None      # points = true: count, max, mean, worst (taught points)
    points_error: str | None = None       # why they could not be placed
    warnings: list[str] = field(default_factory=list)   # pairing a laser and a robot file; unset
    simulated_set: bool | None = None     # False: the simulated frame is unset (review.unset)
    tool_tcp: tuple | None = None         # tcp = "solve" with a tool: its TCP as the file holds it
    tool_patched: str | None = None       # the patched copy the solved TCP was written into
    tool_not_patched: str | None = None   # --patch-dir, tcp = "solve", no tool named: says so
    listing: bool = False                 # the patched copy is a listing, for review only
    program: dict | None = None           # the program written beside it that sets the frame
    program_error: str | None = None      # why no program was written

    @property
    def accepted(self) -> bool:
        return self.error is None and self.solution is not None and bool(self.solution.accepted)

    @property
    def passed(self) -> bool:
        return self.accepted and self.delta is not None and bool(self.delta["pass"])

    @property
    def status(self) -> str:
        if self.error is not None:
            return "error"
        if not self.accepted:
            return "rejected"
        return "pass" if self.passed else "over tolerance"

    @property
    def written(self) -> list[str]:
        """What --patch-dir wrote for the frame, in words: "patched" (a copy
        the controller loads), or "program written" and "listing for review"."""
        if self.patched is None:
            return []
        if not self.listing:
            return ["patched"]
        return (["program written"] if self.program else []) + ["listing for review"]

    @property
    def reason(self) -> str | None:
        """Why the entry's dataset was rejected (the solver's ``reason``: too
        few points, or residuals over the threshold with no point to single
        out); None when it was accepted or never solved."""
        s = self.solution
        if s is None or s.accepted:
            return None
        return getattr(s, "reason", None) or "the dataset was rejected"

    def tool_tcp_dict(self) -> dict[str, Any]:
        """The named tool's TCP as the file holds it, and its distance (mm) from
        the solved one where the entry was solved."""
        x, y, z = self.tool_tcp
        d: dict[str, Any] = {"x": x, "y": y, "z": z}
        s = self.solution
        if s is not None and getattr(s, "tcp_solved", None):
            d["distance"] = math.dist(self.tool_tcp, s.tcp)
        return d

    @property
    def station(self) -> str | None:
        """The entry's ``station``, else its controller's folder, above the
        folders every backup has (KRC/R1/System, RAPID/TASK1/PROGMOD)."""
        en = self.entry
        if en.station:
            return en.station
        if not en.controller:
            return None
        parts = os.path.normpath(en.controller).split(os.sep)[:-1]
        named = [p for p in parts if p and not _BACKUP_FOLDER.match(p)]
        return (named or parts or [None])[-1]

    @property
    def e(self) -> float | None:
        return None if self.solution is None or self.error else self.solution.mean

    @property
    def dt_mean(self) -> float | None:
        return self.delta["dt_mean"] if self.delta else None

    @property
    def group(self) -> int | None:
        return self.delta["group"] if self.delta else None

    def as_dict(self, points: bool = True) -> dict[str, Any]:
        en = self.entry
        d: dict[str, Any] = {
            "name": en.name, "status": self.status, "accepted": self.accepted,
            "e": self.e, "dt_mean": self.dt_mean, "group": self.group, "pass": self.passed,
            "reason": self.reason,
            "frame": self.measured.as_dict() if self.measured is not None else None,
        }
        if self.error is not None:
            d["error"] = self.error
            d["stage"] = self.stage
        d.update({"measurement": en.measurement, "controller": en.controller,
                  "frame_name": en.frame, "station": self.station, "vendor": self.vendor,
                  "tcp": list(en.tcp) if en.tcp is not None else
                  (list(self.solution.tcp) if self.solution is not None else None),
                  "tool": en.tool or en.tcp_tool, "threshold": en.threshold,
                  "min_points": en.min_points,
                  "tolerance": en.tolerance})
        if self.simulated is not None:
            d["simulated"] = self.simulated.as_dict()
        if self.simulated_set is not None:
            d["simulated_set"] = self.simulated_set
        if self.delta is not None:
            d["diff"] = {k: self.delta[k] for k in ("dx", "dy", "dz", "da", "db", "dc", "angle",
                                                     "dist", "dt_mean", "group", "pass")}
        s = self.solution
        if s is not None:
            d.update({"n_points": s.n_points, "n_used": s.n_used, "rms": s.rms, "mean": s.mean,
                      "max": s.max, "precision": s.precision})
            if points:
                d["points"] = [{"name": p.name, "residual": p.residual,
                                "loo_residual": p.loo_residual if math.isfinite(p.loo_residual)
                                else None, "used": p.used, "excluded_by": p.excluded_by}
                               for p in s.points]
            if s.uncertainty is not None:
                d["uncertainty"] = s.uncertainty
                d["uncertainty_axes"] = self.uncertainty_axes or "world"
            if getattr(s, "consistency", None) is not None:
                d["consistency"] = s.consistency
            if getattr(s, "worst", None) is not None:
                d["worst"] = s.worst
                d["gate"] = s.gate
                d["at"] = en.at
                if points:
                    d["working_points"] = s.working_points
        if self.uncertainty_error is not None:
            d["uncertainty_error"] = self.uncertainty_error
        if self.points_moved is not None:
            d["points_moved"] = self.points_moved
        if self.points_error is not None:
            d["points_error"] = self.points_error
        if en.sources is not None:
            d["sources"] = en.sources
        if s is not None and getattr(s, "tcp_solved", None):
            d["tcp_solved"] = s.tcp_solved
        if s is not None and getattr(s, "diagnosis", None):
            d["diagnosis"] = s.diagnosis
        if self.tool_tcp is not None:
            d["tool_tcp"] = self.tool_tcp_dict()
        if self.tool_patched is not None:
            d["tool_patched"] = self.tool_patched
        if self.tool_not_patched is not None:
            d["tool_not_patched"] = self.tool_not_patched
        if self.warnings:
            d["warnings"] = list(self.warnings)
        if self.patched is not None:
            d["patched"] = self.patched
            d["written"] = self.written
        if self.listing:
            d["listing"] = True
        if self.program is not None:
            d["program"] = self.program
        if self.program_error is not None:
            d["program_error"] = self.program_error
        if self.patch_error is not None:
            d["patch_error"] = self.patch_error
        return d


@dataclass
class BatchResult:
    manifest: Manifest
    entries: list[EntryResult]
    summary: dict = field(default_factory=dict)
    timings: dict = field(default_factory=dict)

    @property
    def all_passed(self) -> bool:
        """Every entry passed (and every patched copy asked for was written)."""
        return all(r.passed and r.patch_error is None for r in self.entries)

    def as_dict(self, points: bool = True) -> dict[str, Any]:
        return {"manifest": self.manifest.path,
                "entries": [r.as_dict(points) for r in self.entries],
                "summary": self.summary}


class _Cache:
    """Each file read once: controller files, measurements; errors too (a
    broken file fails every entry that names it, with the same message)."""

    def __init__(self):
        self.controllers: dict[str, Any] = {}
        self.measurements: dict[str, Any] = {}

    @staticmethod
    def _get(store: dict[str, Any], path: str, read):
        if path not in store:
            try:
                store[path] = read(path)
            except UcsioError as exc:
                store[path] = exc
        got = store[path]
        if isinstance(got, Exception):
            raise got
        return got

    def controller(self, path: str):
        from ..parsing.controller import load
        return self._get(self.controllers, path, load)

    def measurement(self, path: str, reading: tuple = ()):
        from ..readers.measurement import read_measurement
        return self._get(self.measurements, (path, reading),
                         lambda _key: read_measurement(path, **dict(reading)))

    def points(self, path: str):
        """A working-point file (readers.points), read once per run."""
        from ..readers.points import read_points
        return self._get(self.measurements, ("at", path), lambda _key: read_points(path))

    def paired(self, sources: dict):
        """(Measurement, warnings) of an entry's laser and robot files."""
        key = tuple(sorted(sources.items()))

        def read(_):
            from ..readers import laser, pairing, robot
            lp = laser.read_laser(sources["laser"], sources.get("laser_units", "mm"))
            rp = robot.read_robot(sources["robot"], config=sources.get("config"),
                                  tool=sources.get("robot_tool", "tool0"),
                                  wobj=sources.get("robot_wobj", "wobj0"),
                                  angle_units=sources.get("angle_units", "deg"),
                                  quaternion_order=sources.get("quaternion_order", "wxyz"))
            mapping = pairing.read_map(sources["map"]) if "map" in sources else ()
            return pairing.pair(lp, rp, mapping, sources.get("map"))
        return self._get(self.measurements, key, read)


def _solve_joint(en: Entry, meas, sigma_laser: float, sigma_robot: float, at=None):
    """An entry with tcp = "solve": its Solution, or the UcsioError."""
    from ..method.tcp_solve import solve_joint
    try:
        return solve_joint(meas, threshold=en.threshold, min_points=en.min_points,
                           exclude=en.exclude, no_exclusion=en.no_exclusion, reach=en.reach,
                           sigma_laser=sigma_laser, sigma_robot=sigma_robot, at=at,
                           gate=en.gate)
    except UcsioError as exc:
        return exc


def _named_mistake(en: Entry, inputs: tuple, sol, sigma_laser: float, sigma_robot: float):
    """The unit or order mistake a rejected entry comes from (method.mistakes),
    refitted as the entry was: its TCP (or the joint model), its settings."""
    from ..method.mistakes import Reading, named_mistake
    from ..method.solve import solve

    tcp, meas, at = inputs

    def fit(m):
        if en.solve_tcp:
            got = _solve_joint(en, m, sigma_laser, sigma_robot, at)
            if isinstance(got, UcsioError):
                raise got
            return got
        return solve(m, tcp, threshold=en.threshold, min_points=en.min_points,
                     exclude=en.exclude, no_exclusion=en.no_exclusion, reach=en.reach,
                     sigma_laser=sigma_laser, sigma_robot=sigma_robot, at=at, gate=en.gate)
    return named_mistake(meas, sol, fit, Reading(**dict(en.reading)),
                         spelled=lambda key, value: f'{key} = "{value}" in the entry')


def _diagnose(en: Entry, meas, sol, sigma_laser: float, sigma_robot: float) -> None:
    """A rejected fixed-TCP entry whose residuals a TCP change explains says
    so in its reason (tcp_solve.diagnose), as ``solve`` does."""
    from ..method.tcp_solve import diagnose
    found = diagnose(meas, sol, threshold=en.threshold, min_points=en.min_points,
                     no_exclusion=en.no_exclusion, reach=en.reach, sigma_laser=sigma_laser,
                     sigma_robot=sigma_robot,
                     advice="check the entry's tool or tcp in the manifest, or solve the TCP "
                            "with the frame (tcp = \"solve\"); the points need not be measured "
                            "again")
    if found:
        sol.diagnosis = found
        sol.reason = f"{sol.reason}; but {found['message']}"


def _tool_tcp(cache: _Cache, spec: str, warnings: list[str]) -> tuple[float, float, float]:
    """The TCP of ``tool = "FILE:NAME"``; an unset tool is warned about."""
    from ..review.names import find_frame
    from ..review.unset import is_set, tool_warning

    file, _, name = spec.rpartition(":")
    cf = cache.controller(file)
    frame = find_frame(cf, name)
    tcp = tool_tcp(frame)
    if not is_set(frame, cf):
        warnings.append(tool_warning(frame, "tool", "tcp = [0, 0, 0]"))
    return tcp


def _solved_tcp_tool(cache: _Cache, spec: str):
    """The tool ``tool = "FILE:NAME"`` names beside ``tcp = "solve"``: a
    robot-held tool with a value, which ``--patch-dir`` writes the solved TCP
    into (UcsioError otherwise)."""
    from ..review.names import find_frame
    from ..review.patch import robot_held_tool

    file, _, name = spec.rpartition(":")
    frame = find_frame(cache.controller(file), name)
    if not robot_held_tool(frame):
        raise UcsioError(f"{frame.name} is {frame.type} relative to {frame.reference}: a solved "
                         "TCP is written into a robot-held tool (tooldata with robhold TRUE, "
                         "KUKA TOOL_DATA)", file=frame.file, line=frame.line)
    if frame.pose is None:
        raise UcsioError(f"{frame.name} has no complete value to write the TCP into",
                         file=frame.file, line=frame.line)
    return frame


def _measured_in_parent(cf, frame, fit: Pose) -> Pose:
    """The fit is the UCS in robot world; express it where the frame is given
    (an ABB object frame: in its user frame). A frame relative to something
    else (a flange, a machine) cannot be compared with a measured UCS."""
    from ..review.reference import measured_in_parent, reference_problem

    why = reference_problem(cf, frame)
    if why and frame.reference != "unknown":  # pose data, plain FRAME variables: as given
        raise UcsioError(f"frame {frame.name}: {why}", file=frame.file, line=frame.line)
    return measured_in_parent(cf, frame, fit)


def _entry_uncertainty(r: EntryResult, meas, cf, frame, n: int, sigma_laser: float,
                       sigma_robot: float, seed: int) -> None:
    """The Monte Carlo uncertainty of an accepted entry (``meas``: its
    measurement), in the axes of its ``frame``: robot world, or for an ABB
    object frame its user frame. There the robot points are expressed in the
    user frame (uframe^-1, the map
    measured_in_parent applies to the fit) before the perturbed fits, so
    every sample pose, and with them std and ci95, are in the same
    coordinates as the frame; the noise is isotropic, so its model is the
    same in either axes, and the angle (a magnitude) does not change."""
    from ..review.reference import measured_in_parent
    from ..method.solve import residual_sigma, solution_uncertainty, uncertainty

    sol = r.solution
    ident = Pose.from_quat(0.0, 0.0, 0.0, (1.0, 0.0, 0.0, 0.0))
    to_parent = measured_in_parent(cf, frame, ident)
    if to_parent is ident:                          # the frame is in robot world
        solution_uncertainty(meas, sol, n, sigma_laser, sigma_robot, seed)
        r.uncertainty_axes = "world"
        return
    used = np.array([p.used for p in sol.points])
    robot = meas.robot_points(sol.tcp)[used]
    R = np.array(to_parent.matrix, dtype=float)
    robot = robot @ R.T + np.array(to_parent.t, dtype=float)
    sol.uncertainty = uncertainty(meas.laser[used], robot, (0.0, 0.0, 0.0),
                                  meas.weights[used], n, sigma_laser, sigma_robot, seed,
                                  sigma_residual=residual_sigma(sol))
    r.uncertainty_axes = "uframe"


def run_batch(manifest: Manifest, *, uncertainty: int = 0,
              sigma_laser: float = SIGMA_LASER, sigma_robot: float = SIGMA_ROBOT, seed: int = 0, patch_dir: str | None = None,
              progress: Progress | None = None) -> BatchResult:
    """Solve and diff every entry; one entry's failure never stops the run."""
    import time

    from .. import vendors
    from ..review.names import find_frame
    from ..review.unset import is_set, warning as unset_warning

    t0 = time.perf_counter()
    cache = _Cache()
    results = [EntryResult(entry=e) for e in manifest.entries]
    datasets: list[Dataset] = []
    owners: list[int] = []
    frames: dict[int, Any] = {}
    read: dict[int, tuple] = {}         # entry index -> (tcp, measurement): run-local state
    joint: list[int] = []               # entries with tcp = "solve" (ucsio.method.tcp_solve)
    total = len(results)
    for k, r in enumerate(results):
        en = r.entry
        if en.problem is not None:          # a bad value in its [[entry]] table
            r.error, r.stage = en.problem, "manifest"
            if progress:
                progress("read", k + 1, total)
            continue
        stage = "controller"
        try:
            cf = cache.controller(en.controller)
            r.vendor = cf.vendor
            frame = find_frame(cf, en.frame)
            r.frame_file, r.frame_line = frame.file, frame.line
            if frame.pose is None:
                raise UcsioError(f"frame {frame.name} has no complete value", file=frame.file,
                                 line=frame.line)
            r.simulated = frame.pose
            frames[k] = (cf, frame)
            r.simulated_set = is_set(frame, cf)
            if not r.simulated_set:     # the diff is then the whole measured pose
                r.warnings = [unset_warning(frame)]
            stage = "tool"
            tcp = en.tcp if en.tool is None else _tool_tcp(cache, en.tool, r.warnings)
            if en.tcp_tool is not None:     # where the solved TCP will go: a robot-held tool
                r.tool_tcp = _solved_tcp_tool(cache, en.tcp_tool).pose.t
            stage = "measurement"
            if en.sources is None:
                meas = cache.measurement(en.measurement, en.reading)
            else:
                meas, paired = cache.paired(en.sources)
                r.warnings = list(paired) + r.warnings    # the cache's list stays as it is
            stage = "at"
            at = cache.points(en.at) if en.at is not None else None
            stage = "measurement"
            if en.solve_tcp:                # the joint model: solved on its own, below
                joint.append(k)
                read[k] = (None, meas, at)
                continue
            datasets.append(Dataset(names=meas.names, laser=meas.laser,
                                    robot=meas.robot_points(tcp), weights=meas.weights,
                                    threshold=en.threshold, min_points=en.min_points,
                                    exclude=en.exclude, no_exclusion=en.no_exclusion,
                                    lines=meas.lines, path=meas.path,
                                    sigma_stated=math.hypot(sigma_laser, sigma_robot),
                                    reach=en.reach, at=at, gate=en.gate))
            owners.append(k)
            read[k] = (tcp, meas, at)
        except UcsioError as exc:
            r.error, r.stage = (f"tool {en.tool or en.tcp_tool}: {exc}" if stage == "tool"
                                else str(exc)), stage
        if progress:
            progress("read", k + 1, total)
    t1 = time.perf_counter()

    solved = solve_many(datasets) if datasets else []
    for k in joint:
        owners.append(k)
        solved.append(_solve_joint(results[k].entry, read[k][1], sigma_laser, sigma_robot,
                                   read[k][2]))
    t2 = time.perf_counter()
    for k, sol in zip(owners, solved):
        r = results[k]
        if isinstance(sol, UcsioError):
            r.error, r.stage = str(sol), "solve"
            continue
        if not sol.accepted:
            mistake = _named_mistake(r.entry, read[k], sol, sigma_laser, sigma_robot)
            if mistake is not None:         # a unit or order mistake: not "measure again"
                r.error, r.stage = str(mistake), "measurement"
                continue
        if read[k][0] is not None:
            sol.tcp = tuple(float(v) for v in read[k][0])
        sol.tool = r.entry.tool
        sol.at_source = r.entry.at
        r.solution = sol
        if not sol.accepted and not r.entry.solve_tcp:
            _diagnose(r.entry, read[k][1], sol, sigma_laser, sigma_robot)
        cf, frame = frames[k]
        try:
            r.measured = _measured_in_parent(cf, frame, sol.pose)
        except UcsioError as exc:
            r.error, r.stage = str(exc), "diff"
            continue
        if sol.accepted:
            r.delta = frame_delta(r.simulated, r.measured, r.entry.tolerance,
                                  vendors.get(frame.vendor).same_rotation_tolerance)
    if progress:
        progress("solve", total, total)
    t3 = time.perf_counter()

    if uncertainty:
        todo = [k for k, r in enumerate(results) if r.accepted]
        for k in [k for k in todo if results[k].entry.solve_tcp]:
            results[k].uncertainty_error = ("not available with tcp = \"solve\" (the first-order "
                                            "numbers are in its precision)")
            todo.remove(k)
        for j, k in enumerate(todo):
            r = results[k]
            try:
                _entry_uncertainty(r, read[k][1], *frames[k], uncertainty, sigma_laser,
                                   sigma_robot, seed)
            except UcsioError as exc:
                r.uncertainty_error = str(exc)
            if progress:
                progress("uncertainty", j + 1, len(todo))
    t4 = time.perf_counter()

    _taught_points(results, frames)

    if patch_dir is not None:
        write_patches(results, frames, cache, patch_dir, manifest)
        write_programs(results, frames)
    t5 = time.perf_counter()
    summary = summarize(results)
    return BatchResult(manifest=manifest, entries=results, summary=summary,
                       timings={"read": t1 - t0, "solve": t2 - t1, "diff": t3 - t2,
                                "uncertainty": t4 - t3, "patch": t5 - t4,
                                "controllers": len(cache.controllers),
                                "measurements": len(cache.measurements)})


def _taught_points(results: list[EntryResult], frames: dict) -> None:
    """``points = true``: how far the taught points of each accepted entry's
    frame move (ucsio.taught); each frame's points are found once per run."""
    from ..taught import find_points, points_moved

    found: dict[int, Any] = {}
    files: dict = {}            # each module or .dat read once per run
    for k, r in enumerate(results):
        if not (r.entry.points and r.accepted and k in frames):
            continue
        cf, frame = frames[k]
        try:
            if id(frame) not in found:
                found[id(frame)] = find_points(cf, frame, files)
            got = points_moved(cf, frame, r.solution.pose, found[id(frame)])
        except UcsioError as exc:
            r.points_error = str(exc)
            continue
        r.points_moved = dict(got["points_moved"], warnings=got["points_warnings"],
                              skipped=got["points_skipped"])


def write_patches(results: list[EntryResult], frames: dict, cache: _Cache, patch_dir: str,
                  manifest: Manifest) -> None:
    """Patched copies of the controller files under ``patch_dir``, at their
    paths relative to the manifest (the originals are never touched). Every
    *passing* entry's frame is written with its measured value (a rejected
    dataset or a frame over tolerance is for a person to look at first), and
    where the entry solved its TCP (``tcp = "solve"``) and names a tool
    (``tool = "FILE:NAME"``), that tool gets the solved TCP's x, y, z and
    nothing else of it (``ucsio.review.patch.patch_tcp``, as ``patch`` does;
    an entry that names no tool gets ``tool_not_patched``, saying so). A file
    with several such changes gets all of them in one copy. Each goes through
    ``patch_frame``'s refusals (the sibling modules of a shared-PERS check
    read through ``cache``, so each file is parsed once per run); the copy
    with all of a file's changes applied is parsed once and every frame must
    read back from it (``ucsio.review.verify.verify``). A refusal is the
    entry's ``patch_error``, and that file's copy is not written (the file's
    other entries get a ``patch_error`` naming the refused one); two entries
    writing one frame or tool are refused too. The copy is not written
    either when the source file changed on disk since it was read (its bytes
    are what was patched): every entry of that file gets the
    ``patch_error``."""
    from .. import vendors
    from ..files import atomic_write
    from ..review import patch as patcher
    from ..review.names import find_frame

    def load(p) -> Any:     # a sibling module, through the run's cache
        return cache.controller(os.path.normpath(os.fspath(p)))

    # per file: (entry result, what: "frame" | "tool", the frame's or tool's name)
    by_file: dict[str, list[tuple[EntryResult, str, str]]] = {}
    for k, r in enumerate(results):
        if not r.passed:
            continue
        by_file.setdefault(r.entry.controller, []).append((r, "frame", frames[k][1].name))
        if r.entry.solve_tcp:
            if r.entry.tcp_tool is None:
                r.tool_not_patched = ("not written into any tool: the entry names none "
                                      "(tool = \"FILE:NAME\" beside tcp = \"solve\" names "
                                      "one)")
            else:
                file, _, name = r.entry.tcp_tool.rpartition(":")
                by_file.setdefault(file, []).append((r, "tool", name))
    base = Path(manifest.path).resolve().parent
    out_root = Path(patch_dir)
    for path, items in by_file.items():
        cf = cache.controller(path)
        try:
            rel = Path(path).resolve().relative_to(base)
        except ValueError:
            rel = Path(Path(path).name)
        target = out_root / rel
        problem = None
        culprit = None          # the entry whose change was refused, if one was
        planned = []
        seen: dict[int, str] = {}
        for r, what, name in items:
            try:
                frame = find_frame(cf, name)
                if id(frame) in seen:
                    problem = (f"entries {seen[id(frame)]!r} and {r.entry.name!r} both write "
                               f"{frame.name}; not patched")
                    break
                seen[id(frame)] = r.entry.name
                if what == "frame":
                    planned.append(patcher.patch_frame(cf, frame.name, r.solution.pose,
                                                       verify=False, load=load))
                else:
                    planned.append(patcher.patch_tcp(cf, frame.name, r.solution.tcp,
                                                     verify=False, load=load))
            except UcsioError as exc:
                problem = str(exc) if what == "frame" else f"tool {r.entry.tcp_tool}: {exc}"
                culprit = r.entry.name
                break
        try:
            if problem is None:
                edits = [e for pr in planned for e in patcher.edits_for(pr.frame, pr.changes)]
                new = cf.document.edited_bytes(edits)
                _verify_combined(cf, new, planned)
                if target.resolve() == Path(path).resolve():
                    raise UcsioError("--patch-dir would overwrite the original", file=path)
                target.parent.mkdir(parents=True, exist_ok=True)
                mode = os.stat(path).st_mode & 0o7777

                def unchanged(path=path, raw=cf.document.raw) -> None:
                    try:
                        same = read_bytes(path) == raw
                    except UcsioError:
                        same = False
                    if not same:
                        raise UcsioError("the file changed on disk since it was read; patched "
                                         "copy not written (run the batch again)", file=path)

                atomic_write(target, new, mode, check=unchanged)
        except UcsioError as exc:
            problem = str(exc)
        except OSError as exc:
            problem = f"cannot write {target}: {exc.strerror or exc}"
        for r, what, name in items:
            if problem is None:
                if what == "frame":
                    r.patched = str(target)
                    # a listing's copy is for review (FANUC: the controller does
                    # not load .va files): a program sets the frame instead
                    review = [(pr, vendors.get(pr.frame.vendor).review_copy_warning)
                              for pr in planned]
                    r.listing = any(w is not None and w in pr.warnings for pr, w in review
                                    if pr.frame.name.casefold() == name.casefold())
                    r.warnings += [w for pr, copy in review for w in pr.warnings
                                   if w == copy and w not in r.warnings]
                else:
                    r.tool_patched = str(target)
                continue
            if culprit is None or r.entry.name == culprit:
                why = problem
            else:       # one copy per file: another entry's refusal stops this one too
                why = (f"not written: the patch of entry {culprit!r} in the same file was "
                       f"refused ({problem})")
            if r.patch_error is None:
                r.patch_error = why
            elif why not in r.patch_error:      # its frame's file and its tool's file
                r.patch_error += f"; {why}"


def write_programs(results: list[EntryResult], frames: dict) -> None:
    """Beside each listing's reviewed copy, the program that sets its frame,
    as ``ucsio program`` writes it, where the frame's vendor writes one
    (its vendor's ``program_writer``); its register from the entry's
    ``pr`` or ``posreg``, else the posreg.va beside the listing. A failure
    is the entry's ``program_error``; the listing's copy stays for review."""
    from .. import vendors

    for k, r in enumerate(results):
        frame = frames[k][1] if k in frames else None
        vendor = vendors.get(frame.vendor) if frame is not None else None
        writer = vendor.program_writer if vendor is not None else None
        if not (r.listing and writer):
            continue
        try:
            made = writer(r.measured, frame, os.path.dirname(r.patched), pr=r.entry.pr,
                          posreg=r.entry.posreg)
        except UcsioError as exc:
            r.program_error = str(exc)
            continue
        except OSError as exc:
            r.program_error = f"program not written: {exc.strerror or exc}"
            continue
        r.program = {k: v for k, v in made.as_dict().items() if k != "text"}
        r.warnings = [w for w in r.warnings if w != vendor.review_copy_warning] + [
            f"the controller does not load .va files: the patched copy of "
            f"{os.path.basename(frame.file)} is for review; {os.path.basename(made.written)} "
            f"beside it sets {frame.name} through PR[{made.pr}] (load it, read it, run it once "
            "in T1)"]


def _verify_combined(cf, new: bytes, planned) -> None:
    """Parse the bytes with all of a file's patches applied, once, and check
    every frame reads back from them (``ucsio.review.verify.verify`` on that parse:
    ``patch_frame`` was told not to parse each frame's copy alone)."""
    from ..parsing.controller import parse
    from ..parsing.document import Document
    from ..review.verify import verify

    try:
        again = parse(Document(new, cf.path))
    except UcsioError as exc:
        raise UcsioError(f"internal error: the patched copy does not parse back: {exc}",
                         file=cf.path) from None
    for pr in planned:
        verify(pr, parsed=again)


# ---------------------------------------------------------------- summary

def _pearson(a: Sequence[float], b: Sequence[float]) -> float | None:
    """Pearson's r, or None where it says nothing: two points always give +-1."""
    if len(a) < 3:
        return None
    x = np.asarray(a, dtype=float)
    y = np.asarray(b, dtype=float)
    dx, dy = x - x.mean(), y - y.mean()
    den = math.sqrt(float(dx @ dx) * float(dy @ dy))
    if den == 0.0 or not math.isfinite(den):
        return None
    return float(dx @ dy) / den


def _finite(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def summarize(results: Sequence[EntryResult]) -> dict[str, Any]:
    """The summary; a missing number (an e, a pose) is left out of the
    statistics it would feed, never an error."""
    total = len(results)
    passed = sum(r.passed for r in results)
    errors = sum(r.error is not None for r in results)
    rejected = sum(r.error is None and r.solution is not None and not r.solution.accepted
                   for r in results)
    accepted = [r for r in results if r.accepted and r.delta is not None]
    groups = []
    for g in range(1, N_GROUPS + 1):
        in_g = [r for r in accepted if r.group == g]
        count = len(in_g)
        es = [r.e for r in in_g if _finite(r.e)]
        groups.append({
            "group": g,
            "range": [0.0 if g == 1 else GROUP_BOUNDS[g - 2],
                      GROUP_BOUNDS[g - 1] if g <= len(GROUP_BOUNDS) else None],
            "count": count,
            "percent": 100.0 * count / total if total else 0.0,
            "mean_e": float(np.mean(es)) if es else None,
            "std_e": float(np.std(es, ddof=1)) if len(es) >= 2 else None,
            "passed": sum(r.passed for r in accepted if r.group == g),
        })
    passing = [r for r in results if r.passed and r.simulated is not None
               and r.measured is not None]
    corr = {axis: _pearson([getattr(r.simulated, axis) for r in passing],
                           [getattr(r.measured, axis) for r in passing]) for axis in "xyz"}
    es_all = [r.e for r in accepted if _finite(r.e)]
    return {
        "total": total, "passed": passed, "rejected": rejected, "errors": errors,
        "over_tolerance": len(accepted) - passed, "accepted": len(accepted),
        "success_rate": passed / total if total else 0.0,
        "groups": groups,
        "mean_e": float(np.mean(es_all)) if es_all else None,
        "std_e": float(np.std(es_all, ddof=1)) if len(es_all) >= 2 else None,
        "correlation": corr,
        "patched": sum(r.patched is not None for r in results),
        "programs": sum(r.program is not None for r in results),
        "listings": sum(r.listing for r in results),
        # files the controller loads: patched copies that are not listings, and programs
        "corrected": sum(r.patched is not None and not r.listing for r in results)
        + sum(r.program is not None for r in results),
        "tools_patched": sum(r.tool_patched is not None for r in results),
        "patch_errors": sum(r.patch_error is not None for r in results),
        "std_convention": "sample (n-1); null below 2 entries",
    }


# ---------------------------------------------------------------- CSV

CSV_COLUMNS = ("name", "status", "accepted", "pass", "e", "dt_mean", "group", "dx", "dy", "dz",
               "da", "db", "dc", "angle", "dist", "x", "y", "z", "a", "b", "c",
               "q1", "q2", "q3", "q4", "n_points", "n_used", "rms", "max", "at_reach",
               "angle_std", "sigma", "tolerance", "measurement", "controller", "frame", "error",
               "patched", "patch_error", "reason", "station", "points_count", "points_max",
               "points_mean", "points_worst", "worst_point", "worst_at_95", "consistency_ratio",
               "consistency_p", "tcp_x", "tcp_y", "tcp_z", "tcp_solved", "tcp_std_x",
               "tcp_std_y", "tcp_std_z", "tcp_at_95", "tool_tcp_distance", "written", "program",
               "program_error")


def _tcp_columns(r: EntryResult) -> dict[str, Any]:
    """The TCP the entry used (given, read from a tool, or solved with the
    frame: then its std and 95 %, and how far it lies from the named tool's)."""
    s = r.solution
    tcp = getattr(s, "tcp", None)
    if s is None or r.error is not None or tcp is None:     # any value may be missing
        return {}
    row: dict[str, Any] = dict(zip(("tcp_x", "tcp_y", "tcp_z"), tcp))
    solved = getattr(s, "tcp_solved", None)
    row["tcp_solved"] = bool(solved)
    if solved:
        row.update({f"tcp_std_{k}": solved["std"][k] for k in "xyz"})
        row["tcp_at_95"] = solved.get("at_95")
        if r.tool_tcp is not None:
            row["tool_tcp_distance"] = r.tool_tcp_dict().get("distance")
    return row


def csv_rows(results: Sequence[EntryResult]) -> list[list[Any]]:
    rows = []
    for r in results:
        d = r.delta or {}
        m = r.measured
        s = r.solution
        row = {"name": r.entry.name, "status": r.status, "accepted": r.accepted,
               "pass": r.passed, "e": r.e, "dt_mean": r.dt_mean, "group": r.group,
               "tolerance": r.entry.tolerance, "measurement": r.entry.measurement,
               "controller": r.entry.controller, "frame": r.entry.frame, "error": r.error or "",
               "patched": r.patched, "patch_error": r.patch_error or "",
               "reason": r.reason or "", "station": r.station}
        pm = r.points_moved
        if pm is not None:
            row.update({"points_count": pm["count"], "points_max": pm["max"],
                        "points_mean": pm["mean"], "points_worst": pm["worst"]})
        for k in ("dx", "dy", "dz", "da", "db", "dc", "angle", "dist"):
            row[k] = d.get(k)
        if s is not None and s.precision:
            row.update({k: s.precision[k] for k in ("at_reach", "angle_std", "sigma")})
        if m is not None:
            row.update(zip(("x", "y", "z", "a", "b", "c"), (m.x, m.y, m.z, *m.abc)))
            row.update(zip(("q1", "q2", "q3", "q4"), m.q))
        if s is not None:   # solved (also when it failed afterwards, at the diff)
            row.update({k: getattr(s, k, None) for k in ("n_points", "n_used", "rms", "max")})
            worst = getattr(s, "worst", None)
            if worst:
                row.update({"worst_point": worst.get("name"), "worst_at_95": worst.get("at_95")})
            cons = getattr(s, "consistency", None)
            if cons:
                row.update({"consistency_ratio": cons.get("ratio"),
                            "consistency_p": cons.get("p")})
        row.update(_tcp_columns(r))
        row.update({"written": "; ".join(r.written),
                    "program": (r.program or {}).get("file"),
                    "program_error": r.program_error or ""})
        rows.append([row.get(c) for c in CSV_COLUMNS])
    return rows


def write_csv(results: Sequence[EntryResult], path: str) -> None:
    import csv
    import io

    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(CSV_COLUMNS)
    for row in csv_rows(results):
        w.writerow(["" if v is None else ("true" if v is True else "false" if v is False
                                          else repr(v) if isinstance(v, float) else v)
                    for v in row])
    atomic_write_text(path, buf.getvalue())


