"""FANUC: variable listings (.va), TP programs (.ls), diagnostic listings (.dg).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the readers and the rest only when called. ``base`` holds
what the three readers share.
"""
from __future__ import annotations


class Fanuc:
    name = "fanuc"
    title = "FANUC"

    # -- reading --------------------------------------------------------------------
    def sniff(self, doc) -> bool:
        from .base import sniff
        return sniff(doc)

    def parse(self, doc, full: bool = False, beside: bool = True):
        """FANUC's three readers, by the listing's kind."""
        from .base import kind_of
        kind = kind_of(doc)
        if kind == "va":
            from . import va
            return va.parse(doc, full=full, beside=beside)
        if kind == "ls":
            from . import tp
            return tp.parse(doc, full=full)
        from . import dg
        return dg.parse(doc, full=full)

    def binary_refusal(self, path: str) -> str | None:
        import os
        from .base import BINARY_SUFFIXES
        if os.path.splitext(path)[1].lower() in BINARY_SUFFIXES:
            return ("binary FANUC file: ucsio reads its ASCII twin (.ls for a .tp "
                    "program, .va for .sv/.vr data)")
        return None

    # -- orientation and numbers ------------------------------------------------------

    # -- robot positions (solve --robot) ------------------------------------------------

    # -- writing frames and programs (patch, program) -----------------------------------
    program_writer = None

    # -- taught points, unset frames, comparing frames (diff) ---------------------------
    def taught_points(self, cf, frame, cache=None):
        from .taught import find
        return find(cf, frame, cache)

    def taught_chain(self, cf, frame, measured):
        from ..common.taught import alone
        return alone(frame, measured)

    def taught_in_frame(self, cf, frame, found):
        from ..common.taught import as_written
        return as_written(found)

    def prefilled(self, frame, cf) -> bool:
        """Every entry of $MNUFRAME/$MNUTOOL; not a frame a TP program sets
        (UFRAME[k]=PR[n]): the program says it is set, whatever its values."""
        return "set_from" not in frame.info

    def default_label(self, frame, label: str) -> bool:
        """The comment the controller gives a frame nobody named (UFrame7, Eoat2)."""
        from .base import default_comment
        return default_comment(frame.type, frame.name, label)

    # W, P, R are SPEC's c, b, a
    native_deltas = (("dw", "dc"), ("dp", "db"), ("dr", "da"))
    # the controller does not load .va listings: a TP program sets a frame
    frames_set_by_program = True


VENDOR = Fanuc()
