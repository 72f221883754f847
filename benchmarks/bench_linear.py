"""Linear time on hostile input (issue 12 point 1).

Every command must stay linear in the input: a file four times longer may
take about four times longer, never sixteen. For each hostile shape below
(long runs of blanks or blank lines inside and around declarations, long
words, unterminated items, comment lines full of number-like text, deep
brackets, ...) this times what `frames`, `check` and `patch` do with a file
of N bytes and of 4N bytes, in this process, and prints the ratio
t(4N) / t(N). A ratio near 4 (or below: fixed costs) is linear; near 16 is
quadratic. Exit status 1 if any ratio exceeds --max-ratio (default 8).

    python benchmarks/bench_linear.py [--size 20000] [--only NAME]
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from ucsio.parsing.controller import parse  # noqa: E402
from ucsio.parsing.document import Document  # noqa: E402
from ucsio.errors import UcsioError  # noqa: E402

WOBJ = 'PERS wobjdata w{i}:=[FALSE,TRUE,"",[[1,2,3],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n'


def rapid(body: str, end: str = "ENDMODULE\n") -> tuple[str, str]:
    return "h.mod", "MODULE M\n" + body + end


def krl(body: str, end: str = "ENDDAT\n") -> tuple[str, str]:
    return "h.dat", "DEFDAT H\n" + body + end


FRAME = "DECL FRAME f{i}={{X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0}}\n"

# name -> function of n (a length in characters) giving (file name, text)
SHAPES = {
    # RAPID: blanks and blank lines inside and around declarations
    "rapid spaces in aggregate": lambda n: rapid('PERS wobjdata w:=[FALSE,TRUE,"",[[1,' + " " * n
                                                 + '2,3],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n'),
    "rapid newlines in aggregate": lambda n: rapid('PERS wobjdata w:=[FALSE,TRUE,"",[[1,' + "\n" * n
                                                   + '2,3],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n'),
    "rapid blanks around decl": lambda n: rapid(" " * (n // 2) + WOBJ.format(i=0) + "\n" * (n // 2)),
    "rapid blanks between keywords": lambda n: rapid("PERS" + " \n" * (n // 2) + "wobjdata w:=[FALSE,"
                                                     'TRUE,"",[[1,2,3],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n'),
    "rapid spaces before ;": lambda n: rapid("PERS num x:=1" + " " * n + ";\n"),
    "rapid blank lines, no decl": lambda n: rapid("\n" * n),
    "rapid many decls": lambda n: rapid("".join(WOBJ.format(i=i) for i in range(n // 75))),
    "rapid blank lines between decls": lambda n: rapid("".join(WOBJ.format(i=i) + "\n" * 40
                                                               for i in range(n // 115))),
    "rapid long word": lambda n: rapid("a" * n + "\n"),
    "rapid long word at EOF": lambda n: rapid("a" * n, end=""),
    "rapid unterminated decl": lambda n: rapid("PERS num " + "a" * n, end=""),
    "rapid unterminated decl, blanks": lambda n: rapid("PERS num x" + " \n" * (n // 2), end=""),
    "rapid unterminated PERS then spaces": lambda n: rapid("PERS" + " " * n, end=""),
    "rapid unterminated string": lambda n: rapid('PERS string s:="' + "a" * n + "\n;\n"),
    "rapid unterminated routine": lambda n: rapid("PROC p()\n" + "  e := 1;\n" * (n // 10), end=""),
    "rapid routine of blanks": lambda n: rapid("PROC p()\n" + " \n" * (n // 2) + "ENDPROC\n"),
    "rapid comment of numbers": lambda n: rapid("! " + "1a " * (n // 3) + "\n"),
    "rapid comment lines of numbers": lambda n: rapid(("! " + "1a " * 20 + "\n") * (n // 63)),
    "rapid digits then letter": lambda n: rapid("PERS num x:=" + "1" * n + "a;\n"),
    "rapid dotted digits": lambda n: rapid("PERS num x:=" + "1." * (n // 2) + ";\n"),
    "rapid many [ unbalanced": lambda n: rapid("PERS num x:=" + "[" * n + ";\n"),
    "rapid many ] unbalanced": lambda n: rapid("PERS num x:=" + "]" * n + ";\n"),
    "rapid unclosed header": lambda n: ("h.mod", "%%%\n" + " " * n + "\nMODULE M\nENDMODULE\n"),
    "rapid percent run": lambda n: ("h.mod", "%" * n + "\nMODULE M\nENDMODULE\n"),
    "rapid MODULE blanks": lambda n: ("h.mod", "MODULE" + " " * n + "M\nENDMODULE\n"),
    "rapid many MODULE": lambda n: ("h.mod", "MODULE M\n" * (n // 9)),
    "rapid many PERS": lambda n: rapid("PERS " * (n // 5), end=""),
    "rapid many !": lambda n: rapid("!" * n + "\n"),
    "rapid many quotes": lambda n: rapid('"' * n + "\n"),
    "rapid many <": lambda n: rapid("PERS num x:=" + "<" * n + ";\n"),
    # KRL
    "krl spaces in struct": lambda n: krl("DECL FRAME f={X 1.0," + " " * n + "Y 2.0,Z 3.0,A 0,B 0,C 0}\n"),
    "krl blank lines": lambda n: krl("\n" * n),
    "krl spaces lines": lambda n: krl(" \n" * (n // 2)),
    "krl many frames": lambda n: krl("".join(FRAME.format(i=i) for i in range(n // 55))),
    "krl long word": lambda n: krl("a" * n + "\n"),
    "krl long word at EOF": lambda n: krl("a" * n, end=""),
    "krl unterminated string": lambda n: krl('DECL CHAR s[5]="' + "a" * n + "\n"),
    "krl many {": lambda n: krl("DECL FRAME f=" + "{" * n + "\n"),
    "krl many }": lambda n: krl("DECL FRAME f=" + "}" * n + "\n"),
    "krl long comment": lambda n: krl(";" + "1a " * (n // 3) + "\n"),
    "krl many & lines": lambda n: ("h.dat", "&ACCESS RV\n" * (n // 11) + "DEFDAT H\nENDDAT\n"),
    "krl many DEFDAT": lambda n: ("h.dat", "DEFDAT H\n" * (n // 9)),
    "krl many ENDDAT": lambda n: ("h.dat", "DEFDAT H\n" + "ENDDAT\n" * (n // 7)),
    "krl digits": lambda n: krl("INT i=" + "1" * n + "\n"),
    "krl digits dots": lambda n: krl("REAL r=" + "1." * (n // 2) + "\n"),
    "krl many =": lambda n: krl("BASE_DATA[1]" + "=" * n + "\n"),
    "krl many [": lambda n: krl("BASE_DATA" + "[" * n + "\n"),
    "krl element blanks": lambda n: krl("BASE_DATA[1]" + " " * n + "={X 1,Y 2,Z 3,A 0,B 0,C 0}\n"),
    "krl no DEFDAT, many lines": lambda n: ("h.dat", "INT i=1\n" * (n // 8)),
}


def run_commands(name: str, text: str) -> None:
    """What frames, check and patch do with the file: the fast path, the
    full parse with its round trip, and a patch plan of the first frame."""
    from ucsio.commands.check import round_trip
    from ucsio.geometry.frames import Pose
    from ucsio.review.patch import patch_frame

    raw = text.encode("utf-8")
    for full in (False, True):
        try:
            cf = parse(Document(raw, name), full=full)
        except UcsioError:
            continue
        if full:
            round_trip(cf)
        elif cf.frames and cf.frames[0].pose is not None:
            try:
                patch_frame(cf, cf.frames[0].name, Pose.from_abc(5, 6, 7, 0, 0, 0),
                            measured=False, check_siblings=False)
            except UcsioError:
                pass


def timed(name: str, text: str, repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        run_commands(name, text)
        best = min(best, time.perf_counter() - t0)
    return best


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=20000,
                    help="smallest N in characters (default 20000); doubled until t(N) >= --min-time")
    ap.add_argument("--min-time", type=float, default=0.05, help="seconds (default 0.05)")
    ap.add_argument("--repeat", type=int, default=3, help="best of R runs (default 3)")
    ap.add_argument("--max-ratio", type=float, default=8.0)
    ap.add_argument("--only", help="shapes whose name contains this")
    args = ap.parse_args(argv)
    # warm up: grammars loaded and compiled once, outside the timings
    run_commands(*rapid(WOBJ.format(i=0)))
    run_commands(*krl(FRAME.format(i=0)))
    worst = 0.0
    print(f"{'shape':38} {'N':>8} {'t(N) ms':>9} {'t(4N) ms':>9} {'ratio':>6}")
    for shape, make in SHAPES.items():
        if args.only and args.only not in shape:
            continue
        # N grows until t(N) is long enough to time (a few ms is all noise)
        n = args.size
        t1 = timed(*make(n), args.repeat)
        while t1 < args.min_time and n < 64 * args.size:
            n *= 2
            t1 = timed(*make(n), args.repeat)
        t4 = timed(*make(4 * n), args.repeat)
        ratio = t4 / t1
        if t4 < args.min_time:      # refused at once however long: nothing to judge
            flag = "  (refused at once)"
        else:
            worst = max(worst, ratio)
            flag = "  <-- not linear" if ratio > args.max_ratio else ""
        print(f"{shape:38} {n:>8} {t1 * 1e3:9.1f} {t4 * 1e3:9.1f} {ratio:6.1f}{flag}", flush=True)
    print(f"worst ratio {worst:.1f} (linear: about 4; quadratic: 16)")
    return 1 if worst > args.max_ratio else 0


if __name__ == "__main__":
    sys.exit(main())
