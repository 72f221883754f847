"""Example cells shipped inside the package, run end to end by ``ucsio demo``.

Each cell is a controller file with a simulated frame, a measurement file of
laser/robot point pairs (synthetic: a known true frame, 0.02 mm noise and one
blunder; fixtures/demo/make_demo.py regenerates them) and the tool that
carried the reflector. The third cell starts where a measurement really
lives: a SpatialAnalyzer export of the laser points and the KUKA measurement
program's data list (E6POS with FDAT), and solves the reflector's TCP with
the frame, because the adapter was never measured; it patches both the base
and the tool's x, y, z. The demo solves, diffs the simulated frame against the
measured one, and previews the patch as a unified diff. ``out`` writes, per
cell, the inputs (controller file, measurement), the solution and the patched
copy (never the shipped files), with ``replay.sh``: the same steps as ucsio
commands, to run by hand; and into ``out/measure`` each cell's measurement
program, as ``program --measure`` makes it from the cell's laser points
(step 0: the program that would have moved the reflector).

A step runs where the cell's vendor has the capability it needs (its reader
of robot positions, of taught points, its program writer) and is otherwise
reported as not run, with the words ``vendors.missing`` gives: the fifth
cell (Yaskawa) turns each step on by itself when its vendor gains it. A
vendor that refuses to patch its files for a stated reason (its
``patch_refusal``: the sixth cell's Stäubli, whose rotation order is not
proved) has the patch step reported as not run with that reason, no
patched copy, and replay.sh's patch commands as comments; the seventh cell
(Universal Robots) patches a plane feature's points. A cell whose robot
side cannot be read yet is not solved: it is listed in ``not_run`` (its
inputs and replay.sh are still written).
"""
from __future__ import annotations

import os
from contextlib import ExitStack
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from .. import vendors
from ..errors import UcsioError


@dataclass(frozen=True)
class Cell:
    name: str
    controller: str      # path inside ucsio/demo/data
    frame: str
    measurement: str
    tool: str            # the tool carrying the reflector (its x, y, z is the TCP)
    story: str
    robot: str | None = None     # the robot side's own file: measurement is then the laser's,
                                 # and the TCP is solved with the frame (and patched into tool)
    tcp_solve: bool = True       # with robot: False takes the tool's TCP as it is
    extra: tuple[str, ...] = ()  # other files of the backup (FANUC: POSREG.VA, a program)
    # the backup's file ``ucsio program`` takes free registers or variables from:
    # (its option, path): FANUC's ("posreg", POSREG.VA), Yaskawa's ("var", VAR.DAT)
    program_input: tuple[str, str] | None = None
    config: str | None = None    # the file that holds the tool, where not the controller file
    points: bool = False         # diff with the positions the backup's programs teach in frame
    program_file: str | None = None  # the program that sets the frame, where the vendor has one
    comment: bool = False        # replay.sh: ucsio program keeps the frame's comment (FANUC)
    # the measurement program ``program --measure`` writes from the cell's laser points (its
    # file, which names the program), and the spread of orientations where the TCP is solved
    measure_file: str | None = None
    measure_spread: float | None = None

    @property
    def vendor(self) -> str:
        """The controller file's vendor, by its name (the registry's suffixes)."""
        return vendors.by_suffix(self.controller)


CELLS = (
    Cell("R01", "R01_kuka/$config.dat", "weld_fixture_A", "R01_kuka/base3_points.csv",
         "SMR_reflector",
         "KUKA KR 210 at a welding fixture: BASE_DATA[3] as simulated vs measured",
         measure_file="MEAS_BASE3.src"),
    Cell("R02", "R02_abb/CellR02.mod", "wobjTable", "R02_abb/table_points.csv",
         "tReflector",
         "ABB IRB 4600 at a press table: wobjTable's user frame as simulated vs measured",
         measure_file="MEAS_TABLE.mod"),
    Cell("R03", "R03_kuka/$config.dat", "jig_B", "R03_kuka/jig_points.txt",
         "SMR_adapter",
         "KUKA KR 120 at a fixing jig, from a SpatialAnalyzer export and the measurement "
         "program's MEASURE.dat: BASE_DATA[1] and the never-measured reflector adapter's TCP",
         robot="R03_kuka/MEASURE.dat", measure_file="MEAS_JIG.src", measure_spread=30.0),
    Cell("R04", "R04_fanuc/SYSFRAME.VA", "UF1", "R04_fanuc/pallet_points.txt", "UT2",
         "FANUC palletising cell, from the tracker's point table and the measurement program "
         "MEASURE.LS: UF1 'PALLET' as simulated vs measured, set by a generated TP program",
         robot="R04_fanuc/MEASURE.LS", tcp_solve=False,
         extra=("R04_fanuc/POSREG.VA", "R04_fanuc/PALLET.LS"),
         program_input=("posreg", "R04_fanuc/POSREG.VA"),
         points=True, program_file="SET_UF1.LS", comment=True, measure_file="MEAS_UF1.LS"),
    Cell("R05", "R05_yaskawa/UFRAME.CND", "UF2", "R05_yaskawa/fixture_points.txt", "UT3",
         "Yaskawa YRC1000 at an assembly fixture, from the tracker's point table and the "
         "measurement job MEASURE.JBI: UF2 'FIXTURE' as simulated vs measured, set by a "
         "generated SETUF job or by patching UFRAME.CND's BUSER",
         robot="R05_yaskawa/MEASURE.JBI", tcp_solve=False, config="R05_yaskawa/TOOL.CND",
         extra=("R05_yaskawa/PLACE.JBI", "R05_yaskawa/VAR.DAT"),
         program_input=("var", "R05_yaskawa/VAR.DAT"), points=True, program_file="SETUF2.JBI",
         measure_file="MEAS_UF2.JBI"),
    Cell("R06", "R06_staubli/CellR06.dtx", "fBattery", "R06_staubli/battery_points.csv",
         "tSMR",
         "Stäubli TX2-90 on a CS9 at an EV battery line: the tray frame fBattery as simulated "
         "vs measured with the reflector tool tSMR of the same .dtx"),
    Cell("R07", "R07_ur/cell.installation", "Fixture", "R07_ur/fixture_points.csv", "SMR",
         "Universal Robots UR10e in final assembly: the plane feature Fixture as taught vs "
         "measured with the installation's TCP SMR; patch writes the plane's points"),
)


def data_root():
    return resources.files(__name__).joinpath("data")


def run_cell(cell: Cell, root: Path, out: str | os.PathLike | None = None,
             tolerance: float | None = None) -> dict[str, Any]:
    """One cell end to end; a cell whose robot side cannot be read yet is
    returned unsolved, with ``why`` (``run_demo`` lists it in ``not_run``)."""
    from ..parsing.controller import load
    from ..review.diff import DEFAULT_TOLERANCE
    from ..geometry.frames import tool_tcp
    from ..review.save import save
    from ..review.compare import diff_frame

    tol = DEFAULT_TOLERANCE if tolerance is None else tolerance
    cf = load(root / cell.controller)
    tool = (load(root / cell.config) if cell.config else cf).frame(cell.tool)
    tcp = tool_tcp(tool)
    sim = cf.frame(cell.frame)
    folder = None if out is None else Path(out) / Path(cell.controller).parent.name
    head = {"cell": cell.name, "vendor": cell.vendor, "story": cell.story,
            "controller": cell.controller, "measurement": cell.measurement,
            "frame": sim.name, "label": sim.label,
            "tool": {"name": tool.name, "label": tool.label, "tcp": list(tcp),
                     "file": cell.config or cell.controller},
            "robot": cell.robot}
    why = robot_side_missing(cell, root)
    if why is not None:
        if folder is not None:
            _mkdir(folder)
            write_inputs(cell, root, folder, None, label=sim.label,
                         skipped=[{"step": "solve", "why": why}])
        return {**head, "step": "solve", "why": why,
                "folder": str(folder) if folder is not None else None}
    warnings: list[str] = []
    if cell.robot is None:
        from ..readers.measurement import read_measurement
        from ..method.solve import solve
        sol = solve(read_measurement(root / cell.measurement), tcp)
    else:
        sol, warnings = _solve_where_it_lives(cell, root, None if cell.tcp_solve else tcp)
    d = diff_frame(cf, cell.frame, sol.pose, tol)
    skipped: list[dict[str, str]] = []
    points = _points(cell, root, cf, sim, sol, skipped) if cell.points else None
    result = _patch(cell, cf, sol, skipped)
    written = None
    if folder is not None:
        _mkdir(folder if result is None else folder / "patched")
    prog = _program(cell, root, sim, sol, folder, skipped) if cell.program_file else None
    measure = (_measure(cell, root, None if out is None else Path(out) / MEASURE_FOLDER,
                        skipped) if cell.measure_file else None)
    if folder is not None:
        write_inputs(cell, root, folder, sol, label=sim.label, skipped=skipped)
        if sol.accepted and result is not None:
            written = save(result, folder / "patched" / Path(cell.controller).name)
    extra = {} if prog is None else {"program": prog}
    if measure is not None:
        extra["measurement_program"] = measure
    if points is not None:
        extra["points"] = points
    return {**extra, **head,
        "warnings": warnings,
        "solve": sol.as_dict(),
        "diff": d,
        "patch": None if result is None else _patch_view(cell, result, written),
        "skipped": skipped,
        "folder": str(folder) if folder is not None else None,
        "ok": bool(sol.accepted and d["pass"]),
    }


def _patch(cell: Cell, cf, sol, skipped: list):
    """The patch of the measured frame (and the solved TCP's, where solved
    with it), or None where the cell's vendor refuses to patch its files for
    a stated reason (``patch_refusal``), or this file is read but not
    written here (``Document.write_refusal``: a gzip stream this Python's
    zlib does not reproduce): the step is then reported as not run, with
    that reason, and the demo still runs everywhere."""
    from ..review.patch import patch_frame
    refusal = vendors.get(cell.vendor).patch_refusal or cf.document.write_refusal
    if refusal is not None:
        skipped.append({"step": "patch", "why": refusal})
        return None
    result = patch_frame(cf, cell.frame, sol.pose, measured=True, check_siblings=False)
    if cell.robot is not None and cell.tcp_solve:
        result = _with_tcp(cf, result, cell.tool, sol.tcp)
    return result


def _patch_view(cell: Cell, result, written) -> dict[str, Any]:
    """The patch as the demo shows it: its diff named as the cell's files are."""
    vendor = vendors.get(cell.vendor)
    path = result.path.lstrip("/")
    return {"changes": [c.as_dict() for c in result.changes],
            "diff": result.diff.replace(f"a/{path}", f"a/{cell.controller}")
                               .replace(f"b/{path}", f"b/{cell.controller}"),
            "warnings": [w for w in result.warnings if w != vendor.review_copy_warning],
            "review_copy": vendor.review_copy_warning is not None,
            "written": str(written) if written else None}


def robot_side_missing(cell: Cell, root: Path) -> str | None:
    """Why the cell's robot file cannot be read yet, or None: its vendor has
    no reader of robot positions for files of its kind (the capability, not
    the vendor's name, decides), and what ucsio says of such a file."""
    if cell.robot is None:
        return None
    vendor = vendors.get(cell.vendor)
    suffix = Path(cell.robot).suffix.lower()
    if vendor.robot_positions is not None and suffix in vendor.robot_suffixes:
        return None
    from ..parsing.foreign import other_vendor
    why = vendors.missing(cell.vendor, "reader of robot positions")
    name = Path(cell.robot).name
    head = (root / cell.robot).read_bytes()[:256].decode("latin-1")
    refusal = other_vendor(name, head)
    return f"{why}: {name} is {refusal}" if refusal else f"{why} ({name})"


def _solve_where_it_lives(cell: Cell, root: Path, tcp=None):
    """Laser export + measurement program; the TCP solved with the frame
    where ``tcp`` is None (the third cell), else that TCP (the FANUC cell)."""
    from ..readers.laser import read_laser
    from ..readers.pairing import pair
    from ..readers.robot import read_robot

    meas, warnings = pair(read_laser(root / cell.measurement),
                          read_robot(root / cell.robot,
                                     config=str(root / (cell.config or cell.controller))))
    if tcp is not None:
        from ..method.solve import solve
        return solve(meas, tcp), warnings
    from ..method.tcp_solve import solve_joint
    return solve_joint(meas), warnings


def _points(cell: Cell, root: Path, cf, sim, sol, skipped: list) -> dict | None:
    """diff --points: how far the positions the backup's programs teach in
    the frame move, where the vendor reads taught points."""
    if vendors.get(cell.vendor).taught_points is None:
        skipped.append({"step": "points", "why": vendors.missing(cell.vendor,
                                                                 "reader of taught points")})
        return None
    from ..taught import points_moved
    found = points_moved(cf, sim, sol.pose, solution=sol.as_dict())
    for row in found["points"] + [found.get("worst") or {}]:
        if "file" in row:       # named as the cell's files are, not where the package lies
            row["file"] = Path(os.path.relpath(row["file"], root)).as_posix()
    return found


def _program(cell: Cell, root: Path, sim, sol, folder: Path | None, skipped: list):
    """The program that sets the measured frame, as ``ucsio program`` writes
    it (replay.sh's step 3), where the cell's vendor has a program writer:
    into the cell's folder where one is written and the solution accepted,
    else only made, so that the demo writes nothing. Its file of the backup
    (``program_input``: FANUC's POSREG.VA, Yaskawa's VAR.DAT) says which
    register or variables are free; FANUC keeps the frame's comment."""
    vendor = vendors.get(cell.vendor)
    if vendor.frame_program is None:
        skipped.append({"step": "program", "why": vendors.missing(cell.vendor, "program writer")
                        + f": {cell.program_file} is not generated"})
        return None
    options: dict[str, Any] = {}
    if cell.program_input is not None:
        option, path = cell.program_input
        options[option] = str(root / path)
    if cell.comment and sim.label:
        options["comment"] = sim.label
    target = folder / cell.program_file if folder is not None and sol.accepted else None
    made = vendor.frame_program(sol.pose, cell.frame, tcp=None, source="solution.json",
                                output=str(target or cell.program_file), **options)
    if target is not None:
        from ..files import atomic_write, write_target
        made.written, _ = atomic_write(write_target(str(target)), made.data)
    info = made.as_dict()
    prog = {"file": cell.program_file, "name": info["name"], "frame": info["frame"],
            "text": info["text"], "written": str(target) if target is not None else None}
    for key in ("pr", "p"):         # FANUC's register, Yaskawa's P variables
        if info.get(key) is not None:
            found = info.get(key + "_from")
            prog[key] = info[key]
            prog[key + "_from"] = Path(found).name if found and not found.startswith("--") \
                else found
    return prog


#: where ``demo --out`` writes the measurement programs: beside the cells' folders, not in
#: them, for each cell's folder is its backup, and a program there teaches positions in the
#: frame that ``diff --points`` would count among the backup's
MEASURE_FOLDER = "measure"


def _measure(cell: Cell, root: Path, folder: Path | None, skipped: list):
    """The measurement program that moved the reflector, as ``program
    --measure`` writes it from the cell's laser points (the plan it would
    have been), where the cell's vendor has a writer: into ``folder`` where
    one is given (the demo's own file: written anew each run), else only
    made."""
    vendor = vendors.get(cell.vendor)
    if vendor.measurement_program is None:
        skipped.append({"step": "measure", "why": vendors.missing(
            cell.vendor, "measurement program writer") + f": {cell.measure_file} is not "
            "generated"})
        return None
    from ..programs import measure
    made = measure.make(root / cell.measurement, root / cell.controller, cell.frame,
                        tool=_measure_tool(cell, root), spread=cell.measure_spread,
                        output=cell.measure_file)
    written = None
    if folder is not None:
        _mkdir(folder)
        for name in measure.files_of(made, cell.measure_file):
            (folder / name).unlink(missing_ok=True)     # this run's own: a rerun makes it anew
        written = measure.save(made, str(folder / cell.measure_file))
    info = made.as_dict()
    side = dict(info["read_back"])      # named as the cell's files are, not where the package lies
    side["config"] = [Path(os.path.relpath(f, root)).as_posix() for f in side["config"]]
    if "tool" in side:
        file, _, name = side["tool"].rpartition(":")
        side["tool"] = f"{Path(os.path.relpath(file, root)).as_posix()}:{name}"
    side.pop("solve")
    return {"file": cell.measure_file, "name": info["name"], "frame": info["frame"],
            "tool": info["tool"], "points": info["points"], "spread": cell.measure_spread,
            "read_back": side, "text": info["text"], "written": written}


def _measure_tool(cell: Cell, root: Path) -> str:
    """The reflector's tool as --tool names it: FILE:NAME where the tool is
    in another file than the controller's."""
    return f"{root / cell.config}:{cell.tool}" if cell.config else cell.tool


def _with_tcp(cf, result, tool: str, tcp):
    """The frame's patch and the solved TCP's, as one patch of the file: the
    TCP goes into the frame-patched text, and the result replaces the
    original's bytes (what ``save`` checks against the file on disk)."""
    from ..parsing.controller import parse
    from ..parsing.document import Document
    from ..review.patch import patch_tcp

    again = parse(Document(result.new_bytes, cf.path))
    tool_patch = patch_tcp(again, tool, tcp, check_siblings=False)
    return result.with_changes(new_bytes=tool_patch.new_bytes,
                               changes=result.changes + tool_patch.changes)


def _mkdir(folder: Path) -> None:
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UcsioError(f"--out: cannot make the folder: {exc.strerror or exc}",
                         file=str(folder)) from None


def replay_script(cell: Cell, label: str | None = None, skipped=()) -> str:
    """The demo's steps for one cell as the commands a user types (``label``:
    the frame's, which the FANUC program keeps as its comment). A step in
    ``skipped`` (``{"step", "why"}``: what this ucsio cannot do yet) is
    written as a comment saying why, so that the script runs what can run."""
    ctl = Path(cell.controller).name
    meas = Path(cell.measurement).name
    q = _sh
    if cell.robot is not None and not cell.tcp_solve:
        return _replay_with_tool(cell, label, {s["step"]: s["why"] for s in skipped})
    if cell.robot is not None:
        robot = Path(cell.robot).name
        return "\n".join([
            "#!/bin/sh",
            f"# ucsio demo, cell {cell.name}: {cell.story}",
            "# Every step of the demo by hand, in this folder. The laser points come from a",
            f"# SpatialAnalyzer export, the robot's from the measurement program {robot};",
            f"# the TCP of {cell.tool} is solved with the frame.",
            "set -e",
            'cd "$(dirname "$0")"',
            *_measure_lines(cell, skipped),
            "# 1. solve: the TCP with the frame (linear start, Gauss-Newton), leave-one-out exclusion",
            f"ucsio solve --laser {q(meas)} --robot {q(robot)} --config {q(ctl)} --tcp solve "
            "-o solution.json",
            "# 2. diff: the simulated frame against the measured one (exit 1 over tolerance)",
            f"ucsio diff {q(ctl)} --frame {q(cell.frame)} --measured solution.json || true",
            "# 3. patch: preview the base and the tool's TCP, then write a patched copy",
            f"ucsio patch {q(ctl)} --frame {q(cell.frame)} --measured solution.json",
            f"ucsio patch {q(ctl)} --frame {q(cell.tool)} --measured solution.json",
            f"ucsio patch {q(ctl)} --frame {q(cell.frame)} --measured solution.json "
            f"-o {q('patched/' + ctl)}",
            f"ucsio patch {q('patched/' + ctl)} --frame {q(cell.tool)} --measured solution.json "
            "--in-place",
            "# 4. review: every frame of the two files",
            f"ucsio diff {q(ctl)} {q('patched/' + ctl)}",
            ""])
    return "\n".join([
        "#!/bin/sh",
        f"# ucsio demo, cell {cell.name}: {cell.story}",
        "# Every step of the demo by hand, in this folder. The TCP is the reflector",
        f"# tool {cell.tool} in the controller file.",
        "set -e",
        'cd "$(dirname "$0")"',
        *_measure_lines(cell, skipped),
        "# 1. solve: Horn's method, leave-one-out outlier exclusion",
        f"ucsio solve {q(meas)} --tool {q(ctl + ':' + cell.tool)} -o solution.json",
        "# 2. diff: the simulated frame against the measured one (exit 1 over tolerance)",
        f"ucsio diff {q(ctl)} --frame {q(cell.frame)} --measured solution.json || true",
        *_patch_lines(cell, next((s["why"] for s in skipped if s["step"] == "patch"), None)),
        ""])


def _patch_lines(cell: Cell, refused: str | None) -> list[str]:
    """replay.sh's patch and review steps; commented out, with the vendor's
    reason, where it refuses to patch its files."""
    ctl = _sh(Path(cell.controller).name)
    patched = _sh("patched/" + Path(cell.controller).name)
    patch = f"ucsio patch {ctl} --frame {_sh(cell.frame)} --measured solution.json"
    commands = [patch, f"{patch} -o {patched}", f"ucsio diff {ctl} {patched}"]
    if refused is not None:
        return [f"# 3. patch: not run ({refused}):"] + [f"#   {c}" for c in commands]
    return ["# 3. patch: preview, then write a patched copy (the input stays as it is)",
            *commands[:2], "# 4. review: every frame of the two files", commands[2]]


def _replay_with_tool(cell: Cell, label: str | None, skipped: dict[str, str]) -> str:
    """replay.sh of a cell measured where it lives with a tool of the
    controller (FANUC, Yaskawa): solve, diff with the taught points, the
    program that sets the frame, the patched copy. A step the cell's vendor
    cannot do yet is a comment; with the solve, every step after it."""
    ctl = Path(cell.controller).name
    cfg = Path(cell.config or cell.controller).name
    meas, robot = Path(cell.measurement).name, Path(cell.robot or "").name
    q = _sh
    no_solve = skipped.get("solve")

    def step(command: str, why: str | None = None) -> str:
        if no_solve:                # said once above: every step needs the solution
            return f"#   {command}"
        return command if why is None else f"# not run yet ({why}):\n#   {command}"

    review = vendors.get(cell.vendor).review_copy_warning is not None
    lines = [
        "#!/bin/sh",
        f"# ucsio demo, cell {cell.name}: {cell.story}",
        "# Every step of the demo by hand, in this folder. The laser points come from the",
        f"# tracker's point table, the robot's from the measurement program {robot} (each",
        f"# position taught with the reflector tool {cell.tool} of {cfg}).",
        "set -e",
        'cd "$(dirname "$0")"']
    lines += _measure_lines(cell, [{"step": k, "why": v} for k, v in skipped.items()])
    if no_solve:
        lines += [f"# Not run yet: {no_solve}.",
                  "# Every step needs the solution: the commands as they will run, commented out."]
    lines += [
        "# 1. solve: Horn's method, leave-one-out outlier exclusion",
        step(f"ucsio solve --laser {q(meas)} --robot {q(robot)} --config {q(cfg)} "
             f"--tool {q(cfg + ':' + cell.tool)} -o solution.json"),
        "# 2. diff: the simulated frame against the measured one"
        + (", and the taught points it moves" if cell.points else "")]
    diff = f"ucsio diff {q(ctl)} --frame {q(cell.frame)} --measured solution.json"
    if cell.points and "points" in skipped and not no_solve:
        lines += [step(diff + " || true"), step(diff + " --points || true", skipped["points"])]
    else:
        lines.append(step(diff + (" --points" if cell.points else "") + " || true"))
    if cell.program_file:
        program = f"ucsio program solution.json --frame {q(cell.frame)} "
        if cell.program_input:  # the backup's file that says what is free
            option, path = cell.program_input
            program += f"--{option} {q(Path(path).name)} "
        if cell.comment and label:
            program += f"--comment {q(label)} "
        lines += [f"# 3. write-back: a program that sets {cell.frame} on the controller",
                  step(program + f"-o {q(cell.program_file)}", skipped.get("program")),
                  step(f"ucsio frames {q(cell.program_file)}", skipped.get("program"))]
    patch = f"ucsio patch {q(ctl)} --frame {q(cell.frame)} --measured solution.json"
    if review:
        lines += ["# 4. review: a copy of the file with the measured frame, against the "
                  "original (the controller does not load it)"]
    else:
        lines += ["# 4. patch: preview, then write a patched copy (the input stays as it is)",
                  step(patch)]
    lines += [step(f"{patch} -o {q('patched/' + ctl)}"),
              step(f"ucsio diff {q(ctl)} {q('patched/' + ctl)} || true"), ""]
    return "\n".join(lines)


def _measure_lines(cell: Cell, skipped=()) -> list[str]:
    """replay.sh's step 0: the measurement program, before the data existed
    (a comment saying why where the cell's vendor has no writer yet)."""
    if not cell.measure_file:
        return []
    q = _sh
    ctl, meas = Path(cell.controller).name, Path(cell.measurement).name
    tool = f"{Path(cell.config).name}:{cell.tool}" if cell.config else cell.tool
    spread = f" --spread {cell.measure_spread:g}" if cell.measure_spread else ""
    command = (f"ucsio program --measure {q(meas)} {q(ctl)} --frame {q(cell.frame)} "
               f"--tool {q(tool)}{spread} -o ../{MEASURE_FOLDER}/{q(cell.measure_file)}")
    stem = Path(cell.measure_file).stem
    lines = ["# 0. before the measurement: the program that moves the reflector to each point,",
             f"#    in ../{MEASURE_FOLDER} (not in this backup, where diff --points would count "
             "its positions;",
             "#    ucsio never writes over a file: the demo's copy is removed first)"]
    why = next((x["why"] for x in skipped if x["step"] == "measure"), None)
    if why is not None:
        return lines + [f"# not run yet ({why}):", f"#   {command}"]
    return lines + [f"mkdir -p ../{MEASURE_FOLDER}", f"rm -f ../{MEASURE_FOLDER}/{q(stem)}.*",
                    command]


def _sh(word: str) -> str:
    import shlex
    return shlex.quote(word)


def write_inputs(cell: Cell, root: Path, folder: Path, sol, label: str | None = None,
                 skipped=()) -> None:
    """The cell's inputs as shipped, the solution (as ``solve -o`` writes it;
    none where the cell was not solved) and replay.sh, so every step can be
    replayed by hand."""
    from ..files import atomic_write, atomic_write_text
    for rel in (cell.controller, cell.config, cell.measurement, cell.robot, *cell.extra):
        if rel is not None:
            atomic_write(folder / Path(rel).name, (root / rel).read_bytes())
    if sol is not None:
        from ..method.solution import solution_text
        atomic_write_text(folder / "solution.json", solution_text(sol.as_dict()))
    atomic_write_text(folder / "replay.sh", replay_script(cell, label, skipped))
    try:
        os.chmod(folder / "replay.sh", 0o755)
    except OSError:
        pass


def run_demo(out: str | os.PathLike | None = None,
             tolerance: float | None = None) -> dict[str, Any]:
    """Every shipped cell end to end; ``out``: also write patched copies there.
    ``not_run``: the cells whose robot side this ucsio cannot read yet."""
    with ExitStack() as stack:
        root = stack.enter_context(resources.as_file(data_root()))
        results = [run_cell(c, Path(root), out, tolerance) for c in CELLS]
    cells = [r for r in results if "solve" in r]
    return {"cells": cells, "not_run": [r for r in results if "solve" not in r],
            "ok": all(c["ok"] for c in cells), "out": str(out) if out is not None else None}
