"""A path program's positions: ``ucsio solve --robot BIG.LS`` on a TP
program of 100,000 taught positions (about 22 MB, benchmarks/
make_big_program.py), cold, against a baseline measured side by side in
the same run: a fresh process that reads the file and converts every
X Y Z W P R with one regex pass (the lean floor for reading the numbers).

Reported: the median wall time of each and their ratio, and the peak
memory (RSS) of each. Targets (issue 24 point 18): at most 10 s and
200 MB (before the fast reader: 72 s and 2.0 GB, a tree of every byte of
/POS), and at most 15x the floor's time (about 12x where this was
written: 4.5 s against 0.37 s; the ratio holds the target on a faster or
slower machine).

    python benchmarks/bench_tp.py [--rounds 3] [--points 100000]

Rounds alternate between the two commands so that machine noise hits both
alike. The laser file pairs 11 points; the fit is not the point here (an
exit status of 1 for its gate is accepted). Exit status 1 if over a target.
"""
from __future__ import annotations

import argparse
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from coldstart import ENV  # noqa: E402
from make_big_program import big_program  # noqa: E402

SYSFRAME = HERE.parent / "fixtures" / "fanuc" / "sysframe_comment.va"
MAX_SECONDS, MAX_MB, MAX_RATIO = 10.0, 200.0, 15.0
FLOOR = ("import re,sys\n"
         "d=open(sys.argv[1],'rb').read()\n"
         "v=[float(x) for x in re.findall(rb'[XYZWPR] = +([-0-9.]+)', d)]\n")


def run(cmd: list[str]) -> tuple[float, float]:
    """(seconds, peak RSS in MB) of one fresh process."""
    t = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=ENV)
    _, status, usage = os.wait4(proc.pid, 0)
    seconds = time.perf_counter() - t
    code = os.waitstatus_to_exitcode(status)
    if code not in (0, 1):
        raise SystemExit(f"{' '.join(cmd)}: exit {code}")
    return seconds, usage.ru_maxrss / 1024


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--points", type=int, default=100_000)
    args = ap.parse_args()
    py = sys.executable
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        big = folder / "BIG.LS"
        big.write_text(big_program(args.points), newline="")
        shutil.copy(SYSFRAME, folder / "sysframe.va")
        laser = folder / "laser.txt"
        step = max(1, args.points // 10)
        laser.write_text("".join(f"P{i} {1200 + 300 * math.cos(i / 1000):.3f} "
                                 f"{300 * math.sin(i / 1000):.3f} {400 + i % 97:.3f}\n"
                                 for i in range(1, args.points + 1, step)))
        ucsio = [py, "-m", "ucsio", "solve", "--laser", str(laser), "--robot", str(big),
                 "--config", str(folder / "sysframe.va"), "--tcp", "0,0,0"]
        floor = [py, "-c", FLOOR, str(big)]
        run(ucsio), run(floor)                      # warm-up: file cache, bytecode, tables
        got = {"ucsio": [], "floor": []}
        for _ in range(args.rounds):
            got["ucsio"].append(run(ucsio))
            got["floor"].append(run(floor))
        size = big.stat().st_size / 1e6
    t_u = statistics.median(t for t, _ in got["ucsio"])
    t_f = statistics.median(t for t, _ in got["floor"])
    mb_u = max(m for _, m in got["ucsio"])
    mb_f = max(m for _, m in got["floor"])
    ok = t_u <= MAX_SECONDS and mb_u <= MAX_MB and t_u / t_f <= MAX_RATIO
    print(f"TP program, {args.points:,} positions ({size:.1f} MB)")
    print(f"  ucsio solve --robot, cold   {t_u:7.2f} s   {mb_u:6.0f} MB   "
          f"(targets <= {MAX_SECONDS:g} s, <= {MAX_MB:g} MB)")
    print(f"  regex floor, cold           {t_f:7.2f} s   {mb_f:6.0f} MB")
    print(f"  ratio                       {t_u / t_f:7.2f}   (target <= {MAX_RATIO:g})")
    print("PASS" if ok else "OVER TARGET")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
