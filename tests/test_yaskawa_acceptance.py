"""Issue 27 (Yaskawa) as its users judge it: the defects an acceptance
test found, each with its minimal reproducer.

Fixtures are written here in the corpus's style (CRLF); numbers are checked
against scipy's Rotation (R = Rz(rz)·Ry(ry)·Rx(rx), ``from_euler('xyz')``).
"""
from __future__ import annotations

import json
import math

import numpy as np
from scipy.spatial.transform import Rotation

from test_yaskawa import cli, crlf, uframe, write
from test_yaskawa_patch import solution
from ucsio.geometry.frames import Pose

RCONF = "///RCONF 0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n"
INST = "//INST\n///DATE 2026/11/30 09:12\n///ATTR SC,RW\n///GROUP1 RB1\nNOP\nEND\n"
UF1 = (1200.0, -300.0, 150.0, 2.0, -3.0, 30.0)
UF2_ON_UF1 = (100.0, 50.0, 20.0, 0.0, 5.0, -20.0)


def six(values) -> str:
    return "%.3f,%.3f,%.3f,%.4f,%.4f,%.4f" % tuple(values)


def matrix(x, y, z, rx, ry, rz) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = Rotation.from_euler("xyz", [rx, ry, rz], degrees=True).as_matrix()
    m[:3, 3] = (x, y, z)
    return m


def pose_of(m: np.ndarray) -> Pose:
    q = Rotation.from_matrix(m[:3, :3]).as_quat()            # x, y, z, w
    return Pose.from_quat(*m[:3, 3], (q[3], q[0], q[1], q[2]))


# -- taught points of a frame that another frame is defined on -------------------------------
def frame_on_frame_backup(tmp_path):
    """UF2 defined on UF1 (///BASICFRM 1,19,1); a job with one position in UF1
    and one in UF2."""
    write(tmp_path, "UFRAME.CND", crlf(uframe(1, "TABLE", six(UF1))
                                       + uframe(2, "FIXTURE", six(UF2_ON_UF1), "1,19,1")))
    pos = ("///TOOL 0\n///USER 1\n///POSTYPE USER\n///RECTAN\n" + RCONF
           + "C00000=10.000,20.000,30.000,0.0000,0.0000,0.0000\n"
           + "///USER 2\nC00001=300.000,-40.000,5.000,0.0000,0.0000,0.0000\n")
    write(tmp_path, "PLACE.JBI", crlf("/JOB\n//NAME PLACE\n//POS\n///NPOS 2,0,0,0,0,0\n"
                                      + pos + INST))
    return tmp_path / "UFRAME.CND"


def test_positions_in_a_frame_defined_on_the_measured_one_move_with_it(tmp_path, capsys):
    """UF2 is defined on UF1: when UF1 turns by 1 deg about its z, a position
    taught in UF2 moves with it (the controller keeps UF2 in UF1), by
    2·|q_xy|·sin(0.5 deg), q the point in UF1's coordinates."""
    cnd = frame_on_frame_backup(tmp_path)
    turned = matrix(*UF1) @ matrix(0, 0, 0, 0, 0, 1)
    measured = solution(tmp_path, pose_of(turned))
    code, out, err = cli(capsys, "diff", cnd, "--frame", "UF1", "--measured", measured,
                         "--points", "--json")
    assert code == 0, err
    moved = {p["name"]: p["moved"] for p in json.loads(out)["points"]}
    in_uf1 = {"C00000": np.array([10.0, 20.0, 30.0]),
              "C00001": (matrix(*UF2_ON_UF1) @ [300.0, -40.0, 5.0, 1.0])[:3]}
    for name, p in in_uf1.items():
        want = 2 * math.hypot(p[0], p[1]) * math.sin(math.radians(0.5))
        assert math.isclose(moved[name], want, rel_tol=1e-9), name
    # and patch's warning counts both
    code, out, err = cli(capsys, "patch", cnd, "--frame", "UF1", "--measured", measured)
    assert code == 0 and "2 positions of the backup's jobs" in err


# -- program: the P variables of the job it replaces -------------------------------------------
def a_var_dat(tmp_path, rows_used: int, rows: int):
    used = '"RECTAN"0,0,4,000000000000000000000000,0,16,1.000,2.000,3.000,0.0000,0.0000,0.0000,0.0000,0.0000\n'
    write(tmp_path, "VAR.DAT", crlf("//VAR\n///P\n" + used * rows_used
                                    + '"UNUSED"\n' * (rows - rows_used)))
    return tmp_path / "VAR.DAT"


def mframe_line(path) -> str:
    return next(line for line in path.read_text().splitlines() if line.startswith("MFRAME"))


def test_program_run_again_takes_the_same_p_variables(tmp_path, capsys):
    """The job being replaced (-o) is not the cell's: running the demo's
    replay in its folder wrote P122-P124 instead of the P125-P127 it said,
    as the previous SETUF2.JBI counted as a user of P125-P127. A folder
    named like a job beside VAR.DAT is no job (it stopped the run)."""
    var = a_var_dat(tmp_path, 4, 12)
    measured = solution(tmp_path, Pose.from_abc(900.0, 200.0, 300.0, 35.0, -20.0, 10.0))
    (tmp_path / "OLD.JBI").mkdir()
    out = tmp_path / "SETUF2.JBI"
    for _ in range(2):
        code, _, err = cli(capsys, "program", measured, "--frame", "UF2", "--var", var,
                           "-o", out)
        assert code == 0, err
        assert mframe_line(out) == "MFRAME UF#(2) P009 P010 P011"
    # another job beside that uses them still counts
    (tmp_path / "KEEP.JBI").write_bytes(out.read_bytes().replace(b"SETUF2", b"KEEP"))
    code, _, err = cli(capsys, "program", measured, "--frame", "UF2", "--var", var, "-o", out)
    assert code == 0, err
    assert mframe_line(out) == "MFRAME UF#(2) P006 P007 P008"


# -- solve --robot: a user frame of another robot ---------------------------------------------
def test_a_user_frame_of_another_robot_is_refused_at_the_position(tmp_path):
    """UF1 belongs to robot 2 (///GROUP 0,1,...): a position of an RB1 job
    in it was composed as if UF1 stood in robot 1's base, a wrong flange
    pose without a word. Refused at its line:col; an RB2 job reads it."""
    from test_yaskawa import GROUP2, tool
    from ucsio.readers.robot import read_robot
    write(tmp_path, "UFRAME.CND", crlf(uframe(1, "R2 TABLE", six(UF1), group=GROUP2)))
    write(tmp_path, "TOOL.CND", crlf(tool(0, "", six([0] * 6), False)))
    pos = ("///TOOL 0\n///USER 1\n///POSTYPE USER\n///RECTAN\n" + RCONF
           + "C00000=10.000,20.000,30.000,0.0000,0.0000,0.0000\n")
    configs = [str(tmp_path / "TOOL.CND"), str(tmp_path / "UFRAME.CND")]
    for robot, problem in (("RB1", "is robot 2's user frame"), ("RB2", None)):
        job = "/JOB\n//NAME M\n//POS\n///NPOS 1,0,0,0,0,0\n" + pos + INST.replace("RB1", robot)
        write(tmp_path, "M.JBI", crlf(job))
        got = read_robot(tmp_path / "M.JBI", config=configs).poses[0].problem
        if problem is None:
            assert got is None
        else:
            assert problem in got.message and (got.line, got.col) == (10, 8)


# -- diff of two files: rx, ry, rz are the rotation ----------------------------------------
def test_rx_180_and_minus_180_are_one_frame(tmp_path, capsys):
    """rx 180 and rx -180 are one rotation: the diff listed `rx: 180 -> -180`
    as a change of the frame (and rounded others with %g: `rz: -179.999`)."""
    for name, rx in (("a.CND", "180.0000"), ("b.CND", "-180.0000")):
        write(tmp_path, name, crlf(uframe(1, "TABLE", f"1200.000,-300.000,150.000,{rx},"
                                          "-3.0000,-179.9991")))
    code, out, err = cli(capsys, "diff", tmp_path / "a.CND", tmp_path / "b.CND", "--json")
    assert code == 0, err
    assert json.loads(out)["changed"] == []
    write(tmp_path, "b.CND", crlf(uframe(1, "TABLE", "1200.000,-300.000,150.000,180.0000,"
                                         "-3.0000,-0.4335")))
    code, out, err = cli(capsys, "diff", tmp_path / "a.CND", tmp_path / "b.CND")
    assert "~ UF1 \"TABLE\" (UFRAME): value changed" in out and "rz:" not in out
    assert "rz -179.9991" in out


# -- patch of an LF-only UFRAME.CND ---------------------------------------------------------
def test_patch_of_an_lf_only_uframe_cnd_says_it_will_not_load(tmp_path, capsys):
    """The patch keeps the file's LF endings (every other byte stays), and
    said nothing although such a UFRAME.CND loads on the controller as
    empty: it warns as check does."""
    lf = uframe(1, "TABLE", six(UF1)).encode()
    write(tmp_path, "UFRAME.CND", lf)
    out = tmp_path / "OUT.CND"
    code, _, err = cli(capsys, "patch", tmp_path / "UFRAME.CND", "--frame", "UF1", "--set",
                       "1,2,3,0,0,0", "-o", out)
    assert code == 0 and "lf-only" in err and "load on the controller as empty" in err
    assert b"\r" not in out.read_bytes()
    write(tmp_path, "UFRAME.CND", crlf(uframe(1, "TABLE", six(UF1))))
    code, _, err = cli(capsys, "patch", tmp_path / "UFRAME.CND", "--frame", "UF1", "--set",
                       "1,2,3,0,0,0", "-o", tmp_path / "OUT2.CND")
    assert code == 0 and "lf-only" not in err


# -- diff --measured of a frame on a frame: its deltas, in Yaskawa's names --------------------
def test_measured_diff_of_a_frame_on_a_frame_in_yaskawa_angles(tmp_path, capsys):
    """UF2 on UF1, measured turned by 1 deg about its own z: the diff is in UF1
    (scipy: the measured pose in UF1, its xyz Euler angles), and --json names
    the deltas as the table does (drx dry drz beside SPEC's dc db da)."""
    cnd = frame_on_frame_backup(tmp_path)
    turned = matrix(*UF1) @ matrix(*UF2_ON_UF1) @ matrix(0, 0, 0, 0, 0, 1)
    code, out, err = cli(capsys, "diff", cnd, "--frame", "UF2", "--measured",
                         solution(tmp_path, pose_of(turned)), "--json")
    assert code == 0, err
    d = json.loads(out)
    in_uf1 = matrix(*UF2_ON_UF1) @ matrix(0, 0, 0, 0, 0, 1)
    want = Rotation.from_matrix(in_uf1[:3, :3]).as_euler("xyz", degrees=True) - UF2_ON_UF1[3:]
    got = [d["drx"], d["dry"], d["drz"]]
    assert np.allclose(got, want, atol=1e-9) and got == [d["dc"], d["db"], d["da"]]
    assert math.isclose(d["angle"], 1.0, abs_tol=1e-9) and d["dist"] < 1e-9


# -- check: a frame on a user frame that is not there -----------------------------------------
def test_a_frame_on_a_missing_or_circular_user_frame_is_a_finding(tmp_path, capsys):
    """UF2 on UF7 (not in the file) or UF1 and UF2 on each other: `check`
    said nothing, the tree put them under "the file does not say"."""
    write(tmp_path, "UFRAME.CND", crlf(uframe(1, "A", six(UF1), "1,19,2")
                                       + uframe(2, "B", six(UF2_ON_UF1), "1,19,1")
                                       + uframe(3, "C", six(UF2_ON_UF1), "1,19,7")
                                       + uframe(4, "D", six(UF1))
                                       + uframe(5, "E", six(UF2_ON_UF1), "1,19,4")))
    code, out, err = cli(capsys, "check", tmp_path / "UFRAME.CND", "--json")
    assert code == 1
    found = [(f["line"], f["message"]) for f in json.loads(out)["files"][0]["lints"]
             if f["code"] == "basicfrm-parent"]
    assert found == [
        (1, "UF1: defined on user frames in a circle (UF1 on UF2 on UF1): its parent is not "
            "known"),
        (12, "UF2: defined on user frames in a circle (UF2 on UF1 on UF2): its parent is not "
             "known"),
        (23, "UF3: defined on UF7 (///BASICFRM 1,19,7), which this file does not hold: its "
             "parent is not known")]


# -- patch TOOL.CND: the ///CRC lines are the file's ------------------------------------------
def test_a_tool_without_its_crc_line_in_a_file_with_crc_is_refused(tmp_path, capsys):
    """UT1 has lost its ///CRC line, UT0 has one: the file carries checksums
    the controller checks, so UT1 is refused too, at the file's ///CRC line,
    and nothing is written."""
    from test_yaskawa import tool
    data = crlf(tool(0, "GUN", six([0, 0, 365.4, 0, 0, 0]), True)
                + tool(1, "SMR", six([0, 0, 100, 0, 0, 0]), False))
    write(tmp_path, "TOOL.CND", data)
    measured = solution(tmp_path, Pose.from_abc(0, 0, 0, 0, 0, 0), tcp=(1.0, 2.0, 300.0))
    code, _, err = cli(capsys, "patch", tmp_path / "TOOL.CND", "--frame", "UT1", "--measured",
                       measured, "--in-place")
    assert code == 2 and "TOOL.CND:2:1: UT1: this TOOL.CND carries a ///CRC checksum" in err
    assert (tmp_path / "TOOL.CND").read_bytes() == data
    assert sorted(p.name for p in tmp_path.iterdir()) == ["S.json", "TOOL.CND"]
