"""The demo's Yaskawa cell R05 (issue 27 point 7): its data checked against
the truth make_demo.py generated them from, independently of ucsio's solver
(scipy's Rotation and a plain Kabsch fit), and its steps wired through the
generic code the other cells run."""
from __future__ import annotations

import re
from importlib import resources

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from ucsio.parsing.controller import load

# make_demo.py's truth: the fixture as it stands, UF2 as simulated, the reflector UT3
TRUE_UF = (1453.870, 386.240, 612.430, 0.2400, -0.1700, 90.4600)
SIM_UF = (1450.000, 390.000, 610.000, 0.0000, 0.0000, 90.0000)
TCP = (0.480, -0.730, 162.250)
NOMINAL = np.array([
    [0.0, 0.0, 0.0], [1000.0, 0.0, 10.0], [1000.0, 700.0, 0.0], [0.0, 700.0, 15.0],
    [500.0, 350.0, 220.0], [210.0, 540.0, 110.0], [800.0, 160.0, 170.0], [390.0, 80.0, 45.0],
])
BLUNDER = "C00004"


def data(name: str):
    return resources.files("ucsio.demo").joinpath("data", "R05_yaskawa", name)


def yaskawa_rotation(rx, ry, rz) -> Rotation:
    """R = Rz(rz)·Ry(ry)·Rx(rx) (corpus/yaskawa/README.md)."""
    return Rotation.from_euler("xyz", [rx, ry, rz], degrees=True)


def groups(text: str) -> dict[str, tuple[str, str | None, str, list[float]]]:
    """Each position of a job's //POS: (POSTYPE, USER, TOOL, values), read
    line by line here, not by ucsio."""
    state = {"TOOL": None, "USER": None, "POSTYPE": None}
    out = {}
    for line in text.split("//INST")[0].splitlines():
        m = re.fullmatch(r"///(TOOL|USER|POSTYPE) (\S+)", line)
        if m:
            state[m[1]] = m[2]
        m = re.fullmatch(r"(C\d{5})=(.*)", line)
        if m:
            out[m[1]] = (state["POSTYPE"], state["USER"], state["TOOL"],
                         [float(v) for v in m[2].split(",")])
    return out


def test_r05_controller_files_read_with_todays_reader():
    """UFRAME.CND (UF1..UF3 on the robot base, UF2 the simulated frame, its
    rotation scipy's) and TOOL.CND (64 blocks, no ///CRC, the reflector UT3):
    CRLF as the controller writes, read and round-tripped by today's reader."""
    for name in ("UFRAME.CND", "TOOL.CND", "MEASURE.JBI", "PLACE.JBI"):
        raw = data(name).read_bytes()
        assert raw.endswith(b"\r\n") and raw.count(b"\n") == raw.count(b"\r\n"), name
    with resources.as_file(data("UFRAME.CND")) as path:
        cf = load(path)
    assert [(f.name, f.label, f.info["basicfrm"]) for f in cf.frames] == [
        ("UF1", "INFEED", "1,16,0"), ("UF2", "FIXTURE", "1,16,0"), ("UF3", "OUTFEED", "1,16,0")]
    uf2 = cf.frame("UF2").pose
    assert uf2.t == pytest.approx(SIM_UF[:3], abs=1e-9)
    assert np.allclose(uf2.matrix, yaskawa_rotation(*SIM_UF[3:]).as_matrix(), atol=1e-12)
    assert cf.document.text.encode() == data("UFRAME.CND").read_bytes()
    with resources.as_file(data("TOOL.CND")) as path:
        tools = load(path)
    assert len(tools.frames) == 64 and b"///CRC" not in data("TOOL.CND").read_bytes()
    smr = tools.frame("UT3")
    assert (smr.label, smr.pose.t, smr.pose.abc) == ("SMR", pytest.approx(TCP), (0.0, 0.0, 0.0))


def test_r05_measurement_job_holds_the_true_flange_poses_times_the_reflector():
    """MEASURE.JBI: eight BASE-type positions with ///TOOL 3; each is a flange
    pose · the reflector's TCP, so its point is the true UF2 applied to the
    fixture's nominal point within the robot's noise (0.05 mm per axis),
    the blunder C00004 3.4 mm off; the flange points the tool down (scipy's
    reading of rx, ry, rz)."""
    text = data("MEASURE.JBI").read_text()
    assert "///NPOS 8,0,0,0,0,0" in text
    pos = groups(text)
    assert list(pos) == [f"C{k:05d}" for k in range(8)]
    truth = yaskawa_rotation(*TRUE_UF[3:]).apply(NOMINAL) + TRUE_UF[:3]
    for k, (name, (postype, user, tool, v)) in enumerate(pos.items()):
        assert (postype, user, tool) == ("BASE", None, "3")
        R = yaskawa_rotation(*v[3:])
        flange_t = np.array(v[:3]) - R.apply(TCP)            # T = flange · tool
        off = np.linalg.norm(flange_t + R.apply(TCP) - truth[k])
        assert (3.2 < off < 3.6) if name == BLUNDER else off < 0.3, (name, off)
        assert R.apply([0.0, 0.0, 1.0])[2] < -0.75          # the tool roughly down


def test_r05_laser_table_and_a_fit_without_ucsio_give_the_true_frame():
    """The tracker's table is the nominal points within the laser's noise
    (0.015 mm per axis); a plain Kabsch fit of laser to robot points without
    the blunder gives the true UF2 (a check of the data, not of ucsio)."""
    rows = [line.split() for line in data("fixture_points.txt").read_text().splitlines()
            if line and not line.startswith("#")][1:]
    names = [r[0] for r in rows]
    laser = np.array([[float(v) for v in r[1:]] for r in rows])
    assert names == [f"C{k:05d}" for k in range(8)]
    assert np.abs(laser - NOMINAL).max() < 0.08
    pos = groups(data("MEASURE.JBI").read_text())
    robot = np.array([pos[n][3][:3] for n in names])
    keep = [k for k, n in enumerate(names) if n != BLUNDER]
    a, b = laser[keep], robot[keep]
    rot, _ = Rotation.align_vectors(b - b.mean(0), a - a.mean(0))
    t = b.mean(0) - rot.apply(a.mean(0))
    assert t == pytest.approx(TRUE_UF[:3], abs=0.1)
    assert (rot * yaskawa_rotation(*TRUE_UF[3:]).inv()).magnitude() < np.radians(0.01)


def test_r05_production_job_is_taught_in_uf2_with_a_pulse_and_a_base_point():
    """PLACE.JBI: USER-type positions under ///USER 2 (they move with UF2), a
    PULSE home and a BASE approach (they do not)."""
    pos = groups(data("PLACE.JBI").read_text())
    kinds = {name: (postype, user) for name, (postype, user, _t, _v) in pos.items()}
    assert kinds == {"C00000": ("PULSE", None), "C00001": ("BASE", None),
                     **{f"C{k:05d}": ("USER", "2") for k in range(2, 7)}}


# ---------------------------------------------------------------- the demo's steps for R05

def _cell():
    from ucsio.demo import CELLS
    (cell,) = [c for c in CELLS if c.name == "R05"]
    return cell


@pytest.fixture
def no_job_reader(monkeypatch):
    """Yaskawa as it was before it read its jobs' positions: the capability
    None, the job a file it does not read (what a vendor without a robot
    reader looks like to the demo)."""
    from ucsio import vendors
    from ucsio.parsing import foreign
    monkeypatch.setattr(vendors.get("yaskawa"), "robot_positions", None)
    monkeypatch.setattr(foreign, "KNOWN", (("a Yaskawa Motoman job", "Yaskawa", (".jbi",),
                                            r"/JOB\b"), *foreign.KNOWN))


def test_r05_not_run_says_what_is_missing_by_the_capability(no_job_reader, tmp_path):
    """Without a reader of the vendor's robot positions, a cell is listed as
    not run, with the capability's words and the reader's own refusal of the
    job; --out still writes its inputs and a replay.sh whose steps are
    commented out, so it runs. Keyed on the capability, not the vendor."""
    import subprocess
    from pathlib import Path

    from ucsio.demo import data_root, run_cell
    with resources.as_file(data_root()) as root:
        got = run_cell(_cell(), Path(root), out=tmp_path)
    assert "solve" not in got and got["step"] == "solve"
    assert got["why"].startswith("Yaskawa has no reader of robot positions yet: MEASURE.JBI is "
                                 "a Yaskawa Motoman job (JBI)")
    folder = tmp_path / "R05_yaskawa"
    assert sorted(p.name for p in folder.iterdir()) == [
        "MEASURE.JBI", "PLACE.JBI", "TOOL.CND", "UFRAME.CND", "VAR.DAT", "fixture_points.txt",
        "replay.sh"]
    script = (folder / "replay.sh").read_text()
    assert "#   ucsio program solution.json --frame UF2 --var VAR.DAT -o SETUF2.JBI" in script
    assert subprocess.run(["sh", str(folder / "replay.sh")], capture_output=True).returncode == 0


def test_r05_runs_every_step(tmp_path):
    """R05 end to end: the true UF2 comes back from the tracker's table and
    MEASURE.JBI, C00004's blunder is excluded, the diff passes; PLACE.JBI's
    five USER positions in UF2 move (its PULSE and BASE ones are skipped);
    the SETUF job loads three P variables VAR.DAT shows unused and reads back
    as the solution; the patch preview rewrites UF2's ////BUSER line alone and
    warns that the taught points no longer give the frame."""
    from pathlib import Path

    from ucsio.demo import data_root, run_cell
    with resources.as_file(data_root()) as root:
        cell = run_cell(_cell(), Path(root), out=tmp_path)
    s = cell["solve"]
    assert s["accepted"] and [p["name"] for p in s["points"] if not p["used"]] == [BLUNDER]
    m = s["frame"]
    assert [m[k] for k in "xyz"] == pytest.approx(TRUE_UF[:3], abs=0.15)
    got = Rotation.from_quat(m["q"], scalar_first=True)
    assert (got * yaskawa_rotation(*TRUE_UF[3:]).inv()).magnitude() < np.radians(0.02)
    assert cell["diff"]["pass"] and cell["ok"] and cell["skipped"] == []
    # PLACE.JBI: C00002..C00006 in UF2 move; C00000 (PULSE) and C00001 (BASE) do not
    points = cell["points"]
    assert points["points_moved"]["count"] == 5 and points["points_skipped"] == 2
    assert sorted(p["name"] for p in points["points"]) == [f"C{k:05d}" for k in range(2, 7)]
    # the SETUF job: P125..P127, the highest three VAR.DAT leaves unused (P000..P015 used)
    prog = cell["program"]
    assert prog["p"] == [125, 126, 127] and prog["p_from"] == "VAR.DAT"
    job = tmp_path / "R05_yaskawa" / "SETUF2.JBI"
    assert job.read_bytes().startswith(b"/JOB\r\n//NAME SETUF2\r\n")
    assert b"MFRAME UF#(2) P125 P126 P127\r\n" in job.read_bytes()
    rows = [[float(v) for v in ln.split("=")[1].split(",")]
            for ln in job.read_text().splitlines() if ln.startswith("P00")]
    org, xx, xy = (np.array(r[:3]) for r in rows)
    x = (xx - org) / np.linalg.norm(xx - org)
    z = np.cross(x, xy - org)
    z /= np.linalg.norm(z)
    built = Rotation.from_matrix(np.column_stack([x, np.cross(z, x), z]))
    assert org == pytest.approx([m["x"], m["y"], m["z"]], abs=1e-3)
    assert (built * got.inv()).magnitude() < np.radians(1e-3)
    diff = cell["patch"]["diff"]
    assert "-////BUSER 1450.000,390.000,610.000,0.0000,0.0000,90.0000" in diff
    assert [ln[:15] for ln in diff.splitlines() if ln[:1] in "+-" and ln[:3] not in
            ("+++", "---")] == ["-////BUSER 1450", "+////BUSER 1453"]
    assert any("RORG" in w for w in cell["patch"]["warnings"])
    patched = load(tmp_path / "R05_yaskawa" / "patched" / "UFRAME.CND")
    assert patched.frame("UF2").pose.t == pytest.approx([m["x"], m["y"], m["z"]], abs=5e-4)
