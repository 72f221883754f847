"""FANUC files (issue 19 points 1 and 2): sysframe.va and the other variable
listings through grammars/va.lark, TP programs (.ls) through grammars/tp.lark,
frame.dg and curpos.dg.

The real files are read in place from ../shared/corpus/fanuc (never copied
into the project; a backup folder is built in a temporary folder where a
test needs files side by side); fixtures/fanuc holds what the corpus lacks.
"""
from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
import sys

import pytest
from scipy.spatial.transform import Rotation

import fuzzing
from conftest import FIXTURES, ROOT, corpus_file, corpus_files
from ucsio.errors import UcsioError
from ucsio.geometry import rotations as rot
from ucsio.parsing import controller
from ucsio.vendors.fanuc import dg
from ucsio.vendors.fanuc import tp
from ucsio.vendors.fanuc import va
from ucsio.parsing.document import Document

FANUC = FIXTURES / "fanuc"
UB = "irbzavalagit__UB10200_RBT01__"
VASC_LABELS = "kjbvtu411450r01__"          # SYSFRAME.VA + FRAMEVAR.VA + POSREG.VA
FANUC_FILES = [p for p in corpus_files("fanuc")
               if p.values[0] is None or p.values[0].suffix.lower() in (".va", ".dg", ".ls")]
SRC = str(ROOT / "src")


def run(*args, cwd=None):
    env = dict(os.environ, PYTHONPATH=SRC)
    return subprocess.run([sys.executable, "-m", "ucsio", *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, env=env)


def snapshot(cf):
    return ([(f.as_dict(), {k: (n.span.start, n.span.end, n.text) for k, n in f.numbers.items()})
             for f in cf.frames], cf.lints)


def whole(doc: Document):
    kind = os.path.splitext(doc.path)[1].lower()
    if kind == ".va":
        return va.parse_whole(doc)
    if kind == ".ls":
        return tp.parse_whole(doc)
    return dg.parse(doc, full=True)


# -- every corpus file ------------------------------------------------------------------
@pytest.mark.parametrize("path", FANUC_FILES)
def test_corpus_reads_fast_full_and_whole_alike_and_round_trips(path):
    doc = Document.read(path)
    assert doc.to_bytes() == doc.raw == path.read_bytes()
    fast = controller.parse(doc)
    full = controller.parse(Document.read(path), full=True)
    ref = whole(Document.read(path))
    assert fast.vendor == "fanuc"
    assert snapshot(fast) == snapshot(full) == snapshot(ref)
    assert fast.extra["kind"] == ref.extra["kind"]
    for fr in fast.frames:
        assert fr.vendor == "fanuc" and fr.type in ("UFRAME", "UTOOL")
        for key, num in fr.numbers.items():       # the spans hold exactly the numbers
            assert doc.text[num.span.start:num.span.end] == num.text
            assert float(num.text) == num.value
    assert doc.to_bytes() == path.read_bytes()


@pytest.mark.parametrize("path", [p for p in FANUC_FILES if p.values[0] is None or
                                  p.values[0].suffix.lower() in (".va", ".ls")])
def test_corpus_trees_are_lark_s(path):
    """ucsio.parsing.lalr runs Lark's tables: the same tree, token for token,
    and the recogniser accepts what Lark accepts."""
    doc = Document.read(path)
    module = va if path.suffix.lower() == ".va" else tp
    text = module._lines(doc)
    theirs = fuzzing.lark_tree(module, text)
    assert theirs is not None
    assert fuzzing.same_tree(module._parser().parse(text, "file"), theirs)
    module._parser().recognise(text, "file")


# -- sysframe.va ------------------------------------------------------------------------
def test_ub10200_sysframe_names_values_and_groups():
    cf = controller.load(corpus_file("fanuc", UB + "sysframe.va"))
    assert cf.extra["kind"] == "sysframe"
    names = [f.name for f in cf.frames]
    assert names[:3] == ["UF1", "UF2", "UF3"] and names[32:34] == ["UF1@2", "UF2@2"]
    assert names[64] == "UT1" and names[-1] == "UT32@2" and len(names) == 128
    uf1 = cf.frame("uf1")                                   # names are case-insensitive
    assert (uf1.type, uf1.reference, uf1.info["group"]) == ("UFRAME", "world", 1)
    assert {k: n.text for k, n in uf1.numbers.items()} == {
        "x": "3495.600", "y": "5813.000", "z": "-1166.400", "w": ".140", "p": ".080",
        "r": "-90.040"}
    d = uf1.as_dict()
    assert (d["vendor"], d["type"], d["group"]) == ("fanuc", "UFRAME", 1)
    assert (d["w"], d["p"], d["r"]) == (0.14, 0.08, -90.04)
    assert (d["a"], d["b"], d["c"]) == (d["r"], d["p"], d["w"])     # SPEC: a = r, b = p, c = w
    assert d["config"] == "N U T, 0, 0, 0"
    assert cf.frame("UT1").reference == "flange"
    gun = cf.frame("UF1@2")                      # the servo gun's group: an empty Config
    assert gun.info["group"] == 2 and gun.info["config"] is None
    assert cf.frame("UT1@2").as_dict()["config"] is None
    # SPEC's matrix: R = Rz(R) Ry(P) Rx(W), scipy's intrinsic ZYX with (R, P, W)
    want = Rotation.from_euler("ZYX", [-90.04, 0.08, 0.14], degrees=True).as_quat()
    q = uf1.pose.q
    assert abs(abs(sum(a * b for a, b in zip((q[1], q[2], q[3], q[0]), want))) - 1) < 1e-12


def test_w_180_and_w_minus_180_are_one_rotation():
    cf = controller.load(corpus_file("fanuc", UB + "sysframe.va"))
    ut1, ut31, ut32 = cf.frame("UT1"), cf.frame("UT31"), cf.frame("UT32")
    assert (ut31.info["w"], ut32.info["w"]) == (180.0, -180.0)
    assert rot.quat_angle(ut31.pose.q, ut32.pose.q) < 1e-9
    assert rot.quat_angle(ut1.pose.q, ut31.pose.q) < 1e-9


def test_array_sizes_come_from_each_record_s_head():
    cf = controller.load(corpus_file("fanuc", "kjltvr411500r01__SYSFRAME"))
    uf = [f for f in cf.frames if f.type == "UFRAME"]
    ut = [f for f in cf.frames if f.type == "UTOOL"]
    assert (len(uf), len(ut)) == (4 * 20, 4 * 29)
    assert uf[-1].name == "UF20@4" and ut[-1].name == "UT29@4"
    assert all(f.info["config"] is None for f in cf.frames if f.info["group"] > 1)


def test_negative_zero_reads_as_zero_and_keeps_its_text():
    cf = controller.load(corpus_file("fanuc", "kjltvr411670r01__SYSFRAME"))
    uf1 = cf.frame("UF1")
    assert uf1.numbers["w"].text == "-.000" and uf1.as_dict()["w"] == 0.0
    assert not math.copysign(1, uf1.as_dict()["w"]) < 0


def test_positions_that_are_not_frames_give_no_frames():
    """kjltvr411670r01: $CELL_GRP[1] has POSITION fields that print Group,
    Config, X and W lines; only $MNUFRAME and $MNUTOOL are frames."""
    cf = controller.load(corpus_file("fanuc", "kjltvr411670r01__SYSFRAME"))
    assert len(cf.frames) == 196 and {f.type for f in cf.frames} == {"UFRAME", "UTOOL"}
    assert "$CELL_GRP" in cf.extra["records"]


def test_comments_on_entry_lines_are_labels_and_groups_may_be_inline():
    cf = controller.load(FANUC / "sysframe_comment.va")
    assert [(f.name, f.label) for f in cf.frames if f.label] == [
        ("UF1", "FIXTURE_A"), ("UF2", "TABLE"), ("UF1@2", "RAIL"), ("UT1", "GUN"),
        ("UT2", "GUN FLIPPED")]
    assert cf.frame("table").name == "UF2"                   # labels name frames too
    assert cf.frame("UF2").info["config"] == "N U T, 0, 0, 0"
    assert cf.frame("UF1@2").info["config"] is None
    assert cf.frame("UF1").numbers["z"].text == ".750" and cf.frame("UF1").pose.z == 0.75
    assert cf.lints == []
    assert snapshot(cf) == snapshot(va.parse_whole(Document.read(FANUC / "sysframe_comment.va")))


@pytest.mark.parametrize("name", ["sysframe_cr.va", "sysframe_mixed.va"])
def test_cr_only_and_mixed_line_endings(name):
    """A bare CR ends a line, as LF and CRLF do (Document.line_starts): the
    same frames, on the same lines, the bytes kept."""
    ref = controller.load(FANUC / "sysframe_comment.va")
    doc = Document.read(FANUC / name)
    assert b"\r" in doc.raw and doc.to_bytes() == (FANUC / name).read_bytes()
    cf = controller.parse(doc)
    assert [(f.name, f.label, f.line, f.pose) for f in cf.frames] == \
        [(f.name, f.label, f.line, f.pose) for f in ref.frames]
    assert snapshot(cf) == snapshot(controller.parse(Document.read(FANUC / name), full=True))
    for f in cf.frames:
        for n in f.numbers.values():
            assert doc.slice(n.span) == n.text


def test_lints():
    cf = controller.load(FANUC / "sysframe_lints.va", full=True)
    got = [(l.line, l.code, l.severity) for l in cf.lints]
    assert got == [(5, "out-of-range", "warning"), (7, "group-mismatch", "warning"),
                   (10, "missing-component", "warning"), (14, "no-value", "info"),
                   (15, "index-out-of-range", "warning"), (17, "out-of-range", "warning"),
                   (22, "not-a-number", "warning"), (19, "duplicate-frame", "warning"),
                   (23, "not-a-frame", "warning"), (23, "duplicate-frame", "warning"),
                   (27, "not-a-frame-array", "warning")]
    assert "W 200 is outside [-180, 180]" in cf.lints[0].message
    assert "$MNUTOOL is ARRAY[4] OF POSITION" in cf.lints[-1].message
    assert {l.code for l in cf.lints} <= set(controller.LINT_CODES)
    assert cf.frame("UF3").pose is None and cf.frame("UF5").pose is not None


def test_repeated_elements_are_read_once_at_their_own_offsets():
    """The fast path parses an element whose text repeats an earlier one's
    once: the copies' numbers still point at their own text."""
    path = corpus_file("fanuc", UB + "sysframe.va")
    doc = Document.read(path)
    text = va._lines(doc)
    spans, shared, plain = va.outline(text, va._frames_wanted)
    assert len(shared) > 100 and plain
    masked = va.masked(text, spans)
    assert len(masked) == len(text) and masked.count("\n") == text.count("\n")
    cf = va.parse(doc)
    uf2, uf3 = cf.frame("UF2"), cf.frame("UF3")
    assert uf2.numbers["x"].span != uf3.numbers["x"].span
    assert doc.line_of(uf3.numbers["x"].span.start) == uf3.line + 2


# -- the files beside sysframe.va ---------------------------------------------------------
def backup(tmp_path, prefix: str, names: dict) -> object:
    """A backup folder of corpus files, each under its controller name."""
    folder = tmp_path / prefix.strip("_")
    folder.mkdir()
    for part, name in names.items():
        shutil.copy(corpus_file("fanuc", prefix + part), folder / name)
    return folder


def test_frame_dg_beside_gives_the_labels(tmp_path):
    folder = backup(tmp_path, UB, {"sysframe.va": "sysframe.va", "frame.dg": "FRAME.DG"})
    cf = controller.load(folder / "sysframe.va")
    assert {f.name: f.label for f in cf.frames if f.label} == {
        "UF1": "UB10200_FXT01", "UF19": "TIPDRESS", "UF20": "CAPCHANGE", "UT1": "SSW",
        "UT10": "MEASURED TCP"}
    assert cf.frame("measured tcp").name == "UT10"
    assert cf.lints == []
    # alone (the corpus folder has no frame.dg under that name): no labels
    assert not any(f.label for f in controller.load(corpus_file("fanuc", UB + "sysframe.va")).frames)


def test_framevar_beside_gives_the_labels_by_group(tmp_path):
    folder = backup(tmp_path, VASC_LABELS, {"SYSFRAME.VA": "SYSFRAME.VA",
                                            "FRAMEVAR.VA": "FRAMEVAR.VA"})
    cf = controller.load(folder / "SYSFRAME.VA")
    assert {f.name: f.label for f in cf.frames if f.label} == {
        "UT1": "G1", "UT2": "Car 0", "UT4": "CAR 0 336", "UF1": "RTCP1"}
    # the fast reading (the comment lines, the rest blanked) is the tree's
    doc = Document.read(folder / "FRAMEVAR.VA")
    assert va.frame_comments(doc) == va.comments_of(va.records(va._parse(doc, va._lines(doc)),
                                                               doc))


def test_a_broken_label_file_beside_is_an_info_not_an_error(tmp_path):
    folder = backup(tmp_path, UB, {"sysframe.va": "sysframe.va"})
    (folder / "frame.dg").write_text("User Frame\n  1.0  2.0 three\n")
    cf = controller.load(folder / "sysframe.va")
    assert len(cf.frames) == 128 and not any(f.label for f in cf.frames)
    (lint,) = cf.lints
    assert (lint.code, lint.severity) == ("label-source", "info")
    assert "frame.dg could not be read" in lint.message
    with pytest.raises(UcsioError, match=r"frame\.dg:2:3: a row of the User Frame table"):
        controller.load(folder / "frame.dg")


# -- the other listings ---------------------------------------------------------------------
def test_posreg_is_read_and_gives_no_frames():
    path = corpus_file("fanuc", UB + "posreg.va")
    cf = controller.load(path)
    assert (cf.extra["kind"], cf.frames) == ("posreg", [])
    regs = va.position_registers(Document.read(path))
    home = regs[(1, 1)]
    assert (home.comment, home.group, home.joints) == ("@Home", 1, True)
    assert [home.coords[f"J{i}"].value for i in range(1, 7)] == [-70, -25, 0, 0, -90, -20]
    pr16 = regs[(1, 16)]
    assert (pr16.comment, pr16.group, pr16.config) == ("", 1, "N U T, 0, 0, 0")
    assert pr16.coords["X"].value == -606.5 and not pr16.joints
    assert regs[(1, 3)].uninit and regs[(1, 3)].comment == "Reserved"
    assert regs[(2, 1)].coords["J1"].value == -130.224


def test_framevar_curpos_and_frame_dg_are_recognised():
    assert controller.load(corpus_file("fanuc", VASC_LABELS + "FRAMEVAR")).extra["kind"] == \
        "framevar"
    labels = controller.load(corpus_file("fanuc", UB + "frame.dg"))
    assert labels.extra["kind"] == "frame comments" and labels.frames == []
    assert labels.extra["labels"][("UTOOL", 10, 1)] == "MEASURED TCP"
    cur = controller.load(corpus_file("fanuc", UB + "curpos.dg"))
    assert cur.extra["kind"] == "current position" and cur.frames == []
    g1, g2 = cur.extra["current"]
    assert (g1.group, g1.uf, g1.ut, g1.world_tool) == (1, 1, 1, 1)
    assert g1.user["x"].text == "6967.59" and g1.world["w"].text == ".08"
    assert g1.user_config == g1.world_config == "N U T, 0, 0, 0"
    assert g2.group == 2 and g2.user is None and g2.world is None
    assert g2.joints[1].value == -50.0


def test_a_dg_ucsio_does_not_read_is_listed(tmp_path):
    p = tmp_path / "iostate.dg"
    p.write_text("IO STATUS::\nDIN[  81]  ON  Hold\n")
    cf = controller.load(p)
    assert (cf.vendor, cf.extra["kind"], cf.frames) == ("fanuc", "diagnostics", [])


# -- TP programs ---------------------------------------------------------------------------
def test_a_program_that_sets_frames():
    path = corpus_file("fanuc", UB + "tooldataub10200rbt01.ls")
    doc = Document.read(path)
    cf = controller.parse(doc)
    assert cf.extra["kind"] == "program" and cf.extra["program"] == "TOOLDATAUB10200RBT01"
    got = [(f.name, f.type, f.label, f.line, f.pose.t) for f in cf.frames]
    assert got == [("UT1", "UTOOL", "SSW", 30, (-0.4, -1100.3, 770.299)),
                   ("UF1", "UFRAME", "UB10200_FXT01", 37, (3500.0, 5820.0, -1176.5)),
                   ("UF19", "UFRAME", "TIPDRESS", 44, (-684.799, -834.099, -772.2)),
                   ("UF20", "UFRAME", "CAPCHANGE", 51, (-606.5, -1058.19, -782.0))]
    ut1 = cf.frame("UT1")
    assert {k: n.text for k, n in ut1.numbers.items()} == {
        "x": "-.4", "y": "-1100.3", "z": "770.299", "w": "180", "p": "0", "r": "-90"}
    # the numbers stand on the PR lines above the frame's line
    assert [doc.line_of(n.span.start) for n in ut1.numbers.values()] == list(range(24, 30))
    assert (ut1.info["set_from"], ut1.info["group"], ut1.info["w"]) == ("PR[16]", 1, 180.0)
    assert cf.lints == []


def test_frames_set_every_way():
    cf = controller.load(FANUC / "program_frames.ls", full=True)
    frames = {(f.name, f.line): f for f in cf.frames}
    uf2 = frames[("UF2", 14)]
    # PR[20]=LPOS-LPOS zeroes it: W and P are 0 and stand nowhere
    assert uf2.pose.t == (1500.25, -250.5, -0.75) and uf2.info["r"] == 90.0
    assert set(uf2.numbers) == {"x", "y", "z", "r"} and uf2.numbers["z"].text == "-.75"
    assert frames[("UT6", 25)].pose.t == (0.0, 0.0, 250.0)     # PR[22]=PR[22]-PR[22]
    indirect = frames[("UF[R[9]]", 18)]
    assert indirect.pose is not None and indirect.info["set_from"] == "PR[20]"
    for name, line in (("UT3", 17), ("UF4", 20), ("UT5", 21), ("UF7", 32), ("UF8", 33)):
        assert frames[(name, line)].pose is None, name
    lints = [(l.line, l.code, l.severity) for l in cf.lints]
    assert lints == [(17, "not-literal", "info"), (18, "not-literal", "info"),
                     (20, "not-literal", "info"), (21, "not-literal", "info"),
                     (26, "unread-frame-set", "warning"), (32, "not-literal", "info"),
                     (33, "not-literal", "info"), (36, "duplicate-frame", "warning")]
    messages = {l.line: l.message for l in cf.lints}
    assert "R[9], known only when the program runs" in messages[18]
    assert "PR[21] Y Z W P R are not given literal values" in messages[17]
    assert "holds joint values" in messages[32]
    assert frames[("UF2", 36)].pose.t == (0.0, 0.0, 250.0)
    # the instruction continued on the next line, a comment naming UFRAME: kept as they are
    assert cf.document.to_bytes() == (FANUC / "program_frames.ls").read_bytes()


def test_positions_of_pos():
    doc = Document.read(corpus_file("fanuc", UB + "s012ssw01.ls"))
    points = tp.positions(doc)
    p2 = points[0]
    assert (p2.name, p2.comment) == ("P[2]", None)
    g1, g2 = p2.groups[1], p2.groups[2]
    assert (g1.uf, g1.ut, g1.config) == (1, 1, "N U T, 0, 0, 0")
    assert g1.values["X"].text == "5947.414" and g1.units["R"] == "deg" and g1.cartesian
    assert g1.pose.t == (5947.414, -1623.844, 1403.576)
    assert (g2.config, g2.values["J1"].value, g2.units["J1"]) == (None, -100.0, "mm")
    assert g2.pose is None
    home = tp.positions(Document.read(corpus_file("fanuc", "HOMEN.LS")))[0]
    assert (home.name, home.comment, home.groups[1].uf) == ("P[1]", "rust positie", 0)
    assert home.groups[1].values["J4"].text == "-.000" and not home.groups[1].cartesian
    gen = tp.positions(Document.read(corpus_file("fanuc", "surface.ls")))
    assert len(gen) == 18 and gen[0].groups[1].values["X"].text == "1680.081761"


def test_a_ls_that_is_not_a_program_is_listed(tmp_path):
    p = tmp_path / "errall.ls"
    p.write_text('ERRALL.LS      Robot Name ROBOT 01-OCT-26 09:00:10\n\n'
                 '1003" 01-OCT-26 09:00:05 " SRVO-003 Deadman switch released " " SERVO " act"\n')
    for full in (False, True):
        cf = controller.load(p, full=full)
        assert (cf.extra["kind"], cf.frames, cf.lints) == ("listing", [], [])


# -- bad input -------------------------------------------------------------------------------
BAD = [
    ("missing_line.va", 5, 3, "not a FANUC variable listing: unexpected 'this line", True),
    ("bad_number.va", 4, 23, "malformed number '12.3.4'", True),
    ("not_a_listing.va", 1, 1, "expected a record", True),
    ("no_end.ls", 8, 1, "unexpected end of file; expected /END", True),
    ("broken_frame_set.ls", 6, 22, "unexpected end of line; expected PR[...]", True),
    ("broken_position.ls", 10, 25, "not a FANUC TP program: unexpected '= 200.000", False),
]


@pytest.mark.parametrize("name, line, col, message, fast", BAD)
def test_bad_input_is_one_positioned_error(name, line, col, message, fast):
    path = FANUC / "bad" / name
    paths = (True, False) if fast else (True,)
    for full in paths:
        with pytest.raises(UcsioError) as got:
            controller.load(path, full=full)
        e = got.value
        assert (e.file, e.line, e.col) == (str(path), line, col), (full, str(e))
        assert message in e.message, e.message
    res = run("check", path)
    assert res.returncode == 2 and res.stdout == ""
    assert res.stderr.startswith(f"ucsio: {path}:{line}:{col}: ") and res.stderr.count("\n") == 1


def test_empty_files_and_binaries_are_refused(tmp_path):
    for name in ("empty.va", "empty.ls", "empty.dg"):
        (tmp_path / name).write_text("\n  \n")
        with pytest.raises(UcsioError, match="empty file"):
            controller.load(tmp_path / name)
    (tmp_path / "prog.tp").write_bytes(b"\x00\x01TP\x00")
    res = run("frames", tmp_path / "prog.tp")
    assert res.returncode == 2 and "binary FANUC file" in res.stderr and ".ls" in res.stderr


def test_frames_command_lists_fanuc_frames_with_w_p_r():
    res = run("frames", FANUC / "sysframe_comment.va")
    assert res.returncode == 0, res.stderr
    head = res.stdout.splitlines()[0].split()
    assert head[4:10] == ["x", "y", "z", "w", "p", "r"]
    assert "FIXTURE_A" in res.stdout
    out = json.loads(run("frames", FANUC / "sysframe_comment.va", "--json").stdout)
    uf2 = [f for f in out["frames"] if f["name"] == "UF2"][0]
    assert {k: uf2[k] for k in ("vendor", "type", "group", "w", "p", "r", "a", "b", "c",
                                "label")} == {
        "vendor": "fanuc", "type": "UFRAME", "group": 1, "w": 180.0, "p": 0.0, "r": -90.0,
        "a": -90.0, "b": 0.0, "c": 180.0, "label": "TABLE"}


def test_check_lists_each_fanuc_file_with_its_kind():
    res = run("check", FANUC / "sysframe_comment.va", FANUC / "program_frames.ls", "--json")
    out = json.loads(res.stdout)
    assert [(r["vendor"], r["kind"], r["round_trip"]) for r in out["files"]] == [
        ("fanuc", "sysframe", True), ("fanuc", "program", True)]
    assert res.returncode == 1          # program_frames.ls: unread-frame-set, duplicate-frame
    assert run("check", FANUC / "program_frames.ls", "--ignore",
               "unread-frame-set,duplicate-frame").returncode == 0


def test_a_sysframe_va_is_never_patched_in_place(tmp_path):
    """The listing is the controller's record, not a file it loads: only a
    reviewed copy (-o) is written (tests/test_fanuc_write.py)."""
    target = tmp_path / "sysframe.va"
    shutil.copy(FANUC / "sysframe_comment.va", target)
    before = target.read_bytes()
    res = run("patch", target, "--frame", "UF1", "--set", "1,2,3,0,0,0", "--in-place")
    assert res.returncode == 2 and "does not load it: not patched in place" in res.stderr
    assert target.read_bytes() == before and sorted(os.listdir(tmp_path)) == ["sysframe.va"]
