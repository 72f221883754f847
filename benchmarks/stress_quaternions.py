"""Issue 9 point 2, the full stress run: 20,000 orientations concentrated at
and near axis-aligned rotations, each patched into an ABB work object's user
frame, object frame or a tool frame, parsed back and verified.

    PYTHONPATH=src python benchmarks/stress_quaternions.py [N]

Prints the worst written rotation and norm error; exits 1 on any refusal or a
bound exceeded. (The suite runs the same check on 300 orientations.)
"""
from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "src"), str(ROOT / "tests")]   # this checkout's ucsio

from test_quat_writer import MAX_ANGLE_DEG, TINY, orientations, patch_everywhere  # noqa: E402
from ucsio.vendors.abb.write import QUAT_NORM_MAX  # noqa: E402


def main() -> int:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 20_000
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "Tiny.mod"
        path.write_text(TINY)
        t0 = time.perf_counter()
        angle, norm = patch_everywhere(path, orientations(n, seed=2026))
        dt = time.perf_counter() - t0
    ok = angle <= MAX_ANGLE_DEG and norm <= QUAT_NORM_MAX
    print(f"{n} patches in {dt:.1f} s: worst rotation {angle:.3g} deg (bound {MAX_ANGLE_DEG:g}), "
          f"worst |sum q^2 - 1| {norm:.3g} (bound {QUAT_NORM_MAX:g}): {'ok' if ok else 'FAILED'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
