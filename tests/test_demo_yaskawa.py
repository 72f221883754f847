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


def stand_in_job_reader(path, *, config=None, load=None, **_):
    """A test's stand-in for Yaskawa's reader of robot positions (a .JBI
    reader is being written beside this): BASE-type positions only, each the
    flange · the tool its ///TOOL names in ``config``, so flange = T · tool⁻¹."""
    from pathlib import Path

    from ucsio.vendors.common.robot import RobotPose, RobotPoses
    tools = load(config)
    poses = []
    text = Path(path).read_text()
    for name, (postype, _user, tool, v) in groups(text).items():
        assert postype == "BASE"
        line = next(k + 1 for k, ln in enumerate(text.splitlines()) if ln.startswith(name + "="))
        T, flange_tool = np.eye(4), np.eye(4)
        T[:3, :3], T[:3, 3] = yaskawa_rotation(*v[3:]).as_matrix(), v[:3]
        pose = tools.frame(f"UT{tool}").pose
        flange_tool[:3, :3], flange_tool[:3, 3] = pose.matrix, pose.t
        poses.append(RobotPose(name, name, line, 1, T @ np.linalg.inv(flange_tool)))
    return RobotPoses(str(path), "yaskawa", poses, "yaskawa")


@pytest.fixture
def job_reader(monkeypatch):
    """Yaskawa with a reader of robot positions in .JBI files: what the demo's
    R05 waits for; the demo's own code is not touched."""
    from ucsio import vendors
    vendor = vendors.get("yaskawa")
    if vendor.robot_positions is None:
        monkeypatch.setattr(vendor, "robot_positions", stand_in_job_reader, raising=False)
        monkeypatch.setattr(vendor, "robot_suffixes", (".jbi",), raising=False)
        entry = vendors.BY_NAME["yaskawa"]
        monkeypatch.setattr(entry, "suffixes", (*entry.suffixes, ".jbi"))
    return vendor


def test_r05_not_run_says_what_is_missing_by_the_capability(tmp_path):
    """Without a reader of Yaskawa's robot positions, R05 is listed as not
    run, with the capability's words and the reader's own refusal of the job;
    --out still writes its inputs and a replay.sh whose steps are commented
    out, so it runs. Keyed on the capability: with the reader, R05 runs."""
    from ucsio import vendors
    from ucsio.demo import data_root, run_cell
    if vendors.get("yaskawa").robot_positions is not None:
        pytest.skip("Yaskawa reads its jobs' positions: test_r05_runs_every_step... holds")
    import subprocess
    from pathlib import Path
    with resources.as_file(data_root()) as root:
        got = run_cell(_cell(), Path(root), out=tmp_path)
    assert "solve" not in got and got["step"] == "solve"
    assert got["why"].startswith("Yaskawa has no reader of robot positions yet: MEASURE.JBI is "
                                 "a Yaskawa Motoman job (JBI)")
    folder = tmp_path / "R05_yaskawa"
    assert sorted(p.name for p in folder.iterdir()) == [
        "MEASURE.JBI", "PLACE.JBI", "TOOL.CND", "UFRAME.CND", "fixture_points.txt", "replay.sh"]
    script = (folder / "replay.sh").read_text()
    assert "#   ucsio program solution.json --frame UF2 -o SETUF2.JBI" in script
    assert subprocess.run(["sh", str(folder / "replay.sh")], capture_output=True).returncode == 0


def test_r05_runs_every_step_its_vendor_can_do(job_reader, tmp_path):
    """With a reader of the job's positions (here a test's stand-in, BASE
    positions through ///TOOL's tool), R05 runs through the same code as the
    other cells: the true UF2 comes back, C00004's blunder is excluded, the
    diff passes; the patch preview rewrites UF2's ////BUSER line alone and
    warns that the taught points no longer give the frame. Taught points and
    the SETUF job run where the vendor has them, else say what is missing."""
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
    assert cell["diff"]["pass"] and cell["ok"]
    diff = cell["patch"]["diff"]
    assert "-////BUSER 1450.000,390.000,610.000,0.0000,0.0000,90.0000" in diff
    assert [ln[:15] for ln in diff.splitlines() if ln[:1] in "+-" and ln[:3] not in
            ("+++", "---")] == ["-////BUSER 1450", "+////BUSER 1453"]
    assert any("RORG" in w for w in cell["patch"]["warnings"])
    patched = load(tmp_path / "R05_yaskawa" / "patched" / "UFRAME.CND")
    assert patched.frame("UF2").pose.t == pytest.approx([m["x"], m["y"], m["z"]], abs=5e-4)
    skipped = {s["step"]: s["why"] for s in cell["skipped"]}
    if job_reader.taught_points is None:
        assert skipped["points"] == "Yaskawa has no reader of taught points yet"
    else:       # PLACE.JBI's five USER positions move; the PULSE and the BASE one do not
        assert cell["points"]["points_moved"]["count"] == 5
    if job_reader.program_writer is None:
        assert skipped["program"] == ("Yaskawa has no program writer yet: SETUF2.JBI is not "
                                      "generated")
        assert "not run yet (Yaskawa has no program writer yet" in \
            (tmp_path / "R05_yaskawa" / "replay.sh").read_text()
    else:
        assert (tmp_path / "R05_yaskawa" / "SETUF2.JBI").read_bytes().startswith(b"/JOB\r\n")
