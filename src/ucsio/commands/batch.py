"""Solve and diff many datasets from a TOML manifest ([defaults] and
[[entry]] tables, paths relative to the manifest), with a summary by group.
One entry's failure is reported and counted, never stops the run. Exit 0 when
every entry passed (and, with --patch-dir, every patched copy was written), 1
when any was over tolerance, rejected or failed or a patched copy was refused
(the last line says which), 2 for a bad manifest or bad options."""
from __future__ import annotations

import argparse
import os
import sys

from . import add_uncertainty_options
from .. import defaults
from ..errors import UcsioError


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("manifest", metavar="MANIFEST.toml",
                   help="[defaults] and [[entry]] tables: name, measurement, controller, frame, "
                        "tcp or tool, threshold, min_points, tolerance, ... (docs/batch.md)")
    p.add_argument("--csv", metavar="FILE", default=None, help="write one row per entry")
    p.add_argument("--report", metavar="FILE.html", default=None,
                   help="write a self-contained HTML report (tables, inline SVG charts)")
    p.add_argument("--patch-dir", metavar="DIR", default=None,
                   help="write patched copies of the controller files there (never the originals)")
    add_uncertainty_options(p, "of every accepted entry")
    p.add_argument("--no-progress", action="store_true",
                   help="no progress bar (it is only drawn when stderr is a terminal)")


class _Bar:
    """A one-line progress bar on stderr; only used when stderr is a terminal."""

    def __init__(self, stream):
        self.stream = stream
        self.last = None

    def __call__(self, stage: str, done: int, total: int) -> None:
        width = 30
        filled = width * done // max(total, 1)
        state = (stage, filled, done == total)
        if state == self.last and done != total:
            return
        self.last = state
        self.stream.write(f"\r{stage:<12} [{'#' * filled}{'.' * (width - filled)}] {done}/{total}")
        self.stream.flush()

    def close(self) -> None:
        if self.last is not None:
            self.stream.write("\r" + " " * 60 + "\r")
            self.stream.flush()


def _check_output(path: str | None, option: str) -> None:
    """Refuse an output the batch could not write before it runs."""
    from ..files import write_target

    if path is None:
        return
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise UcsioError(f"{option} {path}: folder {folder} does not exist")
    write_target(path)


def batch(manifest, *, uncertainty: int = 0, sigma_laser: float = defaults.SIGMA_LASER,
          sigma_robot: float = defaults.SIGMA_ROBOT, seed: int = 0, patch_dir=None, csv=None,
          report=None, progress=None):
    """The command's work, for ``run`` and ``ucsio.api.batch`` alike: read
    the manifest, solve and diff every entry, write the patched copies
    (``patch_dir``), the CSV and the HTML report where asked; returns
    ``fleet.batch.BatchResult`` (``as_dict()`` is --json's document).
    ``progress(stage, done, total)`` is called as the entries go.

    The cyclic garbage collector is paused meanwhile: a batch keeps every
    parsed file and solution until its output, and the collector's full
    passes over them grow with the fleet (a quarter of the run at 4,000
    entries, and the cause of the time per entry rising with the entries)
    while reclaiming nothing. Reference counting still frees everything else."""
    import gc

    enabled = gc.isenabled()
    gc.disable()
    try:
        return _batch(manifest, uncertainty, sigma_laser, sigma_robot, seed, patch_dir, csv,
                      report, progress)
    finally:
        if enabled:
            gc.enable()


def _batch(manifest, uncertainty, sigma_laser, sigma_robot, seed, patch_dir, csv, report,
           progress):
    from ..fleet.batch import read_manifest, run_batch, write_csv
    from ..method.solve import check_sigmas

    if uncertainty and uncertainty < 2:
        raise UcsioError("--uncertainty needs N >= 2 samples")
    check_sigmas(sigma_laser, sigma_robot)  # before anything runs: fail at once
    csv = None if csv is None else os.fspath(csv)
    report = None if report is None else os.fspath(report)
    patch_dir = None if patch_dir is None else os.fspath(patch_dir)
    _check_output(csv, "--csv")
    _check_output(report, "--report")
    manifest = read_manifest(manifest)
    if patch_dir is not None:
        pd = os.path.abspath(patch_dir)
        for e in manifest.entries:
            for original in (e.controller, e.tcp_tool and e.tcp_tool.rpartition(":")[0]):
                if original and os.path.dirname(os.path.abspath(original)) == pd:
                    raise UcsioError(f"--patch-dir {patch_dir} holds the original "
                                     f"controller file {original}; choose another folder")
    result = run_batch(manifest, uncertainty=uncertainty, sigma_laser=sigma_laser,
                       sigma_robot=sigma_robot, seed=seed, patch_dir=patch_dir,
                       progress=progress)
    if csv:
        write_csv(result.entries, csv)  # atomic; errors: one UcsioError
    if report:
        from ..fleet.report import write_report
        write_report(result, report, csv=csv)
    return result


def run(args) -> int:
    from . import options_for
    from ..output import emit_json

    bar = _Bar(sys.stderr) if (sys.stderr.isatty() and not args.no_progress) else None
    try:
        result = batch(**options_for(batch, args), progress=bar)
    finally:
        if bar is not None:
            bar.close()

    if args.json:
        emit_json(result.as_dict())
    else:
        print(render(result, patching=args.patch_dir is not None), end="")
        from ..output import paint
        print(paint(verdict(result), "pass" if result.all_passed else "fail"))
    # what was written: messages, on stderr (stdout holds the results only)
    for opt, path in (("csv", args.csv), ("report", args.report)):
        if path:
            print(f"wrote {path} (--{opt})", file=sys.stderr)
    if args.patch_dir is not None:
        copies = sorted({p for r in result.entries
                         for p in (r.patched, r.tool_patched, (r.program or {}).get("file"))
                         if p is not None})
        if copies:
            print(f"wrote {len(copies)} patched cop{'ies' if len(copies) != 1 else 'y'} "
                  f"under {args.patch_dir}:", file=sys.stderr)
            for c in copies:
                print(f"  {c}", file=sys.stderr)
        else:
            print(f"no patched copy written under {args.patch_dir}", file=sys.stderr)
    return 0 if result.all_passed else 1


def _n(count: int, what: str, plural: str | None = None) -> str:
    return f"{count} {what if count == 1 else (plural or what + 's')}"


def verdict(result) -> str:
    """The last line: why the exit status is what it is."""
    sm = result.summary
    if result.all_passed:
        return f"exit 0: every entry passed ({sm['total']})"
    why = []
    for key, what, plural in (("over_tolerance", "entry over tolerance", "entries over tolerance"),
                              ("rejected", "rejected entry", "rejected entries"),
                              ("errors", "entry failed", "entries failed")):
        if sm.get(key):
            why.append(_n(sm[key], what, plural))
    refused = sum(r.patch_error is not None for r in result.entries)
    if refused:
        why.append(_n(refused, "patched copy not written", "patched copies not written")
                   + " (patch errors above)")
    return "exit 1: " + (", ".join(why) or "not every entry passed")


def _used(s) -> str:
    n_used, n_points = getattr(s, "n_used", None), getattr(s, "n_points", None)
    if n_used is None or n_points is None:
        return "-"
    return f"{n_used}/{n_points}"


def _paint_status(text: str, names: list, statuses: list) -> str:
    """The status column coloured on a terminal (pass green, the rest red);
    painted after the layout, so the codes do not shift the columns."""
    from ..output import colour_on, paint
    if not colour_on():
        return text
    lines = text.split("\n")
    start = max([len("entry")] + [len(str(n)) for n in names]) + 2
    for i, status in enumerate(statuses, start=2):
        ln = lines[i]
        end = start + len(status)
        lines[i] = ln[:start] + paint(ln[start:end], "pass" if status == "pass" else "fail") + ln[end:]
    return "\n".join(lines)


def _solved_tcp(r) -> str:
    """The TCP solved with the frame and its 95 % doubt (mm), or '-'."""
    t = getattr(r.solution, "tcp_solved", None) if r.error is None else None
    if not t:
        return "-"
    return f"{t['x']:.3f}, {t['y']:.3f}, {t['z']:.3f} ±{t['at_95']:.3f}"


def _tool_line(r, patching: bool) -> str | None:
    """Where an entry's solved TCP went: the tool it names, written or not."""
    if r.error is not None or not getattr(r.solution, "tcp_solved", None):
        return None
    name, tool = r.entry.name, r.entry.tcp_tool
    held = holds = ""
    if r.tool_tcp is not None:
        d = r.tool_tcp_dict()
        values = (f"{d['x']:.3f}, {d['y']:.3f}, {d['z']:.3f} mm, {d['distance']:.3f} mm from the "
                  "solved TCP")
        held, holds = f"the tool held {values}", f"{tool} holds {values}"
    if tool is None:
        if r.tool_not_patched:
            return f"{name}: {r.tool_not_patched}"
        return (f"{name}: names no tool to write it into (tool = \"FILE:NAME\" beside "
                "tcp = \"solve\")")
    if r.tool_patched is not None:
        return f"{name}: written into {tool} (copy {r.tool_patched}); {held}"
    if patching and r.patch_error is not None:
        return f"{name}: not written into {tool} (patch errors below); {held}"
    if patching:
        return f"{name}: not written into {tool}: the entry did not pass; {held}"
    return f"{name}: {holds}; --patch-dir writes the solved TCP there"


def render(result, patching: bool | None = None) -> str:
    """The text table, the errors and patch errors, groups and summary lines.
    ``patching``: show the patch column and counts (default: when any entry
    has a patched copy or a patch error)."""
    from ..output import fmt, table

    if patching is None:
        patching = any(r.patched is not None or r.patch_error is not None for r in result.entries)
    # points = true in the manifest: the taught point that moves most, per entry
    points = any(r.entry.points for r in result.entries)
    solved = any(r.entry.solve_tcp for r in result.entries)   # tcp = "solve": the TCP found
    working = any(r.entry.at for r in result.entries)        # at = "FILE": the worst working point
    rows = []
    for r in result.entries:
        d = r.delta or {}
        row = [r.entry.name, r.status, _used(r.solution),
               fmt(r.e), fmt(r.dt_mean), fmt(r.group),
               fmt(d.get("dx")), fmt(d.get("dy")), fmt(d.get("dz")),
               fmt(d.get("angle"), 4)]
        if points:
            pm = r.points_moved or {}
            row.append(f"{fmt(pm.get('max'))} ({pm['count']})" if pm.get("count") else
                       "none" if pm else "-")
        if solved:
            row.append(_solved_tcp(r))
        if working:
            w = getattr(r.solution, "worst", None) if r.error is None else None
            row.append(f"{w['name']} {w['at_95']:.3f}" if w else "-")
        if patching:
            row.append("REFUSED" if r.patch_error is not None else
                       "; ".join(r.written) or "-")
        rows.append(row)
    headers = ["entry", "status", "used", "e", "dt_mean", "group", "dx", "dy", "dz", "angle"]
    if points:
        headers.append("points moved max (n)")
    if solved:
        headers.append("tcp (95 %)")
    if working:
        headers.append("worst working point (95 %)")
    if patching:
        headers.append("patch")
    right = {2, 3, 4, 5, 6, 7, 8, 9} | ({10} if points else set())
    out = [_paint_status(table(headers, rows, right=right), [r[0] for r in rows],
                         [r[1] for r in rows])]
    tools = [line for r in result.entries if r.entry.solve_tcp
             for line in [_tool_line(r, patching)] if line]
    if tools:
        out.append("")
        out.append("solved TCPs:")
        out.extend(f"  {line}" for line in tools)
    rejected = [r for r in result.entries if r.status == "rejected"]
    wrong_tcp = [r for r in rejected if getattr(r.solution, "diagnosis", None)]
    if wrong_tcp:       # the points are fine: the TCP is not (no "measure again")
        out.append("")
        out.append("rejected, a wrong TCP (check the TCP):")
        out.extend(f"  {r.entry.name}: {r.reason}" for r in wrong_tcp)
    rejected = [r for r in rejected if r not in wrong_tcp]
    if rejected:
        out.append("")
        out.append("rejected (measure again):")
        out.extend(f"  {r.entry.name}: {r.reason}" for r in rejected)
    errors = [r for r in result.entries if r.error is not None]
    if errors:
        out.append("")
        out.append("errors:")
        out.extend(f"  {r.entry.name}: {r.error}" for r in errors)
    refused = [r for r in result.entries if r.patch_error is not None]
    if refused:
        out.append("")
        out.append("patch errors (no patched copy written for these):")
        out.extend(f"  {r.entry.name}: {r.patch_error}" for r in refused)
    no_program = [r for r in result.entries if r.program_error is not None]
    if no_program:
        out.append("")
        out.append("programs not written (the listing's copy is for review only):")
        out.extend(f"  {r.entry.name}: {r.program_error}" for r in no_program)
    warned = [r for r in result.entries if r.warnings]
    if warned:
        out.append("")
        out.append("warnings:")
        out.extend(f"  {r.entry.name}: {w}" for r in warned for w in r.warnings)
    unplaced = [r for r in result.entries if r.points_error is not None]
    if unplaced:
        out.append("")
        out.append("taught points not placed:")
        out.extend(f"  {r.entry.name}: {r.points_error}" for r in unplaced)
    noisy = [r for r in result.entries if r.error is None and r.solution is not None
             and (getattr(r.solution, "consistency", None) or {}).get("message")]
    if noisy:
        out.append("")
        out.append("noise check (residuals far above the stated noise):")
        out.extend(f"  {r.entry.name}: {r.solution.consistency['message']}" for r in noisy)
    unc = [r for r in result.entries if getattr(r, "uncertainty_error", None) is not None]
    if unc:
        out.append("")
        out.append("uncertainty not computed:")
        out.extend(f"  {r.entry.name}: {r.uncertainty_error}" for r in unc)
    sm = result.summary
    out.append("")
    grows = []
    for g in sm["groups"]:
        lo, hi = g["range"]
        span = f"{lo:g} <= dt_mean < {hi:g}" if hi is not None else f"dt_mean >= {lo:g}"
        grows.append([g["group"], span, g["count"], fmt(g.get("percent"), 1), fmt(g.get("mean_e")),
                      fmt(g.get("std_e"))])
    out.append(table(["group", "mm", "count", "% of total", "mean e", "std e"], grows,
                     right={2, 3, 4, 5}))
    out.append("")
    c = sm.get("correlation") or {}
    out.append(f"total {sm['total']}   passed {sm['passed']}   over tolerance "
               f"{sm['over_tolerance']}   rejected {sm['rejected']}   errors {sm['errors']}   "
               f"success rate {100 * sm['success_rate']:.1f} %")
    if patching:
        listings = sm.get("listings", 0)
        out.append(f"patched {sm.get('patched', 0) - listings}   "
                   + (f"programs written {sm.get('programs', 0)}   listings for review "
                      f"{listings}   " if listings else "")
                   + f"patch errors {sm.get('patch_errors', 0)}")
    out.append("correlation simulated vs measured (passing entries): "
               + "   ".join(f"{k} {fmt(c.get(k), 5)}" for k in "xyz"))
    return "\n".join(out) + "\n"
