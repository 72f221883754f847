"""List every frame in controller files: ABB wobjdata (uframe and NAME.oframe),
tooldata and pose data; KUKA BASE_DATA[n], TOOL_DATA[n] and other FRAME data;
FANUC user and tool frames of sysframe.va (UF3, UT2, UF3@2 for group 2) and
those a TP program (.ls) sets; Yaskawa user frames of UFRAME.CND (UF1) and
tools of TOOL.CND (UT0).

FILE may be a controller file, a backup folder (every .mod .modx .sys .sysx
.prg .dat .va .dg .ls .cnd .jbi below it) or a .zip archive (members named
ARCHIVE.zip!path). A file that cannot be read is reported on stderr (with
--json also in "errors") and the others are still listed; exit 2 at the end
if any could not be read. A FANUC backup's binary files (.tp .sv .vr) are
counted as not read (--json: "not_read").

Unset frames (KUKA configuration entries, FANUC sysframe.va entries and
Yaskawa TOOL.CND tools whose
six values are all 0 and that have no name: the controller's defaults, which
fill most of a $config.dat or a sysframe.va) are counted in one line, not
listed; --all lists them too. --json always
holds every frame, each with "set" (true or false) and "parent" (what it is
relative to).

--tree prints the hierarchy of each FILE (a backup: of all its files): world
at the top, the robot (robot@2 for motion group 2) with its flange and the
tools on it, the user frames, bases and work objects, each object frame
under its work object's user frame, and the units (an ABB mechanical unit, a
KUKA external kinematic) with the frames they move. With --json: "tree", one
nested structure per FILE, beside the listing's keys."""
from __future__ import annotations

from ..output import emit_json, fmt, table


def add_arguments(p) -> None:
    p.add_argument("files", nargs="+", metavar="FILE",
                   help="RAPID module, KRL .dat file, FANUC .va/.ls file, Yaskawa "
                        ".CND/.JBI/.DAT file, backup folder or .zip archive")
    p.add_argument("--all", action="store_true",
                   help="also list unset frames (KUKA, FANUC and Yaskawa tool entries all 0 "
                        "and without a name)")
    p.add_argument("--tree", action="store_true",
                   help="print the hierarchy: world, robots, flanges, units and each frame "
                        "under what it is relative to")


def document(parsed, errors, not_read=()) -> dict:
    """--json's document (``api.frames`` too): every frame of the files read,
    the files, the files that could not be read, and those not read (a
    FANUC backup's binary files)."""
    from ..review.unset import as_dict
    return {"frames": [as_dict(f, c) for _, c in parsed for f in c.frames],
            "files": [c.path for _, c in parsed],      # every file read, frames or not
            "errors": [e.as_dict() for e in errors],
            "not_read": [{"file": s.name, "reason": s.reason} for s in not_read]}


def run(args) -> int:
    from . import load_inputs, report_failures
    from ..review.unset import is_set

    if args.tree:
        return run_tree(args)
    parsed, errors, not_read = load_inputs(args.files)
    status = 2 if errors else 0
    if args.json:
        emit_json(document(parsed, errors, not_read))
        report_failures(errors)
        return status
    frames = [f for _, c in parsed for f in c.frames if args.all or is_set(f, c)]
    unset = sum(len(c.frames) for _, c in parsed) - len(frames)
    # the vendor's own angle names where every frame is one vendor's (FANUC W, P, R; ABB
    # RobotStudio's rx, ry, rz beside the quaternion), else Pose.abc's a, b, c
    from ..vendors import angle_columns
    cols = angle_columns({f.vendor for f in frames})
    rows = []
    for f in frames:
        p = f.pose
        if p is None:
            nums = ["-"] * 6 + ["-"]
        else:
            abc = dict(zip("abc", p.abc))
            angles = [abc[k] for k in cols.keys]
            nums = [fmt(v) for v in (p.x, p.y, p.z)] + [fmt(v, 4) for v in angles] + \
                   ["[" + ", ".join(f"{v:.6f}" for v in p.q) + "]"]
        ref = f.reference
        role = f.info.get("role")
        if role in ("external_tcp", "workpiece"):   # KUKA: not a plain tool or base
            ref += f" ({role.replace('_', ' ')})"
        rows.append([f.name, f.type, f.label or "", ref, *nums, f"{f.file}:{f.line}"])
    if rows:
        print(table(["name", "type", "label", "ref", "x", "y", "z", *cols.names, "q", "at"],
                    rows, right={4, 5, 6, 7, 8, 9}))
    else:
        print("no set frames" if unset else "no frames")
        for _, c in parsed:             # what a file without frames holds instead (a job)
            if c.extra.get("holds"):
                print(f"{c.path}: {c.extra['holds']}")
    if unset:
        print(f"{unset} unset frame{'s' if unset != 1 else ''} not listed (all six values 0 and "
              "no name: the controller's defaults; --all lists them)")
    if not_read:
        print(_not_read_line(not_read))
    report_failures(errors)
    return status


def _not_read_line(not_read) -> str:
    """'3 binary files not read (2 .tp, 1 .sv): ...'"""
    import os
    counts: dict[str, int] = {}
    for s in not_read:
        suffix = os.path.splitext(s.rel)[1].lower()
        counts[suffix] = counts.get(suffix, 0) + 1
    what = ", ".join(f"{n} {k}" for k, n in sorted(counts.items()))
    n = len(not_read)
    from ..parsing.backup import Foreign
    if any(isinstance(s, Foreign) for s in not_read):
        return (f"{n} file{'s' if n != 1 else ''} not read ({what}): FANUC binaries and data, "
                "or other controllers' files (check lists each with why)")
    return (f"{n} binary FANUC file{'s' if n != 1 else ''} not read ({what}): ucsio reads "
            "their ASCII twins (.ls, .va)")


# ------------------------------------------------------------------ --tree

def load_each(paths: list[str]):
    """load_inputs, one input at a time: ([(path, parsed)], errors, not_read),
    so that each FILE (a backup: all its files) is one tree."""
    from ..parsing.backup import load_all, single_input
    per_input, errors, not_read = [], [], []
    for path in paths:
        parsed, errs, skipped = load_all([path])
        per_input.append((path, parsed))
        errors += errs
        not_read += skipped
    if errors and single_input(paths):
        raise errors[0]
    return per_input, errors, not_read


def trees(per_input, show_all: bool):
    """(path, roots, the file of each frame by id) per input, unset frames
    pruned unless ``show_all``."""
    from ..geometry.tree import build
    from ..review.unset import is_set
    out = []
    for path, parsed in per_input:
        file_of = {id(f): c for _, c in parsed for f in c.frames}
        frames = [f for _, c in parsed for f in c.frames]
        out.append((path, build(frames, lambda f: show_all or is_set(f, file_of[id(f)])),
                    file_of))
    return out


def _node_json(cf_of):
    from ..review.unset import is_set

    def frame_keys(f) -> dict:
        d = {"type": f.type, "file": f.file, "line": f.line, "set": is_set(f, cf_of[id(f)])}
        if f.label is not None:
            d["label"] = f.label
        return d
    return frame_keys


def robot_titles(cf_of) -> dict[str, str]:
    """A robot node's name -> how its frames' controller names that robot
    (Yaskawa's R1, R2: ``robot_title``), where it names it."""
    from .. import vendors
    out: dict[str, str] = {}
    for cf in cf_of.values():
        for f in cf.frames:
            if f.parent.kind == "robot" and f.parent.name not in out:
                at = f.parent.name.find("@")
                title = vendors.get(f.vendor).robot_title(int(f.parent.name[at + 1:])
                                                          if at >= 0 else 1)
                if title is not None:
                    out[f.parent.name] = title
    return out


def _titled(tree: dict, titles: dict[str, str]) -> dict:
    """--json's tree with each robot node's title as its label."""
    if tree["kind"] == "robot" and tree["name"] in titles:
        tree["label"] = titles[tree["name"]]
    for child in tree["children"]:
        _titled(child, titles)
    return tree


def _node_text(cf_of):
    from ..output import paint
    from ..review.unset import is_set
    places = {"unit": " (moves the frames below)",
              "unknown": " (the file does not say what these are relative to)"}
    titles = robot_titles(cf_of)

    def label(node) -> str:
        f = node.frame
        if f is None:
            title = f'  "{titles[node.name]}"' if node.kind == "robot" and \
                node.name in titles else ""
            return paint(node.name, "head") + title + places.get(node.kind, "")
        words = [f.name, f.type]
        role = f.info.get("role")
        if role in ("external_tcp", "workpiece"):   # as the listing says it
            words.append(f"({role.replace('_', ' ')})")
        if f.label:
            words.append(f'"{f.label}"')
        if not is_set(f, cf_of[id(f)]):
            words.append("(unset)")
        return "  ".join(words + [f"{f.file}:{f.line}"])
    return label


def run_tree(args) -> int:
    from . import report_failures
    from ..geometry.tree import as_dict, lines
    from ..review.unset import is_set

    per_input, errors, not_read = load_each(args.files)
    built = trees(per_input, args.all)
    if args.json:
        parsed = [pc for _, pcs in per_input for pc in pcs]
        doc = document(parsed, errors, not_read)
        doc["tree"] = [{"input": path, "roots": [
            _titled(as_dict(r, _node_json(cf_of)), robot_titles(cf_of)) for r in roots]}
            for path, roots, cf_of in built]
        emit_json(doc)
    else:
        for i, (path, roots, cf_of) in enumerate(built):
            if len(built) > 1:
                print(("\n" if i else "") + f"{path}:")
            for root in roots:
                print("\n".join(lines(root, _node_text(cf_of))))
        hidden = sum(1 for _, pcs in per_input for _, c in pcs for f in c.frames
                     if not is_set(f, c))
        if hidden and not args.all:
            print(f"{hidden} unset frame{'s' if hidden != 1 else ''} not shown (all six values "
                  "0 and no name: the controller's defaults; --all shows them)")
        if not_read:
            print(_not_read_line(not_read))
    report_failures(errors)
    return 2 if errors else 0
