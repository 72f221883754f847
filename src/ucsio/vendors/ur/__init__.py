"""Universal Robots: PolyScope installation files (``.installation``, gzip
around XML): the TCPs, in the flange, and the point and plane features, in
the robot base.

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the reader (``installation``) and the writer (``write``)
only when called. Programs (``.urp``) are not read: parsing.foreign refuses
them.
"""
from __future__ import annotations

from ...geometry.angles import AngleColumns
from .. import Defaults


class UniversalRobots(Defaults):
    name = "ur"
    title = "Universal Robots"
    gzip = True                 # an .installation is gzip around XML

    # -- reading --------------------------------------------------------------------
    def sniff(self, doc) -> bool:
        from .installation import sniff
        return sniff(doc)

    def parse(self, doc, full: bool = False, beside: bool = True):
        from .installation import parse
        return parse(doc, full=full)

    # -- orientation and numbers ------------------------------------------------------
    # The file holds rotation vectors (radians); ucsio shows PolyScope's other
    # form, roll, pitch, yaw in degrees: R = Rz(yaw)·Ry(pitch)·Rx(roll), SPEC's
    # c, b, a (frames --json also gives the quaternion q)
    angles = AngleColumns(("roll", "pitch", "yaw"), "cba")
    native_deltas = (("droll", "dc"), ("dpitch", "db"), ("dyaw", "da"))

    # -- robot positions (solve --robot) ------------------------------------------------
    robot_suffixes = (".installation",)     # the features' taught poses

    def robot_positions(self, path: str, config, tool: str, wobj: str, load):
        from .robot import read
        return read(self, path, config, tool, wobj, load)

    # -- writing frames (patch) ------------------------------------------------------
    # numbers are written as Java writes a double (PolyScope's own): read back exactly
    native_keys = ("x", "y", "z", "rx", "ry", "rz")
    same_rotation_tolerance = 1e-9
    readback_angle = 1e-6

    def where(self, frame) -> dict:
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


VENDOR = UniversalRobots()
