"""Measurements where they live: tracker exports, robot poses from the
controller's own files, pairing by name (ucsio.readers). Every export below
is written by hand in its layout; every robot file is built from synthetic
truth with scipy, so the paired result can be checked against the merged
CSV of the same numbers."""
from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from ucsio.cli import main
from ucsio.errors import UcsioError
from ucsio.readers.laser import read_laser
from ucsio.readers.pairing import pair, read_map
from ucsio.readers.robot import read_robot
from ucsio.readers.measurement import read_measurement
from ucsio.method.solve import solve

TCP = (12.5, -30.25, 180.0)


def num(v) -> str:
    """A number as a file would hold it, to full double precision."""
    return repr(float(v))


# ------------------------------------------------------------------ laser exports

def write(tmp_path, name, text, encoding="utf-8"):
    p = tmp_path / name
    p.write_bytes(text.encode(encoding))
    return p


def test_spatial_analyzer_export_comma_separated(tmp_path):
    p = write(tmp_path, "sa.txt",
              "// Version: SA 2019.09.11\n// Frame: A::Fixture\n// Units: Millimeters\n"
              "// Format: Collection,  Group,  Target,  X,  Y,  Z\n\n"
              "A,Nominals,P1,1.000000e+002,2.5,-3\n"
              "A,  Nominals,  P2,  1.05E1, -20.25,  30.0\n")
    pts = read_laser(p)
    assert pts.format == "spatialanalyzer"
    assert pts.names == ["P1", "P2"] and pts.lines == [6, 7]
    np.testing.assert_array_equal(pts.xyz, [[100.0, 2.5, -3.0], [10.5, -20.25, 30.0]])


def test_spatial_analyzer_export_whitespace_no_comments(tmp_path):
    p = write(tmp_path, "sa.txt", "A  Nom  P1   1.0  2.0  3.0\nA\tNom\tP2\t4\t5\t6e0\n")
    pts = read_laser(p)
    assert pts.format == "spatialanalyzer" and pts.names == ["P1", "P2"]
    np.testing.assert_array_equal(pts.xyz, [[1, 2, 3], [4, 5, 6]])


def test_spatial_analyzer_same_target_in_two_groups_is_an_error(tmp_path):
    p = write(tmp_path, "sa.txt", "// SA\nA,Nominal,P1,1,2,3\nA,Measured,P1,1.1,2,3\n")
    with pytest.raises(UcsioError) as e:
        read_laser(p)
    assert (e.value.line, e.value.col) == (3, 12) and "Nominal" in e.value.message


@pytest.mark.parametrize("text", [
    "Point;X [mm];Y [mm];Z [mm]\nP1;100,5;200;3,25\nP2;1;2;3\n",          # ; and decimal comma
    "name,x,y,z\nP1,100.5,200,3.25\nP2,1,2,3\n",                           # header, comma
    "P1\t100,5\t200\t3,25\nP2\t1\t2\t3\n",                                  # tab, no header
    "P1  100,5  200  3,25\r\nP2 1 2 3\r\n",                                 # spaces, CRLF
    "# exported 2026-12-01\nP1, 100.5, 200, 3.25\n\nP2, 1, 2, 3\n",       # comment, blank line
    "X;Y;Z;Name\n100,5;200;3,25;P1\n1;2;3;P2\n",                           # columns by header
])
def test_plain_tables(tmp_path, text):
    pts = read_laser(write(tmp_path, "t.txt", text))
    assert pts.format == "table"
    assert pts.names == ["P1", "P2"]
    np.testing.assert_array_equal(pts.xyz, [[100.5, 200.0, 3.25], [1.0, 2.0, 3.0]])


def test_spec_csv_laser_side_and_units(tmp_path):
    p = write(tmp_path, "l.csv", "point,laser_x,laser_y,laser_z,weight\nA,1,2,3,2\nB,0.5,0,0,1\n")
    pts = read_laser(p, units="m")
    assert pts.format == "csv" and pts.names == ["A", "B"]
    np.testing.assert_array_equal(pts.xyz, [[1000, 2000, 3000], [500, 0, 0]])
    np.testing.assert_array_equal(pts.weights, [2, 1])
    inch = read_laser(write(tmp_path, "t.txt", "P1 1 2 3\n"), units="in")
    np.testing.assert_allclose(inch.xyz, [[25.4, 50.8, 76.2]])


@pytest.mark.parametrize("text,line,col,words", [
    ("P1,1,2,3\nP2,1,x2,3\n", 2, 6, "y not a finite number: 'x2'"),
    ("P1;1;2;3\nP2;1;2;\n", 2, 8, "z empty"),
    ("P1 1 2 3\nP2 1 2\n", 2, 7, "expected name x y z, found 3 fields"),
    ("P1 1 2 3\np1 4 5 6\n", 2, 1, "duplicate point name 'p1'"),
    ("name;x;y;z\nP1;1;2;nan\n", 2, 8, "not a finite number"),
    ("// SA\nA,G,P1,1,2,3\nA,G,P2,1,2,inf\n", 3, 12, "z not a finite number"),
])
def test_bad_lines_name_file_line_col(tmp_path, text, line, col, words):
    p = write(tmp_path, "bad.txt", text)
    with pytest.raises(UcsioError) as e:
        read_laser(p)
    assert (e.value.file, e.value.line, e.value.col) == (str(p), line, col)
    assert words in e.value.message


def test_header_without_xyz_is_an_error(tmp_path):
    with pytest.raises(UcsioError) as e:
        read_laser(write(tmp_path, "t.txt", "name;east;north;up\nP1;1;2;3\n"))
    assert e.value.line == 1 and "X, Y and Z" in e.value.message


# ------------------------------------------------------------------ synthetic cell

def cell(seed=3, n=8, spread=30.0):
    """Truth: the UCS in world, the TCP, flange poses (4x4) at n points."""
    rng = np.random.default_rng(seed)
    R_ucs = Rotation.from_euler("ZYX", rng.uniform(-60, 60, 3), degrees=True)
    t_ucs = rng.uniform(-1500, 1500, 3) + [2000, 0, 500]
    laser = rng.uniform(0, 1, (n, 3)) * [1000, 700, 250]
    world = R_ucs.apply(laser) + t_ucs
    flanges = []
    for i in range(n):
        R = Rotation.from_euler("ZYX", [180, 0, 180], degrees=True) * \
            Rotation.from_euler("ZYX", rng.uniform(-spread, spread, 3), degrees=True)
        T = np.eye(4)
        T[:3, :3] = R.as_matrix()
        T[:3, 3] = world[i] - R.apply(TCP)
        flanges.append(T)
    return laser, np.array(flanges)


def abc(T):
    return Rotation.from_matrix(T[:3, :3]).as_euler("ZYX", degrees=True)


def merged_csv(tmp_path, laser, flanges, names):
    rows = ["point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c"]
    for nm, l, T in zip(names, laser, flanges):
        rows.append(",".join([nm] + [repr(float(v)) for v in (*l, *T[:3, 3], *abc(T))]))
    return write(tmp_path, "merged.csv", "\n".join(rows) + "\n")


def pose_of(T):
    return T


def frame_text(T):
    a, b, c = abc(T)
    x, y, z = T[:3, 3]
    return f"X {num(x)},Y {num(y)},Z {num(z)},A {num(a)},B {num(b)},C {num(c)}"


def inv(T):
    out = np.eye(4)
    out[:3, :3] = T[:3, :3].T
    out[:3, 3] = -T[:3, :3].T @ T[:3, 3]
    return out


def kuka_files(tmp_path, flanges, names, base, tool, base_no=2, tool_no=1):
    """A measurement program .dat: position = base^-1 * flange * tool (the
    TCP in the base), and a $config.dat with those entries."""
    lines = ["&ACCESS RVP", "&REL 3", "DEFDAT  MEASURE PUBLIC", ";FOLD EXTERNAL DECLARATIONS",
             ";ENDFOLD", "DECL FRAME helper={X 0.0,Y 0.0,Z 10.0,A 0.0,B 0.0,C 0.0}"]
    for nm, T in zip(names, flanges):
        P = inv(base) @ T @ tool
        lines.append(f"DECL E6POS X{nm}={{{frame_text(P)},S 6,T 27,E1 0.0,E2 0.0,E3 0.0,"
                     "E4 0.0,E5 0.0,E6 0.0}")
        lines.append(f"DECL FDAT F{nm}={{TOOL_NO {tool_no},BASE_NO {base_no},IPO_FRAME #BASE,"
                     "POINT2[] \" \"}")
    lines.append("ENDDAT")
    dat = write(tmp_path, "measure.dat", "\r\n".join(lines) + "\r\n")
    cfg = ["DEFDAT  $CONFIG", "DECL BASIS_SUGGEST_T LAST_BASIS={POINT1[] \"*\"}",
           "FRAME TOOL_DATA[16]", "FRAME BASE_DATA[32]",
           f"TOOL_DATA[{tool_no}]={{{frame_text(tool)}}}",
           f"BASE_DATA[{base_no}]={{{frame_text(base)}}}", "ENDDAT"]
    config = write(tmp_path, "$config.dat", "\n".join(cfg) + "\n")
    return dat, config


def random_pose(seed, reach=800.0):
    rng = np.random.default_rng(seed)
    T = np.eye(4)
    T[:3, :3] = Rotation.from_euler("ZYX", rng.uniform(-80, 80, 3), degrees=True).as_matrix()
    T[:3, 3] = rng.uniform(-reach, reach, 3)
    return T


def assert_same_solution(a, b):
    assert abs(a.pose.x - b.pose.x) < 1e-9 and abs(a.pose.y - b.pose.y) < 1e-9 \
        and abs(a.pose.z - b.pose.z) < 1e-9
    np.testing.assert_allclose(a.pose.matrix, b.pose.matrix, atol=1e-12)
    assert [p.name for p in a.points] == [p.name for p in b.points]
    for p, q in zip(a.points, b.points):
        assert abs(p.residual - q.residual) < 1e-9
        assert abs(p.loo_residual - q.loo_residual) < 1e-9


def test_kuka_dat_with_base_and_tool_equals_merged_csv(tmp_path):
    laser, flanges = cell()
    names = [f"P{i + 1}" for i in range(len(laser))]
    merged = solve(read_measurement(merged_csv(tmp_path, laser, flanges, names)), TCP)
    dat, config = kuka_files(tmp_path, flanges, names, random_pose(1), random_pose(2, 150))
    sa = write(tmp_path, "sa.txt", "// Format: Collection, Group, Target, X, Y, Z\n" + "".join(
        f"A,Fixture,{nm},{num(l[0])},{num(l[1])},{num(l[2])}\n" for nm, l in zip(names, laser)))
    meas, warnings = pair(read_laser(sa), read_robot(dat, config=str(config)))
    assert meas.names == names
    assert warnings == ["robot positions without a laser point: helper"]
    assert_same_solution(solve(meas, TCP), merged)


def test_kuka_dat_needs_config_only_where_a_base_or_tool_is_used(tmp_path):
    laser, flanges = cell(seed=4)
    names = [f"P{i + 1}" for i in range(len(laser))]
    dat, _ = kuka_files(tmp_path, flanges, names, random_pose(1), random_pose(2))
    with pytest.raises(UcsioError) as e:
        pair(read_laser(merged_csv(tmp_path, laser, flanges, names)), read_robot(dat))
    assert "--config" in e.value.message and e.value.line == 7
    # BASE_NO 0, TOOL_NO 0: the position is the flange in world, no config needed
    dat0, _ = kuka_files(tmp_path, flanges, names, np.eye(4), np.eye(4), base_no=0, tool_no=0)
    meas, _ = pair(read_laser(merged_csv(tmp_path, laser, flanges, names)), read_robot(dat0))
    merged = solve(read_measurement(tmp_path / "merged.csv"), TCP)
    assert_same_solution(solve(meas, TCP), merged)


def test_kuka_external_base_is_refused(tmp_path):
    laser, flanges = cell(seed=5)
    names = [f"P{i + 1}" for i in range(len(laser))]
    dat, config = kuka_files(tmp_path, flanges, names, random_pose(1), random_pose(2))
    config.write_text(config.read_text().replace("ENDDAT", "BASE_TYPE[2]=#TCP\nENDDAT"))
    with pytest.raises(UcsioError) as e:
        pair(read_laser(merged_csv(tmp_path, laser, flanges, names)),
             read_robot(dat, config=str(config)))
    assert "BASE_DATA[2]" in e.value.message and "external_tcp" in e.value.message


def rapid_pose(T):
    q = Rotation.from_matrix(T[:3, :3]).as_quat()       # x, y, z, w
    x, y, z = T[:3, 3]
    return f"[[{num(x)},{num(y)},{num(z)}],[{num(q[3])},{num(q[0])},{num(q[1])},{num(q[2])}]]"


def test_abb_robtargets_in_a_wobj_with_a_tool_equal_merged_csv(tmp_path):
    laser, flanges = cell(seed=6)
    names = [f"P{i + 1}" for i in range(len(laser))]
    merged = solve(read_measurement(merged_csv(tmp_path, laser, flanges, names)), TCP)
    uframe, oframe, tframe = random_pose(7), random_pose(8, 100), random_pose(9, 200)
    targets = "".join(
        f"    CONST robtarget {nm.lower()}:=[{rapid_pose(inv(uframe @ oframe) @ T @ tframe)[1:-1]},"
        "[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n" for nm, T in zip(names, flanges))
    module = write(tmp_path, "Measure.mod", "MODULE Measure\n" + targets +
                   "    PROC main()\n        MoveL p1,v100,fine,tMeas\\WObj:=wMeas;\n"
                   "    ENDPROC\nENDMODULE\n")
    write(tmp_path, "Cell.sys", "MODULE Cell(SYSMODULE)\n"
          f"    PERS tooldata tMeas:=[TRUE,{rapid_pose(tframe)},[1,[0,0,1],[1,0,0,0],0,0,0]];\n"
          f"    PERS wobjdata wMeas:=[FALSE,TRUE,\"\",{rapid_pose(uframe)},{rapid_pose(oframe)}];\n"
          "ENDMODULE\n")
    laser_file = write(tmp_path, "pts.txt", "".join(
        f"{nm}\t{num(l[0])}\t{num(l[1])}\t{num(l[2])}\n" for nm, l in zip(names, laser)))
    meas, warnings = pair(read_laser(laser_file), read_robot(module, tool="tMeas", wobj="wMeas"))
    assert warnings == []
    assert_same_solution(solve(meas, TCP), merged)
    with pytest.raises(UcsioError) as e:
        read_robot(module, tool="tNone")
    assert "--robot-tool tNone" in e.value.message


def test_abb_default_tool0_wobj0_and_spec_csv_robot_side(tmp_path):
    laser, flanges = cell(seed=7)
    names = [f"P{i + 1}" for i in range(len(laser))]
    merged = solve(read_measurement(merged_csv(tmp_path, laser, flanges, names)), TCP)
    module = write(tmp_path, "M.mod", "MODULE M\n" + "".join(
        f"CONST robtarget {nm}:=[{rapid_pose(T)[1:-1]},[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n"
        for nm, T in zip(names, flanges)) + "ENDMODULE\n")
    meas, _ = pair(read_laser(tmp_path / "merged.csv"), read_robot(module))
    assert_same_solution(solve(meas, TCP), merged)
    # the merged file's robot side, read alone
    meas2, _ = pair(read_laser(tmp_path / "merged.csv"), read_robot(tmp_path / "merged.csv"))
    assert_same_solution(solve(meas2, TCP), merged)


def test_pairing_rules(tmp_path):
    laser, flanges = cell(seed=8, n=7)
    names = [f"P{i + 1}" for i in range(7)]
    merged_csv(tmp_path, laser, flanges, names)
    rows = ["point,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c"]
    robot_names = ["p1", "P2", "XP3", "meas_4", "P5", "P6", "home"]
    for nm, T in zip(robot_names, flanges):
        rows.append(",".join([nm] + [repr(float(v)) for v in (*T[:3, 3], *abc(T))]))
    robot = write(tmp_path, "robot.csv", "\n".join(rows) + "\n")
    laser_file = write(tmp_path, "laser.txt", "".join(
        f"{nm} {num(l[0])} {num(l[1])} {num(l[2])}\n" for nm, l in zip(names, laser)))
    mp = write(tmp_path, "map.csv", "laser,robot\nP4,MEAS_4\n")
    meas, warnings = pair(read_laser(laser_file), read_robot(robot), read_map(mp), str(mp))
    # p1 (case), P2, P5, P6 by name, P4 by the map; P3 has no partner here: the
    # X prefix is KUKA's (a .dat position), a CSV name is taken as written
    assert meas.names == ["P1", "P2", "P4", "P5", "P6"]
    assert warnings == ["laser points without a robot position: P3, P7",
                        "robot positions without a laser point: XP3, home"]
    np.testing.assert_allclose(meas.flange[2], flanges[3], atol=1e-9)   # meas_4, mapped
    bad = write(tmp_path, "map2.csv", "P4,nowhere\n")
    with pytest.raises(UcsioError) as e:
        pair(read_laser(laser_file), read_robot(robot), read_map(bad), str(bad))
    assert (e.value.file, e.value.line) == (str(bad), 1)


def test_fewer_than_three_pairs_is_an_error(tmp_path):
    laser_file = write(tmp_path, "l.txt", "A 1 2 3\nB 4 5 6\nC 7 8 9\n")
    robot = write(tmp_path, "r.csv", "point,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c\n"
                  "A,1,2,3,0,0,0\nB,4,5,6,0,0,0\nZ,7,8,9,0,0,0\n")
    with pytest.raises(UcsioError) as e:
        pair(read_laser(laser_file), read_robot(robot))
    assert "only 2 points pair" in e.value.message and "--map" in e.value.message


def test_cli_laser_and_robot(tmp_path, capsys):
    laser, flanges = cell(seed=9)
    names = [f"P{i + 1}" for i in range(len(laser))]
    merged = merged_csv(tmp_path, laser, flanges, names)
    dat, config = kuka_files(tmp_path, flanges, names, random_pose(3), random_pose(4, 100))
    sa = write(tmp_path, "sa.txt", "// SA export\n" + "".join(
        f"A Fixture {nm} {num(l[0] / 1000)} {num(l[1] / 1000)} {num(l[2] / 1000)}\n"
        for nm, l in zip(names, laser)))
    tcp = ",".join(map(str, TCP))
    assert main(["solve", str(merged), "--tcp", tcp, "--json"]) == 0
    want = json.loads(capsys.readouterr().out)
    code = main(["solve", "--laser", str(sa), "--laser-units", "m", "--robot", str(dat),
                 "--config", str(config), "--tcp", tcp, "--json"])
    out = capsys.readouterr()
    assert code == 0
    got = json.loads(out.out)
    for k in "xyz":
        assert abs(got["frame"][k] - want["frame"][k]) < 1e-9
    assert "helper" in out.err and got["warnings"]
    # usage errors: exit 2, one line
    assert main(["solve", "--laser", str(sa), "--tcp", tcp]) == 2
    assert "--robot" in capsys.readouterr().err
    assert main(["solve", str(merged), "--laser", str(sa), "--robot", str(dat)]) == 2


# ------------------------------------------------------------------ real files

def test_kuka_positions_of_a_real_program_dat():
    from conftest import corpus_file
    from ucsio.parsing.document import Document
    from ucsio.vendors.kuka.krl import positions

    found = {p.name: p for p in positions(Document.read(
        corpus_file("kuka", "C1_pickConveyorBP.dat")))}
    p1 = found["Xp1"]
    assert (p1.type, p1.point, p1.fdat, p1.tool_no, p1.base_no, p1.ipo_frame) == \
        ("E6POS", "p1", "Fp1", 1, 0, "#BASE")
    assert p1.pose.t == (-699.022, -1227.66125, 987.959167)
    assert p1.pose.abc == (-167.849564, -0.0432640277, 0.00174230116)
    assert found["zOffsetFrame"].fdat is None and found["zOffsetFrame"].pose.z == 200.0


def test_abb_robtargets_of_a_real_module():
    from conftest import corpus_file
    from ucsio.parsing.controller import load
    from ucsio.vendors.abb.rapid import robtargets

    cf = load(corpus_file("abb", "HandEyeCalibrationExample.modx"), full=True)
    targets = robtargets(cf)
    t = targets[0]
    assert (t.name, t.module) == ("CAL_POSE_1", "RcHandEyeCalibrationExample")
    assert t.pose.t == (232.4, 382.9, 885.4)
    assert len(targets) == 8


def test_spec_csv_after_an_excel_separator_hint(tmp_path):
    pts = read_laser(write(tmp_path, "l.csv", "sep=;\npoint;laser_x;laser_y;laser_z\nA;1,5;2;3\n"))
    assert pts.format == "csv" and pts.xyz.tolist() == [[1.5, 2.0, 3.0]]
