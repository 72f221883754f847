"""Yaskawa jobs (.JBI), issue 27 points 1 (jobs), 3 and 4.

The corpus's jobs round-trip with their numbers at their spans
(tests/test_every_vendor.py, .jbi being Yaskawa's suffix); here: what the
reader finds in them, the forms they lack (CRLF, unknown lines, a wrong
///NPOS), bad input, `solve --robot JOB.JBI` against synthetic truth
(tests/fanuc_cell.py: scipy's Rotation, R = Rz·Ry·Rx as Yaskawa's), and
`diff --points` on a fixture backup and on the corpus's CUT_ONLY.JBI beside
its UFRAME.CND. Fixtures are written in the corpus's style (CRLF).
"""
from __future__ import annotations

import json
import math
import shutil

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from conftest import FIXTURES, corpus_file
from fanuc_cell import Cell, inv
from test_yaskawa import KOMATSU, cli, crlf, tool, uframe, write
from ucsio.errors import UcsioError
from ucsio.parsing.controller import parse
from ucsio.parsing.document import Document
from ucsio.readers.robot import read_robot
from ucsio.vendors.yaskawa import job

RCONF = "///RCONF 0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n"
INST = "//INST\n///DATE 2026/11/30 09:12\n///ATTR SC,RW\n///GROUP1 RB1\nNOP\nEND\n"
BACKUP = FIXTURES / "yaskawa" / "taught_backup"


def a_job(pos: str, npos: str = "0,0,0,0,0,0", name: str = "MEAS") -> str:
    return f"/JOB\n//NAME {name}\n//POS\n///NPOS {npos}\n{pos}{INST}"


def read(path) -> list[job.Position]:
    return parse(Document.read(path)).extra["positions"]


# -- reading ---------------------------------------------------------------------------------
def test_cut_only_holds_base_then_user_points():
    path = corpus_file("yaskawa", "CUT_ONLY.JBI")
    doc = Document.read(path)
    cf = parse(doc)
    assert cf.frames == [] and cf.lints == [] and cf.extra["name"] == "CUT_ONLY"
    got = [(p.name, p.postype, p.user, p.tool, p.pulse) for p in cf.extra["positions"]]
    assert got[0] == ("P00100", "BASE", None, 0, False)
    assert got[1:] == [(f"P0010{i}", "USER", 1, 0, False) for i in range(5, 10)]
    first = cf.extra["positions"][1]
    assert (first.point, first.line) == ("P105", 12)
    for key, n in first.values.items():     # every number at its span
        assert doc.slice(n.span) == n.text and float(n.text) == n.value
    assert first.xyzabc() == (216.374, -55.365, 150.0, 179.9941, -0.0013, -179.9943)


def test_komatsu_jobs_change_tools_and_types_between_points():
    press = read(corpus_file("yaskawa", KOMATSU + "R1_PRESS.JBI"))
    assert [(p.name, p.tool, p.pulse) for p in press] == [
        ("C00000", 3, True), ("C00001", 4, True), ("P00007", 3, True), ("P00008", 4, True),
        ("P00030", 3, True)]
    reset = read(corpus_file("yaskawa", KOMATSU + "R1_RESET.JBI"))
    assert [(p.name, p.postype, p.tool) for p in reset] == [
        ("P00002", "PULSE", 3), ("P00004", "BASE", 3), ("P00006", "BASE", 3),
        ("P00012", "PULSE", 3), ("P00013", "BASE", 3), ("P00014", "BASE", 3),
        ("P00032", "BASE", 0)]
    assert all(p.pulse == (p.postype == "PULSE") for p in reset)
    assert read(corpus_file("yaskawa", KOMATSU + "MAIN.JBI")) == []


def test_fenders_545_pulses_and_three_tool_offsets(capsys):
    path = corpus_file("yaskawa", "FMTV_FENDERS.JBI")
    found = read(path)
    assert sum(p.kind == "C" and p.pulse for p in found) == 545
    assert [p.postype for p in found if not p.pulse] == ["TOOL"] * 3
    code, out, err = cli(capsys, "frames", path)
    assert code == 0 and "no frames" in out
    assert "548 positions (545 PULSE, 3 TOOL)" in out


def test_crlf_and_unknown_lines_are_kept_as_they_are(tmp_path, capsys):
    text = a_job("///TOOL 1\n///POSTYPE BASE\n///RECTAN\n" + RCONF + "///NEWTHING 7\n"
                 "P00001=1.000,2.000,3.000,180.0000,0.0000,90.0000\n"
                 "BC00001=100,200\n", npos="0,1,0,1,0,0")
    text = text.replace("//POS\n", "///COMMENT hello\n//POS\n")
    for data in (crlf(text), text.encode()):
        path = write(tmp_path, "KEEP.JBI", data)
        doc = Document.read(path)
        assert doc.to_bytes() == data
        cf = parse(doc)
        assert [(l.line, l.code, l.severity) for l in cf.lints] == [
            (3, "unknown-line", "info"), (10, "unknown-line", "info")]
        p, axes = cf.extra["positions"]
        assert (p.name, p.tool, p.postype, p.xyzabc()) == (
            "P00001", 1, "BASE", (1.0, 2.0, 3.0, 180.0, 0.0, 90.0))
        assert (axes.kind, list(axes.values)) == ("BC", ["j1", "j2"])
        code, out, err = cli(capsys, "check", path)
        assert code == 0 and "round trip ok" in out, err


def test_npos_that_does_not_count_the_positions_is_a_warning(tmp_path):
    path = write(tmp_path, "N.JBI", crlf(a_job(
        "///TOOL 0\n///POSTYPE PULSE\n///PULSE\nC00000=1,2,3,4,5,6\n", npos="2,0,0,0,0,0")))
    lints = parse(Document.read(path)).lints
    assert [(l.line, l.code, l.severity) for l in lints] == [(4, "npos-count", "warning")]
    assert "C 1 (///NPOS says 2)" in lints[0].message


@pytest.mark.parametrize("pos, where, words", [
    ("///POSTYPE BASE\n///RECTAN\nP00001=1.000,2.000,3.000,0.0000,0.0000\n", "7:39",
     "x,y,z,rx,ry,rz"),
    ("///POSTYPE BASE\n///RECTAN\nP00001=1.000,2.000,3.000,0.0000,0.0000,0.0000,1.0,2.0\n",
     "7:51", "8 values here"),
    ("///POSTYPE BASE\n///RECTAN\nP00001=1.000,abc,3.000,0.0000,0.0000,0.0000\n", "7:14",
     "not a number: 'abc'"),
    ("///POSTYPE PULSE\n///PULSE\nC00000=1,2.5,3,4,5,6\n", "7:10", "joint pulses (integers)"),
    ("///POSTYPE PULSE\n///PULSE\nC00000=1,,3,4,5,6\n", "7:10", "a number is missing"),
    ("///POSTYPE SIDEWAYS\n", "5:12", "///POSTYPE is one of"),
    ("///USER x\n", "5:9", "///USER is a number"),
])
def test_a_malformed_position_is_one_error_at_its_column(tmp_path, capsys, pos, where, words):
    path = write(tmp_path, "BAD.JBI", crlf(a_job(pos)))
    before = path.read_bytes()
    for command in ("check", "frames"):
        code, out, err = cli(capsys, command, path)
        assert code == 2, (command, out, err)
        assert f"{path}:{where}:" in err and words in err, err
    assert path.read_bytes() == before


def test_bad_npos_and_a_file_that_is_not_a_job(tmp_path, capsys):
    path = write(tmp_path, "BAD.JBI", crlf(a_job("", npos="1,2")))
    code, out, err = cli(capsys, "check", path)
    assert code == 2 and f"{path}:4:9:" in err and "///NPOS is six counts" in err
    path = write(tmp_path, "NOT.JBI", b"hello\r\n")
    code, out, err = cli(capsys, "frames", path)
    assert code == 2 and f"{path}:1:1:" in err and "a job begins /JOB" in err


def test_blank_lines_before_job_read_alike_with_or_without_its_name(tmp_path, capsys):
    """Blank lines of any length before /JOB: the job is read by its name,
    by its first line where it has no name (a git temporary file), and by
    solve --robot, all alike (found by benchmarks/fuzz.py: a 16-character
    window made solve --robot refuse what check read)."""
    data = b"\xef\xbb\xbf" + b" " * 40 + b"\r\n" * 3 + crlf(a_job(
        "///TOOL 0\n///POSTYPE BASE\n///RECTAN\nC00000=1.000,2.000,3.000,0.0000,0.0000,0.0000\n",
        npos="1,0,0,0,0,0"))
    for name in ("HOME.JBI", "tmp_job"):
        assert len(parse(Document(data, name)).extra["positions"]) == 1
    path = write(tmp_path, "HOME.JBI", data)
    assert [p.name for p in read_robot(path, config=[]).poses] == ["C00000"]


def test_solve_robot_refuses_a_binary_job_as_check_does(tmp_path, capsys):
    data = crlf(a_job("")).replace(b"NOP", b"N\x13OP")
    path = write(tmp_path, "BIN.JBI", data)
    code, out, err = cli(capsys, "check", path)
    assert code == 2 and f"{path}:9:2: binary or encrypted file (byte 0x13 here)" in err
    with pytest.raises(UcsioError) as exc:
        read_robot(path, config=[])
    assert f"{path}:9:2: binary or encrypted file (byte 0x13 here)" in str(exc.value)


# -- solve --robot JOB.JBI -------------------------------------------------------------------
def fields(values) -> str:
    return ",".join([f"{v:.3f}" for v in values[:3]] + [f"{v:.4f}" for v in values[3:]])


def xyzabc(T) -> list[float]:
    """x, y, z, rx, ry, rz of a 4x4 pose, by scipy (R = Rz·Ry·Rx)."""
    return [*T[:3, 3], *Rotation.from_matrix(T[:3, :3]).as_euler("xyz", degrees=True)]


@pytest.fixture
def cell(tmp_path):
    """Cell's truth written as a Yaskawa controller would: UF2 in UFRAME.CND, the teaching
    tools UT3 (Cell's) and UT1 in TOOL.CND, the reflector UT4; points 1-4 taught as USER
    positions in UF2 with UT3, 5-8 as BASE positions with UT1, and a PULSE home C0."""
    c = Cell()
    ut1 = (5.0, -2.5, 180.25, 0.0, 90.0, 0.0)
    tools = {0: (0.0,) * 6, 1: ut1, 3: c.UT, 4: (*c.TCP, 0.0, 0.0, 0.0)}
    (tmp_path / "TOOL.CND").write_bytes(crlf("".join(
        tool(n, f"T{n}", fields(tools.get(n, (0.0,) * 6)), False) for n in range(8))))
    (tmp_path / "UFRAME.CND").write_bytes(crlf(uframe(2, "TABLE", fields(c.UF))))
    rows = ["///TOOL 3", "///USER 2", "///POSTYPE USER", "///RECTAN", RCONF.strip()]
    for i, T in enumerate(c.flanges[:4]):
        rows.append(f"P{i + 1:05d}=" + fields(xyzabc(inv(c.uf) @ T @ c.ut)))
    from fanuc_cell import pose
    rows += ["///TOOL 1", "///POSTYPE BASE"]
    for i, T in enumerate(c.flanges[4:], 5):
        rows.append(f"P{i:05d}=" + fields(xyzabc(T @ pose(*ut1))))
    rows += ["///POSTYPE PULSE", "///PULSE", "C00000=0,0,0,0,0,0"]
    (tmp_path / "MEAS.JBI").write_bytes(crlf(a_job("\n".join(rows) + "\n", npos="1,0,0,8,0,0")))
    c.names = [f"P{i + 1}" for i in range(len(c.flanges))]
    (tmp_path / "laser.txt").write_text(c.laser_text())
    c.dir = tmp_path
    return c


def test_job_positions_are_the_flange_in_the_robot_base(cell):
    d = cell.dir
    rp = read_robot(d / "MEAS.JBI", config=[str(d / "TOOL.CND"), str(d / "UFRAME.CND")])
    assert rp.format == "yaskawa"
    assert [(p.name, p.point) for p in rp.poses][:2] == [("P00001", "P1"), ("P00002", "P2")]
    for p, T in zip(rp.poses, cell.flanges):
        assert p.problem is None
        # written to 0.001 mm and 0.0001 deg: the flange within that, through 250 mm of tool
        np.testing.assert_allclose(p.flange[:3, 3], T[:3, 3], atol=2e-3)
        angle = Rotation.from_matrix(p.flange[:3, :3].T @ T[:3, :3]).magnitude()
        assert math.degrees(angle) < 2e-4
    home = rp.poses[-1]
    assert home.flange is None and "kinematics" in home.problem.message
    assert (home.problem.line, home.problem.col) == (22, 8)


def test_solve_recovers_the_ucs(cell, capsys):
    d = cell.dir
    code, out, err = cli(capsys, "solve", "--laser", d / "laser.txt", "--robot", d / "MEAS.JBI",
                         "--config", d / "TOOL.CND", "--config", d / "UFRAME.CND",
                         "--tool", f"{d / 'TOOL.CND'}:UT4", "--json")
    assert code == 0, err
    f = json.loads(out)["frame"]
    np.testing.assert_allclose([f["x"], f["y"], f["z"]], cell.ucs[:3, 3], atol=2e-3)
    R = Rotation.from_quat(np.roll(f["q"], -1)).as_matrix()
    assert math.degrees(Rotation.from_matrix(R.T @ cell.ucs[:3, :3]).magnitude()) < 1e-3


def test_a_paired_pulse_is_refused_at_its_line(cell, capsys):
    d = cell.dir
    with open(d / "laser.txt", "a") as f:
        f.write("C0 1.0 2.0 3.0\n")
    code, out, err = cli(capsys, "solve", "--laser", d / "laser.txt", "--robot", d / "MEAS.JBI",
                         "--config", d / "TOOL.CND", "--config", d / "UFRAME.CND", "--tcp",
                         "0,0,100")
    assert code == 2 and f"{d / 'MEAS.JBI'}:22:8:" in err
    assert "joint pulses" in err and "kinematics" in err


@pytest.mark.parametrize("configs, where, words", [
    ([], "10:8", "give --config UFRAME.CND"),
    (["TOOL.CND"], "10:8", "give --config UFRAME.CND"),
    (["UFRAME.CND"], "10:8", "give --config TOOL.CND"),
])
def test_missing_tools_or_user_frames_are_one_clear_error(cell, capsys, configs, where, words):
    d = cell.dir
    opts = [a for c in configs for a in ("--config", d / c)]
    code, out, err = cli(capsys, "solve", "--laser", d / "laser.txt", "--robot", d / "MEAS.JBI",
                         *opts, "--tcp", "0,0,100")
    assert code == 2 and f"{d / 'MEAS.JBI'}:{where}:" in err and words in err, err


def test_a_tool_or_user_frame_the_files_do_not_hold(cell, capsys):
    d = cell.dir
    text = (d / "MEAS.JBI").read_bytes()
    (d / "MEAS.JBI").write_bytes(text.replace(b"///TOOL 1", b"///TOOL 9"))
    rp = read_robot(d / "MEAS.JBI", config=[str(d / "TOOL.CND"), str(d / "UFRAME.CND")])
    assert "does not hold UT9" in rp.poses[4].problem.message
    (d / "MEAS.JBI").write_bytes(text.replace(b"///USER 2", b"///USER 5"))
    rp = read_robot(d / "MEAS.JBI", config=[str(d / "TOOL.CND"), str(d / "UFRAME.CND")])
    assert "does not hold UF5" in rp.poses[0].problem.message
    assert rp.poses[4].problem is None          # a BASE position needs no user frame


def test_config_of_another_kind_and_one_config_for_other_vendors(cell, tmp_path, capsys):
    d = cell.dir
    code, out, err = cli(capsys, "solve", "--laser", d / "laser.txt", "--robot", d / "MEAS.JBI",
                         "--config", d / "MEAS.JBI", "--tcp", "0,0,100")
    assert code == 2 and "take TOOL.CND" in err and "this is a job" in err
    va = FIXTURES / "fanuc" / "sysframe_comment.va"
    ls = FIXTURES / "fanuc" / "program_frames.ls"
    code, out, err = cli(capsys, "solve", "--laser", d / "laser.txt", "--robot", ls,
                         "--config", va, "--config", va, "--tcp", "0,0,100")
    assert code == 2 and "--config given 2 times: FANUC's positions take one file" in err


# -- diff --points ---------------------------------------------------------------------------
def moved(sim, meas, xyz) -> float:
    """How far a point written in a frame moves from the simulated to the measured frame:
    scipy's rotations, not ucsio's."""
    def world(frame):
        x, y, z, rx, ry, rz = frame
        R = Rotation.from_euler("xyz", [rx, ry, rz], degrees=True)
        return R.apply(xyz) + np.array([x, y, z])
    return float(np.linalg.norm(world(meas) - world(sim)))


def solution(tmp_path, x, y, z, rx, ry, rz):
    path = tmp_path / "S.json"
    path.write_text(json.dumps({"frame": {"x": x, "y": y, "z": z, "a": rz, "b": ry, "c": rx},
                                "accepted": True}))
    return path


def test_points_taught_in_uf2_of_the_backups_jobs(tmp_path, capsys):
    shutil.copytree(BACKUP, tmp_path / "backup")
    sim = (1200.0, 300.0, 150.0, 0.0, 0.0, 90.0)
    meas = (1200.5, 299.75, 150.25, 0.02, -0.03, 90.1)
    s = solution(tmp_path, *meas)
    code, out, err = cli(capsys, "diff", tmp_path / "backup" / "UFRAME.CND", "--frame", "UF2",
                         "--measured", s, "--points", "--json")
    assert code == 0, err
    d = json.loads(out)
    rows = {r["name"]: r for r in d["points"]}
    assert set(rows) == {"P00010", "P00011", "P00012"}       # not UF1's P00013, not HOME's
    assert rows["P00012"]["file"].endswith("WELD.JBI") and rows["P00012"]["line"] == 18
    for name, xyz in (("P00010", (0, 0, 50)), ("P00011", (800, 0, 50)),
                      ("P00012", (800, 600, 50))):
        assert rows[name]["moved"] == pytest.approx(moved(sim, meas, xyz), abs=1e-9)
    # WELD's pulse C00000 and base C00001; HOME.JBI does not use UF2
    assert d["points_skipped"] == 2
    code, out, err = cli(capsys, "diff", tmp_path / "backup" / "UFRAME.CND", "--frame", "UF2",
                         "--measured", s, "--points")
    assert "taught points in UF2: 3" in out
    assert "2 PULSE, BASE or ROBOT positions of the jobs that use UF2 skipped" in out


def test_cut_only_beside_its_uframe(tmp_path, capsys):
    (tmp_path / "UFRAME.CND").write_bytes(corpus_file("yaskawa", "UFRAME.CND").read_bytes())
    (tmp_path / "CUT_ONLY.JBI").write_bytes(corpus_file("yaskawa", "CUT_ONLY.JBI").read_bytes())
    uf1 = parse(Document.read(tmp_path / "UFRAME.CND")).frame("UF1")
    sim = tuple(uf1.numbers[k].value for k in ("x", "y", "z", "rx", "ry", "rz"))
    meas = (sim[0] + 0.4, sim[1] - 0.2, sim[2], sim[3], sim[4] + 0.05, sim[5] - 0.1)
    code, out, err = cli(capsys, "diff", tmp_path / "UFRAME.CND", "--frame", "UF1", "--measured",
                         solution(tmp_path, *meas), "--points", "--json")
    assert code == 0, err
    d = json.loads(out)
    assert sorted(r["name"] for r in d["points"]) == [f"P0010{i}" for i in range(5, 10)]
    assert d["points_skipped"] == 1                                 # P00100, a BASE point
    p105 = next(r for r in d["points"] if r["name"] == "P00105")
    assert p105["moved"] == pytest.approx(moved(sim, meas, (216.374, -55.365, 150.0)), abs=1e-9)


def test_patch_warning_names_the_jobs_positions_in_the_frame(tmp_path, capsys):
    shutil.copytree(BACKUP, tmp_path / "backup")
    s = solution(tmp_path, 1200.5, 300.0, 150.0, 0.0, 0.0, 90.0)
    code, out, err = cli(capsys, "patch", tmp_path / "backup" / "UFRAME.CND", "--frame", "UF2",
                         "--measured", s)
    assert code == 0, err
    assert "////RXY) no longer produce this frame" in err
    assert "3 positions of the backup's jobs (" in err and "WELD.JBI) are taught in UF2" in err


def test_a_user_frame_on_another_user_frame_goes_through_it(cell):
    """UF2 defined on UF1 (///BASICFRM 1,19,1): its numbers are in UF1, and the flange
    is UF1 · UF2 · P · tool⁻¹; UF1 and UF2 on each other is refused, not looped."""
    from fanuc_cell import pose
    d = cell.dir
    uf1 = pose(400.0, -250.0, 30.0, 1.5, -2.0, 35.0)
    uf2_in_uf1 = xyzabc(inv(uf1) @ cell.uf)
    (d / "UFRAME.CND").write_bytes(crlf(uframe(1, "BASE1", fields(xyzabc(uf1)))
                                        + uframe(2, "ON1", fields(uf2_in_uf1), "1,19,1")))
    configs = [str(d / "TOOL.CND"), str(d / "UFRAME.CND")]
    rp = read_robot(d / "MEAS.JBI", config=configs)
    for p, T in zip(rp.poses[:4], cell.flanges):
        np.testing.assert_allclose(p.flange[:3, 3], T[:3, 3], atol=3e-3)
    (d / "UFRAME.CND").write_bytes(crlf(uframe(1, "A", fields(xyzabc(uf1)), "1,19,2")
                                        + uframe(2, "B", fields(uf2_in_uf1), "1,19,1")))
    rp = read_robot(d / "MEAS.JBI", config=configs)
    assert "in a circle (UF2 on UF1 on UF2)" in rp.poses[0].problem.message


def test_a_jobs_positions_name_their_own_tool_and_frame(cell, capsys):
    d = cell.dir
    code, out, err = cli(capsys, "solve", "--laser", d / "laser.txt", "--robot", d / "MEAS.JBI",
                         "--config", d / "TOOL.CND", "--robot-tool", "UT3", "--tcp", "0,0,100")
    assert code == 2 and "name their own (///TOOL n, ///USER k)" in err
