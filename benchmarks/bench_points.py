"""diff --points: what reading routines costs, and that the fast path does not pay it.

    python benchmarks/bench_points.py [--targets 20000] [--rounds 7]

On a path module (make_big_module: N robtargets, one routine moving to every
tenth of them in wobjFixture), in one process, medians of alternating rounds:

1. the fast path (``ucsio frames``: rapid.parse) on the module, against the
   same module with its routine cut out: routines cost the fast path one
   regex pass (the outline skips them whole), so the ratio stays near 1;
2. ``diff --points`` work (outline with routines, the \\WObj statements
   parsed with the grammar, the robtargets they name parsed, displacements)
   against the fast path: the price of --points, paid only when asked.

Needs only the sources (PYTHONPATH=src) and the standard library.
"""
from __future__ import annotations

import argparse
import re
import statistics
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "src"))
from make_big_module import big_module  # noqa: E402

from ucsio.parsing import rapid  # noqa: E402
from ucsio.parsing.document import Document  # noqa: E402
from ucsio.geometry.frames import Pose  # noqa: E402
from ucsio.taught import find_points, points_moved  # noqa: E402


def timed(fn) -> float:
    t = time.perf_counter()
    fn()
    return time.perf_counter() - t


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--targets", type=int, default=20000)
    ap.add_argument("--rounds", type=int, default=7)
    args = ap.parse_args()

    text = big_module(args.targets)
    bare = re.sub(r"  PROC Path1\(\).*?ENDPROC\r\n", "", text, flags=re.S)
    doc = Document(text.encode(), "big.mod")
    doc_bare = Document(bare.encode(), "bare.mod")
    measured = Pose.from_quat(1251.5, -339.0, 880.5, (0.7, 0.01, 0.0, 0.714))

    def points():
        cf = rapid.parse(doc)
        frame = cf.frame("wobjFixture")
        return points_moved(cf, frame, measured, find_points(cf, frame))

    n_moves = points()["points_moved"]["count"]       # warm Lark's caches, check the work
    rapid.parse(doc_bare)
    fast, cut, pts = [], [], []
    for _ in range(args.rounds):
        fast.append(timed(lambda: rapid.parse(doc)))
        cut.append(timed(lambda: rapid.parse(doc_bare)))
        pts.append(timed(points))
    f, c, p = (statistics.median(x) for x in (fast, cut, pts))
    print(f"module: {args.targets} robtargets, {n_moves} taught points moved to in wobjFixture, "
          f"{len(text) / 1e6:.1f} MB")
    print(f"fast path (frames)           {f * 1e3:8.1f} ms")
    print(f"  same module, routine cut   {c * 1e3:8.1f} ms   ratio {f / c:.2f} (target <= 1.2)")
    print(f"diff --points work           {p * 1e3:8.1f} ms   ratio {p / f:.2f} to the fast path")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
