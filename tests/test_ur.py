"""Universal Robots installations (issue 30, points 3 and 4): gzip around
XML, read and written back bit for bit, TCPs and features, patches of a
plane with its points and of a TCP from a solved TCP, the safety
configuration's features refused, solve --robot's taught poses.

Independent sources: scipy's Rotation for every rotation vector; the
fixture's gzip framing and deflate stream are made here with zlib itself
(tests/ur_cell.py), not by ucsio; the plane's 3-point construction is
numpy's, from the taught points.
"""
from __future__ import annotations

import json
import re
import zlib

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import ur_cell
from conftest import CORPUS, FIXTURES
from ucsio.cli import main
from ucsio.geometry import rotations as rot
from ucsio.geometry.frames import Pose
from ucsio.parsing.controller import parse
from ucsio.parsing.document import Document

CELL = FIXTURES / "ur" / "cell.installation"
HEADER = bytes.fromhex("1f8b0800000000000000")
CORPUS_FILES = sorted((CORPUS / "ur").glob("*.installation")) if (CORPUS / "ur").is_dir() else []
# the attributes a plane's patch may change, inside its element
POINT_VALUES = re.compile(r'(<(?:toolPosition|toolAxisAngle) value=")[^"]*(")')


def cli(capsys, *args):
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


def read(data: bytes, name: str = "cell.installation"):
    return parse(Document(data, name))


def scipy_quat(rotvec) -> np.ndarray:
    x, y, z, w = Rotation.from_rotvec(rotvec).as_quat()
    return np.array([w, x, y, z])


def same_rotation(q, rotvec, tol_deg=1e-9) -> bool:
    a = Rotation.from_quat([q[1], q[2], q[3], q[0]])
    return np.degrees((a.inv() * Rotation.from_rotvec(rotvec)).magnitude()) <= tol_deg


def solution(tmp_path, pose: Pose, tcp=None, name="S.json"):
    data = {"frame": pose.as_dict(), "accepted": True}
    if tcp is not None:
        data["tcp"] = {"x": tcp[0], "y": tcp[1], "z": tcp[2], "solved": True}
    path = tmp_path / name
    path.write_text(json.dumps(data))
    return path


def test_the_fixture_is_the_xml_framed_as_polyscope_frames_it():
    assert CELL.read_bytes() == ur_cell.installation(ur_cell.XML)


# -- bit for bit -----------------------------------------------------------------------------
@pytest.mark.parametrize("path", CORPUS_FILES + [CELL], ids=lambda p: p.name[-40:])
def test_every_installation_is_written_back_bit_for_bit(path):
    """The header is the fixed one and zlib at level 6 reproduces the stream
    here, at test time: the unedited document writes the file's bytes."""
    raw = path.read_bytes()
    assert raw[:10] == HEADER
    xml = zlib.decompress(raw, 31)
    assert ur_cell.installation(xml.decode("utf-8")) == raw      # this zlib reproduces it
    doc = Document(raw, str(path))
    assert doc.gzip is not None and doc.gzip.refusal is None
    assert doc.text.encode("utf-8") == xml and doc.to_bytes() == raw


def test_a_stream_this_zlib_does_not_reproduce_is_read_and_never_written(tmp_path, capsys):
    data = ur_cell.installation(ur_cell.XML, level=1)       # another deflater's stream
    assert data != CELL.read_bytes()
    path = tmp_path / "cell.installation"
    path.write_bytes(data)
    cf = read(data)
    assert [f.name for f in cf.frames] == ["Pick", "Table", "Fence", "TCP", "Gripper"]
    assert cf.lints == []           # reading needs no deflate: check's full read says it
    cf = parse(Document(data, "cell.installation"), full=True)
    assert [lint.code for lint in cf.lints] == ["gzip-stream"]
    code, out, err = cli(capsys, "check", path)
    assert code == 0 and "gzip-stream" in out
    code, out, err = cli(capsys, "patch", path, "--frame", "Table", "--set", "1,2,3,0,0,0",
                         "--in-place")
    assert code == 2 and "level 6" in err and "nothing written" in err, err
    assert re.search(r"cell\.installation:\d+:1: ", err)
    assert path.read_bytes() == data


@pytest.mark.parametrize("broken, says", [
    (lambda raw: raw[:-5], "cut short"),
    (lambda raw: raw[:-8] + b"\0\0\0\0" + raw[-4:], "CRC-32"),
    (lambda raw: raw[:20], "cut short"),
])
def test_a_broken_gzip_stream_is_one_clear_error(tmp_path, capsys, broken, says):
    path = tmp_path / "cell.installation"
    path.write_bytes(broken(CELL.read_bytes()))
    code, out, err = cli(capsys, "frames", path)
    assert code == 2 and out == "" and says in err and f"{path}:1:1: " in err, err


@pytest.mark.parametrize("edit, says, where", [
    (lambda x: x.replace("</TCPSettings>", "</TCPSetting>"), "</TCPSetting> where </TCPSettings>",
     '</TCPSetting>'),
    (lambda x: x.replace('offset="0.0, 0.0, 0.15,', 'offset="0.0, NaN, 0.15,'), "'NaN' is not",
     "NaN"),
    (lambda x: x.replace('offset="0.0, 0.0, 0.15,', 'offset="0.0, 0.15,'), "6 numbers expected",
     "0.0, 0.15,"),
    (lambda x: x.replace('<toolPosition value="0.3, 0.1, 0.2"/>', ""), "without <toolPosition>",
     '<GeomPoseNode showAxes="true" joggable="true" isVariable="false" id="d'),
    (lambda x: x.replace('name="Gripper"', 'name="Gripper" name="x"'), "given twice", 'name="x"'),
    (lambda x: x.replace("<Installation ", "<Install ").replace("</Installation>", "</Install>"),
     "not a Universal Robots installation",
     "<Install "),
])
def test_bad_xml_is_one_error_at_its_line_and_column(tmp_path, capsys, edit, says, where):
    xml = edit(ur_cell.XML)
    path = tmp_path / "cell.installation"
    path.write_bytes(ur_cell.installation(xml))
    code, out, err = cli(capsys, "check", path)
    assert code == 2 and says in err, err
    at = xml.index(where)
    line = xml.count("\n", 0, at) + 1
    col = at - (xml.rfind("\n", 0, at) + 1) + 1
    assert f"{path}:{line}:" in err
    assert f":{line}:{col}: " in err or where.startswith("<GeomPoseNode"), err
    code, out, err = cli(capsys, "patch", path, "--frame", "Gripper", "--set", "1,2,3,0,0,0",
                         "--in-place")
    assert code == 2 and path.read_bytes() == ur_cell.installation(xml)


def test_xml_nested_deeper_than_pythons_stack_reads_or_fails_cleanly(tmp_path, capsys):
    deep = "<a>" * 50_000 + "</a>" * 50_000
    path = tmp_path / "cell.installation"
    path.write_bytes(ur_cell.installation(ur_cell.XML.replace("<Features>", "<Features>" + deep)))
    code, out, err = cli(capsys, "frames", path)
    assert code == 0 and "Table" in out, err
    path.write_bytes(ur_cell.installation(ur_cell.XML.replace("<Features>", "<Features>" + deep[:-4])))
    code, out, err = cli(capsys, "check", path)
    assert code == 2 and "</Features> where </a> belongs" in err, err


# -- reading: units and conversions --------------------------------------------------------
def test_rotation_vectors_against_scipy():
    """Both conversions on random vectors, tiny angles and angles near pi."""
    rng = np.random.default_rng(30)
    axes = rng.normal(size=(60, 3))
    axes /= np.linalg.norm(axes, axis=1)[:, None]
    angles = np.concatenate([rng.uniform(0, np.pi, 40), [1e-12, 1e-7, 1e-4, 0.0],
                             np.pi - np.array([1e-12, 1e-9, 1e-6, 0.0]), rng.uniform(0, 1e-3, 12)])
    for v in axes * angles[:, None]:
        q = rot.rotvec_to_quat(v)
        want = scipy_quat(v)
        assert np.allclose(q, want, atol=1e-15) or np.allclose(q, -want, atol=1e-15)
        back = rot.quat_to_rotvec(q)
        assert np.degrees((Rotation.from_rotvec(back).inv() * Rotation.from_rotvec(v)).magnitude()) \
            <= 1e-9
        if np.linalg.norm(v) < np.pi - 1e-6:
            assert np.allclose(back, v, atol=1e-14)


@pytest.mark.parametrize("path", CORPUS_FILES + [CELL], ids=lambda p: p.name[-40:])
def test_frames_in_mm_and_degrees_from_metres_and_rotation_vectors(path):
    raw = path.read_bytes()
    cf = read(raw, str(path))
    xml = zlib.decompress(raw, 31).decode()
    for f in cf.frames:
        values = [f.numbers[k].value for k in ("x", "y", "z", "rx", "ry", "rz")]
        assert np.allclose(f.pose.t, np.array(values[:3]) * 1000.0, rtol=0, atol=1e-12)
        assert same_rotation(f.pose.q, values[3:])
        want = Rotation.from_rotvec(values[3:]).as_euler("ZYX", degrees=True)    # yaw pitch roll
        d = f.as_dict()
        assert np.allclose(rot.abc_to_matrix(d["a"], d["b"], d["c"]),
                           Rotation.from_euler("ZYX", want, degrees=True).as_matrix(), atol=1e-12)
        assert f"name=\"{f.name}\"" in xml
    kinds = {f.name: (f.type, f.parent.name) for f in cf.frames}
    assert all(v == ("TCP", "flange") or v[1] == "robot" for v in kinds.values())


def test_the_fixture_lists_points_planes_and_tcps_with_their_parents():
    cf = read(CELL.read_bytes())
    got = {f.name: (f.type, f.reference, f.parent.kind, f.info.get("safety", False))
           for f in cf.frames}
    assert got == {"Pick": ("POINT", "world", "robot", False),
                   "Table": ("PLANE", "world", "robot", False),
                   "Fence": ("PLANE", "world", "robot", True),
                   "TCP": ("TCP", "flange", "flange", False),
                   "Gripper": ("TCP", "flange", "flange", False)}
    gripper = cf.frame("Gripper").pose
    assert np.allclose(gripper.t, (0, 0, 150)) and abs(gripper.abc[0] - 45.0) < 1e-12
    assert cf.lints == []


def construct(p1, p2, p3) -> np.ndarray:
    """The 3-point construction in numpy: x along p1->p2, z = x × (p3 - p1), y = z × x."""
    x = (p2 - p1) / np.linalg.norm(p2 - p1)
    z = np.cross(x, p3 - p1)
    z /= np.linalg.norm(z)
    return np.column_stack([x, np.cross(z, x), z])


def plane_points(f, tag):
    return np.array([f.numbers[f"{tag}.{k}"].value for k in ("x", "y", "z", "rx", "ry", "rz")])


@pytest.mark.parametrize("path", CORPUS_FILES + [CELL], ids=lambda p: p.name[-40:])
def test_a_planes_frame_is_the_3_point_construction_of_its_taught_points(path):
    """PolyScope's frame of a plane (its firstPoint) is the 3-point
    construction (origin, +X, XY) of its taught points, to 1e-9 deg, and
    its secondPoint is the origin plus 1 m along y: checked on the corpus's
    real plane as on the fixture's."""
    planes = [f for f in read(path.read_bytes(), str(path)).frames if f.type == "PLANE"]
    for f in planes:
        taught = [plane_points(f, t)[:3] for t in ("userFirstPoint", "userSecondPoint",
                                                   "userThirdPoint")]
        m = construct(*taught)
        first = [f.numbers[k].value for k in ("rx", "ry", "rz")]
        assert np.degrees((Rotation.from_matrix(m).inv()
                           * Rotation.from_rotvec(first)).magnitude()) < 1e-9
        assert np.allclose(np.array(f.pose.t) / 1000, taught[0], atol=1e-15)
        assert np.allclose(plane_points(f, "secondPoint")[:3], taught[0] + m[:, 1], atol=1e-9)
    if path != CELL:
        assert [f.name for f in planes] == (["Magasin"] if "barriere" in path.name else [])


# -- patching --------------------------------------------------------------------------------
def masked(xml: str, start: int, end: int) -> str:
    """``xml`` with the point values between ``start`` and ``end`` blanked."""
    return xml[:start] + POINT_VALUES.sub(r"\1…\2", xml[start:end]) + xml[end:]


def element_span(xml: str, name: str) -> tuple[int, int]:
    start = xml.index(f'name="{name}"')
    return start, xml.index("</GeomPlaneNode>", start)


def test_patch_of_a_plane_writes_its_frame_and_points_and_nothing_else(tmp_path, capsys):
    old = read(CELL.read_bytes()).frame("Table").pose
    nudge = Rotation.from_euler("xyz", [0.3, -0.2, 0.45], degrees=True)
    r = Rotation.from_quat([old.q[1], old.q[2], old.q[3], old.q[0]]) * nudge
    x, y, z, w = r.as_quat()
    target = Pose.from_quat(old.x + 1.5, old.y - 1.0, old.z + 0.7, (w, x, y, z))
    path = tmp_path / "cell.installation"
    path.write_bytes(CELL.read_bytes())
    code, out, err = cli(capsys, "patch", path, "--frame", "Table", "--measured",
                         solution(tmp_path, target), "--in-place")
    assert code == 0, err
    assert "jointPositionVector" in err             # the joints are the old ones: said
    new_raw = path.read_bytes()
    assert new_raw[:10] == HEADER
    new_xml = zlib.decompress(new_raw, 31).decode()
    assert ur_cell.installation(new_xml) == new_raw      # zlib level 6 of the new XML
    # nothing but the plane's toolPosition and toolAxisAngle values changed
    assert masked(ur_cell.XML, *element_span(ur_cell.XML, "Table")) == \
        masked(new_xml, *element_span(new_xml, "Table"))
    f = read(new_raw).frame("Table")
    frame_rv = plane_points(f, "secondPoint")[3:]
    t = np.array(target.t) / 1000
    m = r.as_matrix()
    assert np.allclose(np.array(f.pose.t) / 1000, t, atol=1e-15)
    assert np.degrees((r.inv() * Rotation.from_rotvec(
        [f.numbers[k].value for k in ("rx", "ry", "rz")])).magnitude()) < 1e-9
    assert np.degrees((r.inv() * Rotation.from_rotvec(frame_rv)).magnitude()) < 1e-9
    # the taught points are the 3-point points of the measured frame (200 mm)
    taught = [plane_points(f, tag) for tag in ("userFirstPoint", "userSecondPoint",
                                                "userThirdPoint")]
    for p, want in zip(taught, (t, t + 0.2 * m[:, 0], t + 0.2 * m[:, 1])):
        assert np.allclose(p[:3], want, atol=1e-15)
    assert np.degrees((Rotation.from_matrix(construct(*[p[:3] for p in taught])).inv()
                       * r).magnitude()) < 1e-9
    assert np.allclose(plane_points(f, "secondPoint")[:3], t + m[:, 1], atol=1e-15)
    assert np.array_equal(plane_points(f, "thirdPoint"), taught[2])
    # each taught point keeps its tool orientation, turned with the frame
    turn = r * Rotation.from_quat([old.q[1], old.q[2], old.q[3], old.q[0]]).inv()
    was = read(CELL.read_bytes()).frame("Table")
    for tag, p in zip(("userFirstPoint", "userSecondPoint", "userThirdPoint"), taught):
        want = turn * Rotation.from_rotvec(plane_points(was, tag)[3:])
        assert np.degrees((want.inv() * Rotation.from_rotvec(p[3:])).magnitude()) < 1e-9
    code, out, err = cli(capsys, "check", path)
    assert code == 0 and "plane-points" not in out


def test_patching_a_plane_with_its_own_frame_changes_no_byte(tmp_path, capsys):
    f = read(CELL.read_bytes()).frame("Pick")
    path = tmp_path / "cell.installation"
    path.write_bytes(CELL.read_bytes())
    code, out, err = cli(capsys, "patch", path, "--frame", "Pick", "--measured",
                         solution(tmp_path, f.pose), "--in-place")
    assert code == 0 and path.read_bytes() == CELL.read_bytes(), err


def test_a_solved_tcp_patches_the_tcps_offset_only(tmp_path, capsys):
    path = tmp_path / "cell.installation"
    path.write_bytes(CELL.read_bytes())
    sol = solution(tmp_path, Pose.from_abc(0, 0, 0, 0, 0, 0), tcp=(1.5, -2.0, 151.25))
    code, out, err = cli(capsys, "patch", path, "--frame", "Gripper", "--measured", sol,
                         "--in-place")
    assert code == 0, err
    new_xml = zlib.decompress(path.read_bytes(), 31).decode()
    assert new_xml == ur_cell.XML.replace('offset="0.0, 0.0, 0.15, 0.0, 0.0, 0.7853981633974483"',
                                          'offset="0.0015, -0.002, 0.15125, 0.0, 0.0, '
                                          '0.7853981633974483"')


@pytest.mark.parametrize("path", [CELL] + [p for p in CORPUS_FILES if "barriere" in p.name],
                         ids=lambda p: p.name[-30:])
def test_a_feature_the_safety_configuration_uses_is_never_patched(tmp_path, capsys, path):
    name = "Fence" if path == CELL else "Magasin"
    raw = path.read_bytes()
    f = read(raw, str(path)).frame(name)
    copy = tmp_path / "x.installation"
    copy.write_bytes(raw)
    for how in (["--in-place"], ["-o", tmp_path / "out.installation"]):
        code, out, err = cli(capsys, "patch", copy, "--frame", name, "--measured",
                             solution(tmp_path, Pose.from_abc(*f.pose.t, 0, 0, 0)), *how)
        assert code == 2 and "safety" in err and "sourceFeatureId" in err, err
        assert f"x.installation:{f.line}:1: " in err
        assert copy.read_bytes() == raw and not (tmp_path / "out.installation").exists()


# -- solve --robot: taught poses as flange poses ---------------------------------------------
def test_taught_poses_read_as_flange_poses(tmp_path):
    """A taught pose is the TCP's: the flange is pose · tcpOffset⁻¹ (Pick was
    taught with a 100 mm TCP); a plane's taught points are PLANE.1 .. 3."""
    from ucsio.readers.robot import read_robot
    got = read_robot(CELL)
    names = [p.name for p in got.poses]
    assert names == ["Pick", "Table.1", "Table.2", "Table.3", "Fence.1", "Fence.2", "Fence.3"]
    pick = got.poses[0].flange
    tcp_rot = Rotation.from_rotvec(Rotation.from_rotvec([0, 3.1, 0.1]).as_rotvec())
    want_t = np.array([300.0, 100.0, 200.0]) - tcp_rot.apply([0, 0, 100.0])
    assert np.allclose(pick[:3, 3], want_t, atol=1e-9)
    assert np.allclose(pick[:3, :3], tcp_rot.as_matrix(), atol=1e-12)
    table = read(CELL.read_bytes()).frame("Table")
    assert np.allclose(got.poses[1].flange[:3, 3],
                       plane_points(table, "userFirstPoint")[:3] * 1000, atol=1e-9)


# -- diff, textconv, folders ------------------------------------------------------------------
def test_diff_of_two_installations_and_of_folders(tmp_path, capsys):
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir(), b.mkdir()
    (a / "cell.installation").write_bytes(CELL.read_bytes())
    moved = ur_cell.XML.replace('offset="0.0, 0.0, 0.15,', 'offset="0.0, 0.0, 0.152,')
    (b / "cell.installation").write_bytes(ur_cell.installation(moved))
    code, out, err = cli(capsys, "diff", a / "cell.installation", b / "cell.installation")
    assert code == 0 and "~ Gripper (TCP)" in out and "dz +2.000" in out, out
    code, out, err = cli(capsys, "diff", a, b)
    assert code == 0 and "Gripper" in out and "Table" not in out.split("unchanged")[0], out
    code, out, err = cli(capsys, "diff", "--textconv", b / "cell.installation")
    assert code == 0 and "Gripper TCP ref=flange x=0.0 y=0.0 z=0.152" in out
    assert '<tcp id="b5935d78' in out           # the XML itself, not gzip's bytes


def test_solve_robot_recovers_a_ucs_from_taught_point_features(tmp_path, capsys):
    """Synthetic truth: six point features taught with a 100 mm TCP at the
    UCS's points, each in another orientation; solve --robot reads their
    flange poses and, with --tcp 0,0,100, recovers the UCS."""
    rng = np.random.default_rng(4)
    ucs_r = Rotation.from_euler("xyz", [2.0, -3.0, 35.0], degrees=True)
    ucs_t = np.array([620.0, -140.0, 85.0])
    laser = rng.uniform(-300, 300, size=(6, 3)) * [1, 1, 0.2]
    nodes, lines = [], []
    for i, p in enumerate(laser, 1):
        tcp_at = (ucs_r.apply(p) + ucs_t) / 1000.0
        rv = (Rotation.from_rotvec([np.pi, 0, 0]) * Rotation.from_euler(
            "xyz", rng.uniform(-25, 25, 3), degrees=True)).as_rotvec()
        nodes.append(
            f'    <GeomPoseNode>\n      <GeomPoseNode id="p{i}" name="M{i}" isVariable="false">\n'
            f'        <toolPosition value="{", ".join(map(repr, tcp_at.tolist()))}"/>\n'
            f'        <toolAxisAngle value="{", ".join(map(repr, rv.tolist()))}"/>\n'
            '        <tcpOffset value="0.0, 0.0, 0.1, 0.0, 0.0, 0.0"/>\n'
            '      </GeomPoseNode>\n    </GeomPoseNode>\n')
        lines.append(f"M{i} " + " ".join(map(repr, p.tolist())))
    xml = ur_cell.XML.replace("  </Features>", "".join(nodes) + "  </Features>")
    (tmp_path / "m.installation").write_bytes(ur_cell.installation(xml))
    (tmp_path / "laser.txt").write_text("\n".join(lines) + "\n")
    code, out, err = cli(capsys, "solve", "--laser", tmp_path / "laser.txt", "--robot",
                         tmp_path / "m.installation", "--tcp", "0,0,100", "--json")
    assert code == 0, err
    f = json.loads(out)["frame"]
    np.testing.assert_allclose([f["x"], f["y"], f["z"]], ucs_t, atol=1e-6)
    got = Rotation.from_quat(np.roll(f["q"], -1))
    assert np.degrees((got.inv() * ucs_r).magnitude()) < 1e-7


def test_a_line_feature_is_named_by_check_and_not_listed(tmp_path, capsys):
    """A line (GeomLineNode) is no feature ucsio reads: frames leaves it
    out, check names it (an info), and patch finds no frame by its name."""
    line = ('<GeomLineNode>\n      <GeomLineNode name="Conveyor" showAxes="true" '
            'id="c0000000-0000-4000-8000-000000000000"/>\n    </GeomLineNode>\n    ')
    xml = ur_cell.XML.replace("<GeomPoseNode>", line + "<GeomPoseNode>", 1)
    path = tmp_path / "cell.installation"
    path.write_bytes(ur_cell.installation(xml))
    code, out, err = cli(capsys, "frames", path)
    assert code == 0 and "Pick" in out and "Conveyor" not in out, err
    code, out, err = cli(capsys, "check", path, "--json")
    lints = [x for f in json.loads(out)["files"] for x in f["lints"]]
    assert code == 0 and [(x["code"], x["severity"]) for x in lints] == [("unread-feature", "info")]
    assert "'Conveyor' is a line (GeomLineNode)" in lints[0]["message"]
    at = xml.index('<GeomLineNode name="Conveyor"')
    assert lints[0]["line"] == xml.count("\n", 0, at) + 1
    code, out, err = cli(capsys, "patch", path, "--frame", "Conveyor", "--set", "1,2,3,0,0,0")
    assert code == 2 and "no frame named 'Conveyor': it is a line (GeomLineNode)" in err, err
