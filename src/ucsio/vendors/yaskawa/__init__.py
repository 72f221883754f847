"""Yaskawa Motoman: user frames (UFRAME.CND) and tools (TOOL.CND).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the reader (``cnd``) only when called. Jobs (.JBI),
RBCALIB.DAT, VAR.DAT and SYSTEM.SYS are not read yet: parsing.foreign
refuses them with what ucsio reads of Yaskawa's files.
"""
from __future__ import annotations

from ...geometry.angles import AngleColumns


class Yaskawa:
    name = "yaskawa"
    title = "Yaskawa"

    # -- reading --------------------------------------------------------------------
    def sniff(self, doc) -> bool:
        from .cnd import sniff
        return sniff(doc)

    def parse(self, doc, full: bool = False, beside: bool = True):
        from .cnd import parse
        return parse(doc, full=full)

    def binary_refusal(self, path: str) -> str | None:
        return None

    # -- orientation and numbers ------------------------------------------------------
    # R = Rz(rz)·Ry(ry)·Rx(rx): rx is SPEC's c, rz its a (tests/test_yaskawa.py)
    angles = AngleColumns(("rx", "ry", "rz"), "cba")
    measurement_columns = None      # SPEC's measurement CSV has no Yaskawa columns yet

    # -- robot positions (solve --robot) ------------------------------------------------
    robot_suffixes: tuple[str, ...] = ()
    robot_positions = None          # jobs (.JBI) are not read yet

    # -- writing frames and programs (patch, program) -----------------------------------
    # patch: not yet (a TOOL.CND's ///CRC cannot be recomputed): review.patch refuses
    # a frame whose vendor has no plan_changes, saying so
    native_keys = ("x", "y", "z", "rx", "ry", "rz")
    same_rotation_tolerance = 0.25e-4   # deg: a quarter of the 4 decimals it writes
    readback_angle = 5e-4
    plan_changes = translation_changes = edits_for = where = read_again = as_module = None
    declaration_end = assignments = check_patchable = check_siblings = None
    check_readback = in_place_refusal = review_copy_warning = None
    program_writer = None

    # -- taught points, unset frames, comparing frames (diff) ---------------------------
    taught_points = None            # jobs (.JBI) are not read yet
    native_deltas = ()

    def taught_chain(self, cf, frame, measured):
        from ..common.taught import alone
        return alone(frame, measured)

    def taught_in_frame(self, cf, frame, found):
        from ..common.taught import as_written
        return as_written(found)

    def prefilled(self, frame, cf) -> bool:
        """TOOL.CND lists all 64 tools: one all zeros without a name is the
        controller's default, nobody's tool. UFRAME.CND lists only defined
        user frames."""
        return frame.type == "TOOL"

    def default_label(self, frame, label: str) -> bool:
        return False


VENDOR = Yaskawa()
