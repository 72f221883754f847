"""Stäubli VAL3: the data files (``.dtx``) of CS8 and s7/CS9 controllers.

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the reader (``dtx``) only when called. Frames and tools are
read with their fathers (the frame tree), points for ``solve --robot``;
``patch`` is refused: the rotation order is not proved (``convention``).
VAL3 programs and projects (``.pgx``, ``.pjx``) are refused by
parsing.foreign with what ucsio reads of Stäubli's files.
"""
from __future__ import annotations

from ...geometry.angles import POSE_ANGLES
from .. import Defaults


class Staubli(Defaults):
    name = "staubli"
    title = "Stäubli"

    # -- reading --------------------------------------------------------------------
    def sniff(self, doc) -> bool:
        from .dtx import sniff
        return sniff(doc)

    def parse(self, doc, full: bool = False, beside: bool = True):
        from .dtx import parse
        return parse(doc, full=full)

    # -- orientation -------------------------------------------------------------------
    # rx, ry, rz are no permutation of SPEC's a, b, c (R = Rz(a)·Ry(b)·Rx(c)):
    # tables show a, b, c of the orientation as ucsio reads it (convention.py),
    # JSON's rx, ry, rz the values as written
    angles = POSE_ANGLES

    # -- robot positions (solve --robot) ------------------------------------------------
    robot_suffixes = (".dtx",)          # its points (pointRx; CS8 <point>)

    def robot_positions(self, path: str, config, tool: str, wobj: str, load):
        from .robot import read
        return read(self, path, config, tool, wobj, load)

    # -- writing frames (patch): refused until the rotation order is proved --------------
    native_keys = ("x", "y", "z", "rx", "ry", "rz")
    same_rotation_tolerance = 0.25e-5
    readback_angle = 5e-4

    @property
    def patch_refusal(self) -> str:
        from .convention import REFUSAL
        return REFUSAL

    def where(self, frame) -> dict:
        return {"file": frame.file, "line": frame.line, "col": 1}

    def check_patchable(self, cf, frame, where, warnings):
        _refuse(frame, where)

    def plan_changes(self, frame, pose):
        _refuse(frame, self.where(frame))

    def translation_changes(self, frame, pose):
        _refuse(frame, self.where(frame))


def _refuse(frame, where: dict):
    from ...errors import UcsioError
    from .convention import REFUSAL
    from .dtx import shown
    raise UcsioError(f"{shown(frame.name)}: {REFUSAL}", **where)


VENDOR = Staubli()
