"""Saving a planned patch: atomically, over the source or to a copy, and
only while the source on disk is still what was read.
"""
from __future__ import annotations

import os

from .. import vendors
from ..errors import UcsioError
from ..files import atomic_write, write_target

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from ..parsing.document import Document
    from .result import PatchResult


def _same_on_disk(path: str, doc: Document) -> bool:
    from ..files import read_bytes   # never waits on a pipe put in the file's place
    try:
        return read_bytes(path) == doc.raw
    except UcsioError:
        return False


def _same_file(a: str, b: str) -> bool:
    """Whether paths ``a`` and ``b`` are one file (a link, another spelling)."""
    try:
        return os.path.samefile(a, b)
    except OSError:
        return os.path.realpath(a) == os.path.realpath(b)


def save(result: PatchResult, path: str | os.PathLike | None = None,
         backup: bool = False) -> str:
    """Write a planned patch: to ``path`` (``-o OUT``), or over the source file
    (``--in-place``; ``backup`` keeps the replaced file as FILE.bak, else
    FILE.bak.1, FILE.bak.2, ...). A link is written through to its file
    (``files.write_target``). Refused, with nothing written, when the source
    changed on disk since it was read; on any failure no file changes, the
    backup included."""
    src = result.document.path
    # a file the controller does not load (a FANUC listing): a reviewed copy only
    refusal = vendors.get(result.frame.vendor).in_place_refusal
    why = refusal(result.frame, None) if refusal is not None and path is None else None
    if why:
        raise UcsioError(why, file=src)
    target = write_target(path if path is not None else src)
    if path is not None and refusal is not None and _same_file(target, src):
        why = refusal(result.frame, os.fspath(path))
        if why:
            raise UcsioError(why, file=src)

    def unchanged() -> None:
        if not _same_on_disk(src, result.document):
            raise UcsioError("the file changed on disk since it was read; nothing written "
                             "(run the command again)", file=src)

    unchanged()
    try:   # a new copy gets the source's mode; a file replaced keeps its own
        st = os.stat(src)
        mode, owner = st.st_mode & 0o7777, (st.st_uid, st.st_gid)
    except OSError:
        mode = owner = None
    written, bak = atomic_write(target, result.new_bytes, mode, check=unchanged, owner=owner,
                                backup=backup)
    result.written, result.backup = written, bak
    return written
