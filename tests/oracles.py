"""What a patch may change, as a test oracle (tests/test_hostile.py, the fuzz tests).

A patch replaces a frame's numbers and, where a value needs the other sign,
deletes a sign that a comment or line break parts from its digits
(frames.Number.signs); in a TP program a negative value's one pair of
parentheses comes and goes with its sign (``(-4)`` -> ``5``, the pendant's
form). Everything else — comments, line breaks, spacing,
other frames — stays byte for byte."""
from __future__ import annotations

import re

from ucsio.geometry.frames import Frame

# one pair of parentheses right around a number (its blanks inside): a TP
# program's negative literal; a deeper pair stays and must stay
_PAIR = re.compile("\\([ \t]*\0[ \t]*\\)")


def skeleton(text: str, frames: list[Frame]) -> str:
    """``text`` with every number of ``frames`` replaced by NUL, their
    detached signs removed, and blanks right before a number dropped (KUKA
    "{X.5" becomes "{X 2.5": the blank the grammar needs): what no patch of
    those frames may change."""
    cuts = []
    for f in frames:
        for n in f.numbers.values():
            cuts.append((n.span.start, n.span.end, "\0"))
            cuts += [(s.start, s.end, "") for s in n.signs]
    out, pos = [], 0
    for start, end, mark in sorted(cuts):
        assert start >= pos, "overlapping number spans"
        out.append(text[pos:start].rstrip(" \t") if mark else text[pos:start])
        out.append(mark)
        pos = end
    out.append(text[pos:])
    return _PAIR.sub("\0", "".join(out))


def only_numbers_changed(old_text: str, old_frames: list[Frame], new_text: str,
                         new_frames: list[Frame]) -> bool:
    """The two texts differ only inside the numbers (and detached signs) of
    the patched frames, parsed from each text."""
    return skeleton(old_text, old_frames) == skeleton(new_text, new_frames)
