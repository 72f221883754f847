"""List every frame in controller files: ABB wobjdata (uframe and NAME.oframe),
tooldata and pose data; KUKA BASE_DATA[n], TOOL_DATA[n] and other FRAME data.

FILE may be a controller file, a backup folder (every .mod .modx .sys .sysx
.prg .dat below it) or a .zip archive (members named ARCHIVE.zip!path). A file
that cannot be read is reported on stderr (with --json also in "errors") and
the others are still listed; exit 2 at the end if any could not be read."""
from __future__ import annotations

from ..output import emit_json, fmt, table


def add_arguments(p) -> None:
    p.add_argument("files", nargs="+", metavar="FILE",
                   help="RAPID module, KRL .dat file, backup folder or .zip archive")


def run(args) -> int:
    from . import load_inputs, report_failures

    parsed, errors = load_inputs(args.files)
    status = 2 if errors else 0
    frames = [fr for _, c in parsed for fr in c.frames]
    if args.json:
        emit_json({"frames": [f.as_dict() for f in frames],
                   "files": [c.path for _, c in parsed],      # every file read, frames or not
                   "errors": [e.as_dict() for e in errors]})
        report_failures(errors)
        return status
    rows = []
    for f in frames:
        p = f.pose
        if p is None:
            nums = ["-"] * 6 + ["-"]
        else:
            nums = [fmt(v) for v in (p.x, p.y, p.z)] + [fmt(v, 4) for v in p.abc] + \
                   ["[" + ", ".join(f"{v:.6f}" for v in p.q) + "]"]
        ref = f.reference
        role = f.info.get("role")
        if role in ("external_tcp", "workpiece"):   # KUKA: not a plain tool or base
            ref += f" ({role.replace('_', ' ')})"
        rows.append([f.name, f.type, f.label or "", ref, *nums, f"{f.file}:{f.line}"])
    if rows:
        print(table(["name", "type", "label", "ref", "x", "y", "z", "a", "b", "c", "q", "at"],
                    rows, right={4, 5, 6, 7, 8, 9}))
    else:
        print("no frames")
    report_failures(errors)
    return status
