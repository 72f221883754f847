"""Reading files with one clear error, and writing them the only safe way:
never half-written.

Every file ucsio writes (patched controller files, solutions, CSV, reports)
goes to a temporary file in the same folder, is flushed to disk, and replaces
the target with one rename; a failure at any step leaves the target (and any
backup) as it was and no temporary file behind. A symbolic link is written
through, never replaced; a file that is replaced keeps its permissions and
owner; a target that exists and is not a regular file (a named pipe, a
device such as /dev/null) is refused, never replaced; a backup never
overwrites an older one.
"""
from __future__ import annotations

import os

from .errors import UcsioError


def write_target(path: str | os.PathLike) -> str:
    """Where a write to ``path`` lands. A symbolic link is written through to
    the file it names, never replaced by a regular file (an engineer who
    links a controller backup into a work folder means that file); a link
    that leads nowhere (dangling, or a loop), a folder, and anything else that
    exists and is not a regular file (a named pipe, a device: the rename would
    replace the node itself, /dev/null included) are refused."""
    given = os.fspath(path)
    path = given
    if os.path.islink(given):
        try:
            path = os.path.realpath(given, strict=True)
        except FileNotFoundError:
            raise UcsioError(f"is a symbolic link to {os.readlink(given)!r}, which does not "
                             "exist: refusing to write through it", file=given) from None
        except OSError:
            raise UcsioError("is a loop of symbolic links: refusing to write", file=given) from None
    if os.path.isdir(path):
        what = "is a directory" if path == given else f"is a link to the directory {path}"
        raise UcsioError(f"{what}: cannot write a file there", file=given)
    kind = _special_kind(path)
    if kind is not None:
        raise UcsioError(f"not a regular file ({kind}): refusing to replace it with a file; "
                         "give a file name", file=given)
    return path


def _special_kind(path: str) -> str | None:
    """What ``path`` is when it exists and is neither a regular file nor a
    folder (a named pipe, a device, a socket); None otherwise."""
    import stat

    try:
        mode = os.stat(path).st_mode
    except OSError:
        return None           # nothing there (yet): a new file
    if stat.S_ISREG(mode) or stat.S_ISDIR(mode):
        return None
    return _kind(mode)


def _kind(mode: int) -> str:
    import stat

    return ("a named pipe (FIFO)" if stat.S_ISFIFO(mode) else
            "a character device" if stat.S_ISCHR(mode) else
            "a block device" if stat.S_ISBLK(mode) else
            "a socket" if stat.S_ISSOCK(mode) else "a special file")


def atomic_write(path: str | os.PathLike, data: bytes, mode: int | None = None,
                 check=None, owner: tuple[int, int] | None = None,
                 backup: bool = False) -> tuple[str, str | None]:
    """Write ``data`` to ``path`` through a temporary file in the same folder,
    fsync, then ``os.replace``; a link is written through (``write_target``).
    A file that is replaced keeps its permissions and owner (a read-only
    file stays read-only). ``mode`` and ``owner`` apply to a new file only;
    ``mode`` defaults to a new file's usual mode (0666 less the umask, not
    mkstemp's 0600). ``check()`` runs just before the rename and may raise to
    abort. ``backup``: the file being replaced is kept as FILE.bak, or the
    first free FILE.bak.1, FILE.bak.2, ... (never overwritten), made only
    after the new bytes are safely on disk and removed again if the rename
    fails: a failure at any step leaves every file as it was and no
    temporary file behind. OS errors become one UcsioError naming the file.
    Returns (the file written, the backup or None)."""
    import tempfile   # only writers pay for it: listing starts without it

    path = write_target(path)
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise UcsioError("cannot write: the folder does not exist", file=path)
    try:
        fd, tmp = tempfile.mkstemp(dir=folder, prefix="." + os.path.basename(path) + ".",
                                   suffix=".ucsio-tmp")
    except OSError as exc:
        raise UcsioError(f"cannot write in this folder: {exc.strerror or exc}", file=path) from None
    bak = None
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        mode, owner = _kept_mode_and_owner(path, mode, owner)
        os.chmod(tmp, mode)
        if owner is not None and hasattr(os, "chown"):
            try:
                os.chown(tmp, *owner)
            except OSError:
                pass           # not allowed to give it away: keep ours
        if check is not None:
            check()
        if backup and os.path.exists(path):
            bak = _keep_backup(path)
        os.replace(tmp, path)
    except BaseException as exc:
        for leftover in (tmp, bak):
            if leftover is not None:
                try:
                    os.unlink(leftover)
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
    return path, bak


def _kept_mode_and_owner(path: str, mode: int | None,
                         owner: tuple[int, int] | None) -> tuple[int, tuple[int, int] | None]:
    """The mode and owner the written file gets: those of the file it
    replaces, so that a rewrite never widens (or narrows) who may read it;
    for a new file, the ones given, else 0666 less the umask."""
    try:
        st = os.stat(path)
    except OSError:
        st = None
    if st is not None:
        return st.st_mode & 0o7777, (st.st_uid, st.st_gid)
    if mode is None:
        umask = os.umask(0)
        os.umask(umask)
        mode = 0o666 & ~umask
    return mode, owner


def backup_names(path: str):
    """FILE.bak, FILE.bak.1, FILE.bak.2, ...: where a backup may go."""
    yield path + ".bak"
    n = 1
    while True:
        yield f"{path}.bak.{n}"
        n += 1


def _keep_backup(path: str) -> str:
    """Keep the file at ``path`` under the first free backup name, never
    replacing one: a hard link to it (instant, no space needed, same bytes,
    mode and times), or where the file system has none, an exclusive copy.
    Returns the backup's name."""
    for bak in backup_names(path):
        try:
            os.link(path, bak)
            return bak
        except FileExistsError:
            continue
        except OSError:
            pass                # no hard links here (FAT, some shares): copy
        try:
            fd = os.open(bak, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        except FileExistsError:
            continue
        try:
            with open(path, "rb") as src, os.fdopen(fd, "wb") as out:
                out.write(src.read())
                out.flush()
                os.fsync(out.fileno())
            st = os.stat(path)
            os.chmod(bak, st.st_mode & 0o7777)
        except BaseException:
            try:
                os.unlink(bak)
            except OSError:
                pass
            raise
        return bak
    raise AssertionError("unreachable")  # pragma: no cover


def atomic_write_text(path: str | os.PathLike, text: str) -> None:
    """UTF-8 text, newlines as given."""
    atomic_write(path, text.encode("utf-8"))


def read_bytes(path: str | os.PathLike, what: str = "file") -> bytes:
    """The bytes of ``path``; a missing file, a folder, anything that is not
    a regular file (after following links: a named pipe, which would block
    until something writes to it; a device such as /dev/zero, which never
    ends; a socket) or an unreadable file is one UcsioError naming it (exit
    2), and nothing is waited for. ``-`` is standard input (once per run: a
    second ``-`` would read nothing)."""
    if os.fspath(path) == "-":
        return _stdin_bytes(what)
    name = os.fspath(path)
    try:
        _regular_file(os.stat(name), name, what)
        # O_NONBLOCK: should a pipe take the file's place after the check,
        # opening it still returns at once, and fstat below refuses it
        fd = os.open(name, os.O_RDONLY | getattr(os, "O_BINARY", 0)
                     | getattr(os, "O_NONBLOCK", 0))
    except FileNotFoundError:
        raise UcsioError(f"no such file (the {what})", file=name) from None
    except IsADirectoryError:
        raise UcsioError(f"is a directory, not a {what}", file=name) from None
    except OSError as exc:
        raise UcsioError(f"cannot read {what}: {exc.strerror or exc}", file=name) from None
    try:
        _regular_file(os.fstat(fd), name, what)
        if hasattr(os, "set_blocking"):
            os.set_blocking(fd, True)
        with os.fdopen(fd, "rb") as fh:
            fd = -1
            return fh.read()
    except OSError as exc:
        raise UcsioError(f"cannot read {what}: {exc.strerror or exc}", file=name) from None
    finally:
        if fd >= 0:
            os.close(fd)


def _regular_file(st: os.stat_result, name: str, what: str) -> None:
    """Refuse what is not a regular file, saying what it is."""
    import stat

    mode = st.st_mode
    if stat.S_ISREG(mode):
        return
    if stat.S_ISDIR(mode):
        raise UcsioError(f"is a directory, not a {what}", file=name)
    kind = _kind(mode)
    raise UcsioError(f"not a regular file ({kind}), so not read as the {what}: give a file "
                     "(or - for standard input)", file=name)


_stdin_read = False


def _stdin_bytes(what: str) -> bytes:
    global _stdin_read
    import sys
    if _stdin_read:
        raise UcsioError(f"standard input is already read: only one input can be - "
                         f"(the {what})", file="-")
    _stdin_read = True
    try:
        return sys.stdin.buffer.read()
    except (OSError, AttributeError, ValueError) as exc:
        raise UcsioError(f"cannot read standard input: {exc}", file="-") from None
