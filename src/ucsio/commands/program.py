"""Write a program that sets a measured frame on the controller: a FANUC
TP program (-o OUT.LS) or a Yaskawa job (-o SETUF2.JBI); or, with
--measure, the robot's measurement program (below). -o's suffix picks
the vendor (--vendor NAME where it does not; FANUC where neither says).

SOLUTION.json is what `ucsio solve -o` wrote (- reads standard input).

FANUC: /PROG, /ATTR, /MN with a MESSAGE and a PAUSE (read it, then run the
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

Yaskawa (UFk only): a job whose //POS holds three positions of the frame in
the robot base (ORG, ORG + 200 mm x, ORG + 200 mm y; BASE type, mm to 3
decimals, the frame's rx, ry, rz to 4) in three global P variables, and
`MFRAME UF#(k) Pa Pb Pc`. Loading the job writes the P variables; running
it once sets the frame. The P variables: --p N (N, N+1, N+2), or --var
VAR.DAT, from which, with every job (.JBI) beside it, three free ones are
taken (the highest run of three free numbers); both: N..N+2 refused where
VAR.DAT or a job uses one. --group g: ///GROUP1 RBg.

Without -o the program goes to standard output; -o OUT writes it
atomically (the program is named after OUT: SET_UF3.LS is /PROG SET_UF3,
SETUF2.JBI is //NAME SETUF2). Before anything is written the program is
read back: the frame must give the solution within 0.001 mm and 0.001 deg.

Exit 1, nothing written: a rejected solution (its dataset failed the gate:
measure again). Exit 2, nothing written: a bad solution, a UTk without a solved
TCP (a Yaskawa UTk: no tool program yet), no register or P variable, one in
use, a comment the pendant cannot hold (16 printable ASCII characters, no
[ ] : ; quotes), an option the vendor's program does not take, a vendor
without a program writer.

--measure PLAN.csv CONTROLLER --frame NAME (--tool NAME | --tcp X,Y,Z) -o
OUT writes the measurement program instead: the reflector moved to each
point of the plan in the controller's frame NAME, approach and retract
--approach MM along --approach-dir (the frame's +Z), linear moves at
--speed MM/S, a stop (or --dwell S) at each point; the plan's orientations,
else --orientation, else the tool down the frame's -Z; --spread DEG turns
the tool point by point for a TCP solved with the frame (plan --tcp solve
says how much). ABB writes a module (-o NAME.mod), FANUC a TP program
(.LS), Yaskawa a job (.JBI), KUKA two files: -o NAME.src and NAME.dat
beside it, both written or neither. An existing file is never replaced.
The program is read back before it is written; the summary's second line
is the solve command that reads it as the robot side (--json: read_back)."""
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
    p.add_argument("--pr", type=int, default=None, metavar="N", help="FANUC: the position register")
    p.add_argument("--posreg", metavar="posreg.va",
                   help="FANUC: the robot's posreg.va: take an unused register (or check --pr)")
    p.add_argument("--comment", metavar="TEXT", help="FANUC: the frame's comment: UFRAME[k:TEXT]")
    p.add_argument("--wpr", metavar="W,P,R",
                   help="FANUC UTk: the tool's W, P, R in degrees (default 0,0,0)")
    p.add_argument("--p", type=int, default=None, metavar="N",
                   help="Yaskawa: the job loads its points into P N, N+1, N+2")
    p.add_argument("--var", metavar="VAR.DAT",
                   help="Yaskawa: the backup's VAR.DAT: take three P variables that neither it "
                        "nor a job beside it uses (or check --p)")
    p.add_argument("--vendor", metavar="NAME", default=None,
                   help="whose program: fanuc, yaskawa (default: by -o's suffix, .LS FANUC, "
                        ".JBI Yaskawa; FANUC where it says neither)")
    m = p.add_argument_group("the measurement program (--measure PLAN.csv CONTROLLER)")
    m.add_argument("--measure", metavar="PLAN.csv",
                   help="write the measurement program of this plan: SOLUTION.json's place "
                        "takes the CONTROLLER file whose --frame and --tool it moves in")
    m.add_argument("--tool", metavar="NAME|FILE:NAME",
                   help="the reflector's tool: one of CONTROLLER's, or of FILE (Yaskawa's "
                        "TOOL.CND:UT1)")
    m.add_argument("--tcp", metavar="X,Y,Z",
                   help="the reflector on the flange (FANUC: the faceplate's positions, UT 0; "
                        "ABB: tool0's; KUKA: TOOL_NO 0)")
    m.add_argument("--approach", type=float, default=100.0, metavar="MM",
                   help="approach and retract distance (default 100)")
    m.add_argument("--approach-dir", metavar="X,Y,Z",
                   help="approach direction in the frame (default 0,0,1: the frame's +Z)")
    m.add_argument("--orientation", metavar="A,B,C",
                   help="the tool's orientation in the frame, in the vendor's angles "
                        "(default: the TCP's z down the frame's -Z); the plan's robot_* "
                        "columns give each point's own")
    m.add_argument("--spread", type=float, default=None, metavar="DEG",
                   help="for a TCP solved with the frame: turn the tool by DEG/2 about its x "
                        "and y axes in turn, point by point (plan --tcp solve says how much)")
    m.add_argument("--speed", type=float, default=100.0, metavar="MM/S",
                   help="linear speed (default 100)")
    m.add_argument("--dwell", type=float, default=None, metavar="S",
                   help="wait S seconds at each point (default: a stop)")
    p.add_argument("-o", "--output", metavar="OUT.LS|OUT.JBI",
                   help="write the program here (default: standard output); --measure's "
                        "ABB module: OUT.mod; KUKA's: OUT.src, and OUT.dat beside it")


def make(solution, frame: str, *, group=None, pr=None, posreg=None, comment=None,
         wpr=None, p=None, var=None, vendor=None, output=None):
    """The program (the vendor's ``frame_program`` result; nothing written),
    for ``run`` and ``ucsio.api.program``. ``solution``: a SOLUTION.json's
    path (- standard input) or its data (a dict); ``wpr``: "W,P,R" or three
    numbers; ``output``: where it will go (it names the program, and its
    suffix the vendor unless ``vendor`` does)."""
    from .. import vendors
    from ..errors import UcsioError, UsageError
    from ..method.solution import pose_from_json, read_json, solved_tcp
    from .patch import parse_values
    name = vendors.program_vendor(output, vendor)
    writer = vendors.get(name)
    if writer.frame_program is None:
        raise UcsioError(vendors.missing(name, "program writer"))
    angles = tuple(parse_values(wpr, 3, "--wpr")) if isinstance(wpr, str) else wpr
    given = {k: v for k, v in (("group", group), ("pr", pr), ("posreg", posreg),
                               ("comment", comment), ("wpr", angles), ("p", p), ("var", var))
             if v is not None}
    for option in given:
        if option not in writer.program_options:
            raise UsageError(f"ucsio program: --{option} does not go with a "
                             f"{vendors.title(name)} program (it takes "
                             + ", ".join("--" + o for o in writer.program_options) + ")"
                             + _whose(option))
    path = None if isinstance(solution, dict) else str(solution)
    data = solution if path is None else read_json(path)
    pose = pose_from_json(data, path)
    return writer.frame_program(pose, frame, tcp=solved_tcp(data, path), source=path,
                                output=output, **given)


def _whose(option: str) -> str:
    """'; --p is for a Yaskawa program: -o NAME.JBI or --vendor yaskawa'."""
    from .. import vendors
    for e in vendors.VENDORS:
        if e.programs and option in vendors.get(e.name).program_options:
            return (f"; --{option} is for a {e.title} program: -o NAME{e.programs[0].upper()} "
                    f"or --vendor {e.name}")
    return ""


def save(result, path: str) -> str:
    """Write a program made by ``make`` atomically (``files.atomic_write``):
    an existing file is replaced, a symbolic link written through, a folder
    or a device refused (``files.write_target``)."""
    from ..files import atomic_write, write_target
    written, _ = atomic_write(write_target(path), result.data)
    result.written = written
    return written


def document(result) -> dict:
    """--json's document (``ucsio.api.program`` too)."""
    return {"program": result.as_dict()}


def run(args) -> int:
    from ..errors import UsageError

    if args.output == "-" and args.json:
        raise UsageError("ucsio program: -o - puts the program on stdout; it does not go "
                         "with --json")
    if args.measure is not None:
        return run_measure(args)
    for option in ("tool", "tcp", "approach_dir", "orientation", "dwell"):
        if getattr(args, option) is not None:
            raise UsageError(f"ucsio program: --{option.replace('_', '-')} goes with --measure")
    result = make(args.solution, args.frame, group=args.group, pr=args.pr, posreg=args.posreg,
                  comment=args.comment, wpr=args.wpr, p=args.p, var=args.var,
                  vendor=args.vendor, output=args.output)
    return deliver(args, result, save, document)


def deliver(args, result, save, document) -> int:
    """What ``program`` does with a program once made, whichever it is: its
    warnings, the file (``save``, atomic), then ``--json``'s
    ``document(result)`` (made after the save: it names the file written),
    the program itself on standard output, or what was written."""
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
    print(result.summary(), file=sys.stderr)
    return 0


def run_measure(args) -> int:
    """``program --measure``: the measurement program, written only where no
    file is."""
    from ..errors import UsageError
    from ..programs import measure
    for option in ("group", "pr", "posreg", "comment", "wpr", "p", "var", "vendor"):
        if getattr(args, option) is not None:
            raise UsageError(f"ucsio program: --{option} does not go with --measure (the "
                             "controller's vendor writes the program, in its --frame)")
    result = measure.make(args.measure, args.solution, args.frame, tool=args.tool,
                          tcp=args.tcp, approach=args.approach, approach_dir=args.approach_dir,
                          orientation=args.orientation, spread=args.spread,
                          speed=args.speed, dwell=args.dwell, output=args.output)
    if result.companions and (not args.output or args.output == "-") and not args.json:
        raise UsageError(f"ucsio program: a {result.vendor.upper()} measurement program is "
                         "more than one file, not one on standard output: give -o "
                         f"NAME{result.suffix} (or --json, which holds every file's text)")
    return deliver(args, result, measure.save,
                   lambda made: {"measurement_program": made.as_dict()})
