"""The whole job on the example cells shipped with ucsio (a KUKA $config.dat and
an ABB RAPID module, each with a laser-tracker measurement holding one
blunder; a KUKA cell measured where the data live, a SpatialAnalyzer export
and the measurement program's .dat, whose reflector TCP is solved with the
frame; and a FANUC cell, a tracker's point table and the measurement program
MEASURE.LS, its frame set by a generated TP program): solve, diff against the
simulated frame, preview the patch. Nothing
is written unless --out DIR is given: then DIR/<cell>/ holds the cell's inputs
(controller file, measurement CSV), solution.json, the patched copy under
patched/, and replay.sh with every step as the ucsio command to type. The
shipped files are never changed. Exit 1 when a cell fails its gate."""
from __future__ import annotations

import sys

from .. import defaults, vendors
from ..output import emit_json, fmt, paint, paint_diff, table
from .diff import delta_table


def add_arguments(p) -> None:
    p.add_argument("--out", metavar="DIR",
                   help="write each cell's inputs, solution, patched copy and replay.sh into DIR")
    p.add_argument("--tolerance", type=float, default=None, metavar="MM",
                   help="dt_mean below this passes (default 100 mm)")


def run(args) -> int:
    from ..demo import run_demo

    result = run_demo(out=args.out, tolerance=args.tolerance)
    status = 0 if result["ok"] else 1   # a cell over tolerance or rejected: a failed gate
    if args.json:
        emit_json(result)
        return status
    for k, cell in enumerate(result["cells"]):
        if k:
            print()
        print_cell(cell)
    print()
    verdict = "every cell passes" if result["ok"] else "a cell failed its gate"
    print(f"demo: {len(result['cells'])} cells, {verdict}.")
    if result["out"]:
        for cell in result["cells"]:
            program = (cell.get("program") or {}).get("written")
            print(f"wrote {cell['folder']}: inputs, solution.json, "
                  + (f"{cell['patch']['written']}, " if cell["patch"]["written"] else "")
                  + (f"{program}, " if program else "")
                  + "replay.sh (every step by hand)", file=sys.stderr)
    else:
        print("nothing written (ucsio demo --out DIR writes the inputs, the solution and the "
              "patched copies, with the commands to replay every step by hand)")
    return status


def print_cell(cell: dict) -> None:
    s = cell["solve"]
    d = cell["diff"]
    label = f" \"{cell['label']}\"" if cell.get("label") else ""
    rule = "=" * 78
    print(rule)
    print(f"cell {cell['cell']} ({vendors.title(cell['vendor'])}): {cell['story']}")
    print(rule)
    print(f"controller   {cell['controller']}   frame {cell['frame']}{label}")
    tool = cell["tool"]
    tl = f" \"{tool['label']}\"" if tool.get("label") else ""
    solved = s.get("tcp") if isinstance(s.get("tcp"), dict) and s["tcp"].get("solved") else None
    tcp = ", ".join(f"{v:.3f}" for v in tool["tcp"])
    if solved:
        print(f"laser        {cell['measurement']}   robot {cell['robot']}")
        print(f"TCP of {tool['name']}{tl}: nominal {tcp}, solved with the frame")
    elif cell.get("robot"):
        print(f"laser        {cell['measurement']}   robot {cell['robot']}   TCP from "
              f"{tool['name']}{tl}: {tcp}")
    else:
        print(f"measurement  {cell['measurement']}   TCP from {tool['name']}{tl}: {tcp}")
    for w in cell.get("warnings") or ():
        print(f"warning: {w}")
    print()
    print("1. solve (" + ("the TCP with the frame: linear start, Gauss-Newton; leave-one-out "
                          "outlier exclusion)" if solved
                          else "Horn's method, leave-one-out outlier exclusion)"))
    rows = []
    for p in s["points"]:
        loo = p["loo_residual"]
        used = "yes" if p["used"] else f"EXCLUDED ({p.get('excluded_by') or 'auto'})"
        rows.append([p["name"], fmt(p["residual"]), fmt(loo), used])
    print(indent(table(["point", "residual", "leave-one-out", "used"], rows, right={1, 2})))
    threshold = s.get("settings", {}).get("threshold", defaults.THRESHOLD)
    print(f"   {s['n_used']} of {s['n_points']} points used, rms {s['rms']:.3f} mm, "
          f"max {s['max']:.3f} mm (threshold {threshold:g} mm): "
          + (paint("accepted", "pass") if s["accepted"] else paint("REJECTED: measure again", "fail")))
    if solved:
        std = solved["std"]
        print(f"   TCP {solved['x']:.3f}, {solved['y']:.3f}, {solved['z']:.3f} mm "
              f"(std {std['x']:.3f} {std['y']:.3f} {std['z']:.3f}; nominal was "
              + ", ".join(f"{v:.3f}" for v in tool["tcp"]) + ")")
    print()
    print("2. diff: measured - simulated")
    print(indent(delta_table(d["simulated"], d["measured"], cell["vendor"], "delta")))
    print(f"   angle {d['angle']:.4f} deg, dist {d['dist']:.3f} mm, dt_mean {d['dt_mean']:.3f} mm: "
          f"group {d['group']}, {paint('PASS', 'pass') if d['pass'] else paint('FAIL', 'fail')} "
          f"(tolerance {d.get('tolerance', defaults.TOLERANCE):g} mm)")
    print()
    program = cell.get("program")
    if program is not None:         # FANUC: the controller does not load .va files
        print(f"3. write-back: a TP program that sets {program['frame']} (PR[{program['pr']}]: "
              f"unused in {program['pr_from']}), as the controller writes its .LS files")
        lines = program["text"].split("\r\n")
        body = lines[lines.index("/MN") + 1:lines.index("/POS")]
        print(indent("\n".join([f"/PROG  {program['name']}", "/MN", *body, "/END"])))
        print()
        print("4. review: the listing with the measured frame (a copy for the reviewer; the "
              "controller does not load it)")
        print(indent(paint_diff(cell["patch"]["diff"].rstrip("\n"))))
        return
    print("3. patch preview (only the frame's numbers change"
          + (f", and {tool['name']}'s x, y, z)" if solved else ")"))
    print(indent(paint_diff(cell["patch"]["diff"].rstrip("\n"))))


def indent(text: str, pad: str = "   ") -> str:
    return "\n".join(pad + line if line else line for line in text.split("\n"))
