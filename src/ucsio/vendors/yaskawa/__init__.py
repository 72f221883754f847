"""Yaskawa Motoman: user frames (UFRAME.CND), tools (TOOL.CND) and jobs (.JBI).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the readers (``cnd``, ``job``) only when called. RBCALIB.DAT,
VAR.DAT and SYSTEM.SYS are not read yet: parsing.foreign refuses them with
what ucsio reads of Yaskawa's files.
"""
from __future__ import annotations

from ...geometry.angles import AngleColumns
from .. import Defaults


class Yaskawa(Defaults):
    name = "yaskawa"
    title = "Yaskawa"

    # -- reading --------------------------------------------------------------------
    def sniff(self, doc) -> bool:
        from . import cnd, job
        return cnd.sniff(doc) or job.sniff(doc)

    def parse(self, doc, full: bool = False, beside: bool = True):
        from . import cnd, job
        # a job by its first line (/JOB) or its name: a .JBI that is not one says so
        reader = job if job.sniff(doc) or doc.path.lower().endswith(".jbi") else cnd
        return reader.parse(doc, full=full)

    # -- orientation and numbers ------------------------------------------------------
    # R = Rz(rz)·Ry(ry)·Rx(rx): rx is SPEC's c, rz its a (tests/test_yaskawa.py)
    angles = AngleColumns(("rx", "ry", "rz"), "cba")
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

    def plan_changes(self, frame, pose):
        from .write import plan
        return plan(frame, pose)

    def translation_changes(self, frame, pose):
        from .write import translation
        return translation(frame, pose)

    def check_patchable(self, cf, frame, where, warnings):
        from .write import check_patchable
        check_patchable(cf, frame, where, warnings)

    # -- taught points, unset frames, comparing frames (diff) ---------------------------
    def taught_points(self, cf, frame, cache=None):
        from .taught import find
        return find(cf, frame, cache)

    skipped_points = ("{count} PULSE or BASE position{s} of the jobs that use {name} skipped: "
                      "joint pulses and positions in the robot base do not move with a frame")

    def prefilled(self, frame, cf) -> bool:
        """TOOL.CND lists all 64 tools: one all zeros without a name is the
        controller's default, nobody's tool. UFRAME.CND lists only defined
        user frames."""
        return frame.type == "TOOL"


VENDOR = Yaskawa()
