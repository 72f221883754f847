"""KUKA: the E6POS/POS points taught in a base.

An inline-form motion keeps its point as ``DECL E6POS XP1={...}`` and its
frame data as ``DECL FDAT FP1={TOOL_NO 1,BASE_NO 3,IPO_FRAME #BASE,...}`` in
the program's .dat. A point is taught in BASE_DATA[n] when its FDAT has
BASE_NO n (and IPO_FRAME #BASE: with #TCP the base is an external TCP and
the point is a robot-held workpiece's, which the base's change moves
differently). Points are searched in every .dat file of the controller's
tree: the KRC folder around $config.dat (KRC/R1/System/$config.dat ->
KRC/), else R1/ for R1/System/$config.dat, else the file's own folder. A
second $config.dat below that folder (a folder of several robots' backups)
marks another robot's tree, found the same way, and its files are left out.

Each .dat is read by ``krl.positions`` (the reader ``solve --robot`` uses) on
the fast path: the position and FDAT declaration lines and the layout lines
kept, the rest blanked, one Lark parse of the masked text.
"""
from __future__ import annotations

import re

from ..common.taught import Found, TaughtPoint, cached_reader, files_around, is_same_file
from ...errors import UcsioError
from ...geometry.frames import Frame
from . import krl
from ...parsing.model import ControllerFile
from ...parsing.document import Document

_BASE_ENTRY = re.compile(r"BASE_DATA\[(\d+)\]\Z", re.I)
MAX_DEPTH = 3        # how far up from $config.dat a KRC folder is looked for


def tree_root(parts: list[str]) -> int:
    """How many of the parts of $config.dat's folder make the controller's
    tree: up to a KRC folder (at most MAX_DEPTH up), else R1 for
    R1/System, else the folder itself."""
    for k in range(len(parts), max(len(parts) - MAX_DEPTH - 1, 0), -1):
        if parts[k - 1].upper() == "KRC":
            return k
    if len(parts) >= 2 and parts[-1].upper() == "SYSTEM" and parts[-2].upper().startswith("R"):
        return len(parts) - 1
    return len(parts)


def points_in(doc: Document, base_no: int, found: Found, read=None) -> None:
    """The E6POS/POS of ``doc`` whose FDAT has BASE_NO ``base_no`` (krl.positions,
    the same reader as ``solve --robot``, on the fast path; ``read``: a cached
    way to it)."""
    for p in (read or (lambda d: krl.positions(d, full=False)))(doc):
        if p.type not in ("E6POS", "POS") or p.base_no != base_no:
            continue
        if p.ipo_frame == "#TCP":
            found.warnings.append(f"{doc.path}:{p.line}: {p.name} is taught with IPO_FRAME #TCP "
                                  "(an external TCP): not counted")
            continue
        if p.pose is None:
            found.warnings.append(f"{doc.path}:{p.line}: {p.name} has no complete value "
                                  f"({p.problem.message if p.problem else 'no X, Y, Z'}): "
                                  "not counted")
            continue
        found.points.append(TaughtPoint(p.name, doc.path, p.line, p.pose.t, p.pose.q))


def find(cf: ControllerFile, frame: Frame, cache: dict | None = None) -> Found:
    found = Found()
    m = _BASE_ENTRY.match(frame.name)
    if frame.type != "BASE_DATA" or m is None:
        found.warnings.append(f"{frame.name} is not a base (BASE_DATA[n]): points are taught "
                              "in bases (FDAT BASE_NO)")
        return found
    base_no = int(m.group(1))

    read = cached_reader(lambda doc: krl.positions(doc, full=False), cache, "kuka")

    for src in files_around(frame.file, tree_root, (".dat",)):
        try:
            doc = cf.document if is_same_file(src, cf) else src.document()
            points_in(doc, base_no, found, read)
        except UcsioError as exc:
            found.warnings.append(f"could not read {src.name} ({exc}); its points are not "
                                  "counted")
    return found
