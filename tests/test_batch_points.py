"""batch with `points = true`: each entry's taught points, in the JSON, the
CSV, the text table and the report. The measurements are made here from a
known true frame without noise, so the solve returns it and the expected
displacements follow from scipy alone."""
from __future__ import annotations

import contextlib
import csv
import io
import json
import shutil

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from conftest import FIXTURES
from ucsio.cli import main

TAUGHT = FIXTURES / "taught"
LASER = np.array([[0, 0, 0], [800, 0, 0], [0, 600, 0], [800, 600, 0], [0, 0, 300],
                  [800, 0, 300], [0, 600, 300], [400, 300, 150]], float)
TRUE_BASE3 = (1501.0, -249.0, 600.5, 30.5, -2.4, 1.0)   # x y z a b c
TRUE_WOBJ = (1201.0, -299.0, 450.5, 0.96, 0.01, 0.0, 0.28)   # x y z q (normalised below)


def run(*args) -> tuple[int, str]:
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        code = main([str(a) for a in args])
    return code, out.getvalue()


def measurement(path, rot: Rotation, t) -> None:
    """Laser points and flange positions (TCP 0,0,0) of a frame that is truly ``rot``, ``t``."""
    robot = rot.apply(LASER) + t
    rows = ["point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c"]
    for i, (p, r) in enumerate(zip(LASER, robot), 1):
        rows.append(f"P{i}," + ",".join(repr(float(v)) for v in (*p, *r)) + ",0,0,0")
    path.write_text("\n".join(rows) + "\n")


def kuka_truth():
    x, y, z, a, b, c = TRUE_BASE3
    return Rotation.from_euler("ZYX", [a, b, c], degrees=True), np.array([x, y, z])


def wobj_truth():
    q = np.array(TRUE_WOBJ[3:]) / np.linalg.norm(TRUE_WOBJ[3:])
    return Rotation.from_quat(q, scalar_first=True), np.array(TRUE_WOBJ[:3])


@pytest.fixture(scope="module")
def fleet(tmp_path_factory):
    root = tmp_path_factory.mktemp("points_fleet")
    shutil.copytree(TAUGHT / "kuka" / "KRC", root / "KRC")
    shutil.copytree(TAUGHT / "abb", root / "cell_abb")
    measurement(root / "base3.csv", *kuka_truth())
    measurement(root / "table.csv", *wobj_truth())
    (root / "manifest.toml").write_text(
        "[defaults]\ntcp = [0, 0, 0]\npoints = true\n\n"
        "[[entry]]\nname = \"kuka weld fixture\"\nmeasurement = \"base3.csv\"\n"
        "controller = \"KRC/R1/System/$config.dat\"\nframe = \"weld_fixture\"\n"
        "station = \"line 1\"\n\n"
        "[[entry]]\nname = \"abb table\"\nmeasurement = \"table.csv\"\n"
        "controller = \"cell_abb/Cell.mod\"\nframe = \"wobjTable\"\n\n"
        "[[entry]]\nname = \"abb table, no points\"\nmeasurement = \"table.csv\"\n"
        "controller = \"cell_abb/Cell.mod\"\nframe = \"wobjTable\"\npoints = false\n\n"
        "[[entry]]\nname = \"abb other\"\nmeasurement = \"table.csv\"\n"
        "controller = \"cell_abb/Cell.mod\"\nframe = \"wobjOther\"\ntolerance = 5000\n")
    code, out = run("batch", root / "manifest.toml", "--json", "--csv", root / "out.csv",
                    "--report", root / "report.html")
    assert code == 0, out
    return root, json.loads(out)


def _moved(sim_chain, true_chain, p):
    def world(chain, p):
        p = np.asarray(p, float)
        for r, t in reversed(chain):
            p = r.apply(p) + t
        return p
    return float(np.linalg.norm(world(true_chain, p) - world(sim_chain, p)))


def test_entries_carry_points_moved(fleet):
    _, data = fleet
    kuka, abb, off, other = data["entries"]
    # KUKA: XP2 (2000 mm out) moves most; four points taught in base 3
    sim = [(Rotation.from_euler("ZYX", [30, -2.5, 1.2], degrees=True),
            np.array([1500.0, -250.0, 600.0]))]
    pts = {"XP1": (0, 0, 0), "XP2": (2000, 0, 0), "xp3": (-300.5, 800.25, 120),
           "XGLOBAL1": (10, 20, 30)}
    want = {n: _moved(sim, [kuka_truth()], p) for n, p in pts.items()}
    pm = kuka["points_moved"]
    assert pm["count"] == 4 and pm["worst"] == "XP2"
    assert pm["max"] == pytest.approx(want["XP2"], abs=1e-6)
    assert pm["mean"] == pytest.approx(np.mean(list(want.values())), abs=1e-6)
    assert any("XP5" in w for w in pm["warnings"])
    # ABB: the measured user frame carries the unchanged object frame
    o = (Rotation.from_quat([0.996195, 0, 0.0871557, 0], scalar_first=True), np.array([50, 20, 0.0]))
    u = (Rotation.from_quat([0.965926, 0, 0, 0.258819], scalar_first=True),
         np.array([1200, -300, 450.0]))
    assert abb["points_moved"]["count"] == 9 and abb["points_moved"]["worst"] == "pB"
    assert abb["points_moved"]["max"] == pytest.approx(
        _moved([u, o], [wobj_truth(), o], (2000, 0, 0)), abs=1e-6)
    assert "points_moved" not in off
    # the same folder's modules, read once in the run, for another work object
    assert other["points_moved"]["count"] == 1 and other["points_moved"]["worst"] == "pElsewhere"
    u_other = (Rotation.identity(), np.array([0, 900, 0.0]))
    assert other["points_moved"]["max"] == pytest.approx(
        _moved([u_other], [wobj_truth()], (10, 10, 10)), abs=1e-6)
    assert [e["station"] for e in data["entries"]] == ["line 1", "cell_abb", "cell_abb",
                                                      "cell_abb"]


def test_csv_and_text_carry_points_moved(fleet):
    root, data = fleet
    rows = list(csv.DictReader((root / "out.csv").open()))
    assert rows[0]["points_count"] == "4" and rows[0]["points_worst"] == "XP2"
    assert float(rows[0]["points_max"]) == data["entries"][0]["points_moved"]["max"]
    assert rows[2]["points_count"] == "" and rows[0]["station"] == "line 1"
    code, out = run("batch", root / "manifest.toml")
    assert code == 0
    assert "points moved max (n)" in out
    assert f"{data['entries'][0]['points_moved']['max']:.3f} (4)" in out


def test_manifest_points_must_be_a_boolean(tmp_path):
    (tmp_path / "m.toml").write_text("[defaults]\npoints = \"yes\"\n[[entry]]\nname = \"a\"\n"
                                     "measurement = \"a.csv\"\ncontroller = \"a.mod\"\n"
                                     "frame = \"w\"\n")
    code, _ = run("batch", tmp_path / "m.toml")
    assert code == 2


@pytest.mark.parametrize("controller, station", [
    ("/plant/R01/KRC/R1/System/$config.dat", "R01"),
    ("/plant/Line3/RAPID/TASK1/PROGMOD/Cell.mod", "Line3"),
    ("/plant/R02/cell.mod", "R02"),
])
def test_default_station_is_the_folder_above_the_backup_layout(controller, station):
    from ucsio.fleet.batch import Entry, EntryResult

    entry = Entry(index=0, name="e", measurement="m.csv", controller=controller, frame="f",
                  tcp=(0.0, 0.0, 0.0), tool=None)
    assert EntryResult(entry=entry).station == station
    assert EntryResult(entry=Entry(**{**entry.__dict__, "station": "cell 9"})).station == "cell 9"
