"""The unified diff of a patch: the file's lines around what changed, as
difflib writes them, without splitting and matching the whole file.
"""
from __future__ import annotations

import bisect
import os

from ..parsing import regex
from ..parsing.document import Document, text_lines


def unified_diff(doc: Document, new_bytes: bytes, label: str | None = None, n: int = 1) -> str:
    new_text = Document(new_bytes, doc.path).text
    label = (label or doc.path).replace(os.sep, "/").lstrip("/")
    old_text = doc.text
    # a patch changes a few lines: only they and their context are split
    # into lines and given to difflib (splitting and matching a 2.6 MB module
    # was a third of a patch); hunk headers are moved back to the file's lines
    starts = doc.line_starts
    first = _common_run(old_text, new_text, min(len(old_text), len(new_text)))
    tail = _common_run(old_text, new_text, min(len(old_text), len(new_text)) - first,
                       from_end=True)
    top = max(0, bisect.bisect_right(starts, first) - 1 - n - 1)
    bottom = bisect.bisect_right(starts, len(old_text) - tail) + n + 1
    begin = starts[top]
    end = starts[bottom] if bottom < len(starts) else len(old_text)
    a = text_lines(old_text[begin:end])
    b = text_lines(new_text[begin:end + len(new_text) - len(old_text)])
    out = unified_lines(a, b, f"a/{label}", f"b/{label}", n, shift=top)
    return "\n".join(out) + ("\n" if new_text != old_text else "")


def common_ends(a: list, b: list) -> tuple[int, int]:
    """How many items two sequences share at their start, and then at their end."""
    lo, limit = 0, min(len(a), len(b))
    while lo < limit and a[lo] == b[lo]:
        lo += 1
    hi = 0
    while hi < limit - lo and a[-1 - hi] == b[-1 - hi]:
        hi += 1
    return lo, hi


def unified_lines(a: list[str], b: list[str], old_label: str, new_label: str, n: int,
                  shift: int = 0):
    """difflib.unified_diff of two lists of lines, its hunk headers ``shift``
    lines further on. Only the lines between what the two share at both ends
    (and ``n`` of those, the context) go to difflib: its matcher slows to a
    crawl on the thousands of equal lines of a listing (a sysframe.va's
    unset frames)."""
    lo, hi = common_ends(a, b)
    hunk = _one_hunk(a, b, lo, hi, old_label, new_label, n, shift)
    if hunk is not None:
        return hunk
    return _difflib_lines(a, b, lo, hi, old_label, new_label, n, shift)


def _one_hunk(a: list[str], b: list[str], lo: int, hi: int, old_label: str, new_label: str,
              n: int, shift: int) -> list[str] | None:
    """The one hunk difflib writes where the lines that differ (between the
    ``lo`` and ``hi`` lines the two share at their ends) hold no line found
    anywhere on the other side: what a patch's rewritten numbers give. Its
    matcher can then only pair the context, so the hunk is the context, the
    old lines and the new ones (tests/test_patch.py holds it to difflib).
    None where difflib must match; [] where nothing differs."""
    old, new = a[lo:len(a) - hi], b[lo:len(b) - hi]
    if not old and not new:
        return []
    before, after = min(n, lo), min(n, hi)
    a_part, b_part = a[lo - before:len(a) - hi + after], b[lo - before:len(b) - hi + after]
    if not set(old).isdisjoint(b_part) or not set(new).isdisjoint(a_part):
        return None
    start = shift + lo - before
    return [f"--- {old_label}", f"+++ {new_label}",
            f"@@ -{_range(start, len(a_part))} +{_range(start, len(b_part))} @@",
            *(" " + line for line in a_part[:before]), *("-" + line for line in old),
            *("+" + line for line in new), *(" " + line for line in a_part[len(a_part) - after:])]


def _range(start: int, length: int) -> str:
    """A hunk header's range as difflib writes it (0-based ``start``)."""
    if length == 1:
        return str(start + 1)
    return f"{start + 1 if length else start},{length}"


def _difflib_lines(a: list[str], b: list[str], lo: int, hi: int, old_label: str,
                   new_label: str, n: int, shift: int):
    lo, hi = max(0, lo - n), max(0, hi - n)
    import difflib          # only where a diff is shown

    out = difflib.unified_diff(a[lo:len(a) - hi], b[lo:len(b) - hi], old_label, new_label,
                               n=n, lineterm="")
    shift += lo
    if shift:
        out = (_HUNK.sub(lambda m: f"@@ -{int(m[1]) + shift}{m[2] or ''} "
                                   f"+{int(m[3]) + shift}{m[4] or ''} @@", line, count=1)
               if line.startswith("@@") else line for line in out)
    return out


def _common_run(a: str, b: str, limit: int, from_end: bool = False) -> int:
    """Length (at most ``limit``) of the longest common prefix of a and b,
    or with ``from_end`` of their longest common suffix: slices compared in
    C, doubling, then halving."""
    na, nb = len(a), len(b)

    def same(lo: int, hi: int) -> bool:      # the run from lo to hi chars in
        if from_end:
            return a[na - hi:na - lo] == b[nb - hi:nb - lo]
        return a[lo:hi] == b[lo:hi]

    lo, step = 0, 4096
    while lo < limit:
        hi = min(limit, lo + step)
        if not same(lo, hi):
            while hi - lo > 1:          # the first lo agree, the first hi do not
                mid = (lo + hi) // 2
                if same(lo, mid):
                    lo = mid
                else:
                    hi = mid
            return lo
        lo, step = hi, step * 2
    return limit


_HUNK = regex.lazy(r"^@@ -(\d+)(,\d+)? \+(\d+)(,\d+)? @@")
