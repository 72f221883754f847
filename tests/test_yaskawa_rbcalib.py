"""Yaskawa's RBCALIB.DAT (issue 27, point 6), the frame tree (point 2) and
diffs of files and backups (point 1): the corpus's two versions of the
Komatsu cell's calibration, fixtures in the corpus's style (CRLF) for what
it lacks, and the numbers against scipy."""
from __future__ import annotations

import json
import shutil

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from conftest import CORPUS, corpus_file
from test_yaskawa import GROUP1, GROUP2, cli, crlf, read, uframe, write

KOMATSU = "lukelalondePZ__Komatsu-Press-Demo__"
SRANG_NOW = (-2135.959, -4.939, -6.363, -0.0003, 0.3284, -179.9991)
SRANG_BEFORE = (21.194, 911.779, 30.780, -0.7153, 2.0659, -0.4335)


def rbcalib(srang: str, mgroup: str = GROUP1, sgroup: str = GROUP2, number: int = 1,
            extra: str = "") -> str:
    """One //RBCALIB block as a YRC1000 writes it (LF: the caller picks the ending)."""
    return (f"//RBCALIB {number}\n///MTOOL 2\n///MGROUP {mgroup}\n///MPULSE\n"
            "////MRBC1 C0000=172854,-24438,-18970,-58627,-39126,-8365\n"
            "////MRBC2 C0001=172854,-7102,-83965,-127137,-40012,35496\n"
            "////MRBC3 C0002=155412,26335,24246,-64943,-50545,-3872\n"
            f"///STOOL 1\n///SGROUP {sgroup}\n///SPULSE\n"
            "////SRBC1 C0000=-183295,20560,16467,67602,-47275,1818\n"
            "////SRBC2 C0001=-183110,35913,-44430,114562,-46550,-32700\n"
            "////SRBC3 C0002=-166762,84875,95125,63404,-64938,7345\n"
            f"{extra}////SRANG {srang}\n")


def komatsu(name: str):
    """A Komatsu cell's file by its whole name (RBCALIB.DAT begins its
    earlier version's name)."""
    path = CORPUS / "yaskawa" / (KOMATSU + name)
    if not path.is_file():
        pytest.skip(f"{path} is absent: the shared corpus is not beside this checkout")
    return path


def matrix(x, y, z, rx, ry, rz):
    m = np.eye(4)
    m[:3, :3] = Rotation.from_euler("xyz", [rx, ry, rz], degrees=True).as_matrix()
    m[:3, 3] = (x, y, z)
    return m


# -- reading ----------------------------------------------------------------------------
@pytest.mark.parametrize("name, srang, tools", [
    ("RBCALIB.DAT", SRANG_NOW, (2, 2)),
    ("RBCALIB.DAT.at-3ec0b394", SRANG_BEFORE, (0, 1)),
])
def test_corpus_rbcalib_is_a_frame_of_both_robots(name, srang, tools):
    from ucsio.parsing.controller import parse
    from ucsio.parsing.document import Document
    path = komatsu(name)
    raw = path.read_bytes()
    cf = parse(Document(raw, str(path)), full=True)    # by its first line, whatever its name
    assert cf.vendor == "yaskawa" and cf.document.to_bytes() == raw
    (frame,) = cf.frames
    assert (frame.name, frame.type, frame.label) == ("RBCALIB1", "RBCALIB", "R2 base in R1 base")
    assert (frame.parent.kind, frame.parent.name) == ("robot", "robot")   # the master's base
    info = frame.info
    assert (info["master"], info["slave"]) == ("R1", "R2")
    assert (info["master_tool"], info["slave_tool"]) == tools
    # the pose is SRANG, R = Rz·Ry·Rx (scipy's extrinsic xyz)
    assert np.allclose(np.array(frame.pose.matrix), matrix(*srang)[:3, :3], atol=1e-12)
    assert frame.pose.t == srang[:3]
    for key, num in frame.numbers.items():
        assert cf.document.slice(num.span) == num.text and float(num.text) == num.value
    assert cf.lints == []           # the taught pulses are known lines: kept, not reported


def test_taught_pulses_are_kept_verbatim_and_not_interpreted():
    """MRBC/SRBC lines are joint pulses: nothing of them is a number of a
    frame, and a changed pulse round-trips as written."""
    text = rbcalib("1.000,2.000,3.000,0.0000,0.0000,0.0000")
    cf = read(crlf(text), "RBCALIB.DAT")
    (frame,) = cf.frames
    srang_line = text.splitlines().index("////SRANG 1.000,2.000,3.000,0.0000,0.0000,0.0000") + 1
    assert {cf.document.line_of(n.span.start) for n in frame.numbers.values()} == {srang_line}
    assert not any("172854" in str(v) for v in frame.info.values())
    odd = crlf(text.replace("C0000=172854", "C0000=+172854.5"))
    assert read(odd, "RBCALIB.DAT").document.to_bytes() == odd


def test_two_blocks_unknown_lines_and_an_unnamed_robot():
    text = (rbcalib("1.000,2.000,3.000,0.0000,0.0000,0.0000", extra="///NEWKEY 7\n")
            + rbcalib("4.000,5.000,6.000,0.0000,0.0000,190.0000", number=2,
                      mgroup="0,0,1" + ",0" * 29, sgroup="0" + ",0" * 31))
    data = crlf(text)
    cf = read(data, "RBCALIB.DAT")
    assert cf.document.to_bytes() == data
    assert [(f.name, f.label, f.parent.name) for f in cf.frames] == [
        ("RBCALIB1", "R2 base in R1 base", "robot"),
        ("RBCALIB2", "an unknown robot base in R3 base", "robot@3")]
    assert sorted((lint.line, lint.code, lint.severity) for lint in cf.lints) == [
        (14, "unknown-line", "info"), (24, "group-flags", "warning"),
        (29, "angle-range", "warning")]


def test_a_block_twice_is_a_warning():
    text = rbcalib("1.000,2.000,3.000,0,0,0") + rbcalib("4.000,5.000,6.000,0,0,0")
    cf = read(crlf(text), "RBCALIB.DAT")
    assert [f.name for f in cf.frames] == ["RBCALIB1", "RBCALIB1"]
    assert [(lint.line, lint.code) for lint in cf.lints] == [(15, "duplicate-block")]
    assert "line 1 and here" in cf.lints[0].message


@pytest.mark.parametrize("text, where, words", [
    ("//RBCALIB 1\n///MTOOL 2\n", "2:11", "//RBCALIB 1 has no ////SRANG line"),
    ("//RBCALIB 1\n////SRANG 1.000,2.000,x,0,0,0\n", "2:23", "////SRANG: not a number: 'x'"),
    ("//RBCALIB 1\n////SRANG 1.000,2.000,3.000,0,0\n", "2:32", "six numbers"),
    ("//RBCALIB\n////SRANG 1,2,3,0,0,0\n", "1:10", "//RBCALIB without its number"),
    ("//RBCALIB 1\n///MTOOL a\n////SRANG 1,2,3,0,0,0\n", "2:10", "///MTOOL is 1 integer"),
    ("//RBCALIB 1\n////SRANG 1,2,3,0,0,0\n//UFRAME 1\n", "3:1", "not an RBCALIB.DAT"),
])
def test_bad_input_is_one_error_at_its_place(tmp_path, capsys, text, where, words):
    path = write(tmp_path, "RBCALIB.DAT", crlf(text))
    for command in ("frames", "check", "diff"):
        args = (path, path) if command == "diff" else (path,)
        code, out, err = cli(capsys, command, *args)
        assert code == 2, (command, out, err)
        assert f"{path}:{where}: " in err and words in err, err
    assert path.read_bytes() == crlf(text)


def test_patch_refuses_the_calibration_and_writes_nothing(tmp_path, capsys):
    data = crlf(rbcalib("1.000,2.000,3.000,0.0000,0.0000,0.0000"))
    path = write(tmp_path, "RBCALIB.DAT", data)
    code, out, err = cli(capsys, "patch", path, "--frame", "RBCALIB1", "--set", "1,2,4,0,0,0",
                         "--in-place")
    assert code == 2 and f"{path}:1:1: RBCALIB1: RBCALIB.DAT's ////SRANG" in err, err
    assert path.read_bytes() == data


# -- the frame tree -----------------------------------------------------------------------
def test_tree_puts_the_calibration_under_the_master_robot(tmp_path, capsys):
    data = crlf(rbcalib("1.000,2.000,3.000,0.0000,0.0000,0.0000", mgroup=GROUP2,
                        sgroup=GROUP1))
    path = write(tmp_path, "RBCALIB.DAT", data)
    code, out, err = cli(capsys, "frames", "--tree", path)
    assert code == 0, err
    assert out.splitlines()[:3] == [
        "world", '└── robot@2  "R2"',
        f'    └── RBCALIB1  RBCALIB  "R1 base in R2 base"  {path}:1']


def test_frame_on_a_frame_is_compared_in_its_parent(tmp_path, capsys):
    """UF2 is defined on UF1 (///BASICFRM 1,19,1). When UF1 moves, UF2's
    BUSER (in UF1) does not change, and the diff does not report UF1's move
    as UF2's; when UF2 moves in UF1 as well, its delta is the one in UF1."""
    old = crlf(uframe(1, "TABLE", "800.000,-600.000,-14.000,0.0000,0.0000,30.0000")
               + uframe(2, "FIXTURE", "100.000,20.000,5.000,0.0000,0.0000,90.0000",
                        basicfrm="1,19,1"))
    moved = old.replace(b"800.000,-600.000,-14.000,0.0000,0.0000,30.0000",
                        b"805.000,-600.000,-14.000,0.0000,0.0000,31.0000")
    a, b = write(tmp_path, "a.CND", old), write(tmp_path, "b.CND", moved)
    code, out, err = cli(capsys, "diff", a, b, "--json")
    doc = json.loads(out)
    assert code == 0, err
    assert [c["name"] for c in doc["changed"]] == ["UF1"] and doc["unchanged"] == 1
    (uf1,) = doc["changed"]
    assert (uf1["dx"], uf1["da"]) == pytest.approx((5.0, 1.0))
    both = write(tmp_path, "c.CND", moved.replace(b"100.000,20.000", b"100.250,20.000"))
    code, out, err = cli(capsys, "diff", a, both, "--json")
    uf2 = {c["name"]: c for c in json.loads(out)["changed"]}["UF2"]
    assert uf2["old"]["parent"] == uf2["new"]["parent"] == "UF1"
    assert (uf2["dx"], uf2["dy"], uf2["dz"], uf2["angle"]) == pytest.approx(
        (0.25, 0.0, 0.0, 0.0), abs=1e-9)


def test_lf_only_lint_on_the_corpus_uframe_and_not_on_a_crlf_copy(tmp_path, capsys):
    path = corpus_file("yaskawa", "UFRAME.CND")
    assert b"\r\n" not in path.read_bytes()         # git normalised it
    code, out, err = cli(capsys, "check", path)
    assert code == 1 and f"{path}:1:11: warning: lf-only" in out
    copy = write(tmp_path, "UFRAME.CND", path.read_bytes().replace(b"\n", b"\r\n"))
    code, out, err = cli(capsys, "check", copy)
    assert code == 0 and "lf-only" not in out and "round trip ok" in out


# -- diff ---------------------------------------------------------------------------------
def test_diff_of_the_corpus_calibrations_says_the_robots_relation_changed(capsys):
    """The two versions disagree by ~2.3 m and 180° on where R2 stands:
    the diff's numbers against numpy and scipy."""
    before, now = komatsu("RBCALIB.DAT.at-3ec0b394"), komatsu("RBCALIB.DAT")
    code, out, err = cli(capsys, "diff", before, now, "--json", "--exit-code")
    doc = json.loads(out)
    assert code == 1, err
    (change,) = doc["changed"]
    assert change["name"] == "RBCALIB1" and change["label"] == "R2 base in R1 base"
    a, b = matrix(*SRANG_BEFORE), matrix(*SRANG_NOW)
    assert change["dist"] == pytest.approx(np.linalg.norm(b[:3, 3] - a[:3, 3]), abs=1e-9)
    assert change["dist"] == pytest.approx(2344.155, abs=1e-3)
    turn = Rotation.from_matrix(a[:3, :3].T @ b[:3, :3]).magnitude()
    assert change["angle"] == pytest.approx(np.degrees(turn), abs=1e-6)
    code, out, err = cli(capsys, "diff", before, now)
    assert '~ RBCALIB1 "R2 base in R1 base" (RBCALIB): value' in out
    assert "master_tool: 0 -> 2" in out and "dist 2344.155 mm" in out


def backup(folder, uframe_cnd, tool_cnd, rbcalib_dat):
    folder.mkdir()
    for name, src in (("UFRAME.CND", uframe_cnd), ("TOOL.CND", tool_cnd),
                      ("RBCALIB.DAT", rbcalib_dat)):
        shutil.copy(src, folder / name)
    return folder


def test_diff_of_two_backup_folders(tmp_path, capsys):
    uframes = corpus_file("yaskawa", "UFRAME.CND")
    old = backup(tmp_path / "old", uframes, komatsu("TOOL.CND.at-3ec0b394"),
                 komatsu("RBCALIB.DAT.at-3ec0b394"))
    new = backup(tmp_path / "new", uframes, komatsu("TOOL.CND"), komatsu("RBCALIB.DAT"))
    code, out, err = cli(capsys, "diff", old, new, "--json")
    assert code == 0, err
    doc = json.loads(out)
    changed = {(c["name"], c["new"]["file"].rpartition("/")[2]) for c in doc["changed"]}
    assert ("RBCALIB1", "RBCALIB.DAT") in changed
    assert not any(file == "UFRAME.CND" for _, file in changed)
    code, out, err = cli(capsys, "diff", old, new, "--exit-code")
    assert code == 1 and '~ RBCALIB1 "R2 base in R1 base" (RBCALIB)' in out



def test_diff_of_tool_cnds_whose_every_crc_changed(capsys):
    """One tool edit changes every ///CRC line of a TOOL.CND: the diff
    reports the tools that moved and shows those lines as the text diff
    (lines changed beyond the frame values), in the corpus's two versions."""
    before, now = komatsu("TOOL.CND.at-3ec0b394"), komatsu("TOOL.CND")
    code, out, err = cli(capsys, "diff", before, now)
    assert code == 0, err
    assert [ln.split()[1] for ln in out.splitlines() if ln.startswith("~ ")] == [
        "UT2", "UT3", "UT4"]
    assert "lines changed beyond the frame values above" in out
    assert sum(ln.startswith("-///CRC ") for ln in out.splitlines()) == 64


def test_diff_of_values_alone_shows_no_text_diff(tmp_path, capsys):
    from test_yaskawa import TOOLS
    a = write(tmp_path, "a.CND", TOOLS)
    b = write(tmp_path, "b.CND", TOOLS.replace(b"365.400", b"365.900"))
    code, out, err = cli(capsys, "diff", a, b)
    assert code == 0 and "~ UT0" in out and "dz +0.500" in out
    assert "lines changed beyond" not in out
    c = write(tmp_path, "c.CND", TOOLS.replace(b"365.400", b"365.900").replace(b"GUN", b"GUN2"))
    code, out, err = cli(capsys, "diff", a, c)
    assert "label: GUN -> GUN2" in out and "lines changed beyond" in out   # ///NAME: not a value
    assert "-///NAME GUN\r" not in out and "-///NAME GUN" in out and "+///NAME GUN2" in out
