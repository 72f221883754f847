"""Verifying a planned patch by reading it back: the frame must give the
target pose within the written precision, nothing outside the edited
numbers may move, and a value written must pass ``check`` as the input did.
"""
from __future__ import annotations

import bisect

from .. import vendors
from ..errors import UcsioError
from ..parsing.controller import parse
from ..parsing.document import Document, Edit, Span
from ..vendors.common.readback import cannot_hold, reads_back, refuse_flagged_values

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from ..geometry.frames import Frame
    from ..parsing.model import ControllerFile
    from .result import PatchResult


def _reread_declaration(result: PatchResult) -> tuple[Frame, ControllerFile] | None:
    """The patched frame (and what parsed it) read back from its own declaration, through the same
    grammar, instead of from the whole file again (the re-parse was a third
    of a cold ``patch``). First checks that the new text is the old text with
    only the edited spans replaced, so the declaration's context is the one
    the original parse read it in. None when the declaration alone does not
    read back (a declaration that spans other ones, an array element, an
    odd line ending): then ``verify`` parses the whole file as before."""
    doc, frame = result.document, result.frame
    vendor = vendors.get(frame.vendor)
    if vendor.declaration_end is None:
        return None         # a FANUC program's PR lines stand above the frame's: the whole file
    old, new = doc.text, Document(result.new_bytes, doc.path).text
    edits = sorted(vendor.edits_for(frame, result.changes), key=lambda e: e.span.start)
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
    end = vendor.declaration_end(old, last)
    if begin > edits[0].span.start or end < 0:
        return None
    i = bisect.bisect_right(starts, end)
    stop = (starts[i] if i < len(starts) else len(old)) + len(new) - len(old)
    # RAPID: a declaration needs its module; a FANUC listing's element, its record's head
    text = vendor.as_module(new[begin:stop], new[:begin])
    try:
        cf = parse(Document(text.encode(doc.encoding), doc.path))
        again = cf.frame(frame.name) if cf.vendor == frame.vendor else None
    except (UcsioError, UnicodeError):
        return None
    return (again, cf) if reads_back(again, result.pose) else None


def _read_again(cf: ControllerFile, frame: Frame) -> Frame:
    """``frame`` in the patched text, as its vendor finds it there (a FANUC
    program that sets it twice: the assignment that reads back worst)."""
    return vendors.get(frame.vendor).read_again(cf, frame)


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
    check = vendors.get(frame.vendor).check_readback    # ABB: the quaternion's norm
    if check is not None:
        check(again, result.changes, doc.path)


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
    edits = vendors.get(result.frame.vendor).edits_for(result.frame, result.changes)
    for e in sorted(edits, key=lambda e: e.span.start):
        start = e.span.start + shift
        if start <= at < start + len(e.text):
            return True
        shift += len(e.text) - (e.span.end - e.span.start)
    return False
