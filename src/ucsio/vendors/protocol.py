"""What a vendor's package provides (its ``VENDOR``), named for type
checkers and for the test that holds every registered vendor to it.

A capability a vendor lacks is ``None``: the generic code that needs it
says so in plain words (``vendors.missing``), never by the vendor's name.
"""
from __future__ import annotations

from typing import Any, Callable, Protocol, runtime_checkable

from ..geometry.angles import AngleColumns, MeasurementColumns
from ..geometry.frames import Frame, Pose
from ..parsing.document import Document, Edit
from ..parsing.model import ControllerFile
from .common.taught import Found
from .common.write import Change


@runtime_checkable
class Vendor(Protocol):
    name: str                   # Frame.vendor, ControllerFile.vendor
    title: str                  # how messages name it: "KUKA"

    def sniff(self, doc: Document) -> bool:
        """Whether a file whose suffix names no vendor begins like this one's."""

    def parse(self, doc: Document, full: bool = False, beside: bool = True) -> ControllerFile:
        """The file's frames and lints (``full``: every byte through the grammar)."""

    def binary_refusal(self, path: str) -> str | None:
        """Why a binary file of this vendor is not read, where ``path`` is one."""

    gzip: bool                  # whether its files are read through gzip (Universal Robots')

    # Orientation: how its angles are named and written (or its quaternion), and its
    # orientation columns in SPEC's measurement CSV (None: the CSV has none of its own).
    angles: AngleColumns
    measurement_columns: MeasurementColumns | None

    # Capabilities: None where the vendor has none.
    # solve --robot: the flange poses in world of a file of its positions, for the
    # suffixes it lists. ``load`` reads a controller file of any vendor as every
    # command does (binary and foreign files refused): the front passes it in, so a
    # vendor never imports the dispatch above it. -> vendors.common.robot.RobotPoses
    robot_suffixes: tuple[str, ...]
    robot_positions: Callable[..., Any] | None
    # how many --config files its reader takes: 1, a path or None; more, a tuple of paths
    robot_configs: int

    # -- writing frames and programs (patch, program): ``review.patch`` plans
    # an edit with these, ``review.verify`` reads it back, ``review.save``
    # writes it; the shared pieces are ``vendors.common.write``.
    native_keys: tuple[str, ...]        # the components a frame is written with
    same_rotation_tolerance: float      # deg: a quarter of the written angle step
    readback_angle: float               # deg: the rotation a written frame reads back within

    # The frame writer: None all six where the vendor writes no frames (yet), and
    # patch says so. (Attributes, not methods: a method set to None would make
    # the vendor fail isinstance(vendor, Vendor).)
    # (frame, pose) -> the number changes that write ``pose`` into ``frame`` natively
    plan_changes: Callable[[Frame, Pose], list[Change]] | None
    # (frame, pose) -> those of x, y, z only (a solved TCP)
    translation_changes: Callable[[Frame, Pose], list[Change]] | None
    # (frame, changes) -> the text edits that make ``frame`` read ``changes``
    edits_for: Callable[[Frame, list[Change]], list[Edit]] | None
    # frame -> file, line (and col) a refusal of ``frame`` names
    where: Callable[[Frame], dict] | None
    # (patched cf, frame) -> ``frame`` in the patched text
    read_again: Callable[[ControllerFile, Frame], Frame] | None
    # (one declaration's text, the text before it) -> a file the vendor's grammar reads
    as_module: Callable[[str, str], str] | None

    # ``declaration_end(text, last)``: the end of a declaration whose last number ends
    # at ``last``; None: a declaration is not read back alone (the whole file)
    declaration_end: Callable[[str, int], int] | None
    # (cf, name) -> every assignment of the frame a program sets it by; None: one declaration
    assignments: Callable[[ControllerFile, str], list[Frame]] | None
    # why patch refuses every frame of its files (Stäubli's unproved rotation order), or None
    patch_refusal: str | None
    # (cf, frame, where, warnings): refuses a file the vendor does not write back
    check_patchable: Callable[[ControllerFile, Frame, dict, list[str]], None] | None
    # (frame, force, warnings, where, load): other modules that declare it too
    check_siblings: Callable[..., None] | None
    # (frame read back, changes, path): what the written numbers must satisfy besides the pose
    check_readback: Callable[[Frame, list[Change], str], None] | None
    # (frame, out or None) -> why the file is only patched as a reviewed copy
    in_place_refusal: Callable[[Frame, str | None], str | None] | None
    review_copy_warning: str | None     # what a patched reviewed copy warns
    # (pose, frame, folder, pr=, posreg=) -> a program that sets a listing's frame
    program_writer: Callable[..., Any] | None
    # ``ucsio program``: (pose, frame, tcp=, source=, output=, **options) -> a
    # program made, not written (``data`` bytes, ``warnings``, ``as_dict()``,
    # ``summary()``, ``written``); None: "X has no program writer yet". Its
    # suffixes are the registry's ``Entry.programs``.
    frame_program: Callable[..., Any] | None
    program_options: tuple[str, ...]    # the options of `ucsio program` it takes
    # ``ucsio program --measure``: (frame, tool or None (--tcp: the flange), targets,
    # settings) -> vendors.common.measure.MeasureProgram; None: "X has no
    # measurement program writer yet"
    measurement_program: Callable[..., Any] | None

    # -- taught points, unset frames, comparing frames (diff) ---------------------------
    # (cf, frame, cache) -> vendors.common.taught.Found: the points taught in a
    # frame, read from the files around it (diff --points, plan --at-taught)
    taught_points: Callable[..., Any] | None
    # the line that counts the positions it skipped ({count}, {s}, {name}): FANUC's joint
    # positions, Yaskawa's pulses and base positions
    skipped_points: str

    def taught_chain(self, cf: ControllerFile, frame: Frame,
                     measured: Pose) -> tuple[list[Pose], list[Pose]]:
        """The poses a point taught in ``frame`` goes through to world,
        simulated and measured (``measured``: the frame's measured pose in
        its parent), innermost last."""

    def taught_in_frame(self, cf: ControllerFile, frame: Frame,
                        found: Found) -> list[tuple[float, float, float]]:
        """Each taught point's position in ``frame``'s own coordinates."""

    def prefilled(self, frame: Frame, cf: ControllerFile | None) -> bool:
        """Whether the controller lists ``frame`` whether anyone taught it or
        not (an entry of a table of defaults): only such a frame can be unset."""

    def default_label(self, frame: Frame, label: str) -> bool:
        """Whether ``label`` is a name the controller gives a frame nobody named."""

    def robot_title(self, group: int) -> str | None:
        """How the controller names motion group ``group``'s robot (Yaskawa's
        R2), shown beside its node of the frame tree; None: no name of its own."""

    # (own key, SPEC's key) pairs: a frame's deltas in the vendor's terms,
    # added beside SPEC's da, db, dc (FANUC: dw = dc)
    native_deltas: tuple[tuple[str, str], ...]
