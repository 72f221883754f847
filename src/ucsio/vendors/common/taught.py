"""What every vendor's reader of taught points shares: the points it finds,
and the controller files around a frame's file that it searches.

The package (``taught/__init__``) picks a vendor's reader and computes the
displacements; the readers import this module, never the package.
"""
from __future__ import annotations

import os

from ...values import Value

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from ...parsing.model import ControllerFile


class TaughtPoint(Value):
    """A position taught in a frame: ``xyz`` in the frame's coordinates (ABB:
    the work object's object frame; KUKA: the base), where it is written;
    ``q`` its orientation where known (ABB RelTool offsets along it)."""

    __slots__ = ("name", "file", "line", "xyz", "q")

    def __init__(self, name: str, file: str, line: int, xyz: tuple[float, float, float],
                 q: tuple[float, float, float, float] | None = None):
        self.name, self.file, self.line, self.xyz, self.q = name, file, line, xyz, q


class Found(Value):
    """What a reader found: the points, what it could not count
    (``warnings``), and the positions taught in the frame that do not move
    with it (``skipped``: FANUC joint positions, as (name, file, line))."""

    __slots__ = ("points", "warnings", "skipped")

    def __init__(self, points: list[TaughtPoint] | None = None,
                 warnings: list[str] | None = None,
                 skipped: list[tuple[str, str, int]] | None = None):
        self.points = points if points is not None else []
        self.warnings = warnings if warnings is not None else []
        self.skipped = skipped if skipped is not None else []


def alone(frame, measured) -> tuple[list, list]:
    """A taught point's way to world where it is written in the frame
    itself: the frame's pose, simulated and measured."""
    return [frame.pose], [measured]


def as_written(found: Found) -> list[tuple[float, float, float]]:
    """The points' positions as the files write them: in the frame."""
    return [p.xyz for p in found.points]


def files_around(file: str, root_of, suffixes: tuple[str, ...]) -> list:
    """The controller files the readers search, as ``ucsio.parsing.sources.Source``s:
    those with ``suffixes`` below ``root_of(folder parts)``'s folder, on disk
    or, for ``ARCHIVE.zip!member``, in the same archive (read in place).
    ``root_of`` maps the file's folder, as a list of path parts, to how many
    of them make the searched root. Shown paths stay as the user gave them
    (relative to the current folder where below it).

    Another file named like ``file`` below that root (a second robot's
    $config.dat in a folder of several backups) owns its own tree, found by
    the same ``root_of``: its files are another controller's, left out."""
    from ...parsing.sources import Source, split_member

    member = split_member(file)
    if member is not None:
        archive, inner = member
        parts = inner.replace("\\", "/").split("/")[:-1]
        prefix = "/".join(parts[:root_of(parts)])
        found = [src for src in _members(archive)
                 if src.rel.lower().endswith(suffixes)
                 and (not prefix or src.rel.casefold().startswith(prefix.casefold() + "/"))]
        return _own_tree(found, inner.replace("\\", "/"), root_of, lambda src: src.rel)
    folder = os.path.dirname(os.path.abspath(file))
    parts = folder.split(os.sep)
    root = os.sep.join(parts[:root_of(parts)]) or os.sep
    out = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = [] if root_of is same_folder else sorted(dirnames)   # ABB: the folder only
        for f in sorted(filenames):
            if f.lower().endswith(suffixes):
                full = os.path.join(dirpath, f)
                rel = os.path.relpath(full)
                shown = rel if not rel.startswith("..") else full
                out.append(Source(shown, os.path.relpath(full, root), path=full))
    return _own_tree(out, os.path.relpath(os.path.abspath(file), root).replace(os.sep, "/"),
                     root_of, lambda src: src.rel.replace(os.sep, "/"))


def _members(archive: str) -> list:
    """The files of a zip archive as Sources, in the order of their paths."""
    from ...parsing.sources import MEMBER_MARK, Source, open_zip

    names = [i.filename for i in open_zip(archive).infolist() if not i.is_dir()]
    found = [Source(f"{archive}{MEMBER_MARK}{n}", n.replace("\\", "/").lstrip("/"),
                    archive=archive, member=n) for n in names]
    return sorted(found, key=lambda s: s.rel.casefold())


def _own_tree(sources: list, mine: str, root_of, rel) -> list:
    """``sources`` less those in the tree of another file named as ``mine``
    (paths relative to the searched root, "/"-separated): that tree is
    another controller's. A tree that holds ``mine`` is not left out."""
    me = tuple(p.casefold() for p in mine.split("/"))
    paths = [tuple(p.casefold() for p in rel(src).split("/")) for src in sources]
    others = []
    for parts in paths:
        if parts[-1] != me[-1] or parts == me:
            continue
        folder = list(parts[:-1])
        tree = tuple(folder[:root_of(folder)])
        if me[:len(tree)] != tree:        # not an ancestor of ours: a tree of its own
            others.append(tree)
    if not others:
        return sources
    return [src for src, parts in zip(sources, paths)
            if not any(parts[:len(t)] == t for t in others)]


def cached_reader(read, cache: dict | None, vendor: str):
    """``read(doc)``, once per file and run where ``cache`` is given (batch
    reads one backup for many entries)."""
    if cache is None:
        return read

    def once(doc):
        key = (vendor, doc.path)
        if key not in cache:
            cache[key] = read(doc)
        return cache[key]
    return once


def same_folder(parts: list[str]) -> int:
    """``files_around``'s root for ABB: the file's own folder, not below it."""
    return len(parts)


def is_same_file(source, cf: ControllerFile) -> bool:
    if source.archive is not None or not cf.path:
        return source.name == cf.path
    try:
        return os.path.samefile(source.path, cf.path)
    except OSError:
        return False
