"""What a vendor's program writer hands back: a program made, not yet written."""
from __future__ import annotations

from ...values import Value


class ProgramMade(Value):
    """A program made and not yet written: the fields its vendor's class
    lists in ``__slots__`` (``text`` among them: ASCII with the controller's
    CRLF), given by name; a field not given is None."""

    __slots__ = ()

    def __init__(self, **fields):
        for k in self.__slots__:
            setattr(self, k, fields.get(k))

    @property
    def data(self) -> bytes:
        """The bytes to write: controllers take their programs as ASCII."""
        return self.text.encode("ascii")
