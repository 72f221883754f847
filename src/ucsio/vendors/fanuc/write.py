"""Writing a FANUC frame back: X, Y, Z, W, P, R to 0.001 mm and 0.001 deg,
in a TP program's ``PR[n,i]=`` lines (``UFRAME[k]=PR[n]``) or a reviewed copy
of a ``.va`` listing (sysframe.va: the controller does not load it).

A listing's field keeps its width; a program's value keeps the pendant's form
(a negative number in parentheses, no leading zero: ``fanuc_number``,
``tp_literal``). W, P, R are chosen together (``wpr_to_write``) so that the
three angles' rounding errors do not add up.
"""
from __future__ import annotations

import itertools
import math

from ...errors import UcsioError
from ...geometry import rotations as rot
from ...parsing.document import Edit, Span
from ...values import Value
from ..common.write import Change, column, format_number, parse_text, poses_equal, \
    translation_changes

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from ...geometry.frames import Frame, Number, Pose
    from ...parsing.model import ControllerFile

KEYS = ("x", "y", "z", "w", "p", "r")
# a TP program's PR[n,i] values and a listing's columns, mm and deg
FANUC_DECIMALS = 3
# read back within 0.001 mm and 0.001 deg (three angles each to 0.001 deg)
READBACK_FANUC_ANGLE_DEG = 1e-3
# How far (deg) a triple nearer the old angles may stand from the rotation to
# write (``rotations.nearest_abc``): a quarter of the written step, so that
# with the rounding it still reads back.
SAME_ROTATION = 0.25 * 10.0 ** -FANUC_DECIMALS

# -- one element read back (a listing) -------------------------------------------------

def declaration_end(text: str, last: int) -> int:
    """A listing's frame element is read back up to the line of its last
    number (R); a TP program's frame is not read back alone (-1: the whole
    file), its PR lines standing above the frame's."""
    return -1 if text[:256].lstrip("\ufeff \t\r\n").startswith("/PROG") else last


def as_module(text: str, before: str) -> str:
    """An element of a listing (``text``, from its ``[g,n] =`` line) under
    its record's head, the last head line in ``before``: a listing the
    grammar reads, the frame named as in the file. Without a head, the text
    as it is (it does not read back, and the whole file is read instead)."""
    from .va import _HEAD_LINE
    end = len(before)
    while end > 0:
        start = before.rfind("\n", 0, end - 1) + 1      # the line before ``end``
        if _HEAD_LINE.match("\n" + before[start:end]) is not None:
            return before[start:end] + text
        end = start
    return text


LISTING_WARNING = ("the controller does not load .va files: this copy of the listing is for "
                   "review (a TP program sets the frame: `ucsio patch PROGRAM.ls` or "
                   "`ucsio program`)")


# ----------------------------------------------------------------- numbers

def fanuc_number(value: float, *, style: str | None = "0.000", leading_zero: bool = False) -> str:
    """``value`` as a FANUC controller prints it: to 0.001 (mm, deg),
    trailing zeros dropped down to ``style``'s decimals (the default keeps
    three, as a listing and a new program write them; None drops them all,
    as a TP program's ``PR[16,2]=(-1100.3)``), and no leading zero
    (``.140``, ``-.4``) unless ``leading_zero``; an exact zero keeps its digit
    (``0.000``, ``0``), as the controller writes it. Never ``-0``."""
    s = format_number(value, FANUC_DECIMALS, old_text=style)
    if not leading_zero and s.startswith(("0.", "-0.")) and parse_text(s) != 0.0:
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
    from .base import kind_of
    return frame.document is not None and kind_of(frame.document) == "va"


def fanuc_style(frame: Frame) -> FanucStyle:
    """The listing's fixed three decimals without leading zero, or the
    program's own: its six numbers' decimals where they are zero-padded
    (``1200.000``), else none kept; a leading zero where one of them has it
    (``0.5``), else none (``.4``, as the pendant writes)."""
    if is_listing(frame):
        return FanucStyle("0.000", False)
    nums = [frame.numbers[k] for k in KEYS if k in frame.numbers]
    texts = [n.text.strip().lstrip("+-") for n in nums]
    return FanucStyle(column(nums, FANUC_DECIMALS),
                      any(t.startswith("0.") for t in texts))


# ----------------------------------------------------------------- W, P, R

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
        a, b, c = rot.nearest_abc(pose.q, (olds[2], olds[1], olds[0]), SAME_ROTATION)
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


def wpr_changes(frame: Frame, pose: Pose) -> list[Change]:
    """W, P, R to 0.001 deg (``wpr_to_write``); an angle that did not move
    keeps its text, and an unchanged orientation (W 180 for W -180, another
    gimbal-lock split) keeps all three."""
    nums = [frame.numbers[k] for k in ("w", "p", "r")]
    old = (nums[0].value, nums[1].value, nums[2].value)
    if _wpr_error(old, pose.q) <= 1e-7:
        return []
    out = []
    for key, n, (text, _val) in zip("wpr", nums, wpr_to_write(pose, old, fanuc_style(frame).number)):
        if text is not None and text != n.written and parse_text(text) != n.value:
            out.append(Change(key, n.written, text, n.value, parse_text(text), n))
    return out


def translation(frame: Frame, pose: Pose) -> list[Change]:
    return translation_changes(frame, pose, fanuc_style(frame).number)


def plan(frame: Frame, pose: Pose) -> list[Change]:
    return translation(frame, pose) + wpr_changes(frame, pose)


# ----------------------------------------------------------------- edits

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


def edits_for(frame: Frame, changes: list[Change]) -> list[Edit]:
    text = frame.document.text if frame.document is not None else ""
    listing = is_listing(frame)
    edits = {}          # a program's frame set twice from one PR line: that line once
    for c in changes:
        n = c.number if c.number is not None else frame.numbers[c.component]
        edits[n.span.start] = fanuc_edit(text, n, c.new, listing)
    return list(edits.values())


# ----------------------------------------------------------------- what is patched

def frame_col(frame: Frame) -> int:
    """The column of a program's UFRAME/UTOOL on its line (1 where not found)."""
    doc = frame.document
    if doc is None or not 0 < frame.line <= len(doc.line_starts):
        return 1
    start = doc.line_starts[frame.line - 1]
    line = doc.text[start:start + 300].split("\n", 1)[0].upper()
    at = line.find(frame.type)
    return at + 1 if at >= 0 else 1


def where(frame: Frame) -> dict:
    """Where a refusal of ``frame`` points: its UFRAME/UTOOL's line and column."""
    return {"file": frame.file, "line": frame.line, "col": frame_col(frame)}


def assignments(cf: ControllerFile, name: str) -> list[Frame]:
    """In a TP program, every assignment of the frame ``name`` names (one
    frame, set once or twice alike: ``program_frames``); else []."""
    if cf.extra.get("kind") != "program":
        return []
    found = cf.matches(name)
    if found and len({f.name.casefold() for f in found}) == 1:
        return program_frames(cf, found[0])
    return []


def check_patchable(cf: ControllerFile, frame: Frame, where: dict, warnings: list[str]) -> None:
    """A program is patched; sysframe.va only as a reviewed copy (a
    warning says so); any other listing not at all."""
    kind = cf.extra.get("kind")
    if kind == "sysframe":
        warnings.append(LISTING_WARNING)
    elif kind != "program":
        raise UcsioError(f"{frame.name}: a {kind or 'FANUC'} listing is not written back; "
                         "patch the TP program that sets the frame (or sysframe.va, for a "
                         "reviewed copy)", **where)


def in_place_refusal(frame: Frame, out: str | None) -> str | None:
    """Why ``frame``'s file is not patched in place (``out`` None) or to
    ``out``, the file itself: a listing, which the controller does not load,
    is patched only as a reviewed copy. None for a program."""
    if not is_listing(frame):
        return None
    if out is None:
        return ("a .va listing is the controller's record of its frames, and the controller "
                "does not load it: not patched in place; -o OUT writes a reviewed copy")
    return (f"-o {out} is the listing itself: a .va listing is not patched in place; -o OUT "
            "writes a reviewed copy elsewhere")


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
                             col=frame_col(f))
    for f in same:
        at = where(f)
        source = f.info.get("set_from", "its source")
        why = next((lint.message for lint in cf.lints
                    if lint.code == "not-literal" and lint.line == f.line), None)
        if f.pose is None or why is not None:
            why = (why or f"{f.name}: its values are not literal").replace(
                "; listed without values", "")
            raise UcsioError(f"{why}: no literal PR[n,i]= values to replace (`ucsio program` "
                             "writes a program that sets it)", **at)
        missing = [k.upper() for k in KEYS if k not in f.numbers]
        if missing:
            raise UcsioError(f"{f.name}: {source} {' '.join(missing)} "
                             f"{'is' if len(missing) == 1 else 'are'} 0 from LPOS-LPOS (or "
                             f"{source}-{source}) with no {source[:-1]},i]= line of "
                             f"{'its' if len(missing) == 1 else 'their'} own above line "
                             f"{f.line}: nothing to replace (add the lines, or use "
                             "`ucsio program`)", **at)
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


def read_again(cf: ControllerFile, frame: Frame) -> Frame:
    """``frame`` in the patched text; a TP program that sets it twice, alike:
    the assignment that reads back worst (each must give the target)."""
    found = [f for f in cf.frames if f.name.casefold() == frame.name.casefold()]
    if len(found) > 1:
        bad = [f for f in found if f.pose is None or not poses_equal(f.pose, found[0].pose)]
        return bad[0] if bad else found[0]
    return cf.frame(frame.name)
