"""Numbers given on the command line (or by the API as text): three for
a TCP, n for a pose or an orientation. Below the commands, so that what
they share with ``programs`` and ``demo`` is read once, alike."""
from __future__ import annotations

from ..errors import UcsioError


def parse_values(text: str, n: int, option: str):
    parts = [s for s in text.replace(";", ",").split(",")]
    try:
        values = [float(s) for s in parts]
    except ValueError:
        raise UcsioError(f"{option} {text!r}: expected {n} numbers separated by commas") from None
    if len(values) != n or not all(v == v and abs(v) != float("inf") for v in values):
        raise UcsioError(f"{option} {text!r}: expected {n} finite numbers separated by commas")
    return values


def parse_tcp(text: str) -> tuple[float, float, float]:
    parts = [s.strip() for s in text.replace(";", ",").split(",")]
    try:
        vals = tuple(float(s) for s in parts)
    except ValueError:
        raise UcsioError(f"--tcp {text!r}: expected three numbers X,Y,Z (mm)") from None
    return check_tcp(vals, repr(text))


def check_tcp(vals, shown: str) -> tuple[float, float, float]:
    """Three finite numbers (mm) within the magnitude any value may have."""
    import math
    from ..defaults import MAX_MAGNITUDE
    try:
        vals = tuple(float(v) for v in vals)
    except (TypeError, ValueError):
        raise UcsioError(f"--tcp {shown}: expected three numbers X,Y,Z (mm)") from None
    if len(vals) != 3 or not all(math.isfinite(v) for v in vals):
        raise UcsioError(f"--tcp {shown}: expected three finite numbers X,Y,Z (mm)")
    if any(abs(v) > MAX_MAGNITUDE for v in vals):
        raise UcsioError(f"--tcp {shown}: at most {MAX_MAGNITUDE:.0e} mm in magnitude")
    return vals  # type: ignore[return-value]
