"""Small synthetic solutions for ``ucsio view``'s tests and docs/view.md's
pictures: a known frame, ten points, and one mistake each."""
from __future__ import annotations

import contextlib
import io
import math

from ucsio.cli import main

TRUTH = dict(x=1500.0, y=-250.0, z=600.0, a=30.0, b=-2.5, c=1.2)     # KUKA A B C, degrees
LASER = [(0, 0, 0), (1200, 0, 10), (1200, 800, 0), (0, 800, 20), (600, 400, 300),
         (300, 100, 150), (900, 700, 250), (100, 600, 320), (1100, 300, 60), (650, 50, 200)]
KRL = ("DEFDAT  $CONFIG\nDECL FRAME BASE_DATA[3]\n"
       "BASE_DATA[3]={{X {x},Y {y},Z {z},A {a},B {b},C {c}}}\nENDDAT\n")


def matrix(a, b, c):
    """KUKA's R = Rz(a)·Ry(b)·Rx(c), plain math (the tests check it with scipy)."""
    a, b, c = map(math.radians, (a, b, c))
    ca, sa, cb, sb, cc, sc = (math.cos(a), math.sin(a), math.cos(b), math.sin(b),
                              math.cos(c), math.sin(c))
    return [[ca * cb, ca * sb * sc - sa * cc, ca * sb * cc + sa * sc],
            [sa * cb, sa * sb * sc + ca * cc, sa * sb * cc - ca * sc],
            [-sb, cb * sc, cb * cc]]


def robot_of(laser, truth=TRUTH):
    R = matrix(truth["a"], truth["b"], truth["c"])
    t = (truth["x"], truth["y"], truth["z"])
    return [tuple(sum(R[i][j] * p[j] for j in range(3)) + t[i] for i in range(3)) for p in laser]


def write_case(folder, kind: str = "clean"):
    """MEAS.csv, SOLUTION.json, $config.dat (the simulated frame) and
    working.csv in ``folder`` for one case; returns their paths."""
    folder.mkdir(parents=True, exist_ok=True)
    laser = list(LASER)
    if kind == "one-sided":
        laser = [(x * 0.2, y * 0.2, z * 0.2) for x, y, z in LASER]
    robot = robot_of(laser)
    noise = [((k * 7) % 5 - 2) * 0.01 for k in range(30)]
    robot = [tuple(v + noise[3 * k + i] for i, v in enumerate(p)) for k, p in enumerate(robot)]
    if kind == "swapped":
        robot[2], robot[3] = robot[3], robot[2]
    if kind == "blunder":
        robot[5] = (robot[5][0] + 2.4, robot[5][1] - 3.2, robot[5][2])
    rows = ["point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c"]
    rows += [f"P{k + 1},{l[0]},{l[1]},{l[2]},{r[0]:.4f},{r[1]:.4f},{r[2]:.4f},0,0,0"
             for k, (l, r) in enumerate(zip(laser, robot))]
    meas = folder / "meas.csv"
    meas.write_text("\n".join(rows) + "\n")
    simulated = dict(TRUTH, x=TRUTH["x"] - 12.0, y=TRUTH["y"] + 8.0)
    if kind == "rotated":
        simulated["a"] = TRUTH["a"] + 25.0
    config = folder / "$config.dat"
    config.write_text(KRL.format(**simulated))
    working = folder / "working.csv"
    working.write_text("point,x,y,z\nW1,1400,900,400\nW2,-300,-200,0\nW3,600,400,900\n")
    sol = folder / "solution.json"
    args = ["solve", str(meas), "--tcp", "0,0,0", "-o", str(sol), "--at", str(working)]
    if kind in ("swapped",):
        args.append("--no-exclusion")
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        main(args)
    return {"meas": meas, "solution": sol, "config": config, "working": working,
            "simulated": simulated}
