"""Write a frame back into its controller file, touching nothing else.

``plan(frame, pose)`` turns a target pose into edits of exactly the frame's
value spans (``Frame.numbers``), in the vendor's native form: each vendor's
``write`` module (``vendors/<vendor>/write.py``) says how its numbers are
written, through the vendor object's ``plan_changes``, ``edits_for`` and
the rest of its "writing frames" section. A component whose value does not
change at the written precision keeps its original text, so the diff shows
only what moved and patching a file with the values it already has changes
no byte.

``patch_frame`` adds the refusals (unknown or ambiguous name, no value, a
moving user frame, a reference the measured solution does not mean
(``review.reference``), what the vendor refuses: a shared RAPID PERS
declared in a sibling module, a FANUC listing other than sysframe.va) and a
read-back check (``review.verify``): the new bytes are parsed again and
must give the target pose within the written precision, with every byte
outside the edited spans unchanged. ``review.save`` writes it atomically;
``review.unified`` shows it as a unified diff.
"""
from __future__ import annotations

from .. import vendors
from ..errors import UcsioError
from ..geometry.frames import Frame, Pose
from ..parsing.document import Edit
from ..parsing.model import ControllerFile
from ..vendors.common.write import Change
from .names import find_frame
from .reference import measured_in_parent, object_frame_basis, reference_problem
from .result import PatchResult
from .verify import verify as verify_patch

def same_rotation_tolerance(vendor: str) -> float:
    """How far (deg) a triple nearer the old angles may stand from the
    rotation to write (``rotations.nearest_abc``): the vendor's, a quarter of
    its written step, so that with the rounding it still reads back."""
    return vendors.get(vendor).same_rotation_tolerance


# ----------------------------------------------------------------- planning

def plan(frame: Frame, pose: Pose) -> list[Change]:
    """The component changes that write ``pose`` into ``frame`` natively."""
    writer = vendors.get(frame.vendor)
    missing = [k for k in writer.native_keys if k not in frame.numbers]
    if missing:
        raise UcsioError(f"{frame.name}: no literal value for {', '.join(missing).upper()} "
                         "(nothing to replace; ucsio does not insert components)",
                         file=frame.file, line=frame.line)
    return writer.plan_changes(frame, pose)


def edits_for(frame: Frame, changes: list[Change]) -> list[Edit]:
    """The edits that write ``changes`` into ``frame``'s text, as its vendor
    writes them."""
    return vendors.get(frame.vendor).edits_for(frame, changes)


def resolve_name(name: str, oframe: bool) -> str:
    if oframe and not name.casefold().endswith(".oframe"):
        return name + ".oframe"
    return name


# ----------------------------------------------------------------- patching

def patch_frame(cf: ControllerFile, name: str, pose: Pose, *, measured: bool = True,
                force: bool = False, oframe: bool = False,
                check_siblings: bool = True, verify: bool = True,
                load=None, translation_only: bool = False) -> PatchResult:
    """Plan the patch of frame ``name`` in ``cf`` to ``pose``.

    ``measured``: the pose is a measured solution (the UCS in robot world), so
    the frame's reference must be world unless ``force``. With ``measured``
    False (``--set``) the values are taken as given in the frame's own
    reference. Refusals raise UcsioError; nothing is written here.

    ``verify``: parse the new bytes back (``verify``); a caller that applies
    several patches to one file and verifies the combined bytes itself
    (``verify(result, parsed=...)``, as ``batch`` does) passes False.
    ``load``: how sibling modules are read for the shared-PERS check
    (ABB's ``check_siblings``)."""
    warnings: list[str] = []
    # a FANUC program that sets the frame twice, alike: every assignment
    assignments = vendors.get(cf.vendor).assignments
    same = assignments(cf, resolve_name(name, oframe)) if assignments is not None else []
    frame = same[0] if same else find_frame(cf, resolve_name(name, oframe))
    writer = vendors.get(frame.vendor)
    if writer.plan_changes is None:         # a vendor that writes no frames (yet)
        raise UcsioError(f"{frame.name}: {vendors.missing(frame.vendor, 'frame writer')}: "
                         "nothing written", file=frame.file, line=frame.line, col=1)
    where = writer.where(frame)
    # what the vendor says of writing the frame (a listing's copy is for
    # review, taught points no longer give it): moot where nothing changes
    about_writing: list[str] = []
    if writer.check_patchable is not None:      # FANUC: which listings are written back
        writer.check_patchable(cf, frame, where, about_writing)
    if frame.info.get("ufprog") is False and frame.info.get("component", "uframe") == "uframe":
        raise UcsioError(f"{frame.name}: moving user frame (ufprog FALSE, ufmec "
                         f"{frame.info.get('ufmec')!r}): the controller sets it; not patchable",
                         **where)
    if frame.info.get("incomplete"):
        raise UcsioError(f"{frame.name}: the declaration holds an editor placeholder (<EXP>, ...): "
                         "incomplete, not patchable", **where)
    if frame.pose is None or not frame.numbers:
        raise UcsioError(f"{frame.name}: the file gives no literal value for this frame; "
                         "nothing to patch", **where)
    if measured:
        pose = measured_in_parent(cf, frame, pose)
        why = reference_problem(cf, frame)
        basis = object_frame_basis(cf, frame)
        if why and frame.parent.kind == "frame" and basis is None:
            # no user frame value to express it in: not even --force can write it
            raise UcsioError(f"{frame.name}: {why}; refusing to write a measured world frame",
                             **where)
        if why:
            if not force:
                how = (f"--force writes it as {basis}" if basis else
                       "--force to write it anyway")
                raise UcsioError(f"{frame.name}: {why}; refusing to write a measured world "
                                 f"frame ({how})", **where)
            if basis:
                warnings.append(f"{frame.name}: {why}; written anyway (--force) as {basis}")
            else:
                warnings.append(f"{frame.name}: {why} (written anyway: --force)")
    if check_siblings and writer.check_siblings is not None:    # ABB: a PERS shared by modules
        if load is None:
            from ..parsing.controller import load
        writer.check_siblings(frame, force, warnings, where, load)
    changes = []
    for f in same or [frame]:         # a program that sets the frame twice, alike: both
        if translation_only:      # a solved TCP: x, y, z; the orientation stays as written
            plan(f, pose)     # the refusals: a component with no literal value
            changes += writer.translation_changes(f, pose)
        else:
            changes += plan(f, pose)
    doc = cf.document
    new_bytes = doc.edited_bytes(writer.edits_for(frame, changes))
    if new_bytes != doc.raw:
        warnings[:0] = about_writing
    result = PatchResult(path=doc.path, frame=frame, pose=pose, document=doc,
                         new_bytes=new_bytes, changes=changes, warnings=warnings,
                         flagged_before=frozenset((lint.code, lint.message) for lint in cf.lints))
    if verify:
        verify_patch(result)
    return result


def robot_held_tool(frame: Frame) -> bool:
    """A TCP in flange coordinates lives here: an ABB tooldata with robhold
    TRUE, a KUKA TOOL_DATA used as a tool (not a robot-guided workpiece)."""
    return (frame.type in ("tooldata", "TOOL_DATA", "UTOOL", "TOOL", "TCP")
            and frame.reference == "flange"
            and frame.info.get("robhold") is not False
            and frame.info.get("role", "tool") == "tool")


def patch_tcp(cf: ControllerFile, name: str, tcp, **options) -> PatchResult:
    """Write a solved TCP (x, y, z in flange coordinates, ``solve --tcp
    solve``) into a robot-held tool: its translation only; orientation, mass
    and load stay as written. The same refusals, read-back check and writing
    as a frame patch."""
    frame = find_frame(cf, name)
    if not robot_held_tool(frame):
        raise UcsioError(f"{frame.name}: a solved TCP belongs in a robot-held tool (tooldata "
                         f"with robhold TRUE, KUKA TOOL_DATA); this is {frame.type} relative to "
                         f"{frame.reference}", file=frame.file, line=frame.line)
    if frame.pose is None:
        raise UcsioError(f"{frame.name}: the file gives no literal value for this tool; "
                         "nothing to patch", file=frame.file, line=frame.line)
    old = frame.pose
    target = Pose(float(tcp[0]), float(tcp[1]), float(tcp[2]), old.q, old.abc)
    return patch_frame(cf, name, target, measured=False, translation_only=True, **options)
