"""KUKA KRL: data lists ($config.dat and a program's .dat), programs (.src, .sub).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the parser and the rest only when called.
"""
from __future__ import annotations

from ...geometry.angles import AngleColumns, MeasurementColumns


class Kuka:
    name = "kuka"
    title = "KUKA"

    # -- reading --------------------------------------------------------------------
    def sniff(self, doc) -> bool:
        return True         # the registry's fallback: a data list has no first word of its own

    def parse(self, doc, full: bool = False, beside: bool = True):
        from .krl import parse
        return parse(doc, full=full)

    def binary_refusal(self, path: str) -> str | None:
        return None

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
    program_writer = None

    # -- taught points, unset frames, comparing frames (diff) ---------------------------


VENDOR = Kuka()
