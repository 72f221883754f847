"""Issue 24, the TP program points: every real FANUC program reads.

- 1: a motion's attached logic (numbered from 1, closed by `------ ;`);
- 2: an untaught position (`UF : F, UT : F`, `********`) is listed, not refused;
- 6: a /MN line ucsio does not understand is kept as text, never a refusal;
- 7: a frame set twice is a warning only where both values are literal and differ;
- 10: a literal no FANUC REAL holds is refused, file:line:col;
- 18: /POS is read without a tree, and reads as the grammar's tree does.

fixtures/fanuc/point_logic.ls is written in the pendant's style (CRLF, the
header of a real backup, motion options, a logic block, a generated line,
two untaught positions)."""
from __future__ import annotations

import json
import re
import shutil

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import FIXTURES, corpus_files
from fanuc_cell import position, program
from ucsio.cli import main
from ucsio.errors import UcsioError
from ucsio.parsing import controller
from ucsio.vendors.fanuc import tp
from ucsio.parsing.document import Document

FANUC = FIXTURES / "fanuc"
LOGIC = FANUC / "point_logic.ls"
SETTINGS = dict(deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow])


def cli(capsys, *args):
    code = main([str(a) for a in args])
    out = capsys.readouterr()
    return code, out.out, out.err


def load_both(path):
    """The fast path's and check's reading (they must agree)."""
    fast, full = controller.load(path), controller.load(path, full=True)
    assert [(f.name, f.line, f.pose) for f in fast.frames] == \
        [(f.name, f.line, f.pose) for f in full.frames]
    assert fast.lints == full.lints
    return full


def program_text(mn: str, pos: str = "") -> str:
    return ("/PROG  T\n/ATTR\nOWNER\t\t= MNEDITOR;\nDEFAULT_GROUP\t= 1,*,*,*,*;\n/MN\n" + mn
            + "/POS\n" + pos + "/END\n")


# -- 1 and 6: what /MN holds ------------------------------------------------------------
def test_a_motion_s_attached_logic_and_its_options_read(capsys):
    cf = load_both(LOGIC)
    assert [(f.name, f.line, f.label) for f in cf.frames] == [
        ("UF3", 26, "TABLE"), ("UF4", 32, "FIXTURE"), ("UF3", 40, "TABLE")]
    # set inside the logic block (its own line 3): read in program order
    assert cf.frame("UF4").pose.t == (0.0, 0.0, 0.0)
    assert cf.document.to_bytes() == LOGIC.read_bytes()
    assert [(l.line, l.code, l.severity) for l in cf.lints] == [
        (40, "not-literal", "info"), (40, "duplicate-frame", "info")]
    code, out, err = cli(capsys, "check", LOGIC)
    assert code == 0, err


@pytest.mark.parametrize("line", [
    ":R[35]=56.6;",                         # generated: no line number
    ": Arc Start[1];",
    "   1 2 3 ;",                           # digits without their ":"
    "       ------ ;",
    "  garbage [ ( { ;",
    "/APPL",
])
def test_an_instruction_line_never_makes_a_program_unreadable(tmp_path, line):
    p = tmp_path / "t.ls"
    text = program_text(f"   1:  UTOOL_NUM=1 ;\n{line}\n   2:  PR[5,1]=10    ;\n")
    p.write_text(text)
    cf = load_both(p)
    assert cf.document.to_bytes() == text.encode()
    first = program_text(f"{line}\n   1:  UTOOL_NUM=1 ;\n")     # as the first /MN line too
    p.write_text(first)
    assert load_both(p).document.to_bytes() == first.encode()


def test_a_header_section_named_pos_is_not_the_positions(tmp_path):
    """Found by fuzzing: the header's `/POS` section is no /POS: the
    positions open at the first /POS line after /MN."""
    p = tmp_path / "t.ls"
    p.write_text("/PROG  T\n/ATTR\n/POS\nOWNER\t\t= MNEDITOR;\n/MN\n   1:  PR[5]=LPOS-LPOS    ;\n"
                 "   2:  UFRAME[3]=PR[5] ;\n/POS\n" + position(1, [(1, 0, 0, (1, 2, 3, 0, 0, 0))])
                 + "\r\n/END\n")
    assert [f.name for f in load_both(p).frames] == ["UF3"]
    doc = Document.read(p)
    assert [x.name for x in tp.positions(doc)] == ["P[1]"] == [
        x.name for x in tp.positions_whole(doc)]


def test_a_line_without_its_number_is_an_info_lint(capsys):
    path = FANUC / "no_line_number.ls"
    cf = load_both(path)
    assert [(l.line, l.col, l.code, l.severity) for l in cf.lints] == [
        (6, 3, "unread-line", "info")]
    assert "UTOOL_NUM=1 ;" in cf.lints[0].message
    assert cli(capsys, "check", path)[0] == 0


def test_a_frame_assignment_ucsio_cannot_place_warns(tmp_path):
    p = tmp_path / "t.ls"
    p.write_text(program_text("   1:  PR[5]=LPOS-LPOS    ;\n  UFRAME[2]=PR[5] ;\n"
                              ":UFRAME[3]=PR[5];\n"))
    cf = load_both(p)
    # without ":" it is text; with a bare ":" it is a statement, read
    assert [f.name for f in cf.frames] == ["UF3"] and cf.frame("UF3").pose.t == (0, 0, 0)
    assert [(l.line, l.code, l.severity) for l in cf.lints] == [
        (7, "unread-frame-set", "warning")]


def test_a_broken_frame_assignment_is_still_refused(capsys):
    path = FANUC / "bad" / "broken_frame_set.ls"
    for full in (False, True):
        with pytest.raises(UcsioError) as got:
            controller.load(path, full=full)
        assert (got.value.line, got.value.col) == (6, 22)
    code, out, err = cli(capsys, "check", path)
    assert code == 2 and out == "" and f"{path}:6:22: " in err


# -- 7: a frame set twice ---------------------------------------------------------------
@pytest.mark.parametrize("second, severity", [
    ("   5:  PR[31]=LPOS    ;\n   6:  UFRAME[3]=PR[31] ;\n", "info"),        # computed
    ("   5:  UFRAME[3]=PR[30] ;\n", "info"),                                  # the same value
    ("   5:  PR[31]=LPOS-LPOS    ;\n   6:  PR[31,1]=1    ;\n"
     "   7:  UFRAME[3]=PR[31] ;\n", "warning"),                               # two that differ
])
def test_a_frame_set_twice_warns_only_for_two_literals_that_differ(tmp_path, capsys, second,
                                                                    severity):
    p = tmp_path / "t.ls"
    p.write_text(program_text("   1:  PR[30]=PR[30]-PR[30]    ;\n   2:  UFRAME[3]=PR[30] ;\n"
                              + second))
    cf = load_both(p)
    (dup,) = [l for l in cf.lints if l.code == "duplicate-frame"]
    assert dup.severity == severity and "UF3 is set twice (lines 7 and" in dup.message
    assert cli(capsys, "check", p, "--ignore", "not-literal")[0] == (1 if severity == "warning"
                                                                     else 0)


# -- 10: beyond a FANUC REAL -----------------------------------------------------------
@pytest.mark.parametrize("value, col", [("9" * 400, 17), ("(-" + "9" * 39 + ")", 18),
                                        ("1e39", 17), ("((-4E+40))", 19)])
def test_a_literal_no_real_holds_is_refused(tmp_path, capsys, value, col):
    p = tmp_path / "t.ls"
    text = program_text(f"   1:  PR[16]=LPOS-LPOS    ;\n   2:  PR[16,1]={value}    ;\n"
                        "   3:  UFRAME[1]=PR[16] ;\n")
    p.write_text(text)
    for full in (False, True):
        with pytest.raises(UcsioError) as got:
            controller.load(p, full=full)
        assert (got.value.line, got.value.col) == (7, col)
        assert "is out of range for a FANUC REAL" in got.value.message
    for command in ("frames", "check"):
        code, out, err = cli(capsys, command, p)
        assert code == 2 and out == "" and f"t.ls:7:{col}: number " in err, err
    assert p.read_text() == text


def test_a_real_s_range_is_kept_and_a_pos_value_beyond_it_refused(tmp_path, capsys):
    p = tmp_path / "t.ls"
    p.write_text(program_text("   1:  PR[16]=LPOS-LPOS    ;\n   2:  PR[16,1]=340000000000000000"
                              "000000000000000000000    ;\n   3:  UFRAME[1]=PR[16] ;\n"))
    assert controller.load(p).frame("UF1").pose.x == 3.4e38          # within float32's range
    huge = program("H", [position(1, [(1, 0, 1, (1e39, 2, 3, 0, 0, 0))], decimals=0)])
    p.write_text(huge)
    for read in (tp.positions, tp.positions_whole):
        with pytest.raises(UcsioError, match="out of range for a FANUC REAL"):
            read(Document.read(p))
    line = huge[:huge.index("X =")].count("\n") + 1
    code, out, err = cli(capsys, "check", p)
    assert code == 2 and re.search(rf"t\.ls:{line}:\d+: number 9999999", err), err
    # a syntax error further on is the error, as the grammar's tree reports it
    p.write_text(huge.replace("/END", "P[2]{ oops\r\n/END"))
    with pytest.raises(UcsioError, match="not a FANUC TP program: unexpected") as got:
        tp.positions(Document.read(p))
    assert got.value.line == line + 3


# -- 2: untaught positions ----------------------------------------------------------------
def test_an_untaught_position_is_listed_without_values():
    doc = Document.read(LOGIC)
    points = {p.number: p for p in tp.positions(doc)}
    assert sorted(points) == [1, 2, 3, 4, 5, 6, 7]
    g3 = points[3].groups[1]
    assert g3.untaught and (g3.uf, g3.ut) == (None, None) and g3.pose is None
    assert set(g3.values) == {"X", "Y", "Z", "W", "P", "R"} and not any(g3.values.values())
    assert (points[7].groups[1].config, points[7].groups[1].untaught) == ("", True)
    assert not points[2].groups[1].untaught and points[2].groups[1].pose.t == (1350.25, -210.5,
                                                                                640.0)
    assert tp.positions_whole(doc) == tp.positions(doc)


def test_solve_refuses_an_untaught_position_it_is_given_and_reads_the_rest(tmp_path, capsys):
    laser = tmp_path / "laser.txt"
    laser.write_text("P1 0 0 0\nP2 100 0 0\nP4 0 100 0\nP3 0 0 100\n")
    prog = tmp_path / "CAL_UF3.LS"          # taught in world with the faceplate: no --config
    prog.write_bytes(LOGIC.read_bytes().replace(b"UF : 0, UT : 1", b"UF : 0, UT : 0"))
    code, out, err = cli(capsys, "solve", "--laser", laser, "--robot", prog, "--tcp", "0,0,0")
    assert code == 2 and out == ""
    assert f"{prog}:58:4: P[3]: never taught (UF : F, UT : F)" in err, err
    assert len(err.strip().splitlines()) == 1


def test_points_of_a_folder_with_untaught_positions(tmp_path, capsys):
    shutil.copy(FANUC / "sysframe_comment.va", tmp_path / "sysframe.va")
    text = LOGIC.read_bytes().replace(b"UF : 0, UT : 1", b"UF : 1, UT : 1")
    (tmp_path / "CAL_UF3.LS").write_bytes(text)
    sol = tmp_path / "s.json"
    sol.write_text(json.dumps({"frame": {"x": 1200.5, "y": -300.25, "z": 1.75, "a": 90.0,
                                         "b": -0.08, "c": 0.14}, "accepted": True}))
    code, out, err = cli(capsys, "diff", tmp_path / "sysframe.va", "--frame", "UF1",
                         "--measured", sol, "--points", "--json")
    assert code == 0, err
    got = json.loads(out)
    # P[3] and P[7] were never taught: in no frame, not counted, no warning
    assert [p["name"] for p in got["points"]] == ["P[1]", "P[2]", "P[4]", "P[5]", "P[6]"]
    assert got["points_moved"]["count"] == 5 and got["points_warnings"] == []


# -- 18: /POS without a tree, as the tree reads it -------------------------------------------
def ls_files():
    corpus = [p for p in corpus_files("fanuc") if p.values[0] is None
              or p.values[0].suffix.lower() == ".ls"]
    return corpus + [pytest.param(p, id=p.name) for p in sorted(FANUC.glob("*.ls"))]


@pytest.mark.parametrize("path", ls_files())
def test_the_fast_reader_reads_what_the_tree_reads(path):
    doc = Document.read(path)
    assert tp.positions(doc) == tp.positions_whole(doc)


def test_positions_build_no_tree(monkeypatch):
    from ucsio.parsing import lalr
    monkeypatch.setattr(lalr.Parser, "parse", lambda *a: pytest.fail("a tree was built"))
    text = program("BIG", [position(i, [(1, 1, 2, (i, -i, 3.5, 180, 0, -90))])
                           for i in range(1, 200)])
    points = tp.positions(Document(text.encode(), "big.ls"))
    assert len(points) == 199 and points[-1].groups[1].pose.t == (199.0, -199.0, 3.5)


# Generated /POS sections: every spelling the grammar allows between tokens,
# and small damage; the fast reader must give the grammar's points, or the
# grammar's own error.
GAP = st.sampled_from(["", " ", "\t", "  \t", "\f"])        # a bare CR ends a line
NL = st.sampled_from(["\n", "\r\n", "\n\n", "\n\t", "\n \n  ", "\r", "\r\r\n", "\r\r"])
AXIS_GAP = st.sampled_from(["", " ", "\t"])        # AXIS looks ahead to "=" over these only
UNIT = st.sampled_from(["mm", "deg"])
NUM = st.sampled_from(["0.000", "-.500", "1200.5", "1e3", "-2.5E-2", "********", "+7", "3.",
                       "-0.000000", "99", "1e39"])


@st.composite
def group(draw, g):
    gap = lambda: draw(GAP)                                 # noqa: E731
    opt_nl = lambda: draw(st.sampled_from(["", draw(NL)]))  # noqa: E731
    uf = draw(st.sampled_from(["0", "1", "12", "F"]))
    ut = draw(st.sampled_from(["0", "2", "F"]))
    out = f"{gap()}GP{g}{gap()}:{opt_nl()}{gap()}UF{gap()}:{gap()}{uf}{gap()},{opt_nl()}"
    out += f"{gap()}UT{gap()}:{gap()}{ut}{gap()},{opt_nl()}"
    if draw(st.booleans()):
        word = draw(st.sampled_from(["CONFIG", "KONFIG"]))
        out += f"{gap()}{word}{gap()}:{gap()}'{draw(st.sampled_from(['N U T, 0, 0, 0', '']))}'"
        out += f"{gap()},{opt_nl()}"
    axes = draw(st.sampled_from([list("XYZWPR"), ["J1", "J2", "J3"], ["X", "E1"], []]))
    items = [f"{gap()}{a}{draw(AXIS_GAP)}={gap()}{draw(NUM)}{gap()}{draw(UNIT)}" for a in axes]
    seps = [f"{gap()},{opt_nl()}" for _ in items[1:]]
    out += "".join(i + s for i, s in zip(items, seps + [""]))
    if items:
        out += draw(st.sampled_from(["", ",", f"{gap()},"])) + opt_nl()
    return out


@st.composite
def pos_section(draw):
    points = []
    for n in range(draw(st.integers(0, 3))):
        comment = draw(st.sampled_from(["", ':"App"', ': "a b"']))
        head = f"P{draw(GAP)}[{draw(GAP)}{n + 1}{draw(GAP)}{comment}]{draw(GAP)}{{"
        groups = "".join(draw(group(g)) for g in range(1, draw(st.integers(1, 2)) + 1))
        points.append(head + draw(st.sampled_from(["", draw(NL)])) + groups + "};" + draw(NL))
    return "".join(points)


@settings(max_examples=150, **SETTINGS)
@given(pos=pos_section(), cut=st.integers(0, 10_000), junk=st.sampled_from(
    ["", "\n", ",", "X", "*", ";", "}", " mm", "F", "1e", ":", "'", '"']))
def test_generated_positions_read_alike(pos, cut, junk):
    text = program_text("   1:L P[1] 100mm/sec FINE    ;\n", pos)
    start = text.index("/POS\n") + 5
    at = start + cut % (len(text) - start - 5 + 1) if junk else start
    mutated = text[:at] + junk + text[at:]

    def read(reader):
        try:
            return reader(Document(mutated.encode(), "g.ls"))
        except UcsioError as exc:
            return ("error", exc.line, exc.col, exc.message)
    assert read(tp.positions) == read(tp.positions_whole)
    if not junk and "1e39" not in pos:
        assert isinstance(read(tp.positions), list)          # what is generated reads
