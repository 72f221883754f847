"""What a reviewer reads before anything goes to a controller.

- ``diff_frame``: one frame of a file (simulated) against a measured pose,
  with SPEC's keys (``diff.frame_delta``).
- ``diff_files``: every frame of two controller files matched by name
  (case-insensitively): ``changed``, ``added``, ``removed``. Values that are
  equal at the controllers' float32 precision count as unchanged, and so do
  q and -q, or two A, B, C (FANUC W, P, R) splits of the same rotation:
  W 180 and W -180 are one frame.
- ``textconv``: a stable one-line-per-frame listing (values as written),
  then the file's text, for git's ``diff.<driver>.textconv``.
- ``git_diff``: the seven-argument form git passes to an external diff
  driver (``GIT_EXTERNAL_DIFF`` or ``diff.<driver>.command``).
"""
from __future__ import annotations

import os

from .. import vendors
from ..errors import UcsioError
from ..geometry.frames import Frame, Pose
from ..parsing.controller import parse
from ..parsing.document import Document, text_lines
from ..parsing.model import ControllerFile
from .diff import DEFAULT_TOLERANCE, frame_delta
from .names import find_frame
from .unset import is_set, warning as unset_warning
from ..vendors.common.write import close32 as _close32, poses_equal
from .patch import resolve_name, same_rotation_tolerance
from .reference import measured_in_parent, object_frame_basis, reference_problem
from .unified import unified_lines

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from typing import Any


def _is_devnull(path: str) -> bool:
    """git passes the literal /dev/null for an added or removed file, on
    every platform."""
    return path in ("/dev/null", os.devnull) or (os.name == "nt" and path.lower() == "nul")


def diff_frame(cf: ControllerFile, name: str, measured: Pose,
               tolerance: float = DEFAULT_TOLERANCE, oframe: bool = False) -> dict[str, Any]:
    """SPEC's one-frame diff: Δ = measured − simulated (the frame in ``cf``)."""
    frame = find_frame(cf, resolve_name(name, oframe))
    if frame.pose is None:
        raise UcsioError(f"{frame.name}: the file gives no literal value for this frame",
                         file=frame.file, line=frame.line)
    d: dict[str, Any] = {"name": frame.name, "file": frame.file, "line": frame.line,
                         "vendor": frame.vendor, "type": frame.type,
                         "reference": frame.reference}
    if frame.label:
        d["label"] = frame.label
    d.update(frame_delta(frame.pose, measured_in_parent(cf, frame, measured), tolerance,
                         same_rotation_tolerance(frame.vendor)))
    _native_deltas(d)
    warnings = []
    why = reference_problem(cf, frame)
    if why:
        basis = object_frame_basis(cf, frame)
        warnings.append(f"{frame.name}: {why}; compared as {basis}" if basis else
                        f"{frame.name}: {why}; the measured frame is in robot world")
    d["set"] = is_set(frame, cf)
    if not d["set"]:
        warnings.append(unset_warning(frame))
    if warnings:
        d["warning"] = "; ".join(warnings)
    return d


# ------------------------------------------------------------- two files

# FANUC's W, P, R and Yaskawa's rx, ry, rz are the pose's rotation, compared
# as one (frame_changes' "value"), never as three numbers: W 180 and W -180
# are one frame (and "rz: -179.999 -> -0.4335" said a rotation twice, rounded)
_IGNORED_INFO = {"module", "w", "p", "r", "rx", "ry", "rz"}


def _native_deltas(d: dict) -> None:
    """A frame's deltas in its vendor's own terms beside SPEC's (FANUC:
    dw = dc, dp = db, dr = da: a = r, b = p, c = w)."""
    if "da" in d:
        for own, spec in vendors.get(d["vendor"]).native_deltas:
            d[own] = d[spec]


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return _close32(float(a), float(b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return a == b


def frame_changes(old: Frame, new: Frame, memo: dict | None = None) -> list[str]:
    """Which aspects of a frame differ: 'value' (the pose), 'type',
    'reference', 'label', and info keys (robhold, ufprog, load, ...).
    ``memo``: number_texts' across the frames of two files."""
    if _written_alike(old, new, memo):
        return []
    out = []
    if not poses_equal(old.pose, new.pose):
        out.append("value")
    for attr in ("type", "reference", "label"):
        if getattr(old, attr) != getattr(new, attr):
            out.append(attr)
    for k in sorted(set(old.info) | set(new.info)):
        if k in _IGNORED_INFO or k in out:
            continue
        if not _same(old.info.get(k), new.info.get(k)):
            out.append(k)
    return out


def _written_alike(old: Frame, new: Frame, memo: dict | None = None) -> bool:
    """The same numbers written the same way, the same type, reference,
    label and info: nothing can differ (a listing's hundreds of unset
    frames are compared in a blink)."""
    from ..geometry.frames import number_texts
    return (old.type == new.type and old.reference == new.reference
            and old.label == new.label and old.info == new.info
            and number_texts(old.numbers, memo) == number_texts(new.numbers, memo))


def _index(frames: list[Frame]) -> dict[str, list[Frame]]:
    out: dict[str, list[Frame]] = {}
    for f in frames:
        out.setdefault(f.name.casefold(), []).append(f)
    return out


def diff_files(old: ControllerFile | None, new: ControllerFile | None) -> dict[str, Any]:
    """Every frame of ``old`` and ``new`` matched by name. ``None`` stands for
    a file that does not exist (git's /dev/null): all added or all removed."""
    old_frames = old.frames if old is not None else []
    new_frames = new.frames if new is not None else []
    oi, ni = _index(old_frames), _index(new_frames)
    changed, added, removed = [], [], []
    unchanged = 0
    order = list(oi) + [k for k in ni if k not in oi]
    memo: dict = {}
    for key in order:
        olds, news = oi.get(key, []), ni.get(key, [])
        for o, n in zip(olds, news):
            what = frame_changes(o, n, memo)
            if not what:
                unchanged += 1
                continue
            item: dict[str, Any] = {"name": n.name, "vendor": n.vendor, "type": n.type,
                                    "changes": what, "old": o.as_dict(), "new": n.as_dict()}
            if n.label:
                item["label"] = n.label
            if o.pose is not None and n.pose is not None:
                delta = frame_delta(o.pose, n.pose,
                                    same_rotation=same_rotation_tolerance(n.vendor))
                # simulated/measured are SPEC's names for the two sides;
                # here they are the old file and the new one.
                for k in ("dx", "dy", "dz", "da", "db", "dc", "angle", "dist", "dt_mean",
                          "group", "pass"):
                    item[k] = delta[k]
                item["simulated"], item["measured"] = delta["simulated"], delta["measured"]
                _native_deltas(item)
            changed.append(item)
        removed.extend(o.as_dict() for o in olds[len(news):])
        added.extend(n.as_dict() for n in news[len(olds):])
    return {"old": old.path if old is not None else None,
            "new": new.path if new is not None else None,
            "changed": changed, "added": added, "removed": removed,
            "unchanged": unchanged}


# ------------------------------------------------------------- text forms

def _num(v: float | None, digits: int) -> str:
    if v is None:
        return "-"
    s = f"{v:.{digits}f}"
    return s.lstrip("-") if float(s) == 0 else s


def _info_text(v: Any) -> str:
    """An info value as a reviewer reads it: a load as M/CM/J numbers, not a dict."""
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} {_info_text(x)}" for k, x in v.items()) + "}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_info_text(x) for x in v) + "]"
    if v is None:
        return "-"
    if isinstance(v, float):
        return f"{v:g}"
    return str(v)


def frame_line(f: Frame) -> str:
    """One stable line per frame: name, type, label, reference, every value
    exactly as the file writes it, and what else defines the frame (robhold,
    ufprog, types, the tool's load). No file position, so unrelated edits do
    not show on it."""
    parts = [f.name, f.type]
    if f.label:
        parts.append(f"label={f.label!r}")
    parts.append(f"ref={f.reference}")
    if f.pose is None:
        parts.append("no value")
    for key, n in f.numbers.items():
        parts.append(f"{key}={n.written}")
    for k in ("robhold", "ufprog", "ufmec", "storage", "base_type", "tool_type", "role", "load",
              "machine", "group", "config", "set_from"):
        if k in f.info and f.info[k] is not None and f.info[k] != "":
            parts.append(f"{k}={_info_text(f.info[k])}")
    return " ".join(str(x) for x in parts)


def textconv(cf: ControllerFile) -> str:
    """What git diffs in textconv mode: a line per frame (values as written),
    then the file's own text, so that a change anywhere in the file shows
    and a frame's change reads as one line before the raw lines."""
    head = "".join(frame_line(f) + "\n" for f in cf.frames)
    text = "\n".join(text_lines(cf.document.text))
    return f"# ucsio: {len(cf.frames)} frames\n{head}# ucsio: the file\n{text}\n"


def _pose_text(d: dict, extra: int = 0) -> str:
    """A pose at the written precision (+ ``extra`` digits, to show a change
    that the written precision would round away)."""
    if d.get("x") is None:
        return "no value"
    from ..vendors import angle_columns

    t, a, q = 3 + extra, 4 + extra, 6 + extra
    cols = angle_columns(d.get("vendor"))        # the vendor's own names (FANUC w p r, ...)
    s = f"x {d['x']:.{t}f}  y {d['y']:.{t}f}  z {d['z']:.{t}f}  "
    s += "  ".join(f"{name} {d[k]:.{a}f}" for name, k in zip(cols.names, cols.keys))
    if cols.quaternion and d.get("q"):
        s += "  q [" + ", ".join(f"{c:.{q}f}" for c in d["q"]) + "]"
    return s


def _pose_pair(old: dict, new: dict) -> tuple[str, str]:
    for extra in (0, 3, 6):
        a, b = _pose_text(old, extra), _pose_text(new, extra)
        if a != b:
            break
    return a, b


def format_files_diff(result: dict[str, Any], old_label: str, new_label: str) -> str:
    lines = [f"ucsio diff a/{old_label} b/{new_label}"]
    if not (result["changed"] or result["added"] or result["removed"]):
        lines.append(f"  no frame changed ({result['unchanged']} frames compared)")
        return "\n".join(lines) + "\n"
    lines.extend(change_lines(result))
    lines.append(f"  {len(result['changed'])} changed, {len(result['added'])} added, "
                 f"{len(result['removed'])} removed, {result['unchanged']} unchanged")
    return "\n".join(lines) + "\n"


def change_lines(result: dict[str, Any]) -> list[str]:
    """The frames changed (with their Δ and old/new values), added and removed."""
    lines: list[str] = []
    for c in result["changed"]:
        head = f"~ {_named(c)}: {', '.join(c['changes'])} changed"
        lines.append(head)
        if "dx" in c and "value" in c["changes"]:
            from ..vendors import angle_columns
            cols = angle_columns(c.get("vendor"))
            angles = "  ".join(f"d{name} {c['d' + k]:+.4f}"
                               for name, k in zip(cols.names, cols.keys))
            lines.append(f"    Δ dx {c['dx']:+.3f}  dy {c['dy']:+.3f}  dz {c['dz']:+.3f} mm  "
                         f"{angles} deg  "
                         f"angle {c['angle']:.4f} deg  dist {c['dist']:.3f} mm  "
                         f"dt_mean {c['dt_mean']:.3f} mm (group {c['group']})")
        if "value" in c["changes"]:
            old_text, new_text = _pose_pair(c["old"], c["new"])
            lines.append(f"    - {old_text}")
            lines.append(f"    + {new_text}")
        else:
            lines.append(f"      {_pose_text(c['new'])}")
        for k in c["changes"]:
            if k != "value":
                lines.append(f"    {k}: {_info_text(c['old'].get(k))} -> {_info_text(c['new'].get(k))}")
    for a in result["added"]:
        lines.append(f"+ {_named(a)} added: {_pose_text(a)}")
    for r in result["removed"]:
        lines.append(f"- {_named(r)} removed: {_pose_text(r)}")
    return lines


def _named(item: dict) -> str:
    """A frame as a reviewer knows it: its name, its label where the file
    gives one (KUKA ``BASE_NAME[3,]``, quoted as the file writes it), its
    type: ``BASE_DATA[3] "pintura" (BASE_DATA)``, ``wobj1 (wobjdata)``."""
    label = item.get("label")
    if label is None and isinstance(item.get("new"), dict):
        label = item["new"].get("label")
    shown = f' "{label}"' if label else ""
    return f"{item['name']}{shown} ({item['type']})"


# ------------------------------------------------------------- git

def load_as(path: str, display: str) -> ControllerFile | None:
    """Parse ``path`` (a git temporary file, maybe /dev/null) as if it were
    ``display`` (the path in the repository: its suffix picks the vendor)."""
    if _is_devnull(path):
        return None
    doc = Document.read(path)
    doc.path = display
    return parse(doc)


def files_diff_text(old: ControllerFile | None, new: ControllerFile | None,
                    old_label: str, new_label: str) -> tuple[str, dict]:
    """The two-file review: the frame changes, then the text diff whenever
    lines outside the reported frames' values changed too, so that a changed
    comment, load, robtarget or routine is never hidden behind "no frame
    changed". Returns the text and the structured result."""
    result = diff_files(old, new)
    text = format_files_diff(result, old_label, new_label)
    reported = {x["name"] for key in ("changed", "added", "removed") for x in result[key]}
    if _other_lines_changed(old, new, reported):
        text += "  lines changed beyond the frame values above; text diff:\n"
        text += _unified(_lines(old), _lines(new),
                         "/dev/null" if old is None else f"a/{old_label}",
                         "/dev/null" if new is None else f"b/{new_label}")
    return text, result


def git_diff(path: str, old_file: str, new_file: str) -> tuple[str, dict | None]:
    """Text (and the structured result, or None when the files could not be
    parsed) for git's external diff driver."""
    try:
        old, new = load_as(old_file, path), load_as(new_file, path)
    except UcsioError as exc:
        return (f"ucsio diff a/{path} b/{path}\n  not a controller file ucsio can read ({exc}); "
                "plain text diff:\n" + plain_diff(path, old_file, new_file)), None
    return files_diff_text(old, new, path, path)


def _unified(a: list[str], b: list[str], old_label: str, new_label: str) -> str:
    return "\n".join(unified_lines(a, b, old_label, new_label, 3)) + "\n"


def _lines(cf: ControllerFile | None) -> list[str]:
    return [] if cf is None else text_lines(cf.document.text)


def _frame_lines(cf: ControllerFile | None, names: set[str]) -> set[int]:
    """0-based numbers of the lines that hold the values of the frames named."""
    if cf is None:
        return set()
    doc = cf.document
    return {doc.line_of(n.span.start) - 1 for f in cf.frames if f.name in names
            for n in f.numbers.values()}


def lines_changed_beyond_frames(old: ControllerFile | None, new: ControllerFile | None,
                                result: dict[str, Any]) -> bool:
    """Whether a two-file diff ``result`` leaves lines changed that its frame
    report does not show (a comment, a routine, a load)."""
    reported = {x["name"] for key in ("changed", "added", "removed") for x in result[key]}
    return _other_lines_changed(old, new, reported)


def _other_lines_changed(old: ControllerFile | None, new: ControllerFile | None,
                         reported: set[str]) -> bool:
    """Whether lines changed beyond the values of the frames ``reported``
    (a frame rewritten within float32 noise counts as such a line: the
    reviewer sees its text change rather than nothing)."""
    a, b = _lines(old), _lines(new)
    fa, fb = _frame_lines(old, reported), _frame_lines(new, reported)
    # Without the lines of the values reported, the rest must be the same
    # lines in the same order. (A line matcher crawls on a file of many equal
    # lines whose changes are spread over it: a TOOL.CND whose 64 ///CRC
    # lines all change with one tool.)
    return [ln for i, ln in enumerate(a) if i not in fa] != \
        [ln for i, ln in enumerate(b) if i not in fb]


def plain_diff(path: str, old_file: str, new_file: str) -> str:
    def lines(p):
        if _is_devnull(p):
            return []
        return text_lines(Document.read(p).text)
    old_label = "/dev/null" if _is_devnull(old_file) else f"a/{path}"
    new_label = "/dev/null" if _is_devnull(new_file) else f"b/{path}"
    return _unified(lines(old_file), lines(new_file), old_label, new_label)


def textconv_file(path: str) -> str:
    """The listing of a file for git textconv. A file ucsio cannot read, or
    one without any frame, is passed through as text. Files beside it are
    not read (git hands over one side as a temporary copy, the other as the
    work tree's file: a FANUC frame's comment from frame.dg beside one only
    would show as a change)."""
    try:
        cf = parse(Document.read(path), beside=False)
        if cf.frames:
            return textconv(cf)
    except UcsioError:
        pass
    return Document.read(path).text


__all__ = ["diff_frame", "diff_files", "frame_changes", "textconv", "frame_line",
           "format_files_diff", "files_diff_text", "git_diff", "textconv_file"]
