"""A patched copy written into the cell's folder (issue 25, point 7): it
declares the same MODULE, so the next patch is refused naming the copy and
saying to move it, and `diff --points` does not count its points twice; the
README's walk-through writes its copy elsewhere."""
from __future__ import annotations

import json
import re
import shutil

from conftest import ROOT
from ucsio.cli import main

DEMO = ROOT / "src" / "ucsio" / "demo" / "data" / "R02_abb"


def _cell(tmp_path, capsys):
    cell = tmp_path / "cell"
    cell.mkdir()
    shutil.copy(DEMO / "CellR02.mod", cell)
    shutil.copy(DEMO / "table_points.csv", cell)
    assert main(["solve", cell / "table_points.csv", "--tool", f"{cell / 'CellR02.mod'}:tReflector",
                 "-o", cell / "solution.json"]) == 0
    capsys.readouterr()
    return cell


def _patch(cell, *more):
    return main(["patch", cell / "CellR02.mod", "--frame", "wobjTable", "--measured",
                 cell / "solution.json", *more])


def test_a_copy_in_the_folder_is_named_and_to_be_moved(tmp_path, capsys):
    cell = _cell(tmp_path, capsys)
    main(["diff", cell / "CellR02.mod", "--frame", "wobjTable", "--measured",
          cell / "solution.json", "--points", "--json"])
    alone = json.loads(capsys.readouterr().out)["points_moved"]["count"]
    assert _patch(cell, "-o", cell / "CellR02.new.mod") == 0
    capsys.readouterr()
    before = (cell / "CellR02.mod").read_bytes()
    assert _patch(cell, "--in-place") == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"ucsio: {cell / 'CellR02.mod'}:7: wobjTable: CellR02.new.mod declares "
                          "MODULE CellR02 too: a copy of CellR02.mod")
    assert "move the copy out of this folder" in err and len(err.splitlines()) == 1
    assert (cell / "CellR02.mod").read_bytes() == before
    # the taught points: counted once, and the copy said
    main(["diff", cell / "CellR02.mod", "--frame", "wobjTable", "--measured",
          cell / "solution.json", "--points", "--json"])
    captured = capsys.readouterr()
    assert json.loads(captured.out)["points_moved"]["count"] == alone == 2
    assert "CellR02.new.mod declares MODULE CellR02 too" in captured.err
    # moved out: patched as before
    (tmp_path / "review").mkdir()
    shutil.move(cell / "CellR02.new.mod", tmp_path / "review")
    assert _patch(cell) == 0


def test_a_module_of_another_name_still_shares_its_pers(tmp_path, capsys):
    """Not a copy: RAPID shares one PERS between two modules of a task."""
    cell = _cell(tmp_path, capsys)
    text = (cell / "CellR02.mod").read_text()
    (cell / "Other.mod").write_text(text.replace("MODULE CellR02", "MODULE Other"))
    assert _patch(cell) == 2
    err = capsys.readouterr().err
    assert "also declared in Other.mod" in err and "copy" not in err


def test_the_readme_writes_its_copy_outside_the_cell():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    block = readme.split("## Five minutes on your own cell", 1)[1].split("```sh", 1)[1]
    block = block.split("```", 1)[0]
    outs = re.findall(r"ucsio patch \S+ .*-o (\S+)", block)
    assert outs and all(o.startswith("../") for o in outs), outs
