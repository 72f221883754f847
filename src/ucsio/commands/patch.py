"""Write a frame back into a controller file, in the vendor's native form
(ABB quaternion, KUKA A, B, C, FANUC X Y Z W P R), changing only that frame's
numbers.

Inputs: FILE (a RAPID module, a KRL .dat file, a FANUC TP program .ls that
sets the frame from literal PR[n,i]= lines, a FANUC sysframe.va, or a Yaskawa
UFRAME.CND or TOOL.CND without ///CRC; not a Stäubli .dtx, whose rotation
order is not proved; not a
file inside a .zip archive: extract it first), the frame's name, and the
values: --measured
SOLUTION.json (written by `ucsio solve -o`; - reads it from standard input),
or --set / --set-q.

Without -o or --in-place the unified diff of the patch is printed and nothing
is written (exit 0). -o OUT writes the patched file there (-o - to standard
output, the diff then on stderr); --in-place overwrites FILE, --backup first
keeps the original as FILE.bak (FILE.bak.1, .2, ... when that exists). A
measured solution is the UCS in robot world; for an ABB object frame
(NAME.oframe) it is written as uframe^-1 * world.

Exit 1, nothing written: a rejected solution (its dataset failed the gate:
measure again; --force writes it anyway).

Exit 2, nothing written: an unknown or ambiguous name, a frame with no
literal value, a moving user frame (ufprog FALSE), a measured (world)
solution for a frame that is not relative to world (a robot-held tool, KUKA
BASE_TYPE #TCP or a base on an external kinematic, an ABB wobj with robhold
TRUE, an oframe of a moving or robot-held wobj) or a RAPID PERS that another
module in the same folder also declares (RAPID shares it; --force overrides
these two: such an oframe then gets uframe^-1 * world with the user frame the
file holds, and the warning says so; an oframe whose uframe has no literal
value is refused even then), an archive member, a rejected solution, and a file that changed on
disk since it was read. A robot-held tool (ABB tooldata with robhold TRUE, KUKA
TOOL_DATA) with a solution from `solve --tcp solve` gets the solved TCP's x, y,
z and nothing else (orientation, mass and load stay); a solution whose TCP was
given has none to write there (exit 2). --set and --set-q take the values as
given, in the frame's own
reference (negative values need no "=": --set -5,1,2,0,0,0).

FANUC: in a TP program (UFRAME[1:FIXTURE]=PR[16] after PR[16,1]=(-.4) ...)
the six PR[16,i] values are replaced, in the program's own style (negatives
in parentheses, no leading zero, to 0.001 mm and 0.001 deg); refused (exit
2, file:line:col) where the program does not write all six as literals of
their own (PR[16]=LPOS alone, LPOS-LPOS zeros, an indirect index, a value
another frame reads too) or sets the frame twice differently. A UTk gets the
solved TCP's x, y, z. A sysframe.va gets a reviewed copy (-o OUT; never
--in-place): the controller does not load .va files; `ucsio program`
writes a TP program that sets the frame.

Yaskawa: a UFRAME.CND's ////BUSER numbers are rewritten (x, y, z with 3
decimals, rx, ry, rz with 4; --set's A, B, C are rz, ry, rx), with a warning
that the frame's taught points no longer produce it; a TOOL.CND without
///CRC takes a solved TCP; a TOOL.CND with ///CRC is refused (exit 2,
file:line:col): its checksum cannot be recomputed."""
from __future__ import annotations

import sys

from ..output import emit_json
from ..readers.options import parse_values  # noqa: F401  (their home: readers.options)


def add_arguments(p) -> None:
    p.add_argument("file", metavar="FILE",
                   help="RAPID module, KRL .dat file, FANUC TP program (.ls), sysframe.va, "
                        "UFRAME.CND or TOOL.CND")
    p.add_argument("--frame", required=True, metavar="NAME",
                   help="frame to patch (wobj1, wobj1.oframe, tool1, BASE_DATA[3], UF1, UT2 "
                        "or its label)")
    src = p.add_mutually_exclusive_group(required=True)
    src.add_argument("--measured", metavar="SOLUTION.json",
                     help="the solution written by `ucsio solve -o` (the UCS in robot world)")
    src.add_argument("--set", metavar="X,Y,Z,A,B,C",
                     help="values in mm and degrees (KUKA A, B, C; FANUC: A=R, B=P, C=W; "
                          "Yaskawa: A=rz, B=ry, C=rx)")
    src.add_argument("--set-q", metavar="X,Y,Z,Q1,Q2,Q3,Q4", help="values in mm and an ABB quaternion")
    p.add_argument("--oframe", action="store_true", help="ABB: patch the object frame of the wobj")
    p.add_argument("--force", action="store_true",
                   help="write despite a reference mismatch, a shared PERS, or a rejected solution")
    out = p.add_mutually_exclusive_group()
    out.add_argument("-o", "--output", metavar="OUT",
                     help="write the patched file here (- for standard output)")
    out.add_argument("--in-place", action="store_true", help="overwrite FILE (atomically)")
    p.add_argument("--backup", action="store_true",
                   help="with --in-place: keep the original as FILE.bak (never overwriting "
                        "one: then FILE.bak.1, FILE.bak.2, ...)")


def target_pose(args):
    """The pose to write, and whether it is a measured (world) solution."""
    from ..geometry.frames import Pose
    if args.measured:
        from ..method.solution import pose_from_json, read_json
        args.solution_data = read_json(args.measured)   # read once: it may be standard input
        return pose_from_json(args.solution_data, args.measured,
                              allow_rejected=args.force), True
    if args.set:
        return Pose.from_abc(*parse_values(args.set, 6, "--set")), False
    x, y, z, *q = parse_values(args.set_q, 7, "--set-q")
    if sum(c * c for c in q) == 0:
        from ..errors import UcsioError
        raise UcsioError("--set-q: the quaternion is all zeros")
    return Pose.from_quat(x, y, z, q), False


def solved_tcp_for(cf, name: str, oframe: bool, solution, path=None, force: bool = False):
    """The solved TCP to write when ``name`` is a robot-held tool (SPEC:
    patch on a tool writes the solved TCP's x, y, z and nothing else of it);
    None for every other frame, and where the solution's TCP was given, not
    solved (patch_frame then refuses a world frame for a tool, as before)."""
    from ..review.names import find_frame
    from ..review.patch import resolve_name, robot_held_tool
    from ..method.solution import solved_tcp

    found = cf.matches(resolve_name(name, oframe))
    if found and len({f.name.casefold() for f in found}) == 1:
        frame = found[0]        # a TP program that sets it twice: patch_frame says more
    else:
        frame = find_frame(cf, resolve_name(name, oframe))
    if not robot_held_tool(frame):
        return None
    return solved_tcp(solution, path, allow_rejected=force)


def plan_patch(cf, frame: str, pose, *, measured: bool = True, solution=None, path=None,
               force: bool = False, oframe: bool = False, check_siblings: bool = True):
    """The patch to write (``review.result.PatchResult``; nothing written), for
    ``run`` and ``ucsio.api.patch``: ``pose`` into ``frame``, or, for a
    robot-held tool and a measured ``solution`` (its JSON data) whose TCP was
    solved, that TCP's x, y, z."""
    from ..review.patch import patch_frame, patch_tcp
    tcp = solved_tcp_for(cf, frame, oframe, solution, path, force) \
        if measured and solution is not None else None
    if tcp is not None:
        return patch_tcp(cf, frame, tcp, force=force, check_siblings=check_siblings)
    return patch_frame(cf, frame, pose, measured=measured, force=force, oframe=oframe,
                       check_siblings=check_siblings)


def document(result) -> dict:
    """--json's document (``ucsio.api.patch`` too)."""
    return {"patch": result.as_dict()}


def run(args) -> int:
    from ..parsing.controller import load
    from ..errors import UsageError
    from ..output import paint_diff
    from ..review.save import save

    if args.backup and not args.in_place:
        raise UsageError("ucsio patch: --backup goes with --in-place")
    if args.output == "-" and args.json:
        raise UsageError("ucsio patch: -o - puts the patched file on stdout; it does not "
                         "go with --json")
    from ..parsing.backup import refuse_member
    refuse_member(args.file)
    pose, measured = target_pose(args)
    cf = load(args.file)
    result = plan_patch(cf, args.frame, pose, measured=measured,
                        solution=getattr(args, "solution_data", None), path=args.measured,
                        force=args.force, oframe=args.oframe)
    if args.output == "-":         # the patched file is the data on stdout
        for w in result.warnings:
            print(f"ucsio: warning: {w}", file=sys.stderr)
        sys.stderr.write(paint_diff(result.diff, sys.stderr))
        sys.stdout.flush()
        sys.stdout.buffer.write(result.new_bytes)
        sys.stdout.buffer.flush()
        return 0
    if args.in_place or args.output:
        if result.changed or args.output:
            save(result, args.output, backup=args.backup)
    for w in result.warnings:
        print(f"ucsio: warning: {w}", file=sys.stderr)
    if args.json:
        emit_json(document(result))
        return 0
    if not result.changed:
        print(f"{result.path}: {result.frame.name} already has these values "
              "at the written precision; nothing to change")
    else:
        sys.stdout.write(paint_diff(result.diff))
    if result.written:
        extra = f" (backup {result.backup})" if result.backup else ""
        print(f"wrote {result.written}{extra}", file=sys.stderr)
    return 0
