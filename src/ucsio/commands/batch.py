"""Solve and diff many datasets from a TOML manifest ([defaults] and
[[entry]] tables, paths relative to the manifest), with a summary by group.
One entry's failure is reported and counted, never stops the run. Exit 0 when
every entry passed, 1 when any was over tolerance, rejected or failed, 2 for a
bad manifest."""
from __future__ import annotations

import argparse
import os
import sys

from ..errors import UcsioError
from . import add_uncertainty_options


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("manifest", metavar="MANIFEST.toml")
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
    if path is None:
        return
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise UcsioError(f"{option} {path}: folder {folder} does not exist")


def run(args) -> int:
    from ..batch import read_manifest, run_batch, write_csv
    from ..output import emit_json

    if args.uncertainty and args.uncertainty < 2:
        raise UcsioError("--uncertainty needs N >= 2 samples")
    _check_output(args.csv, "--csv")
    _check_output(args.report, "--report")
    manifest = read_manifest(args.manifest)
    if args.patch_dir is not None:
        pd = os.path.abspath(args.patch_dir)
        for e in manifest.entries:
            if os.path.dirname(os.path.abspath(e.controller)) == pd:
                raise UcsioError(f"--patch-dir {args.patch_dir} holds the original controller "
                                 f"file {e.controller}; choose another folder")

    bar = _Bar(sys.stderr) if (sys.stderr.isatty() and not args.no_progress) else None
    try:
        result = run_batch(manifest, uncertainty=args.uncertainty, sigma_laser=args.sigma_laser,
                           sigma_robot=args.sigma_robot, seed=args.seed,
                           patch_dir=args.patch_dir, progress=bar)
    finally:
        if bar is not None:
            bar.close()

    if args.csv:
        try:
            write_csv(result.entries, args.csv)
        except OSError as exc:
            raise UcsioError(f"cannot write {args.csv}: {exc.strerror or exc}") from None
    if args.report:
        from ..report import write_report
        try:
            write_report(result, args.report)
        except OSError as exc:
            raise UcsioError(f"cannot write {args.report}: {exc.strerror or exc}") from None

    if args.json:
        emit_json(result.as_dict())
    else:
        print(render(result), end="")
        for opt, path in (("csv", args.csv), ("report", args.report), ("patched copies", args.patch_dir)):
            if path:
                print(f"written ({opt}): {path}")
    return 0 if result.all_passed else 1


def render(result) -> str:
    from ..output import fmt, table

    rows = []
    for r in result.entries:
        s = r.solution if r.error is None else None
        d = r.delta or {}
        rows.append([r.entry.name, r.status,
                     f"{s.n_used}/{s.n_points}" if s is not None else "-",
                     fmt(r.e), fmt(r.dt_mean), fmt(r.group),
                     fmt(d.get("dx")), fmt(d.get("dy")), fmt(d.get("dz")),
                     fmt(d.get("angle"), 4)])
    out = [table(["entry", "status", "used", "e", "dt_mean", "group", "dx", "dy", "dz", "angle"],
                 rows, right={2, 3, 4, 5, 6, 7, 8, 9})]
    errors = [r for r in result.entries if r.error is not None]
    if errors:
        out.append("")
        out.append("errors:")
        out.extend(f"  {r.entry.name}: {r.error}" for r in errors)
    sm = result.summary
    out.append("")
    grows = []
    for g in sm["groups"]:
        lo, hi = g["range"]
        span = f"{lo:g} <= dt_mean < {hi:g}" if hi is not None else f"dt_mean >= {lo:g}"
        grows.append([g["group"], span, g["count"], f"{g['percent']:.1f}", fmt(g["mean_e"]),
                      fmt(g["std_e"])])
    out.append(table(["group", "mm", "count", "% of total", "mean e", "std e"], grows,
                     right={2, 3, 4, 5}))
    out.append("")
    c = sm["correlation"]
    out.append(f"total {sm['total']}   passed {sm['passed']}   over tolerance "
               f"{sm['over_tolerance']}   rejected {sm['rejected']}   errors {sm['errors']}   "
               f"success rate {100 * sm['success_rate']:.1f} %")
    out.append("correlation simulated vs measured (passing entries): "
               + "   ".join(f"{k} {fmt(c[k], 5)}" for k in "xyz"))
    return "\n".join(out) + "\n"
