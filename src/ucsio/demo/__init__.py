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
commands, to run by hand.
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
    posreg: str | None = None    # FANUC: the listing program() picks an unused register from

    @property
    def vendor(self) -> str:
        """The controller file's vendor, by its name (the registry's suffixes)."""
        return vendors.by_suffix(self.controller)

    @property
    def set_by_program(self) -> bool:
        """Whether the vendor has a program that sets the measured frame
        (FANUC: a TP program; its controller loads no file ucsio patches)."""
        return vendors.get(self.vendor).program_writer is not None


CELLS = (
    Cell("R01", "R01_kuka/$config.dat", "weld_fixture_A", "R01_kuka/base3_points.csv",
         "SMR_reflector",
         "KUKA KR 210 at a welding fixture: BASE_DATA[3] as simulated vs measured"),
    Cell("R02", "R02_abb/CellR02.mod", "wobjTable", "R02_abb/table_points.csv",
         "tReflector",
         "ABB IRB 4600 at a press table: wobjTable's user frame as simulated vs measured"),
    Cell("R03", "R03_kuka/$config.dat", "jig_B", "R03_kuka/jig_points.txt",
         "SMR_adapter",
         "KUKA KR 120 at a fixing jig, from a SpatialAnalyzer export and the measurement "
         "program's MEASURE.dat: BASE_DATA[1] and the never-measured reflector adapter's TCP",
         robot="R03_kuka/MEASURE.dat"),
    Cell("R04", "R04_fanuc/SYSFRAME.VA", "UF1", "R04_fanuc/pallet_points.txt", "UT2",
         "FANUC palletising cell, from the tracker's point table and the measurement program "
         "MEASURE.LS: UF1 'PALLET' as simulated vs measured, set by a generated TP program",
         robot="R04_fanuc/MEASURE.LS", tcp_solve=False,
         extra=("R04_fanuc/POSREG.VA", "R04_fanuc/PALLET.LS"), posreg="R04_fanuc/POSREG.VA"),
)


def data_root():
    return resources.files(__name__).joinpath("data")


def run_cell(cell: Cell, root: Path, out: str | os.PathLike | None = None,
             tolerance: float | None = None) -> dict[str, Any]:
    from ..parsing.controller import load
    from ..review.diff import DEFAULT_TOLERANCE
    from ..readers.measurement import read_measurement
    from ..geometry.frames import tool_tcp
    from ..review.patch import patch_frame
    from ..review.save import save
    from ..review.compare import diff_frame
    from ..method.solve import solve

    tol = DEFAULT_TOLERANCE if tolerance is None else tolerance
    controller = root / cell.controller
    cf = load(controller)
    tool = cf.frame(cell.tool)
    tcp = tool_tcp(tool)
    warnings: list[str] = []
    if cell.robot is None:
        sol = solve(read_measurement(root / cell.measurement), tcp)
    else:
        sol, warnings = _solve_where_it_lives(cell, root, None if cell.tcp_solve else tcp)
    sim = cf.frame(cell.frame)
    d = diff_frame(cf, cell.frame, sol.pose, tol)
    # FANUC: the listing's reviewed copy (the controller does not load .va
    # files) and the TP program that sets the frame
    result = patch_frame(cf, cell.frame, sol.pose, measured=True, check_siblings=False)
    if cell.robot is not None and cell.tcp_solve:
        result = _with_tcp(cf, result, cell.tool, sol.tcp)
    prog = _program(cell, root, sim, sol) if cell.set_by_program else None
    written = folder = None
    if out is not None:
        folder = Path(out) / Path(cell.controller).parent.name
        _mkdir(folder / "patched")
        write_inputs(cell, root, folder, sol, label=sim.label)
        if sol.accepted:
            written = save(result, folder / "patched" / Path(cell.controller).name)
            if prog is not None:
                from ..vendors.fanuc.program import save as save_program
                save_program(prog, str(folder / PROGRAM_FILE))     # sets prog.written
    label = f"a/{cell.controller}"
    extra = {} if prog is None else {"program": {
        "file": PROGRAM_FILE, "name": prog.name, "frame": prog.frame, "pr": prog.pr,
        "pr_from": Path(prog.pr_from).name if prog.pr_from != "--pr" else prog.pr_from,
        "text": prog.text, "written": str(prog.written) if prog.written else None}}
    return {**extra, 
        "cell": cell.name, "vendor": cell.vendor, "story": cell.story,
        "controller": cell.controller, "measurement": cell.measurement,
        "frame": sim.name, "label": sim.label,
        "tool": {"name": tool.name, "label": tool.label, "tcp": list(tcp)},
        "robot": cell.robot, "warnings": warnings,
        "solve": sol.as_dict(),
        "diff": d,
        "patch": {"changes": [c.as_dict() for c in result.changes],
                  "diff": result.diff.replace(f"a/{result.path.lstrip('/')}", label)
                                     .replace(f"b/{result.path.lstrip('/')}",
                                              f"b/{cell.controller}"),
                  "written": str(written) if written else None},
        "folder": str(folder) if folder is not None else None,
        "ok": bool(sol.accepted and d["pass"]),
    }


def _solve_where_it_lives(cell: Cell, root: Path, tcp=None):
    """Laser export + measurement program; the TCP solved with the frame
    where ``tcp`` is None (the third cell), else that TCP (the FANUC cell)."""
    from ..readers.laser import read_laser
    from ..readers.pairing import pair
    from ..readers.robot import read_robot

    meas, warnings = pair(read_laser(root / cell.measurement),
                          read_robot(root / cell.robot, config=str(root / cell.controller)))
    if tcp is not None:
        from ..method.solve import solve
        return solve(meas, tcp), warnings
    from ..method.tcp_solve import solve_joint
    return solve_joint(meas), warnings


PROGRAM_FILE = "SET_UF1.LS"     # the FANUC cell's program (its name is the program's)


def _program(cell: Cell, root: Path, sim, sol):
    """The TP program that sets the FANUC cell's frame, its register one that
    the backup's POSREG.VA shows unused, the frame's comment kept."""
    from ..vendors.fanuc.program import program

    return program(sol.pose, cell.frame, comment=sim.label,
                   posreg=str(root / cell.posreg) if cell.posreg else None, out=PROGRAM_FILE)


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


def replay_script(cell: Cell, label: str | None = None) -> str:
    """The demo's steps for one cell as the commands a user types (``label``:
    the frame's, which the FANUC program keeps as its comment)."""
    ctl = Path(cell.controller).name
    meas = Path(cell.measurement).name
    q = _sh
    if cell.set_by_program:
        robot = Path(cell.robot or "").name
        posreg = Path(cell.posreg or "").name
        return "\n".join([
            "#!/bin/sh",
            f"# ucsio demo, cell {cell.name}: {cell.story}",
            "# Every step of the demo by hand, in this folder. The laser points come from the",
            f"# tracker's point table, the robot's from the measurement program {robot} (each",
            f"# position taught with the reflector tool {cell.tool}); the controller does not",
            "# load .va files: a TP program sets the frame.",
            "set -e",
            'cd "$(dirname "$0")"',
            "# 1. solve: Horn's method, leave-one-out outlier exclusion",
            f"ucsio solve --laser {q(meas)} --robot {q(robot)} --config {q(ctl)} "
            f"--tool {q(ctl + ':' + cell.tool)} -o solution.json",
            "# 2. diff: the simulated frame against the measured one, and the taught points it moves",
            f"ucsio diff {q(ctl)} --frame {q(cell.frame)} --measured solution.json --points || true",
            f"# 3. write-back: a TP program that sets {cell.frame} (a register {posreg} shows unused)",
            f"ucsio program solution.json --frame {q(cell.frame)} --posreg {q(posreg)} "
            + (f"--comment {q(label)} " if label else "") + f"-o {PROGRAM_FILE}",
            f"ucsio frames {PROGRAM_FILE}",
            "# 4. review: a copy of the listing with the measured frame, against the original",
            f"ucsio patch {q(ctl)} --frame {q(cell.frame)} --measured solution.json "
            f"-o {q('patched/' + ctl)}",
            f"ucsio diff {q(ctl)} {q('patched/' + ctl)} || true",
            ""])
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
        "# 1. solve: Horn's method, leave-one-out outlier exclusion",
        f"ucsio solve {q(meas)} --tool {q(ctl + ':' + cell.tool)} -o solution.json",
        "# 2. diff: the simulated frame against the measured one (exit 1 over tolerance)",
        f"ucsio diff {q(ctl)} --frame {q(cell.frame)} --measured solution.json || true",
        "# 3. patch: preview, then write a patched copy (the input stays as it is)",
        f"ucsio patch {q(ctl)} --frame {q(cell.frame)} --measured solution.json",
        f"ucsio patch {q(ctl)} --frame {q(cell.frame)} --measured solution.json "
        f"-o {q('patched/' + ctl)}",
        "# 4. review: every frame of the two files",
        f"ucsio diff {q(ctl)} {q('patched/' + ctl)}",
        ""])


def _sh(word: str) -> str:
    import shlex
    return shlex.quote(word)


def write_inputs(cell: Cell, root: Path, folder: Path, sol, label: str | None = None) -> None:
    """The cell's inputs as shipped, the solution (as ``solve -o`` writes it)
    and replay.sh, so every step can be replayed by hand."""
    from ..files import atomic_write, atomic_write_text
    from ..method.solution import solution_text
    for rel in (cell.controller, cell.measurement, cell.robot, *cell.extra):
        if rel is not None:
            atomic_write(folder / Path(rel).name, (root / rel).read_bytes())
    atomic_write_text(folder / "solution.json", solution_text(sol.as_dict()))
    atomic_write_text(folder / "replay.sh", replay_script(cell, label))
    try:
        os.chmod(folder / "replay.sh", 0o755)
    except OSError:
        pass


def run_demo(out: str | os.PathLike | None = None,
             tolerance: float | None = None) -> dict[str, Any]:
    """Every shipped cell end to end; ``out``: also write patched copies there."""
    with ExitStack() as stack:
        root = stack.enter_context(resources.as_file(data_root()))
        cells = [run_cell(c, Path(root), out, tolerance) for c in CELLS]
    return {"cells": cells, "ok": all(c["ok"] for c in cells),
            "out": str(out) if out is not None else None}
