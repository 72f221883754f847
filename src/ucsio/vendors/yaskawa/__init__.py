"""Yaskawa Motoman: user frames (UFRAME.CND), tools (TOOL.CND) and the
robot-to-robot calibration (RBCALIB.DAT).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the readers (``cnd``, ``rbcalib``, ``var`` for VAR.DAT)
only when called. Jobs (.JBI) and SYSTEM.SYS are not read yet:
parsing.foreign refuses them with what ucsio reads of Yaskawa's files.
"""
from __future__ import annotations

from ...geometry.angles import AngleColumns
from .. import Defaults


class Yaskawa(Defaults):
    name = "yaskawa"
    title = "Yaskawa"

    # -- reading --------------------------------------------------------------------
    def sniff(self, doc) -> bool:
        from . import cnd, rbcalib, var
        return cnd.sniff(doc) or rbcalib.sniff(doc) or var.sniff(doc)

    def parse(self, doc, full: bool = False, beside: bool = True):
        from . import rbcalib, var  # each file by its first line (a git temporary file has no name)
        if rbcalib.sniff(doc):
            return rbcalib.parse(doc, full=full)
        if var.sniff(doc):          # //VAR: the global variables (no frames)
            return var.parse(doc, full=full)
        from .cnd import parse
        return parse(doc, full=full)

    # -- orientation and numbers ------------------------------------------------------
    # R = Rz(rz)·Ry(ry)·Rx(rx): rx is SPEC's c, rz its a (tests/test_yaskawa.py)
    angles = AngleColumns(("rx", "ry", "rz"), "cba")
    # SPEC's measurement CSV has no Yaskawa columns yet (measurement_columns None)

    # -- robot positions (solve --robot) ------------------------------------------------
    # none yet: jobs (.JBI) are not read

    # -- writing frames and programs (patch, program) -----------------------------------
    # patch rewrites a ////BUSER line or a tool's pose line in place; a TOOL.CND
    # with ///CRC is refused (its checksum cannot be recomputed)
    native_keys = ("x", "y", "z", "rx", "ry", "rz")
    same_rotation_tolerance = 0.25e-4   # deg: a quarter of the 4 decimals it writes
    readback_angle = 5e-4

    def plan_changes(self, frame, pose):
        from .write import plan
        return plan(frame, pose)

    def translation_changes(self, frame, pose):
        from .write import translation
        return translation(frame, pose)

    def check_patchable(self, cf, frame, where, warnings):
        from .write import check_patchable
        check_patchable(cf, frame, where, warnings)

    # ``ucsio program -o SETUF2.JBI``: a job that sets a user frame by MFRAME from
    # three positions it loads into free P variables (``program``)
    program_options = ("group", "p", "var")

    def frame_program(self, pose, frame, **options):
        from .program import from_solution
        return from_solution(pose, frame, **options)

    # -- taught points, unset frames, comparing frames (diff) ---------------------------
    # no taught points yet: jobs (.JBI) are not read

    def prefilled(self, frame, cf) -> bool:
        """TOOL.CND lists all 64 tools: one all zeros without a name is the
        controller's default, nobody's tool. UFRAME.CND lists only defined
        user frames."""
        return frame.type == "TOOL"

    def robot_title(self, group: int) -> str | None:
        return f"R{group}"          # ///GROUP's flag k: the pendant's robot Rk


VENDOR = Yaskawa()
