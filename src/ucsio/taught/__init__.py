"""Taught points: how far the programmed path moves when a frame changes
(``ucsio diff FILE --frame NAME --measured SOLUTION.json --points``).

The positions a robot was taught in a frame are stored relative to it, so
they move with it: a 0.5 deg correction moves a point 2 m away by 17 mm while
the frame's own dt_mean may say 3 mm. The readers find them:

- ``kuka``: E6POS/POS data whose FDAT has the frame's BASE_NO, in the .dat
  files of the controller's tree (the KRC tree around $config.dat);
- ``abb``: robtargets used by instructions with ``\\WObj:=NAME``, in the
  modules of the file's folder;
- ``fanuc``: /POS positions whose group says ``UF : k``, in the .ls files of
  the backup (the folder of the sysframe.va, and below it); joint positions
  are counted as skipped (they do not move with a frame);
- ``yaskawa``: USER positions under ``///USER k`` in the .JBI jobs of the
  backup (the folder of the UFRAME.CND, and below it); the pulses and base
  positions of those jobs are counted as skipped.

``points_moved`` puts each one through the simulated and the measured frame
(frames.Pose, the one place for frame algebra) and reports
moved = |T_measured p - T_simulated p| in world, mm.
"""
from __future__ import annotations

import math
import os

from .. import vendors
from ..errors import UcsioError
from ..geometry.frames import Frame, Pose
from ..parsing.model import ControllerFile
from ..vendors.common.taught import Found

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from typing import Any

WORST = 10          # the table shows the points that move most


FRAME_FILES = ("sysframe.va", "$config.dat")     # what holds the frames of a backup folder


def frames_file_in(folder: str) -> str:
    """The one file of a backup folder that holds its frames (a FANUC
    sysframe.va, a KUKA $config.dat; any case), searched in the folder and
    below it; none or several is an error."""
    found = []
    for dirpath, dirnames, filenames in os.walk(folder):
        dirnames.sort()
        found += [os.path.join(dirpath, f) for f in sorted(filenames)
                  if f.lower() in FRAME_FILES]
    if len(found) == 1:
        return found[0]
    if not found:
        raise UcsioError("a folder without a sysframe.va or $config.dat: give the controller "
                         "file that holds the frame", file=folder)
    shown = ", ".join(os.path.relpath(f, folder) for f in found[:5])
    raise UcsioError(f"a folder of several controllers ({shown}"
                     f"{' ...' if len(found) > 5 else ''}): give the file that holds the frame",
                     file=folder)


def find_points(cf: ControllerFile, frame: Frame, cache: dict | None = None) -> Found:
    """The points taught in ``frame`` (of ``cf``), read from the files around it
    by its vendor's reader; ``cache`` (any dict kept for a run, as ``batch``
    does) reads each file once."""
    read = vendors.get(frame.vendor).taught_points
    if read is None:
        raise UcsioError(vendors.missing(frame.vendor, "reader of taught points"),
                         file=frame.file, line=frame.line)
    return read(cf, frame, cache)


def _chain(cf: ControllerFile, frame: Frame, measured: Pose) -> tuple[list[Pose], list[Pose]]:
    """The poses a taught point goes through to world, simulated and
    measured, innermost last: the vendor's (ABB: uframe * oframe, the
    measured frame given in its parent by review.reference.measured_in_parent; KUKA:
    the base alone)."""
    from ..review.reference import measured_in_parent

    mine = measured_in_parent(cf, frame, measured)
    return vendors.get(frame.vendor).taught_chain(cf, frame, mine)


def in_ucs(cf: ControllerFile, frame: Frame, found: Found) -> list[tuple[float, float, float]]:
    """Each taught point's position in ``frame``'s own coordinates: the UCS a
    measurement of that frame fits (``plan --at-taught``, the working points
    of ``diff --points``). KUKA: as written (the base). ABB: a robtarget is
    in the object frame, so a user frame's points go through its object
    frame; an object frame's are as written."""
    return vendors.get(frame.vendor).taught_in_frame(cf, frame, found)


def _through(chain: list[Pose], p) -> tuple[float, float, float]:
    for pose in reversed(chain):
        p = pose.apply(p)
    return p


def points_moved(cf: ControllerFile, frame: Frame, measured: Pose,
                 found: Found | None = None, solution: Any = None) -> dict[str, Any]:
    """SPEC's ``points`` (each ``name``, ``file``, ``line``, ``moved`` in mm,
    worst first) and ``points_moved`` (``count``, ``max``, ``mean``,
    ``worst``: the name of the point that moves most), with the readers'
    ``points_warnings`` and ``points_skipped`` (how many positions taught
    in the frame do not move with it: FANUC joint positions, Yaskawa
    pulses and base positions). Given the
    ``solution``'s JSON with its covariance, the taught points are its
    working points: each row gets ``at_95``, the
    predicted 95 % error of the measured frame there (mm), and
    ``working_points`` / ``worst`` are SPEC's (plain math: diff imports no
    numpy)."""
    if found is None:
        found = find_points(cf, frame)
    sim, meas = _chain(cf, frame, measured)
    rows = []
    for p in found.points:
        a, b = _through(sim, p.xyz), _through(meas, p.xyz)
        moved = math.dist(a, b)
        rows.append({"name": p.name, "file": p.file, "line": p.line, "moved": moved})
    out: dict[str, Any] = {}
    cov = None
    if solution is not None:
        from ..method.working import describe, from_solution, predict_plain
        cov = from_solution(solution)
    if cov is not None:
        xyz = in_ucs(cf, frame, found)
        at95 = predict_plain(cov, measured.matrix, xyz)
        for row, q in zip(rows, at95):
            row["at_95"] = q
        tcp = solution.get("tcp")
        if isinstance(tcp, dict) and tcp.get("solved") is True:     # a TCP solved with the frame
            out["tcp_at_95"] = solution.get("tcp_at_95", tcp.get("at_95"))
            out["orientation_span"] = solution.get("orientation_span")
        out["working_points"], out["worst"] = describe(
            [p.name for p in found.points], xyz, at95,
            [{"file": p.file, "line": p.line, "moved": r["moved"]}
             for p, r in zip(found.points, rows)])
    rows.sort(key=lambda r: (-r["moved"], r["file"], r["line"], r["name"]))
    summary = summarize(rows)
    out.update({"points": rows, "points_moved": summary,
                "points_warnings": list(found.warnings), "points_skipped": len(found.skipped)})
    return out


def summarize(rows: list[dict]) -> dict[str, Any]:
    """count, max, mean and worst of rows sorted worst first."""
    if not rows:
        return {"count": 0, "max": None, "mean": None, "worst": None}
    worst = rows[0]
    return {"count": len(rows), "max": worst["moved"],
            "mean": sum(r["moved"] for r in rows) / len(rows), "worst": worst["name"],
            "worst_file": worst["file"], "worst_line": worst["line"]}
