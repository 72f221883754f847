"""The registry: which vendor reads a file, and that vendor's capabilities.

One line per vendor (``VENDORS``) names its file suffixes and the package
that holds everything that knows its files. ``get(name)`` imports that
package only when a file of its kind is read, so a command that reads one
RAPID module imports nothing of KUKA or FANUC. What a vendor's package
provides is ``vendors.protocol.Vendor``; a capability it lacks is ``None``,
and the commands say so with ``missing(vendor, what)``.

Generic code never compares vendor names: it asks ``get(frame.vendor)``.
"""
from __future__ import annotations

import os
import sys

TYPE_CHECKING = False      # typing costs a cold start; annotations are strings
if TYPE_CHECKING:
    from ..geometry.angles import AngleColumns, MeasurementColumns
    from .protocol import Vendor


class Entry:
    """A vendor's registry line: its name (``Frame.vendor``), how it is
    shown, the suffixes of the files it reads, those of them a backup's
    folders and archives are searched for, and its package."""

    __slots__ = ("name", "title", "suffixes", "in_backups", "package", "grammars", "fallback",
                 "heads", "programs")

    def __init__(self, name: str, title: str, suffixes: tuple[str, ...],
                 in_backups: tuple[str, ...], package: str,
                 grammars: tuple[tuple[str, tuple[str, ...]], ...], fallback: bool = False,
                 heads: tuple[str, ...] = (), programs: tuple[str, ...] = ()):
        self.name, self.title, self.suffixes = name, title, suffixes
        self.in_backups, self.package, self.fallback = in_backups, package, fallback
        # (grammars/NAME.lark, start symbols) of each parser its package runs:
        # the wheel ships their LALR tables (hatch_build.py)
        self.grammars = grammars
        # first words that make a file this vendor's whatever its suffix says
        # (Yaskawa's RBCALIB.DAT and VAR.DAT end as KUKA's data lists do)
        self.heads = heads
        # the suffixes of the programs `ucsio program -o` writes for it (its
        # ``frame_program``): -o's suffix picks the vendor without importing one
        self.programs = programs


# A file of unknown suffix is sniffed by each vendor in this order; the
# fallback reads what none claims (a KRL data list has no first word of its own).
VENDORS = (
    Entry("abb", "ABB", (".mod", ".modx", ".sys", ".sysx", ".prg"),
          (".mod", ".modx", ".sys", ".sysx", ".prg"), "ucsio.vendors.abb",
          (("rapid", ("file", "data_decl")), ("rapid", ("statements",)))),
    # a KUKA backup's frames are in .dat files; its .src programs are read on their own
    Entry("kuka", "KUKA", (".dat", ".src", ".sub"), (".dat",), "ucsio.vendors.kuka",
          (("krl", ("file",)),), fallback=True),
    Entry("fanuc", "FANUC", (".va", ".dg", ".ls"), (".va", ".dg", ".ls"), "ucsio.vendors.fanuc",
          (("va", ("file",)), ("tp", ("file",))), programs=(".ls",)),
    # read line by line (no grammar): UFRAME.CND, TOOL.CND, jobs, and the
    # RBCALIB.DAT and VAR.DAT a backup's .dat search finds (claimed by their
    # first line); what ucsio does not read yet is refused by parsing.foreign
    Entry("yaskawa", "Yaskawa", (".cnd", ".jbi"), (".cnd", ".jbi"), "ucsio.vendors.yaskawa", (),
          heads=("//RBCALIB", "//VAR"), programs=(".jbi",)),
    Entry("ur", "Universal Robots", (".installation",), (".installation",), "ucsio.vendors.ur", (), heads=("<Installation",)),
    Entry("staubli", "Stäubli", (".dtx",), (".dtx",), "ucsio.vendors.staubli", ()),
)
BY_NAME = {e.name: e for e in VENDORS}
# every suffix a backup's folders and archives are searched for
BACKUP_SUFFIXES = tuple(s for e in VENDORS for s in e.in_backups)
# `ucsio program` where neither -o's suffix nor --vendor names a vendor: the
# first with programs (FANUC's TP programs were the only ones it wrote at first)
PROGRAM_DEFAULT = next(e.name for e in VENDORS if e.programs)
GRAMMARS = tuple(g for e in VENDORS for g in e.grammars)

_loaded: dict[str, Vendor] = {}


class Defaults:
    """What a vendor's class has unless it says otherwise (each vendor's
    ``VENDOR`` derives from it): no capability it has not written (None), the
    shared number edits of ``vendors.common.write``, and taught points written
    in the frame itself. Here, beside the registry, so that a vendor's package
    costs a command no module more."""

    def binary_refusal(self, path: str) -> str | None:
        return None

    measurement_columns = None
    gzip = False            # whether its files are read through gzip (parsing.document.Gzip)
    robot_suffixes: tuple[str, ...] = ()
    robot_positions = None
    robot_configs = 1       # how many --config files its positions take (more: a tuple)

    # the frame writer: each vendor's plan_changes; the rest shared where it does not differ
    plan_changes = None

    def translation_changes(self, frame, pose):
        from .common.write import translation_changes
        return translation_changes(frame, pose)

    def edits_for(self, frame, changes):
        from .common.write import edits_for
        return edits_for(frame, changes)

    def where(self, frame) -> dict:
        from .common.write import where
        return where(frame)

    def read_again(self, cf, frame):
        from .common.write import read_again
        return read_again(cf, frame)

    def as_module(self, text: str, before: str = "") -> str:
        return text                 # a declaration's text reads as a file as it is

    # why ``patch`` refuses every frame of its files, where it does (a stated reason,
    # which the demo reports as its patch step's): None, frames are written
    patch_refusal: str | None = None
    declaration_end = assignments = check_patchable = check_siblings = check_readback = None
    in_place_refusal = review_copy_warning = program_writer = None
    frame_program = measurement_program = None
    program_options: tuple[str, ...] = ()

    taught_points = None
    # diff --points: the line that counts the positions its reader skipped
    skipped_points = ("{count} joint position{s} taught in {name} skipped: joint values do not "
                      "move with a frame")

    def taught_chain(self, cf, frame, measured):
        from .common.taught import alone
        return alone(frame, measured)

    def taught_in_frame(self, cf, frame, found):
        from .common.taught import as_written
        return as_written(found)

    def prefilled(self, frame, cf) -> bool:
        return False                # no table of defaults: every frame listed is someone's

    def default_label(self, frame, label: str) -> bool:
        return False

    def robot_title(self, group: int) -> str | None:
        return None

    native_deltas: tuple[tuple[str, str], ...] = ()


def get(name: str) -> Vendor:
    """The vendor called ``name``, its package imported on first use."""
    vendor = _loaded.get(name)
    if vendor is None:
        package = BY_NAME[name].package
        __import__(package)         # importlib itself would cost every command its import
        vendor = _loaded[name] = sys.modules[package].VENDOR
    return vendor


def title(name: str) -> str:
    return BY_NAME[name].title


def by_suffix(path: str) -> str | None:
    """The vendor whose files end as ``path`` does, or None."""
    suffix = os.path.splitext(path)[1].lower()
    for e in VENDORS:
        if suffix in e.suffixes:
            return e.name
    return None


def claimed(text: str) -> str | None:
    """The vendor whose first words ``text`` begins with, whatever the
    file's suffix says (``Entry.heads``), or None."""
    head = text[:64].lstrip("\ufeff \t\r\n")
    for e in VENDORS:
        for word in e.heads:
            if head.startswith(word) and not head[len(word):len(word) + 1].isalnum():
                return e.name
    return None


def detect(doc) -> str:
    """The vendor of a document: by its first line where a vendor claims
    it, else by its suffix, else by its first words."""
    name = claimed(doc.text) or by_suffix(doc.path)
    if name is not None:
        return name
    for e in VENDORS:
        if not e.fallback and get(e.name).sniff(doc):
            return e.name
    return next(e.name for e in VENDORS if e.fallback)


def program_vendor(out: str | None, name: str | None) -> str:
    """The vendor whose program ``ucsio program`` writes: ``name``
    (--vendor), else the one whose programs end as ``out`` (-o) does, else
    ``PROGRAM_DEFAULT``. An -o suffix of another vendor's programs than
    ``name`` is an error (the file would not load where its name says)."""
    from ..errors import UsageError
    suffix = os.path.splitext(out or "")[1].lower()
    by_out = next((e.name for e in VENDORS if suffix and suffix in e.programs), None)
    if name is None:
        return by_out or PROGRAM_DEFAULT
    entry = BY_NAME.get(name.lower())
    if entry is None:
        raise UsageError(f"ucsio program: --vendor {name!r}: one of "
                         f"{', '.join(e.name for e in VENDORS)}")
    if by_out is not None and by_out != entry.name:
        raise UsageError(f"ucsio program: -o {out} is a {title(by_out)} program's name; "
                         f"--vendor {entry.name} writes {title(entry.name)}'s "
                         f"({', '.join(entry.programs) or 'none yet'})")
    return entry.name


def missing(name: str, what: str) -> str:
    """The plain words for a capability a vendor lacks: "KUKA has no program
    writer yet"."""
    return f"{title(name)} has no {what} yet"


def lint_codes() -> dict[str, str]:
    """Every vendor's lint codes (``check --ignore`` accepts exactly these),
    from each vendor's ``lints`` module: a table, imported without its parser."""
    out: dict[str, str] = {}
    for e in VENDORS:
        __import__(e.package + ".lints")
        out.update(sys.modules[e.package + ".lints"].LINT_CODES)
    return out


def angle_columns(names) -> AngleColumns:
    """The angle columns of a table of frames of the vendors ``names`` (one
    name, or several): that vendor's own where they are one, else Pose.abc's
    a, b, c (also for no vendor, or one not registered)."""
    names = {names} if isinstance(names, str) or names is None else set(names)
    only = names.pop() if len(names) == 1 else None
    if only in BY_NAME:
        return get(only).angles
    from ..geometry.angles import POSE_ANGLES
    return POSE_ANGLES


def measurement_forms() -> list[tuple[str, MeasurementColumns]]:
    """Every vendor's orientation columns in SPEC's measurement CSV, by vendor
    name, in the order of their first column: messages list them the same
    whatever the registry's order."""
    forms = [(e.name, get(e.name).measurement_columns) for e in VENDORS]
    return sorted(((name, cols) for name, cols in forms if cols is not None),
                  key=lambda form: form[1].names[0])
