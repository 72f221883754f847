"""Write a frame back into its controller file, touching nothing else.

``plan(frame, pose)`` turns a target pose into edits of exactly the frame's
value spans (``Frame.numbers``), in the vendor's native form:

- ABB (``wobjdata`` uframe/oframe, ``tooldata`` tframe, ``pose``): x, y, z and
  the quaternion q1..q4. Translations to 0.001 mm; quaternion components to 6
  decimals, normalised *after* rounding (SPEC, ``quat_to_write``): plain
  rounding where the text, parsed back, has |sum q^2 - 1| <= 1e-6 (FORMATS.md
  1.6), else the 6-decimal quaternion within that bound nearest in rotation. Written with q1 >= 0 (SPEC); where q1 rounds to 0,
  the sign on the old value's side (positive dot product) keeps the diff
  small.
- KUKA (``BASE_DATA``, ``TOOL_DATA``, ``FRAME``): X, Y, Z to 0.001 mm and A, B,
  C to 0.0001 deg in SPEC's ranges (B in [-90, 90], A and C in (-180, 180]);
  REAL always with a decimal point.

A component whose value does not change at the written precision keeps its
original text, so the diff shows only what moved and patching a file with the
values it already has changes no byte. New text keeps the old text's number
of decimals where that is within the precision (``-180.000`` stays a
three-decimal column), strips other trailing zeros, and never writes ``-0``.

``patch_frame`` adds the refusals (unknown or ambiguous name, no value, a
moving user frame, a reference the measured solution does not mean, a shared
RAPID PERS declared in a sibling module) and a read-back check: the new bytes
are parsed again and must give the target pose within the written precision,
with every byte outside the edited spans unchanged.

``save`` writes atomically: a temporary file in the target's folder, fsync,
``os.replace``; the original's permissions kept; refused (nothing written, no
temporary file left) if the source file changed on disk since it was read.
"""
from __future__ import annotations

import bisect
import itertools
import math
import os

from ..errors import UcsioError
from ..files import atomic_write, write_target
from ..geometry import rotations as rot
from ..geometry.frames import Frame, Number, Pose
from ..parsing import regex
from ..parsing.controller import parse
from ..vendors import BY_NAME
from ..parsing.document import Document, Edit, Span, looks_binary, text_lines
from ..parsing.model import ControllerFile
from ..values import Value
from .names import find_frame

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from typing import Any

# Written precision (decimals) and half a step: what "unchanged" means.
TRANS_DECIMALS = 3
ANGLE_DECIMALS = 4
QUAT_DECIMALS = 6
QUAT_NORM_MAX = 1e-6          # |sum q^2 - 1| of the written text (FORMATS 1.6)
# Read-back tolerances (a little over half a step, and the rotation those give).
READBACK_TRANS = 0.5 * 10.0 ** -TRANS_DECIMALS + 1e-9
READBACK_ANGLE_DEG = 5e-4

ABB_KEYS = ("x", "y", "z", "q1", "q2", "q3", "q4")
KUKA_KEYS = ("x", "y", "z", "a", "b", "c")
FANUC_KEYS = ("x", "y", "z", "w", "p", "r")
# FANUC: a TP program's PR[n,i] values and a listing's columns, mm and deg
FANUC_DECIMALS = 3
# read back within 0.001 mm and 0.001 deg (three angles each to 0.001 deg)
READBACK_FANUC_ANGLE_DEG = 1e-3


def same_rotation_tolerance(vendor: str) -> float:
    """How far (deg) a triple nearer the old angles may stand from the
    rotation to write (``rotations.nearest_abc``): a quarter of the written
    step, so that with the rounding it still reads back (READBACK_*)."""
    return 0.25 * 10.0 ** -(FANUC_DECIMALS if vendor == "fanuc" else ANGLE_DECIMALS)


# ----------------------------------------------------------------- numbers

def _decimals_of(text: str | None) -> int:
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
    keep = min(_decimals_of(old_text), decimals)
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


def _parse_text(text: str) -> float:
    return float(text.replace(" ", "").replace("\t", ""))


_F32 = memoryview(bytearray(4)).cast("f")      # struct's rounding, without importing struct


def f32(v: float) -> float:
    """``v`` rounded through IEEE single precision (RAPID num, KRL REAL)."""
    try:
        _F32[0] = v
        return _F32[0]
    except OverflowError:
        return v


# ----------------------------------------------------------------- planning

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


def _column(nums: list[Number], decimals: int) -> str | None:
    """The zero-padded style of a group of numbers ('100.000' among them:
    three decimals), as an example text for ``format_number``."""
    d = min(max((_decimals_of(n.text) for n in nums), default=0), decimals)
    return "0." + "0" * d if d else None


def _translation_changes(frame: Frame, pose: Pose, point: bool) -> list[Change]:
    out = []
    half = 0.5 * 10.0 ** -TRANS_DECIMALS
    style = _column([frame.numbers[k] for k in "xyz"], TRANS_DECIMALS)
    fanuc = fanuc_style(frame) if frame.vendor == "fanuc" else None
    for key, v in zip("xyz", pose.t):
        n = frame.numbers[key]
        if abs(v - n.value) <= half:
            continue
        text = (fanuc.number(v) if fanuc is not None else
                format_number(v, TRANS_DECIMALS, point=point, old_text=style))
        if _parse_text(text) == n.value:
            continue
        out.append(Change(key, n.written, text, n.value, _parse_text(text),
                          n if fanuc is not None else None))
    return out


def _rotation_gap(c: list[float], q: list[float]) -> float:
    """Radians of the rotation between the (not quite unit) quaternion ``c``
    as a controller reads it (normalised) and the unit quaternion ``q``:
    2 atan2(|c x q part|, |c . q|), accurate near 0."""
    dot = sum(a * b for a, b in zip(c, q))
    cc = sum(a * a for a in c)
    perp2 = max(cc - dot * dot, 0.0)        # |c|^2 - (c.q)^2: the part of c off q's axis
    return 2.0 * math.atan2(math.sqrt(perp2), abs(dot))


def _quat_candidates(q: list[float], reach: int):
    """6-decimal quaternions around ``q``: every component within ``reach``
    steps of q_i's floor/ceiling (reach 0: floor or ceiling only)."""
    step = 10.0 ** -QUAT_DECIMALS
    options = []
    for v in q:
        lo = math.floor(round(v / step, 3))
        hi = math.ceil(round(v / step, 3))
        # as the text will parse: round(k * step) is float('0.653282'), k * step is not
        options.append(sorted({round(k * step, QUAT_DECIMALS)
                               for k in range(lo - reach, hi + reach + 1)}))
    return itertools.product(*options)


def quat_to_write(q: list[float]) -> list[float]:
    """The 6-decimal quaternion written for unit quaternion ``q`` (SPEC,
    "Files ucsio writes"): plain rounding where that gives |sum q^2 - 1| <=
    1e-6; else, among the 6-decimal quaternions within that bound, the one
    nearest in rotation to ``q``, looking first only at each component's floor
    and ceiling (so every component stays within one step of the exact value)
    and further out only where no such candidate meets the bound."""
    plain = [round(v, QUAT_DECIMALS) for v in q]
    if abs(sum(c * c for c in plain) - 1.0) <= QUAT_NORM_MAX:
        return plain
    for reach in (0, 1, 2):
        best = None
        for cand in _quat_candidates(q, reach):
            if abs(sum(c * c for c in cand) - 1.0) > QUAT_NORM_MAX:
                continue
            gap = _rotation_gap(list(cand), q)
            if best is None or gap < best[0]:
                best = (gap, list(cand))
        if best is not None:
            return best[1]
    raise UcsioError(f"cannot write {q} as a normalised 6-decimal quaternion")  # pragma: no cover


def _quat_changes(frame: Frame, pose: Pose) -> list[Change]:
    nums = [frame.numbers[k] for k in ("q1", "q2", "q3", "q4")]
    old = [n.value for n in nums]
    half = 0.5 * 10.0 ** -QUAT_DECIMALS
    norm = math.sqrt(sum(c * c for c in old))
    if norm > 0:
        old_unit = [c / norm for c in old]
        q_can = pose.q
        if any(all(abs(s * a - b) <= half for a, b in zip(q_can, old_unit)) for s in (1, -1)):
            return []          # the same orientation at the written precision: keep the text
    # SPEC writes q1 >= 0. Only where q1 rounds to 0 are both signs that, and
    # then the one on the old value's side keeps the diff small.
    q = list(pose.q)
    if abs(q[0]) < half and sum(a * b for a, b in zip(old, q)) < 0:
        q = [-c for c in q]
    style = _column(nums, QUAT_DECIMALS)
    # A component that does not move at the written precision keeps its text,
    # so the diff shows only what moved, where the kept text still gives a
    # quaternion within the norm bound; otherwise all four are written.
    keep = [abs(q[i] - old[i]) <= half for i in range(4)]
    vals = [old[i] if keep[i] else round(q[i], QUAT_DECIMALS) for i in range(4)]
    if not any(keep) or abs(sum(c * c for c in vals) - 1.0) > QUAT_NORM_MAX:
        keep = [False] * 4
        vals = quat_to_write(q)
    texts = [nums[i].written if keep[i] else format_number(vals[i], QUAT_DECIMALS, old_text=style)
             for i in range(4)]
    parsed = [old[i] if keep[i] else _parse_text(texts[i]) for i in range(4)]
    return [Change(f"q{i + 1}", nums[i].written, texts[i], nums[i].value, parsed[i])
            for i in range(4) if not keep[i] and texts[i] != nums[i].written]


def _angle_changes(frame: Frame, pose: Pose) -> list[Change]:
    nums = [frame.numbers[k] for k in ("a", "b", "c")]
    old = [n.value for n in nums]
    half = 0.5 * 10.0 ** -ANGLE_DECIMALS
    try:
        old_q = rot.abc_to_quat(*old)
        if rot.quat_angle(old_q, pose.q) <= half * 0.5:
            return []          # the same orientation (also across a gimbal-lock split)
    except ValueError:
        pass
    out = []
    style = _column(nums, ANGLE_DECIMALS)
    # at B = +-90 many triples write this rotation: the one nearest the old
    # values, so that a small correction looks small in the diff
    near = rot.nearest_abc(pose.q, tuple(old), same_rotation_tolerance("kuka"))
    for key, n, v in zip("abc", nums, near):
        if abs(rot.wrap180(v - n.value)) <= half:
            continue
        text = format_number(v, ANGLE_DECIMALS, point=True, old_text=style)
        if key in "ac" and _parse_text(text) == -180.0:
            text = format_number(180.0, ANGLE_DECIMALS, point=True, old_text=style)
        out.append(Change(key, n.written, text, n.value, _parse_text(text)))
    return out


def native_keys(frame: Frame) -> tuple[str, ...]:
    return ABB_KEYS if frame.vendor == "abb" else FANUC_KEYS if frame.vendor == "fanuc" \
        else KUKA_KEYS


def plan(frame: Frame, pose: Pose) -> list[Change]:
    """The component changes that write ``pose`` into ``frame`` natively."""
    missing = [k for k in native_keys(frame) if k not in frame.numbers]
    if missing:
        raise UcsioError(f"{frame.name}: no literal value for {', '.join(missing).upper()} "
                         "(nothing to replace; ucsio does not insert components)",
                         file=frame.file, line=frame.line)
    if frame.vendor == "abb":
        return _translation_changes(frame, pose, point=False) + _quat_changes(frame, pose)
    if frame.vendor == "fanuc":
        return _translation_changes(frame, pose, point=False) + _wpr_changes(frame, pose)
    return _translation_changes(frame, pose, point=True) + _angle_changes(frame, pose)


def edits_for(frame: Frame, changes: list[Change]) -> list[Edit]:
    text = frame.document.text if frame.document is not None else ""
    if frame.vendor == "fanuc":
        listing = is_listing(frame)
        edits = {}          # a program's frame set twice from one PR line: that line once
        for c in changes:
            n = c.number if c.number is not None else frame.numbers[c.component]
            edits[n.span.start] = fanuc_edit(text, n, c.new, listing)
        return list(edits.values())
    edits: list[Edit] = []
    for c in changes:
        edits += number_edits(text, frame.numbers[c.component], c.new)
    return edits


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
    if _parse_text(new) == 0.0:
        return [Edit(n.span, new)]           # -0 is 0
    return [Edit(s, "") for s in n.signs] + [Edit(n.span, new)]


# ----------------------------------------------------------------- FANUC

def fanuc_number(value: float, *, style: str | None = "0.000", leading_zero: bool = False) -> str:
    """``value`` as a FANUC controller prints it: to 0.001 (mm, deg),
    trailing zeros dropped down to ``style``'s decimals (the default keeps
    three, as a listing and a new program write them; None drops them all,
    as a TP program's ``PR[16,2]=(-1100.3)``), and no leading zero
    (``.140``, ``-.4``) unless ``leading_zero``; an exact zero keeps its digit
    (``0.000``, ``0``), as the controller writes it. Never ``-0``."""
    s = format_number(value, FANUC_DECIMALS, old_text=style)
    if not leading_zero and s.startswith(("0.", "-0.")) and _parse_text(s) != 0.0:
        s = s.replace("0.", ".", 1)
    return s


def tp_literal(text: str) -> str:
    """A number as a TP program's value: a negative one in parentheses,
    ``(-1100.3)``, as the pendant writes it."""
    return f"({text})" if text.startswith("-") else text


class FanucStyle(Value):
    """How a FANUC file writes a frame's numbers: ``decimals_text`` the
    zero-padded style (``"0.000"``: three decimals kept) or None (trailing
    zeros dropped, a TP program's ``(-1100.3)``), and ``leading_zero``."""

    __slots__ = ("decimals_text", "leading_zero")

    def __init__(self, decimals_text: str | None, leading_zero: bool):
        self.decimals_text, self.leading_zero = decimals_text, leading_zero

    def number(self, value: float) -> str:
        return fanuc_number(value, style=self.decimals_text, leading_zero=self.leading_zero)


def is_listing(frame: Frame) -> bool:
    """A frame of a ``.va`` listing (sysframe.va), not of a TP program."""
    from ..vendors.fanuc.base import kind_of
    return frame.document is not None and kind_of(frame.document) == "va"


def fanuc_style(frame: Frame) -> FanucStyle:
    """The listing's fixed three decimals without leading zero, or the
    program's own: its six numbers' decimals where they are zero-padded
    (``1200.000``), else none kept; a leading zero where one of them has it
    (``0.5``), else none (``.4``, as the pendant writes)."""
    if is_listing(frame):
        return FanucStyle("0.000", False)
    nums = [frame.numbers[k] for k in FANUC_KEYS if k in frame.numbers]
    texts = [n.text.strip().lstrip("+-") for n in nums]
    return FanucStyle(_column(nums, FANUC_DECIMALS),
                      any(t.startswith("0.") for t in texts))


def _wpr_error(wpr: tuple[float, float, float], q) -> float:
    return rot.quat_angle(rot.abc_to_quat(wpr[2], wpr[1], wpr[0]), q)


def wpr_to_write(pose: Pose, olds: tuple[float, float, float] | None = None,
                 number=None) -> list[tuple[str | None, float]]:
    """W, P, R of ``pose`` to 0.001 deg, each as (text, value): of the
    triples that give its rotation, the one nearest the old values ``olds``
    (``rotations.nearest_abc``: at P = +-90 there are many); then of each
    angle's two neighbours at that step (and its old value, text None,
    where that is within half a step), the three that together are
    nearest in rotation to ``pose``; so rounding errors that add up (W and R
    turn about one axis at P = +-90) cancel instead. ``number`` writes a
    value (``fanuc_number``)."""
    number = number or fanuc_number
    step = 10.0 ** -FANUC_DECIMALS
    half = 0.5 * step
    if olds is None:
        a, b, c = rot.canonical_abc(pose.abc, pose.q)
    else:       # at P = +-90, of the triples that write it, the one nearest the old W, P, R
        a, b, c = rot.nearest_abc(pose.q, (olds[2], olds[1], olds[0]),
                                  same_rotation_tolerance("fanuc"))
    options = []
    for i, v in enumerate((c, b, a)):
        opts: list[tuple[str | None, float]] = []
        if olds is not None and abs(rot.wrap180(v - olds[i])) <= half:
            opts.append((None, olds[i]))
        for k in sorted({math.floor(round(v / step, 6)), math.ceil(round(v / step, 6))}):
            val = round(k * step, FANUC_DECIMALS) + 0.0
            if i != 1 and val == -180.0:
                val = 180.0         # W and R in (-180, 180]: the same rotation
            if abs(val) <= 180.0:
                opts.append((number(val), val))
        options.append(opts)
    best = min(itertools.product(*options),
               key=lambda combo: (round(_wpr_error(tuple(o[1] for o in combo), pose.q), 9),
                                  sum(o[0] is not None for o in combo)))
    return list(best)


def _wpr_changes(frame: Frame, pose: Pose) -> list[Change]:
    """W, P, R to 0.001 deg (``wpr_to_write``); an angle that did not move
    keeps its text, and an unchanged orientation (W 180 for W -180, another
    gimbal-lock split) keeps all three."""
    nums = [frame.numbers[k] for k in ("w", "p", "r")]
    old = (nums[0].value, nums[1].value, nums[2].value)
    if _wpr_error(old, pose.q) <= 1e-7:
        return []
    out = []
    for key, n, (text, _val) in zip("wpr", nums, wpr_to_write(pose, old, fanuc_style(frame).number)):
        if text is not None and text != n.written and _parse_text(text) != n.value:
            out.append(Change(key, n.written, text, n.value, _parse_text(text), n))
    return out


def fanuc_edit(text: str, n: Number, new: str, listing: bool) -> Edit:
    """The edit that makes ``n`` read ``new``. In a listing, the field keeps
    its width: the number stays right-aligned where it ended, the blanks
    after the ``X:`` take up the difference (at least one stays). In a TP
    program, the value keeps the program's form: a negative number in
    parentheses (added where the old value had none; a positive value
    drops the pair the old negative one had, and keeps a pair the program
    wrote around a positive one, ``(115)``), deeper parentheses kept,
    blanks inside them too (``( -5 )``)."""
    start, end = n.span.start, n.span.end
    if listing:
        b = start
        while b > 0 and text[b - 1] in " \t":
            b -= 1
        width = end - b
        blanks = max(1 if b < start else 0, width - len(new))
        return Edit(Span(b, end), " " * blanks + new)
    before, after = start, end           # past the blanks inside the parentheses
    while before > 0 and text[before - 1] in " \t":
        before -= 1
    while after < len(text) and text[after] in " \t":
        after += 1
    wrapped = before > 0 and text[before - 1] == "(" and after < len(text) and text[after] == ")"
    outer = before - 1
    while outer > 0 and text[outer - 1] in " \t":
        outer -= 1
    double = wrapped and outer > 0 and text[outer - 1] == "("
    if not wrapped:
        return Edit(n.span, tp_literal(new))
    if double or not n.text.lstrip().startswith("-") or new.startswith("-"):
        return Edit(n.span, new)           # ((-29)), (115), (-4) -> (-7): the number only
    return Edit(Span(before - 1, after + 1), new)     # (-4) -> 5: the pendant's form


LISTING_WARNING = ("the controller does not load .va files: this copy of the listing is for "
                   "review (a TP program sets the frame: `ucsio patch PROGRAM.ls` or "
                   "`ucsio program`)")


def _frame_col(frame: Frame) -> int:
    """The column of a program's UFRAME/UTOOL on its line (1 where not found)."""
    doc = frame.document
    if doc is None or not 0 < frame.line <= len(doc.line_starts):
        return 1
    start = doc.line_starts[frame.line - 1]
    line = doc.text[start:start + 300].split("\n", 1)[0].upper()
    at = line.find(frame.type)
    return at + 1 if at >= 0 else 1


def program_frames(cf: ControllerFile, frame: Frame) -> list[Frame]:
    """The assignments of ``frame`` in a TP program that ``patch`` rewrites:
    each ``UFRAME[k]=PR[n]`` of that name, whose six values stand as literal
    ``PR[n,i]=`` lines above it that no other frame reads. Refused (file:
    line:col): a frame whose values the program does not write as literals
    (``PR[n]=LPOS`` alone, an indirect index, ``PR[n,i]=R[3]``, a component
    zeroed by ``LPOS-LPOS`` with no line of its own), a ``PR[n,i]=`` line
    another frame reads too, a frame set twice with different values."""
    same = [f for f in cf.frames if f.name.casefold() == frame.name.casefold()]
    first = same[0]
    for f in same[1:]:
        if not poses_equal(f.pose, first.pose):
            raise UcsioError(f"{f.name} is set twice in this program, with different values "
                             f"(lines {first.line} and {f.line}): ucsio does not choose one; "
                             "edit the program by hand", file=f.file, line=f.line,
                             col=_frame_col(f))
    for f in same:
        where = {"file": f.file, "line": f.line, "col": _frame_col(f)}
        source = f.info.get("set_from", "its source")
        why = next((lint.message for lint in cf.lints
                    if lint.code == "not-literal" and lint.line == f.line), None)
        if f.pose is None or why is not None:
            why = (why or f"{f.name}: its values are not literal").replace(
                "; listed without values", "")
            raise UcsioError(f"{why}: no literal PR[n,i]= values to replace (`ucsio program` "
                             "writes a program that sets it)", **where)
        missing = [k.upper() for k in FANUC_KEYS if k not in f.numbers]
        if missing:
            raise UcsioError(f"{f.name}: {source} {' '.join(missing)} "
                             f"{'is' if len(missing) == 1 else 'are'} 0 from LPOS-LPOS (or "
                             f"{source}-{source}) with no {source[:-1]},i]= line of "
                             f"{'its' if len(missing) == 1 else 'their'} own above line "
                             f"{f.line}: nothing to replace (add the lines, or use "
                             "`ucsio program`)", **where)
        mine = {n.span.start for n in f.numbers.values()}
        for g in cf.frames:
            if g.name.casefold() == f.name.casefold() or not g.numbers:
                continue
            shared = sorted(mine & {n.span.start for n in g.numbers.values()})
            if shared:
                line, col = cf.document.line_col(shared[0])
                raise UcsioError(f"{f.name}: the {source} value on line {line} also sets "
                                 f"{g.name} (line {g.line}): patching it would move {g.name} "
                                 "too; give each frame its own PR[n,i]= lines",
                                 file=f.file, line=line, col=col)
    return same


# ----------------------------------------------------------------- refusals

def resolve_name(name: str, oframe: bool) -> str:
    if oframe and not name.casefold().endswith(".oframe"):
        return name + ".oframe"
    return name


def _parent_frame(cf: ControllerFile, frame: Frame) -> Frame | None:
    """The frame of ``cf`` that ``frame`` is given in (its Parent names a
    frame: an ABB object frame's work object, whose user frame it hangs
    from), or None."""
    parent = frame.parent
    if parent.kind != "frame":
        return None
    try:
        return cf.frame(parent.name)
    except UcsioError:
        return None


def measured_in_parent(cf: ControllerFile, frame: Frame, world: Pose) -> Pose:
    """A measured UCS (robot world) expressed where ``frame`` is given: an ABB
    object frame is relative to its user frame (world = uframe * oframe), so
    it becomes uframe^-1 * world, with the user frame the file holds (also
    where that is not fixed in world: reference_problem says so, and only
    ``--force`` writes it); every other frame is compared as it is
    (reference_problem says when that is not robot world)."""
    uframe = _parent_frame(cf, frame)
    if uframe is not None and uframe.pose is not None:
        return uframe.pose.inverse().compose(world)
    return world


def _uframe_words(uframe: Frame) -> str:
    """Why an ABB user frame is not a fixed frame in robot world."""
    if uframe.info.get("ufprog") is False:
        return f"the controller moves it: ufprog FALSE, ufmec {uframe.info.get('ufmec')!r}"
    if uframe.reference == "wrist":
        return "it is relative to the wrist: robhold TRUE, the robot holds the work object"
    return f"it is relative to {uframe.reference!r}"


def object_frame_basis(cf: ControllerFile, frame: Frame) -> str | None:
    """For an ABB object frame whose user frame is not fixed in robot world
    but has a value: how a measured frame is put into it (what --force
    writes and diff compares), naming that user frame's values; else None."""
    uframe = _parent_frame(cf, frame)
    if uframe is None or uframe.parent.kind == "world" or uframe.pose is None:
        return None
    p = uframe.pose
    a, b, c = p.abc
    return (f"uframe⁻¹ · world with {uframe.name}'s user frame as this file holds it "
            f"(x {p.x:.3f} y {p.y:.3f} z {p.z:.3f} a {a:.4f} b {b:.4f} c {c:.4f}), right only "
            "while the user frame is there")


def reference_problem(cf: ControllerFile, frame: Frame) -> str | None:
    """Why a measured solution (the UCS in robot world) does not fit this
    frame's reference, or None when it does (directly, or for an object frame
    through its user frame: measured_in_parent)."""
    ref = frame.reference
    if frame.info.get("role") == "external_tcp":
        # KUKA BASE_TYPE #TCP: a fixed tool kept in the base table (krl.py):
        # in world, but not a fixture, so a measured UCS does not belong there.
        return ("BASE_TYPE #TCP: an external (fixed) TCP, not a plain base: a measured "
                "fixture frame does not belong here")
    if ref == "world":
        return None
    if frame.parent.kind == "frame":
        uframe = _parent_frame(cf, frame)
        if uframe is not None and uframe.parent.kind == "world" and uframe.pose is not None:
            return None
        if uframe is None or uframe.pose is None:
            return ("the object frame is relative to a user frame with no literal value: a "
                    "measured world frame cannot be expressed in it")
        return ("the object frame is relative to a user frame that is not a fixed frame "
                f"in robot world ({_uframe_words(uframe)})")
    if ref == "flange":
        return ("this tool is held by the robot: its frame is relative to the flange, not world "
                "(a TCP solved with `solve --tcp solve` is what can be written here)")
    if ref == "machine":
        return "this base is on an external kinematic (MACHINE_FRAME_DAT): not relative to world"
    if ref == "wrist":
        return "robhold TRUE: the robot holds this work object (stationary tool); " \
               "its user frame is relative to the wrist"
    return f"this frame is relative to {ref!r}, not robot world"


def shared_declarations(frame: Frame, warnings: list[str] | None = None, *,
                        load=None) -> list[dict]:
    """Other modules in the same folder that declare the same RAPID PERS.
    ``load(path)``: how a sibling module is read (default
    ``ucsio.parsing.controller.load``; ``batch`` passes its cache, so a folder's
    modules are parsed once per run, not once per patched frame)."""
    storage = str(frame.info.get("storage") or "").upper()
    if frame.vendor != "abb" or "PERS" not in storage.split() or "LOCAL" in storage.split():
        return []
    here = frame.file
    folder = os.path.dirname(here)
    try:
        siblings = sorted(os.path.join(folder, n) if folder else n
                          for n in os.listdir(folder or ".")
                          if os.path.splitext(n)[1].lower() in BY_NAME["abb"].suffixes
                          and os.path.isfile(os.path.join(folder or ".", n)))
    except OSError:
        return []
    if load is None:
        from ..parsing.controller import load
    found = []
    key = frame.name.casefold()
    here_resolved = os.path.realpath(here)
    for p in siblings:
        if os.path.realpath(p) == here_resolved:
            continue
        if not _may_declare(p, frame.name):
            continue
        try:
            other = load(p)
        except Exception as exc:  # noqa: BLE001 - a sibling is only consulted: never fatal
            why = exc.message if isinstance(exc, UcsioError) else f"{type(exc).__name__}: {exc}"
            if warnings is not None:
                warnings.append(f"could not read sibling module {os.path.basename(p)} ({why}); "
                                "it may declare the same PERS")
            continue
        for f in other.frames:
            if f.name.casefold() == key and f.type == frame.type:
                same = poses_equal(frame.pose, f.pose)
                found.append({"file": p, "line": f.line, "same_value": same,
                              "copy": _same_module(f, frame)})
    return found


def _same_module(a: Frame, b: Frame) -> bool:
    """Both in a MODULE of one name: one file is a copy of the other (a
    patched copy, a backup), never a module the controller loads beside it."""
    name = str(a.info.get("module") or "")
    return bool(name) and name.casefold() == str(b.info.get("module") or "").casefold()


def copies_message(frame: Frame, copies: list[dict]) -> str:
    """The refusal where the other declarations are copies of the module."""
    names = ", ".join(os.path.basename(s["file"]) for s in copies)
    here = os.path.basename(frame.file)
    return (f"{frame.name}: {names} declare{'s' if len(copies) == 1 else ''} MODULE "
            f"{frame.info.get('module')} too: a copy of {here} (a patched copy or a backup), "
            "not a module the controller loads beside it; move the copy out of this folder "
            f"(write patched copies elsewhere: -o OTHER_FOLDER/{here})")


def _may_declare(path: str, name: str) -> bool:
    """Whether a sibling module can declare ``name`` at all: its bytes hold
    the data's name as a word, in any case (RAPID names are ASCII, so this holds in
    any ASCII-compatible encoding). Only those are parsed: a backup folder's
    other thirty modules cost a file read each, not a parse. A file that is
    not plain text (encrypted, UTF-16) is parsed anyway, so it is read or
    warned about as before."""
    import re

    try:
        with open(path, "rb") as fh:
            raw = fh.read()
    except OSError:
        return True                         # let the loader say what is wrong
    if looks_binary(raw):
        return True
    data = re.match(r"[A-Za-z_]\w*", name)   # the data's own name: wobj1 of wobj1.oframe, tools{2}
    if data is None:
        return True
    # lower-cased bytes and a plain substring test first: an IGNORECASE regex
    # over every sibling was most of a patch beside 34 modules (issue 13)
    needle, low = data.group().lower().encode("ascii"), raw.lower()
    if needle not in low:
        return False
    word = rb"(?<![a-z0-9_])" + re.escape(needle) + rb"(?![a-z0-9_])"
    return re.search(word, low) is not None


def poses_equal(a: Pose | None, b: Pose | None) -> bool:
    """Equal at the controllers' float32 precision."""
    if a is None or b is None:
        return a is None and b is None
    for u, v in zip(a.t, b.t):
        if not _close32(u, v):
            return False
    return rot.quat_angle(a.q, b.q) <= 2e-5


F32_EPS = 2.0 ** -23


def _close32(u: float, v: float) -> bool:
    """Equal as the controller stores them (RAPID num, KRL REAL: float32):
    the same single-precision value, or within two units of its last place."""
    return f32(u) == f32(v) or abs(u - v) <= 2 * F32_EPS * max(1.0, abs(u), abs(v))


# ----------------------------------------------------------------- patching

class PatchResult(Value):
    """A planned patch: the new bytes and what changed. Nothing is written
    until ``save``."""

    __slots__ = ("path", "frame", "pose", "document", "new_bytes", "changes", "warnings",
                 "written", "backup", "flagged_before")

    def __init__(self, path: str, frame: Frame, pose: Pose, document: Document,
                 new_bytes: bytes, changes: list[Change], warnings: list[str] | None = None,
                 written: str | None = None, backup: str | None = None,
                 flagged_before: frozenset = frozenset()):
        self.path, self.frame, self.pose, self.document = path, frame, pose, document
        self.new_bytes, self.changes = new_bytes, changes
        self.warnings = [] if warnings is None else warnings
        self.written, self.backup = written, backup
        # (code, message) of the source's own warnings: what the patch did not cause
        self.flagged_before = flagged_before

    def with_changes(self, **fields) -> "PatchResult":
        """A copy with these fields replaced (LibCST's name for it)."""
        values = {k: getattr(self, k) for k in self.__slots__}
        values.update(fields)
        return PatchResult(**values)

    @property
    def old_bytes(self) -> bytes:
        return self.document.raw

    @property
    def changed(self) -> bool:
        return self.new_bytes != self.document.raw

    @property
    def diff(self) -> str:
        return unified_diff(self.document, self.new_bytes, self.path)

    def as_dict(self) -> dict[str, Any]:
        return {"file": self.path, "frame": self.frame.name, "type": self.frame.type,
                "vendor": self.frame.vendor, "line": self.frame.line,
                "reference": self.frame.reference,
                "old": self.frame.pose.as_dict() if self.frame.pose else None,
                "new": self.pose.as_dict(), "changed": self.changed,
                "changes": [c.as_dict() for c in self.changes], "diff": self.diff,
                "warnings": list(self.warnings), "written": self.written,
                "backup": self.backup}


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


def _refuse_without_writer(frame: Frame, where: dict) -> None:
    """A vendor whose package says it writes no frames (``frame_writer =
    None``: Yaskawa, whose TOOL.CND may carry a checksum ucsio cannot
    compute) is refused before anything is planned."""
    from .. import vendors
    if getattr(vendors.get(frame.vendor), "frame_writer", True) is None:
        raise UcsioError(f"{frame.name}: {vendors.missing(frame.vendor, 'frame writer')}: "
                         "nothing written", **where, col=1)


def patch_frame(cf: ControllerFile, name: str, pose: Pose, *, measured: bool = True,
                force: bool = False, oframe: bool = False,
                check_siblings: bool = True, verify: bool = True,
                load=None, translation_only: bool = False) -> PatchResult:
    """Plan the patch of frame ``name`` in ``cf`` to ``pose``.

    ``measured``: the pose is a measured solution (the UCS in robot world), so
    the frame's reference must be world unless ``force``. With ``measured``
    False (``--set``) the values are taken as given in the frame's own
    reference. Refusals raise UcsioError; nothing is written here.

    ``verify``: parse the new bytes back (``verify``); a caller that applies
    several patches to one file and verifies the combined bytes itself
    (``verify(result, parsed=...)``, as ``batch`` does) passes False.
    ``load``: how sibling modules are read for the shared-PERS check
    (``shared_declarations``)."""
    warnings: list[str] = []
    same: list[Frame] = []
    if cf.vendor == "fanuc" and cf.extra.get("kind") == "program":
        found = cf.matches(resolve_name(name, oframe))
        if found and len({f.name.casefold() for f in found}) == 1:
            same = program_frames(cf, found[0])     # set twice alike: every assignment
    frame = same[0] if same else find_frame(cf, resolve_name(name, oframe))
    where = {"file": frame.file, "line": frame.line}
    _refuse_without_writer(frame, where)
    if frame.vendor == "fanuc":
        where["col"] = _frame_col(frame)
        kind = cf.extra.get("kind")
        if kind == "sysframe":
            warnings.append(LISTING_WARNING)
        elif kind != "program":
            raise UcsioError(f"{frame.name}: a {kind or 'FANUC'} listing is not written back; "
                             "patch the TP program that sets the frame (or sysframe.va, for a "
                             "reviewed copy)", **where)
    if frame.info.get("ufprog") is False and frame.info.get("component", "uframe") == "uframe":
        raise UcsioError(f"{frame.name}: moving user frame (ufprog FALSE, ufmec "
                         f"{frame.info.get('ufmec')!r}): the controller sets it; not patchable",
                         **where)
    if frame.info.get("incomplete"):
        raise UcsioError(f"{frame.name}: the declaration holds an editor placeholder (<EXP>, ...): "
                         "incomplete, not patchable", **where)
    if frame.pose is None or not frame.numbers:
        raise UcsioError(f"{frame.name}: the file gives no literal value for this frame; "
                         "nothing to patch", **where)
    if measured:
        pose = measured_in_parent(cf, frame, pose)
        why = reference_problem(cf, frame)
        basis = object_frame_basis(cf, frame)
        if why and frame.parent.kind == "frame" and basis is None:
            # no user frame value to express it in: not even --force can write it
            raise UcsioError(f"{frame.name}: {why}; refusing to write a measured world frame",
                             **where)
        if why:
            if not force:
                how = (f"--force writes it as {basis}" if basis else
                       "--force to write it anyway")
                raise UcsioError(f"{frame.name}: {why}; refusing to write a measured world "
                                 f"frame ({how})", **where)
            if basis:
                warnings.append(f"{frame.name}: {why}; written anyway (--force) as {basis}")
            else:
                warnings.append(f"{frame.name}: {why} (written anyway: --force)")
    if check_siblings:
        shared = shared_declarations(frame, warnings, load=load)
        copies = [s for s in shared if s["copy"]]
        if copies and not force:
            raise UcsioError(copies_message(frame, copies) + "; --force patches this file only",
                             **where)
        if copies:
            warnings.append(copies_message(frame, copies) + " (patched this file only: --force)")
        shared = [s for s in shared if not s["copy"]]
        if shared:
            names = "; ".join(f"{os.path.basename(s['file'])}:{s['line']} "
                              f"({'same value' if s['same_value'] else 'different value'})"
                              for s in shared)
            msg = (f"{frame.name}: this PERS is also declared in {names}; RAPID shares one "
                   "PERS object between modules, so every declaration must be patched")
            if not force:
                raise UcsioError(msg + " (--force patches this file only)", **where)
            warnings.append(msg + " (patched this file only: --force)")
    changes = []
    for f in same or [frame]:         # a program that sets the frame twice, alike: both
        if translation_only:      # a solved TCP: x, y, z; the orientation stays as written
            plan(f, pose)     # the refusals: a component with no literal value
            changes += _translation_changes(f, pose, point=f.vendor == "kuka")
        else:
            changes += plan(f, pose)
    doc = cf.document
    new_bytes = doc.edited_bytes(edits_for(frame, changes))
    result = PatchResult(path=doc.path, frame=frame, pose=pose, document=doc,
                         new_bytes=new_bytes, changes=changes, warnings=warnings,
                         flagged_before=frozenset((lint.code, lint.message) for lint in cf.lints))
    if verify:
        globals()["verify"](result)     # the function (the keyword shadows its name)
    return result


def robot_held_tool(frame: Frame) -> bool:
    """A TCP in flange coordinates lives here: an ABB tooldata with robhold
    TRUE, a KUKA TOOL_DATA used as a tool (not a robot-guided workpiece)."""
    return (frame.type in ("tooldata", "TOOL_DATA", "UTOOL") and frame.reference == "flange"
            and frame.info.get("robhold") is not False
            and frame.info.get("role", "tool") == "tool")


def patch_tcp(cf: ControllerFile, name: str, tcp, **options) -> PatchResult:
    """Write a solved TCP (x, y, z in flange coordinates, ``solve --tcp
    solve``) into a robot-held tool: its translation only; orientation, mass
    and load stay as written. The same refusals, read-back check and writing
    as a frame patch."""
    frame = find_frame(cf, name)
    if not robot_held_tool(frame):
        raise UcsioError(f"{frame.name}: a solved TCP belongs in a robot-held tool (tooldata "
                         f"with robhold TRUE, KUKA TOOL_DATA); this is {frame.type} relative to "
                         f"{frame.reference}", file=frame.file, line=frame.line)
    if frame.pose is None:
        raise UcsioError(f"{frame.name}: the file gives no literal value for this tool; "
                         "nothing to patch", file=frame.file, line=frame.line)
    old = frame.pose
    target = Pose(float(tcp[0]), float(tcp[1]), float(tcp[2]), old.q, old.abc)
    return patch_frame(cf, name, target, measured=False, translation_only=True, **options)


def reads_back(frame: Frame | None, pose: Pose) -> bool:
    """Whether ``frame``, parsed from patched text, gives ``pose`` within the
    written precision. Only components that were kept (unchanged at the
    written precision) may differ, and by at most half a step."""
    p = frame.pose if frame is not None else None
    angle = READBACK_FANUC_ANGLE_DEG if frame is not None and frame.vendor == "fanuc" \
        else READBACK_ANGLE_DEG
    return (p is not None
            and all(abs(a - b) <= READBACK_TRANS for a, b in zip(p.t, pose.t))
            and rot.quat_angle(p.q, pose.q) <= angle)


def _reread_declaration(result: PatchResult) -> tuple[Frame, ControllerFile] | None:
    """The patched frame (and what parsed it) read back from its own declaration, through the same
    grammar, instead of from the whole file again (the re-parse was a third
    of a cold ``patch``). First checks that the new text is the old text with
    only the edited spans replaced, so the declaration's context is the one
    the original parse read it in. None when the declaration alone does not
    read back (a declaration that spans other ones, an array element, an
    odd line ending): then ``verify`` parses the whole file as before."""
    doc, frame = result.document, result.frame
    if frame.vendor == "fanuc":
        return None         # a program's PR lines stand above the frame's: the whole file
    old, new = doc.text, Document(result.new_bytes, doc.path).text
    edits = sorted(edits_for(frame, result.changes), key=lambda e: e.span.start)
    pos_old = pos_new = 0
    for e in edits + [Edit(Span(len(old), len(old)), "")]:
        kept = e.span.start - pos_old
        if new[pos_new:pos_new + kept] != old[pos_old:e.span.start] or \
                new[pos_new + kept:pos_new + kept + len(e.text)] != e.text:
            raise UcsioError("internal error: the patch changed text outside the edited "
                             "numbers", file=doc.path)
        pos_old, pos_new = e.span.end, pos_new + kept + len(e.text)
    if pos_new != len(new):
        raise UcsioError("internal error: the patch changed text outside the edited numbers",
                         file=doc.path)

    # the declaration: from its first line to the line that ends it (RAPID: the ';')
    starts = doc.line_starts
    begin = starts[frame.line - 1] if 0 < frame.line <= len(starts) else len(old)
    last = edits[-1].span.end
    end = old.find(";", last) if frame.vendor == "abb" else last
    if begin > edits[0].span.start or end < 0:
        return None
    i = bisect.bisect_right(starts, end)
    stop = (starts[i] if i < len(starts) else len(old)) + len(new) - len(old)
    text = new[begin:stop]
    if frame.vendor == "abb":
        text = f"MODULE ucsio_readback\n{text}\nENDMODULE\n"
    try:
        cf = parse(Document(text.encode(doc.encoding), doc.path))
        again = cf.frame(frame.name) if cf.vendor == frame.vendor else None
    except (UcsioError, UnicodeError):
        return None
    return (again, cf) if reads_back(again, result.pose) else None


def _read_again(cf: ControllerFile, frame: Frame) -> Frame:
    """``frame`` in the patched text; a TP program that sets it twice, alike:
    the assignment that reads back worst (each must give the target)."""
    if frame.vendor == "fanuc":
        found = [f for f in cf.frames if f.name.casefold() == frame.name.casefold()]
        if len(found) > 1:
            bad = [f for f in found if f.pose is None or not poses_equal(f.pose, found[0].pose)]
            return bad[0] if bad else found[0]
    return cf.frame(frame.name)


def verify(result: PatchResult, *, parsed: ControllerFile | None = None) -> None:
    """Parse the new bytes again: the frame must read back as the target pose
    within the written precision (``reads_back``), and nothing outside its
    spans may move. ``parsed``: text with this patch applied, already parsed
    (a copy of the file with several frames patched, parsed once for all of
    them); then the frame is looked up there instead of parsing
    ``result.new_bytes``."""
    doc = result.document
    frame = result.frame
    if not result.changes:
        if result.new_bytes != doc.raw:  # pragma: no cover - defensive
            raise UcsioError("internal error: an empty patch changed bytes", file=doc.path)
        return
    try:
        if parsed is not None:
            again = _read_again(parsed, frame)
        else:
            reread = _reread_declaration(result)
            if reread is None:  # the declaration alone did not read back: the whole file
                parsed = parse(Document(result.new_bytes, doc.path))
                again = _read_again(parsed, frame)
            else:
                again, parsed = reread
    except UcsioError as exc:
        if _in_new_numbers(exc, result):    # the reader refuses a value written
            raise cannot_hold(f"{frame.name}: {exc.message}", exc) from None
        raise UcsioError(f"internal error: the patched text does not parse back: {exc}",
                         file=doc.path) from None
    refuse_flagged_values(parsed, again, [c.component for c in result.changes],
                          known=result.flagged_before)
    p = again.pose
    if p is None:
        raise UcsioError("internal error: the patched frame has no value", file=doc.path)
    target = result.pose
    if not reads_back(again, target):
        raise UcsioError(f"internal error: {frame.name} reads back as {p.as_dict()}, "
                         f"not {target.as_dict()}", file=doc.path)
    if frame.vendor == "abb":
        q = [again.numbers[k].value for k in ("q1", "q2", "q3", "q4")]
        if any(c.component.startswith("q") for c in result.changes) and \
                abs(sum(c * c for c in q) - 1.0) > QUAT_NORM_MAX:
            raise UcsioError("internal error: written quaternion is not normalised",
                             file=doc.path)


def cannot_hold(reason: str, at: UcsioError | None = None) -> UcsioError:
    """The refusal of a value the controller cannot hold: the reader's or
    check's own words, at the position ``at`` names in the written text
    (none for a new program, which has no file yet)."""
    where = {"file": at.file, "line": at.line, "col": at.col} if at is not None else {}
    return UcsioError(f"{reason}: the controller cannot hold this value; nothing written",
                      **where)


def refuse_flagged_values(parsed: ControllerFile, frame: Frame, components,
                          positioned: bool = True, known: frozenset = frozenset()) -> None:
    """A value written must pass ``check`` as the input did: the first
    warning lint the read-back raises at one of ``frame``'s written numbers
    (``components``) refuses the write with that lint's message (FANUC's
    out-of-range, and whatever a vendor's reader flags in a value). A lint
    the input had already (``known``: (code, message)) is not the patch's.
    ``positioned``: name the number's line and column (a file patched),
    else nothing (a new program has no file yet)."""
    doc = parsed.document
    spans = [frame.numbers[k].span for k in components if k in frame.numbers]
    for lint in parsed.lints:
        if lint.severity != "warning" or lint.line > len(doc.line_starts) \
                or (lint.code, lint.message) in known:
            continue
        at = doc.line_starts[lint.line - 1] + lint.col - 1
        if any(sp.start <= at < sp.end for sp in spans):
            raise cannot_hold(f"{lint.message} ({lint.code})",
                              UcsioError("", file=doc.path, line=lint.line, col=lint.col)
                              if positioned else None)


def _in_new_numbers(exc: UcsioError, result: PatchResult) -> bool:
    """Whether a read-back error stands in one of the numbers the patch
    wrote (the reader refuses the value itself: a REAL out of range)."""
    if exc.line is None or exc.col is None:
        return False
    new = Document(result.new_bytes, result.document.path)
    if exc.line > len(new.line_starts):
        return False
    at = new.line_starts[exc.line - 1] + exc.col - 1
    shift = 0
    for e in sorted(edits_for(result.frame, result.changes), key=lambda e: e.span.start):
        start = e.span.start + shift
        if start <= at < start + len(e.text):
            return True
        shift += len(e.text) - (e.span.end - e.span.start)
    return False


# ----------------------------------------------------------------- writing

def _same_on_disk(path: str, doc: Document) -> bool:
    from ..files import read_bytes   # never waits on a pipe put in the file's place
    try:
        return read_bytes(path) == doc.raw
    except UcsioError:
        return False


def _same_file(a: str, b: str) -> bool:
    """Whether paths ``a`` and ``b`` are one file (a link, another spelling)."""
    try:
        return os.path.samefile(a, b)
    except OSError:
        return os.path.realpath(a) == os.path.realpath(b)


def save(result: PatchResult, path: str | os.PathLike | None = None,
         backup: bool = False) -> str:
    """Write a planned patch: to ``path`` (``-o OUT``), or over the source file
    (``--in-place``; ``backup`` keeps the replaced file as FILE.bak, else
    FILE.bak.1, FILE.bak.2, ...). A link is written through to its file
    (``files.write_target``). Refused, with nothing written, when the source
    changed on disk since it was read; on any failure no file changes, the
    backup included."""
    src = result.document.path
    if path is None and result.frame.vendor == "fanuc" and is_listing(result.frame):
        raise UcsioError("a .va listing is the controller's record of its frames, and the "
                         "controller does not load it: not patched in place; -o OUT writes a "
                         "reviewed copy", file=src)
    target = write_target(path if path is not None else src)
    if path is not None and result.frame.vendor == "fanuc" and is_listing(result.frame) \
            and _same_file(target, src):
        raise UcsioError(f"-o {os.fspath(path)} is the listing itself: a .va listing is not "
                         "patched in place; -o OUT writes a reviewed copy elsewhere", file=src)

    def unchanged() -> None:
        if not _same_on_disk(src, result.document):
            raise UcsioError("the file changed on disk since it was read; nothing written "
                             "(run the command again)", file=src)

    unchanged()
    try:   # a new copy gets the source's mode; a file replaced keeps its own
        st = os.stat(src)
        mode, owner = st.st_mode & 0o7777, (st.st_uid, st.st_gid)
    except OSError:
        mode = owner = None
    written, bak = atomic_write(target, result.new_bytes, mode, check=unchanged, owner=owner,
                                backup=backup)
    result.written, result.backup = written, bak
    return written
