"""A sysframe.va of a given size, made of real elements.

    python benchmarks/make_big_sysframe.py OUT.va [--kb 100]

The UB10200 backup's sysframe.va of the shared corpus (its $MNUFRAME and
$MNUTOOL, 2 groups of 32 frames) with each frame record's elements
replicated, renumbered, until the file is the size asked for: the layout,
the fixed-width numbers, the CRLF endings and the mix of set and unset
frames are the controller's. Without the corpus, the same layout is
written from one set and one unset element.
"""
from __future__ import annotations

import argparse
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CORPUS = ROOT.parent / "shared" / "corpus" / "fanuc"
SOURCE = CORPUS / "irbzavalagit__UB10200_RBT01__sysframe.va"
_RECORD = re.compile(r"(\[\*SYSTEM\*\]\$MNU(?:FRAME|TOOL)  Storage: SHADOW  Access: RW  : "
                     r"ARRAY\[)(\d+),(\d+)(\] OF POSITION\r?\n)((?:    \[\d+,\d+\] = .*?(?=\r?\n\r?\n|"
                     r"\r?\n\[)\r?\n))", re.S)
_ELEMENT = re.compile(r"    \[(\d+),(\d+)\] = ")


def _fallback() -> str:
    set_ = ("  Group: 1   Config: N U T, 0, 0, 0\r\n  X:  3495.600   Y:  5813.000   Z: -1166.400\r\n"
            "  W:      .140   P:      .080   R:   -90.040\r\n")
    unset = ("  Group: 1   Config: N D B, 0, 0, 0\r\n  X:     0.000   Y:     0.000   Z:     0.000\r\n"
             "  W:     0.000   P:     0.000   R:     0.000\r\n")
    out = []
    for name in ("FRAME", "TOOL"):
        out.append(f"[*SYSTEM*]$MNU{name}  Storage: SHADOW  Access: RW  : ARRAY[1,32] OF POSITION\r\n")
        out += [f"    [1,{n}] = \r\n" + (set_ if n in (1, 9) else unset) for n in range(1, 33)]
        out.append("\r\n")
    return "".join(out)


def big_sysframe(kb: float = 100) -> str:
    text = SOURCE.read_bytes().decode("ascii") if SOURCE.is_file() else _fallback()
    records = list(_RECORD.finditer(text))
    per_copy = sum(len(m.group(5)) for m in records)
    copies = max(1, round((kb * 1000 - (len(text) - per_copy)) / per_copy))
    out, pos = [], 0
    for m in records:
        groups, size = int(m.group(2)), int(m.group(3))
        elements = re.split(r"(?=    \[\d+,\d+\] = )", m.group(5))[1:]
        grown = []
        for c in range(copies):
            for e in elements:
                g, n = (int(x) for x in _ELEMENT.match(e).groups())
                grown.append(_ELEMENT.sub(f"    [{g},{n + c * size}] = ", e, count=1))
        grown.sort(key=lambda e: tuple(int(x) for x in _ELEMENT.match(e).groups()))
        out.append(text[pos:m.start()] + m.group(1) + f"{groups},{size * copies}" + m.group(4)
                   + "".join(grown))
        pos = m.end()
    out.append(text[pos:])
    return "".join(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--kb", type=float, default=100)
    args = ap.parse_args(argv)
    args.out.write_bytes(big_sysframe(args.kb).encode("ascii"))
    print(f"{args.out}: {args.out.stat().st_size / 1000:.1f} KB")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
