"""Each vendor's own angle names in tables (issue 25, point 11): KUKA a b c,
FANUC w p r, ABB RobotStudio's rx ry rz beside the quaternion; and a Δ row
that adds up to the rows above it. JSON keys stay as SPEC says."""
from __future__ import annotations

import json
import re

import pytest
from scipy.spatial.transform import Rotation

from ucsio.cli import main


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    out = tmp_path_factory.mktemp("demo")
    assert main(["demo", "--out", str(out / "demo")]) == 0
    return out / "demo"


def _table(text: str) -> tuple[list[str], dict[str, list[str]]]:
    """The header and the rows (by their first cell) of the first table."""
    lines = [ln.strip() for ln in text.splitlines()]
    k = next(i for i, ln in enumerate(lines) if ln.startswith("---"))
    rows = {}
    for ln in lines[k + 1:]:
        if not ln or not re.match(r"(simulated|measured|Δ|delta)\s", ln):
            break
        cells = re.findall(r"\[[^\]]*\]|\S+", ln)
        rows[cells[0]] = cells[1:]
    return lines[k - 1].split(), rows


def _adds_up(rows, delta="Δ"):
    for s, m, d in zip(rows["simulated"][:6], rows["measured"][:6], rows[delta][:6]):
        diff = float(m) - float(s)
        diff = -((-diff + 180.0) % 360.0 - 180.0)
        decimals = len(d.split(".")[1])
        assert f"{diff:+.{decimals}f}" == d, (s, m, d)


@pytest.mark.parametrize("ctl, frame, names", [
    ("R01_kuka/$config.dat", "BASE_DATA[3]", ["a", "b", "c"]),
    ("R02_abb/CellR02.mod", "wobjTable", ["rx", "ry", "rz", "q"]),
    ("R04_fanuc/SYSFRAME.VA", "UF1", ["w", "p", "r"]),
])
def test_diff_table_names_and_adds_up(demo, capsys, ctl, frame, names):
    folder = demo / ctl.split("/")[0]
    main(["diff", str(demo / ctl), "--frame", frame, "--measured", str(folder / "solution.json")])
    header, rows = _table(capsys.readouterr().out)
    assert header == ["x", "y", "z", *names]
    _adds_up(rows)
    main(["diff", str(demo / ctl), "--frame", frame, "--measured", str(folder / "solution.json"),
          "--json"])
    d = json.loads(capsys.readouterr().out)
    assert {"da", "db", "dc"} <= d.keys() and {"a", "b", "c", "q"} <= d["measured"].keys()
    if names[0] == "rx":      # RobotStudio's Euler ZYX angles of the quaternion, by scipy
        w, x, y, z = d["measured"]["q"]
        rz, ry, rx = Rotation.from_quat([x, y, z, w]).as_euler("ZYX", degrees=True)
        assert [float(v) for v in rows["measured"][3:6]] == \
            pytest.approx([rx, ry, rz], abs=1e-4)
        assert rows["measured"][6] == "[" + ", ".join(f"{v:.6f}" for v in d["measured"]["q"]) + "]"


def test_the_abb_delta_adds_up_where_rounding_parted_it(demo, capsys):
    """wobjTable's simulated angle is −35.00002 (its 6-decimal quaternion),
    shown −35.0000: the Δ shown is −35.4196 − (−35.0000), not −0.4195."""
    main(["diff", str(demo / "R02_abb/CellR02.mod"), "--frame", "wobjTable", "--measured",
          str(demo / "R02_abb/solution.json")])
    _, rows = _table(capsys.readouterr().out)
    assert rows["simulated"][5] == "-35.0000" and rows["measured"][5] == "-35.4196"
    assert rows["Δ"][5] == "-0.4196"


def test_demo_tables_in_each_vendors_names(capsys):
    main(["demo"])
    out = capsys.readouterr().out
    cells = out.split("2. diff: measured - simulated")[1:]
    assert len(cells) == 7
    headers = []
    for cell in cells:
        header, rows = _table(cell)
        _adds_up(rows, "delta")
        headers.append(header[3:])
    assert ["a", "b", "c"] in headers and ["rx", "ry", "rz", "q"] in headers
    assert ["w", "p", "r"] in headers and ["rx", "ry", "rz"] in headers     # FANUC, Yaskawa
    assert ["roll", "pitch", "yaw"] in headers                                # Universal Robots


def test_frames_and_two_file_diff_in_each_vendors_names(demo, capsys, tmp_path):
    main(["frames", str(demo / "R02_abb/CellR02.mod")])
    header = capsys.readouterr().out.splitlines()[0].split()
    assert header[:10] == ["name", "type", "label", "ref", "x", "y", "z", "rx", "ry", "rz"]
    main(["frames", str(demo / "R04_fanuc/SYSFRAME.VA")])
    assert capsys.readouterr().out.splitlines()[0].split()[7:10] == ["w", "p", "r"]
    old = demo / "R02_abb/CellR02.mod"
    main(["diff", str(old), str(demo / "R02_abb/patched/CellR02.mod")])
    out = capsys.readouterr().out
    assert "drx " in out and " rz " in out and " q [" in out and "da " not in out
