"""Timing fresh processes side by side (shared by the start-up benchmarks).

Each round runs both commands once, one after the other, so machine noise hits
both alike; medians are compared. Bytecode is allowed (PYTHONDONTWRITEBYTECODE
removed): an installed package runs from the .pyc files pip compiled, as numpy
does here; without them every run would recompile ucsio's sources and measure
the compiler, not ucsio.
"""
from __future__ import annotations

import os
import statistics
import subprocess
import time

ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def run_cold(cmd: list[str]) -> float:
    t = time.perf_counter()
    code = subprocess.run(cmd, stdout=subprocess.DEVNULL, env=ENV).returncode
    if code not in (0, 1):                  # 1: a frame over tolerance, a gate; fine here
        raise SystemExit(f"{' '.join(cmd)}: exit {code}")
    return time.perf_counter() - t


def alternate(a: list[str], b: list[str], rounds: int) -> tuple[float, float]:
    """Median seconds of ``a`` and of ``b`` over ``rounds`` alternating runs,
    after one warm-up of each (OS file cache, bytecode, Lark's grammar cache)."""
    run_cold(a), run_cold(b)
    ta, tb = [], []
    for _ in range(rounds):
        ta.append(run_cold(a))
        tb.append(run_cold(b))
    return statistics.median(ta), statistics.median(tb)
