"""``ucsio batch`` over 1,000 entries vs the same point sets solved in one
batched Horn call, side by side in one run.

    python benchmarks/bench_batch.py            # 1,000 entries, best of 3
    python benchmarks/bench_batch.py --entries 5000 --repeat 5

What is timed (best of --repeat, after one warm-up run):

- batch (in process): ``ucsio.cli.main(["batch", MANIFEST, "--json"])`` with
  stdout to a null device: reading the manifest, parsing every controller
  file (once per file), reading every CSV, the batched solve with
  leave-one-out exclusion, the diffs, the summary and the JSON output.
- batch (subprocess): the same as a user runs it, interpreter start and
  imports included.
- baseline, read + 1 call: read the same CSVs (``read_measurement``), put the
  flange poses through the TCP, and fit all sets in ONE ``horn_batch`` call
  (no leave-one-out, no exclusion, no controller files, no diff, no output).
- baseline, 1 call: that ``horn_batch`` call alone, on arrays already in memory.
- for scale: ``ucsio.solve.solve`` entry by entry (the loop batch replaces).

The target is batch (in process) / (read + 1 call) < 10x.
"""
from __future__ import annotations

import argparse
import contextlib
import importlib.util
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _make_fleet():
    spec = importlib.util.spec_from_file_location("make_fleet", ROOT / "fixtures/fleet/make_fleet.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.make_fleet


def best(fn, repeat):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--entries", type=int, default=1000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--keep", metavar="DIR", help="generate the fleet here and keep it")
    args = ap.parse_args(argv)

    import numpy as np

    from ucsio import horn
    from ucsio.batch import read_manifest
    from ucsio.cli import main as cli_main
    from ucsio.measurement import read_measurement

    n = args.entries
    shares = (0.40, 0.25, 0.15, 0.12)
    groups = [round(n * s) for s in shares]
    groups.append(n - sum(groups))
    with contextlib.ExitStack() as stack:
        dest = Path(args.keep) if args.keep else Path(stack.enter_context(tempfile.TemporaryDirectory()))
        t = time.perf_counter()
        truth = _make_fleet()(dest, groups=tuple(groups), rejected=0, broken=False)
        gen = time.perf_counter() - t
        manifest = dest / "manifest.toml"
        m = read_manifest(manifest)
        print(f"fleet: {truth['summary']['total']} entries, "
              f"{len({e.controller for e in m.entries})} controller files "
              f"(RAPID and KUKA), {len(m.entries)} CSVs; generated in {gen:.2f} s")

        devnull = open(os.devnull, "w")
        stack.enter_context(devnull)

        def run_batch():
            with contextlib.redirect_stdout(devnull):
                cli_main(["batch", str(manifest), "--json"])

        def run_sub():
            subprocess.run([sys.executable, "-m", "ucsio", "batch", str(manifest), "--json"],
                           stdout=subprocess.DEVNULL, check=False)

        tcps = {}
        from ucsio.batch import _Cache, _tool_tcp
        cache = _Cache()
        for e in m.entries:
            tcps[e.name] = e.tcp if e.tool is None else _tool_tcp(cache, e.tool)

        def read_all():
            sets = []
            for e in m.entries:
                meas = read_measurement(e.measurement)
                sets.append((meas.laser, meas.robot_points(tcps[e.name]), meas.weights))
            return sets

        def stack_sets(sets):
            k = max(len(s[0]) for s in sets)
            L = np.zeros((len(sets), k, 3))
            R = np.zeros((len(sets), k, 3))
            W = np.zeros((len(sets), k))
            for i, (l, r, w) in enumerate(sets):
                L[i, :len(l)], R[i, :len(l)], W[i, :len(l)] = l, r, w
            return L, R, W

        def read_and_fit():
            L, R, W = stack_sets(read_all())
            horn.horn_batch(L, R, W)

        arrays = stack_sets(read_all())

        def fit_only():
            horn.horn_batch(*arrays)

        def per_entry():
            from ucsio import solve
            for e in m.entries:
                meas = read_measurement(e.measurement)
                solve.solve(meas, tcps[e.name], threshold=e.threshold, min_points=e.min_points)

        run_batch()   # warm-up: imports, grammar caches
        read_and_fit()
        t_batch = best(run_batch, args.repeat)
        t_sub = best(run_sub, max(1, args.repeat))
        t_read_fit = best(read_and_fit, args.repeat)
        t_fit = best(fit_only, max(args.repeat, 5))
        t_loop = best(per_entry, 1)

    rows = [("ucsio batch --json (in process)", t_batch),
            ("ucsio batch --json (subprocess)", t_sub),
            ("baseline: read CSVs + 1 horn_batch call", t_read_fit),
            ("baseline: 1 horn_batch call (arrays in memory)", t_fit),
            ("for scale: ucsio.solve.solve per entry", t_loop)]
    width = max(len(r[0]) for r in rows)
    print()
    for name, t in rows:
        print(f"  {name:<{width}}  {t * 1000:9.1f} ms   {t / n * 1e6:8.1f} us/entry")
    ratio = t_batch / t_read_fit
    print()
    print(f"ratio batch (in process) / (read + 1 call): {ratio:.2f}x  "
          f"(target < 10x: {'met' if ratio < 10 else 'NOT met'})")
    print(f"ratio batch (in process) / (1 call alone):  {t_batch / t_fit:.1f}x")
    print(f"ratio per-entry solve / batch:              {t_loop / t_batch:.1f}x")
    print()
    print("rerun: python benchmarks/bench_batch.py [--entries N] [--repeat R] [--keep DIR]")
    return 0 if ratio < 10 else 1


if __name__ == "__main__":
    raise SystemExit(main())
