"""Stäubli VAL3 data files (.dtx), issue 30 points 1, 2 and 4 (Stäubli):
both dialects read as text (frames, tools, their fathers, points), check's
lints, errors at file:line:col, diff, patch refused while the rotation order
is not proved, and a .dtx's points as solve --robot's flange poses."""
from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from conftest import FIXTURES, corpus_file
from ucsio import vendors
from ucsio.cli import main
from ucsio.parsing.controller import load, parse
from ucsio.parsing.document import Document
from ucsio.vendors.staubli.convention import xyz_to_quat

CS8 = FIXTURES / "staubli" / "cell_cs8.dtx"
CS9 = FIXTURES / "staubli" / "cell_cs9.dtx"


def cli(capsys, *args):
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


def read(text: str, name: str = "cell.dtx"):
    return parse(Document(text.encode(), name))


def cs9(*values: str, extra: str = "") -> str:
    """An s7/CS9 .dtx of one datum per (name, type, its <Value> lines)."""
    body = "".join(values)
    return ('<?xml version="1.0" encoding="utf-8"?>\n<Database xmlns="http://www.staubli.com/'
            f'robotics/VAL3/Data/2">\n  <Datas>\n{body}  </Datas>\n{extra}</Database>\n')


def datum(name: str, type_: str, *entries: str) -> str:
    inner = "".join(f"      <Value {e} />\n" for e in entries)
    return f'    <Data name="{name}" type="{type_}" size="{len(entries)}">\n{inner}    </Data>\n'


def matrix(x, y, z, rx, ry, rz) -> np.ndarray:
    """The independent reading: scipy's intrinsic X, Y', Z'' (R = Rx·Ry·Rz)."""
    T = np.eye(4)
    T[:3, :3] = Rotation.from_euler("XYZ", [rx, ry, rz], degrees=True).as_matrix()
    T[:3, 3] = (x, y, z)
    return T


# -- reading ----------------------------------------------------------------------------
def test_the_cs8_corpus_file_lists_its_tools_on_the_flange():
    cf = load(str(corpus_file("staubli", "NovaAplicacio")))
    assert cf.extra["dialect"] == "CS8"
    # world and flange (an empty fFather) are VAL3's roots, not frames of the file
    assert [(f.name, f.type, f.parent.name) for f in cf.frames] == [
        ("einaLateral", "tool", "flange"), ("einaPunta", "tool", "flange")]
    lateral = cf.frames[0]
    assert lateral.pose.t == (30.0, 30.0, 170.0)
    assert (lateral.info["rx"], lateral.info["ry"], lateral.info["rz"]) == (-90.0, 44.0, -90.0)
    assert np.allclose(lateral.pose.matrix, matrix(30, 30, 170, -90, 44, -90)[:3, :3])
    # its five points are solve --robot's, not frames
    assert [e.name for e in cf.extra["points"]] == ["p1", "p2", "p3", "p4", "p5"]


def test_the_cs9_corpus_tool_without_values_is_the_flange_itself():
    cf = load(str(corpus_file("staubli", "ros_server")))
    assert cf.extra["dialect"] == "CS9"
    (tool,) = cf.frames
    assert (tool.name, tool.type, tool.parent.name) == ("tTool", "tool", "flange")
    assert tool.pose.t == (0.0, 0.0, 0.0) and tool.pose.q == (1.0, 0.0, 0.0, 0.0)
    assert tool.numbers == {} and tool.info["absent"] == ["x", "y", "z", "rx", "ry", "rz"]


def test_cs8_frames_on_frames_tools_on_tools_and_array_entries():
    cf = load(str(CS8))
    got = {f.name: (f.type, f.parent.kind, f.parent.name) for f in cf.frames}
    assert got == {"fTable": ("frame", "world", "world"),
                   "fFixture[0]": ("frame", "frame", "fTable"),
                   "fFixture[1]": ("frame", "frame", "fTable"),
                   "tGripper": ("tool", "flange", "flange"),
                   "tReflector": ("tool", "frame", "tGripper")}
    assert not cf.lints
    fixture1 = cf.frame("fFixture[1]")
    assert fixture1.pose.t == (300.0, 50.0, 12.5) and fixture1.info["father"] == "fTable[0]"


def test_cs9_absent_attributes_are_zero_and_fathers_name_entries():
    cf = load(str(CS9))
    pallet1, part, torch = cf.frame("fPallet[1]"), cf.frame("fPart"), cf.frame("tTorch")
    assert pallet1.pose.t == (1200.5, 300.0, 0.0) and pallet1.info["absent"] == ["z", "rx", "ry"]
    assert np.allclose(pallet1.pose.matrix, matrix(0, 0, 0, 0, 0, 180)[:3, :3])
    assert part.parent.name == "fPallet[1]"           # fatherId="fPallet[1]"
    assert torch.pose.t == (0.0, 0.0, 366.58) and set(torch.numbers) == {"z", "ry"}
    assert [e.name for e in cf.extra["points"]] == ["pTaught[0]", "pTaught[1]", "pTaught[2]"]


def test_frames_tree_and_json(capsys):
    code, out, _ = cli(capsys, "frames", "--tree", CS8)
    assert code == 0
    assert "└── fTable  frame" in out and "    ├── fFixture[0]  frame" in out
    assert "        └── tReflector  tool" in out
    code, out, _ = cli(capsys, "frames", "--json", CS9)
    frames = {f["name"]: f for f in json.loads(out)["frames"]}
    assert frames["fPart"]["parent"] == "fPallet[1]" and frames["fPart"]["vendor"] == "staubli"
    assert (frames["tTorch"]["rx"], frames["tTorch"]["ry"]) == (0.0, -22.5)   # as written


def test_a_file_without_its_suffix_is_known_by_its_root():
    for path in (CS8, CS9):
        doc = Document(path.read_bytes(), "tmp_Xq1z")        # git's temporary file
        assert vendors.detect(doc) == "staubli"


@pytest.mark.parametrize("raw", [
    CS8.read_bytes(),                                           # BOM, CRLF
    CS9.read_bytes()[3:],                                       # no BOM, LF
    CS9.read_bytes().replace(b'x="1200.5" y="-300"', b"y = '-300'   x='1200.5'"),
    CS9.read_bytes().replace(b"\n", b"\r"),                     # bare CR
], ids=["bom-crlf", "lf", "quotes-order-blanks", "cr"])
def test_every_byte_round_trips_and_numbers_are_their_spans(raw):
    doc = Document(raw, "cell.dtx")
    assert doc.to_bytes() == raw
    cf = parse(doc)
    assert len(cf.frames) == 5
    for f in cf.frames:
        for key, num in f.numbers.items():
            assert doc.slice(num.span) == num.text and float(num.text) == num.value


# -- errors: one clear error at file:line:col, exit 2 -------------------------------------
@pytest.mark.parametrize("text, where, words", [
    (cs9(datum("f", "frame", 'key="0" x="1O0" fatherId="world[0]"')), "5:25", "not a number"),
    (cs9(datum("f", "frame", 'key="0" x="1e999"')), "5:25", "out of range"),
    (cs9(datum("f", "frame", 'key="0" x="1" x="2"')), "5:28", "given twice"),
    (cs9(datum("f", "frame", 'key="0" fatherId="world"')), "5:32", "not name[index]"),
    (cs9(datum("f", "frame", 'key="zero"')), "5:19", "not a whole number"),
    # names with blanks or line breaks (a mangled file) are no VAL3 names
    (cs9(datum("f", "frame", 'key="0" fatherId="world\r\n[0]"')), "5:32", "not name[index]"),
    (cs9(datum("f\nf", "frame", 'key="0"')), "4:17", "is not a VAL3 name"),
    (cs9(datum("f", "frame", 'key="0" x=1')), "5:22", "not an attribute"),
    (cs9("    <Data name=\"f\" type=\"frame\" size=\"1\">\n", extra="  </Data>\n"),
     "5:3", "</Datas> where <Data> (line 4) is still open"),
    (cs9("").replace("</Database>\n", ""), "2:1", "<Database> is never closed"),
    (cs9("    <Data name=\"f\" type=\"frame\" size=\"1\" <Value/>\n"), "4:5", "'<' that opens"),
    ('<?xml version="1.0"?>\n<robot>\n</robot>\n', "2:1", "not a Stäubli VAL3 data file"),
    (cs9("") + "<Database/>\n", "6:1", "a second top-level element <Database>"),
])
def test_malformed_files_are_one_error_naming_the_place(capsys, tmp_path, text, where, words):
    path = tmp_path / "bad.dtx"
    path.write_text(text)
    code, out, err = cli(capsys, "frames", path)
    assert code == 2 and out == ""
    assert f"{path}:{where}:" in err and words in err, err


# -- check's lints --------------------------------------------------------------------------
@pytest.mark.parametrize("values, code, words", [
    ([datum("f", "frame", 'key="0" fatherId="fNowhere[0]"')], "father-missing",
     "father fNowhere[0], which this file does not hold"),
    ([datum("f", "frame", 'key="0"')], "father-missing", "no father"),
    ([datum("a", "frame", 'key="0" fatherId="b[0]"'), datum("b", "frame", 'key="0" fatherId="a[0]"')],
     "father-circle", "circle (a on b on a)"),
    ([datum("t", "tool", 'key="0" fatherId="world[0]"')], "father-kind", "tool t hangs from world"),
    ([datum("t", "tool", 'key="0" fatherId="flange[0]"'),
      datum("f", "frame", 'key="0" fatherId="t[0]"')], "father-kind", "frame f hangs from tool t"),
    ([datum("p", "pointRx", 'key="0" fatherId="nowhere[2]"')], "father-missing", "point p"),
    ([datum("f", "frame", 'key="0" fatherId="world[0]"', 'key="0" fatherId="world[0]"')],
     "entry-index", "entry 0 comes twice"),
    ([datum("f", "frame", 'key="3" fatherId="world[0]"')], "entry-index", "outside its size 1"),
])
def test_check_reports_fathers_and_entries(capsys, tmp_path, values, code, words):
    path = tmp_path / "cell.dtx"
    path.write_text(cs9(*values))
    cf = load(str(path))
    assert [(lint.code, lint.line) for lint in cf.lints if lint.code == code][:1], cf.lints
    assert any(words in lint.message for lint in cf.lints), [lint.message for lint in cf.lints]
    rc, out, _ = cli(capsys, "check", path)
    assert code in out and rc == 1


def test_a_circle_of_fathers_hangs_under_unknown_in_the_tree(capsys, tmp_path):
    path = tmp_path / "cell.dtx"
    path.write_text(cs9(datum("a", "frame", 'key="0" fatherId="b[0]"'),
                        datum("b", "frame", 'key="0" fatherId="a[0]"')))
    code, out, _ = cli(capsys, "frames", "--tree", path)
    assert code == 0 and out.startswith("world\nunknown (the file does not say")
    assert "├── a  frame" in out and "└── b  frame" in out


# -- the convention: read as RoboDK does, not written --------------------------------------
def test_reading_rx_ry_rz_is_scipy_intrinsic_xyz():
    rng = np.random.default_rng(30)
    for rx, ry, rz in rng.uniform(-180, 180, (200, 3)):
        ours = np.array(xyz_to_quat(rx, ry, rz))
        x, y, z, w = Rotation.from_euler("XYZ", [rx, ry, rz], degrees=True).as_quat()
        theirs = np.array([w, x, y, z])
        assert np.allclose(ours, theirs, atol=1e-12) or np.allclose(ours, -theirs, atol=1e-12)


def test_patch_is_refused_with_the_reason_and_nothing_is_written(capsys, tmp_path):
    path = tmp_path / "cell.dtx"
    raw = CS8.read_bytes()
    path.write_bytes(raw)
    for args in (["--set", "1,2,3,0,0,0"], ["--set", "1,2,3,0,0,0", "--in-place"],
                 ["--set", "1,2,3,0,0,0", "-o", tmp_path / "out.dtx"]):
        code, out, err = cli(capsys, "patch", path, "--frame", "fTable", *args)
        assert code == 2 and out == ""
        assert f"{path}:13:1:" in err and "not proved from Stäubli's VAL3 documentation" in err
        assert path.read_bytes() == raw and not (tmp_path / "out.dtx").exists()


# -- diff: two files, two folders ----------------------------------------------------------
def test_diff_of_two_files_and_of_two_folders(capsys, tmp_path):
    old, new = tmp_path / "old", tmp_path / "new"
    old.mkdir(), new.mkdir()
    (old / "cell.dtx").write_bytes(CS9.read_bytes())
    (new / "cell.dtx").write_bytes(CS9.read_bytes().replace(b'x="25" y="25"', b'x="25.5" y="25"'))
    code, out, _ = cli(capsys, "diff", old / "cell.dtx", new / "cell.dtx")
    assert code == 0 and "fPart" in out and "+0.5" in out and "fPallet" not in out
    code, out, _ = cli(capsys, "diff", old, new)
    assert code == 0 and "fPart" in out and "+0.5" in out


def test_reading_commands_import_nothing_slow(tmp_path):
    """frames, --tree, check, diff and textconv of a .dtx: no numpy, scipy or lark."""
    from test_startup import MODULES_PROBE
    import os
    env = dict(os.environ, UCSIO_CACHE_DIR=str(tmp_path / "cache"))
    subprocess.run([sys.executable, "-m", "ucsio", "check", str(CS8)], env=env,
                   capture_output=True, check=True)
    for args in (["frames", CS8], ["frames", "--tree", CS9], ["check", CS9],
                 ["diff", CS8, CS8], ["diff", "--textconv", CS9]):
        res = subprocess.run([sys.executable, "-c", MODULES_PROBE, *map(str, args)],
                             capture_output=True, text=True, env=env, check=True)
        allowed = ["difflib"] if args[0] == "diff" and len(args) == 3 else []
        assert res.stdout.split() in ([], allowed), (args, res.stdout)


def test_programs_and_projects_are_still_refused_with_what_is_read(capsys, tmp_path):
    path = tmp_path / "start.pgx"
    path.write_text('<?xml version="1.0"?>\n<Programs/>\n')
    code, _, err = cli(capsys, "frames", path)
    assert code == 2 and "of Stäubli's files it reads VAL3 data files (.dtx)" in err


# -- solve --robot: a .dtx's points as flange poses ----------------------------------------
def test_points_are_flange_poses_through_their_father_frames():
    from ucsio.readers.robot import read_robot
    got = read_robot(str(CS9))
    poses = {p.name: p for p in got.poses}
    # pTaught[1] in fPart, itself on fPallet[1] on world; the flange is the tool (tool0)
    world_part = matrix(1200.5, 300, 0, 0, 0, 180) @ matrix(25, 25, 5, 0, 0, 0)
    expected = world_part @ matrix(10, -20, 30, 180, 0, 90)
    assert np.allclose(poses["pTaught[1]"].flange, expected, atol=1e-9)
    assert np.allclose(poses["pTaught[0]"].flange,
                       matrix(568.40361, 92.80391, -333.62302, -176.48891, -1.58266, -10.02892))
    assert "not prove" not in poses["pTaught[0]"].note and "R = Rx" in poses["pTaught[0]"].note


def test_a_named_tool_is_taken_off_the_point():
    from ucsio.readers.robot import read_robot
    got = read_robot(str(CS8), tool="tReflector")
    (p0, p1) = got.poses
    tool = matrix(0, 0, 120, 0, 0, -90) @ matrix(15, -5, 40.75, 0, 30, 0)   # on tGripper
    father = matrix(812.5, -140.25, -22.4, 0.35, -0.12, 90.5) @ matrix(300, 50, 12.5, 180, 0, 45)
    expected = father @ matrix(10, 20, 30, 180, 0, 15) @ np.linalg.inv(tool)
    assert np.allclose(p0.flange, expected, atol=1e-9)
    assert "tool tReflector" in p0.note


def test_an_unresolvable_point_carries_its_problem(tmp_path):
    from ucsio.errors import UcsioError
    from ucsio.readers.robot import read_robot
    path = tmp_path / "cell.dtx"
    path.write_text(cs9(datum("p", "pointRx", 'key="0" x="1" fatherId="fGone[0]"',
                              'key="1" x="2" fatherId="world[0]"')))
    a, b = read_robot(str(path)).poses
    assert isinstance(a.problem, UcsioError) and "fGone[0] is not a frame" in str(a.problem)
    assert b.problem is None and b.flange[0, 3] == 2.0
    with pytest.raises(UcsioError, match="not a tool of this file"):
        read_robot(str(path), tool="tNone")


def test_solve_reads_a_pointrx_table_as_the_robot_side(capsys, tmp_path):
    """End to end on synthetic truth: the UCS's points, seen by the tracker in
    the UCS and taught as pointRx poses (in world, the reflector 10,-5,120 on
    the flange), give back the UCS."""
    rng = np.random.default_rng(4)
    truth = matrix(1500.0, -250.0, 300.0, 0, 0, 0)
    truth[:3, :3] = Rotation.from_euler("ZYX", [30.0, 5.0, -2.0], degrees=True).as_matrix()
    tcp = np.array([10.0, -5.0, 120.0])
    laser = rng.uniform([-200, -200, 0], [200, 200, 150], (6, 3))
    values, rows = [], ["point,laser_x,laser_y,laser_z"]
    for k, p in enumerate(laser):
        rx, ry, rz = rng.uniform(-40, 40, 3) + (180, 0, 0)
        flange_r = Rotation.from_euler("XYZ", [rx, ry, rz], degrees=True).as_matrix()
        x, y, z = (truth @ [*p, 1.0])[:3] - flange_r @ tcp
        values.append(f'key="{k}" x="{x:.6f}" y="{y:.6f}" z="{z:.6f}" rx="{rx:.6f}" '
                      f'ry="{ry:.6f}" rz="{rz:.6f}" fatherId="world[0]"')
        rows.append(f"pMeas[{k}],{p[0]:.6f},{p[1]:.6f},{p[2]:.6f}")
    (tmp_path / "cell.dtx").write_text(cs9(datum("pMeas", "pointRx", *values)))
    (tmp_path / "laser.csv").write_text("\n".join(rows) + "\n")
    code, out, err = cli(capsys, "solve", "--laser", tmp_path / "laser.csv", "--robot",
                         tmp_path / "cell.dtx", "--tcp", "10,-5,120", "--json")
    assert code == 0, err
    frame = json.loads(out)["frame"]
    assert np.allclose([frame["x"], frame["y"], frame["z"]], truth[:3, 3], atol=1e-4)
    assert np.allclose([frame["a"], frame["b"], frame["c"]], [30.0, 5.0, -2.0], atol=1e-5)
