"""ucsio view SOLUTION.json [--controller FILE --frame NAME] [--at FILE] [--plan PLAN.json]
           -o view.html

One self-contained HTML page (no network: three.js is inside it) with a 3D
view of the solution: the tracker's points mapped through the fit, the
robot's points, each residual magnified by a stated factor, excluded points
named, the measured frame and (with --controller and --frame) the simulated
one with their offset Δ, working points coloured by their predicted 95 %
error, a plan's points; and three orthographic SVG projections that print
without script. -o - writes the page to standard output.

Exit 0 written; 2 bad input (nothing written)."""
from __future__ import annotations

import os
import sys


def add_arguments(p) -> None:
    p.add_argument("solution", metavar="SOLUTION.json", help="written by `ucsio solve -o`")
    p.add_argument("--controller", metavar="FILE",
                   help="the controller file that holds the simulated frame (with --frame)")
    p.add_argument("--frame", metavar="NAME", help="the simulated frame in --controller")
    p.add_argument("--at", metavar="FILE",
                   help="working points (CSV of point, x, y, z in the UCS, mm), coloured by "
                        "the solution's predicted 95 %% error")
    p.add_argument("--plan", metavar="PLAN.json",
                   help="`ucsio plan --json`'s output: its planned, suggested and dropped points")
    p.add_argument("-o", "--output", metavar="view.html", required=True,
                   help="the page to write; - for standard output")


def view(solution: str, controller: str | None = None, frame: str | None = None,
         at: str | None = None, plan: str | None = None) -> tuple[dict, str]:
    """(scene, page): what ``run`` writes and ``ucsio.api.view`` returns."""
    from ..errors import UsageError
    from ..picture.inputs import read_scene
    from ..picture.page import page

    if (controller is None) != (frame is None):
        raise UsageError("ucsio view: --controller FILE and --frame NAME go together")
    s = read_scene(solution, controller=controller, frame=frame, at=at, plan=plan)
    return s, page(s)


def run(args) -> int:
    from ..errors import UcsioError
    from ..files import atomic_write_text, write_target
    from ..output import emit_json

    out = args.output
    if out != "-":
        write_target(out)                      # a folder or a device: refused before any work
        folder = os.path.dirname(os.path.abspath(out))
        if not os.path.isdir(folder):
            raise UcsioError(f"-o {out}: folder {folder} does not exist")
    from . import options_for
    s, html = view(**options_for(view, args))
    if out == "-":
        sys.stdout.write(html)
        return 0
    atomic_write_text(out, html)
    if args.json:
        emit_json({"output": out, "points": len(s["points"]), "magnify": s["magnify"]})
    else:
        print(f"wrote {out} ({len(s['points'])} points, residuals ×{s['magnify']:g})",
              file=sys.stderr)
    return 0
