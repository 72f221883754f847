"""Which parser reads a controller file, and the codes of check's findings.

``load(path)`` picks the vendor from the file's name and first words, so a
KUKA ``.dat``, an ABB ``.mod`` and a FANUC ``.va``/``.ls``/``.dg`` go to
the right parser; each returns a ``parsing.model.ControllerFile``.
"""
from __future__ import annotations

import os

from ..errors import UcsioError
from .document import BOM, Document, looks_binary
from .lalr import paused_gc
from .model import ControllerFile

ABB_SUFFIXES = {".mod", ".modx", ".sys", ".sysx", ".prg"}
KUKA_SUFFIXES = {".dat", ".src", ".sub"}
FANUC_SUFFIXES = {".va", ".dg", ".ls"}


# Every code check can report, with what it means (docs/controllers.md: "Lint codes").
# `check --ignore CODE` accepts exactly these.
LINT_CODES = {
    # ABB RAPID
    "unnormalized-quaternion": "an orient with |sum q^2 - 1| above 1e-4: wrong positions on the controller",
    "quaternion-rounding": "info: |sum q^2 - 1| between 1e-5 and 1e-4, as RobotWare writes itself",
    "zero-quaternion": "an orient that is all zeros",
    "tool-mass": "a robot-held tool whose load mass is not above 0",
    "moving-uframe": "a work object with ufprog FALSE: the controller overwrites its uframe",
    "no-value": "info: declared without a value (given elsewhere); listed, not patchable",
    "incomplete": "an editor placeholder (<EXP> ...) in frame data; not patchable",
    "not-literal": "info: frame data computed from other names; listed without numbers",
    "bad-shape": "frame data with the wrong number of components",
    "array-size": "an array value whose element count differs from its declared size",
    "long-name": "an identifier longer than RAPID's 32 characters",
    "duplicate": "a name declared twice in one module",
    # KUKA KRL
    "bad-label": "a TOOL_NAME/BASE_NAME entry that is not a string",
    "bad-type": "a TOOL_TYPE/BASE_TYPE entry that is not an #ENUM value",
    "unknown-type": "a TOOL_TYPE/BASE_TYPE value ucsio does not know",
    "index-out-of-range": "a FRAME array element outside its declared size",
    "duplicate-frame": "a frame initialised twice",
    "duplicate-label": "two tools or two bases with the same label",
    "not-a-frame": "a FRAME variable whose value is not {X ..,Y ..,Z ..,A ..,B ..,C ..}",
    "duplicate-component": "a FRAME component given twice",
    "unknown-component": "a FRAME component other than X Y Z A B C",
    "not-a-number": "a FRAME component that is not a number",
    "missing-component": "a FRAME value missing one of X Y Z A B C",
    "label-too-long": "a TOOL_NAME/BASE_NAME label longer than the controller allows",
    "label-quote": "a label containing a double quote",
    "base-not-world": "a base on an external kinematic: not relative to world",
    # FANUC
    "not-a-frame-array": "a $MNUFRAME/$MNUTOOL record that is not ARRAY[groups,frames] OF POSITION",
    "group-mismatch": "a frame whose Group: line is not the group of its index [g,n]",
    "out-of-range": "a frame value the controller does not hold: W, P or R outside [-180, 180], "
                    "or a translation of 1 km or more",
    "unread-frame-set": "a program's UFRAME/UTOOL assignment in a form ucsio does not read",
    "label-source": "info: frame.dg or FRAMEVAR.VA beside a sysframe.va could not be read; "
                    "frames listed without their comments",
    "after-end": "info: text after a program's /END on its line",
    "unread-line": "info: a program's /MN line that is no numbered statement, kept as it is",
}

# Findings about a whole file, not a lint: every output format of check names
# them by these codes. They fail the check and cannot be --ignored.
FILE_CODES = {
    "syntax-error": "error: a file ucsio cannot parse (the error names its line and column); nothing in it is checked",
    "unreadable": "error: an input that cannot be read at all: missing, not a regular file, binary or encrypted, "
                  "a broken archive, a folder without controller files",
    "round-trip": "error: the bytes ucsio would write for the unedited file are not the file's bytes, "
                  "or a frame number's span does not hold that number: a patch could change more than its numbers",
}

# A code never changes meaning between releases. A code check no longer
# reports moves here (code -> the release that retired it, and why) and stays
# reserved: it is never given to another finding. `--ignore` still accepts
# it, so a CI configuration written for an older ucsio keeps working.
RETIRED: dict[str, str] = {}


def detect_vendor(doc: Document) -> str:
    suffix = os.path.splitext(doc.path)[1].lower()
    if suffix in ABB_SUFFIXES:
        return "abb"
    if suffix in KUKA_SUFFIXES:
        return "kuka"
    if suffix in FANUC_SUFFIXES:
        return "fanuc"
    head = doc.text[:4096].lstrip("\ufeff \t\r\n").upper()
    if head.startswith(("%%%", "MODULE", "!")):
        return "abb"
    from .fanuc import sniff
    if sniff(doc):
        return "fanuc"
    return "kuka"


def parse(doc: Document, full: bool = False, beside: bool = True) -> ControllerFile:
    """Parse a document. ``full`` also runs the whole-file grammar over every
    byte (what ``check`` does); without it only what frames need is parsed.
    ``beside``: the files beside the document's path are its backup's (a
    FANUC sysframe.va takes its frames' comments from them); False for a
    file that stands alone (git's textconv hands over a temporary copy)."""
    _refuse_foreign(doc, beside)
    if looks_binary(doc.raw):
        from .fanuc import BINARY_SUFFIXES
        if os.path.splitext(doc.path)[1].lower() in BINARY_SUFFIXES:
            raise UcsioError("binary FANUC file: ucsio reads its ASCII twin (.ls for a .tp "
                             "program, .va for .sv/.vr data)", file=doc.path)
        raise _binary_error(doc)
    vendor = detect_vendor(doc)
    # The trees and frames of a file hold no reference cycles; the cyclic
    # collector's passes over their growing heap made a long file's
    # reading grow faster than the file (tests: benchmarks/bench_linear.py).
    with paused_gc():
        if vendor == "abb":
            from . import rapid
            return rapid.parse(doc, full=full)
        if vendor == "fanuc":
            return _parse_fanuc(doc, full, beside)
        from . import krl
        return krl.parse(doc, full=full)


def _parse_fanuc(doc: Document, full: bool, beside: bool) -> ControllerFile:
    """FANUC's three readers, by the listing's kind."""
    from . import fanuc
    kind = fanuc.kind_of(doc)
    if kind == "va":
        from . import va
        return va.parse(doc, full=full, beside=beside)
    if kind == "ls":
        from . import tp
        return tp.parse(doc, full=full)
    from . import dg
    return dg.parse(doc, full=full)


def _binary_error(doc: Document) -> UcsioError:
    """'binary or encrypted file', at the first byte that made it so (a NUL
    deep in a text file is found wherever it stands)."""
    from .document import first_binary_byte

    if doc.raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        return UcsioError("UTF-16 text: ucsio reads controller files as UTF-8 or Windows-1252; "
                          "save it as UTF-8", file=doc.path)
    at = first_binary_byte(doc.raw)
    before = doc.raw[len(BOM) if doc.bom else 0:at].decode(doc.encoding)
    return doc.error(f"binary or encrypted file (byte 0x{doc.raw[at]:02x} here): refusing to "
                     "read or patch it", len(before))


def _refuse_foreign(doc: Document, beside: bool) -> None:
    """A file ucsio recognises and does not read (another controller's, a
    FANUC backup's .DAT: parsing.foreign) is refused with what it is."""
    from . import foreign
    why = foreign.other_vendor(doc.path, doc.text[:512])
    if why is None and beside and doc.path.lower().endswith(".dat"):
        why = foreign.fanuc_data(doc.path, doc.text[:4096], foreign.beside(doc.path))
    if why is not None:
        raise Unsupported(why, file=doc.path)


class Unsupported(UcsioError):
    """A file ucsio recognises and does not read: named on its own it is an
    error; in a folder or an archive it is listed as not read."""


def load(path: str | os.PathLike, full: bool = False) -> ControllerFile:
    return parse(Document.read(path), full=full)
