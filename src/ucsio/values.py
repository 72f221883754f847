"""A tiny base for the value classes every command creates.

``dataclasses`` costs ~8 ms to import and ~1 ms per class at start-up; the
listing and patching commands run once per file under ``git diff``, so the
classes on their path are plain slotted classes with value equality.
"""
from __future__ import annotations


class Value:
    __slots__: tuple[str, ...] = ()
    _compare: tuple[str, ...] | None = None   # fields that make equality; default all

    def _astuple(self) -> tuple:
        return tuple(getattr(self, k) for k in (self._compare or self.__slots__))

    def __eq__(self, other) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return self._astuple() == other._astuple()

    def __hash__(self) -> int:
        return hash(self._astuple())  # unhashable fields (dicts) make this raise, as they should

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={getattr(self, k)!r}" for k in self.__slots__)
        return f"{type(self).__name__}({args})"
