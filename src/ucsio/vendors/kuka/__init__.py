"""KUKA KRL: data lists ($config.dat and a program's .dat), programs (.src, .sub).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the parser and the rest only when called.
"""
from __future__ import annotations

from ...geometry.angles import AngleColumns, MeasurementColumns
from .. import Defaults


class Kuka(Defaults):
    name = "kuka"
    title = "KUKA"

    # -- reading --------------------------------------------------------------------
    def sniff(self, doc) -> bool:
        return True         # the registry's fallback: a data list has no first word of its own

    def parse(self, doc, full: bool = False, beside: bool = True):
        from .krl import parse
        return parse(doc, full=full)

    # -- orientation and numbers ------------------------------------------------------
    angles = AngleColumns(("a", "b", "c"), "abc")       # A, B, C: Rz(A)·Ry(B)·Rx(C)
    measurement_columns = MeasurementColumns(("robot_a", "robot_b", "robot_c"), "robot_a/b/c",
                                             "KUKA")

    # -- robot positions (solve --robot) ------------------------------------------------
    robot_suffixes = (".dat",)      # a program's data list; .src and .sub hold none

    def robot_positions(self, path: str, config, tool: str, wobj: str, load):
        """A program .dat's positions, each in the base and tool its FDAT names."""
        from .robot import read
        return read(self, path, config, tool, wobj, load)

    # -- writing frames and programs (patch, program) -----------------------------------
    native_keys = ("x", "y", "z", "a", "b", "c")
    same_rotation_tolerance = 2.5e-5    # deg: a quarter of the written step (0.0001 deg)
    readback_angle = 5e-4               # deg: A, B, C to 0.0001 deg read back within this

    def plan_changes(self, frame, pose):
        from .write import plan
        return plan(frame, pose)

    def translation_changes(self, frame, pose):
        from .write import translation
        return translation(frame, pose)

    def declaration_end(self, text: str, last: int) -> int:
        from .write import declaration_end
        return declaration_end(text, last)

    # ``ucsio program --measure``: a KRL program, NAME.src and NAME.dat
    def measurement_program(self, frame, tool, targets, settings):
        from .measure import measurement_program
        return measurement_program(frame, tool, targets, settings)

    # -- taught points, unset frames, comparing frames (diff) ---------------------------
    def taught_points(self, cf, frame, cache=None):
        from .taught import find
        return find(cf, frame, cache)

    def prefilled(self, frame, cf) -> bool:
        """A BASE_DATA[n] or TOOL_DATA[n] entry, or another FRAME of the
        controller's configuration (REF_PT[n], TOOL_CORR, ...); not the
        FRAMEs a program's .dat declares."""
        return frame.type in ("BASE_DATA", "TOOL_DATA") or (
            frame.type == "FRAME" and _configuration(cf))



def _configuration(cf) -> bool:
    """Whether ``cf`` is the controller's configuration (``DEFDAT $CONFIG``)."""
    defdat = cf.extra.get("defdat") if cf is not None else None
    return isinstance(defdat, dict) and str(defdat.get("name") or "").upper() == "$CONFIG"


VENDOR = Kuka()
