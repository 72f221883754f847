"""What a vendor's package provides (its ``VENDOR``), named for type
checkers and for the test that holds every registered vendor to it.

A capability a vendor lacks is ``None``: the generic code that needs it
says so in plain words (``vendors.missing``), never by the vendor's name.
"""
from __future__ import annotations

from typing import Any, Callable, Protocol, runtime_checkable

from ..geometry.frames import Frame, Pose
from ..parsing.document import Document
from ..parsing.model import ControllerFile
from .common.taught import Found


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

    # Capabilities: None where the vendor has none.
    program_writer: Callable[..., Any] | None

    # -- taught points, unset frames, comparing frames (diff) ---------------------------
    # (cf, frame, cache) -> vendors.common.taught.Found: the points taught in a
    # frame, read from the files around it (diff --points, plan --at-taught)
    taught_points: Callable[..., Any] | None

    def taught_chain(self, cf: ControllerFile, frame: Frame,
                     measured: Pose) -> tuple[list[Pose], list[Pose]]:
        """The poses a point taught in ``frame`` goes through to world,
        simulated and measured (``measured``: the frame's measured pose in
        its parent), innermost last."""

    def taught_in_frame(self, cf: ControllerFile, frame: Frame,
                        found: Found) -> list[tuple[float, float, float]]:
        """Each taught point's position in ``frame``'s own coordinates."""

    def prefilled(self, frame: Frame, cf: ControllerFile | None) -> bool:
        """Whether the controller lists ``frame`` whether anyone taught it or
        not (an entry of a table of defaults): only such a frame can be unset."""

    def default_label(self, frame: Frame, label: str) -> bool:
        """Whether ``label`` is a name the controller gives a frame nobody named."""

    # (own key, SPEC's key) pairs: a frame's deltas in the vendor's terms,
    # added beside SPEC's da, db, dc (FANUC: dw = dc)
    native_deltas: tuple[tuple[str, str], ...]
    # whether the controller loads no file ucsio patches, so that a program
    # sets a measured frame (FANUC: a TP program, not the .va listing)
    frames_set_by_program: bool
