"""batch --patch-dir on a FANUC entry (issue 25, point 8): the listing's copy
is for review, and beside it the TP program that sets the frame, as
`ucsio program` writes it; the table, CSV, JSON and report say "program
written" and "listing for review", never counting a listing as corrected."""
from __future__ import annotations

import csv
import json
import re
import shutil

import pytest

from conftest import ROOT
from ucsio.cli import main

DATA = ROOT / "src" / "ucsio" / "demo" / "data"
MANIFEST = '''
[[entry]]
name = "R04 pallet"
laser = "R04/pallet_points.txt"
robot = "R04/MEASURE.LS"
config = "R04/SYSFRAME.VA"
tool = "R04/SYSFRAME.VA:UT2"
controller = "R04/SYSFRAME.VA"
frame = "UF1"
{extra}
[[entry]]
name = "R02 table"
measurement = "R02/table_points.csv"
tool = "R02/CellR02.mod:tReflector"
controller = "R02/CellR02.mod"
frame = "wobjTable"
'''


def _fleet(tmp_path, extra="", posreg=True):
    shutil.copytree(DATA / "R04_fanuc", tmp_path / "R04")
    shutil.copytree(DATA / "R02_abb", tmp_path / "R02")
    if not posreg:
        (tmp_path / "R04" / "POSREG.VA").unlink()
    (tmp_path / "m.toml").write_text(MANIFEST.format(extra=extra))
    return tmp_path / "m.toml"


def _batch(m, out, capsys, *more):
    assert main(["batch", m, "--json", "--patch-dir", out, *more]) == 0
    return json.loads(capsys.readouterr().out)


def test_the_program_is_written_beside_the_listing(tmp_path, capsys):
    m = _fleet(tmp_path)
    out = tmp_path / "out"
    report, table = tmp_path / "r.html", tmp_path / "r.csv"
    doc = _batch(m, out, capsys, "--report", report, "--csv", table)
    fanuc, abb = doc["entries"]
    assert fanuc["written"] == ["program written", "listing for review"] and fanuc["listing"]
    assert abb["written"] == ["patched"] and "listing" not in abb and "program" not in abb
    program = out / "R04" / "SET_UF1.LS"
    assert fanuc["program"]["file"] == str(program) and fanuc["program"]["pr"] == 20
    s = doc["summary"]
    assert (s["patched"], s["corrected"], s["programs"], s["listings"]) == (2, 2, 1, 1)
    # the same program `ucsio program` writes from solve's solution of the same files
    r04 = tmp_path / "R04"
    assert main(["solve", "--laser", r04 / "pallet_points.txt", "--robot", r04 / "MEASURE.LS",
                 "--config", r04 / "SYSFRAME.VA", "--tool", f"{r04 / 'SYSFRAME.VA'}:UT2",
                 "-o", tmp_path / "s.json"]) == 0
    assert main(["program", tmp_path / "s.json", "--frame", "UF1", "--posreg",
                 r04 / "POSREG.VA", "--comment", "PALLET", "-o", tmp_path / "SET_UF1.LS"]) == 0
    capsys.readouterr()
    assert program.read_bytes() == (tmp_path / "SET_UF1.LS").read_bytes()
    # the CSV and the report in the same words
    rows = {r["name"]: r for r in csv.DictReader(table.open(encoding="utf-8"))}
    assert rows["R04 pallet"]["written"] == "program written; listing for review"
    assert rows["R04 pallet"]["program"] == str(program)
    assert rows["R02 table"]["written"] == "patched" and rows["R02 table"]["program"] == ""
    page = report.read_text().split('<script type="application/json"', 1)[0]
    row = page.split('<tr class="entry" data-name="R04 pallet"', 1)[1].split("</tr>", 1)[0]
    assert ">program written</span>" in row and ">listing for review</span>" in row
    assert ">patched</span>" not in row
    assert 'data-key="corrected" data-value="2"' in page
    assert 'data-key="listings" data-value="1"' in page
    # each entry's details name the angles as its vendor does (issue 25, point 11)
    for name, heads in (("R04 pallet", "w p r"), ("R02 table", "rx ry rz")):
        detail = page.split(f"<b>{name}</b>", 1)[1].split("</table>", 1)[0]
        assert re.findall(r"<th class='n'>(\w+) °</th>", detail) == heads.split()
    table_r02 = page.split("<b>R02 table</b>", 1)[1].split("</table>", 1)[0]
    assert "<td class='n'>-35.4196</td>" in table_r02 and "<td class='n'>-0.4196</td>" in table_r02
    # the text table
    assert main(["batch", m, "--patch-dir", tmp_path / "again"]) == 0
    text = capsys.readouterr().out
    assert "program written; listing for review" in text
    assert "patched 1   programs written 1   listings for review 1" in text


@pytest.mark.parametrize("extra, posreg, pr", [("pr = 90", False, 90),
                                               ('posreg = "R04/POSREG.VA"', True, 20)])
def test_the_register_from_the_entry(tmp_path, capsys, extra, posreg, pr):
    doc = _batch(_fleet(tmp_path, extra, posreg), tmp_path / "out", capsys)
    program = doc["entries"][0]["program"]
    assert program["pr"] == pr
    assert f"PR[{pr},1]=" in (tmp_path / "out" / "R04" / "SET_UF1.LS").read_text()


def test_no_register_no_program_and_it_says_so(tmp_path, capsys):
    doc = _batch(_fleet(tmp_path, posreg=False), tmp_path / "out", capsys)
    fanuc = doc["entries"][0]
    assert fanuc["written"] == ["listing for review"] and "program" not in fanuc
    assert "no posreg.va beside SYSFRAME.VA" in fanuc["program_error"]
    assert "pr = N or posreg" in fanuc["program_error"]
    assert doc["summary"]["corrected"] == 1 and doc["summary"]["listings"] == 1
    assert not (tmp_path / "out" / "R04" / "SET_UF1.LS").exists()
    main(["batch", tmp_path / "m.toml", "--patch-dir", tmp_path / "again"])
    text = capsys.readouterr().out
    assert "programs not written (the listing's copy is for review only):" in text
    assert "R04 pallet  pass" in text and "listing for review" in text
