"""A .dtx's frame, tool and point entries, and the node each hangs from.

Shared by the reader (``dtx``), its lints (``fathers``) and the robot
positions (``robot``)."""
from __future__ import annotations

from ...geometry.frames import UNKNOWN, WORLD, Number, Parent, flange, frame_parent

COMPONENTS = ("x", "y", "z", "rx", "ry", "rz")


class Entry:
    """One array entry of a frame, tool or point: its datum, index, the
    numbers written (absent ones are 0) and its father as written."""

    __slots__ = ("kind", "data", "index", "size", "numbers", "father", "at", "data_at")

    def __init__(self, kind: str, data: str, index: int, size: int, numbers: dict[str, Number],
                 father: tuple[str, int] | None, at: int, data_at: int):
        self.kind, self.data, self.index, self.size = kind, data, index, size
        self.numbers, self.father, self.at, self.data_at = numbers, father, at, data_at

    @property
    def name(self) -> str:
        return entry_name(self.data, self.index, self.size)

    def values(self) -> tuple[float, ...]:
        return tuple(self.numbers[k].value if k in self.numbers else 0.0 for k in COMPONENTS)


def entry_name(data: str, index: int, size: int) -> str:
    return data if size <= 1 and index == 0 else f"{data}[{index}]"


def father_parent(e: Entry, known: dict[str, Entry]) -> Parent:
    """The node an entry hangs from: another frame or tool of the file
    (``name[k]``, or ``name`` for a datum of one entry), else VAL3's roots
    ``world[0]`` and ``flange[0]``; a father the file does not hold is a
    frame the tree lists under unknown (and check reports)."""
    if e.father is None:
        return UNKNOWN
    name, index = e.father
    for candidate in (f"{name}[{index}]", name if index == 0 else None):
        if candidate in known:
            return frame_parent(candidate)
    if index == 0 and name == "world":
        return WORLD
    if index == 0 and name == "flange":
        return flange()
    return frame_parent(f"{name}[{index}]")
