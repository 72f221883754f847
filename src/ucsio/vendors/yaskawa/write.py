"""Writing a Yaskawa frame back: a UFRAME.CND ``////BUSER`` line or a
TOOL.CND pose line, in place.

The controller writes every number with fixed decimals (x, y, z to 0.001
mm, rx, ry, rz to 0.0001 deg, ``-0.0176``, ``0.000``), so a new number
is written the same way whatever the old one looks like. R = Rz(rz)·Ry(ry)·
Rx(rx): SPEC's A, B, C are rz, ry, rx. What the patch cannot write: a
TOOL.CND with a ``///CRC`` line (its checksum is not known) and an
RBCALIB.DAT (the controller's calibration of two robots), refused.
"""
from __future__ import annotations

from ...errors import UcsioError
from ...geometry import rotations as rot
from ..common.write import Change, format_number, parse_text, translation_changes

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from ...geometry.frames import Frame, Pose
    from ...parsing.model import ControllerFile

TRANS_STYLE, ANGLE_DECIMALS = "0.000", 4
ANGLE_STYLE = "0." + "0" * ANGLE_DECIMALS
# a triple nearer the old angles may stand this far (deg) from the rotation:
# a quarter of the written step, so that with the rounding it reads back
SAME_ROTATION = 0.25 * 10.0 ** -ANGLE_DECIMALS
# SPEC's a, b, c (R = Rz(a)·Ry(b)·Rx(c)) in Yaskawa's names
ABC_KEYS = ("rz", "ry", "rx")

TAUGHT_POINTS_WARNING = (
    "{name}: the taught points stored with it (////RORG, ////RXX, ////RXY) no longer "
    "produce this frame: if someone redefines the frame from its points on the pendant, "
    "it jumps back to the old one")


def translation(frame: Frame, pose: Pose) -> list[Change]:
    """x, y, z to 0.001 mm, always three decimals as the controller writes them."""
    return translation_changes(frame, pose,
                               lambda v: format_number(v, 3, old_text=TRANS_STYLE))


def angle_changes(frame: Frame, pose: Pose) -> list[Change]:
    nums = [frame.numbers[k] for k in ABC_KEYS]
    old = tuple(n.value for n in nums)
    half = 0.5 * 10.0 ** -ANGLE_DECIMALS
    if rot.quat_angle(rot.abc_to_quat(*old), pose.q) <= half * 0.5:
        return []               # the same orientation (also across a gimbal-lock split)
    # at ry = +-90 many triples write this rotation: the one nearest the old
    # values, so that a small correction looks small in the diff
    near = rot.nearest_abc(pose.q, old, SAME_ROTATION)
    out = []
    for key, n, v in zip(ABC_KEYS, nums, near):
        if abs(rot.wrap180(v - n.value)) <= half:
            continue
        text = format_number(v, ANGLE_DECIMALS, old_text=ANGLE_STYLE)
        if key != "ry" and parse_text(text) == -180.0:
            text = format_number(180.0, ANGLE_DECIMALS, old_text=ANGLE_STYLE)
        out.append(Change(key, n.written, text, n.value, parse_text(text), n))
    return out


def plan(frame: Frame, pose: Pose) -> list[Change]:
    return translation(frame, pose) + angle_changes(frame, pose)


def check_patchable(cf: ControllerFile, frame: Frame, where: dict, warnings: list[str]) -> None:
    """A frame of a condition file with a ``///CRC`` line is refused at its
    block's ///CRC line (else the file's first); a user frame is written with the warning that its taught points
    no longer match it. RBCALIB.DAT's SRANG is refused: the controller
    calibrates it from its taught points in both robots."""
    if frame.type == "RBCALIB":
        raise UcsioError(f"{frame.name}: RBCALIB.DAT's ////SRANG is the robots' calibration, "
                         "computed by the controller from the points both robots taught: ucsio "
                         "does not write it, nothing written (calibrate again on the pendant)",
                         file=where.get("file"), line=frame.line, col=1)
    # the tool's own ///CRC line, else any in the file: one checksum may
    # cover every block, so no block of such a file is written
    crc_line = _crc_line(frame) if frame.info.get("crc") else cf.extra.get("crc_line")
    if crc_line is not None:
        tool = frame.type == "TOOL"
        raise UcsioError(f"{frame.name}: this {'TOOL' if tool else 'UFRAME'}.CND carries a "
                         "///CRC checksum that ucsio cannot compute, and a controller may reject "
                         "a file whose checksum does not match: not patched, nothing written "
                         f"(edit the {'tool' if tool else 'user frame'} on the pendant)",
                         file=where.get("file"), line=crc_line, col=1)
    if frame.type == "UFRAME":
        warnings.append(TAUGHT_POINTS_WARNING.format(name=frame.name) + _in_jobs(cf, frame))
        # the patch keeps the file's line endings: say that these will not load
        warnings += [f"{lint.message} (lf-only)" for lint in cf.lints if lint.code == "lf-only"]


def _in_jobs(cf: ControllerFile, frame: Frame) -> str:
    """What the backup's jobs hold in the frame: those positions move with
    it (read as ``diff --points`` reads them)."""
    if frame.file in (None, "", "-"):     # standard input: no backup around it
        return ""
    from .taught import find
    found = find(cf, frame)
    n = len(found.points)
    if not n:
        return ""
    files = sorted({p.file for p in found.points})
    shown = ", ".join(files[:3]) + (f" and {len(files) - 3} more" if len(files) > 3 else "")
    return (f"; {n} position{'s' if n != 1 else ''} of the backup's jobs ({shown}) "
            f"{'are' if n != 1 else 'is'} taught in {frame.name} and move{'' if n != 1 else 's'} "
            "with it (diff --points shows how far)")


def _crc_line(frame: Frame) -> int:
    """The line of the tool's ``///CRC`` (the block's head where not found)."""
    text, starts = frame.document.text, frame.document.line_starts
    for number in range(frame.line + 1, len(starts) + 1):
        line = text[starts[number - 1]:starts[number - 1] + 6]
        if line == "///CRC":
            return number
        if line.startswith("//") and not line.startswith("///"):
            break
    return frame.line
