"""What every vendor's frame writer shares: the number formatting, a change
of one number, the translation's changes, the edit that replaces one number,
and "equal as the controller stores them".

The vendor folders' ``write`` modules build on this; the orchestration
(``review.patch``: plan an edit, verify it, save it) calls them through the
vendor object. New text keeps the old text's number of decimals where that is
within the precision (``-180.000`` stays a three-decimal column), strips other
trailing zeros, and never writes ``-0``.
"""
from __future__ import annotations

import math

from ...errors import UcsioError
from ...geometry import rotations as rot
from ...parsing.document import Edit
from ...values import Value

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from typing import Any, Callable

    from ...geometry.frames import Frame, Number, Pose

# Written precision of a translation (decimals, mm) and its read-back
# tolerance: a little over half a step.
TRANS_DECIMALS = 3
READBACK_TRANS = 0.5 * 10.0 ** -TRANS_DECIMALS + 1e-9
# The rotation a frame written to 0.0001 deg (KUKA A, B, C) or a 6-decimal
# quaternion (ABB) reads back within.
READBACK_ANGLE_DEG = 5e-4


# ----------------------------------------------------------------- numbers

def decimals_of(text: str | None) -> int:
    """Decimals of a zero-padded decimal literal, i.e. a column style
    ('-180.000' -> 3, '2087.50' -> 2); 0 for '-61.6146', '5', '1E-05'."""
    if not text:
        return 0
    t = text.strip().lstrip("+-").strip()
    if "e" in t.lower() or "." not in t or not t.endswith("0"):
        return 0
    return len(t.split(".", 1)[1])


def format_number(value: float, decimals: int, *, point: bool = False,
                  old_text: str | None = None) -> str:
    """``value`` rounded to ``decimals``, trailing zeros stripped down to the
    old text's decimals (capped at ``decimals``); ``point``: always keep a
    decimal point (KUKA REAL). Never ``-0``, never an exponent."""
    if not math.isfinite(value):
        raise UcsioError(f"cannot write a non-finite number ({value})")
    keep = min(decimals_of(old_text), decimals)
    if point:
        keep = max(keep, 1)
    s = f"{value:.{decimals}f}"
    if float(s) == 0.0:
        s = s.lstrip("-")
    if "." in s:
        whole, frac = s.split(".")
        frac = frac.rstrip("0")
        if len(frac) < keep:
            frac = frac + "0" * (keep - len(frac))
        s = whole + ("." + frac if frac else "")
    return s


def parse_text(text: str) -> float:
    return float(text.replace(" ", "").replace("\t", ""))


def column(nums: list[Number], decimals: int) -> str | None:
    """The zero-padded style of a group of numbers ('100.000' among them:
    three decimals), as an example text for ``format_number``."""
    d = min(max((decimals_of(n.text) for n in nums), default=0), decimals)
    return "0." + "0" * d if d else None


_F32 = memoryview(bytearray(4)).cast("f")      # struct's rounding, without importing struct


def f32(v: float) -> float:
    """``v`` rounded through IEEE single precision (RAPID num, KRL REAL)."""
    try:
        _F32[0] = v
        return _F32[0]
    except OverflowError:
        return v


F32_EPS = 2.0 ** -23


def close32(u: float, v: float) -> bool:
    """Equal as the controller stores them (RAPID num, KRL REAL: float32):
    the same single-precision value, or within two units of its last place."""
    return f32(u) == f32(v) or abs(u - v) <= 2 * F32_EPS * max(1.0, abs(u), abs(v))


def poses_equal(a: Pose | None, b: Pose | None) -> bool:
    """Equal at the controllers' float32 precision."""
    if a is None or b is None:
        return a is None and b is None
    for u, v in zip(a.t, b.t):
        if not close32(u, v):
            return False
    return rot.quat_angle(a.q, b.q) <= 2e-5


# ----------------------------------------------------------------- changes

class Change(Value):
    """One number rewritten: its component, old and new text and value."""

    __slots__ = ("component", "old", "new", "old_value", "new_value", "number")
    _compare = ("component", "old", "new", "old_value", "new_value")

    def __init__(self, component: str, old: str, new: str, old_value: float, new_value: float,
                 number: Number | None = None):
        self.component, self.old, self.new = component, old, new
        self.old_value, self.new_value = old_value, new_value
        self.number = number        # the Number replaced, where not frame.numbers[component]

    def as_dict(self) -> dict[str, Any]:
        return {"component": self.component, "old": self.old, "new": self.new,
                "old_value": self.old_value, "new_value": self.new_value}


def translation_changes(frame: Frame, pose: Pose, write: Callable[[float], str] | None = None,
                        *, point: bool = False) -> list[Change]:
    """X, Y, Z to 0.001 mm: each in the column style of the three
    (``format_number``, ``point`` keeping a decimal point), or as
    ``write(value)`` gives it, where a vendor writes its numbers its own way
    (the Change then names the Number it replaces); a value that does not
    move at that precision keeps its text."""
    out = []
    half = 0.5 * 10.0 ** -TRANS_DECIMALS
    style = column([frame.numbers[k] for k in "xyz"], TRANS_DECIMALS)
    for key, v in zip("xyz", pose.t):
        n = frame.numbers[key]
        if abs(v - n.value) <= half:
            continue
        text = (write(v) if write is not None else
                format_number(v, TRANS_DECIMALS, point=point, old_text=style))
        if parse_text(text) == n.value:
            continue
        out.append(Change(key, n.written, text, n.value, parse_text(text),
                          n if write is not None else None))
    return out


# ----------------------------------------------------------------- edits

_NAME_CHARS = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_$")


def number_edits(text: str, n: Number, new: str) -> list[Edit]:
    """The edits that make ``n`` read ``new``, replacing only what is the
    number's own:

    - a sign that a comment or a line break parts from the digits
      (``n.signs``, RAPID "- ! note\n670") stays where it is and the digits
      carry the rest of the value; only where the new value needs the other
      sign are those signs deleted, and the comment, the line break and
      everything else between them stay;
    - a number glued to the name before it (KUKA "{X.00000,...}", legal)
      must read back as that name and a number: "X0.5" would be the name
      X0, so the glued form keeps the leading dot (".5") or, for a value
      of 1 or more, gets the blank the grammar needs ("X 6.0")."""
    start = n.signs[0].start if n.signs else n.span.start
    if start > 0 and text[start - 1] in _NAME_CHARS and new[:1].isdigit():
        new = new[1:] if new.startswith("0.") else " " + new
    if not n.signs:
        return [Edit(n.span, new)]
    negative = n.lead.count("-") % 2 == 1
    if not negative:
        return [Edit(n.span, new)]           # "+ ! c\n5" -> "+ ! c\n-7" reads -7
    if new.startswith("-"):
        return [Edit(n.span, new[1:])]       # "- ! c\n670" -> "- ! c\n700"
    if parse_text(new) == 0.0:
        return [Edit(n.span, new)]           # -0 is 0
    return [Edit(s, "") for s in n.signs] + [Edit(n.span, new)]


def edits_for(frame: Frame, changes: list[Change]) -> list[Edit]:
    """Each changed number's edits (``number_edits``), in the frame's text."""
    text = frame.document.text if frame.document is not None else ""
    edits: list[Edit] = []
    for c in changes:
        edits += number_edits(text, frame.numbers[c.component], c.new)
    return edits


def where(frame: Frame) -> dict:
    """Where a refusal of ``frame`` points: its declaration's line."""
    return {"file": frame.file, "line": frame.line}


def read_again(cf, frame: Frame) -> Frame:
    """``frame`` in the patched text ``cf``."""
    return cf.frame(frame.name)
