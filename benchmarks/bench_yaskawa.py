"""Yaskawa's files: cold ``frames`` against the lean floor, and ``check``'s
throughput over the Yaskawa corpus.

    python benchmarks/bench_yaskawa.py [--rounds 7] [--repeat 5]

- Cold start (as bench_cold.py: a plain venv made here, ucsio from this
  checkout's ``src``, the installed console script's way in, each round the
  command and the floor one after the other, medians compared). The floor
  is bench_cold.py's, for Yaskawa's blocks: a fresh ``python`` that reads
  the file and runs one regex pass over it (counting its ``//KIND n``
  block heads). Files: the corpus's full TOOL.CND
  (the Komatsu cell's: 64 tools, ///CRC), its UFRAME.CND, a UFRAME.CND
  with all 63 user frames defined (generated here, CRLF) and RBCALIB.DAT.
  Target: ``frames`` <= 2x the floor on each; ``frames --tree``, ``check``
  and ``diff`` (of the two versions of the Komatsu files) are reported.
- Throughput: ``ucsio.cli.main(["check", ...])`` in one process over every
  file of the Yaskawa corpus ucsio reads (the .CND files, the jobs, both
  RBCALIB.DAT and VAR.DAT), CPU time, best of --repeat after a warm-up. Target >= 1 MB/s.
"""
from __future__ import annotations

import argparse
import contextlib
import os
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
import bench_cold  # noqa: E402
from bench_cold import CORPUS, plain_venv, ucsio  # noqa: E402
from coldstart import ENV, alternate  # noqa: E402

YASKAWA = CORPUS / "yaskawa"
KOMATSU = "lukelalondePZ__Komatsu-Press-Demo__"
GROUP1 = "1" + ",0" * 31
# bench_cold.py's floor (read the file, one regex pass) for Yaskawa's block heads
FLOOR = ("import re,sys\n"
         "d=open(sys.argv[1],'rb').read()\n"
         "n=sum(1 for m in re.finditer(rb'(?m)^//([A-Z]+)[ \\t]+(\\d+)\\r?$', d))\n")


def full_uframe_cnd() -> bytes:
    """A UFRAME.CND with every user frame (1..63) defined, as a YRC1000
    writes it (CRLF), its values varied so that no two frames are alike."""
    blocks = []
    for n in range(1, 64):
        blocks.append(
            f"//UFRAME {n}\n///NAME FIXTURE {n}\n///TOOL 0\n///GROUP {GROUP1}\n"
            "///BASICFRM 1,16,0\n///BASEP 0.000,0.000,0.000,0.0000,0.0000,0.0000\n///PULSE\n"
            f"////RORG C000=-202041,-68179,-82397,-47606,-56939,{36000 + n},0,0,0\n"
            f"////RXX C001=-217178,-82740,-89297,-47410,-66939,{39000 + n},0,0,0\n"
            f"////RXY C002=-208718,-43873,-68857,-50000,-57576,{40000 + n},0,0,0\n"
            f"////BUSER {700 + n * 3.25:.3f},{-600 + n * 1.5:.3f},{n * 0.125:.3f},"
            f"{n * 0.01:.4f},{-n * 0.02:.4f},{n * 2.5 - 80:.4f}\n")
    return "".join(blocks).replace("\n", "\r\n").encode("ascii")


def read_files() -> list[Path]:
    """Every Yaskawa corpus file ucsio reads: the .CND files, the jobs,
    RBCALIB.DAT and VAR.DAT (the earlier versions, .at-3ec0b394, too); not
    SYSTEM.SYS (refused: not read yet), the README and the manifest."""
    return sorted(p for p in YASKAWA.iterdir()
                  if p.suffix.lower() not in (".md", ".tsv") and "SYSTEM.SYS" not in p.name.upper())


def cold(rounds: int, tmp: Path) -> bool:
    full = tmp / "UFRAME.CND"
    full.write_bytes(full_uframe_cnd())
    tool, tool_before = YASKAWA / (KOMATSU + "TOOL.CND"), YASKAWA / (KOMATSU +
                                                                     "TOOL.CND.at-3ec0b394")
    cal, cal_before = YASKAWA / (KOMATSU + "RBCALIB.DAT"), YASKAWA / (KOMATSU +
                                                                      "RBCALIB.DAT.at-3ec0b394")
    uframe = YASKAWA / "icors2__Yaskawa-Job-Helper__fixtures__transform__UFRAME.CND"
    fenders = YASKAWA / "lukelalondePZ__Fiberdome-GP88-Spindle-Cell__FMTV_FENDERS.JBI"
    var = YASKAWA / (KOMATSU + "VAR.DAT")
    python = bench_cold.PYTHON = plain_venv(tmp / "venv")
    ENV["PYTHONPATH"] = str(ROOT / "src")
    ENV["UCSIO_CACHE_DIR"] = str(tmp / "cache")
    rows = [("TOOL.CND, 64 tools", tool, ["frames", str(tool)], 2.0),
            ("TOOL.CND, 64 tools", tool, ["frames", "--tree", str(tool)], None),
            ("TOOL.CND, 64 tools", tool, ["check", str(tool)], None),
            ("TOOL.CND, 64 tools", tool, ["diff", str(tool_before), str(tool)], None),
            ("UFRAME.CND, corpus (3 frames)", uframe, ["frames", str(uframe)], 2.0),
            ("UFRAME.CND, 63 frames, CRLF", full, ["frames", str(full)], 2.0),
            ("UFRAME.CND, 63 frames, CRLF", full, ["check", str(full)], None),
            ("RBCALIB.DAT", cal, ["frames", str(cal)], 2.0),
            ("RBCALIB.DAT", cal, ["diff", str(cal_before), str(cal)], None),
            ("job, 548 positions (40 KB)", fenders, ["frames", str(fenders)], None),
            ("job, 548 positions (40 KB)", fenders, ["check", str(fenders)], None),
            ("VAR.DAT, 250 P rows", var, ["check", str(var)], None)]
    ok = True
    print(f"{'file':<30} {'command':<13} {'ucsio':>9} {'floor':>9} {'ratio':>6}  target")
    for label, path, args, target in rows:
        t_u, t_f = alternate(ucsio(*args), [python, "-c", FLOOR, str(path)], rounds)
        ratio = t_u / t_f
        verdict = "(reported)"
        if target is not None:
            ok &= ratio <= target
            verdict = f"<= {target:g} {'met' if ratio <= target else 'NOT met'}"
        command = args[0] + (" --tree" if "--tree" in args else "")
        print(f"{label:<30} {command:<13} {t_u * 1000:7.1f}ms {t_f * 1000:7.1f}ms {ratio:6.2f}"
              f"  {verdict}")
    return ok


def throughput(repeat: int) -> bool:
    sys.path.insert(0, str(ROOT / "src"))
    from ucsio.cli import main as cli_main
    paths = read_files()
    size = sum(p.stat().st_size for p in paths)
    devnull = open(os.devnull, "w")

    def check():
        with contextlib.redirect_stdout(devnull), contextlib.redirect_stderr(devnull):
            cli_main(["check", *map(str, paths), "--json"])

    check()                                         # warm-up: imports, pattern cache
    best = float("inf")
    for _ in range(repeat):
        t = time.process_time()
        check()
        best = min(best, time.process_time() - t)
    mb = size / 1e6
    print(f"\ncheck over the Yaskawa corpus: {len(paths)} files, {size / 1000:.1f} KB: "
          f"{best * 1000:.1f} ms, {mb / best:.2f} MB/s (target >= 1 MB/s: "
          f"{'met' if mb / best >= 1 else 'NOT met'})")
    return mb / best >= 1


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    if not YASKAWA.is_dir():
        raise SystemExit(f"{YASKAWA}: the shared corpus is absent")
    with tempfile.TemporaryDirectory() as tmp:
        ok = cold(args.rounds, Path(tmp))
    ok &= throughput(args.repeat)
    print("\nrerun: python benchmarks/bench_yaskawa.py [--rounds N] [--repeat N]")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
