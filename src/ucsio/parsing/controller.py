"""Which parser reads a controller file, and the codes of check's findings.

``load(path)`` picks the vendor from the file's name and first words, so a
KUKA ``.dat``, an ABB ``.mod`` and a FANUC ``.va``/``.ls``/``.dg`` go to
the right parser; each returns a ``parsing.model.ControllerFile``.
"""
from __future__ import annotations

import os

from .. import vendors
from ..errors import UcsioError
from .document import BOM, Document, looks_binary
from .lalr import paused_gc
from .model import ControllerFile


def __getattr__(name: str):
    """``LINT_CODES``: every code check can report, with what it means
    (docs/controllers.md: "Lint codes"): each vendor's table
    (vendors/<name>/lints.py), in the registry's order; `check --ignore`
    accepts exactly these. Gathered on first use: reading a RAPID module
    imports nothing of the other vendors."""
    if name == "LINT_CODES":
        codes = globals()["LINT_CODES"] = vendors.lint_codes()
        return codes
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

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
    return vendors.detect(doc)


def parse(doc: Document, full: bool = False, beside: bool = True) -> ControllerFile:
    """Parse a document. ``full`` also runs the whole-file grammar over every
    byte (what ``check`` does); without it only what frames need is parsed.
    ``beside``: the files beside the document's path are its backup's (a
    FANUC sysframe.va takes its frames' comments from them); False for a
    file that stands alone (git's textconv hands over a temporary copy)."""
    _refuse_foreign(doc, beside)
    if doc.gzip_error is not None:
        raise UcsioError(f"{doc.gzip_error}: refusing to read or patch it", file=doc.path,
                         line=1, col=1)
    if looks_binary(doc.body):
        raise _binary_error(doc)
    vendor = vendors.get(vendors.detect(doc))
    if doc.gzip is not None and not vendor.gzip:
        # only a vendor whose files come compressed reads through gzip
        raise _binary_error(doc)
    # The trees and frames of a file hold no reference cycles; the cyclic
    # collector's passes over their growing heap made a long file's
    # reading grow faster than the file (tests: benchmarks/bench_linear.py).
    with paused_gc():
        return vendor.parse(doc, full=full, beside=beside)


def _binary_error(doc: Document) -> UcsioError:
    """'binary or encrypted file', at the first byte that made it so (a NUL
    deep in a text file is found wherever it stands)."""
    from .document import first_binary_byte

    for entry in vendors.VENDORS:
        refusal = vendors.get(entry.name).binary_refusal(doc.path)
        if refusal is not None:
            return UcsioError(refusal, file=doc.path)
    if doc.raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        return UcsioError("UTF-16 text: ucsio reads controller files as UTF-8 or Windows-1252; "
                          "save it as UTF-8", file=doc.path)
    if doc.gzip is not None and not looks_binary(doc.body):
        return UcsioError(f"a gzip-compressed {vendors.title(vendors.detect(doc))} file: its "
                          "files are not read through gzip (decompress it)", file=doc.path,
                          line=1, col=1)
    at = first_binary_byte(doc.body)
    before = doc.body[len(BOM) if doc.bom else 0:at].decode(doc.encoding)
    return doc.error(f"binary or encrypted file (byte 0x{doc.body[at]:02x} here): refusing to "
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
