"""Writing an ABB frame back (``wobjdata`` uframe/oframe, ``tooldata``
tframe, ``pose``): x, y, z and the quaternion q1..q4.

Translations to 0.001 mm; quaternion components to 6 decimals, normalised
*after* rounding (SPEC, ``quat_to_write``): plain rounding where the text,
parsed back, has |sum q^2 - 1| <= 1e-6 (FORMATS.md 1.6), else the 6-decimal
quaternion within that bound nearest in rotation. Written with q1 >= 0
(SPEC); where q1 rounds to 0, the sign on the old value's side (positive dot
product) keeps the diff small.

A RAPID PERS is one object for every module that declares it: the other
declarations in the module's folder (``shared_declarations``) refuse the
patch of one of them alone (``check_siblings``).
"""
from __future__ import annotations

import itertools
import math
import os

from ...errors import UcsioError
from ...parsing.document import looks_binary
from .. import BY_NAME
from ..common.write import Change, column, format_number, parse_text, poses_equal, \
    translation_changes

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from ...geometry.frames import Frame, Pose

QUAT_DECIMALS = 6
QUAT_NORM_MAX = 1e-6          # |sum q^2 - 1| of the written text (FORMATS 1.6)
QUAT_KEYS = ("q1", "q2", "q3", "q4")


# ----------------------------------------------------------------- the quaternion

def rotation_gap(c: list[float], q: list[float]) -> float:
    """Radians of the rotation between the (not quite unit) quaternion ``c``
    as a controller reads it (normalised) and the unit quaternion ``q``:
    2 atan2(|c x q part|, |c . q|), accurate near 0."""
    dot = sum(a * b for a, b in zip(c, q))
    cc = sum(a * a for a in c)
    perp2 = max(cc - dot * dot, 0.0)        # |c|^2 - (c.q)^2: the part of c off q's axis
    return 2.0 * math.atan2(math.sqrt(perp2), abs(dot))


def _quat_candidates(q: list[float], reach: int):
    """6-decimal quaternions around ``q``: every component within ``reach``
    steps of q_i's floor/ceiling (reach 0: floor or ceiling only)."""
    step = 10.0 ** -QUAT_DECIMALS
    options = []
    for v in q:
        lo = math.floor(round(v / step, 3))
        hi = math.ceil(round(v / step, 3))
        # as the text will parse: round(k * step) is float('0.653282'), k * step is not
        options.append(sorted({round(k * step, QUAT_DECIMALS)
                               for k in range(lo - reach, hi + reach + 1)}))
    return itertools.product(*options)


def quat_to_write(q: list[float]) -> list[float]:
    """The 6-decimal quaternion written for unit quaternion ``q`` (SPEC,
    "Files ucsio writes"): plain rounding where that gives |sum q^2 - 1| <=
    1e-6; else, among the 6-decimal quaternions within that bound, the one
    nearest in rotation to ``q``, looking first only at each component's floor
    and ceiling (so every component stays within one step of the exact value)
    and further out only where no such candidate meets the bound."""
    plain = [round(v, QUAT_DECIMALS) for v in q]
    if abs(sum(c * c for c in plain) - 1.0) <= QUAT_NORM_MAX:
        return plain
    for reach in (0, 1, 2):
        best = None
        for cand in _quat_candidates(q, reach):
            if abs(sum(c * c for c in cand) - 1.0) > QUAT_NORM_MAX:
                continue
            gap = rotation_gap(list(cand), q)
            if best is None or gap < best[0]:
                best = (gap, list(cand))
        if best is not None:
            return best[1]
    raise UcsioError(f"cannot write {q} as a normalised 6-decimal quaternion")  # pragma: no cover


def quat_changes(frame: Frame, pose: Pose) -> list[Change]:
    nums = [frame.numbers[k] for k in QUAT_KEYS]
    old = [n.value for n in nums]
    half = 0.5 * 10.0 ** -QUAT_DECIMALS
    norm = math.sqrt(sum(c * c for c in old))
    if norm > 0:
        old_unit = [c / norm for c in old]
        q_can = pose.q
        if any(all(abs(s * a - b) <= half for a, b in zip(q_can, old_unit)) for s in (1, -1)):
            return []          # the same orientation at the written precision: keep the text
    # SPEC writes q1 >= 0. Only where q1 rounds to 0 are both signs that, and
    # then the one on the old value's side keeps the diff small.
    q = list(pose.q)
    if abs(q[0]) < half and sum(a * b for a, b in zip(old, q)) < 0:
        q = [-c for c in q]
    style = column(nums, QUAT_DECIMALS)
    # A component that does not move at the written precision keeps its text,
    # so the diff shows only what moved, where the kept text still gives a
    # quaternion within the norm bound; otherwise all four are written.
    keep = [abs(q[i] - old[i]) <= half for i in range(4)]
    vals = [old[i] if keep[i] else round(q[i], QUAT_DECIMALS) for i in range(4)]
    if not any(keep) or abs(sum(c * c for c in vals) - 1.0) > QUAT_NORM_MAX:
        keep = [False] * 4
        vals = quat_to_write(q)
    texts = [nums[i].written if keep[i] else format_number(vals[i], QUAT_DECIMALS, old_text=style)
             for i in range(4)]
    parsed = [old[i] if keep[i] else parse_text(texts[i]) for i in range(4)]
    return [Change(f"q{i + 1}", nums[i].written, texts[i], nums[i].value, parsed[i])
            for i in range(4) if not keep[i] and texts[i] != nums[i].written]


def plan(frame: Frame, pose: Pose) -> list[Change]:
    return translation_changes(frame, pose) + quat_changes(frame, pose)


def check_readback(again: Frame, changes: list[Change], path: str) -> None:
    """A quaternion written must read back normalised (FORMATS 1.6)."""
    q = [again.numbers[k].value for k in QUAT_KEYS]
    if any(c.component.startswith("q") for c in changes) and \
            abs(sum(c * c for c in q) - 1.0) > QUAT_NORM_MAX:
        raise UcsioError("internal error: written quaternion is not normalised", file=path)


# ----------------------------------------------------------------- one declaration

def declaration_end(text: str, last: int) -> int:
    """Where a declaration whose last number ends at ``last`` ends: its ';'."""
    return text.find(";", last)


def as_module(text: str) -> str:
    """A declaration alone, as a module the grammar reads."""
    return f"MODULE ucsio_readback\n{text}\nENDMODULE\n"


# ----------------------------------------------------------------- shared PERS

def check_siblings(frame: Frame, force: bool, warnings: list[str], where: dict, load) -> None:
    """A PERS declared in another module of the folder too is one object:
    refused unless ``force`` (then a warning), and so is a copy of this
    module beside it (a patched copy, a backup). ``load(path)``: how a
    sibling module is read."""
    shared = shared_declarations(frame, warnings, load=load)
    copies = [s for s in shared if s["copy"]]
    if copies and not force:
        raise UcsioError(copies_message(frame, copies) + "; --force patches this file only",
                         **where)
    if copies:
        warnings.append(copies_message(frame, copies) + " (patched this file only: --force)")
    shared = [s for s in shared if not s["copy"]]
    if shared:
        names = "; ".join(f"{os.path.basename(s['file'])}:{s['line']} "
                          f"({'same value' if s['same_value'] else 'different value'})"
                          for s in shared)
        msg = (f"{frame.name}: this PERS is also declared in {names}; RAPID shares one "
               "PERS object between modules, so every declaration must be patched")
        if not force:
            raise UcsioError(msg + " (--force patches this file only)", **where)
        warnings.append(msg + " (patched this file only: --force)")


def shared_declarations(frame: Frame, warnings: list[str] | None = None, *,
                        load) -> list[dict]:
    """Other modules in the same folder that declare the same RAPID PERS.
    ``load(path)``: how a sibling module is read (``parsing.controller.load``;
    ``batch`` passes its cache, so a folder's modules are parsed once per
    run, not once per patched frame)."""
    storage = str(frame.info.get("storage") or "").upper()
    if "PERS" not in storage.split() or "LOCAL" in storage.split():
        return []
    here = frame.file
    folder = os.path.dirname(here)
    try:
        siblings = sorted(os.path.join(folder, n) if folder else n
                          for n in os.listdir(folder or ".")
                          if os.path.splitext(n)[1].lower() in BY_NAME["abb"].suffixes
                          and os.path.isfile(os.path.join(folder or ".", n)))
    except OSError:
        return []
    found = []
    key = frame.name.casefold()
    here_resolved = os.path.realpath(here)
    for p in siblings:
        if os.path.realpath(p) == here_resolved:
            continue
        if not _may_declare(p, frame.name):
            continue
        try:
            other = load(p)
        except Exception as exc:  # noqa: BLE001 - a sibling is only consulted: never fatal
            why = exc.message if isinstance(exc, UcsioError) else f"{type(exc).__name__}: {exc}"
            if warnings is not None:
                warnings.append(f"could not read sibling module {os.path.basename(p)} ({why}); "
                                "it may declare the same PERS")
            continue
        for f in other.frames:
            if f.name.casefold() == key and f.type == frame.type:
                same = poses_equal(frame.pose, f.pose)
                found.append({"file": p, "line": f.line, "same_value": same,
                              "copy": _same_module(f, frame)})
    return found


def _same_module(a: Frame, b: Frame) -> bool:
    """Both in a MODULE of one name: one file is a copy of the other (a
    patched copy, a backup), never a module the controller loads beside it."""
    name = str(a.info.get("module") or "")
    return bool(name) and name.casefold() == str(b.info.get("module") or "").casefold()


def copies_message(frame: Frame, copies: list[dict]) -> str:
    """The refusal where the other declarations are copies of the module."""
    names = ", ".join(os.path.basename(s["file"]) for s in copies)
    here = os.path.basename(frame.file)
    return (f"{frame.name}: {names} declare{'s' if len(copies) == 1 else ''} MODULE "
            f"{frame.info.get('module')} too: a copy of {here} (a patched copy or a backup), "
            "not a module the controller loads beside it; move the copy out of this folder "
            f"(write patched copies elsewhere: -o OTHER_FOLDER/{here})")


def _may_declare(path: str, name: str) -> bool:
    """Whether a sibling module can declare ``name`` at all: its bytes hold
    the data's name as a word, in any case (RAPID names are ASCII, so this holds in
    any ASCII-compatible encoding). Only those are parsed: a backup folder's
    other thirty modules cost a file read each, not a parse. A file that is
    not plain text (encrypted, UTF-16) is parsed anyway, so it is read or
    warned about as before."""
    import re

    try:
        with open(path, "rb") as fh:
            raw = fh.read()
    except OSError:
        return True                         # let the loader say what is wrong
    if looks_binary(raw):
        return True
    data = re.match(r"[A-Za-z_]\w*", name)   # the data's own name: wobj1 of wobj1.oframe, tools{2}
    if data is None:
        return True
    # lower-cased bytes and a plain substring test first: an IGNORECASE regex
    # over every sibling was most of a patch beside 34 modules (issue 13)
    needle, low = data.group().lower().encode("ascii"), raw.lower()
    if needle not in low:
        return False
    word = rb"(?<![a-z0-9_])" + re.escape(needle) + rb"(?![a-z0-9_])"
    return re.search(word, low) is not None
