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
_X = re.compile(r"(  X: +)(-?[0-9]*\.[0-9]+)")
BACKUP = CORPUS / "JuniorNatalin__VASC__KJLTVX__Backups__24.06.2024__LTVR__kjltvr411670r01__SYSFRAME.VA"


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


def backup_sysframe(kb: float = 100) -> str:
    """A sysframe.va shaped like a whole real backup's: the VASC robot
    kjltvr411670r01's (4 groups; $CELL_FLOOR, $CELL_GRP with its POSITION
    fields, $MNUFRAME [4,20], $MNUFRAMENUM, $MNUTOOL [4,29], $MNUTOOLNUM),
    its frame records grown to ``kb``, with CRLF as the controller writes
    (git stored it LF). Each copy moves the set frames' X by a few
    hundredths, so that they are distinct frames, as a real cell's are."""
    text = BACKUP.read_bytes().decode("ascii") if BACKUP.is_file() else None
    return big_sysframe(kb, text, vary=True).replace("\r\n", "\n").replace("\n", "\r\n")


def _moved(element: str, copy: int) -> str:
    """``element`` with its X moved by ``copy`` * 0.013 mm where it is set."""
    m = _X.search(element)
    if m is None or float(m.group(2)) == 0.0 or copy == 0:
        return element
    x = f"{float(m.group(2)) + copy * 0.013:9.3f}"
    return element[:m.start(2)] + x[-len(m.group(2)):].rjust(len(m.group(2))) + \
        element[m.end(2):]


def big_sysframe(kb: float = 100, text: str | None = None, vary: bool = False) -> str:
    if text is None:
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
                e = _moved(e, c) if vary else e
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
