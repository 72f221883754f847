"""A FANUC TP program of N taught positions, shaped like a generated path
program (a motion line per point in /MN, CRLF, 3 decimals), for the
benchmarks: ``big_program(100_000)`` is about 18 MB.

    python benchmarks/make_big_program.py N OUT.LS
"""
from __future__ import annotations

import math
import sys


def position(i: int) -> str:
    a = i * 0.001
    x, y, z = 1200 + 300 * math.cos(a), 300 * math.sin(a), 400 + (i % 97)
    w, p, r = 180.0, (i % 7) * 0.5, -90 + (i % 13)
    return (f"P[{i}]{{\r\n   GP1:\r\n\tUF : 1, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',\r\n"
            f"\tX = {x:9.3f}  mm,\tY = {y:9.3f}  mm,\tZ = {z:9.3f}  mm,\r\n"
            f"\tW = {w:9.3f} deg,\tP = {p:9.3f} deg,\tR = {r:9.3f} deg\r\n}};\r\n")


def big_program(n: int) -> str:
    mn = "".join(f"{i:4d}:L P[{i}] 500mm/sec CNT100    ;\r\n" for i in range(1, n + 1))
    return ("/PROG  BIG\r\n/ATTR\r\nOWNER\t\t= MNEDITOR;\r\nCOMMENT\t\t= \"\";\r\n"
            f"LINE_COUNT\t= {n};\r\nDEFAULT_GROUP\t= 1,*,*,*,*;\r\n/MN\r\n{mn}/POS\r\n"
            + "".join(position(i) for i in range(1, n + 1)) + "/END\r\n")


if __name__ == "__main__":
    with open(sys.argv[2], "w", newline="") as fh:
        fh.write(big_program(int(sys.argv[1])))
