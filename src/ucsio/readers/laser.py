"""The laser side: points in the UCS, from the file the tracker software wrote.

One small function per export format, tried in the order of ``FORMATS``
(each with the test that recognises it):

- ``spec_csv``: SPEC's measurement CSV (``point``, ``laser_x/y/z``,
  ``weight``), read by ``measurement.py`` itself; a merged file's robot
  columns are ignored here.
- ``spatial_analyzer``: a SpatialAnalyzer ASCII point export: ``//`` header
  lines (version, frame, units, format), then ``Collection, Group, Target,
  X, Y, Z`` rows, comma or whitespace separated, numbers in any float form
  (``1.234560e+002``).
- ``plain_table``: any ``name x y z`` table, with or without a header row,
  separated by comma, semicolon, tab or spaces; a decimal comma is read where
  the separator is not a comma.

Coordinates are scaled to mm (``--laser-units``). Point names must be unique
(case-insensitive); a bad row is an error naming its file, line and column.
"""
from __future__ import annotations

import os
import re
from dataclasses import dataclass, field

import numpy as np

from ..defaults import LENGTH_UNITS
from ..errors import UcsioError
from .text import SEPARATORS, content_lines, coordinates, number, read_text, split

@dataclass
class LaserPoints:
    path: str
    format: str              # 'csv' | 'spatialanalyzer' | 'table'
    names: list[str]
    lines: list[int]
    xyz: np.ndarray          # (n, 3) mm, in the UCS
    weights: np.ndarray      # (n,)
    warnings: list[str] = field(default_factory=list)


# ---------------------------------------------------------------- formats

def is_spec_csv(text: str) -> bool:
    """A header with laser_x, on the first line or after Excel's sep= hint."""
    return any("laser_x" in line.lower() for _, line in content_lines(text)[:2])


def spec_csv(text: str, path: str) -> LaserPoints:
    from .measurement import parse_measurement

    m = parse_measurement(text, path, sides=("laser",))
    return LaserPoints(path, "csv", m.names, m.lines, m.laser, m.weights)


SA_COLUMNS = ("collection", "group", "target", "x", "y", "z")


def is_spatial_analyzer(text: str) -> bool:
    if any(line.lstrip().startswith("//") for line in text.splitlines()[:50]):
        return True
    rows = content_lines(text)
    if not rows:
        return False
    sep = _separator(rows, 6)
    first = split(rows[0][1], sep)
    if first and first[0][0].strip().casefold() == "collection":
        return True
    # no header: every row is three names and three numbers
    return all(len(f) == 6 and all(number(t, sep) is None for t, _ in f[:3])
               and all(number(t, sep) is not None for t, _ in f[3:])
               for f in (split(line, sep) for _, line in rows))


def spatial_analyzer(text: str, path: str) -> LaserPoints:
    """Target is the point's name; collection and group only tell two
    targets of the same name apart in an error."""
    return _table(text, path, "spatialanalyzer", SA_COLUMNS)


def plain_table(text: str, path: str) -> LaserPoints:
    return _table(text, path, "table", ("name", "x", "y", "z"))


#: (name, recognises, reads): tried in order; the last one takes anything
FORMATS = (
    ("csv", is_spec_csv, spec_csv),
    ("spatialanalyzer", is_spatial_analyzer, spatial_analyzer),
    ("table", lambda text: True, plain_table),
)


def read_laser(path: str | os.PathLike, units: str = "mm") -> LaserPoints:
    """The laser side of a measurement, in mm, whatever the export format."""
    path = os.fspath(path)
    if units not in LENGTH_UNITS:
        raise UcsioError(f"--laser-units {units!r}: expected one of {', '.join(LENGTH_UNITS)}")
    text = read_text(path, "laser file")
    for _name, recognises, read in FORMATS:
        if recognises(text):
            points = read(text, path)
            break
    if units != "mm":
        points.xyz = points.xyz * LENGTH_UNITS[units]
        _within_magnitude(points, units)
    return points


def _within_magnitude(points: LaserPoints, units: str) -> None:
    """The magnitude limit the readers hold each number to, once more in mm
    (a value in metres is a thousand times larger there)."""
    from ..defaults import MAX_MAGNITUDE
    from .text import too_large

    beyond = np.flatnonzero(np.abs(points.xyz).max(axis=1, initial=0.0) > MAX_MAGNITUDE)
    if beyond.size:
        i = int(beyond[0])
        raise UcsioError(too_large(f"point {points.names[i]!r}",
                                   f"({', '.join(f'{v:g}' for v in points.xyz[i])} mm)"),
                         file=points.path, line=points.lines[i])


# ---------------------------------------------------------------- tables

# what a header calls the point's name
NAME_WORDS = {"name", "point", "target", "id", "label", "pt", "punkt", "point name", "pointname"}
_UNIT_SUFFIX = re.compile(r"\s*[\[(].*$")


def _header_key(text: str) -> str:
    """'X [mm]' -> 'x', ' Target ' -> 'target'."""
    return _UNIT_SUFFIX.sub("", text).strip().strip('"').casefold()


def _numeric(fields, sep) -> int:
    return sum(number(t, sep) is not None for t, _ in fields)


def _separator(rows, width: int):
    """The first separator under which a row (the first, or the second after
    a header) has the layout's fields, three of them numbers."""
    for _, line in rows[:2]:
        for sep in SEPARATORS:
            fields = split(line, sep)
            if len(fields) >= width and _numeric(fields, sep) >= 3:
                return sep
    # no row reads well: the first separator that gives the header (or the
    # first row) its fields, so the error names the bad value
    return next((sep for sep in SEPARATORS if len(split(rows[0][1], sep)) >= width), None)


def _table(text: str, path: str, fmt: str, layout: tuple[str, ...]) -> LaserPoints:
    rows = content_lines(text)
    if not rows:
        raise UcsioError("no points: the file holds no data rows", file=path)
    width = len(layout)
    sep = _separator(rows, width)
    name_col, cols = None, None
    first_fields = split(rows[0][1], sep)
    if _numeric(first_fields, sep) < 3:
        # a header row: find the columns by their names
        hline = rows[0][0]
        keys = [_header_key(t) for t, _ in first_fields]
        try:
            cols = [keys.index(k) for k in ("x", "y", "z")]
        except ValueError:
            raise UcsioError(f"header {rows[0][1].strip()!r}: expected columns named X, Y and Z"
                             + (" (collection, group, target, x, y, z)" if width == 6 else
                                " (name, x, y, z)"), file=path, line=hline) from None
        wanted = ("target", "point", "name") if width == 6 else NAME_WORDS
        name_col = next((i for i, k in enumerate(keys) if k in wanted), 0 if width == 4 else 2)
        rows = rows[1:]
        if not rows:
            raise UcsioError("no data rows after the header", file=path, line=hline)
    names: list[str] = []
    lines: list[int] = []
    xyz = []
    seen: dict[str, tuple[int, str]] = {}
    for lineno, line in rows:
        fields = split(line, sep)
        if cols is None:
            # no header: the last three fields are x, y, z, the one before
            # them the name (a name may hold spaces in a space-separated file)
            if len(fields) < 4:
                raise UcsioError(f"expected {' '.join(layout)}, found {len(fields)} field"
                                 f"{'s' if len(fields) != 1 else ''}", file=path, line=lineno,
                                 col=len(line.rstrip()) + 1)
            values = coordinates(fields, (len(fields) - 3, len(fields) - 2, len(fields) - 1),
                                 sep, path, lineno)
            if width == 6 and len(fields) >= 6:
                name, ncol = fields[-4]
                group = " ".join(t for t, _ in fields[:-4])
            else:
                name = " ".join(t for t, _ in fields[:-3])
                ncol, group = fields[0][1], ""
        else:
            values = coordinates(fields, cols, sep, path, lineno)
            if name_col >= len(fields):
                raise UcsioError("no point name in this row", file=path, line=lineno)
            name, ncol = fields[name_col]
            group = ""
        name = name.strip()
        if not name:
            raise UcsioError("empty point name", file=path, line=lineno, col=ncol)
        key = name.casefold()
        if key in seen:
            first, first_group = seen[key]
            where = (f" (groups {first_group!r} and {group!r}: export one group)"
                     if group and first_group != group else "")
            raise UcsioError(f"duplicate point name {name!r} (first on line {first}){where}",
                             file=path, line=lineno, col=ncol)
        seen[key] = (lineno, group)
        names.append(name)
        lines.append(lineno)
        xyz.append(values)
    return LaserPoints(path, fmt, names, lines, np.array(xyz, dtype=float), np.ones(len(names)))
