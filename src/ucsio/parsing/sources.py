"""Where a controller file's bytes are: a path on disk, or a member of a
``.zip`` archive (``ARCHIVE.zip!path/in/archive``), read in place with the
standard library and never extracted.

``parsing.backup`` expands folders and archives into these and parses them;
a FANUC listing reads the label files beside it through them too, so they
live below both.
"""
from __future__ import annotations

import os

from ..errors import UcsioError
from ..values import Value

MEMBER_MARK = "!"


class Source(Value):
    """One controller file to read: ``name`` as shown and as frames' ``file``,
    ``rel`` its path inside the backup it came from (for pairing two backups;
    the base name for a file given on its own), and where its bytes are."""

    __slots__ = ("name", "rel", "path", "archive", "member")

    def __init__(self, name: str, rel: str, path: str | None = None,
                 archive: str | None = None, member: str | None = None):
        self.name, self.rel, self.path, self.archive, self.member = name, rel, path, archive, member

    def read(self) -> bytes:
        if self.archive is None:
            from ..files import read_bytes
            return read_bytes(self.path, "controller file")
        return read_member(self.archive, self.member, self.name)

    def document(self):
        from .document import Document
        return Document(self.read(), self.name)


def split_member(name: str) -> tuple[str, str] | None:
    """``ARCHIVE.zip!path`` -> (archive, member) when the archive exists."""
    i = name.lower().find(".zip" + MEMBER_MARK)
    if i < 0:
        return None
    archive, member = name[:i + 4], name[i + 5:]
    if not os.path.isfile(archive) or not member:
        return None
    return archive, member


_OPEN: dict[str, object] = {}   # archive path -> ZipFile: its directory is read once per run


def open_zip(archive: str):
    import zipfile   # only archives pay for it
    zf = _OPEN.get(archive)
    if zf is None:
        try:
            zf = zipfile.ZipFile(archive)
        except (zipfile.BadZipFile, OSError, ValueError) as exc:
            raise UcsioError(f"not a readable zip archive ({exc})", file=archive) from None
        _OPEN[archive] = zf
    return zf


def read_member(archive: str, member: str, name: str) -> bytes:
    import zipfile
    zf = open_zip(archive)
    try:
        return zf.read(member)
    except KeyError:
        raise UcsioError("no such file in the archive", file=name) from None
    except (zipfile.BadZipFile, RuntimeError, NotImplementedError, OSError, EOFError) as exc:
        # RuntimeError: an encrypted member; NotImplementedError: an unknown compression
        raise UcsioError(f"cannot read from the archive ({exc})", file=name) from None
