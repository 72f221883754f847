"""What a vendor's package provides (its ``VENDOR``), named for type
checkers and for the test that holds every registered vendor to it.

A capability a vendor lacks is ``None``: the generic code that needs it
says so in plain words (``vendors.missing``), never by the vendor's name.
"""
from __future__ import annotations

from typing import Any, Callable, Protocol, runtime_checkable

from ..geometry.angles import AngleColumns, MeasurementColumns
from ..parsing.document import Document
from ..parsing.model import ControllerFile


@runtime_checkable
class Vendor(Protocol):
    name: str                   # Frame.vendor, ControllerFile.vendor
    title: str                  # how messages name it: "KUKA"

    def sniff(self, doc: Document) -> bool:
        """Whether a file whose suffix names no vendor begins like this one's."""

    def parse(self, doc: Document, full: bool = False, beside: bool = True) -> ControllerFile:
        """The file's frames and lints (``full``: every byte through the grammar)."""

    def binary_refusal(self, path: str) -> str | None:
        """Why a binary file of this vendor is not read, where ``path`` is one."""

    # Orientation: how its angles are named and written (or its quaternion), and its
    # orientation columns in SPEC's measurement CSV (None: the CSV has none of its own).
    angles: AngleColumns
    measurement_columns: MeasurementColumns | None

    # Capabilities: None where the vendor has none.
    # solve --robot: the flange poses in world of a file of its positions, for the
    # suffixes it lists. ``load`` reads a controller file of any vendor as every
    # command does (binary and foreign files refused): the front passes it in, so a
    # vendor never imports the dispatch above it. -> vendors.common.robot.RobotPoses
    robot_suffixes: tuple[str, ...]
    robot_positions: Callable[..., Any] | None
    program_writer: Callable[..., Any] | None
