"""ABB RAPID: modules (.mod, .modx), system modules (.sys, .sysx), programs (.prg).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the parser and the rest only when called.
"""
from __future__ import annotations

from ...geometry.angles import AngleColumns, MeasurementColumns
from .. import BY_NAME, Defaults


class Abb(Defaults):
    name = "abb"
    title = "ABB"

    # -- reading --------------------------------------------------------------------
    def sniff(self, doc) -> bool:
        head = doc.text[:4096].lstrip("\ufeff \t\r\n").upper()
        return head.startswith(("%%%", "MODULE", "!"))

    def parse(self, doc, full: bool = False, beside: bool = True):
        from .rapid import parse
        return parse(doc, full=full)

    # -- orientation and numbers ------------------------------------------------------
    # quaternions (q1 real); tables show RobotStudio's Euler ZYX rx, ry, rz (rx = C, rz = A)
    angles = AngleColumns(("rx", "ry", "rz"), "cba", quaternion=True)
    measurement_columns = MeasurementColumns(("robot_q1", "robot_q2", "robot_q3", "robot_q4"),
                                             "robot_q1..q4", "ABB")

    # -- robot positions (solve --robot) ------------------------------------------------
    robot_suffixes = BY_NAME["abb"].suffixes        # every module and program

    def robot_positions(self, path: str, config, tool: str, wobj: str, load):
        """A module's robtargets: the TCP of ``tool`` in ``wobj``'s object frame."""
        from .robot import read
        return read(self, path, config, tool, wobj, load)

    # -- writing frames and programs (patch, program) -----------------------------------
    native_keys = ("x", "y", "z", "q1", "q2", "q3", "q4")
    # deg: how far a rotation's angles may move to stay nearest the old ones
    # (KUKA's, a quarter of 0.0001 deg: diff compares ABB frames in angles too)
    same_rotation_tolerance = 2.5e-5
    readback_angle = 5e-4       # deg: a 6-decimal quaternion reads back within this

    def plan_changes(self, frame, pose):
        from .write import plan
        return plan(frame, pose)

    def declaration_end(self, text: str, last: int) -> int:
        from .write import declaration_end
        return declaration_end(text, last)

    def as_module(self, text: str, before: str = "") -> str:
        from .write import as_module
        return as_module(text)

    def check_siblings(self, frame, force, warnings, where, load) -> None:
        from .write import check_siblings
        check_siblings(frame, force, warnings, where, load)

    def check_readback(self, again, changes, path) -> None:
        from .write import check_readback
        check_readback(again, changes, path)

    # ``ucsio program --measure``: a RAPID module of robtargets in the work object
    def measurement_program(self, frame, tool, targets, settings):
        from .measure import measurement_program
        return measurement_program(frame, tool, targets, settings)

    # -- taught points, unset frames, comparing frames (diff) ---------------------------
    def taught_points(self, cf, frame, cache=None):
        from .taught import find
        return find(cf, frame, cache)

    def taught_chain(self, cf, frame, measured):
        from .taught import chain
        return chain(cf, frame, measured)

    def taught_in_frame(self, cf, frame, found):
        from .taught import in_frame
        return in_frame(cf, frame, found)



VENDOR = Abb()
