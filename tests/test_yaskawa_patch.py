"""Writing Yaskawa frames back (issue 27, point 5, the UFRAME.CND route):
``patch`` rewrites a ////BUSER line or a tool's pose line in place.

What it holds: every byte outside the six numbers stays (every corpus user
frame, the fixtures here, CRLF kept); the numbers are written as the
controller writes them (3 and 4 decimals) and read back to the pose, the
angles checked against scipy; the taught-points warning; a measured frame
on another user frame goes through that frame, on the master robot's tool it
is refused; a TOOL.CND with ///CRC is refused at its ///CRC line, one
without takes a solved TCP. Fixtures are in the corpus's style (CRLF).
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from conftest import CORPUS
from test_yaskawa import UFRAMES, cli, crlf, tool, uframe, write
from ucsio.geometry.frames import Pose
from ucsio.parsing.controller import parse
from ucsio.parsing.document import Document

CORPUS_UFRAME = CORPUS / "yaskawa" / "icors2__Yaskawa-Job-Helper__fixtures__transform__UFRAME.CND"
NUMBERS = ("x", "y", "z", "rx", "ry", "rz")
WARNING = "no longer produce this frame"


def corpus_uframe() -> bytes:
    if not CORPUS_UFRAME.is_file():
        pytest.skip(f"{CORPUS_UFRAME} is absent: the shared corpus is not beside this checkout")
    return CORPUS_UFRAME.read_bytes()


def read(data: bytes, name: str = "UFRAME.CND"):
    return parse(Document(data, name))


def yaskawa_pose(x, y, z, rx, ry, rz) -> Pose:
    """A pose from Yaskawa's own numbers, through scipy (R = Rz·Ry·Rx)."""
    q = Rotation.from_euler("xyz", [rx, ry, rz], degrees=True).as_quat()   # x, y, z, w
    return Pose.from_quat(x, y, z, (q[3], q[0], q[1], q[2]))


def solution(tmp_path, pose: Pose, tcp=None):
    data = {"frame": pose.as_dict(), "accepted": True}
    if tcp is not None:
        data["tcp"] = {"x": tcp[0], "y": tcp[1], "z": tcp[2], "solved": True}
    path = tmp_path / "S.json"
    path.write_text(json.dumps(data))
    return path


def outside_spans(data: bytes, frame) -> bytes:
    """``data`` with the frame's six numbers cut out (a text of ASCII)."""
    text = data.decode("ascii")
    spans = sorted((frame.numbers[k].span for k in NUMBERS), key=lambda sp: sp.start)
    kept, pos = [], 0
    for sp in spans:
        kept.append(text[pos:sp.start])
        pos = sp.end
    return "|".join(kept + [text[pos:]]).encode("ascii")


def assert_written(before: bytes, after: bytes, name: str, pose: Pose):
    """Only the frame's six spans changed; they hold the pose as the
    controller writes it, to the written precision (scipy's angles)."""
    old, new = read(before).frame(name), read(after).frame(name)
    assert outside_spans(before, old) == outside_spans(after, new)
    texts = [new.numbers[k].text for k in NUMBERS]
    assert all(len(t.split(".")[1]) == (3 if i < 3 else 4) for i, t in enumerate(texts)), texts
    assert np.allclose(new.pose.t, pose.t, atol=0.0005 + 1e-9)
    got = Rotation.from_euler("xyz", [new.numbers[k].value for k in ("rx", "ry", "rz")],
                              degrees=True)
    want = Rotation.from_quat([pose.q[1], pose.q[2], pose.q[3], pose.q[0]])
    assert math.degrees((got.inv() * want).magnitude()) <= 5e-4


# -- UFRAME.CND: --measured and --set ---------------------------------------------------
@pytest.mark.parametrize("name", ["UF1", "UF2", "UF3"])
def test_measured_patch_of_every_corpus_user_frame(tmp_path, capsys, name):
    """Each corpus frame moved by a known small correction: only its BUSER
    numbers change (the LF file stays LF), the warning names its taught points."""
    data = corpus_uframe()
    old = read(data).frame(name).pose
    nudge = Rotation.from_euler("xyz", [0.31, -0.12, 0.45], degrees=True)
    r = Rotation.from_quat([old.q[1], old.q[2], old.q[3], old.q[0]]) * nudge
    x, y, z = (v + d for v, d in zip(old.t, (1.2345, -0.5, 2.0)))
    rx, ry, rz = r.as_euler("xyz", degrees=True)
    target = yaskawa_pose(x, y, z, rx, ry, rz)
    path = write(tmp_path, "UFRAME.CND", data)
    code, out, err = cli(capsys, "patch", path, "--frame", name,
                         "--measured", solution(tmp_path, target), "--in-place")
    assert code == 0, err
    assert f"{name}: the taught points stored with it (////RORG, ////RXX, ////RXY) " \
           f"{WARNING}" in err and "jumps back" in err
    assert_written(data, path.read_bytes(), name, target)
    assert b"\r\n" not in path.read_bytes()


def test_a_patch_that_changes_nothing_warns_of_nothing(tmp_path, capsys):
    """The taught-points warning is about a changed frame: a patch to the
    values the file already holds says so, and nothing else."""
    data = corpus_uframe()
    pose = read(data).frame("UF2")
    values = [pose.numbers[k].text for k in ("x", "y", "z", "rz", "ry", "rx")]
    path = write(tmp_path, "UFRAME.CND", data)
    code, out, err = cli(capsys, "patch", path, "--frame", "UF2", "--set", ",".join(values))
    assert code == 0 and "nothing to change" in out, (out, err)
    assert "RORG" not in err and "warning" not in err, err
    assert path.read_bytes() == data


def test_set_writes_crlf_fixture_in_place(tmp_path, capsys):
    """--set X,Y,Z,A,B,C takes SPEC's A, B, C: A = rz, B = ry, C = rx."""
    path = write(tmp_path, "UFRAME.CND", UFRAMES)
    code, out, err = cli(capsys, "patch", path, "--frame", "UF3",
                         "--set", "-50.4996,1,700,-30,12.5,-170.25", "--in-place")
    assert code == 0, err
    after = path.read_bytes()
    assert b"////BUSER -50.500,1.000,700.000,-170.2500,12.5000,-30.0000\r\n" in after
    assert after.count(b"\r\n") == UFRAMES.count(b"\r\n") and b"\n" not in after.replace(
        b"\r\n", b"")
    assert_written(UFRAMES, after, "UF3", yaskawa_pose(-50.4996, 1, 700, -170.25, 12.5, -30))
    assert WARNING in err


def test_angle_at_180_and_a_rotation_that_does_not_move_keep_their_text(tmp_path, capsys):
    """UF3 holds rx 180, ry -45: a translation alone changes x only, the
    angles keep their text."""
    path = write(tmp_path, "UFRAME.CND", UFRAMES)
    code, out, err = cli(capsys, "patch", path, "--frame", "UF3",
                         "--set", "-40,0,700,0,-45,180", "-o", tmp_path / "out.CND")
    assert code == 0, err
    after = (tmp_path / "out.CND").read_bytes()
    assert after == UFRAMES.replace(b"////BUSER -50.500,", b"////BUSER -40.000,")


def test_frame_on_another_user_frame_is_written_in_that_frame(tmp_path, capsys):
    """UF2 is defined on UF1 (///BASICFRM 1,19,1): a measured frame in the
    robot base is written as UF1^-1 · measured, checked by composing back."""
    path = write(tmp_path, "UFRAME.CND", UFRAMES)
    target = yaskawa_pose(900.0, -500.0, 10.0, 1.5, -2.0, 30.0)
    code, out, err = cli(capsys, "patch", path, "--frame", "UF2",
                         "--measured", solution(tmp_path, target), "--in-place")
    assert code == 0, err
    cf = read(path.read_bytes())
    uf1, uf2 = cf.frame("UF1"), cf.frame("UF2")

    def matrix(f):
        n = [f.numbers[k].value for k in NUMBERS]
        m = np.eye(4)
        m[:3, :3] = Rotation.from_euler("xyz", n[3:], degrees=True).as_matrix()
        m[:3, 3] = n[:3]
        return m

    world = matrix(uf1) @ matrix(uf2)
    want = Rotation.from_quat([target.q[1], target.q[2], target.q[3], target.q[0]])
    assert np.allclose(world[:3, 3], target.t, atol=0.002)
    angle = (Rotation.from_matrix(world[:3, :3]).inv() * want).magnitude()
    assert math.degrees(angle) <= 1e-3


def test_nested_or_master_tool_frames_refuse_a_measured_patch(tmp_path, capsys):
    """A frame on a frame that is on a frame, or on the master robot's tool:
    a measured frame in the robot base does not fit; exit 2, nothing written."""
    data = crlf(uframe(1, "A", "100.000,0.000,0.000,0.0000,0.0000,0.0000")
                + uframe(2, "B", "10.000,0.000,0.000,0.0000,0.0000,90.0000", basicfrm="1,19,1")
                + uframe(3, "C", "1.000,2.000,3.000,0.0000,0.0000,0.0000", basicfrm="1,19,2")
                + uframe(4, "D", "1.000,2.000,3.000,0.0000,0.0000,0.0000", basicfrm="1,20,0"))
    path = write(tmp_path, "UFRAME.CND", data)
    sol = solution(tmp_path, Pose.from_abc(1, 2, 3, 0, 0, 0))
    for name, line, why in (("UF3", 23, "defined on UF1 in turn"),
                            ("UF4", 34, "moves with master robot's tool")):
        for force in ([], ["--force"]) if name == "UF3" else ([],):
            code, out, err = cli(capsys, "patch", path, "--frame", name, "--measured", sol,
                                 "--in-place", *force)
            assert code == 2 and f"{path}:{line}:" in err and why in err, err
            assert path.read_bytes() == data


def test_unknown_robot_refuses_a_measured_patch(tmp_path, capsys):
    """///GROUP with no flag: the frame's robot is not known."""
    data = crlf(uframe(1, "A", "1.000,2.000,3.000,0.0000,0.0000,0.0000", group="0" + ",0" * 31))
    path = write(tmp_path, "UFRAME.CND", data)
    code, out, err = cli(capsys, "patch", path, "--frame", "UF1", "--measured",
                         solution(tmp_path, Pose.from_abc(1, 2, 4, 0, 0, 0)), "--in-place")
    assert code == 2 and "not robot world" in err and path.read_bytes() == data


# -- TOOL.CND ---------------------------------------------------------------------------
def tools(crc: bool) -> bytes:
    return crlf(tool(0, "STANDARD TOOL", "0.000,0.000,0.000,0.0000,90.0000,0.0000", crc)
                + tool(1, "TORCH", "1.500,-2.000,300.000,0.0000,0.0000,0.0000", crc))


def test_tool_cnd_with_crc_is_refused_with_the_reason(tmp_path, capsys):
    data = tools(crc=True)
    path = write(tmp_path, "TOOL.CND", data)
    for args in (["--set", "1,2,3,0,0,0"],
                 ["--measured", solution(tmp_path, Pose.from_abc(0, 0, 0, 0, 0, 0),
                                         tcp=(1, 2, 301))]):
        code, out, err = cli(capsys, "patch", path, "--frame", "UT1", *args, "--in-place")
        assert code == 2, err
        assert f"{path}:10:1: UT1: this TOOL.CND carries a ///CRC checksum" in err
        assert "may reject a file whose checksum does not match" in err
        assert path.read_bytes() == data


def test_a_crc_line_in_another_block_still_refuses_the_file(tmp_path, capsys):
    """Only UT1 carries ///CRC (a block's line lost, a hand edit): the file
    has a checksum all the same, so UT0 is not written either; a user frame
    file with one likewise (found by benchmarks/fuzz.py)."""
    data = crlf(tool(0, "STANDARD TOOL", "0.000,0.000,0.000,0.0000,90.0000,0.0000", False)
                + tool(1, "TORCH", "1.500,-2.000,300.000,0.0000,0.0000,0.0000", True))
    path = write(tmp_path, "TOOL.CND", data)
    code, out, err = cli(capsys, "patch", path, "--frame", "UT0", "--set", "1,2,3,0,0,0",
                         "--in-place")
    assert code == 2 and path.read_bytes() == data
    assert f"{path}:9:1: UT0: this TOOL.CND carries a ///CRC checksum" in err
    frames = UFRAMES.replace(b"///NAME TABLE\r\n", b"///NAME TABLE\r\n///CRC 12\r\n")
    path = write(tmp_path, "UFRAME.CND", frames)
    code, out, err = cli(capsys, "patch", path, "--frame", "UF1", "--set", "1,2,3,0,0,0",
                         "--in-place")
    assert code == 2 and path.read_bytes() == frames
    assert f"{path}:3:1: UF1: this UFRAME.CND carries a ///CRC checksum" in err


def test_tool_cnd_without_crc_takes_a_solved_tcp(tmp_path, capsys):
    data = tools(crc=False)
    path = write(tmp_path, "TOOL.CND", data)
    sol = solution(tmp_path, Pose.from_abc(0, 0, 0, 0, 0, 0), tcp=(1.25, -2.0, 301.4567))
    code, out, err = cli(capsys, "patch", path, "--frame", "UT1", "--measured", sol,
                         "--in-place")
    assert code == 0, err
    after = path.read_bytes()
    assert after == data.replace(b"1.500,-2.000,300.000,", b"1.250,-2.000,301.457,")
    assert WARNING not in err


def test_a_measured_frame_is_not_a_tool(tmp_path, capsys):
    """A tool is relative to the flange: a measured frame without a solved
    TCP is refused there as for the other vendors."""
    data = tools(crc=False)
    path = write(tmp_path, "TOOL.CND", data)
    code, out, err = cli(capsys, "patch", path, "--frame", "UT1", "--measured",
                         solution(tmp_path, Pose.from_abc(1, 2, 3, 0, 0, 0)), "--in-place")
    assert code == 2 and "relative to the flange" in err and path.read_bytes() == data



def test_patch_stays_light(tmp_path):
    """patch of a UFRAME.CND imports none of numpy, scipy, lark."""
    import subprocess
    import sys
    path = write(tmp_path, "UFRAME.CND", UFRAMES)
    probe = ("import sys, io, contextlib\nfrom ucsio.cli import main\n"
             "with contextlib.redirect_stdout(io.StringIO()):\n    main(sys.argv[1:])\n"
             "print(' '.join(m for m in ('numpy', 'scipy', 'lark') if m in sys.modules))")
    args = ["patch", str(path), "--frame", "UF1", "--set", "1,2,3,4,5,6"]
    res = subprocess.run([sys.executable, "-c", probe, *args], capture_output=True, text=True,
                         check=True)
    assert res.stdout.strip() == "", res.stdout
