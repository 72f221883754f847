"""A planned patch (``review.patch.patch_frame``): the new bytes and what
changed, shown as a unified diff; ``review.save`` writes it."""
from __future__ import annotations

from ..values import Value
from .unified import unified_diff

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from typing import Any

    from ..geometry.frames import Frame, Pose
    from ..parsing.document import Document
    from ..vendors.common.write import Change


class PatchResult(Value):
    """A planned patch: the new bytes and what changed. Nothing is written
    until ``review.save.save``."""

    __slots__ = ("path", "frame", "pose", "document", "new_bytes", "changes", "warnings",
                 "written", "backup", "flagged_before")

    def __init__(self, path: str, frame: Frame, pose: Pose, document: Document,
                 new_bytes: bytes, changes: list[Change], warnings: list[str] | None = None,
                 written: str | None = None, backup: str | None = None,
                 flagged_before: frozenset = frozenset()):
        self.path, self.frame, self.pose, self.document = path, frame, pose, document
        self.new_bytes, self.changes = new_bytes, changes
        self.warnings = [] if warnings is None else warnings
        self.written, self.backup = written, backup
        # (code, message) of the source's own warnings: what the patch did not cause
        self.flagged_before = flagged_before

    def with_changes(self, **fields) -> "PatchResult":
        """A copy with these fields replaced (LibCST's name for it)."""
        values = {k: getattr(self, k) for k in self.__slots__}
        values.update(fields)
        return PatchResult(**values)

    @property
    def old_bytes(self) -> bytes:
        return self.document.raw

    @property
    def changed(self) -> bool:
        return self.new_bytes != self.document.raw

    @property
    def diff(self) -> str:
        return unified_diff(self.document, self.new_bytes, self.path)

    def as_dict(self) -> dict[str, Any]:
        return {"file": self.path, "frame": self.frame.name, "type": self.frame.type,
                "vendor": self.frame.vendor, "line": self.frame.line,
                "reference": self.frame.reference,
                "old": self.frame.pose.as_dict() if self.frame.pose else None,
                "new": self.pose.as_dict(), "changed": self.changed,
                "changes": [c.as_dict() for c in self.changes], "diff": self.diff,
                "warnings": list(self.warnings), "written": self.written,
                "backup": self.backup}
