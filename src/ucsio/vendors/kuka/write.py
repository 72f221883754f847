"""Writing a KUKA frame back (``BASE_DATA``, ``TOOL_DATA``, ``FRAME``): X, Y,
Z to 0.001 mm and A, B, C to 0.0001 deg in SPEC's ranges (B in [-90, 90], A
and C in (-180, 180]); REAL always with a decimal point.
"""
from __future__ import annotations

from ...geometry import rotations as rot
from ..common.write import Change, column, format_number, parse_text, translation_changes

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from ...geometry.frames import Frame, Pose

ANGLE_DECIMALS = 4
# How far (deg) a triple nearer the old angles may stand from the rotation to
# write (``rotations.nearest_abc``): a quarter of the written step, so that
# with the rounding it still reads back (common.write.READBACK_ANGLE_DEG).
SAME_ROTATION = 0.25 * 10.0 ** -ANGLE_DECIMALS


def translation(frame: Frame, pose: Pose) -> list[Change]:
    return translation_changes(frame, pose, point=True)


def angle_changes(frame: Frame, pose: Pose) -> list[Change]:
    nums = [frame.numbers[k] for k in ("a", "b", "c")]
    old = [n.value for n in nums]
    half = 0.5 * 10.0 ** -ANGLE_DECIMALS
    try:
        old_q = rot.abc_to_quat(*old)
        if rot.quat_angle(old_q, pose.q) <= half * 0.5:
            return []          # the same orientation (also across a gimbal-lock split)
    except ValueError:
        pass
    out = []
    style = column(nums, ANGLE_DECIMALS)
    # at B = +-90 many triples write this rotation: the one nearest the old
    # values, so that a small correction looks small in the diff
    near = rot.nearest_abc(pose.q, tuple(old), SAME_ROTATION)
    for key, n, v in zip("abc", nums, near):
        if abs(rot.wrap180(v - n.value)) <= half:
            continue
        text = format_number(v, ANGLE_DECIMALS, point=True, old_text=style)
        if key in "ac" and parse_text(text) == -180.0:
            text = format_number(180.0, ANGLE_DECIMALS, point=True, old_text=style)
        out.append(Change(key, n.written, text, n.value, parse_text(text)))
    return out


def plan(frame: Frame, pose: Pose) -> list[Change]:
    return translation(frame, pose) + angle_changes(frame, pose)


def declaration_end(text: str, last: int) -> int:
    """A KRL declaration is read back up to the line of its last number."""
    return last


def as_module(text: str) -> str:
    return text
