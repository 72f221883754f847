"""``ucsio batch`` over 10,000 entries vs reading the same files and solving
the same point sets in one batched Horn call, side by side in one run.

    python benchmarks/bench_batch.py                  # 10,000 entries (and 1,000 for linearity)
    python benchmarks/bench_batch.py --entries 2000 --repeat 3

What is timed (best of --repeat, after one warm-up run; CPU time in process,
wall time for the subprocess):

- batch (in process): ``ucsio.cli.main(["batch", MANIFEST, "--json"])`` with
  stdout to a null device: reading the manifest, parsing every controller
  file (once per file), reading every CSV, the batched solve with
  leave-one-out exclusion, the diffs, the summary and the JSON output.
- batch (subprocess): the same as a user runs it, interpreter start and
  imports included.
- baseline, read + 1 call: read the same files (the manifest, every
  controller file through ``controller.load``, every CSV through
  ``read_measurement``), put the flange poses through the TCP, and fit all
  sets in ONE ``horn_batch`` call (no leave-one-out, no exclusion, no diff,
  no output).
- baseline, 1 call: that ``horn_batch`` call alone, on arrays already in memory.
- for scale: ``ucsio.method.solve.solve`` entry by entry on the first 1,000 entries
  (the loop batch replaces), extrapolated.
- linearity: batch (in process) on a fleet a tenth the size, per entry.

Targets: batch (in process) / (read + 1 call) <= 1.3 at 10,000 entries, and
the time per entry at 10,000 within 1.2x of that at 1,000 (linear).
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
sys.path.insert(0, str(ROOT / "src"))   # this checkout's ucsio, not an installed one


def _make_fleet():
    spec = importlib.util.spec_from_file_location("make_fleet", ROOT / "fixtures/fleet/make_fleet.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.make_fleet


def best(fn, repeat, clock=time.process_time):
    """Best of ``repeat`` runs. In-process work is timed in CPU time
    (``time.process_time``): on a shared machine, wall time mostly measures
    the neighbours; a subprocess is timed on the wall clock."""
    times = []
    for _ in range(repeat):
        t = clock()
        fn()
        times.append(clock() - t)
    return min(times)


def fleet(dest: Path, n: int) -> dict:
    shares = (0.40, 0.25, 0.15, 0.12)
    groups = [round(n * s) for s in shares]
    groups.append(n - sum(groups))
    return _make_fleet()(dest, groups=tuple(groups), rejected=0, broken=False)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--entries", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--keep", metavar="DIR", help="generate the fleets here and keep them "
                    "(reused when already there)")
    args = ap.parse_args(argv)

    import numpy as np

    from ucsio.method import horn
    from ucsio.fleet.batch import read_manifest
    from ucsio.cli import main as cli_main
    from ucsio.parsing.controller import load
    from ucsio.readers.measurement import read_measurement

    n = args.entries
    with contextlib.ExitStack() as stack:
        base = Path(args.keep) if args.keep else Path(stack.enter_context(tempfile.TemporaryDirectory()))
        dest, small = base / f"fleet{n}", base / f"fleet{n // 10}"
        t = time.perf_counter()
        for d, k in ((dest, n), (small, n // 10)):
            if not (d / "manifest.toml").exists():
                fleet(d, k)
        gen = time.perf_counter() - t
        manifest = dest / "manifest.toml"
        m = read_manifest(manifest)
        controllers = sorted({e.controller for e in m.entries}
                             | {e.tool.rpartition(":")[0] for e in m.entries if e.tool})
        print(f"fleet: {len(m.entries)} entries, {len(controllers)} controller files "
              f"(RAPID and KUKA), {len(m.entries)} CSVs; generated in {gen:.2f} s")

        devnull = open(os.devnull, "w")
        stack.enter_context(devnull)

        def run_batch(path=manifest):
            with contextlib.redirect_stdout(devnull):
                cli_main(["batch", str(path), "--json"])

        def run_sub():
            subprocess.run([sys.executable, "-m", "ucsio", "batch", str(manifest), "--json"],
                           stdout=subprocess.DEVNULL, check=False,
                           env=dict(os.environ, PYTHONPATH=str(ROOT / "src")))

        def read_all():
            """Every file batch reads, read once, and the point sets."""
            from ucsio.geometry.frames import tool_tcp
            mf = read_manifest(manifest)
            files = {p: load(p) for p in controllers}
            sets = []
            for e in mf.entries:
                tcp = e.tcp
                if e.tool is not None:
                    file, _, name = e.tool.rpartition(":")
                    tcp = tool_tcp(files[file].frame(name))
                meas = read_measurement(e.measurement)
                sets.append((meas.laser, meas.robot_points(tcp), meas.weights))
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

        n_loop = min(1000, n)

        def per_entry():
            from ucsio.method import solve
            for e in m.entries[:n_loop]:
                meas = read_measurement(e.measurement)
                solve.solve(meas, e.tcp if e.tool is None else (0.0, 0.0, 0.0),
                            threshold=e.threshold, min_points=e.min_points)

        run_batch()   # warm-up: imports, grammar caches
        read_and_fit()
        # interleaved, so that both sides see the same load on a shared machine
        t_batch, t_read_fit = float("inf"), float("inf")
        for _ in range(args.repeat):
            t_batch = min(t_batch, best(run_batch, 1))
            t_read_fit = min(t_read_fit, best(read_and_fit, 1))
        t_small = best(lambda: run_batch(small / "manifest.toml"), args.repeat)
        t_sub = best(run_sub, 1, clock=time.perf_counter)
        t_fit = best(fit_only, max(args.repeat, 5))
        t_loop = best(per_entry, 1) * n / n_loop

    n_small = n // 10
    rows = [("ucsio batch --json (in process)", t_batch, n),
            ("ucsio batch --json (subprocess, wall clock)", t_sub, n),
            ("baseline: read all files + 1 horn_batch call", t_read_fit, n),
            ("baseline: 1 horn_batch call (arrays in memory)", t_fit, n),
            (f"for scale: ucsio.method.solve.solve per entry (x{n // n_loop})", t_loop, n),
            (f"ucsio batch --json, {n_small:,} entries (in process)", t_small, n_small)]
    width = max(len(r[0]) for r in rows)
    print()
    for name, t, k in rows:
        print(f"  {name:<{width}}  {t * 1000:9.1f} ms   {t / k * 1e6:8.1f} us/entry")
    ratio = t_batch / t_read_fit
    linear = (t_batch / n) / (t_small / n_small)
    print()
    print(f"ratio batch (in process) / (read all files + 1 call): {ratio:.2f}x  "
          f"(target <= 1.3x: {'met' if ratio <= 1.3 else 'NOT met'})")
    print(f"per entry, {n:,} vs {n_small:,} entries:                 {linear:.2f}x  "
          f"(linear: <= 1.2x: {'met' if linear <= 1.2 else 'NOT met'})")
    print(f"ratio batch (in process) / (1 call alone):            {t_batch / t_fit:.1f}x")
    print(f"ratio per-entry solve / batch:                        {t_loop / t_batch:.1f}x")
    print()
    print("rerun: python benchmarks/bench_batch.py [--entries N] [--repeat R] [--keep DIR]")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
