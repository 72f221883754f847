"""Parser speed, as ratios against baselines measured side by side in one run.

    python benchmarks/bench_rapid.py [--rounds 9]

1. ``ucsio frames`` on a typical RAPID module, cold (a fresh process each
   time), against ``python -c "import numpy"``. Target: at most 1.5x.
2. ``ucsio frames`` on a 2.5 MB module with 20,000 robtargets, cold, against a
   fresh process that runs a bare regex scan for declarations over the same
   file. Target: at most 3x. The same comparison in-process (parse vs regex,
   interpreter start excluded) is printed too.

Rounds alternate between the two commands of a pair so that machine noise
hits both alike; medians are compared (see coldstart.py). Needs ucsio
installed (pip install .).
"""
from __future__ import annotations

import argparse
import re
import statistics
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "src"))   # this checkout's ucsio
from coldstart import alternate  # noqa: E402
from make_big_module import big_module  # noqa: E402

CORPUS = HERE.parents[1] / "shared" / "corpus" / "abb"
TYPICAL = CORPUS / "EdgarIvanMM__PaletizadoCajasConFrascos__RAPID__TASK1__PROGMOD__MainModule.mod"
FALLBACK = HERE.parent / "fixtures" / "abb" / "variants.mod"
SCAN = (rb"(?im)^[ \t]*(?:(?:LOCAL|TASK)[ \t]+)?(?:PERS|CONST|VAR)[ \t]+(\w+)[ \t]+(\w+)")
REGEX_CMD = ("import re,sys\n"
             "d=open(sys.argv[1],'rb').read()\n"
             f"n=sum(1 for m in re.finditer({SCAN!r}, d))\n")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=9)
    args = ap.parse_args()
    py = sys.executable
    ok = True

    typical = TYPICAL if TYPICAL.exists() else FALLBACK
    t_ucsio, t_numpy = alternate([py, "-m", "ucsio", "frames", str(typical)],
                            [py, "-c", "import numpy"], args.rounds)
    ratio = t_ucsio / t_numpy
    ok &= ratio <= 1.5
    print(f"typical module ({typical.name}, {typical.stat().st_size / 1024:.0f} KiB)")
    print(f"  ucsio frames, cold   {t_ucsio * 1000:7.1f} ms")
    print(f"  import numpy, cold   {t_numpy * 1000:7.1f} ms")
    print(f"  ratio                {ratio:7.2f}   (target <= 1.5)")

    with tempfile.TemporaryDirectory() as tmp:
        big = Path(tmp) / "big.mod"
        big.write_text(big_module(20000), newline="")
        size = big.stat().st_size / 1e6
        t_ucsio, t_regex = alternate([py, "-m", "ucsio", "frames", str(big)],
                                [py, "-c", REGEX_CMD, str(big)], args.rounds)
        ratio = t_ucsio / t_regex
        ok &= ratio <= 3.0
        print(f"big module (20,000 robtargets, {size:.2f} MB)")
        print(f"  ucsio frames, cold   {t_ucsio * 1000:7.1f} ms")
        print(f"  regex scan, cold     {t_regex * 1000:7.1f} ms")
        print(f"  ratio                {ratio:7.2f}   (target <= 3)")

        from ucsio.vendors.abb import rapid
        from ucsio.parsing.document import Document
        raw = big.read_bytes()
        scan = re.compile(SCAN)
        rapid.parse(Document(raw, big))  # grammar loaded, caches warm
        tp, tr = [], []
        for _ in range(args.rounds):
            t = time.perf_counter()
            rapid.parse(Document(raw, big))
            tp.append(time.perf_counter() - t)
            t = time.perf_counter()
            sum(1 for _ in scan.finditer(raw))
            tr.append(time.perf_counter() - t)
        p, r = statistics.median(tp), statistics.median(tr)
        print(f"  in-process: parse {p * 1000:.1f} ms, regex {r * 1000:.1f} ms, ratio {p / r:.2f}"
              f" ({size / p:.0f} MB/s)")
    print("PASS" if ok else "OVER TARGET")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
