"""Measurement files: laser tracker points paired with robot flange poses,
read into ``method.measurement.Measurement``.

The format (../shared/SPEC.md, "Measurement files"): a CSV with a header row;
columns in any order, header names case-insensitive:

- ``point`` (optional; default P1, P2, ...)
- ``laser_x, laser_y, laser_z``: the point in the UCS (mm)
- ``robot_x, robot_y, robot_z``: the flange position in robot world (mm)
- the flange orientation in exactly one form: ``robot_a, robot_b, robot_c``
  (KUKA, deg), ``robot_q1 .. robot_q4`` (ABB, q1 real), ``robot_w, robot_p,
  robot_r`` (Fanuc, deg)
- ``weight`` (optional, default 1; must be positive)

Other columns are ignored (``comment``, ``time``, ...), but a header name
that is a near miss of a known one (``weigth``, ``laser-x``, ``robot_q5``)
is an error with the suggestion: a typo must not silently drop a column.
Lines starting with ``#``, blank lines and rows whose fields are all empty
(``;;;;;``, as spreadsheets export) are skipped. A header containing ``;``
means a European export: ``;`` separates fields and a decimal comma is
accepted (``1234,5``). Tab-separated files work too. Excel's separator hint,
a first line ``sep=;`` (or ``sep=,`` ...), sets the separator. A data row
with fewer fields than the known columns need, or with more fields than the
header (a decimal comma in a comma-separated file shifts the columns), is an
error. Every error names the file, the line and (where it is one cell) the
column.
"""
from __future__ import annotations

import difflib
import math
import os
import re

import numpy as np

from .. import vendors
from ..defaults import LENGTH_UNITS, MAX_MAGNITUDE
from ..errors import UcsioError
from ..geometry.arrays import flange_matrices
from ..method.measurement import Measurement, spec_orientation
from ..parsing.document import text_lines
from ..vendors import measurement_forms
from .text import read_text, too_large

#: Each vendor's orientation columns, by its name (``Measurement.form``), as
#: the vendors declare them (``measurement_columns``).
FORMS = dict(measurement_forms())
POSITION = ("laser_x", "laser_y", "laser_z", "robot_x", "robot_y", "robot_z")
KNOWN = set(POSITION) | {"point", "weight"} | {c for cols in FORMS.values() for c in cols.names}

#: A header name this close to a known one (difflib ratio) is taken for a
#: typo of it: ``weigth``/``weight`` 0.83, ``laser-x``/``laser_x`` 0.86,
#: ``robot_q5``/``robot_q4`` 0.88; everyday extra columns (``comment``,
#: ``note``, ``time``, ``timestamp``, ``operator``) score below 0.55.
NEAR_MISS_CUTOFF = 0.8
#: Extra columns that are legitimately close to a known name: the rest of a
#: KUKA E6POS (S, T, E1..E6) or axis values (A1..A6), joints, ABB robconf and
#: external axes, deviations and tracker statistics.
EXTRA_OK = re.compile(r"robot_(s|t|status|turn|e\d+|a\d+|j\d+|axis_?\d+|cf[146x]|cfg|conf\w*|"
                      r"eax\w*|ext\w*)|(laser|robot)_(d[xyz]|dist|rms|sigma|std|err\w*|unc\w*)")
#: Orientation columns in other vendors' or tools' names (``robot_rx``,
#: ``robot_yaw``, ``robot_qw``): the answer is the forms ucsio reads, not
#: the nearest spelling (``robot_rx`` is one letter from ``robot_x``).
OTHER_ORIENTATION = re.compile(r"robot_(r[xyz]|rot_?[xyz]|roll|pitch|yaw|q[wxyz]|quat\w*|"
                               r"euler\w*|orient\w*|[abcwpr]_?deg)")
ORIENTATION_FORMS = ("robot_a, robot_b, robot_c (KUKA A, B, C, deg); robot_q1 .. robot_q4 "
                     "(ABB quaternion, q1 the real part); or robot_w, robot_p, robot_r (FANUC "
                     "W, P, R, deg; also Yaskawa's Rx, Ry, Rz, the same R = Rz·Ry·Rx)")
#: Excel's separator hint, the first line of a file: ``sep=;``.
SEP_HINT = re.compile(r'\s*"?sep=(.)"?\s*', re.IGNORECASE)
SEPARATORS = (",", ";", "\t", "|")

#: ABB quaternions are read back to 6 decimals; further off than this from
#: unit norm is a typo or a wrong column, not rounding.
QUAT_NORM_TOLERANCE = 1e-3
SIDES = ("laser", "robot")
#: How a CSV's numbers are written where the file cannot say: ``--laser-units``
#: (defaults.LENGTH_UNITS), ``--angle-units`` for robot_a/b/c and robot_w/p/r,
#: ``--quaternion-order`` for robot_q1..q4 (SPEC's order is q1 the real part).
ANGLE_UNITS = ("deg", "rad")
QUATERNION_ORDERS = ("wxyz", "xyzw")


def check_reading(angle_units: str = "deg", quaternion_order: str = "wxyz") -> None:
    """The two spellings options, from the command line, the API or a manifest."""
    if angle_units not in ANGLE_UNITS:
        raise UcsioError(f"--angle-units {angle_units!r}: expected deg or rad")
    if quaternion_order not in QUATERNION_ORDERS:
        raise UcsioError(f"--quaternion-order {quaternion_order!r}: expected wxyz or xyzw")


# ---------------------------------------------------------------- reading

def _split(line: str, sep: str) -> list[tuple[str, int]]:
    """Fields of one line with their 1-based start column; double quotes
    may enclose a field (``""`` inside is a quote)."""
    fields: list[tuple[str, int]] = []
    i, n = 0, len(line)
    while True:
        start = i
        while i < n and line[i] in " \t" and sep != "\t":
            i += 1
        if i < n and line[i] == '"':
            i += 1
            buf = []
            while i < n:
                if line[i] == '"':
                    if i + 1 < n and line[i + 1] == '"':
                        buf.append('"')
                        i += 2
                        continue
                    i += 1
                    break
                buf.append(line[i])
                i += 1
            text = "".join(buf)
            while i < n and line[i] != sep:
                i += 1
            fields.append((text, start + 1))
        else:
            j = line.find(sep, i)
            j = n if j < 0 else j
            fields.append((line[start:j].strip(), start + 1))
            i = j
        if i >= n:
            return fields
        i += 1   # the separator
        if i == n:
            fields.append(("", i + 1))
            return fields


def _either(forms: dict) -> str:
    """'robot_a/b/c (KUKA), robot_q1..q4 (ABB) or robot_w/p/r (Fanuc)'."""
    labels = [cols.label for cols in forms.values()]
    return ", ".join(labels[:-1]) + " or " + labels[-1] if len(labels) > 1 else labels[0]


def read_measurement(path: str | os.PathLike, sides: tuple[str, ...] = SIDES,
                     what: str = "measurement file", **reading) -> Measurement:
    """Read a measurement CSV; UcsioError (exit 2) on anything wrong.
    ``sides``: the columns required, ``("laser",)`` or ``("robot",)`` for one
    side of a measurement (``solve --laser/--robot``); the other side's
    columns are then not needed (and its array is None). ``reading``:
    ``laser_units``, ``angle_units``, ``quaternion_order``."""
    path = os.fspath(path)
    return parse_measurement(read_text(path, what), path, sides, **reading)


def parse_measurement(text: str, path: str = "<measurement>",
                      sides: tuple[str, ...] = SIDES, *, laser_units: str = "mm",
                      angle_units: str = "deg", quaternion_order: str = "wxyz") -> Measurement:

    check_reading(angle_units, quaternion_order)
    if laser_units not in LENGTH_UNITS:
        raise UcsioError(f"--laser-units {laser_units!r}: expected one of {', '.join(LENGTH_UNITS)}")
    laser_side, robot_side = "laser" in sides, "robot" in sides
    text = text.lstrip("\ufeff")
    header = None
    rows: list[tuple[int, list[tuple[str, int]]]] = []
    sep = ","
    hinted = False
    for lineno, line in enumerate(text_lines(text), start=1):   # the one rule for line ends
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        if header is None and not hinted:
            m = SEP_HINT.fullmatch(line)
            if m:                                   # Excel: "sep=;" before the header
                if m.group(1) not in SEPARATORS:
                    raise UcsioError(f"separator hint {stripped!r}: expected sep=, sep=; "
                                     "sep=| or a tab", file=path, line=lineno)
                sep, hinted = m.group(1), True
                continue
        if not stripped.strip(",;|\t \"" + sep):
            continue                                # a spreadsheet row of empty cells
        if header is None:
            if not hinted:
                sep = ";" if ";" in line else ("\t" if "\t" in line else ",")
            header = (lineno, _split(line, sep))
            continue
        rows.append((lineno, _split(line, sep)))
    if header is None:
        first = "laser_x, laser_y" if laser_side else "robot_x, robot_y"
        raise UcsioError(f"no header row (expected {first}, ... columns)", file=path)
    decimal_comma = sep != ","

    header_line, header_fields = header
    columns: dict[str, int] = {}
    for idx, (name, col) in enumerate(header_fields):
        key = name.strip().lower()
        if key in KNOWN:
            if key in columns:
                raise UcsioError(f"column {key!r} given twice", file=path, line=header_line, col=col)
            columns[key] = idx
        elif OTHER_ORIENTATION.fullmatch(key):
            raise UcsioError(f"unknown column {name.strip()!r}: the flange orientation is read "
                             f"as {ORIENTATION_FORMS}", file=path, line=header_line, col=col)
        elif key and not EXTRA_OK.fullmatch(key):
            close = difflib.get_close_matches(key, sorted(KNOWN), n=1, cutoff=NEAR_MISS_CUTOFF)
            if close:
                raise UcsioError(f"unknown column {name.strip()!r} \u2014 did you mean "
                                 f"{close[0]!r}?", file=path, line=header_line, col=col)

    present = [form for form, cols in FORMS.items() if any(c in columns for c in cols.names)]
    if not robot_side:
        present = present[:1]       # the laser side of a merged file: orientation unused
    if len(present) > 1:
        raise UcsioError("flange orientation given in two forms: "
                         + " and ".join(FORMS[f].label for f in present)
                         + "; keep exactly one", file=path, line=header_line)
    if not present and robot_side:
        raise UcsioError(f"no flange orientation columns: need {_either(FORMS)}",
                         file=path, line=header_line)
    form = present[0] if present else "none"
    needed = ((POSITION[:3] if laser_side else ()) + (POSITION[3:] if robot_side else ())
              + (FORMS[form].names if robot_side else ()))
    missing = [c for c in needed if c not in columns]
    if missing:
        raise UcsioError(f"missing column{'s' if len(missing) > 1 else ''} "
                         + ", ".join(missing), file=path, line=header_line)
    if not rows:
        raise UcsioError("no data rows after the header", file=path, line=header_line)

    width = max(columns.values()) + 1
    names: list[str] = []
    seen: dict[str, int] = {}
    lines: list[int] = []
    values = np.empty((len(rows), len(needed)))
    weights = np.ones(len(rows))

    def number(fields, key, lineno) -> float:
        text, col = fields[columns[key]]
        s = text.strip()
        if decimal_comma:
            s = s.replace(",", ".")
        try:
            v = float(s)
        except ValueError:
            what = "empty" if not s else f"not a number: {text!r}"
            raise UcsioError(f"{key} {what}", file=path, line=lineno, col=col) from None
        if not math.isfinite(v):
            raise UcsioError(f"{key} is not finite: {text!r}", file=path, line=lineno, col=col)
        if abs(v) > MAX_MAGNITUDE:
            raise UcsioError(too_large(key, text.strip()), file=path, line=lineno, col=col)
        return v

    for r, (lineno, fields) in enumerate(rows):
        if len(fields) < width:
            raise UcsioError(f"expected at least {width} fields, found {len(fields)}",
                             file=path, line=lineno)
        if len(fields) > len(header_fields):
            hint = ("; a decimal comma in a comma-separated file?" if sep == ","
                    else "")
            raise UcsioError(f"{len(fields)} fields, but the header (line {header_line}) has "
                             f"{len(header_fields)}: the columns would shift{hint}",
                             file=path, line=lineno, col=fields[len(header_fields)][1])
        for k, key in enumerate(needed):
            values[r, k] = number(fields, key, lineno)
        if "weight" in columns and fields[columns["weight"]][0].strip():
            wv = number(fields, "weight", lineno)
            if wv <= 0:
                raise UcsioError(f"weight must be positive, got {wv:g}", file=path, line=lineno,
                                 col=fields[columns["weight"]][1])
            weights[r] = wv
        name = fields[columns["point"]][0].strip() if "point" in columns else ""
        name = name or f"P{r + 1}"
        key = name.casefold()
        if key in seen:
            raise UcsioError(f"duplicate point name {name!r} (first on line {seen[key]})",
                             file=path, line=lineno,
                             col=fields[columns["point"]][1] if "point" in columns else None)
        seen[key] = lineno
        names.append(name)
        lines.append(lineno)

    if laser_side:
        values[:, 0:3] *= LENGTH_UNITS[laser_units]
    if not robot_side:
        return Measurement(path=path, names=names, lines=lines, laser=values[:, 0:3].copy(),
                           flange=None, weights=weights, form=form, orientation=None)
    laser = values[:, 0:3] if laser_side else None
    k = 3 if laser_side else 0
    position = values[:, k:k + 3]
    orientation = values[:, k + 3:]
    convention = vendors.get(form).angles
    if convention.quaternion:
        norms = np.linalg.norm(orientation, axis=1)
        bad = np.flatnonzero(np.abs(norms - 1.0) > QUAT_NORM_TOLERANCE)
        if bad.size:
            i = int(bad[0])
            first = FORMS[form].names[0]
            raise UcsioError(f"{FORMS[form].short} is not a unit quaternion "
                             f"(norm {norms[i]:.6g})",
                             file=path, line=lines[i], col=rows[i][1][columns[first]][1])
    flange = flange_matrices(
        convention, spec_orientation(convention, orientation, angle_units, quaternion_order),
        position)
    return Measurement(path=path, names=names, lines=lines,
                       laser=None if laser is None else laser.copy(), flange=flange,
                       weights=weights, form=form, orientation=orientation.copy())
