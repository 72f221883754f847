"""A parsed controller file: the document, its frames, and lint findings.

Every vendor's parser fills one; the dispatcher (``parsing.controller``)
picks the parser. It lives apart from both so that the parsers import it
without importing the module that imports them.
"""
from __future__ import annotations

from ..errors import UcsioError
from ..values import Value
from .document import Document

TYPE_CHECKING = False      # typing costs a cold start; annotations are strings
if TYPE_CHECKING:
    from typing import Callable

    from ..geometry.frames import Frame


class Lint(Value):
    """A finding of ``check``. A ``warning`` fails the check (exit 1); an
    ``info`` is legal code worth knowing (a PERS whose value another module
    gives) and does not."""

    __slots__ = ("line", "col", "code", "message", "severity")

    def __init__(self, line: int, col: int, code: str, message: str, severity: str = "warning"):
        self.line, self.col, self.code, self.message = line, col, code, message
        self.severity = severity

    def as_dict(self) -> dict:
        return {"line": self.line, "col": self.col, "code": self.code, "message": self.message,
                "severity": self.severity}


class ControllerFile:
    def __init__(self, document: Document, vendor: str):
        self.document = document
        self.vendor = vendor
        self.frames: list[Frame] = []
        self.lints: list[Lint] = []
        # vendor-specific extras (KUKA tables, ABB declarations); parsers fill them.
        self.extra: dict = {}
        # a vendor whose frames have names of a form of their own (FANUC's UF2)
        # sets its test here: a name of that form names a frame, never a label
        self.name_form: Callable[[str], bool] | None = None

    @property
    def path(self) -> str:
        return self.document.path

    def lint(self, offset: int, code: str, message: str, severity: str = "warning") -> None:
        line, col = self.document.line_col(offset)
        self.lints.append(Lint(line, col, code, message, severity))

    def matches(self, name: str) -> list[Frame]:
        """Frames called ``name`` (case-insensitive). A frame's own name wins
        over a label: a KUKA base labelled "BASE_DATA[1]" cannot take the
        place of the real BASE_DATA[1]. A FANUC frame's name (UF2, UT3@2)
        names that frame only: where the file does not set it, a frame
        commented "UF2" (UFRAME[1:UF2]) is not it."""
        key = name.strip().casefold()
        by_name = [f for f in self.frames if f.name.casefold() == key]
        if by_name:
            return by_name
        if self.name_form is not None and self.name_form(key):
            return []
        return [f for f in self.frames if f.label is not None and f.label.casefold() == key]

    def frame(self, name: str) -> Frame:
        """The frame called ``name`` (case-insensitive; KUKA labels too)."""
        found = self.matches(name)
        if not found:
            from ..errors import did_you_mean
            names = [f.name for f in self.frames] + [f.label for f in self.frames if f.label]
            hint = did_you_mean(name.strip(), names)
            raise UcsioError(f"no frame named {name!r}{hint} (ucsio frames lists them)",
                             file=self.path)
        distinct = {id(f) for f in found}
        if len(distinct) > 1:
            which = ", ".join(f"{f.name} (line {f.line})" for f in found)
            raise UcsioError(f"frame name {name!r} is ambiguous: {which}", file=self.path)
        return found[0]
