"""Named points in the UCS: working-point and candidate files (``plan --at``,
``plan --candidates``, ``solve --at``; SPEC "Planning and working points").

A CSV with a header row: ``point, x, y, z`` (mm, in the UCS), columns in any
order, names case-insensitive (a unit after the name, ``x [mm]``, is allowed);
``point`` is optional (default P1, P2, ...); other columns are ignored. A
header containing ``;`` means a European export (``;`` separates, a decimal
comma is read); a tab-separated file works too. ``#`` lines and blank lines
are skipped. Anything wrong names ``file:line:col``: a missing or extra
field, a value that is not a finite number or is beyond what a fit can use,
an empty or repeated name.

Lines are read with ``str.split`` and ``float`` first (10,000 working points
in a few tens of milliseconds); a line that does not read that way is read
again field by field, for the column of what is wrong.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass

import numpy as np

from ..defaults import MAX_MAGNITUDE
from ..errors import UcsioError
from ..parsing.document import text_lines
from .laser import _header_key
from .text import read_text, split

AXES = ("x", "y", "z")


@dataclass
class Points:
    path: str | None
    names: list[str]
    lines: list[int | None]
    xyz: np.ndarray                  # (n, 3) mm, in the UCS
    files: list[str] | None = None   # per point, the file it was read from (taught points)

    def __len__(self) -> int:
        return len(self.names)


def read_points(path: str | os.PathLike, what: str = "working-point file") -> Points:
    path = os.fspath(path)
    return parse_points(read_text(path, what), path)


def parse_points(text: str, path: str = "<points>") -> Points:
    rows = []
    header = None
    for lineno, line in enumerate(text_lines(text), start=1):      # the one rule for line ends
        s = line.strip()
        if not s or s.startswith("#"):
            continue
        if header is None:
            header = (lineno, line)
        else:
            rows.append((lineno, line))
    if header is None:
        raise UcsioError("no header row (expected point, x, y, z)", file=path)
    hline, htext = header
    sep = ";" if ";" in htext else ("\t" if "\t" in htext else ",")
    fields = split(htext, sep)
    keys = [_header_key(t) for t, _ in fields]
    cols = {}
    for idx, (k, (_name, col)) in enumerate(zip(keys, fields)):
        if k in AXES or k == "point":
            if k in cols:
                raise UcsioError(f"column {k!r} given twice", file=path, line=hline, col=col)
            cols[k] = idx
    missing = [a for a in AXES if a not in cols]
    if missing:
        raise UcsioError(f"missing column{'s' if len(missing) > 1 else ''} {', '.join(missing)} "
                         f"(expected point, x, y, z; the header reads {htext.strip()!r})",
                         file=path, line=hline)
    if not rows:
        raise UcsioError("no points after the header", file=path, line=hline)
    width = len(fields)
    ix, iy, iz = cols["x"], cols["y"], cols["z"]
    ip = cols.get("point")
    comma = sep != ","
    names: list[str] = []
    lines: list[int | None] = []
    xyz = np.empty((len(rows), 3))
    seen: dict[str, int] = {}
    for r, (lineno, line) in enumerate(rows):
        parts = line.split(sep)
        try:
            if len(parts) != width or '"' in line:
                raise ValueError
            vals = [parts[ix], parts[iy], parts[iz]]
            if comma:
                vals = [v.replace(",", ".") for v in vals]
            x, y, z = float(vals[0]), float(vals[1]), float(vals[2])
            if not (abs(x) <= MAX_MAGNITUDE and abs(y) <= MAX_MAGNITUDE
                    and abs(z) <= MAX_MAGNITUDE):
                raise ValueError
            name = parts[ip].strip() if ip is not None else f"P{r + 1}"
            if not name:
                raise ValueError
        except ValueError:
            (x, y, z), name = _careful(line, lineno, sep, width, (ix, iy, iz), ip, r, path)
        key = name.casefold()
        if key in seen:
            raise UcsioError(f"duplicate point name {name!r} (first on line {seen[key]})",
                             file=path, line=lineno,
                             col=split(line, sep)[ip][1] if ip is not None else None)
        seen[key] = lineno
        names.append(name)
        lines.append(lineno)
        xyz[r] = (x, y, z)
    return Points(path, names, lines, xyz)


def _careful(line: str, lineno: int, sep: str, width: int, axes, ip, r: int, path: str):
    """A line the fast read refused, field by field: its values, or the
    error naming the column."""
    fields = split(line, sep)
    if len(fields) < width:
        raise UcsioError(f"expected {width} fields (as the header), found {len(fields)}",
                         file=path, line=lineno, col=len(line.rstrip()) + 1)
    if len(fields) > width:
        hint = "; a decimal comma in a comma-separated file?" if sep == "," else ""
        raise UcsioError(f"{len(fields)} fields, but the header has {width}{hint}",
                         file=path, line=lineno, col=fields[width][1])
    out = []
    for axis, c in zip(AXES, axes):
        text, col = fields[c]
        s = text.strip()
        if sep != ",":
            s = s.replace(",", ".")
        try:
            v = float(s)
        except ValueError:
            what = "empty" if not s else f"not a number: {text!r}"
            raise UcsioError(f"{axis} {what}", file=path, line=lineno, col=col) from None
        if not math.isfinite(v):
            raise UcsioError(f"{axis} is not finite: {text!r}", file=path, line=lineno, col=col)
        if abs(v) > MAX_MAGNITUDE:
            raise UcsioError(f"{axis} {s} is too large: at most {MAX_MAGNITUDE:.0e} mm "
                             "(a unit or export error?)", file=path, line=lineno, col=col)
        out.append(v)
    if ip is None:
        return out, f"P{r + 1}"
    name, col = fields[ip]
    if not name.strip():
        raise UcsioError("empty point name", file=path, line=lineno, col=col)
    return out, name.strip()
