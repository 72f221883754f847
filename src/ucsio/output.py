"""Printing: JSON for scripts, aligned tables for people."""
from __future__ import annotations

import json
import math
import sys
from typing import Any, Iterable, Sequence


def _clean(obj: Any) -> Any:
    # JSON has no NaN/inf; a number a script cannot read is worse than null.
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    if hasattr(obj, "tolist"):       # numpy arrays and scalars
        return _clean(obj.tolist())
    return obj


def emit_json(obj: Any, stream=None) -> None:
    stream = stream or sys.stdout
    json.dump(_clean(obj), stream, indent=2, ensure_ascii=False)
    stream.write("\n")


def fmt(v: Any, digits: int = 3, none: str = "-") -> str:
    """A value for a table: fixed decimals, yes/no, ``none`` for null or NaN."""
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return none
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return f"{v:.{digits}f}"
    return str(v)


def table(headers: Sequence[str], rows: Iterable[Sequence[Any]], right: set[int] | None = None) -> str:
    rows = [[str(c) for c in r] for r in rows]
    widths = [len(h) for h in headers]
    for r in rows:
        for i, c in enumerate(r):
            widths[i] = max(widths[i], len(c))
    right = right if right is not None else set()

    def line(cells):
        out = []
        for i, c in enumerate(cells):
            out.append(c.rjust(widths[i]) if i in right else c.ljust(widths[i]))
        return "  ".join(out).rstrip()

    return "\n".join([line(headers), line(["-" * w for w in widths])] + [line(r) for r in rows])
