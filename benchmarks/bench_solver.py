"""Throughput and memory of the batched Horn solver, against a Python loop
over scipy, and leave-one-out on one very large measurement.

    python benchmarks/bench_solver.py              # 100,000 sets, loop timed on 5,000
    python benchmarks/bench_solver.py --full-loop  # time the scipy loop on all sets
    python benchmarks/bench_solver.py --sets 20000 --loop-sets 2000 --memory-sets 100000

Speed: both sides solve the same problem: eight point pairs per set,
weighted centroids, rotation, translation. The reference is what one would
write without ucsio: for each set, centre the points and call
``scipy.spatial.transform.Rotation.align_vectors``, then t = c_r - R c_l.
Target: >= 100x.

Memory: the peak resident memory (``/usr/bin/time -v``) of a process that
loads --memory-sets eight-point sets from .npy files and solves them in one
``horn_batch`` call, less that of a process that only starts Python and
imports ucsio.method.horn, against the size of the two input arrays. Target: <= 2
(the inputs themselves count once, the outputs and the work the rest).

Leave-one-out: one set of --loo-points points (100,000), every point against
the fit of the others, against one fit of all of them; and a set of 10,000
collinear points, refused.

Also times ``ucsio.method.solve.uncertainty`` with 10,000 Monte Carlo samples of an
eight-point set (the shipped example kuka_base3.csv).
"""
from __future__ import annotations

import argparse
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import scipy
from scipy.spatial.transform import Rotation

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))   # this checkout's ucsio, not an installed one

from ucsio.errors import UcsioError  # noqa: E402
from ucsio.geometry import arrays  # noqa: E402
from ucsio.method import horn  # noqa: E402
from ucsio.readers.measurement import read_measurement  # noqa: E402
from ucsio.method.solve import solve_points, uncertainty  # noqa: E402



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


def peak_rss_mb(code: str) -> float:
    """Maximum resident set size (MB) of ``python -c code``, from /usr/bin/time -v."""
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    r = subprocess.run(["/usr/bin/time", "-v", sys.executable, "-c", code], env=env,
                       capture_output=True, text=True, check=True)
    return int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", r.stderr).group(1)) / 1024


def memory(n_sets: int) -> None:
    laser, robot = make_sets(n_sets)
    input_mb = (laser.nbytes + robot.nbytes) / 2**20
    with tempfile.TemporaryDirectory() as tmp:
        np.save(Path(tmp) / "l.npy", laser)
        np.save(Path(tmp) / "r.npy", robot)
        del laser, robot
        load = (f"import numpy as np; from ucsio.method import horn; "
                f"l = np.load({str(Path(tmp) / 'l.npy')!r}); r = np.load({str(Path(tmp) / 'r.npy')!r})")
        bare = peak_rss_mb("import numpy as np; from ucsio.method import horn")
        loaded = peak_rss_mb(load)
        solved = peak_rss_mb(load + "; res = horn.horn_batch(l, r); assert res.ok.all()")
    peak = solved - bare
    print(f"peak memory, {n_sets:,} sets of 8 point pairs (max RSS above python + imports, "
          f"{bare:.0f} MB):")
    print(f"  input arrays (laser + robot):     {input_mb:8.0f} MB")
    print(f"  load the inputs:                  {loaded - bare:8.0f} MB")
    print(f"  load + batched solve:             {peak:8.0f} MB   "
          f"(of which outputs {n_sets * 161 / 2**20:.0f} MB: q, R, t, lambda_m, spread, status)")
    ratio = peak / input_mb
    print(f"  ratio to the inputs: {ratio:.2f}  (target <= 2: {'met' if ratio <= 2 else 'NOT met'})")


def large_set(n: int) -> None:
    rng = np.random.default_rng(1)
    truth = Rotation.random(random_state=2)
    laser = rng.uniform(0, 1, size=(n, 3)) * [1200.0, 800.0, 300.0]
    robot = truth.apply(laser) + 500.0 + rng.normal(0, 0.05, size=(n, 3))
    fit, _, _ = best_of(lambda: horn.horn_batch(laser[None], robot[None]), 3)
    loo, _, _ = best_of(lambda: horn.leave_one_out(laser[None], robot[None]), 3)
    names = [f"P{i}" for i in range(n)]
    whole, _, sol = best_of(lambda: solve_points(names, laser, robot), 1)
    print(f"one set of {n:,} points:")
    print(f"  one fit of all points:            {fit * 1000:8.1f} ms")
    print(f"  every point's leave-one-out fit:  {loo * 1000:8.1f} ms   "
          f"({loo / fit:.0f}x one fit, {loo / n * 1e6:.1f} us per point)")
    print(f"  solve_points (fit, leave-one-out, exclusion, {sol.n_used:,} used): {whole:.2f} s")
    line = np.outer(rng.uniform(0, 2000, 10_000), [0.48, 0.6, 0.64]) + rng.normal(0, 0.01, (10_000, 3))
    t0 = time.perf_counter()
    try:
        solve_points(names[:10_000], line, truth.apply(line))
        verdict = "NOT refused"
    except UcsioError as exc:
        verdict = f"refused: {exc}"
    print(f"  10,000 collinear points: {(time.perf_counter() - t0) * 1000:.0f} ms, {verdict[:60]}...")


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
    ap.add_argument("--memory-sets", type=int, default=1_000_000,
                    help="sets for the peak memory measurement (1000000; 0 skips it)")
    ap.add_argument("--loo-points", type=int, default=100_000,
                    help="points of the large leave-one-out set (100000)")
    ap.add_argument("--repeat", type=int, default=5,
                    help="repeats of the batched timing; best is reported (5); the loop gets 3")
    args = ap.parse_args(argv)

    print(f"python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__},"
          f" {platform.machine()} ({platform.processor() or platform.platform()})")
    laser, robot = make_sets(args.sets)
    horn.horn_batch(laser[:100], robot[:100])                        # warm up

    # Interleaved, so that both sides see the same load on a shared machine.
    n_loop = args.sets if args.full_loop else min(args.loop_sets, args.sets)
    loop_repeat = 1 if args.full_loop else 3
    fit_times, loop_times = [], []
    for k in range(max(args.repeat, loop_repeat)):
        if k < args.repeat:
            t0 = time.perf_counter()
            res = horn.horn_batch(laser, robot)
            fit_times.append(time.perf_counter() - t0)
        if k < loop_repeat:
            t0 = time.perf_counter()
            R_ref, t_ref = scipy_loop(laser[:n_loop], robot[:n_loop])
            loop_times.append(time.perf_counter() - t0)
    assert res.ok.all()
    best, median = min(fit_times), statistics.median(fit_times)
    loop, loop_median = min(loop_times), statistics.median(loop_times)
    loop_total = loop * args.sets / n_loop

    dR = arrays.rotation_angle_deg(res.R[:n_loop], R_ref).max()
    dt = np.abs(res.t[:n_loop] - t_ref).max()
    print()
    print(f"{args.sets:,} sets of 8 point pairs")
    print(f"  batched Horn (horn_batch):                  {best:8.3f} s  "
          f"(median of {args.repeat}: {median:.3f} s)   {args.sets / best:12,.0f} sets/s")
    how = ("all sets" if n_loop == args.sets
           else f"best of {loop_repeat} on {n_loop:,} sets ({loop:.3f} s), extrapolated x{args.sets / n_loop:g}")
    print(f"  scipy align_vectors loop:                   {loop_total:8.3f} s  "
          f"({how})   {n_loop / loop:12,.0f} sets/s")
    ratio = loop_total / best
    print(f"  ratio: {ratio:.1f}x  (best vs best; target >= 100x: {'met' if ratio >= 100 else 'NOT met'})")
    print(f"  ratio of medians: {loop_median * args.sets / n_loop / median:.1f}x")
    print(f"  agreement on the looped sets: max rotation difference {dR:.2e} deg,"
          f" max translation difference {dt:.2e} mm")

    if args.memory_sets:
        print()
        memory(args.memory_sets)
    print()
    large_set(args.loo_points)

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
