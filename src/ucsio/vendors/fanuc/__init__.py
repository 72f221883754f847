"""FANUC: variable listings (.va), TP programs (.ls), diagnostic listings (.dg).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the readers and the rest only when called. ``base`` holds
what the three readers share.
"""
from __future__ import annotations

from ...geometry.angles import AngleColumns, MeasurementColumns
from .. import Defaults


class Fanuc(Defaults):
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
    native_keys = ("x", "y", "z", "w", "p", "r")
    same_rotation_tolerance = 2.5e-4    # deg: a quarter of the written step (0.001 deg)
    readback_angle = 1e-3               # deg: W, P, R to 0.001 deg read back within this
    # a listing's frame is read back from its element under its record's head; a
    # program's PR lines stand above the frame's: verified by reading the whole file
    def declaration_end(self, text: str, last: int) -> int:
        from .write import declaration_end
        return declaration_end(text, last)

    def as_module(self, text: str, before: str = "") -> str:
        from .write import as_module
        return as_module(text, before)

    def plan_changes(self, frame, pose):
        from .write import plan
        return plan(frame, pose)

    def translation_changes(self, frame, pose):
        from .write import translation
        return translation(frame, pose)

    def edits_for(self, frame, changes):
        from .write import edits_for
        return edits_for(frame, changes)

    def where(self, frame) -> dict:
        from .write import where
        return where(frame)

    def read_again(self, cf, frame):
        from .write import read_again
        return read_again(cf, frame)

    def assignments(self, cf, name: str):
        from .write import assignments
        return assignments(cf, name)

    def check_patchable(self, cf, frame, where: dict, warnings: list) -> None:
        from .write import check_patchable
        check_patchable(cf, frame, where, warnings)

    def in_place_refusal(self, frame, out):
        from .write import in_place_refusal
        return in_place_refusal(frame, out)

    @property
    def review_copy_warning(self) -> str:
        """What a patch of a listing warns: its copy is for review."""
        from .write import LISTING_WARNING
        return LISTING_WARNING

    def program_writer(self, pose, frame, folder: str, *, pr=None, posreg=None):
        """The TP program that sets a listing's frame, beside its reviewed copy."""
        from .program import write_beside
        return write_beside(pose, frame, folder, pr=pr, posreg=posreg)

    # ``ucsio program``: a TP program (.LS) that sets a measured frame
    program_options = ("group", "pr", "posreg", "comment", "wpr")

    def frame_program(self, pose, frame, **options):
        from .program import from_solution
        return from_solution(pose, frame, **options)

    # ``ucsio program --measure``: a TP program (.LS) to the planned points
    def measurement_program(self, frame, tool, targets, settings):
        from .measure import measurement_program
        return measurement_program(frame, tool, targets, settings)

    # -- taught points, unset frames, comparing frames (diff) ---------------------------
    def taught_points(self, cf, frame, cache=None):
        from .taught import find
        return find(cf, frame, cache)

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


VENDOR = Fanuc()
