"""Reading files with one clear error, and writing them the only safe way:
never half-written.

Every file ucsio writes (patched controller files, solutions, CSV, reports)
goes to a temporary file in the same folder, is flushed to disk, and replaces
the target with one rename; a failure at any step leaves the target as it was
and no temporary file behind.
"""
from __future__ import annotations

import os

from .errors import UcsioError


def atomic_write(path: str | os.PathLike, data: bytes, mode: int | None = None,
                 check=None, owner: tuple[int, int] | None = None) -> None:
    """Write ``data`` to ``path`` through a temporary file in the same folder,
    fsync, then ``os.replace``. ``mode`` defaults to a new file's usual mode
    (0666 less the umask, not mkstemp's 0600). ``check()`` runs just before
    the rename and may raise to abort. The temporary file never outlives a
    failure; OS errors become one UcsioError naming the file."""
    import tempfile   # only writers pay for it: listing starts without it

    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise UcsioError("cannot write: the folder does not exist", file=path)
    try:
        fd, tmp = tempfile.mkstemp(dir=folder, prefix="." + os.path.basename(path) + ".",
                                   suffix=".ucsio-tmp")
    except OSError as exc:
        raise UcsioError(f"cannot write in this folder: {exc.strerror or exc}", file=path) from None
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        if mode is None:
            umask = os.umask(0)
            os.umask(umask)
            mode = 0o666 & ~umask
        os.chmod(tmp, mode)
        if owner is not None and hasattr(os, "chown"):
            try:
                os.chown(tmp, *owner)
            except OSError:
                pass           # not allowed to give it away: keep ours
        if check is not None:
            check()
        os.replace(tmp, path)
    except BaseException as exc:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(exc, OSError):
            raise UcsioError(f"cannot write: {exc.strerror or exc}", file=path) from None
        raise
    try:  # make the rename durable
        dfd = os.open(folder, os.O_RDONLY)
        try:
            os.fsync(dfd)
        finally:
            os.close(dfd)
    except OSError:
        pass


def atomic_write_text(path: str | os.PathLike, text: str) -> None:
    """UTF-8 text, newlines as given."""
    atomic_write(path, text.encode("utf-8"))


def read_bytes(path: str | os.PathLike, what: str = "file") -> bytes:
    """The bytes of ``path``; a missing file, a folder or an unreadable file
    is one UcsioError naming it (exit 2)."""
    try:
        with open(path, "rb") as fh:
            return fh.read()
    except FileNotFoundError:
        raise UcsioError(f"no such file (the {what})", file=os.fspath(path)) from None
    except IsADirectoryError:
        raise UcsioError(f"is a directory, not a {what}", file=os.fspath(path)) from None
    except OSError as exc:
        raise UcsioError(f"cannot read {what}: {exc.strerror or exc}", file=os.fspath(path)) from None
