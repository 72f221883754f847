"""What a written value must pass when it is read back: the pose within the
written precision, and no warning lint of the reader at a written number.

``review.verify`` checks a patched file with these; a vendor's program
writer (FANUC's TP program) checks the program it makes.
"""
from __future__ import annotations

from ...errors import UcsioError
from ...geometry import rotations as rot
from .write import READBACK_TRANS

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from ...geometry.frames import Frame, Pose
    from ...parsing.model import ControllerFile


def reads_back(frame: Frame | None, pose: Pose) -> bool:
    """Whether ``frame``, parsed from patched text, gives ``pose`` within the
    written precision (its vendor's ``readback_angle``). Only components that
    were kept (unchanged at the written precision) may differ, and by at
    most half a step."""
    p = frame.pose if frame is not None else None
    if p is None:
        return False
    from ... import vendors
    angle = vendors.get(frame.vendor).readback_angle
    return (all(abs(a - b) <= READBACK_TRANS for a, b in zip(p.t, pose.t))
            and rot.quat_angle(p.q, pose.q) <= angle)


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
