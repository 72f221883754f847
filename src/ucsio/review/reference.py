"""Frames given in another frame: a measured UCS (robot world) expressed
where a frame is given, and why a measured solution does not fit a frame's
reference. The frame's ``parent`` says what it is relative to; an ABB
object frame hangs from its work object's user frame (world = uframe *
oframe).
"""
from __future__ import annotations

from ..errors import UcsioError

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from ..geometry.frames import Frame, Pose
    from ..parsing.model import ControllerFile


def _parent_frame(cf: ControllerFile, frame: Frame) -> Frame | None:
    """The frame of ``cf`` that ``frame`` is given in (its Parent names a
    frame: an ABB object frame's work object, whose user frame it hangs
    from), or None."""
    parent = frame.parent
    if parent.kind != "frame":
        return None
    try:
        return cf.frame(parent.name)
    except UcsioError:
        return None


def measured_in_parent(cf: ControllerFile, frame: Frame, world: Pose) -> Pose:
    """A measured UCS (robot world) expressed where ``frame`` is given: an ABB
    object frame is relative to its user frame (world = uframe * oframe), so
    it becomes uframe^-1 * world, with the user frame the file holds (also
    where that is not fixed in world: reference_problem says so, and only
    ``--force`` writes it); every other frame is compared as it is
    (reference_problem says when that is not robot world)."""
    uframe = _parent_frame(cf, frame)
    if uframe is not None and uframe.pose is not None:
        return uframe.pose.inverse().compose(world)
    return world


# a frame these parents hold is fixed in robot world: a robot's base is the
# world it keeps fixed (a measured solution is in it)
FIXED_PARENTS = ("world", "robot")


def _uframe_words(uframe: Frame) -> str:
    """Why a user frame is not a fixed frame in robot world."""
    if uframe.parent.kind == "frame":
        return f"it is defined on {uframe.parent.name} in turn"
    if uframe.info.get("ufprog") is False:
        return f"the controller moves it: ufprog FALSE, ufmec {uframe.info.get('ufmec')!r}"
    if uframe.reference == "wrist":
        return "it is relative to the wrist: robhold TRUE, the robot holds the work object"
    return f"it is relative to {uframe.reference!r}"


def object_frame_basis(cf: ControllerFile, frame: Frame) -> str | None:
    """For an ABB object frame whose user frame is not fixed in robot world
    but has a value: how a measured frame is put into it (what --force
    writes and diff compares), naming that user frame's values; else None."""
    uframe = _parent_frame(cf, frame)
    # a user frame on another frame: uframe^-1 * world would leave that one out
    if uframe is None or uframe.parent.kind in FIXED_PARENTS + ("frame",) \
            or uframe.pose is None:
        return None
    p = uframe.pose
    a, b, c = p.abc
    return (f"uframe⁻¹ · world with {uframe.name}'s user frame as this file holds it "
            f"(x {p.x:.3f} y {p.y:.3f} z {p.z:.3f} a {a:.4f} b {b:.4f} c {c:.4f}), right only "
            "while the user frame is there")


def reference_problem(cf: ControllerFile, frame: Frame) -> str | None:
    """Why a measured solution (the UCS in robot world) does not fit this
    frame's reference, or None when it does (directly, or for an object frame
    through its user frame: measured_in_parent)."""
    ref = frame.reference
    if frame.info.get("role") == "external_tcp":
        # KUKA BASE_TYPE #TCP: a fixed tool kept in the base table (krl.py):
        # in world, but not a fixture, so a measured UCS does not belong there.
        return ("BASE_TYPE #TCP: an external (fixed) TCP, not a plain base: a measured "
                "fixture frame does not belong here")
    if ref == "world":
        return None
    if frame.parent.kind == "frame":
        uframe = _parent_frame(cf, frame)
        if uframe is not None and uframe.parent.kind in FIXED_PARENTS \
                and uframe.pose is not None:
            return None
        if uframe is None or uframe.pose is None:
            return ("this frame is relative to a user frame with no literal value: a "
                    "measured world frame cannot be expressed in it")
        return ("this frame is relative to a user frame that is not a fixed frame "
                f"in robot world ({_uframe_words(uframe)})")
    if ref == "flange":
        return ("this tool is held by the robot: its frame is relative to the flange, not world "
                "(a TCP solved with `solve --tcp solve` is what can be written here)")
    if ref == "machine":
        return (f"this frame moves with {frame.parent.name} (an external kinematic or "
                "another robot's tool): not relative to world")
    if ref == "wrist":
        return "robhold TRUE: the robot holds this work object (stationary tool); " \
               "its user frame is relative to the wrist"
    return f"this frame is relative to {ref!r}, not robot world"
