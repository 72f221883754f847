"""ABB RAPID: modules (.mod, .modx), system modules (.sys, .sysx), programs (.prg).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the parser and the rest only when called.
"""
from __future__ import annotations

from ...geometry.angles import AngleColumns, MeasurementColumns
from .. import BY_NAME


class Abb:
    name = "abb"
    title = "ABB"

    # -- reading --------------------------------------------------------------------
    def sniff(self, doc) -> bool:
        head = doc.text[:4096].lstrip("\ufeff \t\r\n").upper()
        return head.startswith(("%%%", "MODULE", "!"))

    def parse(self, doc, full: bool = False, beside: bool = True):
        from .rapid import parse
        return parse(doc, full=full)

    def binary_refusal(self, path: str) -> str | None:
        return None

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
    program_writer = None

    # -- taught points, unset frames, comparing frames (diff) ---------------------------


VENDOR = Abb()
