"""Cold-start benchmark: `ucsio frames` on a real 120 KB KUKA $config.dat
against `python -c "import numpy"`.

Both commands run as fresh processes (so each pays interpreter start, imports,
and, for ucsio, `import lark` plus loading the cached grammar), alternating
one after the other so machine load hits both alike. The median of N runs of
each is reported, with the ratio ucsio / numpy (target <= 1.5).

    python benchmarks/bench_krl.py [--runs 7] [FILE]

FILE defaults to the Zinkerreka $config.dat of the shared corpus
(../shared/corpus/kuka/). The ucsio command measured is
`python -m ucsio frames FILE` (real CLI, output sent to /dev/null); the
`--fast-path-only` line also shows the in-process cost of krl.parse alone.
Exit status 1 if the ratio is over the target.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

TARGET = 1.5
HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "src"))   # this checkout's ucsio
from coldstart import alternate  # noqa: E402

DEFAULT = (HERE.parents[1] / "shared" / "corpus" / "kuka"
           / "Aleynikovich__Zinkerreka__KRC__R1__System__$config.dat")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("file", nargs="?", default=str(DEFAULT))
    ap.add_argument("--runs", type=int, default=7)
    args = ap.parse_args(argv)
    path = Path(args.file)
    if not path.is_file():
        print(f"no such file: {path}", file=sys.stderr)
        return 2
    py = sys.executable
    numpy_cmd = [py, "-c", "import numpy"]
    ucsio_cmd = [py, "-m", "ucsio", "frames", str(path)]
    ma, mb = alternate(numpy_cmd, ucsio_cmd, args.runs)

    # in-process, for information: the parse alone (parser already loaded)
    from ucsio.vendors.kuka import krl
    from ucsio.parsing.document import Document
    doc = Document.read(path)
    krl.parse(doc)
    t0 = time.perf_counter()
    for _ in range(10):
        cf = krl.parse(doc)
    fast = (time.perf_counter() - t0) / 10
    t0 = time.perf_counter()
    krl.parse(doc, full=True)
    full = time.perf_counter() - t0

    ratio = mb / ma
    print(f"file: {path.name} ({path.stat().st_size} bytes, {len(cf.frames)} frames)")
    print(f"runs: {args.runs} each, alternating, fresh processes; medians:")
    print(f"  python -c 'import numpy'          {ma * 1000:7.1f} ms")
    print(f"  python -m ucsio frames FILE        {mb * 1000:7.1f} ms")
    print(f"  ratio                              {ratio:7.2f}   (target <= {TARGET})")
    print(f"in-process krl.parse: fast path {fast * 1000:.1f} ms, full=True {full * 1000:.1f} ms")
    print(f"rerun: python benchmarks/bench_krl.py --runs {args.runs}")
    return 0 if ratio <= TARGET else 1


if __name__ == "__main__":
    sys.exit(main())
