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


def points_in(doc: Document, within: dict[int, Pose | None], found: Found,
              read=None) -> None:
    """The positions of ``doc`` in the user frames of ``within`` ({k: UFk
    in the searched frame, None for the frame itself}); where the job has
    any, its pulses and base positions are skipped."""
    mine, fixed = [], []
    for p in (read or job.positions)(doc):
        if p.kind not in job.ROBOT_KINDS:
            continue
        if p.cartesian and p.postype == "USER" and p.user in within:
            mine.append(p)
        elif p.pulse or p.postype in FIXED:
            fixed.append(p)
    if not mine:
        return                      # a job that does not use the frame
    for p in mine:
        x, y, z, rx, ry, rz = p.xyzabc()
        pose = Pose.from_abc(x, y, z, rz, ry, rx)
        if within[p.user] is not None:            # in a frame defined on this one
            pose = within[p.user].compose(pose)
        found.points.append(TaughtPoint(p.name, doc.path, p.line, pose.t, pose.q))
    found.skipped += [(p.name, doc.path, p.line) for p in fixed]


def frames_within(cf: ControllerFile, uf: int) -> dict[int, Pose | None]:
    """User frame ``uf`` (None: its own coordinates) and every user frame
    defined on it, directly or through others (``///BASICFRM 1,19,k``), as
    its pose in UF``uf``: their positions move with UF``uf`` too."""
    on = {int(f.name[2:]): f for f in cf.frames
          if f.type == "UFRAME" and f.parent.kind == "frame" and _USER_FRAME.match(f.name)}
    within: dict[int, Pose | None] = {uf: None}
    grew = True
    while grew:                 # a chain of frames on frames, a cycle ends it
        grew = False
        for k, f in on.items():
            parent = int(f.parent.name[2:])
            if k not in within and parent in within:
                up = within[parent]
                within[k] = f.pose if up is None else up.compose(f.pose)
                grew = True
    return within


def find(cf: ControllerFile, frame: Frame, cache: dict | None = None) -> Found:
    found = Found()
    m = _USER_FRAME.match(frame.name)
    if frame.type != "UFRAME" or m is None:
        found.warnings.append(f"{frame.name} is not a user frame (UFk): a job's positions are "
                              "taught in user frames (///USER k)")
        return found
    within = frames_within(cf, int(m.group(1)))
    read = cached_reader(job.positions, cache, "yaskawa")
    # the .CND too: another controller's UFRAME.CND below ours marks its tree (left out)
    for src in files_around(frame.file, backup_root, (".jbi", ".cnd")):
        if not src.name.lower().endswith(".jbi"):
            continue
        try:
            points_in(src.document(), within, found, read)
        except UcsioError as exc:
            found.warnings.append(f"could not read {src.name} ({exc}); its points are not "
                                  "counted")
    return found
