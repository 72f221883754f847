"""Throughput of the batched Horn solver against a Python loop over scipy.

    python benchmarks/bench_solver.py              # 100,000 sets, loop timed on 5,000
    python benchmarks/bench_solver.py --full-loop  # time the scipy loop on all sets
    python benchmarks/bench_solver.py --sets 20000 --loop-sets 2000

Both sides solve the same problem: eight point pairs per set, weighted
centroids, rotation, translation. The reference is what one would write
without ucsio: for each set, centre the points and call
``scipy.spatial.transform.Rotation.align_vectors``, then t = c_r - R c_l.
Also times ``ucsio.solve.uncertainty`` with 10,000 Monte Carlo samples of an
eight-point set (the shipped example kuka_base3.csv).
"""
from __future__ import annotations

import argparse
import platform
import statistics
import sys
import time
from pathlib import Path

import numpy as np
import scipy
from scipy.spatial.transform import Rotation

from ucsio import horn
from ucsio.measurement import read_measurement
from ucsio.solve import uncertainty

ROOT = Path(__file__).resolve().parents[1]


def make_sets(n_sets: int, n_points: int = 8, seed: int = 0):
    rng = np.random.default_rng(seed)
    truth = Rotation.random(n_sets, random_state=seed)
    t = rng.uniform(-3000, 3000, size=(n_sets, 3))
    laser = rng.uniform(0, 1, size=(n_sets, n_points, 3)) * [1200.0, 800.0, 300.0]
    robot = np.einsum("bij,bmj->bmi", truth.as_matrix(), laser) + t[:, None, :]
    robot += rng.normal(0, 0.05, size=robot.shape)
    return laser, robot


def scipy_loop(laser, robot):
    R_out = np.empty((len(laser), 3, 3))
    t_out = np.empty((len(laser), 3))
    for i in range(len(laser)):
        cl = laser[i].mean(axis=0)
        cr = robot[i].mean(axis=0)
        rot, _ = Rotation.align_vectors(robot[i] - cr, laser[i] - cl)
        R = rot.as_matrix()
        R_out[i] = R
        t_out[i] = cr - R @ cl
    return R_out, t_out


def best_of(fn, repeat):
    times = []
    result = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
    return min(times), statistics.median(times), result


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sets", type=int, default=100_000, help="number of 8-point sets (100000)")
    ap.add_argument("--loop-sets", type=int, default=5_000,
                    help="sets the scipy loop is timed on, then extrapolated (5000)")
    ap.add_argument("--full-loop", action="store_true", help="time the scipy loop on every set")
    ap.add_argument("--repeat", type=int, default=5,
                    help="repeats of the batched timing; best is reported (5); the loop gets 2")
    args = ap.parse_args(argv)

    print(f"python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__},"
          f" {platform.machine()} ({platform.processor() or platform.platform()})")
    laser, robot = make_sets(args.sets)
    horn.horn_batch(laser[:100], robot[:100])                        # warm up

    best, median, res = best_of(lambda: horn.horn_batch(laser, robot), args.repeat)
    assert res.ok.all()
    n_loop = args.sets if args.full_loop else min(args.loop_sets, args.sets)
    loop, loop_median, (R_ref, t_ref) = best_of(
        lambda: scipy_loop(laser[:n_loop], robot[:n_loop]), 1 if args.full_loop else 2)
    loop_total = loop * args.sets / n_loop

    dR = horn.rotation_angle_deg(res.R[:n_loop], R_ref).max()
    dt = np.abs(res.t[:n_loop] - t_ref).max()
    print()
    print(f"{args.sets:,} sets of 8 point pairs")
    print(f"  batched Horn (one eigh on ({args.sets}, 4, 4)):  {best:8.3f} s  "
          f"(median of {args.repeat}: {median:.3f} s)   {args.sets / best:12,.0f} sets/s")
    how = ("all sets" if n_loop == args.sets
           else f"best of 2 on {n_loop:,} sets ({loop:.3f} s), extrapolated x{args.sets / n_loop:g}")
    print(f"  scipy align_vectors loop:                   {loop_total:8.3f} s  "
          f"({how})   {n_loop / loop:12,.0f} sets/s")
    ratio = loop_total / best
    print(f"  ratio: {ratio:.1f}x  (best vs best; target >= 30x: {'met' if ratio >= 30 else 'NOT met'})")
    print(f"  ratio of medians: {loop_median * args.sets / n_loop / median:.1f}x")
    print(f"  agreement on the looped sets: max rotation difference {dR:.2e} deg,"
          f" max translation difference {dt:.2e} mm")

    m = read_measurement(ROOT / "fixtures" / "measurements" / "kuka_base3.csv")
    tcp = (-20.67, 89.73, 33.44)
    uncertainty(m.laser, m.flange, tcp, m.weights, 100)              # warm up
    best_u, median_u, u = best_of(
        lambda: uncertainty(m.laser, m.flange, tcp, m.weights, 10_000), args.repeat)
    print()
    print(f"uncertainty, 10,000 Monte Carlo samples of an 8-point set: {best_u * 1000:.1f} ms"
          f" (median {median_u * 1000:.1f} ms)")
    for label, key in (("Monte Carlo", "std"), ("analytical", "analytical_std")):
        print(f"  std ({label}):".ljust(22) + "  ".join(
            f"{k} {u[key][k]:.4f}" for k in ("x", "y", "z", "angle")) + "  (mm, deg)")
    print()
    print("rerun: python benchmarks/bench_solver.py  [--full-loop] [--sets N] [--loop-sets N]")
    return 0


if __name__ == "__main__":
    sys.exit(main())
