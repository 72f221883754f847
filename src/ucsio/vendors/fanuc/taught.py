"""FANUC: the /POS positions taught in a user frame.

A TP program keeps its points in /POS, each group with the frames it was
taught in (``GP1: UF : 1, UT : 1, ...``). A position is taught in user
frame UFk of group g (``UFk``, ``UFk@g``) when its GPg says ``UF : k``;
its X, Y, Z are the TCP in that frame, so they move with it. Joint
positions (``J1 = ...``) do not: they are counted as skipped, not moved.
Points are searched in every ``.ls`` of the backup: the folder of the file
that holds the frame (a sysframe.va, or the program that sets it) and the
folders below it; a second file of the same name below it (another robot's
sysframe.va in a folder of several backups) marks that robot's tree, whose
files are left out (``files_around``).

Each program is read by ``tp.positions``, the reader ``solve --robot``
uses.
"""
from __future__ import annotations

import re

from ..common.taught import Found, TaughtPoint, cached_reader, files_around, is_same_file
from ...errors import UcsioError
from ...geometry.frames import Frame
from . import tp
from ...parsing.model import ControllerFile
from ...parsing.document import Document

_USER_FRAME = re.compile(r"UF(\d+)(?:@(\d+))?\Z", re.I)


def backup_root(parts: list[str]) -> int:
    """``files_around``'s root for FANUC: the file's folder and the folders
    below it (a backup is one folder; programs may sit in subfolders)."""
    return len(parts)


def points_in(doc: Document, uf: int, group: int, found: Found, read=None) -> None:
    """The positions of ``doc`` whose group ``group`` is taught in UF ``uf``."""
    for p in (read or tp.positions)(doc):
        g = p.groups.get(group)
        if g is None or g.uf != uf:
            continue
        where = f"{doc.path}:{g.line}"
        if g.joint:
            found.skipped.append((p.name, doc.path, g.line))
            continue
        if not g.cartesian:
            found.warnings.append(f"{where}: {p.name} has no complete X Y Z W P R "
                                  "(********): not counted")
            continue
        pose = g.pose
        found.points.append(TaughtPoint(p.name, doc.path, g.line, pose.t, pose.q))


def find(cf: ControllerFile, frame: Frame, cache: dict | None = None) -> Found:
    found = Found()
    m = _USER_FRAME.match(frame.name)
    if frame.type != "UFRAME" or m is None:
        found.warnings.append(f"{frame.name} is not a user frame (UFk): points are taught in "
                              "user frames (UF : k in /POS)")
        return found
    uf, group = int(m.group(1)), int(m.group(2) or 1)

    read = cached_reader(tp.positions, cache, "fanuc")

    # the .va too: another robot's sysframe.va below ours marks its tree (left out)
    for src in files_around(frame.file, backup_root, (".ls", ".va")):
        if not src.name.lower().endswith(".ls"):
            continue
        try:
            doc = cf.document if is_same_file(src, cf) else src.document()
            points_in(doc, uf, group, found, read)
        except UcsioError as exc:
            found.warnings.append(f"could not read {src.name} ({exc}); its points are not "
                                  "counted")
    return found
