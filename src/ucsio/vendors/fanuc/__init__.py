"""FANUC: variable listings (.va), TP programs (.ls), diagnostic listings (.dg).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the readers and the rest only when called. ``base`` holds
what the three readers share.
"""
from __future__ import annotations

from ...geometry.angles import AngleColumns, MeasurementColumns


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
    angles = AngleColumns(("w", "p", "r"), "cba")       # W, P, R: W = C, R = A
    measurement_columns = MeasurementColumns(("robot_w", "robot_p", "robot_r"), "robot_w/p/r",
                                             "Fanuc")

    # -- robot positions (solve --robot) ------------------------------------------------
    robot_suffixes = (".ls", ".va")     # a TP program's /POS, posreg.va's registers

    def robot_positions(self, path: str, config, tool: str, wobj: str, load):
        """A TP program's positions (in their UF and UT), or posreg.va's registers."""
        from .robot import read
        return read(self, path, config, tool, wobj, load)

    # -- writing frames and programs (patch, program) -----------------------------------
    program_writer = None

    # -- taught points, unset frames, comparing frames (diff) ---------------------------


VENDOR = Fanuc()
