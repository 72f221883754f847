"""Frame differences, in four forms:

  ucsio diff FILE --frame NAME --measured SOLUTION.json [--tolerance T]
      the simulated frame in FILE against the measured one: dx dy dz da db dc
      angle dist dt_mean, group, pass. Exit 1 when dt_mean is not below the
      tolerance (default 100 mm). --points: how far each position taught in
      the frame moves in world (the worst ten, and the count).
  ucsio diff OLD NEW
      every frame of two controller files matched by name: changed, added,
      removed. Differences below float32 precision count as unchanged.
      OLD and NEW may be two backup folders or .zip archives: files are paired
      by their path inside each, and files added and removed are listed too.
      Exit 0 whether or not anything changed (as git's external diff
      expects); with --exit-code, 1 when anything differs (as git diff
      --exit-code); 2 when a changed file cannot be read.
  ucsio diff --textconv FILE
      one stable line per frame (values as written), then the file's text,
      for git's diff.<driver>.textconv: nothing in the file can change unseen.
  ucsio diff PATH OLD-FILE OLD-HEX OLD-MODE NEW-FILE NEW-HEX NEW-MODE
      the seven arguments git passes to an external diff driver
      (GIT_EXTERNAL_DIFF, or diff.<driver>.command); /dev/null for an added
      or removed file. Always exit 0.

Git setup for a folder of controller backups:
  git config diff.ucsio.command "ucsio diff"          (or textconv: "ucsio diff --textconv")
  echo '*.mod diff=ucsio' >> .gitattributes; likewise *.sys *.dat *.va *.ls ..."""
from __future__ import annotations

import os
import sys

from ..output import emit_json, fmt, shown_difference, table


def add_arguments(p) -> None:
    # the description's forms keep their lines: cli gives every subcommand a raw-description help
    p.add_argument("files", nargs="*", metavar="FILE",
                   help="FILE (with --frame), OLD NEW (two controller files, or two backup "
                        "folders or .zip archives), or git's seven arguments")
    p.add_argument("--frame", metavar="NAME", help="the frame to compare with --measured")
    p.add_argument("--measured", metavar="SOLUTION.json",
                   help="written by `ucsio solve -o`; - for standard input")
    p.add_argument("--tolerance", type=float, default=None, metavar="MM",
                   help="dt_mean below this passes (default 100 mm)")
    p.add_argument("--oframe", action="store_true", help="ABB: the object frame of the wobj")
    p.add_argument("--points", action="store_true",
                   help="also: how far each position taught in the frame moves in world "
                        "(KUKA E6POS/POS with its BASE_NO in the controller's tree, ABB "
                        "robtargets moved to with \\WObj:=NAME in the folder's modules, FANUC "
                        "/POS positions with UF : k in the backup's .ls programs)")
    p.add_argument("--textconv", action="store_true",
                   help="print FILE's frames one per line (git diff.<driver>.textconv)")
    p.add_argument("--exit-code", action="store_true",
                   help="OLD NEW: exit 1 when anything differs, 0 when nothing does")


def run(args) -> int:
    from ..errors import UsageError

    files = args.files
    if args.textconv:
        if args.json:
            raise UsageError("ucsio diff: --textconv prints text for git; it does not go with --json")
        if len(files) != 1 or args.frame or args.measured:
            raise UsageError("ucsio diff: --textconv takes exactly one FILE")
        from ..review.compare import textconv_file
        sys.stdout.write(textconv_file(files[0]))
        return 0
    if args.frame or args.measured:
        if not (args.frame and args.measured) or len(files) != 1:
            raise UsageError("ucsio diff: expected FILE --frame NAME --measured SOLUTION.json")
        return _one_frame(args)
    if args.tolerance is not None or args.oframe or args.points:
        raise UsageError("ucsio diff: --tolerance, --oframe and --points go with --frame "
                         "and --measured")
    if len(files) == 7:
        return _git(args)
    if len(files) != 2:
        raise UsageError("ucsio diff: expected OLD NEW, FILE --frame NAME --measured "
                         "SOLUTION.json, or --textconv FILE (see ucsio diff --help)")
    if both_backups(*files):
        return _backups(args)
    from ..parsing.backup import load_one
    from ..output import paint_diff
    from ..review.compare import files_diff_text
    old, new = load_one(files[0]), load_one(files[1])
    text, result = files_diff_text(old, new, files[0], files[1])
    if args.json:
        emit_json(result)
    else:
        sys.stdout.write(paint_diff(text))
    if args.exit_code and old.document.raw != new.document.raw:
        return 1
    return 0


def both_backups(old, new) -> bool:
    """Whether OLD and NEW are two backups (True) or two files (False); a
    path that does not exist, or a backup against a single file, is an error."""
    from ..errors import UsageError
    from ..parsing.backup import is_many, is_member
    files = [os.fspath(old), os.fspath(new)]
    for f in files:     # a wrong path first: it says more than "both files or both backups"
        if not os.path.lexists(f) and not is_member(f):
            from ..errors import UcsioError
            raise UcsioError("does not exist (no such file or folder)", file=f)
    many = [is_many(f) for f in files]
    if any(many) and not all(many):
        backup, single = (files[0], files[1]) if many[0] else (files[1], files[0])
        raise UsageError(f"ucsio diff: {backup} is a backup (a folder or .zip archive) and "
                         f"{single} a single file: give two files or two backups")
    return all(many)


def backups(old, new) -> dict:
    """Two backups compared (``review.backup_diff``), checked as the command
    checks them; ``as_json`` of it is --json's document."""
    from ..errors import UsageError
    from ..review.backup_diff import diff_backups
    if not both_backups(old, new):
        raise UsageError(f"ucsio diff: {os.fspath(old)} and {os.fspath(new)} are single files, "
                         "not backups (folders or .zip archives)")
    return diff_backups(os.fspath(old), os.fspath(new))


def _backups(args) -> int:
    from ..review.backup_diff import as_json, differs, format_backup_diff
    from ..output import paint_diff
    from . import report_failures

    result = backups(*args.files)
    if args.json:
        emit_json(as_json(result))
    else:
        sys.stdout.write(paint_diff(format_backup_diff(result)))
    report_failures(result["errors"])
    if result["errors"]:
        return 2
    return 1 if args.exit_code and differs(result) else 0


def _git(args) -> int:
    from ..review.compare import git_diff
    path, old_file, _oh, _om, new_file, _nh, _nm = args.files
    text, result = git_diff(path, old_file, new_file)
    if args.json:
        emit_json(result if result is not None else {"path": path, "error": text})
    else:
        sys.stdout.write(text)
    return 0


def tolerance_of(tolerance) -> float:
    """--tolerance, checked; None is the default (100 mm)."""
    from ..review.diff import DEFAULT_TOLERANCE
    tol = DEFAULT_TOLERANCE if tolerance is None else tolerance
    if not tol > 0:
        from ..errors import UcsioError
        raise UcsioError(f"--tolerance must be positive, got {tolerance}")
    return tol


def one_frame(cf, frame: str, measured, solution=None, *, tolerance=None,
              oframe: bool = False, points: bool = False) -> dict:
    """``diff FILE --frame NAME --measured SOLUTION.json``'s document (for
    ``run`` and ``ucsio.api.diff_frame``): ``measured`` the solution's Pose,
    ``solution`` its JSON data where there is one (with ``points``, its
    covariance gives each taught point's ``at_95``)."""
    from ..review.compare import diff_frame

    tol = tolerance_of(tolerance)
    d = diff_frame(cf, frame, measured, tol, oframe=oframe)
    if points:
        d.update(taught_points(cf, frame, measured, solution, oframe=oframe))
    return d


def taught_points(cf, frame: str, measured, solution=None, *, oframe: bool = False) -> dict:
    """--points' keys: ``points``, ``points_moved``, ``points_warnings``, and
    from a solution with its covariance ``working_points`` and ``worst``."""
    from ..review.patch import resolve_name
    from ..taught import points_moved
    data = solution if isinstance(solution, dict) else None
    return points_moved(cf, cf.frame(resolve_name(frame, oframe)), measured, solution=data)


def _one_frame(args) -> int:
    from ..method.solution import pose_from_json, read_json
    from ..parsing.backup import load_one as load

    tol = tolerance_of(args.tolerance)
    data = read_json(args.measured)
    measured = pose_from_json(data, args.measured)
    cf = load(args.files[0])
    d = one_frame(cf, args.frame, measured, data, tolerance=tol, oframe=args.oframe,
                  points=args.points)
    for w in d.get("points_warnings", ()):
        print(f"ucsio: warning: {w}", file=sys.stderr)
    if args.json:
        emit_json(d)
        return 0 if d["pass"] else 1
    if "warning" in d:
        print(f"ucsio: warning: {d['warning']}", file=sys.stderr)
    label = f" ({d['label']})" if d.get("label") else ""
    print(f"{d['name']}{label}  {d['type']}  {d['file']}:{d['line']}")
    print(delta_table(d["simulated"], d["measured"], d.get("vendor"), "Δ"))
    from ..output import paint
    verdict = paint("PASS", "pass") if d["pass"] else paint("FAIL", "fail")
    print(f"angle {d['angle']:.4f} deg  dist {d['dist']:.3f} mm  dt_mean {d['dt_mean']:.3f} mm  "
          f"group {d['group']}  {verdict} (tolerance {tol:g} mm)")
    if args.points:
        print(_points_text(d))
    return 0 if d["pass"] else 1


def delta_table(sim: dict, mea: dict, vendor: str | None, delta: str = "Δ") -> str:
    """Simulated, measured and their difference, in the vendor's own angle
    names (vendors.angle_columns) and, where it writes
    one, its quaternion. The Δ row is the difference of the numbers shown above it, so
    it adds up (SPEC's unrounded Δ is in --json)."""
    from ..vendors import angle_columns

    cols = angle_columns(vendor)
    rows = []
    for head, pose in (("simulated", sim), ("measured", mea)):
        row = [head, *(fmt(pose[k]) for k in "xyz"), *(fmt(pose[k], 4) for k in cols.keys)]
        if cols.quaternion:
            row.append("[" + ", ".join(f"{v:.6f}" for v in pose["q"]) + "]")
        rows.append(row)
    rows.append([delta, *(f"{shown_difference(mea[k], sim[k], 3):+.3f}" for k in "xyz"),
                 *(f"{shown_difference(mea[k], sim[k], 4, wrap=True):+.4f}" for k in cols.keys)]
                + ([""] if cols.quaternion else []))
    return table(["", "x", "y", "z", *cols.names] + (["q"] if cols.quaternion else []), rows,
                 right={1, 2, 3, 4, 5, 6})


def _points_text(d: dict) -> str:
    """The taught points: how many, how far they move, the worst ten."""
    from ..taught import WORST

    pm = d["points_moved"]
    skipped = d.get("points_skipped") or 0
    tail = ""
    if skipped:
        from .. import vendors
        said = vendors.get(d["vendor"]).skipped_points if d.get("vendor") in vendors.BY_NAME \
            else vendors.Defaults.skipped_points
        tail = "\n" + said.format(count=skipped, s="s" if skipped != 1 else "", name=d["name"])
    if not pm["count"]:
        return f"taught points in {d['name']}: none found" + tail
    head = (f"taught points in {d['name']}: {pm['count']}, moved in world by max "
            f"{pm['max']:.3f} mm (worst {pm['worst']}), mean {pm['mean']:.3f} mm")
    rows = d["points"][:WORST]
    shown = "" if len(d["points"]) <= WORST else f" (the {WORST} that move most)"
    known = "worst" in d and d["worst"] is not None
    text = head + shown + "\n" + table(
        ["point", "file:line", "moved mm"] + (["95 % mm"] if known else []),
        [[r["name"], f"{r['file']}:{r['line']}", f"{r['moved']:.3f}"]
         + ([f"{r['at_95']:.3f}"] if known else []) for r in rows], right={2, 3})
    if known:
        w = d["worst"]
        text += (f"\nthe measured frame is known within {w['at_95']:.3f} mm (95 %) at its "
                 f"taught points (worst {w['name']}, {w['file']}:{w['line']})")
    return text + tail
