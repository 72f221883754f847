"""Yaskawa Motoman: user frames (UFRAME.CND), tools (TOOL.CND), jobs (.JBI),
the robot-to-robot calibration (RBCALIB.DAT) and the global variables (VAR.DAT).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the readers (``cnd``, ``job``, ``rbcalib``, ``var``) only
when called. SYSTEM.SYS and the other condition files are not read yet:
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
        from . import cnd, job, rbcalib, var
        return cnd.sniff(doc) or job.sniff(doc) or rbcalib.sniff(doc) or var.sniff(doc)

    def parse(self, doc, full: bool = False, beside: bool = True):
        # each file by its first line (a git temporary file has no name); a
        # .JBI that is not a job says so
        from . import cnd, job, rbcalib, var
        if rbcalib.sniff(doc):
            return rbcalib.parse(doc, full=full)
        if var.sniff(doc):          # //VAR: the global variables (no frames)
            return var.parse(doc, full=full)
        reader = job if job.sniff(doc) or doc.path.lower().endswith(".jbi") else cnd
        return reader.parse(doc, full=full)

    # -- orientation and numbers ------------------------------------------------------
    # R = Rz(rz)·Ry(ry)·Rx(rx): rx is SPEC's c, rz its a (tests/test_yaskawa.py)
    angles = AngleColumns(("rx", "ry", "rz"), "cba")
    # diff --json's deltas in the names the table shows (drx = SPEC's dc)
    native_deltas = (("drx", "dc"), ("dry", "db"), ("drz", "da"))
    # SPEC's measurement CSV has no Yaskawa columns yet (measurement_columns None)

    # -- robot positions (solve --robot) ------------------------------------------------
    robot_suffixes = (".jbi",)          # a job's C and P positions
    robot_configs = 2                   # --config TOOL.CND and --config UFRAME.CND

    def robot_positions(self, path: str, config, tool: str, wobj: str, load):
        from .robot import read
        return read(self, path, config, tool, wobj, load)

    # -- writing frames and programs (patch, program) -----------------------------------
    # patch rewrites a ////BUSER line or a tool's pose line in place; a TOOL.CND
    # with ///CRC is refused (its checksum cannot be recomputed)
    native_keys = ("x", "y", "z", "rx", "ry", "rz")
    same_rotation_tolerance = 0.25e-4   # deg: a quarter of the 4 decimals it writes
    readback_angle = 5e-4

    def where(self, frame) -> dict:
        # a frame's line is its block's head (//UFRAME n, //TOOL n), which
        # begins the line: a refusal names file:line:col as any error does
        return {"file": frame.file, "line": frame.line, "col": 1}

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

    # ``ucsio program --measure``: a job (.JBI) of USER-type positions to the planned points
    def measurement_program(self, frame, tool, targets, settings):
        from .measure import measurement_program
        return measurement_program(frame, tool, targets, settings)

    # -- taught points, unset frames, comparing frames (diff) ---------------------------
    def taught_points(self, cf, frame, cache=None):
        from .taught import find
        return find(cf, frame, cache)

    skipped_points = ("{count} PULSE, BASE or ROBOT position{s} of the jobs that use {name} "
                      "skipped: joint pulses and positions in the robot base do not move with a "
                      "frame")

    def prefilled(self, frame, cf) -> bool:
        """TOOL.CND lists all 64 tools: one all zeros without a name is the
        controller's default, nobody's tool. UFRAME.CND lists only defined
        user frames."""
        return frame.type == "TOOL"

    def robot_title(self, group: int) -> str | None:
        return f"R{group}"          # ///GROUP's flag k: the pendant's robot Rk


VENDOR = Yaskawa()
