"""Printing: JSON for scripts, aligned tables for people."""
from __future__ import annotations

import math
import os
import sys

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from typing import Any, Iterable, Sequence


#: The version of the JSON every command prints with --json and of the
#: SOLUTION.json ``solve -o`` writes: one integer, the same in every
#: document, raised only when a key scripts rely on changes its meaning or
#: goes away (new keys do not raise it). docs/json.md; docs/schema/.
SCHEMA_VERSION = 1


def versioned(doc: dict[str, Any]) -> dict[str, Any]:
    """``doc`` with ``schema_version`` first (a copy; a document that has it
    is returned as it is)."""
    if "schema_version" in doc:
        return doc
    return {"schema_version": SCHEMA_VERSION, **doc}


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


def _plain(obj: Any) -> Any:
    if hasattr(obj, "tolist"):       # numpy arrays and scalars (float64 is a float already)
        return obj.tolist()
    raise TypeError(f"{type(obj).__name__} is not JSON serializable")


def emit_json(obj: Any, stream=None, *, document: bool = True) -> None:
    """``obj`` as JSON: indented on a terminal, where a person reads it;
    otherwise one line from json's C encoder, in one pass (indenting forces
    the pure-Python encoder: seconds for a 10,000-entry batch). A
    ``document`` (a command's --json output) gets ``schema_version``; a
    format defined elsewhere (SARIF, GitLab's) is printed as it is."""
    import json         # a table on a terminal needs none of it

    if document and isinstance(obj, dict):
        obj = versioned(obj)
    stream = stream or sys.stdout
    isatty = getattr(stream, "isatty", None)
    indent = 2 if isatty is not None and isatty() else None
    try:
        text = json.dumps(obj, indent=indent, ensure_ascii=False, allow_nan=False, default=_plain)
    except ValueError:               # a NaN or inf somewhere: those become null
        text = json.dumps(_clean(obj), indent=indent, ensure_ascii=False)
    stream.write(text + "\n")


def fmt(v: Any, digits: int = 3, none: str = "-") -> str:
    """A value for a table: fixed decimals, yes/no, ``none`` for null or NaN."""
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return none
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return f"{v:.{digits}f}"
    return str(v)


def shown_difference(new: float, old: float, digits: int, wrap: bool = False) -> float:
    """new − old of the two values as a table shows them (``digits``
    decimals), so a Δ row adds up to the rows above it; ``wrap``: an angle's,
    in (−180, 180]."""
    d = round(new, digits) - round(old, digits)
    if wrap:
        d = -((-d + 180.0) % 360.0 - 180.0)
    return round(d, digits) + 0.0


def table(headers: Sequence[str], rows: Iterable[Sequence[Any]], right: set[int] | None = None) -> str:
    rows = [[str(c) for c in r] for r in rows]
    right = right if right is not None else set()
    if all(len(r) == len(headers) for r in rows):
        # one format per line (a listing of a few hundred frames is a table of thousands
        # of cells, formatted on every run of a command that reads one file)
        widths = [max(map(len, column)) for column in zip(headers, *rows)]
        form = "  ".join(f"{{:{'>' if i in right else '<'}{w}}}" for i, w in enumerate(widths))
        return "\n".join(form.format(*r).rstrip()
                         for r in [list(headers), ["-" * w for w in widths], *rows])
    widths = [len(h) for h in headers]
    for r in rows:
        for i, c in enumerate(r):
            widths[i] = max(widths[i], len(c))

    def line(cells):
        out = []
        for i, c in enumerate(cells):
            out.append(c.rjust(widths[i]) if i in right else c.ljust(widths[i]))
        return "  ".join(out).rstrip()

    return "\n".join([line(headers), line(["-" * w for w in widths])] + [line(r) for r in rows])


# ANSI styles for what a reviewer must not miss: PASS/FAIL and diff lines.
_STYLES = {"pass": "32", "fail": "1;31", "add": "32", "remove": "31", "change": "33",
           "info": "36", "head": "1", "hunk": "36"}


def colour_on(stream=None) -> bool:
    """Colour only on a terminal, and never when NO_COLOR is set (no-color.org)
    or the terminal is dumb: a pipe or a file gets plain text."""
    stream = stream or sys.stdout
    if os.environ.get("NO_COLOR") or os.environ.get("TERM") == "dumb":
        return False
    isatty = getattr(stream, "isatty", None)
    try:
        return bool(isatty and isatty())
    except ValueError:          # a closed stream
        return False


def paint(text: str, style: str, stream=None) -> str:
    """``text`` in ``style`` when ``stream`` (default stdout) shows colour."""
    if not text or not colour_on(stream):
        return text
    return f"\033[{_STYLES[style]}m{text}\033[0m"


def paint_diff(text: str, stream=None) -> str:
    """A unified diff or ucsio's frame review, coloured line by line like git's."""
    if not colour_on(stream):
        return text
    out = []
    for line in text.split("\n"):
        s = line.lstrip()
        if line.startswith(("+++", "---")):
            out.append(paint(line, "head", stream))
        elif line.startswith("@@"):
            out.append(paint(line, "hunk", stream))
        elif s.startswith("+"):
            out.append(paint(line, "add", stream))
        elif s.startswith("-"):
            out.append(paint(line, "remove", stream))
        elif s.startswith("~"):
            out.append(paint(line, "change", stream))
        else:
            out.append(line)
    return "\n".join(out)
