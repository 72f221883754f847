"""Write a FANUC TP program that sets a measured frame. The controller does
not load .va listings; a frame reaches it through a program.

SOLUTION.json is what `ucsio solve -o` wrote (- reads standard input). The
program: /PROG, /ATTR, /MN with a MESSAGE and a PAUSE (read it, then run the
program once in T1), PR[N]=LPOS-LPOS, the six PR[N,i]= values (X Y Z W P R
to 0.001 mm and 0.001 deg, negatives in parentheses, no leading zero, as the
controller writes), UFRAME[k:comment]=PR[N] (UTOOL[k] for UTk), /POS, /END,
CRLF line endings. Load it as a .TP (ASCII upload or Roboguide).

--frame UFk writes the solution's frame (the UCS in robot world). UTk
writes the TCP of a solution whose TCP was solved (`solve --tcp solve`),
with W, P, R from --wpr (default 0, 0, 0); a solution whose TCP was given
is refused. --group g (or UFk@g) makes g the program's DEFAULT_GROUP.

The register: --pr N, or --posreg posreg.va, from which the highest-numbered
register that is Uninitialized and has no comment in every group is taken
(a register is one for all groups); with both, a PR[N] that the listing
shows in use (a value or a comment, in any group) is refused;
with neither, an error. Check that no program of the cell uses it.

Without -o the program goes to standard output; -o OUT.LS writes it
atomically (the program is named after OUT: SET_UF3.LS is /PROG SET_UF3).
Before anything is written the program is read back through ucsio's TP
grammar: the frame must give the solution within 0.001 mm and 0.001 deg.

Exit 1, nothing written: a rejected solution (its dataset failed the gate:
measure again). Exit 2, nothing written: a bad solution, a UTk without a solved
TCP, no register, a register in use, a comment the pendant cannot hold
(16 printable ASCII characters, no [ ] : ; quotes)."""
from __future__ import annotations

import sys

from ..output import emit_json


def add_arguments(p) -> None:
    p.add_argument("solution", metavar="SOLUTION.json",
                   help="the solution written by `ucsio solve -o` (- for standard input)")
    p.add_argument("--frame", required=True, metavar="UFk|UTk",
                   help="the frame the program sets: UF3, UT2 (UF3@2: group 2)")
    p.add_argument("--group", type=int, default=None, metavar="G",
                   help="motion group (default 1)")
    p.add_argument("--pr", type=int, default=None, metavar="N", help="the position register")
    p.add_argument("--posreg", metavar="posreg.va",
                   help="the robot's posreg.va: take an unused register (or check --pr)")
    p.add_argument("--comment", metavar="TEXT", help="the frame's comment: UFRAME[k:TEXT]")
    p.add_argument("--wpr", metavar="W,P,R",
                   help="UTk: the tool's W, P, R in degrees (default 0,0,0)")
    p.add_argument("-o", "--output", metavar="OUT.LS",
                   help="write the program here (default: standard output)")


def make(solution, frame: str, *, group=None, pr=None, posreg=None, comment=None,
         wpr=None, output=None):
    """The program (``vendors.fanuc.program.ProgramResult``; nothing written), for
    ``run`` and ``ucsio.api.program``. ``solution``: a SOLUTION.json's path
    (- standard input) or its data (a dict); ``wpr``: "W,P,R" or three
    numbers; ``output``: where it will go (it names the program)."""
    from ..method.solution import pose_from_json, read_json, solved_tcp
    from ..vendors.fanuc.program import program
    from .patch import parse_values
    path = None if isinstance(solution, dict) else str(solution)
    data = solution if path is None else read_json(path)
    pose = pose_from_json(data, path)
    tcp = solved_tcp(data, path)
    angles = tuple(parse_values(wpr, 3, "--wpr")) if isinstance(wpr, str) else wpr
    return program(pose, frame, group=group, pr=pr, comment=comment, posreg=posreg,
                   out=output, tcp=tcp, wpr=angles)


def document(result) -> dict:
    """--json's document (``ucsio.api.program`` too)."""
    return {"program": result.as_dict()}


def run(args) -> int:
    from ..errors import UsageError
    from ..vendors.fanuc.program import save

    if args.output == "-" and args.json:
        raise UsageError("ucsio program: -o - puts the program on stdout; it does not go "
                         "with --json")
    result = make(args.solution, args.frame, group=args.group, pr=args.pr, posreg=args.posreg,
                  comment=args.comment, wpr=args.wpr, output=args.output)
    for w in result.warnings:
        print(f"ucsio: warning: {w}", file=sys.stderr)
    if args.output and args.output != "-":
        save(result, args.output)
    if args.json:
        emit_json(document(result))
        return 0
    if not args.output or args.output == "-":
        sys.stdout.flush()
        sys.stdout.buffer.write(result.data)
        sys.stdout.buffer.flush()
        return 0
    v = result.values
    print(f"wrote {result.written}: /PROG {result.name} sets {result.frame} from "
          f"PR[{result.pr}] ({'chosen: --pr' if result.pr_from == '--pr' else 'unused in ' + result.pr_from})"
          f"\n  x {v['x']:.3f}  y {v['y']:.3f}  z {v['z']:.3f}  "
          f"w {v['w']:.3f}  p {v['p']:.3f}  r {v['r']:.3f}", file=sys.stderr)
    return 0
