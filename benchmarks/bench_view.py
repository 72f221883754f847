"""How fast ``ucsio view`` writes its page for a 10-point solution, beside
``ucsio solve`` on the same data, and a batch report's pictures for 2,000
entries beside the batch that solves them (issue 29: each within a second
of the command that makes its input).

    python benchmarks/bench_view.py
    python benchmarks/bench_view.py --repeat 7 --entries 2000

Fresh processes on the wall clock, alternating, best of --repeat: what the
engineer waits for each command, start-up included. ``view`` reads the
solution, the controller's simulated frame and working points, and writes a
~720 KB page (three.js inlined). The report's pictures: in process, best of
--repeat on the CPU clock, ``fleet.report.write_views`` (one page, the
entries' data, three.js) beside ``run_batch`` on benchmarks/bench_batch.py's
fleet.
"""
from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))


def timed(args: list[str]) -> float:
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "ucsio", *args], check=False,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--entries", type=int, default=2000)
    args = ap.parse_args()
    from view_cases import write_case
    folder = Path(tempfile.mkdtemp(prefix="ucsio-bench-view-"))
    c = write_case(folder, "blunder")
    solve = ["solve", str(c["meas"]), "--tcp", "0,0,0", "--at", str(c["working"]), "-o",
             str(folder / "again.json")]
    view = ["view", str(c["solution"]), "--controller", str(c["config"]), "--frame",
            "BASE_DATA[3]", "--at", str(c["working"]), "-o", str(folder / "view.html")]
    got = {"solve": [], "view": []}
    for _ in range(args.repeat):
        got["solve"].append(timed(solve))
        got["view"].append(timed(view))
    s, v = min(got["solve"]), min(got["view"])
    size = (folder / "view.html").stat().st_size
    print(f"solve, 10 points          {s * 1000:8.1f} ms")
    print(f"view, same solution       {v * 1000:8.1f} ms   page {size / 1024:.0f} KB")
    print(f"view / solve              {v / s:8.2f}   view - solve {(v - s) * 1000:+.1f} ms "
          "(target: within 1 s)")
    report_pictures(args.entries, args.repeat)


def report_pictures(n: int, repeat: int) -> None:
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
    import bench_batch
    from ucsio.fleet.batch import read_manifest, run_batch
    from ucsio.fleet.report import write_views
    folder = Path(tempfile.mkdtemp(prefix="ucsio-bench-report-"))
    bench_batch.fleet(folder, n)
    manifest = read_manifest(str(folder / "manifest.toml"))
    batch = pictures = float("inf")
    for _ in range(repeat):
        t0 = time.process_time()
        result = run_batch(manifest)
        batch = min(batch, time.process_time() - t0)
        t0 = time.process_time()
        write_views(result, str(folder / "report.html"))
        pictures = min(pictures, time.process_time() - t0)
    print(f"batch, {n} entries       {batch * 1000:8.1f} ms")
    print(f"their pictures            {pictures * 1000:8.1f} ms   (target: within 1 s)")


if __name__ == "__main__":
    main()
