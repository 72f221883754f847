"""ABB RAPID: the corpus, the syntax variants, frame values, bad input."""
from __future__ import annotations

import json
import re
import subprocess
import sys

import pytest
from scipy.spatial.transform import Rotation

import ucsio
from ucsio.vendors.abb import rapid
from ucsio.parsing.document import Document
from ucsio.errors import UcsioError

from conftest import FIXTURES, corpus_file, corpus_files

ABB = FIXTURES / "abb"


def frames_by_name(cf):
    return {f.name: f for f in cf.frames}


# -- the corpus ----------------------------------------------------------------
@pytest.mark.parametrize("path", corpus_files("abb"))
def test_corpus_parses_and_round_trips(path):
    raw = path.read_bytes()
    doc = Document(raw, path)
    assert doc.to_bytes() == raw
    fast = rapid.parse(doc)
    full = rapid.parse_whole(Document(raw, path))
    # the outline + compact parse and Lark's tree of the whole file agree exactly
    assert [f.as_dict() for f in fast.frames] == [f.as_dict() for f in full.frames]
    assert [f.numbers for f in fast.frames] == [f.numbers for f in full.frames]
    assert fast.lints == full.lints
    for f in fast.frames:
        for key, num in f.numbers.items():
            text = doc.slice(num.span)
            assert text == num.text
            assert float(re.sub(r"^([+-])\s+", r"\1", text)) == pytest.approx(num.value, abs=0), key


@pytest.mark.parametrize("path", corpus_files("abb"))
def test_corpus_frames_match_scipy(path):
    for f in ucsio.load(path).frames:
        if f.pose is None:
            continue
        q = [f.numbers[k].value for k in ("q1", "q2", "q3", "q4")]
        r = Rotation.from_quat(q, scalar_first=True)  # normalises, like we do
        assert f.pose.abc == pytest.approx(_abc(r), abs=1e-7)
        assert (f.pose.x, f.pose.y, f.pose.z) == tuple(f.numbers[k].value for k in "xyz")


def _abc(r):
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # gimbal lock: scipy also sets the third angle to 0
        a, b, c = r.as_euler("ZYX", degrees=True)
    return tuple(ucsio.geometry.rotations.wrap180(v) for v in (a, b, c))


def test_corpus_values_read_by_hand():
    cf = ucsio.load(corpus_file("abb", "CalibData.mod"))
    f = frames_by_name(cf)
    assert set(f) >= {"Gripper", "Mandrell", "Mandrell.oframe", "Laser.oframe"}
    m = f["Mandrell.oframe"]
    assert (m.pose.x, m.pose.y, m.pose.z) == (2812.88, -226.05, 592.36)
    assert m.numbers["q4"].text == "0.65415"
    assert m.reference == "uframe" and m.line == 5
    g = f["Gripper_Sleeve"]
    assert g.type == "tooldata" and g.reference == "flange" and g.info["robhold"] is True
    assert g.info["load"]["mass"] == 25 and g.info["load"]["cog"] == [0, 0, 800]
    assert f["Sleeves"].info["ufprog"] is True and f["Sleeves"].info["ufmec"] == ""


def test_false_positives_are_not_frames():
    # a user type named like tooldata, PERS procedure parameters, a commented template
    assert ucsio.load(corpus_file("abb", "eg1tol.sys")).frames == []
    assert ucsio.load(corpus_file("abb", "eg1bas.sys")).frames == []
    assert ucsio.load(corpus_file("abb", "joseballester__abb-rapidserver__HOME__user.sys")).frames == []


def test_commented_duplicates_are_not_live():
    path = corpus_file("abb", "Tool_Create.mod")
    cf = ucsio.load(path)
    text = path.read_text()
    for f in cf.frames:
        line = text.splitlines()[f.line - 1]
        assert not line.lstrip().startswith("!"), f.name


def test_moving_work_object_is_reported():
    cf = ucsio.load(corpus_file("abb", "Head_Data.mod"))
    moving = [f for f in cf.frames if f.info.get("ufprog") is False]
    assert {f.name for f in moving} >= {"wobjWeldLine1", "wobjWeldLine1.oframe"}
    assert cf.frame("wobjWeldLine1").info["ufmec"] == "ELM_X"
    linted = {l.line for l in cf.lints if l.code == "moving-uframe"}
    assert {f.line for f in moving} == linted


def test_bom_and_header_prg():
    cf = ucsio.load(corpus_file("abb", "ppacal.prg"))
    assert cf.document.bom and cf.document.to_bytes() == cf.document.raw
    assert cf.frame("WorkObject").info["storage"] == "TASK PERS"


def test_wobj_nested_in_user_record_is_not_a_frame_but_file_parses():
    cf = ucsio.load(corpus_file("abb", "ppaUser.sys"), full=True)
    assert all(f.type in ("tooldata", "wobjdata", "pose") for f in cf.frames)


# -- syntax variants (our fixtures) ------------------------------------------------
def test_variants_fixture():
    cf = ucsio.load(ABB / "variants.mod")
    f = frames_by_name(cf)
    assert f["tools{1}"].pose.t == (1, 2, 3)
    t2 = f["tools{2}"]
    assert t2.pose.t == (0.5, 5.0, 0.0)
    assert t2.pose.abc == pytest.approx((0, 90, 0), abs=1e-4)
    assert t2.numbers["z"].text == "-0"
    w = f["wobjSpaced"]
    assert w.pose.t == (-100.5, 200.0, 30.0)
    assert w.numbers["x"].text == "- 100.5"  # the minus and its number are one value span
    assert f["wobjSpaced.oframe"].numbers["z"].text == "9E9"
    p = f["pShift"]
    assert p.type == "pose" and p.info["storage"] == "LOCAL PERS"
    assert p.pose.y == -2.5e-3 and p.numbers["x"].value == 1.4013e-45
    assert f["wobjVar"].pose is None and f["tNoValue"].pose is None
    assert {"cube{1,1}", "cube{2,1}", "cube{2,1}.oframe"} <= set(f)
    assert f["cube{2,1}"].pose.x == 20
    # not frames: the commented wobj, the user type, record fields, routine locals, parameters
    assert not {"wobjCommented", "notATool", "tLocal", "Tool", "WObj", "t"} & set(f)
    assert f["wobjSpaced"].info["storage"] == "TASK PERS"
    assert f["tools{1}"].line == 11 and f["tools{2}"].line == 12


def test_variants_fixture_full_grammar_agrees():
    fast = ucsio.load(ABB / "variants.mod")
    full = ucsio.load(ABB / "variants.mod", full=True)
    assert [x.as_dict() for x in fast.frames] == [x.as_dict() for x in full.frames]


def test_two_modules_with_crcrlf_and_no_final_newline():
    path = ABB / "two_modules_crcrlf.prg"
    raw = path.read_bytes()
    assert b"\r\r\n" in raw and not raw.endswith(b"\n")
    cf = ucsio.load(path)
    f = frames_by_name(cf)
    assert f["wobjA"].line == 7 and f["wobjA"].info["module"] == "First"
    assert f["tB"].line == 10 and f["tB"].info["module"] == "Second"
    assert cf.document.to_bytes() == raw


def test_latin1_and_bom_files():
    cf = ucsio.load(ABB / "latin1.mod")
    assert cf.document.encoding == "latin-1"
    assert cf.frame("WOBJL").pose.abc == pytest.approx((90, 0, 0), abs=1e-4)  # case-insensitive
    assert cf.document.to_bytes() == (ABB / "latin1.mod").read_bytes()
    cf = ucsio.load(ABB / "bom.mod")
    assert cf.document.bom and cf.frame("p1").pose.t == (1, 2, 3)


def test_unnormalised_quaternion_and_massless_tool_are_linted():
    doc = Document(b"MODULE m\n"
                   b"  PERS tooldata t1:=[TRUE,[[0,0,100],[0.9,0,0,0]],[0,[0,0,0],[1,0,0,0],0,0,0]];\n"
                   b"  PERS wobjdata w1:=[FALSE,FALSE,\"STN1\",[[0,0,0],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n"
                   b"ENDMODULE\n", "lint.mod")
    lints = rapid.parse(doc).lints
    assert {"unnormalized-quaternion", "tool-mass", "moving-uframe"} <= {l.code for l in lints}
    assert all(l.severity == "warning" for l in lints)
    ok = Document(b"MODULE m\n  PERS tooldata t1:=[TRUE,[[0,0,100],[1,0,0,0]],[1,[0,0,0],[1,0,0,0],0,0,0]];\nENDMODULE\n")
    assert rapid.parse(ok).lints == []


def test_stationary_tool_and_robot_held_wobj_references():
    doc = Document(b"MODULE m\n"
                   b"  PERS tooldata tFixed:=[FALSE,[[500,0,800],[1,0,0,0]],[1,[0,0,0],[1,0,0,0],0,0,0]];\n"
                   b"  PERS wobjdata wHeld:=[TRUE,TRUE,\"\",[[0,0,0],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n"
                   b"ENDMODULE\n")
    f = frames_by_name(rapid.parse(doc))
    assert f["tFixed"].reference == "world"
    assert f["wHeld"].reference == "wrist" and f["wHeld.oframe"].reference == "uframe"


def test_ambiguous_name_is_refused():
    doc = Document(b"MODULE a\n  PERS pose p:=[[1,0,0],[1,0,0,0]];\nENDMODULE\n"
                   b"MODULE b\n  PERS pose P:=[[2,0,0],[1,0,0,0]];\nENDMODULE\n", "two.prg")
    with pytest.raises(UcsioError, match="ambiguous"):
        rapid.parse(doc).frame("p")


# -- bad input ---------------------------------------------------------------------
BAD = {
    "truncated.mod": (3, 1, "ENDMODULE missing"),
    "unbalanced.mod": (2, 3, "unbalanced"),
    "unbalanced_frame.mod": (2, 3, "unbalanced"),
    "badnumber.mod": (2, 30, "bad number '1.2.3'"),
    "garbage.mod": (3, 3, "unexpected text"),
    "unterminated_proc.mod": (2, 3, "without its ENDPROC"),
}


def run_cli(*args):
    return subprocess.run([sys.executable, "-m", "ucsio", *map(str, args)],
                          capture_output=True, text=True)


@pytest.mark.parametrize("command", ["frames", "check"])
@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_input_one_line_with_position(command, name, tmp_path):
    path = ABB / "bad" / name
    line, col, words = BAD[name]
    before = sorted(p.name for p in path.parent.iterdir())
    res = run_cli(command, path)
    assert res.returncode == 2
    assert res.stdout == ""
    assert res.stderr.count("\n") == 1
    assert f"{path}:{line}:{col}: " in res.stderr and words in res.stderr
    assert sorted(p.name for p in path.parent.iterdir()) == before  # nothing written


def test_bad_number_in_a_robtarget_is_found_by_check():
    res = run_cli("check", ABB / "bad" / "badnumber_target.mod")
    assert res.returncode == 2 and ":2:29: bad number '3e'" in res.stderr


@pytest.mark.parametrize("command", ["frames", "check"])
def test_binary_and_missing_files(command, tmp_path):
    res = run_cli(command, ABB / "encrypted.mod")
    assert res.returncode == 2 and "encrypted" in res.stderr and res.stderr.count("\n") == 1
    res = run_cli(command, tmp_path / "nope.mod")
    assert res.returncode == 2 and "nope.mod: no such file" in res.stderr


# -- the commands ------------------------------------------------------------------
def test_frames_json_keys():
    res = run_cli("frames", "--json", ABB / "variants.mod", ABB / "two_modules_crcrlf.prg")
    assert res.returncode == 0
    frames = json.loads(res.stdout)["frames"]
    for item in frames:
        assert {"name", "file", "line", "vendor", "type", "x", "y", "z", "a", "b", "c", "q"} <= set(item)
        assert item["vendor"] == "abb"
    tb = next(i for i in frames if i["name"] == "tB")
    assert tb["z"] == 150 and tb["q"] == [1, 0, 0, 0] and tb["type"] == "tooldata"


def test_frames_table_is_readable():
    res = run_cli("frames", ABB / "two_modules_crcrlf.prg")
    assert res.returncode == 0
    assert re.search(r"wobjA\s+wobjdata\s+world\s+100\.000\s+200\.000\s+300\.000", res.stdout)


def test_check_reports_round_trip_and_lints():
    res = run_cli("check", "--json", ABB / "two_modules_crcrlf.prg")
    assert res.returncode == 0
    out = json.loads(res.stdout)
    assert out["ok"] and out["files"][0]["round_trip"] and out["files"][0]["lints"] == []
    # a PERS or VAR without a value is legal RAPID: reported as info, the check passes
    res = run_cli("check", ABB / "variants.mod")
    assert res.returncode == 0 and "info: no-value" in res.stdout


def test_check_fails_on_warnings(tmp_path):
    bad = tmp_path / "lint.mod"
    bad.write_text("MODULE m\n  PERS tooldata t:=[TRUE,[[0,0,1],[0.9,0,0,0]],[1,[0,0,0],[1,0,0,0],0,0,0]];\n"
                   "ENDMODULE\n")
    res = run_cli("check", "--json", bad)
    out = json.loads(res.stdout)
    assert res.returncode == 1 and not out["ok"]
    assert [(l["code"], l["severity"]) for l in out["files"][0]["lints"]] == \
        [("unnormalized-quaternion", "warning")]


def test_check_whole_corpus_round_trips():
    paths = [p.values[0] for p in corpus_files("abb") if p.values[0] is not None]
    if not paths:
        pytest.skip("corpus absent")
    res = run_cli("check", "--json", *paths)
    out = json.loads(res.stdout)
    assert all(f["round_trip"] for f in out["files"]) and len(out["files"]) == len(paths)


def test_outline_and_grammar_share_routine_and_record_patterns():
    """The outline scanner skips routines and records with the grammar's own
    terminals: a LOCAL on its own line must not pass one path and fail the other."""
    assert "(?P<routine>" + rapid._grammar_terminal("ROUTINE") + ")" in rapid._OUTLINE.pattern
    assert "(?P<record>" + rapid._grammar_terminal("RECORD_DEF") + ")" in rapid._OUTLINE.pattern
    text = ("MODULE m\n  LOCAL\n  PROC p()\n  ENDPROC\n  LOCAL\n  RECORD r\n    num a;\n  ENDRECORD\n"
            "  PERS pose x:=[[1,2,3],[1,0,0,0]];\nENDMODULE\n")
    for full in (False, True):
        assert rapid.parse(Document(text.encode(), "l.mod"), full=full).frame("x").pose.t == (1, 2, 3)


def test_check_round_trip_catches_a_span_off_by_one():
    from ucsio.commands.check import round_trip
    from ucsio.geometry.frames import Number
    from ucsio.parsing.document import Span
    cf = rapid.parse(Document((ABB / "two_modules_crcrlf.prg").read_bytes(), "x.prg"), full=True)
    assert round_trip(cf)
    n = cf.frames[0].numbers["x"]
    cf.frames[0].numbers["x"] = Number(Span(n.span.start, n.span.end + 1), n.text, n.value)
    assert not round_trip(cf)


def test_placeholders_are_legal_and_make_a_declaration_incomplete(tmp_path):
    text = ("MODULE m\n  <DDN>\n  PERS <TDN> w0 := 1;\n"
            '  PERS wobjdata wPh := [FALSE,TRUE,"",[[<EXP>,2,3],[1,0,0,0]],[[4,5,6],[1,0,0,0]]];\n'
            "ENDMODULE\n")
    for full in (False, True):
        cf = rapid.parse(Document(text.encode(), "ph.mod"), full=full)
        assert cf.frame("wPh.oframe").info["incomplete"] is True
        assert [(l.code, l.line) for l in cf.lints if l.severity == "warning"] == [("incomplete", 4)]
    path = tmp_path / "ph.mod"
    path.write_text(text)
    res = run_cli("patch", path, "--frame", "wPh.oframe", "--set", "1,2,3,0,0,0")
    assert res.returncode == 2 and "placeholder" in res.stderr and path.read_text() == text


@pytest.mark.parametrize("body,code", [
    ('PERS wobjdata w := [FALSE,TRUE,"",[[1,2,3],[1,0,0,0]]];', "bad-shape"),
    ('PERS wobjdata w := [FALSE,TRUE,"",[[1,2,3],[1,0,0]],[[0,0,0],[1,0,0,0]]];', "bad-shape"),
    ("PERS pose w{3} := [[[1,2,3],[1,0,0,0]],[[1,2,3],[1,0,0,0]]];", "array-size"),
    ("PERS pose w := [[1,2,3],[1,0,0,0]];\n  PERS pose W := [[1,2,3],[1,0,0,0]];", "duplicate"),
])
def test_ill_formed_frame_data_is_a_warning(body, code):
    text = f"MODULE m\n  {body}\nENDMODULE\n"
    for full in (False, True):
        cf = rapid.parse(Document(text.encode(), "s.mod"), full=full)
        assert [l.code for l in cf.lints if l.severity == "warning"] == [code]


def test_number_beyond_float32_is_bad_input():
    with pytest.raises(UcsioError, match="out of range"):
        rapid.parse(Document(b"MODULE m\n  PERS pose p := [[1E400,0,0],[1,0,0,0]];\nENDMODULE\n"))
