"""The whole job on the example cells shipped with ucsio (a KUKA $config.dat and
an ABB RAPID module, each with a laser-tracker measurement holding one
blunder; a KUKA cell measured where the data live, a SpatialAnalyzer export
and the measurement program's .dat, whose reflector TCP is solved with the
frame; a FANUC cell, a tracker's point table and the measurement program
MEASURE.LS, its frame set by a generated TP program; and a Yaskawa cell, a
point table and the measurement job MEASURE.JBI with TOOL.CND, its frame set
by a generated SETUF job or a patch of UFRAME.CND's BUSER; a Stäubli cell,
whose patch is refused for the vendor's stated reason and reported as not
run; and a Universal Robots cell, a plane feature patched): solve, diff
against the simulated frame (and the taught points of the cell's production
program), preview the patch. A step the cell's vendor cannot do yet is said
so and not run; a cell whose robot side ucsio cannot read yet is listed as
not run, with the reason, and does not fail the demo. Nothing
is written unless --out DIR is given: then DIR/<cell>/ holds the cell's inputs
(controller file, measurement CSV), solution.json, the patched copy under
patched/, and replay.sh with every step as the ucsio command to type. The
shipped files are never changed. Exit 1 when a cell fails its gate."""
from __future__ import annotations

import sys
from pathlib import Path

from .. import defaults, vendors
from ..output import emit_json, fmt, paint, paint_diff, table
from .diff import _points_text as points_text, delta_table


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
    every = sorted(result["cells"] + result["not_run"], key=lambda c: c["cell"])
    for k, cell in enumerate(every):
        if k:
            print()
        print_cell(cell) if "solve" in cell else print_not_run(cell)
    print()
    print(summary(result))
    if result["out"]:
        for cell in every:
            program = (cell.get("program") or {}).get("written")
            patched = (cell.get("patch") or {}).get("written")
            measure = (cell.get("measurement_program") or {}).get("written")
            print(f"wrote {cell['folder']}: inputs, "
                  + ("solution.json, " if "solve" in cell else "")
                  + (f"{patched}, " if patched else "")
                  + (f"{program}, " if program else "")
                  + (f"{measure}, " if measure else "")
                  + "replay.sh (every step by hand)", file=sys.stderr)
    else:
        print("nothing written (ucsio demo --out DIR writes the inputs, the solution and the "
              "patched copies, with the commands to replay every step by hand)")
    return status


def summary(result: dict) -> str:
    """The last line: how many cells, whether they pass, which could not run."""
    ran, not_run = result["cells"], result["not_run"]
    verdict = "every cell passes" if result["ok"] else "a cell failed its gate"
    if not not_run:
        return f"demo: {len(ran)} cells, {verdict}."
    names = ", ".join(c["cell"] for c in not_run)
    return (f"demo: {len(ran)} of {len(ran) + len(not_run)} cells run, {verdict}; not run yet: "
            f"{names} (what this ucsio cannot read yet is said above).")


def print_header(cell: dict) -> None:
    label = f" \"{cell['label']}\"" if cell.get("label") else ""
    rule = "=" * 78
    print(rule)
    print(f"cell {cell['cell']} ({vendors.title(cell['vendor'])}): {cell['story']}")
    print(rule)
    print(f"controller   {cell['controller']}   frame {cell['frame']}{label}")


def tool_words(cell: dict) -> str:
    """UT3 "SMR" (R05_yaskawa/TOOL.CND): the tool, and its file where not the controller."""
    tool = cell["tool"]
    tl = f" \"{tool['label']}\"" if tool.get("label") else ""
    where = tool.get("file")
    return tool["name"] + tl + (f" ({where})" if where and where != cell["controller"] else "")


def print_not_run(cell: dict) -> None:
    """A cell whose robot side this ucsio cannot read yet: what it holds, and why."""
    print_header(cell)
    tcp = ", ".join(f"{v:.3f}" for v in cell["tool"]["tcp"])
    print(f"laser        {cell['measurement']}   robot {cell['robot']}   TCP from "
          f"{tool_words(cell)}: {tcp}")
    print()
    print(f"1. solve: not run: {cell['why']}")
    print("   the diff, the taught points, the write-back and the patch preview need the "
          "solution: not run")


def print_cell(cell: dict) -> None:
    s = cell["solve"]
    d = cell["diff"]
    print_header(cell)
    tool = cell["tool"]
    solved = s.get("tcp") if isinstance(s.get("tcp"), dict) and s["tcp"].get("solved") else None
    tcp = ", ".join(f"{v:.3f}" for v in tool["tcp"])
    if solved:
        print(f"laser        {cell['measurement']}   robot {cell['robot']}")
        print(f"TCP of {tool_words(cell)}: nominal {tcp}, solved with the frame")
    elif cell.get("robot"):
        print(f"laser        {cell['measurement']}   robot {cell['robot']}   TCP from "
              f"{tool_words(cell)}: {tcp}")
    else:
        print(f"measurement  {cell['measurement']}   TCP from {tool_words(cell)}: {tcp}")
    for w in cell.get("warnings") or ():
        print(f"warning: {w}")
    print()
    print_measure(cell)
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
    skipped = {s["step"]: s["why"] for s in cell.get("skipped") or ()}
    if cell.get("points") is not None:
        print(indent(points_text({**cell["points"], "name": cell["frame"], "vendor": cell["vendor"]})))
    elif "points" in skipped:
        print(f"   taught points: not run: {skipped['points']}")
    print()
    step = 3
    program = cell.get("program")
    if program is not None or "program" in skipped:
        print_program(program, skipped.get("program"))
        print()
        step = 4
    patch = cell["patch"]
    if patch is None:                   # the vendor refuses to patch its files: its reason
        print(f"{step}. patch: not run: {skipped.get('patch')}")
        return
    if patch.get("review_copy"):        # FANUC: the controller does not load .va files
        print(f"{step}. review: the listing with the measured frame (a copy for the reviewer; "
              "the controller does not load it)")
    else:
        print(f"{step}. patch preview (only the frame's numbers change"
              + (f", and {tool['name']}'s x, y, z)" if solved else ")"))
    print(indent(paint_diff(patch["diff"].rstrip("\n"))))
    for w in patch.get("warnings") or ():
        print(indent(f"warning: {w}"))


def print_measure(cell: dict) -> None:
    """Step 0: the measurement program generated from the cell's laser
    points (before the data existed), or why there is none."""
    m = cell.get("measurement_program")
    why = next((s["why"] for s in cell.get("skipped") or () if s["step"] == "measure"), None)
    if m is None and why is None:
        return
    if m is None:
        print(f"0. measurement program: not run: {why}")
    else:
        spread = f", turned {m['spread']:g} deg apart for the TCP" if m.get("spread") else ""
        print(f"0. measurement program: {m['file']} moves {m['tool']} to the "
              f"{len(m['points'])} points of {Path(cell['measurement']).name} in "
              f"{m['frame']}{spread} (ucsio program --measure; demo --out writes it)")
    print()


def print_program(program: dict | None, why: str | None) -> None:
    """Step 3: the generated program that sets the frame, or why there is none."""
    if program is None:
        print(f"3. write-back by a generated program: not run: {why}")
        return
    register = ""
    if program.get("pr") is not None:       # FANUC: the position register it fills
        register = f" (PR[{program['pr']}]: unused in {program['pr_from']})"
    elif program.get("p") is not None:     # Yaskawa: the P variables it loads
        register = (" (" + " ".join(f"P{n:03d}" for n in program["p"])
                    + f": unused in {program['p_from']})")
    print(f"3. write-back: {program['file']}, a program that sets {program['frame']}"
          f"{register}, as the controller writes its programs")
    print(indent(program["text"].replace("\r\n", "\n").rstrip("\n")))


def indent(text: str, pad: str = "   ") -> str:
    return "\n".join(pad + line if line else line for line in text.split("\n"))
