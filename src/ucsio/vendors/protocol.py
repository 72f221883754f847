"""What a vendor's package provides (its ``VENDOR``), named for type
checkers and for the test that holds every registered vendor to it.

A capability a vendor lacks is ``None``: the generic code that needs it
says so in plain words (``vendors.missing``), never by the vendor's name.
"""
from __future__ import annotations

from typing import Any, Callable, Protocol, runtime_checkable

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

    # Capabilities: None where the vendor has none.
    program_writer: Callable[..., Any] | None
