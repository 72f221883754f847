"""Issue 19 point 5: measurements from FANUC files. `solve --robot prog.ls
--config sysframe.va`: each Cartesian /POS position, taught in UF u with
UT t, is the flange in world UF[u]·P·UT[t]⁻¹; posreg.va's Cartesian
registers the same way (their frames given by --robot-wobj/--robot-tool);
--tool sysframe.va:UTk gives the TCP. The cell is synthetic truth
(tests/fanuc_cell.py, scipy's Rotation the reference); the corpus programs
and registers must all read."""
from __future__ import annotations

import json
import re

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from conftest import CORPUS, corpus_file, corpus_files
from fanuc_cell import Cell, inv, pose, position, program, registers, wpr
from ucsio import api
from ucsio.cli import main
from ucsio.errors import UcsioError
from ucsio.readers.measurement import read_measurement
from ucsio.method.solve import solve
from ucsio.readers.laser import read_laser
from ucsio.readers.pairing import pair
from ucsio.readers.robot import read_robot

UB = "irbzavalagit__UB10200_RBT01__"


def cli(capsys, *args):
    code = main([str(a) for a in args])
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.fixture
def cell(tmp_path):
    c = Cell()
    (tmp_path / "sysframe.va").write_text(c.sysframe_text(), newline="")
    pts = [position(i + 1, [(1, 2, 3, v)], comment=nm)
           for i, (nm, v) in enumerate(zip(c.names, c.taught()))]
    # a joint position and a point of another frame that the laser file does not name
    pts.append(position(20, [(1, 2, 3, {"J1": 10, "J2": -20, "J3": 30, "J4": 0, "J5": -90,
                                        "J6": 0})], comment="HOME"))
    (tmp_path / "meas.ls").write_text(program("MEAS", pts), newline="")
    (tmp_path / "laser.txt").write_text(c.laser_text())
    c.dir = tmp_path
    return c


def merged_csv(path, cell):
    """SPEC's CSV of the same flange poses, robot_w/p/r by scipy."""
    rows = ["point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_w,robot_p,robot_r"]
    for nm, L, T in zip(cell.names, cell.laser, cell.flanges):
        rows.append(",".join([nm] + [repr(float(v)) for v in (*L, *wpr(T))]))
    path.write_text("\n".join(rows) + "\n")
    return path


def test_program_positions_are_the_flange_in_world(cell):
    rp = read_robot(cell.dir / "meas.ls", config=str(cell.dir / "sysframe.va"))
    assert rp.format == "fanuc" and rp.form == "fanuc"
    assert [p.name for p in rp.poses][:2] == ["P[1]", "P[2]"]
    assert (rp.poses[0].point, rp.poses[0].aliases) == ("M1", ("P1",))
    for p, T in zip(rp.poses, cell.flanges):
        np.testing.assert_allclose(p.flange, T, atol=2e-5)     # 6 decimals written
    home = rp.poses[-1]
    assert home.flange is None and "joint position" in home.problem.message


def test_solve_recovers_the_ucs_and_equals_the_merged_csv(cell, capsys):
    d = cell.dir
    code, out, err = cli(capsys, "solve", "--laser", d / "laser.txt", "--robot", d / "meas.ls",
                         "--config", d / "sysframe.va", "--tool", f"{d / 'sysframe.va'}:UT4",
                         "--json")
    assert code == 0, err
    got = json.loads(out)
    f = got["frame"]
    np.testing.assert_allclose([f["x"], f["y"], f["z"]], cell.ucs[:3, 3], atol=1e-3)
    R = Rotation.from_euler("ZYX", [f["a"], f["b"], f["c"]], degrees=True).as_matrix()
    assert Rotation.from_matrix(R.T @ cell.ucs[:3, :3]).magnitude() < np.radians(1e-5)
    assert got["rms"] < 1e-3
    # the joint position is not a measurement point: listed, not an error
    assert "robot positions without a laser point: P[20]" in err
    # the same numbers through SPEC's CSV (robot_w/p/r): the same frame
    want = solve(read_measurement(merged_csv(d / "merged.csv", cell)), Cell.TCP)
    meas, _ = pair(read_laser(d / "laser.txt"),
                   read_robot(d / "meas.ls", config=str(d / "sysframe.va")))
    sol = solve(meas, Cell.TCP)
    np.testing.assert_allclose(sol.pose.t, want.pose.t, atol=1e-4)
    np.testing.assert_allclose(sol.pose.matrix, want.pose.matrix, atol=1e-8)


def test_points_pair_by_p_n_by_comment_and_as_pn(cell, tmp_path):
    c = cell
    laser = tmp_path / "by_number.txt"
    laser.write_text("".join(f"{nm} {x} {y} {z}\n" for nm, (x, y, z) in
                             zip(["P[1]", "p2", "P3", "M4", "m5", "P6", "P7", "P8"], c.laser)))
    meas, warnings = pair(read_laser(laser), read_robot(c.dir / "meas.ls",
                                                        config=str(c.dir / "sysframe.va")))
    assert meas.names == ["P[1]", "p2", "P3", "M4", "m5", "P6", "P7", "P8"]
    for T, F in zip(c.flanges, meas.flange):
        np.testing.assert_allclose(F, T, atol=2e-5)


def test_a_frame_the_sysframe_does_not_hold_is_file_line_col(cell, capsys):
    d = cell.dir
    text = (d / "meas.ls").read_bytes().decode()
    bad = text.replace("UF : 2, UT : 3", "UF : 12, UT : 3", 1)       # ARRAY[2,9]: no UF12
    (d / "meas.ls").write_text(bad, newline="")
    line = bad[:bad.index("UF : 12")].count("\n") + 1
    col = bad.index("UF : 12") - bad.rfind("\n", 0, bad.index("UF : 12")) + len("UF : ")
    code, out, err = cli(capsys, "solve", "--laser", d / "laser.txt", "--robot", d / "meas.ls",
                         "--config", d / "sysframe.va", "--tcp", "0,0,0")
    assert code == 2 and out == ""
    assert f"meas.ls:{line}:{col}: P[1]: UF : 12, but " in err and "does not hold UF12" in err
    assert len(err.strip().splitlines()) == 1


def test_a_joint_position_used_as_a_point_is_file_line_col(cell, capsys):
    d = cell.dir
    (d / "laser.txt").write_text(cell.laser_text() + "HOME 1 2 3\n")
    code, out, err = cli(capsys, "solve", "--laser", d / "laser.txt", "--robot", d / "meas.ls",
                         "--config", d / "sysframe.va", "--tcp", "0,0,0", "-o", d / "s.json")
    text = (d / "meas.ls").read_bytes().decode()
    line = text[:text.index('P[20:"HOME"]')].count("\n") + 2        # its GP1: line
    assert code == 2 and f"meas.ls:{line}:4: P[20]: a joint position" in err
    assert not (d / "s.json").exists()


def test_config_needed_where_a_frame_is_not_0_and_must_be_fanuc(cell, tmp_path):
    d = cell.dir
    with pytest.raises(UcsioError) as e:
        pair(read_laser(d / "laser.txt"), read_robot(d / "meas.ls"))
    assert "give --config sysframe.va" in e.value.message and e.value.col is not None
    kuka = tmp_path / "$config.dat"
    kuka.write_text("DEFDAT $CONFIG\nFRAME BASE_DATA[2]\nENDDAT\n")
    with pytest.raises(UcsioError) as e:
        pair(read_laser(d / "laser.txt"), read_robot(d / "meas.ls", config=str(kuka)))
    assert "a KUKA file" in e.value.message
    # UF 0 and UT 0: the numbers are the flange in world, no config needed
    pts = [position(i + 1, [(1, 0, 0, wpr(T))], comment=nm)
           for i, (nm, T) in enumerate(zip(cell.names, cell.flanges))]
    (tmp_path / "world.ls").write_text(program("WORLD", pts))
    rp = read_robot(tmp_path / "world.ls")
    for p, T in zip(rp.poses, cell.flanges):
        np.testing.assert_allclose(p.flange, T, atol=2e-5)


def test_a_group_2_only_position_and_stars_are_refused_with_reasons(tmp_path):
    pts = [position(1, [(2, 0, 0, (1, 2, 3, 0, 0, 0))]),
           re.sub(r"Y = +2\.000000", "Y = ********", position(2, [(1, 0, 0, (1, 2, 3, 0, 0, 0))])),
           position(3, [(1, 0, 0, (1, 2, 3, 0, 0, 0)), (2, 0, 0, {"J1": -100})])]
    (tmp_path / "p.ls").write_text(program("P", pts))
    rp = read_robot(tmp_path / "p.ls")
    assert "no group 1 (GP1)" in rp.poses[0].problem.message
    assert "Y not a number (********)" in rp.poses[1].problem.message
    np.testing.assert_allclose(rp.poses[2].flange[:3, 3], [1, 2, 3])     # GP2 ignored


def test_tool_from_sysframe(cell):
    from ucsio.commands.solve import tool_tcp
    assert tool_tcp(f"{cell.dir / 'sysframe.va'}:UT4") == Cell.TCP
    assert tool_tcp(f"{cell.dir / 'sysframe.va'}:ut4") == Cell.TCP
    with pytest.raises(UcsioError) as e:
        tool_tcp(f"{cell.dir / 'sysframe.va'}:UF2")
    assert "not a robot-held tool" in e.value.message


# ------------------------------------------------------------------ posreg.va

def test_posreg_registers_in_world_and_in_given_frames(cell, tmp_path, capsys):
    c = cell
    world = [(1, i + 1, nm, wpr(T)) for i, (nm, T) in enumerate(zip(c.names, c.flanges))]
    extra = [(1, 15, "Home", {"J1": 0, "J2": 0, "J3": 0, "J4": 0, "J5": -90, "J6": 0}),
             (1, 16, "Reserved", None), (2, 1, "M1", (9, 9, 9, 0, 0, 0))]
    (tmp_path / "posreg.va").write_text(registers(world + extra), newline="")
    rp = read_robot(tmp_path / "posreg.va")
    assert [p.name for p in rp.poses] == [f"PR[{i}]" for i in range(1, 9)] + ["PR[15]"]
    meas, warnings = pair(read_laser(c.dir / "laser.txt"), rp)
    for T, F in zip(c.flanges, meas.flange):
        np.testing.assert_allclose(F, T, atol=1e-3)       # 3 decimals written
    assert any("UF 0, UT 0" in w for w in warnings)
    assert "robot positions without a laser point: PR[15]" in warnings
    # taken in UF2 with UT3: --robot-wobj UF2 --robot-tool UT3 --config sysframe.va
    inframe = [(1, i + 1, nm, v) for i, (nm, v) in enumerate(zip(c.names, c.taught()))]
    (tmp_path / "posreg2.va").write_text(registers(inframe), newline="")
    rp2 = read_robot(tmp_path / "posreg2.va", config=str(c.dir / "sysframe.va"), tool="UT3",
                     wobj="UF2")
    for p, T in zip(rp2.poses, c.flanges):
        np.testing.assert_allclose(p.flange, T, atol=5e-3)
    code, out, err = cli(capsys, "solve", "--laser", c.dir / "laser.txt", "--robot",
                         tmp_path / "posreg2.va", "--robot-wobj", "UF2", "--robot-tool", "UT3",
                         "--config", c.dir / "sysframe.va", "--tcp", ",".join(map(str, Cell.TCP)),
                         "--json")
    assert code == 0, err
    f = json.loads(out)["frame"]
    np.testing.assert_allclose([f["x"], f["y"], f["z"]], c.ucs[:3, 3], atol=0.02)
    with pytest.raises(UcsioError) as e:
        read_robot(tmp_path / "posreg2.va", wobj="UF2")
    assert "--robot-wobj: UF2: give --config" in e.value.message
    with pytest.raises(UcsioError) as e:
        read_robot(tmp_path / "posreg2.va", wobj="wobjTable")
    assert "UFk" in e.value.message
    # a joint register used as a point: file:line:col
    (c.dir / "l2.txt").write_text(c.laser_text() + "Home 1 2 3\n")
    with pytest.raises(UcsioError) as e:
        pair(read_laser(c.dir / "l2.txt"), rp)
    # line 1 the head, 8 registers of 4 lines, 6 Uninitialized: [1,15] on line 40
    assert (e.value.line, e.value.col) == (40, 5) and "joint position" in e.value.message


def test_a_va_that_is_not_posreg_is_refused(cell):
    with pytest.raises(UcsioError) as e:
        read_robot(cell.dir / "sysframe.va")
    assert "no position registers" in e.value.message


def test_the_frames_of_a_program_are_its_own(cell):
    with pytest.raises(UcsioError) as e:
        read_robot(cell.dir / "meas.ls", config=str(cell.dir / "sysframe.va"), wobj="UF2")
    assert "give their own UF and UT" in e.value.message


# ------------------------------------------------------------------ batch, plan, api

def test_batch_entry_names_fanuc_files(cell, capsys):
    d = cell.dir
    (d / "m.toml").write_text(
        '[[entry]]\nname = "R1 UF2"\nlaser = "laser.txt"\nrobot = "meas.ls"\n'
        'config = "sysframe.va"\ntool = "sysframe.va:UT4"\ncontroller = "sysframe.va"\n'
        'frame = "UF2"\ntolerance = 5.0\npoints = true\n')
    code, out, err = cli(capsys, "batch", d / "m.toml", "--json")
    assert code == 0, (out, err)
    e = json.loads(out)["entries"][0]
    assert e["accepted"] and e["pass"] and "error" not in e
    # simulated UF2 vs the measured UCS: the offset the cell was built with
    assert abs(e["dt_mean"] - np.mean(np.abs(cell.ucs[:3, 3] - cell.uf[:3, 3]))) < 1e-3
    assert e["points_moved"]["count"] == 8
    # --patch-dir: the listing's reviewed copy, said to be one (as patch says)
    code, out, err = cli(capsys, "batch", d / "m.toml", "--json", "--patch-dir", d / "out")
    assert code == 0, (out, err)
    e = json.loads(out)["entries"][0]
    assert e["patched"] and any("does not load .va files" in w for w in e["warnings"])
    original = (d / "sysframe.va").read_bytes().splitlines()
    copy = (d / "out" / "sysframe.va").read_bytes().splitlines()
    assert len(copy) == len(original) and sum(a != b for a, b in zip(original, copy)) == 2


def test_plan_with_a_fanuc_program_and_taught_points(cell, capsys):
    d = cell.dir
    plan = d / "plan.csv"
    plan.write_text("point,laser_x,laser_y,laser_z\n" + "".join(
        f"{nm},{x},{y},{z}\n" for nm, (x, y, z) in zip(cell.names, cell.laser)))
    code, out, err = cli(capsys, "plan", plan, "--robot", d / "meas.ls", "--config",
                         d / "sysframe.va", "--tcp", "solve", "--json")
    assert code in (0, 1), err
    r = json.loads(out)
    assert r["planned"] == 8 and "tcp_at_95" in r
    for at in (d / "sysframe.va", d):
        code, out, err = cli(capsys, "plan", plan, "--at-taught", at, "--frame", "UF2",
                             "--tcp", "0,0,0", "--json")
        assert code in (0, 1), err
        r = json.loads(out)
        assert sorted(w["name"] for w in r["working_points"]) == sorted(
            f"P[{i}]" for i in range(1, 9))
        # the working points are the positions' X, Y, Z in UF2, the UCS
        xyz = {w["name"]: (w["x"], w["y"], w["z"]) for w in r["working_points"]}
        np.testing.assert_allclose(xyz["P[3]"], cell.taught()[2][:3], atol=1e-5)


def test_api_solve_and_taught_points(cell):
    d = cell.dir
    res = api.solve(laser=d / "laser.txt", robot=d / "meas.ls", config=d / "sysframe.va",
                    tool=f"{d / 'sysframe.va'}:UT4")
    np.testing.assert_allclose([res.frame["x"], res.frame["y"], res.frame["z"]],
                               cell.ucs[:3, 3], atol=1e-3)
    tp = api.taught_points(d / "sysframe.va", "UF2", res)
    assert tp.points_moved["count"] == 8 and tp.points_skipped == 1


# ------------------------------------------------------------------ the corpus

CORPUS_POSITIONS = [p for p in corpus_files("fanuc") if p.values[0] is None
                    or p.values[0].suffix.lower() == ".ls" or "posreg" in p.values[0].name.lower()]


@pytest.mark.parametrize("path", CORPUS_POSITIONS)
def test_every_corpus_position_is_a_pose_or_a_clear_reason(path):
    config = None
    if path.name.startswith(UB):
        config = str(CORPUS / "fanuc" / (UB + "sysframe.va"))
    rp = read_robot(path, config=config)
    for p in rp.poses:
        assert (p.flange is None) != (p.problem is None), p
        if p.problem is not None:
            e = p.problem
            assert e.file == str(path) and e.line and e.col, e
            assert any(w in e.message for w in ("joint position", "give --config")), e.message
        else:
            assert p.flange.shape == (4, 4) and np.isfinite(p.flange).all()


def test_corpus_spot_weld_path_in_world_by_scipy():
    """s012ssw01.ls P[2] (UF1, UT1) against the same product by scipy from the
    numbers of sysframe.va as printed."""
    rp = read_robot(corpus_file("fanuc", UB + "s012ssw01.ls"),
                    config=str(corpus_file("fanuc", UB + "sysframe.va")))
    uf1 = pose(3495.600, 5813.000, -1166.400, .140, .080, -90.040)
    ut1 = pose(-1.314, -1090.600, 764.587, -180.000, 0.0, -90.000)
    p2 = pose(5947.414, -1623.844, 1403.576, 0.0, 0.0, 127.808)
    assert rp.poses[0].name == "P[2]"
    np.testing.assert_allclose(rp.poses[0].flange, uf1 @ p2 @ inv(ut1), atol=1e-9)
