"""Plain-text tables as tracker software exports them: decoding, comment
lines, separators, decimal commas, numbers with the column they stand in.

Every field keeps its 1-based column, so a bad value is reported as
``file:line:col``."""
from __future__ import annotations

import bisect
import math
import re

from ..defaults import MAX_MAGNITUDE
from ..errors import UcsioError
from ..parsing.document import text_lines

#: candidate separators in the order they are tried; None is "runs of
#: spaces or tabs" (fixed-width or whitespace-separated exports)
SEPARATORS = (";", "\t", ",", None)
_WS_FIELD = re.compile(r"\S+")


def read_text(path: str, what: str) -> str:
    """The text of a table file (``decode``); ``what`` names it in errors."""
    from ..files import read_bytes

    return decode(read_bytes(path, what), path)


def decode(raw: bytes, path: str = "<text>") -> str:
    """UTF-8 (BOM or not), UTF-16 with its byte-order mark (Excel's and
    Notepad's "Unicode"), else Windows-1252: what tracker PCs write. A NUL
    or other control character is refused at its line and column: it is no
    part of a name or a number, and would make a point a different one."""
    if raw.startswith(_UTF16_BOMS):
        try:
            text = raw.decode("utf-16")
        except UnicodeDecodeError:
            raise UcsioError("UTF-16 text that does not decode: save it as UTF-8",
                             file=path) from None
    else:
        if raw.startswith(b"\xef\xbb\xbf"):
            raw = raw[3:]
        try:
            text = raw.decode("utf-8")
        except UnicodeDecodeError:
            text = raw.decode("cp1252", errors="replace")
    bad = _CONTROL.search(text)
    if bad is not None:
        raise _control_error(raw, text, bad.start(), path)
    return text


_UTF16_BOMS = (b"\xff\xfe", b"\xfe\xff")
# what no text file holds (the controller files' binary rule): C0 controls
# but tab, LF, FF and CR
_CONTROL = re.compile(r"[\x00-\x08\x0b\x0e-\x1f]")


def _control_error(raw: bytes, text: str, at: int, path: str) -> UcsioError:
    """UTF-16 saved without its mark (every other byte a NUL), or one
    control character where it does not belong."""
    from ..parsing.document import line_starts

    if raw.count(0) * 3 >= len(raw):
        return UcsioError("UTF-16 text without a byte-order mark: save it as UTF-8", file=path)
    starts = line_starts(text)
    line = bisect.bisect_right(starts, at)
    return UcsioError(f"control character {ord(text[at]):#04x} in the text (a NUL inside a name "
                      "or a number makes it another one): remove it", file=path, line=line,
                      col=at - starts[line - 1] + 1)


def content_lines(text: str) -> list[tuple[int, str]]:
    """(line number, text) of the lines that hold data or a header: blank
    lines and ``#`` or ``//`` comment lines are left out."""
    out = []
    for lineno, line in enumerate(text_lines(text), start=1):   # the one rule for line ends
        s = line.strip()
        if s and not s.startswith(("#", "//")):
            out.append((lineno, line))
    return out


def split(line: str, sep: str | None) -> list[tuple[str, int]]:
    """Fields of a line with their 1-based start column; surrounding spaces
    and double quotes are taken off a field."""
    if sep is None:
        return [(_unquote(m.group()), m.start() + 1) for m in _WS_FIELD.finditer(line)]
    fields = []
    start = 0
    for part in line.split(sep):
        lead = len(part) - len(part.lstrip())
        fields.append((_unquote(part.strip()), start + lead + 1))
        start += len(part) + len(sep)
    return fields


def _unquote(s: str) -> str:
    return s[1:-1] if len(s) >= 2 and s[0] == s[-1] == '"' else s


def number(text: str, sep: str | None) -> float | None:
    """The value of a field, or None if it is not a finite number. A decimal
    comma is read where the separator is not a comma."""
    s = text.strip()
    if sep != "," and "," in s and "." not in s:
        s = s.replace(",", ".")
    try:
        v = float(s)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


def too_large(what: str, text: str) -> str:
    """The error for a number no fit can use (``defaults.MAX_MAGNITUDE``)."""
    return (f"{what} {text} is too large for a fit: at most {MAX_MAGNITUDE:.0e} in magnitude "
            "(double precision cannot resolve a micrometre beyond it; a unit or export error?)")


def coordinates(fields, cols, sep, path: str, lineno: int, labels=("x", "y", "z")):
    """The numbers in columns ``cols`` of one row; a bad one is an error
    naming its line and column: not a finite number, or beyond the
    magnitude any fit (solve, plan) can use."""
    out = []
    for c, label in zip(cols, labels):
        if c >= len(fields):
            raise UcsioError(f"{label}: missing (the row has {len(fields)} fields)",
                             file=path, line=lineno)
        text, col = fields[c]
        v = number(text, sep)
        if v is None:
            what = "empty" if not text.strip() else f"not a finite number: {text!r}"
            raise UcsioError(f"{label} {what}", file=path, line=lineno, col=col)
        if abs(v) > MAX_MAGNITUDE:
            raise UcsioError(too_large(label, text.strip()), file=path, line=lineno, col=col)
        out.append(v)
    return out
