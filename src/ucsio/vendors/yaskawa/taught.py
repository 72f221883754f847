"""Yaskawa: the job positions taught in a user frame.

A job's //POS keeps each Cartesian position in the frame its group names:
``///USER k`` with ``///POSTYPE USER`` is a position in user frame ``UFk``,
so it moves with it. Joint pulses (``///PULSE``) and positions in the robot
base (``///POSTYPE BASE`` or ``ROBOT``) do not: in a job that uses UFk they
are counted as skipped, not moved. (TOOL and MTOOL positions are offsets
from a tool, in no user frame: neither.)

Points are searched in every ``.JBI`` of the backup: the folder of the
UFRAME.CND and the folders below it; another UFRAME.CND below it (another
controller's backup in a folder of several) marks that controller's tree,
whose jobs are left out (``files_around``). Each job is read by
``job.positions``, the reader ``solve --robot`` uses.
"""
from __future__ import annotations

import re

from ...errors import UcsioError
from ...geometry.frames import Pose
from ..common.taught import Found, TaughtPoint, cached_reader, files_around
from . import job

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from ...geometry.frames import Frame
    from ...parsing.document import Document
    from ...parsing.model import ControllerFile

_USER_FRAME = re.compile(r"UF(\d+)\Z", re.I)
# the positions of a job in UFk that do not move with it
FIXED = ("BASE", "ROBOT")


def backup_root(parts: list[str]) -> int:
    """``files_around``'s root: the UFRAME.CND's folder and those below it."""
    return len(parts)


def points_in(doc: Document, uf: int, found: Found, read=None) -> None:
    """The positions of ``doc`` in user frame ``uf``; where the job has any,
    its pulses and base positions are skipped."""
    mine, fixed = [], []
    for p in (read or job.positions)(doc):
        if p.kind not in job.ROBOT_KINDS:
            continue
        if p.cartesian and p.postype == "USER" and p.user == uf:
            mine.append(p)
        elif p.pulse or p.postype in FIXED:
            fixed.append(p)
    if not mine:
        return                      # a job that does not use the frame
    for p in mine:
        x, y, z, rx, ry, rz = p.xyzabc()
        pose = Pose.from_abc(x, y, z, rz, ry, rx)
        found.points.append(TaughtPoint(p.name, doc.path, p.line, pose.t, pose.q))
    found.skipped += [(p.name, doc.path, p.line) for p in fixed]


def find(cf: ControllerFile, frame: Frame, cache: dict | None = None) -> Found:
    found = Found()
    m = _USER_FRAME.match(frame.name)
    if frame.type != "UFRAME" or m is None:
        found.warnings.append(f"{frame.name} is not a user frame (UFk): a job's positions are "
                              "taught in user frames (///USER k)")
        return found
    uf = int(m.group(1))
    read = cached_reader(job.positions, cache, "yaskawa")
    # the .CND too: another controller's UFRAME.CND below ours marks its tree (left out)
    for src in files_around(frame.file, backup_root, (".jbi", ".cnd")):
        if not src.name.lower().endswith(".jbi"):
            continue
        try:
            points_in(src.document(), uf, found, read)
        except UcsioError as exc:
            found.warnings.append(f"could not read {src.name} ({exc}); its points are not "
                                  "counted")
    return found
