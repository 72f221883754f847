"""How fast ``ucsio view`` writes its page for a 10-point solution, beside
``ucsio solve`` on the same data (issue 29: within a second of it).

    python benchmarks/bench_view.py
    python benchmarks/bench_view.py --repeat 7

Fresh processes on the wall clock, alternating, best of --repeat: what the
engineer waits for each command, start-up included. ``view`` reads the
solution, the controller's simulated frame and working points, and writes a
~720 KB page (three.js inlined).
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


if __name__ == "__main__":
    main()
