"""Plan a measurement before it is taken: the predicted 95 % error of the
fitted frame at every working point, the worst, a verdict against
--threshold, and what to change (a point to add, a point to drop).

Inputs: PLAN.csv, the planned points (point, laser_x/y/z: the fixture's
nominal references, as in the measurement CSV; optional robot_* columns or
--robot FILE: the planned flange poses, needed for --tcp solve); the noise
(--sigma-laser, --sigma-robot); the working points (--at FILE: point, x, y, z
in the UCS; or --at-taught CONTROLLER --frame NAME: the positions taught in
that frame, as diff --points finds them; default: the determinacy gate's
point --reach mm from the centroid); candidate locations for a further point
(--candidates FILE, default a grid of locations within --margin mm of a
planned point); the noise (--sigma-laser, --sigma-robot, or --history FILE:
the fleet's past residuals; default an uncalibrated robot's, printed in the
first line).

Exit 0 when the worst working point (and with --tcp solve the TCP) is
predicted within the threshold, 1 when not, 2 bad input."""
from __future__ import annotations

import argparse
import os
import sys

from .. import defaults
from ..errors import UcsioError
from ..readers.plan import read_plan  # noqa: F401  (its home: readers.plan)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("plan", metavar="PLAN.csv",
                   help="planned points: point, laser_x/y/z (UCS, mm), optionally robot_* "
                        "(planned flange poses) and weight")
    g = p.add_argument_group("planned flange poses (for --tcp solve)")
    g.add_argument("--robot", metavar="FILE", default=None,
                   help="the measurement program's poses: SPEC CSV, KUKA .dat, ABB module, "
                        "FANUC .ls or posreg.va, paired with the plan's points by name (as "
                        "solve --robot)")
    g.add_argument("--config", metavar="FILE", default=None,
                   help="KUKA $config.dat for TOOL_NO/BASE_NO; ABB: a module declaring "
                        "--robot-tool/--robot-wobj; FANUC: sysframe.va for UF/UT")
    g.add_argument("--robot-tool", metavar="NAME", default="tool0",
                   help="ABB: the tool the robtargets are taught with (default tool0); "
                        "FANUC posreg.va: the registers' tool frame, UTk")
    g.add_argument("--robot-wobj", metavar="NAME", default="wobj0",
                   help="ABB: the work object the robtargets are in (default wobj0); FANUC "
                        "posreg.va: the registers' user frame, UFk")
    g.add_argument("--map", metavar="FILE", default=None,
                   help="CSV of plan,robot name pairs for points whose names differ")
    g.add_argument("--spread", type=float, default=None, metavar="DEG",
                   help="without planned poses: plan the orientations program --measure "
                        "--spread DEG writes (the tool turned by DEG/2 about its x and y "
                        "axes in turn); default the least of 5, 10, ... 90 deg that holds the "
                        "threshold")
    src = p.add_mutually_exclusive_group()
    src.add_argument("--tcp", metavar="X,Y,Z|solve", default=None,
                     help="the reflector on the flange: given (its value does not change the "
                          "prediction) or 'solve' (planned with the frame: needs the flange "
                          "poses, or plans program --measure's --spread)")
    src.add_argument("--tool", metavar="FILE:NAME", default=None,
                     help="the TCP from a robot-held tool in a controller file")
    at = p.add_mutually_exclusive_group()
    at.add_argument("--at", metavar="FILE", default=None,
                    help="working points: CSV of point, x, y, z in the UCS (mm)")
    at.add_argument("--at-taught", metavar="CONTROLLER", default=None,
                    help="working points: the positions taught in --frame in this controller "
                         "file (its tree or folder is searched, as diff --points does), or a "
                         "backup folder holding one sysframe.va or $config.dat")
    p.add_argument("--frame", metavar="NAME", default=None,
                   help="with --at-taught: the frame the positions are taught in (the UCS)")
    p.add_argument("--candidates", metavar="FILE", default=None,
                   help="where a further point could go: CSV of point, x, y, z in the UCS "
                        "(default: a grid of locations within --margin of a planned point)")
    p.add_argument("--margin", type=float, default=defaults.MARGIN, metavar="MM",
                   help="without --candidates: how far from a planned point a further "
                        f"reflector could go (default {defaults.MARGIN:g})")
    p.add_argument("--laser-units", choices=("mm", "m", "in"), default="mm",
                   help="units of the plan's laser coordinates (default mm)")
    p.add_argument("--threshold", type=float, default=defaults.THRESHOLD, metavar="MM",
                   help=f"the worst working point's 95 %% error must be within this "
                        f"(default {defaults.THRESHOLD})")
    p.add_argument("--reach", type=float, default=defaults.REACH, metavar="MM",
                   help="without --at: the generic working point this far from the "
                        f"centroid, as the determinacy gate takes it (default {defaults.REACH:g})")
    p.add_argument("--min-points", type=int, default=defaults.MIN_POINTS, metavar="N",
                   help="solve rejects fewer used points: a plan below it is warned about, and "
                        f"a drop never goes below it (default {defaults.MIN_POINTS})")
    noise = p.add_argument_group("the noise (default: an uncalibrated robot)")
    noise.add_argument("--sigma-laser", type=float, default=None, metavar="MM",
                       help=f"laser noise per axis, mm (default {defaults.SIGMA_LASER})")
    noise.add_argument("--sigma-robot", type=float, default=None, metavar="MM",
                       help=f"robot noise per axis, mm (default {defaults.PLAN_SIGMA_ROBOT}: "
                            "an uncalibrated industrial robot's absolute error, the seed "
                            "paper's mean + one standard deviation over 485 datasets)")
    noise.add_argument("--history", metavar="FILE", default=None,
                       help="take the noise from past results: a batch --json result, a "
                            "SOLUTION.json or a folder of them (the mean + one standard "
                            "deviation of their residual sigma)")


def working_points(at=None, at_taught=None, frame=None):
    """(readers.points.Points or None, warnings): --at (a file, or Points from
    Python), or --at-taught CONTROLLER with --frame."""
    if at is not None and at_taught is not None:
        raise UcsioError("give --at or --at-taught, not both")
    if at_taught is None:
        if frame is not None:
            raise UcsioError("--frame goes with --at-taught CONTROLLER")
        if at is None:
            return None, []
        if isinstance(at, (str, os.PathLike)):
            from ..readers.points import read_points
            return read_points(at), []
        return at, []
    if frame is None:
        raise UcsioError("--at-taught CONTROLLER needs --frame NAME: the frame the positions "
                         "are taught in")
    return taught_points(os.fspath(at_taught), frame)


def taught_points(controller: str, name: str):
    """The positions taught in frame ``name`` of ``controller``, in the frame's
    coordinates, as working points (``ucsio.taught``, as diff --points)."""
    import numpy as np

    from ..parsing.backup import load_one
    from ..readers.points import Points
    from ..review.names import find_frame
    from ..taught import find_points, frames_file_in, in_ucs

    if os.path.isdir(controller):       # a backup folder: its sysframe.va or $config.dat
        controller = frames_file_in(controller)
    cf = load_one(controller)
    frame = find_frame(cf, name)
    found = find_points(cf, frame)
    if not found.points:
        why = "; ".join(found.warnings)
        raise UcsioError(f"no positions taught in {frame.name} found" + (f" ({why})" if why else
                                                                         ""), file=controller)
    xyz = np.array(in_ucs(cf, frame, found), dtype=float)
    pts = found.points
    return (Points(controller, [p.name for p in pts], [p.line for p in pts], xyz,
                   files=[p.file for p in pts]), list(found.warnings))


def plan_measurement(plan, *, robot=None, config=None, map=None, robot_tool: str = "tool0",
                     robot_wobj: str = "wobj0", tcp=None, tool=None, at=None, at_taught=None,
                     frame=None, candidates=None, threshold: float = defaults.THRESHOLD,
                     reach: float = defaults.REACH, min_points: int = defaults.MIN_POINTS,
                     margin: float = defaults.MARGIN, laser_units: str = "mm",
                     sigma_laser: float | None = None, sigma_robot: float | None = None,
                     history=None, spread: float | None = None) -> dict:
    """The command's work, for ``run`` and ``ucsio.api.plan`` alike: --json's
    document. Each keyword is the option of that name; ``tcp`` may also be
    three numbers, ``at`` and ``candidates`` ``readers.points.Points``."""
    import math

    from ..method.plan import plan as plan_points

    sigma_laser, sigma_robot, noise, warnings = plan_noise(sigma_laser, sigma_robot, history)
    for opt, v in (("--threshold", threshold), ("--reach", reach), ("--margin", margin)):
        if not (math.isfinite(v) and v > 0):
            raise UcsioError(f"{opt} {v}: expected a positive number of mm")
    if min_points < 3:
        raise UcsioError(f"--min-points must be at least 3, got {min_points}")
    joint = isinstance(tcp, str) and tcp.strip().casefold() == "solve"
    if tool is not None or tcp is not None:
        from .solve import resolve_tcp
        resolve_tcp(tcp, tool, warnings)    # checked (an unset tool warned about); a known
                                            # TCP's value changes nothing
    planned, more = read_plan(plan, joint, robot=robot, config=config, map=map,
                              robot_tool=robot_tool, robot_wobj=robot_wobj,
                              laser_units=laser_units)
    warnings += more
    points, more = working_points(at, at_taught, frame)
    warnings += more
    planned, spread = planned_spread(planned, joint, spread, at=points, threshold=threshold,
                                     reach=reach, sigma_laser=sigma_laser,
                                     sigma_robot=sigma_robot)
    if isinstance(candidates, (str, os.PathLike)):
        from ..readers.points import read_points
        candidates = read_points(candidates, "candidate file")
    result = plan_points(planned, joint=joint, at=points, candidates=candidates,
                         threshold=threshold, reach=reach, sigma_laser=sigma_laser,
                         sigma_robot=sigma_robot, min_points=min_points, margin=margin)
    result["noise"] = noise
    if spread is not None:
        result["spread"] = spread
    result["warnings"] = warnings + result["warnings"]
    result["source"] = os.fspath(plan)
    if points is not None:
        result["at"] = (f"{os.fspath(at_taught)}:{frame}" if at_taught is not None else
                        os.fspath(at) if isinstance(at, (str, os.PathLike)) else points.path)
    return result


def planned_spread(planned, joint: bool, spread, **judge):
    """(the plan, the spread it takes or None): with --tcp solve and no
    planned flange poses, the orientations ``program --measure --spread``
    writes stand in for them, at --spread or the least spread that holds the
    threshold (``judge``: at, threshold, reach and the noise)."""
    from dataclasses import replace

    from ..method import spread as pattern
    from ..method.plan import least_spread

    if spread is not None:
        pattern.check(spread)
        if not joint:
            raise UcsioError("--spread plans the orientations a TCP solved with the frame "
                             "needs: it goes with --tcp solve")
        if planned.flange is not None:
            raise UcsioError("--spread: the plan gives the flange poses (robot_* columns or "
                             "--robot); the spread is theirs", file=planned.path)
    if not joint or planned.flange is not None:
        return planned, None
    if spread is None:
        spread = least_spread(planned, **judge)
    return replace(planned, flange=pattern.flanges(planned.laser, spread)), float(spread)


def plan_noise(sigma_laser, sigma_robot, history):
    """(σ_laser, σ_robot, the JSON's ``noise``, warnings): the stated noise,
    else the fleet's own (--history), else an uncalibrated robot's. A noise
    of 0 predicts no error at all: refused."""
    import math

    from ..method import solve as solver

    if history is not None:
        if sigma_laser is not None or sigma_robot is not None:
            raise UcsioError("--history takes the noise from past results: give it or "
                             "--sigma-laser/--sigma-robot, not both")
        from ..readers.history import read_history
        h = read_history(history)
        noise = {"sigma": h.sigma, "source": "history", "history": os.fspath(history),
                 "datasets": len(h.sigmas), "mean": h.mean, "std": h.std,
                 "statistic": "mean + 1 sd of the datasets' residual sigma"}
        k = len(h.skipped)
        warnings = [f"--history: skipped {k} JSON file{'s' if k != 1 else ''} that "
                    f"{'is' if k == 1 else 'are'} not a solution or batch result"] if k else []
        if len(h.sigmas) == 1:
            warnings.append("--history: one past dataset: its own residual sigma (one "
                            "measurement says little about a fleet)")
        # the residuals' σ already holds the tracker's share
        return 0.0, h.sigma, noise, warnings
    source = "default" if sigma_laser is None and sigma_robot is None else "stated"
    sigma_laser = defaults.SIGMA_LASER if sigma_laser is None else sigma_laser
    sigma_robot = defaults.PLAN_SIGMA_ROBOT if sigma_robot is None else sigma_robot
    solver.check_sigmas(sigma_laser, sigma_robot)
    sigma = math.hypot(sigma_laser, sigma_robot)
    if sigma == 0:
        raise UcsioError("--sigma-laser 0 and --sigma-robot 0: a plan without noise predicts "
                         "no error at all; state the noise, or take it from --history FILE")
    warnings = []
    if sigma_robot == 0:
        warnings.append("--sigma-robot 0: a robot without noise; the plan is optimistic "
                        "(an uncalibrated robot is about 0.4-0.7 mm per axis)")
    return sigma_laser, sigma_robot, {"sigma": sigma, "source": source,
                                      "sigma_laser": sigma_laser, "sigma_robot": sigma_robot}, \
        warnings


def run(args) -> int:
    from . import options_for
    from ..output import emit_json

    result = plan_measurement(**options_for(plan_measurement, args))
    for w in result["warnings"]:
        print(f"ucsio: warning: {w}", file=sys.stderr)
    if args.json:
        emit_json(result)
    else:
        print(render(result, args), end="")
    return 0 if result["verdict"] == "pass" else 1


SHOWN = 10          # the working points the table shows (the worst)


def render(r: dict, args=None, stream=None) -> str:
    from ..method.plan import from_nearest, location
    from ..output import paint, table

    lines = [f"plan: {r['planned']} points from {r['source']}; noise {r['sigma']:.3f} mm per "
             f"axis ({noise_words(r['noise'])}); threshold {r['threshold']:g} mm"]
    rows = sorted(r["working_points"], key=lambda w: -w["at_95"])
    n = len(rows)
    what = (f"working points: {n} from {r['at']}" if r.get("at") else
            f"working point: the generic one {r['reach']:g} mm from the centroid, across the "
            "least certain rotation axis (--at FILE for yours)")
    lines.append(what + (f"; the {SHOWN} predicted worst:" if n > SHOWN else ":"))
    lines.append(table(["point", "x", "y", "z", "95 % mm"],
                       [[w["name"], f"{w['x']:.1f}", f"{w['y']:.1f}", f"{w['z']:.1f}",
                         f"{w['at_95']:.3f}"] for w in rows[:SHOWN]], right={1, 2, 3, 4}))
    worst = r["worst"]
    lines.append(f"worst: {worst['name']} within {worst['at_95']:.3f} mm (95 %)")
    if "tcp_at_95" in r:
        lines.append(f"tcp: within {r['tcp_at_95']:.3f} mm (95 %); the flange orientations "
                     f"span {r['orientation_span']:.1f} deg")
        if r.get("spread") is not None:
            lines.append(f"spread: the orientations of program --measure --spread "
                         f"{r['spread']:g} (the tool turned by {r['spread'] / 2:g} deg about "
                         "its x and y axes in turn)")
    add, drop = r["suggest"]["add"], r["suggest"]["drop"]
    if add is not None:
        tail = ""
        if "tcp_at_95_after" in add:
            tail = (f", tcp {add['tcp_at_95_after']:.3f} mm (flange held as at "
                    f"{add['orientation_from']})")
        lines.append(f"add:  a point at {location(add)}, {from_nearest(add)}: worst then "
                     f"{add['worst_after']:.3f} mm{tail}")
    if drop is not None:
        tail = (f", tcp {drop['tcp_at_95_after']:.3f} mm" if "tcp_at_95_after" in drop else "")
        lines.append(f"drop: {drop['name']} costs least: worst then {drop['worst_after']:.3f} mm"
                     f"{tail}")
    if r["verdict"] == "pass":
        lines.append(paint("PASS", "pass", stream))
    else:
        advice = f"; {r['advice']}" if r.get("advice") else ""
        lines.append(paint(f"FAIL: {r['reason']}{advice}", "fail", stream))
    return "\n".join(lines) + "\n"


def noise_words(noise: dict) -> str:
    """Where the plan's noise comes from, for its first line."""
    if noise["source"] == "history":
        return (f"from {noise['datasets']} past dataset{'s' if noise['datasets'] != 1 else ''} "
                f"in {noise['history']}: mean {noise['mean']:.3f} + 1 sd {noise['std']:.3f}")
    if noise["source"] == "default":
        return ("an uncalibrated robot, ucsio's default: --sigma-robot or --history FILE for "
                "yours")
    return f"stated: laser {noise['sigma_laser']:g}, robot {noise['sigma_robot']:g}"
