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
(--candidates FILE, default the corners of the box around the planned and
the working points).

Exit 0 when the worst working point (and with --tcp solve the TCP) is
predicted within the threshold, 1 when not, 2 bad input."""
from __future__ import annotations

import argparse
import sys

from .. import defaults
from ..errors import UcsioError


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("plan", metavar="PLAN.csv",
                   help="planned points: point, laser_x/y/z (UCS, mm), optionally robot_* "
                        "(planned flange poses) and weight")
    g = p.add_argument_group("planned flange poses (for --tcp solve)")
    g.add_argument("--robot", metavar="FILE", default=None,
                   help="the measurement program's poses: SPEC CSV, KUKA .dat, ABB module, "
                        "paired with the plan's points by name (as solve --robot)")
    g.add_argument("--config", metavar="FILE", default=None,
                   help="KUKA $config.dat for TOOL_NO/BASE_NO; ABB: a module declaring "
                        "--robot-tool/--robot-wobj")
    g.add_argument("--robot-tool", metavar="NAME", default="tool0",
                   help="ABB: the tool the robtargets are taught with (default tool0)")
    g.add_argument("--robot-wobj", metavar="NAME", default="wobj0",
                   help="ABB: the work object the robtargets are in (default wobj0)")
    g.add_argument("--map", metavar="FILE", default=None,
                   help="CSV of plan,robot name pairs for points whose names differ")
    src = p.add_mutually_exclusive_group()
    src.add_argument("--tcp", metavar="X,Y,Z|solve", default=None,
                     help="the reflector on the flange: given (its value does not change the "
                          "prediction) or 'solve' (planned with the frame: needs the flange "
                          "poses)")
    src.add_argument("--tool", metavar="FILE:NAME", default=None,
                     help="the TCP from a robot-held tool in a controller file")
    at = p.add_mutually_exclusive_group()
    at.add_argument("--at", metavar="FILE", default=None,
                    help="working points: CSV of point, x, y, z in the UCS (mm)")
    at.add_argument("--at-taught", metavar="CONTROLLER", default=None,
                    help="working points: the positions taught in --frame in this controller "
                         "file (its tree or folder is searched, as diff --points does)")
    p.add_argument("--frame", metavar="NAME", default=None,
                   help="with --at-taught: the frame the positions are taught in (the UCS)")
    p.add_argument("--candidates", metavar="FILE", default=None,
                   help="where a further point could go: CSV of point, x, y, z in the UCS "
                        "(default: the corners of the box around the planned and working points)")
    p.add_argument("--threshold", type=float, default=defaults.THRESHOLD, metavar="MM",
                   help=f"the worst working point's 95 %% error must be within this "
                        f"(default {defaults.THRESHOLD})")
    p.add_argument("--reach", type=float, default=defaults.REACH, metavar="MM",
                   help="without --at: the generic working point this far from the "
                        f"centroid, as the determinacy gate takes it (default {defaults.REACH:g})")
    p.add_argument("--min-points", type=int, default=defaults.MIN_POINTS, metavar="N",
                   help="solve rejects fewer used points: a plan below it is warned about, and "
                        f"a drop never goes below it (default {defaults.MIN_POINTS})")
    p.add_argument("--sigma-laser", type=float, default=defaults.SIGMA_LASER, metavar="MM",
                   help=f"laser noise per axis, mm (default {defaults.SIGMA_LASER})")
    p.add_argument("--sigma-robot", type=float, default=defaults.SIGMA_ROBOT, metavar="MM",
                   help=f"robot noise per axis, mm (default {defaults.SIGMA_ROBOT})")


def read_plan(args, joint: bool):
    """(method.plan.Planned, warnings) from PLAN.csv and --robot."""
    import numpy as np

    from ..files import read_bytes
    from ..method.plan import Planned
    from ..readers.text import content_lines, decode

    text = decode(read_bytes(args.plan, "plan file"))
    has_robot = any("robot_x" in line.lower() for _, line in content_lines(text)[:2])
    warnings: list[str] = []
    if has_robot and args.robot is not None:
        raise UcsioError("the plan has robot_* columns and --robot is given: plan the flange "
                         "poses once", file=args.plan)
    for opt, given in (("--config", args.config), ("--map", args.map)):
        if given is not None and args.robot is None:
            raise UcsioError(f"{opt} goes with --robot")
    if has_robot:
        from ..method.measurement import parse_measurement
        m = parse_measurement(text, args.plan)
        return Planned(args.plan, m.names, m.lines, m.laser, m.weights, m.flange), warnings
    from ..readers import laser
    lp = laser.read_laser(args.plan)
    if args.robot is None:
        return Planned(args.plan, lp.names, lp.lines, lp.xyz, lp.weights), list(lp.warnings)
    if not joint:
        warnings.append("--robot: the planned flange poses matter only with --tcp solve (a "
                        "known TCP's frame error does not depend on them); not read")
        return Planned(args.plan, lp.names, lp.lines, lp.xyz, lp.weights), warnings
    from ..readers import pairing, robot
    rp = robot.read_robot(args.robot, config=args.config, tool=args.robot_tool,
                          wobj=args.robot_wobj)
    mapping = pairing.read_map(args.map) if args.map else ()
    m, more = pairing.pair(lp, rp, mapping, args.map)
    return (Planned(args.plan, m.names, m.lines, m.laser, m.weights,
                    np.asarray(m.flange, dtype=float)), warnings + more)


def working_points(args):
    """(readers.points.Points or None, warnings): --at, or --at-taught."""
    if args.at_taught is None:
        if args.frame is not None:
            raise UcsioError("--frame goes with --at-taught CONTROLLER")
        if args.at is None:
            return None, []
        from ..readers.points import read_points
        return read_points(args.at), []
    if args.frame is None:
        raise UcsioError("--at-taught CONTROLLER needs --frame NAME: the frame the positions "
                         "are taught in")
    return taught_points(args.at_taught, args.frame)


def taught_points(controller: str, name: str):
    """The positions taught in frame ``name`` of ``controller``, in the frame's
    coordinates, as working points (``ucsio.taught``, as diff --points)."""
    import numpy as np

    from ..parsing.backup import load_one
    from ..readers.points import Points
    from ..review.names import find_frame
    from ..taught import find_points, in_ucs

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


def run(args) -> int:
    import math

    from ..method import solve as solver
    from ..method.plan import plan
    from ..output import emit_json

    solver.check_sigmas(args.sigma_laser, args.sigma_robot)
    for opt, v in (("--threshold", args.threshold), ("--reach", args.reach)):
        if not (math.isfinite(v) and v > 0):
            raise UcsioError(f"{opt} {v}: expected a positive number of mm")
    if args.min_points < 3:
        raise UcsioError(f"--min-points must be at least 3, got {args.min_points}")
    joint = args.tcp is not None and args.tcp.strip().casefold() == "solve"
    if args.tool:
        from .solve import tool_tcp
        tool_tcp(args.tool)                 # checked; a known TCP's value changes nothing
    elif args.tcp is not None and not joint:
        from .solve import parse_tcp
        parse_tcp(args.tcp)
    planned, warnings = read_plan(args, joint)
    at, more = working_points(args)
    warnings += more
    candidates = None
    if args.candidates is not None:
        from ..readers.points import read_points
        candidates = read_points(args.candidates, "candidate file")
    result = plan(planned, joint=joint, at=at, candidates=candidates,
                  threshold=args.threshold, reach=args.reach, sigma_laser=args.sigma_laser,
                  sigma_robot=args.sigma_robot, min_points=args.min_points)
    result["warnings"] = warnings + result["warnings"]
    result["source"] = args.plan
    if at is not None:
        result["at"] = args.at or f"{args.at_taught}:{args.frame}"
    for w in result["warnings"]:
        print(f"ucsio: warning: {w}", file=sys.stderr)
    if args.json:
        emit_json(result)
    else:
        print(render(result, args), end="")
    return 0 if result["verdict"] == "pass" else 1


SHOWN = 10          # the working points the table shows (the worst)


def render(r: dict, args=None, stream=None) -> str:
    from ..output import paint, table

    lines = [f"plan: {r['planned']} points from {r['source']}; noise {r['sigma']:.3f} mm per "
             f"axis; threshold {r['threshold']:g} mm"]
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
    add, drop = r["suggest"]["add"], r["suggest"]["drop"]
    if add is not None:
        where = f"{add['x']:.1f}, {add['y']:.1f}, {add['z']:.1f}"
        tail = ""
        if "tcp_at_95_after" in add:
            tail = (f", tcp {add['tcp_at_95_after']:.3f} mm (flange held as at "
                    f"{add['orientation_from']})")
        lines.append(f"add:  a point at {add['name']} ({where}): worst then "
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
