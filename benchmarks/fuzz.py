"""Hunt for hostile inputs for N minutes (issue 12 point 8).

Mutates the real corpus and our fixtures (byte flips, truncations, token
insertions, CR alone, NUL, BOMs, huge numbers, deep nesting: tests/fuzzing.py)
and runs every result through the oracle (clean error or valid result; the
fast path agrees with check; round trip identical; a patch changes only the
frame's numbers). Each distinct failure is saved once, as
OUT/NNN--original-name, with OUT/NNN--original-name.txt saying what went
wrong and how to replay it. Move a saved input to fixtures/fuzz/ once fixed:
tests/test_fuzz.py replays everything there.

    python benchmarks/fuzz.py --minutes 30 [--seed 1] [--out fuzz-findings] [--max-size 50000]
        [--only yaskawa]

Exit status 1 if anything was found.
"""
from __future__ import annotations

import argparse
import collections
import random
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "src"), str(ROOT / "tests")]

import fuzzing  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--minutes", type=float, default=10.0)
    ap.add_argument("--seed", type=int, default=None, help="random seed (default: from the clock)")
    ap.add_argument("--out", default="fuzz-findings", help="folder for failing inputs")
    ap.add_argument("--max-size", type=int, default=None,
                    help="only seed files up to this many bytes (default: all)")
    ap.add_argument("--only", default=None, metavar="WORD",
                    help="only seed files whose path holds WORD (a vendor: yaskawa)")
    ap.add_argument("--max-ops", type=int, default=3, help="mutations stacked per input")
    args = ap.parse_args(argv)
    seed = args.seed if args.seed is not None else int(time.time())
    rng = random.Random(seed)
    seeds = fuzzing.seed_files(args.max_size)
    if args.only:
        seeds = [p for p in seeds if args.only.lower() in str(p).lower()]
    if not seeds:
        print("no seed files (corpus and fixtures missing?)", file=sys.stderr)
        return 2
    raws = {p: p.read_bytes() for p in seeds}
    out = Path(args.out)
    outcomes: collections.Counter = collections.Counter()
    seen: dict[str, int] = {}
    deadline = time.monotonic() + 60 * args.minutes
    last_report = time.monotonic()
    print(f"fuzzing {len(seeds)} seed files for {args.minutes:g} min, seed {seed}", flush=True)
    n = 0
    while time.monotonic() < deadline:
        path = rng.choice(seeds)
        ops = [(rng.randrange(fuzzing.KINDS), rng.randrange(1 << 20), rng.randrange(1 << 20))
               for _ in range(rng.randint(1, args.max_ops))]
        raw = fuzzing.mutate(raws[path], ops)
        n += 1
        try:
            outcomes[fuzzing.check_bytes(path.name, raw)] += 1
        except fuzzing.Finding as exc:
            outcomes["FOUND"] += 1
            key = str(exc).split(":", 1)[0] + ":" + str(exc)[:80]
            if key in seen:
                continue
            seen[key] = len(seen) + 1
            out.mkdir(parents=True, exist_ok=True)
            name = f"{seen[key]:03d}--{path.name}"
            (out / name).write_bytes(raw)
            (out / (name + ".txt")).write_text(
                f"{exc}\n\nseed file: {path}\nmutations: {ops}\n"
                f"replay: python -c \"import sys; sys.path[:0]=['src','tests']; import fuzzing; "
                f"fuzzing.check_bytes({path.name!r}, open({str(out / name)!r},'rb').read())\"\n")
            print(f"FOUND {name}: {str(exc)[:200]}", flush=True)
        if time.monotonic() - last_report > 60:
            last_report = time.monotonic()
            print(f"{n} inputs: {dict(outcomes)}", flush=True)
    print(f"{n} inputs in {args.minutes:g} min: {dict(outcomes)}; {len(seen)} distinct findings"
          + (f" saved in {out}/" if seen else ""))
    return 1 if seen else 0


if __name__ == "__main__":
    sys.exit(main())
