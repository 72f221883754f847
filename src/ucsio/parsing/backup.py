"""Whole backups: the controller files in folders and ``.zip`` archives.

A command given a folder (an ABB backup or ``RAPID`` tree, a KUKA ``KRC``
tree, a FANUC or Yaskawa backup) reads every ``.mod .modx .sys .sysx .prg
.dat``, ``.va .dg .ls`` and ``.cnd`` below it (any case); given a ``.zip`` (a KUKA archive) it
reads the same members straight from the archive with the standard library,
never extracting anything to disk. A FANUC backup's binary files (``.tp``
programs, ``.sv`` system and ``.vr`` variable files) are listed as not read
(``Binary``): ucsio reads their ASCII twins. A member is
named ``ARCHIVE.zip!path/in/archive``, and that name is accepted back as an
input.

Each input becomes Sources; reading or parsing one can fail on its own, so
commands collect the failures and go on (one encrypted module never hides the
35 good files beside it).
"""
from __future__ import annotations

import os

from ..errors import UcsioError
from ..values import Value
from ..vendors import BACKUP_SUFFIXES   # SPEC: what a folder or archive holds that ucsio reads
from .sources import MEMBER_MARK, Source, open_zip, split_member

TYPE_CHECKING = False      # typing costs a cold start; annotations are strings
if TYPE_CHECKING:
    from .model import ControllerFile

# SPEC: a FANUC backup's binary files, listed as not read
BINARY_SUFFIXES = (".tp", ".sv", ".vr")


def load_source(source: Source, full: bool = False) -> ControllerFile:
    """The parsed file (a UcsioError naming the file when it cannot be read)."""
    from .controller import parse
    return parse(source.document(), full=full)


class Binary(Source):
    """A file of a backup ucsio lists but does not read: a FANUC binary
    (.tp, .sv, .vr), whose ASCII twin (.ls, .va) is read instead."""

    __slots__ = ()

    @property
    def reason(self) -> str:
        what = {".tp": "a TP program", ".sv": "a system file", ".vr": "a variable file"}
        suffix = os.path.splitext(self.rel)[1].lower()
        twin = ".ls" if suffix == ".tp" else ".va"
        return f"binary FANUC file ({what.get(suffix, 'binary')}; its ASCII {twin} is what " \
               "ucsio reads)"


class Foreign(Binary):
    """A file of a folder or archive ucsio recognises and does not read
    (parsing.foreign: another controller's, a FANUC backup's .DAT)."""

    __slots__ = ("why",)

    def __init__(self, source: Source, why: str):
        super().__init__(source.name, source.rel, source.path, source.archive, source.member)
        self.why = why

    @property
    def reason(self) -> str:
        return self.why


class Failure(Value):
    """An input that could not be read at all (a missing path, a broken archive)."""

    __slots__ = ("error",)

    def __init__(self, error: UcsioError):
        self.error = error


def is_archive(path: str) -> bool:
    return path.lower().endswith(".zip") and os.path.isfile(path)


def is_member(name: str) -> bool:
    return not os.path.exists(name) and split_member(name) is not None


def is_many(path: str) -> bool:
    """Whether an input stands for many files (a folder or an archive)."""
    return os.path.isdir(path) or is_archive(path)


def expand(paths: list[str]) -> list[Source | Failure]:
    """Every controller file the inputs stand for, in order: a file as
    itself, a folder's and an archive's controller files sorted by path."""
    out: list[Source | Failure] = []
    for p in paths:
        p = os.fspath(p)
        try:
            if os.path.isdir(p):
                found = folder_sources(p)
                if not found:   # a wrong folder, most likely: say so rather than list nothing
                    raise UcsioError("no controller files (" + " ".join(BACKUP_SUFFIXES)
                                     + ") in this folder", file=p)
                out.extend(found)
            elif is_archive(p):
                out.extend(archive_sources(p))
            elif is_member(p):
                archive, member = split_member(p)
                out.append(Source(p, member, archive=archive, member=member))
            else:
                out.append(Source(p, os.path.basename(p), path=p))
        except UcsioError as exc:
            out.append(Failure(exc))
    return out


def folder_sources(folder: str) -> list[Source]:
    found = []
    for root, dirs, files in os.walk(folder, onerror=None):
        dirs.sort()
        listed = []
        for f in files:
            kind = _kind(f)
            if kind is not None:
                full = os.path.join(root, f)
                rel = os.path.relpath(full, folder).replace(os.sep, "/")
                listed.append(kind(full, rel, path=full))
        found += _fanuc_data(listed, files)
    found.sort(key=lambda s: s.rel.casefold())
    return found


def _fanuc_data(sources: list[Source], names) -> list[Source]:
    """``sources`` of one folder holding ``names``, each .dat that is a
    FANUC backup's own (parsing.foreign: by the folder and its text) made
    Foreign: listed as not read."""
    from . import foreign
    if not foreign.is_fanuc_backup(names):
        return sources
    out = []
    for s in sources:
        if type(s) is Source and s.rel.lower().endswith(".dat"):
            try:
                head = s.read()[:4096].decode("latin-1")
            except UcsioError:
                head = ""       # reading it fails again, and is reported, where it is read
            why = foreign.fanuc_data(s.rel, head, names)
            if why is not None:
                s = Foreign(s, why)
        out.append(s)
    return out


def archive_sources(archive: str) -> list[Source]:
    zf = open_zip(archive)
    names = [i.filename for i in zf.infolist() if not i.is_dir()]
    # rel: '/' separators even where a Windows tool wrote '\\' into the archive
    found = [_kind(n)(f"{archive}{MEMBER_MARK}{n}", n.replace("\\", "/").lstrip("/"),
                      archive=archive, member=n)
             for n in names if _kind(n) is not None]
    found = _by_folder(found, names)
    if not found:
        raise UcsioError("no controller files (" + " ".join(BACKUP_SUFFIXES)
                         + ") in this archive", file=archive)
    found.sort(key=lambda s: s.rel.casefold())
    return found


def _by_folder(sources: list[Source], names: list[str]) -> list[Source]:
    """An archive's sources, each folder's .dat files decided by the folder
    they are in (``_fanuc_data``)."""
    folders: dict[str, list[str]] = {}
    for n in names:
        d, _, base = n.replace("\\", "/").lstrip("/").rpartition("/")
        folders.setdefault(d.casefold(), []).append(base)
    out = []
    for s in sources:
        folder = s.rel.rpartition("/")[0].casefold()
        out += _fanuc_data([s], folders.get(folder, ()))
    return out


def _kind(name: str):
    """Source for a file ucsio reads, Binary for one it lists as not read,
    None for any other file of a folder or archive."""
    low = name.lower()
    if low.endswith(BACKUP_SUFFIXES):
        return Source
    if low.endswith(BINARY_SUFFIXES):
        return Binary
    return None


def load_all(paths: list[str], full: bool = False):
    """Parse every controller file the inputs stand for. Returns
    ``(parsed, errors, not_read)``: (Source, ControllerFile) pairs,
    UcsioErrors, and the Binary files of the backups (listed, not read), so
    that one bad file is reported beside the others, never instead of them."""
    from .controller import Unsupported
    parsed, errors, not_read = [], [], []
    for p in paths:
        many = is_many(os.fspath(p))
        for s in expand([p]):
            if isinstance(s, Failure):
                errors.append(s.error)
                continue
            if isinstance(s, Binary):
                not_read.append(s)
                continue
            try:
                parsed.append((s, load_source(s, full=full)))
            except Unsupported as exc:
                if not many:
                    errors.append(exc)
                    continue
                # another controller's file, found in a folder: listed, as a binary is
                not_read.append(Foreign(s, exc.message))
            except UcsioError as exc:
                if exc.file is None:
                    exc.file = s.name
                errors.append(exc)
    return parsed, errors, not_read


def single_input(paths: list[str]) -> bool:
    """One plain file: its error is SPEC's single ``error`` object, not a list."""
    return len(paths) == 1 and not is_many(os.fspath(paths[0]))


def load_one(name: str, full: bool = False) -> ControllerFile:
    """A single controller file, which may be an archive member."""
    if is_member(name):
        archive, member = split_member(name)
        return load_source(Source(name, member, archive=archive, member=member), full=full)
    from .controller import load
    return load(name, full=full)


def refuse_member(name: str, what: str = "patch") -> None:
    """``patch`` writes files; a file inside an archive must be extracted first."""
    if is_member(name) or is_archive(name):
        raise UcsioError(f"{what} does not write into an archive: extract the file first",
                         file=name)
