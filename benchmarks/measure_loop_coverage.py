"""How often the plan's stated 95 % holds over the whole measurement loop
(issue 28 point 2): plan -> program --measure -> a tracker simulated with
the true frame and the planned noise -> solve with the program as the robot
side. Not speed: the counts behind the tests' "at least 15 of 20".

    python benchmarks/measure_loop_coverage.py                 # 2,000 trials a vendor
    python benchmarks/measure_loop_coverage.py --trials 8000 --vendor fanuc
    python benchmarks/measure_loop_coverage.py --joint         # the TCP solved too

The cells are the tests' (tests/test_measure_program.py ``LOOPS``, one per
vendor with a writer; tests/test_measure_spread.py for ``--joint``: the TCP
2.9 mm off the nominal one the program aims with, the plan's own spread).
Each trial draws the robot's noise (0.2 mm per axis) and the tracker's
(0.02 mm), solves without exclusion, and asks whether the true frame's
working point (and with --joint the true TCP) lies within the plan's 95 %.
Printed: the fraction within, with its binomial standard error; a stated
95 % holds where the fraction is 0.95 within about two of them (or above:
a prediction may be cautious, never bold).
"""
from __future__ import annotations

import argparse
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))      # this checkout's ucsio, not an installed one
sys.path.insert(0, str(ROOT / "tests"))    # the tests' cells

import test_measure_program as fixed  # noqa: E402
import test_measure_spread as joint  # noqa: E402
from ucsio import api  # noqa: E402
from ucsio.cli import main  # noqa: E402
from ucsio.readers.robot import read_robot  # noqa: E402

SIGMA_LASER, SIGMA_ROBOT = 0.02, 0.2
TRUE_OFFSET = (1.2, -0.9, 0.5, 0.05, -0.08, 0.06)      # the true frame from the simulated one
WORK = np.array([450.0, 350.0, 60.0, 1.0])


def cell_folder() -> Path:
    cell = Path(tempfile.mkdtemp(prefix="ucsio-loop-"))
    (cell / "sysframe.va").write_bytes(
        fixed.SYSFRAME.format(*fixed.UF1, *fixed.UT1).replace("\n", "\r\n").encode())
    (cell / "at.csv").write_text("point,x,y,z\nW1,450,350,60\n")
    return cell


def tracker(cell: Path, flanges: dict, tcp, true, rng) -> Path:
    rows = []
    for name, flange in flanges.items():
        reflector = (flange @ np.append(tcp, 1.0))[:3] + rng.normal(0, SIGMA_ROBOT, 3)
        seen = (np.linalg.inv(true) @ np.append(reflector, 1.0))[:3]
        seen += rng.normal(0, SIGMA_LASER, 3)
        rows.append(f"{name},{seen[0]:.4f},{seen[1]:.4f},{seen[2]:.4f}\n")
    laser = cell / "tracker.csv"
    laser.write_text("point,x,y,z\n" + "".join(rows))
    return laser


def made(argv: list[str]) -> dict:
    """``program --measure --json``'s read_back: how solve reads the program."""
    import contextlib
    import io
    import json
    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        assert main(argv) == 0
    return json.loads(buffer.getvalue())["measurement_program"]["read_back"]


def fixed_loop(vendor: str, trials: int, seed: int) -> tuple[int, int]:
    cell = cell_folder()
    controller, frame, tool, name, frame_values, tool_values, config, names = \
        fixed.LOOPS[vendor]
    controller = controller.format(cell=cell)
    tool_spec = tool if ":" in tool else f"{controller}:{tool}"
    points = {names.format(k=k): xyz for k, xyz in enumerate(joint.POINTS)}
    plan = cell / "loop.csv"
    plan.write_text("point,laser_x,laser_y,laser_z\n" +
                    "".join(f"{n},{x},{y},{z}\n" for n, (x, y, z) in points.items()))
    at_95 = api.plan(plan, at=cell / "at.csv", tool=tool_spec, sigma_laser=SIGMA_LASER,
                     sigma_robot=SIGMA_ROBOT).as_dict()["working_points"][0]["at_95"]
    side = made(["program", "--measure", str(plan), controller, "--frame", frame, "--tool",
                 tool, "-o", str(cell / name), "--json"])
    out = side["robot"]                    # as the program says solve reads it
    options = {"robot_tool": side.get("robot_tool", "tool0"),
               "robot_wobj": side.get("robot_wobj", "wobj0")}
    robot = read_robot(out, config=side["config"], tool=options["robot_tool"],
                       wobj=options["robot_wobj"])
    by_point = {p.point: p.flange for p in robot.poses}
    flanges = {n: by_point[n] for n in points}
    true = fixed.matrix(*frame_values) @ fixed.matrix(*TRUE_OFFSET)
    rng = np.random.default_rng(seed)
    within = 0
    for _ in range(trials):
        laser = tracker(cell, flanges, tool_values[:3], true, rng)
        got = api.solve(laser=laser, robot=out, config=side["config"], tool=side["tool"],
                        no_exclusion=True, **options).as_dict()
        measured = np.asarray(got["frame"]["matrix"])
        within += np.linalg.norm((measured @ WORK - true @ WORK)[:3]) <= at_95
    return within, trials


def joint_loop(trials: int, seed: int) -> tuple[tuple[int, int], int]:
    cell = cell_folder()
    (cell / "plan.csv").write_text(
        "point,laser_x,laser_y,laser_z\n" +
        "".join(f"M{k},{x},{y},{z}\n" for k, (x, y, z) in enumerate(joint.POINTS)))
    planned = api.plan(cell / "plan.csv", tcp="solve", at=cell / "at.csv",
                       sigma_laser=SIGMA_LASER, sigma_robot=SIGMA_ROBOT).as_dict()
    at_95, tcp_95 = planned["working_points"][0]["at_95"], planned["tcp_at_95"]
    out = cell / "LOOP.LS"
    assert main(["program", "--measure", str(cell / "plan.csv"), str(cell / "sysframe.va"),
                 "--frame", "UF1", "--tcp", ",".join(map(str, joint.NOMINAL)), "--spread",
                 f"{planned['spread']:g}", "-o", str(out)]) == 0
    robot = read_robot(out, config=str(cell / "sysframe.va"))
    flanges = {p.point: p.flange for p in robot.poses if not p.point.endswith(" UP")}
    true = fixed.matrix(*fixed.UF1) @ fixed.matrix(*TRUE_OFFSET)
    true_tcp = np.add(joint.NOMINAL, (2.0, -1.5, 1.4))
    rng = np.random.default_rng(seed)
    frame_in = tcp_in = 0
    for _ in range(trials):
        laser = tracker(cell, flanges, true_tcp, true, rng)
        got = api.solve(laser=laser, robot=out, config=cell / "sysframe.va", tcp="solve",
                        no_exclusion=True, sigma_laser=SIGMA_LASER,
                        sigma_robot=SIGMA_ROBOT).as_dict()
        measured = np.asarray(got["frame"]["matrix"])
        frame_in += np.linalg.norm((measured @ WORK - true @ WORK)[:3]) <= at_95
        t = got["tcp"]
        tcp_in += np.linalg.norm(np.array([t["x"], t["y"], t["z"]]) - true_tcp) <= tcp_95
    return (frame_in, tcp_in), trials


def line(what: str, within: int, trials: int) -> str:
    p = within / trials
    se = math.sqrt(0.95 * 0.05 / trials)
    return (f"{what:28s} {within:6d} of {trials:6d} within the plan's 95 %: {100 * p:5.2f} % "
            f"(+-{100 * se:.2f}; {(p - 0.95) / se:+.1f} se from 95 %)")


def main_(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--trials", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=28)
    ap.add_argument("--vendor", action="append", choices=sorted(fixed.LOOPS))
    ap.add_argument("--joint", action="store_true", help="the TCP solved with the frame")
    args = ap.parse_args(argv)
    if args.joint:
        (frame_in, tcp_in), n = joint_loop(args.trials, args.seed)
        print(line("joint: frame at W1", frame_in, n))
        print(line("joint: TCP", tcp_in, n))
        return 0
    for vendor in args.vendor or sorted(fixed.LOOPS):
        print(line(f"{vendor}: frame at W1", *fixed_loop(vendor, args.trials, args.seed)))
    return 0


if __name__ == "__main__":
    sys.exit(main_())
