"""Write a large RAPID module: N robtargets (a RobotStudio-style path module)
with a few wobjdata/tooldata and routines, for the parser benchmarks.

    python benchmarks/make_big_module.py OUT.mod [N]
"""
from __future__ import annotations

import random
import sys


def big_module(n: int = 20000, seed: int = 1) -> str:
    rng = random.Random(seed)
    out = ["MODULE BigPath", "  ! generated for benchmarks: %d robtargets" % n,
           '  TASK PERS wobjdata wobjFixture:=[FALSE,TRUE,"",[[1250.5,-340.25,880],[0.707107,0,0,0.707107]],[[0,0,0],[1,0,0,0]]];',
           "  PERS tooldata tGun:=[TRUE,[[-20.67,89.73,333.44],[0.92388,0,0.382683,0]],[4.5,[0,0,120],[1,0,0,0],0,0,0]];"]
    for i in range(n):
        x, y, z = (rng.uniform(-2000, 2000) for _ in range(3))
        q = [rng.uniform(-1, 1) for _ in range(4)]
        s = sum(c * c for c in q) ** 0.5
        q = [c / s for c in q]
        out.append("  CONST robtarget p%d:=[[%.2f,%.2f,%.2f],[%.5f,%.5f,%.5f,%.5f],[0,-1,0,1],"
                   "[9E9,9E9,9E9,9E9,9E9,9E9]];" % (i, x, y, z, *q))
    out.append("  PROC Path1()")
    for i in range(0, n, 10):
        out.append("    MoveL p%d, v1000, z10, tGun\\WObj:=wobjFixture;  ! step %d" % (i, i))
    out.append("  ENDPROC")
    out.append("ENDMODULE")
    return "\r\n".join(out) + "\r\n"


if __name__ == "__main__":
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 20000
    with open(sys.argv[1], "w", newline="") as f:
        f.write(big_module(n))
