"""Yaskawa Motoman UFRAME.CND and TOOL.CND (issue 27, first part: reading them).

The shared tests hold what every vendor gets (tests/test_every_vendor.py:
the corpus's .CND files round-trip with their numbers at their spans;
tests/test_frames_snapshot.py: their frames). Here: the convention against
scipy and the corpus's own evidence, the files' forms the corpus lacks
(CRLF, a frame on another frame, a second robot, unknown lines), the frame
tree, the lints, bad input, the files still refused, and the commands.
Fixtures are written here in the corpus's style (CRLF, as controllers write).
"""
from __future__ import annotations

import json
import random
import subprocess
import sys

import pytest

from conftest import CORPUS, corpus_file
from ucsio.cli import main
from ucsio.parsing.controller import parse
from ucsio.parsing.document import Document

KOMATSU = "lukelalondePZ__Komatsu-Press-Demo__"
GROUP1 = "1" + ",0" * 31
GROUP2 = "0,1" + ",0" * 30


def uframe(n: int, name: str, buser: str, basicfrm: str = "1,16,0", group: str = GROUP1,
           basep: str = "0.000,0.000,0.000,0.0000,0.0000,0.0000", extra: str = "") -> str:
    """One //UFRAME block as a YRC1000 writes it (LF: the caller picks the ending)."""
    return (f"//UFRAME {n}\n///NAME {name}\n///TOOL 0\n///GROUP {group}\n///BASICFRM {basicfrm}\n"
            f"///BASEP {basep}\n///PULSE\n"
            "////RORG C000=-202041,-68179,-82397,-47606,-56939,36643,0,0,0\n"
            "////RXX C001=-217178,-82740,-89297,-47410,-66939,39264,0,0,0\n"
            "////RXY C002=-208718,-43873,-68857,-50000,-57576,40017,0,0,0\n"
            f"{extra}////BUSER {buser}\n")


def tool(n: int, name: str, pose: str, crc: bool) -> str:
    head = f"//TOOL {n}\n" + ("///CRC 3243358777\n" if crc else "")
    named = f"///NAME {name}\n" if name else "///NAME\n"
    return head + named + pose + "\n0.000,0.000,0.000\n0.000\n0.000,0.000,0.000\n0.000,0,1\n"


def komatsu_tool():
    """The Komatsu cell's TOOL.CND, by its whole name (it begins its earlier
    version's name, TOOL.CND.at-3ec0b394)."""
    path = CORPUS / "yaskawa" / (KOMATSU + "TOOL.CND")
    if not path.is_file():
        pytest.skip(f"{path} is absent: the shared corpus is not beside this checkout")
    return path


def crlf(text: str) -> bytes:
    return text.replace("\n", "\r\n").encode()


UFRAMES = crlf(uframe(1, "TABLE", "841.349,-619.510,-14.118,-0.0176,0.0306,-10.0157")
               + uframe(2, "FIXTURE", "100.000,20.000,5.000,0.0000,0.0000,90.0000",
                        basicfrm="1,19,1")
               + uframe(3, "R2 TABLE", "-50.500,0.000,700.000,180.0000,-45.0000,0.0000",
                        group=GROUP2)
               + uframe(4, "ON GRIPPER", "1.000,2.000,3.000,0.0000,0.0000,0.0000",
                        basicfrm="1,20,0"))


def write(tmp_path, name: str, data: bytes):
    path = tmp_path / name
    path.write_bytes(data)
    return path


def read(data: bytes, name: str = "UFRAME.CND", full: bool = False):
    return parse(Document(data, name), full=full)


def cli(capsys, *args):
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


# -- the convention ---------------------------------------------------------------------
def test_rotation_is_rz_ry_rx_as_scipys_extrinsic_xyz():
    """R = Rz(rz)·Ry(ry)·Rx(rx): scipy's from_euler('xyz', [rx, ry, rz]) (lower
    case: extrinsic), on the corpus's user frames and on random angles."""
    from scipy.spatial.transform import Rotation
    import numpy as np

    rng = random.Random(27)
    angles = [tuple(rng.uniform(-180, 180) for _ in range(3)) for _ in range(20)]
    angles[:0] = [(0.7381, 0.4043, 87.7138), (-0.0176, 0.0306, -10.0157), (180.0, -45.0, 0.0)]
    for rx, ry, rz in angles:
        text = f"//UFRAME 1\n///GROUP {GROUP1}\n////BUSER 1.000,2.000,3.000,{rx},{ry},{rz}\n"
        (frame,) = read(crlf(text)).frames
        want = Rotation.from_euler("xyz", [rx, ry, rz], degrees=True).as_matrix()
        assert np.allclose(np.array(frame.pose.matrix), want, atol=1e-12), (rx, ry, rz)
        # the intrinsic reading (X-Y'-Z'') is another matrix: the test tells them apart
        other = Rotation.from_euler("XYZ", [rx, ry, rz], degrees=True).as_matrix()
        assert not np.allclose(want, other, atol=1e-6) or abs(ry) < 1e-9
    corpus = corpus_file("yaskawa", "UFRAME.CND")
    for frame in parse(Document.read(corpus)).frames:
        i = frame.info
        want = Rotation.from_euler("xyz", [i["rx"], i["ry"], i["rz"]], degrees=True).as_matrix()
        assert np.allclose(np.array(frame.pose.matrix), want, atol=1e-12), frame.name


def test_the_corpus_tools_point_where_they_reach():
    """The corpus's own evidence of the signs: the Komatsu cell's suction tools
    stand 165.205 mm off the flange axis, SUCTION1 along -x with ry = -90,
    SUCTION2 along +y with rx = -90; with R = Rz·Ry·Rx each one's approach
    axis (R·z) points the way its offset reaches (a sign flipped would point
    it back into the robot)."""
    cf = parse(Document.read(komatsu_tool()))
    for name, axis in (("UT3", (-1.0, 0.0, 0.0)), ("UT4", (0.0, 1.0, 0.0))):
        frame = cf.frame(name)
        z = tuple(row[2] for row in frame.pose.matrix)
        assert z == pytest.approx(axis, abs=1e-12), name
        x, y, _ = frame.pose.t
        assert (x * axis[0] + y * axis[1]) == pytest.approx(165.205)


# -- reading -------------------------------------------------------------------------------
def test_user_frames_names_labels_values_and_spans():
    cf = read(UFRAMES, full=True)
    assert [(f.name, f.type, f.label, f.line) for f in cf.frames] == [
        ("UF1", "UFRAME", "TABLE", 1), ("UF2", "UFRAME", "FIXTURE", 12),
        ("UF3", "UFRAME", "R2 TABLE", 23), ("UF4", "UFRAME", "ON GRIPPER", 34)]
    uf1 = cf.frames[0]
    assert uf1.pose.t == (841.349, -619.51, -14.118)
    assert uf1.pose.abc == (-10.0157, 0.0306, -0.0176)         # KUKA's A = rz, C = rx
    assert (uf1.info["rx"], uf1.info["ry"], uf1.info["rz"]) == (-0.0176, 0.0306, -10.0157)
    assert uf1.info["tool"] == 0 and uf1.info["basicfrm"] == "1,16,0"
    doc = cf.document
    assert doc.to_bytes() == UFRAMES
    for f in cf.frames:
        assert list(f.numbers) == ["x", "y", "z", "rx", "ry", "rz"]
        for num in f.numbers.values():
            assert doc.slice(num.span) == num.text and float(num.text) == num.value
    # the spans are exactly the BUSER values: replacing them changes nothing else
    assert doc.slice(uf1.numbers["rz"].span) == "-10.0157"
    assert doc.text[uf1.numbers["x"].span.start - 10:uf1.numbers["x"].span.start] == "////BUSER "


@pytest.mark.parametrize("crc", [True, False], ids=["with-crc", "without-crc"])
@pytest.mark.parametrize("ending", ["\r\n", "\n", "\r"], ids=["crlf", "lf", "cr"])
def test_tool_cnd_with_and_without_crc_round_trips(crc, ending):
    text = (tool(0, "STANDARD TOOL", "0.000,0.000,0.000,0.0000,90.0000,0.0000", crc)
            + tool(1, "", "0.000,0.000,0.000,0.0000,0.0000,0.0000", crc)
            + tool(2, "SUCTION1", "-165.205,0.000,358.005,0.0000,-90.0000,0.0000", crc))
    data = text.replace("\n", ending).encode()
    cf = read(data, "TOOL.CND", full=True)
    assert cf.document.to_bytes() == data
    assert [(f.name, f.label, f.reference, f.parent.kind) for f in cf.frames] == [
        ("UT0", "STANDARD TOOL", "flange", "flange"), ("UT1", None, "flange", "flange"),
        ("UT2", "SUCTION1", "flange", "flange")]
    assert all(f.info.get("crc", False) is crc for f in cf.frames)
    assert cf.frames[2].pose.t == (-165.205, 0.0, 358.005)
    assert cf.lints == []           # LF is only a trap for UFRAME.CND


def test_corpus_tool_cnd_at_an_earlier_version_reads_by_its_first_line():
    """The corpus's TOOL.CND.at-3ec0b394 has no .CND suffix (a git temporary
    file has none either): its first line says what it is."""
    path = corpus_file("yaskawa", KOMATSU + "TOOL.CND.at-3ec0b394")
    raw = path.read_bytes()
    cf = parse(Document(raw, str(path)), full=True)
    assert cf.vendor == "yaskawa" and len(cf.frames) == 64
    assert cf.document.to_bytes() == raw
    assert cf.frame("UT1").label == "R2 STANDARD TOOL"


def test_unset_tools_are_the_defaults(capsys):
    """TOOL.CND lists all 64 tools; the unnamed all-zero ones are not listed."""
    path = komatsu_tool()
    code, out, err = cli(capsys, "frames", path, "--json")
    frames = json.loads(out)["frames"]
    assert code == 0 and len(frames) == 64
    assert [f["name"] for f in frames if f["set"]] == ["UT0", "UT1", "UT2", "UT3", "UT4"]
    code, out, err = cli(capsys, "frames", path)
    assert "59 unset frames not listed" in out and "rx" in out.splitlines()[0]


def test_unknown_lines_and_blocks_are_kept_and_reported_as_info():
    text = ("//UFRAME 1\n///NAME A\n///NEWKEY 1,2,3\n///GROUP " + GROUP1 + "\n"
            "a line nobody knows\n////BUSER 1.000,2.000,3.000,0.0000,0.0000,0.0000\n"
            "//NEWBLOCK 7\n///NAME whatever\n")
    data = crlf(text)
    cf = read(data)
    assert cf.document.to_bytes() == data
    assert [f.name for f in cf.frames] == ["UF1"]
    assert [(lint.line, lint.code, lint.severity) for lint in cf.lints] == [
        (3, "unknown-line", "info"), (5, "unknown-line", "info"), (7, "unknown-line", "info")]


# -- the frame tree ----------------------------------------------------------------------
def test_parents_from_basicfrm_and_group():
    cf = read(UFRAMES)
    parents = {f.name: (f.parent.kind, f.parent.name, f.reference) for f in cf.frames}
    assert parents == {"UF1": ("robot", "robot", "world"),
                       "UF2": ("frame", "UF1", "uframe"),
                       "UF3": ("robot", "robot@2", "world"),
                       "UF4": ("unit", "master robot's tool", "machine")}
    assert cf.frame("UF3").info["group"] == 2


def test_frames_tree_shows_them(tmp_path, capsys):
    path = write(tmp_path, "UFRAME.CND", UFRAMES)
    code, out, err = cli(capsys, "frames", "--tree", path)
    assert code == 0, err
    lines = out.splitlines()

    def depth(name):
        (line,) = [ln for ln in lines if f" {name} " in ln or ln.endswith(f" {name}")]
        return line.index(name)

    # each robot named as ///GROUP's flag names it on the pendant: R1, R2
    assert any(ln.rstrip().endswith('── robot  "R1"') for ln in lines)
    assert any(ln.rstrip().endswith('── robot@2  "R2"') for ln in lines)
    assert depth("UF2") > depth("UF1")              # UF2 hangs on UF1
    code, out, err = cli(capsys, "frames", "--tree", path, "--json")
    tree = json.dumps(json.loads(out))
    assert '"kind": "unit"' in tree and "master robot's tool" in tree
    robots = json.loads(out)["tree"][0]["roots"][0]["children"]
    assert [(r["name"], r["kind"], r.get("label")) for r in robots[:2]] == [
        ("robot", "robot", "R1"), ("robot@2", "robot", "R2")]


# -- lints --------------------------------------------------------------------------------
def test_lf_only_uframe_cnd_is_a_warning(tmp_path, capsys):
    lf = write(tmp_path, "UFRAME.CND", UFRAMES.replace(b"\r\n", b"\n"))
    ok = write(tmp_path, "UFRAME_CRLF.CND", UFRAMES)
    code, out, err = cli(capsys, "check", lf)
    assert code == 1 and f"{lf}:1:11: warning: lf-only" in out
    code, out, err = cli(capsys, "check", ok)
    assert code == 0 and "lf-only" not in out


def test_lints_of_the_traps():
    text = (uframe(1, "A", "1.000,2.000,3.000,0.0000,0.0000,190.0000", group="0" + ",0" * 31)
            + uframe(1, "B", "1.000,2.000,3.000,0.0000,0.0000,0.0000",
                     basep="1500.000,0.000,0.000,0.0000,0.0000,0.0000"))
    cf = read(crlf(text))
    found = sorted((lint.line, lint.code, lint.severity) for lint in cf.lints)
    assert found == [(4, "group-flags", "warning"), (11, "angle-range", "warning"),
                     (12, "duplicate-block", "warning"), (17, "track-position", "info")]
    assert cf.frames[0].parent.kind == "unknown"       # no robot named: no parent known
    assert cf.frames[1].info["basep"][0] == 1500.0


# -- bad input ------------------------------------------------------------------------------
@pytest.mark.parametrize("text, where, words", [
    ("//UFRAME 1\n////BUSER 1.000,2.000,abc,0.0000,0.0000,0.0000\n", "2:23",
     "not a number: 'abc'"),
    ("//UFRAME 1\n////BUSER 1.000,2.000,3.000,0.0000,0.0000\n", "2:42", "six numbers"),
    ("//UFRAME 1\n////BUSER 1.000,2.000,3.000,0.0000,0.0000,0.0000,7\n", "2:50", "a seventh"),
    ("//UFRAME 1\n////BUSER 1.000,,3.000,0.0000,0.0000,0.0000\n", "2:17", "a number is missing"),
    ("//UFRAME 1\n///NAME A\n///PULSE\n", "3:9", "//UFRAME 1 has no ////BUSER line"),
    ("//UFRAME x\n", "1:1", "not a UFRAME.CND or TOOL.CND"),
    ("//UFRAME\n////BUSER 1,2,3,4,5,6\n", "1:9", "//UFRAME without its number"),
    ("//UFRAME 1\n///GROUP 1,0,x\n////BUSER 1,2,3,4,5,6\n", "2:10", "///GROUP is"),
    ("//TOOL 0\n///NAME T\n0.000,0.000\n", "3:12", "a tool's pose line is six numbers"),
    ("hello\n//TOOL 0\n", "1:1", "not a UFRAME.CND or TOOL.CND"),
    ("", "", "not a UFRAME.CND or TOOL.CND"),
    ("//UFRAME 1\n////BUSER " + "9" * 400 + ",0,0,0,0,0\n", "2:11", "number out of range"),
    ("//UFRAME 99999999999\n", "1:10", "out of range (32 bits)"),
])
def test_bad_input_is_one_error_at_its_place(tmp_path, capsys, text, where, words):
    path = write(tmp_path, "UFRAME.CND", crlf(text))
    before = path.read_bytes()
    for command in ("frames", "check"):
        code, out, err = cli(capsys, command, path)
        assert code == 2, (command, out, err)
        assert f"{path}:{where}:" in (err + out) if where else f"{path}:" in (err + out)
        assert words in err + out
    assert path.read_bytes() == before


# -- the files ucsio does not read yet -------------------------------------------------------
@pytest.mark.parametrize("name, text", [
    ("ARCSRT.CND", "//ARCSRT 1\r\n///NAME\r\n"),
    ("SYSTEM.SYS", "/SYSTEM 8\r\n//DATE      : 2023/09/19 17:45:46\r\n"),
])
def test_other_yaskawa_files_are_refused_saying_which_are_read(tmp_path, capsys, name, text):
    path = write(tmp_path, name, text.encode())
    code, out, err = cli(capsys, "frames", path)
    assert code == 2 and "of Yaskawa's files it reads " in err
    reads = err.partition("of Yaskawa's files it reads ")[2]
    assert all(name in reads for name in
               ("UFRAME.CND", "TOOL.CND", "RBCALIB.DAT", "VAR.DAT", "jobs (.JBI)")), err


# -- commands --------------------------------------------------------------------------------
def backup(folder, uframes: bytes, tools: bytes):
    folder.mkdir()
    (folder / "UFRAME.CND").write_bytes(uframes)
    (folder / "TOOL.CND").write_bytes(tools)
    (folder / "JOB1.JBI").write_bytes(b"/JOB\r\n//NAME JOB1\r\n")
    return folder


TOOLS = crlf(tool(0, "GUN", "0.000,0.000,365.400,0.0000,0.0000,0.0000", True))


def test_diff_of_two_files_and_of_two_backups(tmp_path, capsys):
    moved = UFRAMES.replace(b"100.000,20.000,5.000", b"100.500,20.000,5.000")
    old = backup(tmp_path / "old", UFRAMES, TOOLS)
    new = backup(tmp_path / "new", moved, TOOLS)
    code, out, err = cli(capsys, "diff", old / "UFRAME.CND", new / "UFRAME.CND", "--json")
    doc = json.loads(out)
    assert code == 0, err
    assert [c["name"] for c in doc["changed"]] == ["UF2"]
    code, out, err = cli(capsys, "diff", old, new, "--exit-code")
    assert code == 1, err
    assert "~ UF2 \"FIXTURE\" (UFRAME): value changed" in out and "dx +0.500" in out
    assert "1 changed, 0 added, 0 removed, 2 unchanged" in out      # TOOL.CND, JOB1.JBI
    assert "UF1 " not in out and "~ TOOL.CND" not in out


def test_check_json_and_sarif(tmp_path, capsys):
    lf = write(tmp_path, "UFRAME.CND", UFRAMES.replace(b"\r\n", b"\n"))
    code, out, err = cli(capsys, "check", lf, "--json")
    doc = json.loads(out)
    (f,) = doc["files"]
    assert code == 1 and f["vendor"] == "yaskawa" and f["frames"] == 4
    code, out, err = cli(capsys, "check", lf, "--output-format", "sarif")
    sarif = json.loads(out)
    assert [r["ruleId"] for r in sarif["runs"][0]["results"]] == ["lf-only"]


def test_frames_json_validates_against_the_schema(tmp_path, capsys):
    from jsonschema import Draft202012Validator
    from conftest import ROOT
    schema = json.loads((ROOT / "docs" / "schema" / "frames.json").read_text())
    path = write(tmp_path, "UFRAME.CND", UFRAMES)
    code, out, err = cli(capsys, "frames", path, "--json")
    assert code == 0
    Draft202012Validator(schema).validate(json.loads(out))


def test_reading_commands_stay_light(tmp_path):
    """frames, check and diff of a .CND import none of numpy, scipy, lark."""
    path = write(tmp_path, "UFRAME.CND", UFRAMES)
    probe = ("import sys, io, contextlib\nfrom ucsio.cli import main\n"
             "with contextlib.redirect_stdout(io.StringIO()):\n    main(sys.argv[1:])\n"
             "print(' '.join(m for m in ('numpy', 'scipy', 'lark') if m in sys.modules))")
    for args in (["frames", path], ["check", path], ["diff", path, path]):
        res = subprocess.run([sys.executable, "-c", probe, *map(str, args)],
                             capture_output=True, text=True, check=True)
        assert res.stdout.strip() == "", (args, res.stdout)


def test_patch_of_a_tool_cnd_with_crc_is_refused_and_writes_nothing(tmp_path, capsys):
    """A TOOL.CND with ///CRC must never be rewritten: patch refuses it, at
    its ///CRC line, and the file stays as it is (the rest of patch:
    tests/test_yaskawa_patch.py)."""
    path = write(tmp_path, "TOOL.CND", TOOLS)
    code, out, err = cli(capsys, "patch", path, "--frame", "UT0", "--set", "1,2,3,0,0,0",
                         "--in-place")
    assert code == 2 and f"{path}:2:1: UT0: this TOOL.CND carries a ///CRC checksum" in err, err
    assert path.read_bytes() == TOOLS
