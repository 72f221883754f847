"""What a patch may change, as a test oracle (tests/test_hostile.py, the fuzz tests).

A patch replaces a frame's numbers and, where a value needs the other sign,
deletes a sign that a comment or line break parts from its digits
(frames.Number.signs); in a TP program a negative value's one pair of
parentheses comes and goes with its sign (``(-4)`` -> ``5``, the pendant's
form). Everything else — comments, line breaks, spacing,
other frames — stays byte for byte."""
from __future__ import annotations

from ucsio.geometry.frames import Frame


def skeleton(text: str, frames: list[Frame]) -> str:
    """``text`` with every number of ``frames`` replaced by NUL, their
    detached signs removed, and blanks right before a number dropped (KUKA
    "{X.5" becomes "{X 2.5": the blank the grammar needs): what no patch of
    those frames may change."""
    cuts = []
    for f in frames:
        for n in f.numbers.values():
            span = n.span.start, n.span.end
            cuts.append((*(_with_parentheses(text, *span) if f.vendor == "fanuc" else span), "\0"))
            cuts += [(s.start, s.end, "") for s in n.signs]
    out, pos = [], 0
    for start, end, mark in sorted(set(cuts)):     # two settings of one register: one cut
        assert start >= pos, "overlapping number spans"
        out.append(text[pos:start].rstrip(" \t") if mark else text[pos:start])
        out.append(mark)
        pos = end
    out.append(text[pos:])
    return "".join(out)


def _with_parentheses(text: str, start: int, end: int) -> tuple[int, int]:
    """A TP program's value with the pair of parentheses around it: the
    patch writes a negative value in parentheses and a positive one without
    (``(-4)`` -> ``5``), so the pair belongs to the number."""
    before, after = start, end
    while before > 0 and text[before - 1] in " \t":
        before -= 1
    while after < len(text) and text[after] in " \t":
        after += 1
    if before > 0 and text[before - 1] == "(" and text[after:after + 1] == ")":
        return before - 1, after + 1
    return start, end


def only_numbers_changed(old_text: str, old_frames: list[Frame], new_text: str,
                         new_frames: list[Frame]) -> bool:
    """The two texts differ only inside the numbers (and detached signs) of
    the patched frames, parsed from each text."""
    return skeleton(old_text, old_frames) == skeleton(new_text, new_frames)
