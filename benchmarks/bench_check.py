"""``ucsio check`` over the whole shared corpus in one process, against a
regex tokenizer over the same bytes, side by side in one run.

    python benchmarks/bench_check.py [--repeat 5] [--corpus DIR] [--vendor abb|kuka|fanuc]

- check: ``ucsio.cli.main(["check", CORPUS/abb, CORPUS/kuka, CORPUS/fanuc,
  "--json"])`` with stdout to a null device: reading every file, the
  whole-file grammar over every byte, the frames, the round-trip proof and
  the lints. ``--vendor`` takes one vendor's folder only.
- baseline: read the same files and run one regex tokenizer over their bytes
  (strings, comments, numbers, names, operators, blanks: every byte lands in
  a token), counting the tokens.

Both are timed in CPU time (``time.process_time``), best of --repeat, after
a warm-up. Targets: check >= 1 MB/s, and <= 5x the tokenizer.
"""
from __future__ import annotations

import argparse
import contextlib
import os
import re
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CORPUS = ROOT.parent / "shared" / "corpus"
if not CORPUS.exists():
    CORPUS = Path("/work/shared/corpus")

TOKEN = re.compile(rb"""
      "(?:[^"\r\n]|"")*"?             # string (RAPID doubles its quotes)
    | [!;][^\r\n]*                    # comment: RAPID !, KRL ;
    | &[^\r\n]*                       # KRL &ACCESS and friends
    | (?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?   # number
    | [A-Za-z_$#][\w$#]*               # name
    | :=|<>|<=|>=|==|[^\s\w]          # operator or punctuation
    | \s+                             # blanks and line breaks
    | .                               # anything else (non-ASCII letters)
""", re.X | re.S)


def files(corpus: Path) -> list[Path]:
    suffixes = {".mod", ".modx", ".sys", ".sysx", ".prg", ".dat", ".va", ".dg", ".ls"}
    return sorted(p for p in corpus.rglob("*") if p.is_file() and p.suffix.lower() in suffixes)


def best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t = time.process_time()
        fn()
        times.append(time.process_time() - t)
    return min(times)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--corpus", type=Path, default=CORPUS)
    ap.add_argument("--vendor", choices=("abb", "kuka", "fanuc"),
                    help="only that vendor's folder of the corpus")
    args = ap.parse_args(argv)
    if args.vendor:
        args.corpus = args.corpus / args.vendor
    sys.path.insert(0, str(ROOT / "src"))
    from ucsio.cli import main as cli_main

    paths = files(args.corpus)
    size = sum(p.stat().st_size for p in paths)
    folders = sorted({str(p.parent) for p in paths})
    devnull = open(os.devnull, "w")

    def check():
        with contextlib.redirect_stdout(devnull), contextlib.redirect_stderr(devnull):
            cli_main(["check", *folders, "--json"])

    def tokenize():
        n = 0
        for p in paths:
            n += sum(1 for _ in TOKEN.finditer(p.read_bytes()))
        return n

    check(), tokenize()                                  # warm-up: imports, grammar cache
    t_check, t_tok = float("inf"), float("inf")
    for _ in range(args.repeat):                         # interleaved: same load on both
        t_check = min(t_check, best(check, 1))
        t_tok = min(t_tok, best(tokenize, 1))
    mb = size / 1e6
    print(f"corpus: {len(paths)} files, {mb:.2f} MB ({args.corpus})")
    print(f"  ucsio check (in process):  {t_check * 1000:8.1f} ms   {mb / t_check:6.2f} MB/s")
    print(f"  regex tokenizer:           {t_tok * 1000:8.1f} ms   {mb / t_tok:6.2f} MB/s"
          f"   ({tokenize():,} tokens)")
    ratio = t_check / t_tok
    print()
    print(f"check throughput: {mb / t_check:.2f} MB/s  (target >= 1 MB/s: "
          f"{'met' if mb / t_check >= 1 else 'NOT met'})")
    print(f"ratio check / tokenizer: {ratio:.1f}x  (target <= 5x: {'met' if ratio <= 5 else 'NOT met'})")
    print()
    print("rerun: python benchmarks/bench_check.py [--repeat N]")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
