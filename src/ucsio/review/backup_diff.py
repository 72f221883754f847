"""Two whole backups side by side: the review before a download.

``ucsio diff OLD NEW`` on two folders or archives pairs the controller files
by their path inside each backup (case-insensitively, as the controllers'
file systems are), and reports files added and removed, then per changed
file its frames changed, added and removed. Files whose bytes are equal are
not even parsed (an encrypted module that did not change is no error); a file
that changed but cannot be read is listed with its error (exit 2). A FANUC
backup's binary files (.tp .sv .vr) are compared by their bytes and listed
as not read: added, removed or changed, never an error.
"""
from __future__ import annotations


from ..errors import UcsioError
from ..parsing.backup import Binary, Failure, expand, load_source
from ..parsing.sources import Source

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from typing import Any


def _sources(path: str) -> list[Source]:
    out = []
    for s in expand([path]):
        if isinstance(s, Failure):      # the backup itself is unreadable: nothing to compare
            raise s.error
        out.append(s)
    return out


def _common_top(sources: list[Source]) -> bool:
    """Whether every file lies in one top folder (an archive of the backup
    folder itself: ``R1_BACKUP_2026-12-01/RAPID/...``)."""
    tops = {s.rel.split("/", 1)[0].casefold() if "/" in s.rel else None for s in sources}
    return len(tops) == 1 and None not in tops


def _keyed(sources: list[Source], strip: bool) -> dict[str, tuple[str, Source]]:
    out: dict[str, tuple[str, Source]] = {}
    for s in sources:
        rel = s.rel.split("/", 1)[1] if strip else s.rel
        out.setdefault(rel.casefold(), (rel, s))
    return out


def pair(old: list[Source], new: list[Source]):
    """Files keyed by their path inside each backup. Where one backup wraps
    everything in a top folder the other has not (a zip of the backup folder
    against the folder's contents), that folder is set aside: of the four
    ways, the one pairing the most files wins (as given, on a tie)."""
    best = None
    for so in (False, True) if _common_top(old) else (False,):
        for sn in (False, True) if _common_top(new) else (False,):
            o, n = _keyed(old, so), _keyed(new, sn)
            score = len(o.keys() & n.keys())
            if best is None or score > best[0]:
                best = (score, o, n)
    return best[1], best[2]


def _frame_names(src: Source, errors: list) -> list[str]:
    if isinstance(src, Binary):
        return []
    try:
        return [f.name for f in load_source(src).frames]
    except UcsioError as exc:
        errors.append(exc)
        return []


def diff_backups(old_path: str, new_path: str) -> dict[str, Any]:
    from .compare import diff_files, lines_changed_beyond_frames

    olds, news = pair(_sources(old_path), _sources(new_path))
    errors: list[UcsioError] = []
    files_added, files_removed, files_changed = [], [], []
    changed, added, removed = [], [], []
    unchanged_files = 0
    for key in sorted(set(olds) | set(news)):
        (orel, o), (nrel, n) = olds.get(key, (None, None)), news.get(key, (None, None))
        if o is None:
            files_added.append(_binary({"path": nrel, "file": n.name,
                                        "frames": _frame_names(n, errors)}, n))
            continue
        if n is None:
            files_removed.append(_binary({"path": orel, "file": o.name,
                                          "frames": _frame_names(o, errors)}, o))
            continue
        try:
            old_bytes, new_bytes = o.read(), n.read()
        except UcsioError as exc:
            errors.append(exc)
            continue
        if old_bytes == new_bytes:
            unchanged_files += 1
            continue
        if isinstance(o, Binary) or isinstance(n, Binary):
            files_changed.append({"path": nrel, "old_file": o.name, "file": n.name,
                                  "frames_changed": None, "frames_added": None,
                                  "frames_removed": None, "other_lines": None,
                                  "not_read": (n if isinstance(n, Binary) else o).reason})
            continue
        from ..parsing.controller import parse
        from ..parsing.document import Document
        try:
            ocf = parse(Document(old_bytes, o.name))
            ncf = parse(Document(new_bytes, n.name))
        except UcsioError as exc:
            errors.append(exc)
            files_changed.append({"path": nrel, "old_file": o.name, "file": n.name,
                                  "frames_changed": None, "frames_added": None,
                                  "frames_removed": None, "other_lines": None,
                                  "error": str(exc)})
            continue
        r = diff_files(ocf, ncf)
        for key_, bucket in (("changed", changed), ("added", added), ("removed", removed)):
            for item in r[key_]:
                bucket.append(dict(item, path=nrel))
        files_changed.append({"path": nrel, "old_file": o.name, "file": n.name,
                              "frames_changed": len(r["changed"]),
                              "frames_added": len(r["added"]),
                              "frames_removed": len(r["removed"]),
                              "frames_unchanged": r["unchanged"],
                              "other_lines": lines_changed_beyond_frames(ocf, ncf, r),
                              "detail": r})
    return {"old": old_path, "new": new_path,
            "files_added": files_added, "files_removed": files_removed,
            "files_changed": files_changed, "files_unchanged": unchanged_files,
            "changed": changed, "added": added, "removed": removed,
            "errors": errors}


def _binary(entry: dict, src: Source) -> dict:
    """A file added or removed, with ``not_read`` where it is a binary one."""
    if isinstance(src, Binary):
        entry["not_read"] = src.reason
    return entry


def differs(result: dict[str, Any]) -> bool:
    return bool(result["files_added"] or result["files_removed"] or result["files_changed"])


def as_json(result: dict[str, Any]) -> dict[str, Any]:
    out = {k: v for k, v in result.items() if k != "errors"}
    out["files_changed"] = [{k: v for k, v in f.items() if k != "detail"}
                            for f in result["files_changed"]]
    out["errors"] = [e.as_dict() for e in result["errors"]]
    return out


def _frames_text(f: dict) -> str:
    """'2 frames: wobjA, wobjB', or why the file is not read."""
    if f.get("not_read"):
        return f"not read: {f['not_read']}"
    names = f["frames"]
    return _n(len(names), "frame") + (": " + ", ".join(names[:8]) +
                                      (", ..." if len(names) > 8 else "") if names else "")


def _n(count: int, what: str) -> str:
    return f"{count} {what}{'' if count == 1 else 's'}"


def format_backup_diff(result: dict[str, Any]) -> str:
    """Summary first (what a reviewer needs in ten seconds), then files added
    and removed, then each changed file with its frames."""
    from .compare import change_lines

    fa, fr, fc = result["files_added"], result["files_removed"], result["files_changed"]
    total = len(fa) + len(fr) + len(fc) + result["files_unchanged"]
    lines = [f"ucsio diff {result['old']} {result['new']}",
             f"  files:  {len(fc)} changed, {len(fa)} added, {len(fr)} removed, "
             f"{result['files_unchanged']} unchanged ({total} controller files)",
             f"  frames: {len(result['changed'])} changed, {len(result['added'])} added, "
             f"{len(result['removed'])} removed (in files present in both)"]
    if result["errors"]:
        lines.append(f"  NOT READ: {_n(len(result['errors']), 'file')} (marked NOT READ below)")
    if not differs(result):
        lines.append("  no difference")
    for f in fa:
        lines.append(f"+ {f['path']}: file added ({_frames_text(f)})")
    for f in fr:
        lines.append(f"- {f['path']}: file removed ({_frames_text(f)})")
    for f in fc:
        if f.get("not_read"):
            lines.append(f"~ {f['path']}: changed, not read: {f['not_read']}")
            continue
        if f.get("error"):
            lines.append(f"~ {f['path']}: changed, NOT READ: {f['error']}")
            continue
        r = f["detail"]
        n_frames = f["frames_changed"] + f["frames_added"] + f["frames_removed"]
        what = []
        if n_frames:
            what.append(f"{_n(f['frames_changed'], 'frame')} changed, {f['frames_added']} added, "
                        f"{f['frames_removed']} removed")
        if f["other_lines"]:
            what.append("other lines changed" if n_frames else
                        "lines changed, no frame (ucsio diff OLD-FILE NEW-FILE shows them)")
        lines.append(f"~ {f['path']}: " + "; ".join(what or ["bytes changed (line endings "
                                                              "or encoding), no line"]))
        lines.extend("    " + ln for ln in change_lines(r))
    shown = {f["error"] for f in fc if f.get("error")}
    for e in result["errors"]:
        if str(e) not in shown:
            lines.append(f"! NOT READ: {e}")
    return "\n".join(lines) + "\n"
