"""Fit the measured UCS to laser/robot point pairs (Horn's closed form),
with leave-one-out outlier exclusion.

Inputs: MEAS.csv (laser and robot sides in one CSV), or --laser FILE and
--robot FILE (the files they live in, paired by point name); and the TCP:
--tcp X,Y,Z, --tool FILE:NAME or --tcp solve.

Exit 0 accepted; 1 rejected (fewer than --min-points left after exclusion,
or points that do not pin the frame down: the reason is printed); 2 bad
input. -o writes the solution JSON that diff and patch read."""
from __future__ import annotations

import argparse
import os
import sys

from . import add_uncertainty_options
from .. import defaults
from ..errors import UcsioError
from ..files import atomic_write_text
from ..readers.options import check_tcp, parse_tcp  # noqa: F401  (their home: readers.options)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("measurement", metavar="MEAS.csv", nargs="?", default=None,
                   help="measurement CSV: point, laser_x/y/z, robot_x/y/z, the flange orientation "
                        "(robot_a/b/c, robot_q1..q4 or robot_w/p/r), weight (docs/"
                        "measurements.md); - for standard input; or --laser and --robot")
    add_source_options(p)
    src = p.add_mutually_exclusive_group()
    src.add_argument("--tcp", metavar="X,Y,Z|solve", default=None,
                     help="reflector position in flange coordinates, mm (required unless "
                          "--tool: 0,0,0 says the points are flange positions); 'solve' "
                          "estimates it with the frame (needs varied flange orientations)")
    src.add_argument("--tool", metavar="FILE:NAME", default=None,
                     help="take the TCP from a robot-held tool in a controller file")
    p.add_argument("--threshold", type=float, default=defaults.THRESHOLD, metavar="MM",
                   help="leave-one-out residual above which a point is excluded "
                        f"(default {defaults.THRESHOLD})")
    p.add_argument("--min-points", type=int, default=defaults.MIN_POINTS, metavar="N",
                   help=f"fewer used points than this rejects the dataset (default {defaults.MIN_POINTS})")
    p.add_argument("--exclude", action="append", default=[], metavar="NAME",
                   help="drop this point by hand (repeatable)")
    p.add_argument("--no-exclusion", action="store_true", help="keep every point")
    p.add_argument("--reach", type=float, default=defaults.REACH, metavar="MM",
                   help="the determinacy gate judges the 95 %% displacement of a point this far "
                        f"from the points' centroid against --threshold (default {defaults.REACH:g})")
    add_working_point_options(p)
    add_three_point_options(p)
    add_uncertainty_options(p, "of the frame")
    p.add_argument("-o", "--output", metavar="SOLUTION.json", default=None,
                   help="write the result as JSON (atomically); - for standard output "
                        "(the table then goes to stderr)")


def add_working_point_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--at", metavar="FILE", default=None,
                   help="working points (CSV of point, x, y, z in the UCS, mm): the solution "
                        "predicts the 95 %% error of the frame at each")
    p.add_argument("--gate", choices=("reach", "at"), default="reach",
                   help="what the determinacy gate judges: the generic point --reach mm from "
                        "the centroid (default), or the worst working point of --at")


def add_three_point_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--three-point-distance", type=float, default=200.0, metavar="MM",
                   help="how far the +X and XY points that set the measured frame by hand lie "
                        "from its origin (default 200)")
    p.add_argument("--reach-box", metavar="XMIN,XMAX,YMIN,YMAX,ZMIN,ZMAX", default=None,
                   help="where the robot reaches (robot base, mm): the three points move "
                        "inside it along the frame's axes, and the offset to take back is "
                        "stated (docs/measurements.md)")


def add_source_options(p: argparse.ArgumentParser) -> None:
    """--laser/--robot and what the robot side needs: the two sides of a
    measurement from the files they live in (ucsio.readers)."""
    g = p.add_argument_group("measurements where they live (instead of MEAS.csv)")
    g.add_argument("--laser", metavar="FILE", default=None,
                   help="laser tracker points: SPEC CSV, SpatialAnalyzer ASCII export, or a "
                        "name x y z table")
    g.add_argument("--laser-units", choices=("mm", "m", "in"), default="mm",
                   help="units of the laser coordinates, in the laser file or MEAS.csv "
                        "(default mm)")
    g.add_argument("--angle-units", choices=("deg", "rad"), default="deg",
                   help="units of a CSV's robot_a/b/c or robot_w/p/r (default deg)")
    g.add_argument("--quaternion-order", choices=("wxyz", "xyzw"), default="wxyz",
                   help="order of a CSV's robot_q1..q4: wxyz, the real part first as ABB "
                        "writes it (default), or xyzw")
    g.add_argument("--robot", metavar="FILE", default=None,
                   help="flange poses: SPEC CSV (robot_* columns), a KUKA program .dat "
                        "(E6POS/POS/FRAME with FDAT), an ABB module (robtargets), a FANUC TP "
                        "program .ls (/POS) or posreg.va, a Yaskawa job .JBI (//POS)")
    g.add_argument("--config", metavar="FILE", default=None, action="append",
                   help="KUKA $config.dat for the positions' TOOL_NO/BASE_NO; ABB: a module "
                        "declaring --robot-tool/--robot-wobj; FANUC: sysframe.va for UF/UT; "
                        "Yaskawa: TOOL.CND, and a second --config UFRAME.CND for USER positions")
    g.add_argument("--robot-tool", metavar="NAME", default="tool0",
                   help="ABB: the tool the robtargets were taught with (default tool0); "
                        "FANUC posreg.va: the registers' tool frame, UTk")
    g.add_argument("--robot-wobj", metavar="NAME", default="wobj0",
                   help="ABB: the work object the robtargets are in (default wobj0); FANUC "
                        "posreg.va: the registers' user frame, UFk")
    g.add_argument("--map", metavar="FILE", default=None,
                   help="CSV of laser,robot name pairs for points whose names differ")


def read_inputs(measurement=None, laser=None, robot=None, *, laser_units: str = "mm",
                config=None, robot_tool: str = "tool0", robot_wobj: str = "wobj0", map=None,
                angle_units: str = "deg", quaternion_order: str = "wxyz"):
    """(Measurement, warnings) from MEAS.csv or from --laser and --robot."""
    both = laser is not None and robot is not None
    if measurement is not None and (laser is not None or robot is not None):
        raise UcsioError("give MEAS.csv or --laser and --robot, not both")
    if measurement is None:
        if not both:
            missing = "--robot" if laser is not None else (
                "--laser" if robot is not None else "MEAS.csv (or --laser and --robot)")
            raise UcsioError(f"solve needs {missing}")
        from ..readers import laser as lasers, pairing, robot as robots
        lp = lasers.read_laser(laser, laser_units)
        rp = robots.read_robot(robot, config=config, tool=robot_tool, wobj=robot_wobj,
                               angle_units=angle_units, quaternion_order=quaternion_order)
        mapping = pairing.read_map(map) if map else ()
        return pairing.pair(lp, rp, mapping, map)
    for opt, given in (("--map", map), ("--config", config)):
        if given is not None:
            raise UcsioError(f"{opt} goes with --laser and --robot")
    from ..readers.measurement import read_measurement
    return read_measurement(measurement, laser_units=laser_units, angle_units=angle_units,
                            quaternion_order=quaternion_order), []


def resolve_tcp(tcp, tool, warnings: list | None = None
                ) -> tuple[tuple[float, float, float] | None, bool]:
    """(the TCP, whether it is solved with the frame) from ``--tcp`` (text
    X,Y,Z or ``solve``; from Python also three numbers) or ``--tool
    FILE:NAME``; neither is an error that names the three options.
    ``warnings`` gets what the user must read (an unset tool)."""
    if tool is not None and tcp is not None:
        raise UcsioError("give --tcp or --tool, not both")
    if tool is not None:
        return tool_tcp(tool, warnings), False
    if isinstance(tcp, str):
        if tcp.strip().casefold() == "solve":
            return None, True
        return parse_tcp(tcp), False
    if tcp is not None:
        return check_tcp(tcp, repr(tcp)), False
    from ..method.solve import NO_TCP
    raise UcsioError(NO_TCP)


def tool_tcp(spec: str, warnings: list | None = None) -> tuple[float, float, float]:
    """``FILE:NAME`` -> the translation of a robot-held tool (split at the
    last ':', so ``C:\\cell\\x.mod:tool1`` works); an unset tool (the
    controller's default) adds its warning to ``warnings``."""
    file, sep, name = spec.rpartition(":")
    if not sep or not file or not name:
        raise UcsioError(f"--tool {spec!r}: expected FILE:NAME")
    from ..parsing.controller import load
    from ..geometry.frames import tool_tcp as tcp_of
    from ..review.names import find_frame
    from ..review.unset import is_set, tool_warning
    cf = load(file)
    frame = find_frame(cf, name)
    tcp = tcp_of(frame, "--tool")
    if warnings is not None and not is_set(frame, cf):
        warnings.append(tool_warning(frame))
    return tcp


def solve(measurement=None, *, laser=None, robot=None, laser_units: str = "mm", config=None,
          robot_tool: str = "tool0", robot_wobj: str = "wobj0", map=None, tcp=None, tool=None,
          threshold: float = defaults.THRESHOLD, min_points: int = defaults.MIN_POINTS,
          exclude=(), no_exclusion: bool = False, reach: float = defaults.REACH, at=None,
          gate: str = "reach", uncertainty: int = 0,
          sigma_laser: float = defaults.SIGMA_LASER, sigma_robot: float = defaults.SIGMA_ROBOT,
          seed: int = 0, angle_units: str = "deg", quaternion_order: str = "wxyz",
          three_point_distance: float = 200.0, reach_box=None):
    """The command's work, for ``run`` and ``ucsio.api.solve`` alike: (the
    solver's Solution, --json's document without ``schema_version``, the
    readers' warnings). Each keyword is the option of that name; ``at`` may
    also be ``readers.points.Points``; ``reach_box`` also six numbers."""
    from ..method import solve as solver
    from ..method import three_points

    if uncertainty and uncertainty < 2:
        raise UcsioError("--uncertainty N: needs at least 2 samples")
    if uncertainty:
        solver.check_sigmas(sigma_laser, sigma_robot)
    tool_warnings: list[str] = []
    fixed, solve_tcp = resolve_tcp(tcp, tool, tool_warnings)
    three_point_distance = three_points.check_distance(three_point_distance)
    box = three_points.parse_box(reach_box)
    solver.check_sigmas(sigma_laser, sigma_robot)
    points = at
    if isinstance(at, (str, os.PathLike)):
        from ..readers.points import read_points
        points = read_points(at)
    solver.check_gate(gate, points)
    meas, warnings = read_inputs(measurement, laser, robot, laser_units=laser_units,
                                 config=config, robot_tool=robot_tool, robot_wobj=robot_wobj,
                                 map=map, angle_units=angle_units,
                                 quaternion_order=quaternion_order)
    warnings = tool_warnings + warnings
    settings = dict(threshold=threshold, min_points=min_points, no_exclusion=no_exclusion,
                    reach=reach, sigma_laser=sigma_laser, sigma_robot=sigma_robot)
    exclude = list(exclude or ())

    def fit(m):
        if solve_tcp:
            from ..method.tcp_solve import solve_joint
            return solve_joint(m, exclude=exclude, at=points, gate=gate, **settings)
        return solver.solve(m, fixed, exclude=exclude, tool=tool, at=points, gate=gate,
                            **settings)

    sol = fit(meas)
    if not sol.accepted:            # a unit or order mistake is named, not "measure again"
        from ..method.mistakes import Reading, named_mistake
        mistake = named_mistake(meas, sol, fit, Reading(laser_units, angle_units,
                                                        quaternion_order))
        if mistake is not None:
            raise mistake
    if not solve_tcp and not sol.accepted:
        from ..method.tcp_solve import diagnose
        sol.diagnosis = diagnose(meas, sol, **settings)
        if sol.diagnosis:
            sol.reason = f"{sol.reason}; but {sol.diagnosis['message']}"
    if sol.working_points is not None:
        sol.at_source = os.fspath(at) if isinstance(at, (str, os.PathLike)) else \
            getattr(points, "path", None)
    if uncertainty and solve_tcp:
        from ..method.tcp_solve import uncertainty as joint_uncertainty
        sol.uncertainty = joint_uncertainty(meas, sol, uncertainty, sigma_laser, sigma_robot,
                                            seed)
    elif uncertainty:
        solver.solution_uncertainty(meas, sol, uncertainty, sigma_laser, sigma_robot, seed)
    by_three_points(meas, sol, points, reach, three_point_distance, box)
    result = sol.as_dict()
    result["warnings"] = warnings + result["warnings"]
    return sol, result, warnings


def by_three_points(meas, sol, points, reach: float, distance: float, box) -> None:
    """The pendant's 3-point view of a fit (``method.three_points``): the
    frame three of the measured points give, beside the fit; and, for an
    accepted fit, the three points that set it by hand."""
    import numpy as np
    from ..method import three_points

    R = np.array(sol.pose.matrix, dtype=float)
    t = np.array(sol.pose.t, dtype=float)
    used = np.array([p.used for p in sol.points])
    sol.three_point_frame = three_points.compare(meas.names, meas.laser,
                                                 meas.robot_points(sol.tcp), meas.weights,
                                                 used, R, t, reach, points)
    if sol.accepted:
        sol.three_points = three_points.setting(R, t, distance, sol.tcp, sol.tool, box)


def run(args) -> int:
    from . import options_for
    from ..method.solution import solution_text
    from ..output import emit_json

    to_stdout = args.output == "-"
    if args.output is not None and not to_stdout:
        folder = os.path.dirname(os.path.abspath(args.output))
        if not os.path.isdir(folder):
            raise UcsioError(f"-o {args.output}: folder {folder} does not exist")
    sol, result, warnings = solve(**options_for(solve, args))
    for w in warnings:
        print(f"ucsio: warning: {w}", file=sys.stderr)

    if to_stdout:                  # -o -: the solution is the data on stdout
        emit_json(result)
        if not args.json:
            print(render(sol, sys.stderr), end="", file=sys.stderr)
        return 0 if sol.accepted else 1
    if args.output is not None:
        atomic_write_text(args.output, solution_text(result))  # errors: one UcsioError

    if args.json:
        emit_json(result)
    else:
        print(render(sol), end="")
    if args.output is not None:
        print(f"wrote {args.output}", file=sys.stderr)
    return 0 if sol.accepted else 1


def render(sol, stream=None) -> str:
    """The readable report; the verdict coloured when ``stream`` (default
    stdout) is a terminal."""
    from ..output import fmt, paint, table

    f = sol.pose
    a, b, c = f.abc
    w, p, r = f.wpr
    lines = [f"measured frame (UCS in robot world) from {sol.source}",
             f"  tcp     {fmt(sol.tcp[0])}, {fmt(sol.tcp[1])}, {fmt(sol.tcp[2])}"
             + (f"  (tool {sol.tool})" if sol.tool else "") + _solved(sol),
             f"  x y z   {f.x:.3f}  {f.y:.3f}  {f.z:.3f}",
             f"  a b c   {a:.4f}  {b:.4f}  {c:.4f}   (KUKA)",
             f"  q       [{', '.join(f'{v:.6f}' for v in f.q)}]   (ABB)",
             f"  w p r   {w:.4f}  {p:.4f}  {r:.4f}   (Fanuc)",
             "  matrix"]
    for row in sol.matrix4:
        lines.append("    " + "  ".join(f"{v:12.6f}" for v in row))
    lines.append("")
    rows = []
    for pt in sol.points:
        used = "yes" if pt.used else f"no ({pt.excluded_by})"
        rows.append([pt.name, fmt(pt.dx), fmt(pt.dy), fmt(pt.dz), fmt(pt.residual),
                     fmt(pt.loo_residual if pt.loo_residual == pt.loo_residual else None), used])
    lines.append(table(["point", "dx", "dy", "dz", "|d|", "leave-one-out", "used"], rows,
                       right={1, 2, 3, 4, 5}))
    lines.append("")
    lines.append(f"n {sol.n_used} of {sol.n_points} used   rms {sol.rms:.3f}   mean {sol.mean:.3f}"
                 f"   max {sol.max:.3f} mm   (threshold {sol.threshold:g} mm,"
                 f" min points {sol.min_points})")
    if sol.precision:
        pr = sol.precision
        lines.append(f"precision: a point {pr['reach']:g} mm from the centroid within "
                     f"{pr['at_reach']:.3f} mm (95 %), orientation ±{pr['angle_std']:.4f} deg, "
                     f"noise {pr['sigma']:.3f} mm per axis")
    if sol.working_points is not None:
        lines.append(working_points_text(sol.working_points, sol.worst,
                                         sol.at_source, sol.gate))
    if sol.consistency and sol.consistency.get("message"):
        lines.append(f"noise check: {sol.consistency['message']}")
    if sol.uncertainty:
        u = sol.uncertainty
        s, ci, an = u["std"], u["ci95"], u["analytical_std"]
        scaled = (" (scaled up to the residuals' noise)"
                  if u.get("sigma_source") == "residuals" else "")
        lines.append(f"uncertainty ({u['samples']} samples, sigma laser {u['sigma_laser']:.4g},"
                     f" robot {u['sigma_robot']:.4g} mm{scaled}):")
        urows = [[k, "deg" if k == "angle" else "mm", f"{s[k]:.4f}",
                  f"[{ci[k][0]:.4f}, {ci[k][1]:.4f}]", f"{an[k]:.4f}"]
                 for k in ("x", "y", "z", "angle")]
        lines.append(table(["", "unit", "std", "ci95", "analytical std"], urows, right={2, 4}))
    if sol.three_point_frame:
        lines.append(three_point_frame_text(sol.three_point_frame))
    if sol.three_points:
        lines.append(three_points_text(sol.three_points))
    lines.extend(f"warning: {w}" for w in sol.warnings)
    if sol.diagnosis:                 # not the measurement's fault: no "measure again"
        lines.append(paint(f"REJECTED: {sol.reason}", "fail", stream))
    else:
        lines.append(paint("accepted", "pass", stream) if sol.accepted else
                     paint(f"REJECTED: {sol.reason}; measure again", "fail", stream))
    return "\n".join(lines) + "\n"


def working_points_text(rows, worst, source=None, gate: str = "reach", shown: int = 10) -> str:
    """The working points' predicted errors: the worst ``shown``, and the worst."""
    from ..output import table

    order = sorted(rows, key=lambda r: -r["at_95"])
    head = (f"working points{f' from {source}' if source else ''}: {len(rows)}"
            + (f"; the {shown} predicted worst" if len(rows) > shown else "")
            + (" (the determinacy gate judges the worst: --gate at)" if gate == "at" else ""))
    body = table(["point", "x", "y", "z", "95 % mm"],
                 [[r["name"], f"{r['x']:.1f}", f"{r['y']:.1f}", f"{r['z']:.1f}",
                   f"{r['at_95']:.3f}"] for r in order[:shown]], right={1, 2, 3, 4})
    tail = f"worst working point: {worst['name']} within {worst['at_95']:.3f} mm (95 %)" \
        if worst else "no working points"
    return f"{head}\n{body}\n{tail}"


def three_point_frame_text(tp: dict, shown: int = 10) -> str:
    """The pendant's frame from three measured points beside the best fit."""
    from ..output import table

    f = tp["frame"]
    org, xx, xy = (p["name"] for p in tp["points"])
    rows = sorted(tp["working_points"], key=lambda r: -r["dist"])[:shown]
    body = table(["working point", "x", "y", "z", "apart mm"],
                 [[r["name"], f"{r['x']:.1f}", f"{r['y']:.1f}", f"{r['z']:.1f}",
                   f"{r['dist']:.3f}"] for r in rows], right={1, 2, 3, 4})
    return "\n".join([
        f"three-point frame (a pendant's construction from {org} origin, {xx} +X, {xy} XY):",
        f"  x y z   {f['x']:.3f}  {f['y']:.3f}  {f['z']:.3f}",
        f"  a b c   {f['a']:.4f}  {f['b']:.4f}  {f['c']:.4f}   (KUKA)",
        f"  from the best fit: origin {tp['dist']:.3f} mm, axes {tp['angle']:.4f} deg; "
        "where the two frames put the working points:", body])


def three_points_text(sp: dict) -> str:
    """The three TCP positions that set the measured frame on a pendant."""
    from ..output import fmt, table

    tcp = sp["tcp"]
    tool = f" (tool {tcp['tool']})" if tcp["tool"] else ""
    body = table(["point", "x", "y", "z"],
                 [[p["role"], f"{p['x']:.3f}", f"{p['y']:.3f}", f"{p['z']:.3f}"]
                  for p in sp["points"]], right={1, 2, 3})
    lines = [f"to set the measured frame by its three points ({sp['distance']:g} mm apart; "
             f"robot base, positions of the TCP {fmt(tcp['x'])}, {fmt(tcp['y'])}, "
             f"{fmt(tcp['z'])}{tool}):", body]
    if sp["moved"]:
        o = sp["offset"]
        lines.append(f"  moved into the reach box: these give the measured orientation with the "
                     f"origin at {o['x']:.3f}, {o['y']:.3f}, {o['z']:.3f} in the measured frame; "
                     f"take the origin back by {-o['x']:.3f}, {-o['y']:.3f}, {-o['z']:.3f} "
                     "along the frame's own axes")
    return "\n".join(lines)


def _solved(sol) -> str:
    """'  (solved with the frame, std 0.05 0.06 0.08 mm)' for --tcp solve."""
    t = sol.tcp_solved
    if not t:
        return ""
    std = t["std"]
    return (f"  (solved with the frame; std {std['x']:.3f} {std['y']:.3f} {std['z']:.3f} mm, "
            f"95 % within {t['at_95']:.3f} mm)")
