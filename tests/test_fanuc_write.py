"""FANUC write-back (issue 19 point 6): ``patch prog.ls`` replaces a TP
program's six ``PR[n,i]`` values in its own style, ``patch sysframe.va -o``
writes a reviewed copy of the listing with its field widths, and ``ucsio
program`` writes a new TP program that reads back as the solution (a
property test over random frames, angles near +-180 and P = +-90).

Numbers are checked against independent sources: the written text parsed
back by ucsio's grammar and compared with the target through scipy-tested
rotations (tests/test_rotations.py), and the bytes outside the edited
values compared with the original."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import CORPUS, FIXTURES, ROOT, corpus_file
from ucsio.geometry import rotations as rot
from ucsio.geometry.frames import Pose
from ucsio.parsing.controller import load, parse
from ucsio.parsing.document import Document
from ucsio.vendors.fanuc.program import make_program, program
from ucsio.vendors.fanuc.write import fanuc_edit, fanuc_number, tp_literal

SRC = str(ROOT / "src")
FANUC = FIXTURES / "fanuc"
UB = "irbzavalagit__UB10200_RBT01__"
needs_corpus = pytest.mark.skipif(not (CORPUS / "fanuc").is_dir(),
                                  reason="the shared corpus (../shared/corpus/fanuc) is absent")


def run(*args, cwd=None):
    env = dict(os.environ, PYTHONPATH=SRC, NO_COLOR="1")
    return subprocess.run([sys.executable, "-m", "ucsio", *map(str, args)], cwd=cwd,
                          capture_output=True, env=env)


def solution(path, x, y, z, w, p, r, tcp=None):
    pose = Pose.from_wpr(x, y, z, w, p, r)
    a, b, c = pose.abc
    doc = {"frame": {"x": x, "y": y, "z": z, "a": a, "b": b, "c": c}, "accepted": True}
    if tcp is not None:
        doc["tcp"] = {"x": tcp[0], "y": tcp[1], "z": tcp[2], "solved": True}
    path.write_text(json.dumps(doc))
    return path


def close(frame, pose):
    assert frame.pose is not None
    assert all(abs(a - b) <= 5e-4 + 1e-9 for a, b in zip(frame.pose.t, pose.t))
    assert rot.quat_angle(frame.pose.q, pose.q) <= 1e-3


def changed_lines(old: bytes, new: bytes):
    a, b = old.split(b"\n"), new.split(b"\n")
    assert len(a) == len(b)
    return [(i + 1, x, y) for i, (x, y) in enumerate(zip(a, b)) if x != y]


# -- numbers -----------------------------------------------------------------------------
def test_numbers_as_the_controller_writes_them():
    assert fanuc_number(0.14) == ".140" and fanuc_number(-0.515) == "-.515"
    assert fanuc_number(3495.6) == "3495.600" and fanuc_number(0.0) == "0.000"
    assert fanuc_number(-1e-9) == "0.000"                 # never -0
    assert fanuc_number(-1100.3, style=None) == "-1100.3"
    assert fanuc_number(-0.4, style=None) == "-.4" and fanuc_number(180.0, style=None) == "180"
    assert fanuc_number(0.25, leading_zero=True) == "0.250"
    assert fanuc_number(1.23456, style=None) == "1.235"
    assert tp_literal("-.4") == "(-.4)" and tp_literal("770.299") == "770.299"


def test_an_edit_keeps_a_listing_s_field_width_and_a_program_s_parentheses():
    from ucsio.geometry.frames import Number
    from ucsio.parsing.document import Span

    def edit(text, number, new, listing):
        s = text.index(number)
        e = fanuc_edit(text, Number(Span(s, s + len(number)), number, float(number)), new,
                       listing)
        return text[:e.span.start] + e.text + text[e.span.end:]

    line = "  W:      .140   P:      .080   R:   -90.040"
    assert edit(line, ".140", "-12.345", True) == "  W:   -12.345   P:      .080   R:   -90.040"
    assert edit("  X:  3495.600", "3495.600", "-12345.678", True) == "  X: -12345.678"
    assert edit("PR[16,2]=(-1100.3)    ;", "-1100.3", "5", False) == "PR[16,2]=5    ;"
    assert edit("PR[16,3]=770.299    ;", "770.299", "-7", False) == "PR[16,3]=(-7)    ;"
    assert edit("PR[6,3]=((-29))    ;", "-29", "4", False) == "PR[6,3]=((4))    ;"


# -- a program that sets the frame ----------------------------------------------------------
@needs_corpus
def test_patch_of_the_oem_program_replaces_six_values_and_nothing_else(tmp_path):
    prog = tmp_path / "TOOLDATA.LS"
    shutil.copy(corpus_file("fanuc", UB + "tooldataub10200rbt01.ls"), prog)
    before = prog.read_bytes()
    sol = solution(tmp_path / "s.json", 3500.4567, 5819.1, -1176.0, -0.02, 0.1234, -89.95)
    res = run("patch", prog, "--frame", "UB10200_FXT01", "--measured", sol)
    assert res.returncode == 0, res.stderr
    assert prog.read_bytes() == before                    # a preview
    assert b"+   9:  PR[16,1]=3500.457    ;" in res.stdout
    out = tmp_path / "new.LS"
    assert run("patch", prog, "--frame", "UF1", "--measured", sol, "-o", out).returncode == 0
    new = out.read_bytes()
    assert changed_lines(before, new) == [
        (31, b"   9:  PR[16,1]=3500    ;\r", b"   9:  PR[16,1]=3500.457    ;\r"),
        (32, b"  10:  PR[16,2]=5820    ;\r", b"  10:  PR[16,2]=5819.1    ;\r"),
        (33, b"  11:  PR[16,3]=(-1176.5)    ;\r", b"  11:  PR[16,3]=(-1176)    ;\r"),
        (34, b"  12:  PR[16,4]=0    ;\r", b"  12:  PR[16,4]=(-.02)    ;\r"),
        (35, b"  13:  PR[16,5]=0    ;\r", b"  13:  PR[16,5]=.123    ;\r"),
        (36, b"  14:  PR[16,6]=(-90)    ;\r", b"  14:  PR[16,6]=(-89.95)    ;\r")]
    cf = load(str(out))
    close(cf.frame("UF1"), Pose.from_wpr(3500.4567, 5819.1, -1176.0, -0.02, 0.1234, -89.95))
    for other in ("UT1", "UF19", "UF20"):
        assert cf.frame(other).pose == load(str(prog)).frame(other).pose
    # again with the values it now has: nothing to change
    again = run("patch", out, "--frame", "UF1", "--measured", sol, "--in-place", "--backup")
    assert again.returncode == 0 and b"already has these values" in again.stdout
    assert not (tmp_path / "new.LS.bak").exists()
    # in place, with a backup
    assert run("patch", prog, "--frame", "UF1", "--measured", sol, "--in-place",
               "--backup").returncode == 0
    assert prog.read_bytes() == new and (tmp_path / "TOOLDATA.LS.bak").read_bytes() == before


@needs_corpus
def test_a_tool_of_the_program_gets_the_solved_tcp_only(tmp_path):
    prog = tmp_path / "TOOLDATA.LS"
    shutil.copy(corpus_file("fanuc", UB + "tooldataub10200rbt01.ls"), prog)
    before = prog.read_bytes()
    sol = solution(tmp_path / "t.json", 1, 2, 3, 0, 0, 0, tcp=(-0.5, -1100.25, 771))
    res = run("patch", prog, "--frame", "SSW", "--measured", sol, "--json")
    assert res.returncode == 0, res.stderr
    doc = json.loads(res.stdout)["patch"]
    assert [(c["component"], c["old"], c["new"]) for c in doc["changes"]] == [
        ("x", "-.4", "-.5"), ("y", "-1100.3", "-1100.25"), ("z", "770.299", "771")]
    given = solution(tmp_path / "g.json", 1, 2, 3, 0, 0, 0)
    res = run("patch", prog, "--frame", "UT1", "--measured", given)
    assert res.returncode == 2 and b"TOOLDATA.LS:30:8: UT1: this tool is held by the robot" \
        in res.stderr
    assert prog.read_bytes() == before


@pytest.mark.parametrize("frame, where, why", [
    ("UF2", "36:8", "set twice in this program, with different values (lines 14 and 36)"),
    ("UT3", "17:8", "PR[21] Y Z W P R are not given literal values"),
    ("UF4", "20:8", "PR[20] X Y Z W P R are not given literal values"),
    ("UT5", "21:8", "the register is R[3], known only when the program runs"),
    ("UT6", "25:8", "PR[22] X Y P R are 0 from LPOS-LPOS"),
    ("UF[R[9]]", "18:8", "the frame number is R[9], known only when the program runs"),
    ("UF7", "32:8", "PR[23] holds joint values (JPOS)"),
    ("UF8", "33:8", "PR[99] is not given values in this program"),
])
def test_a_frame_the_program_does_not_set_from_literals_is_refused(tmp_path, frame, where, why):
    prog = tmp_path / "p.ls"
    shutil.copy(FANUC / "program_frames.ls", prog)
    sol = solution(tmp_path / "s.json", 1, 2, 3, 4, 5, 6)
    res = run("patch", prog, "--frame", frame, "--measured", sol, "--in-place", "--backup")
    err = res.stderr.decode()
    assert res.returncode == 2 and err.startswith(f"ucsio: {prog}:{where}: ") and why in err, err
    assert len(err.splitlines()) == 1
    assert prog.read_bytes() == (FANUC / "program_frames.ls").read_bytes()
    assert sorted(os.listdir(tmp_path)) == ["p.ls", "s.json"]


def test_a_value_two_frames_read_is_refused_and_a_frame_set_twice_alike_is_patched(tmp_path):
    prog = tmp_path / "p.ls"
    shutil.copy(FANUC / "program_patch.ls", prog)
    before = prog.read_bytes()
    sol = solution(tmp_path / "s.json", 3500.4567, 5819.1, -1176.0, -0.02, 0.1234, -89.95)
    res = run("patch", prog, "--frame", "UF5", "--measured", sol, "--in-place")
    assert res.returncode == 2 and b"p.ls:19:17: UF5: the PR[31] value on line 19 also sets " \
        b"UF6 (line 26)" in res.stderr and prog.read_bytes() == before
    assert run("patch", prog, "--frame", "TWICE", "--measured", sol, "--in-place").returncode == 0
    cf = load(str(prog))
    twice = [f for f in cf.frames if f.name == "UF7"]
    assert len(twice) == 2
    for f in twice:
        close(f, Pose.from_wpr(3500.4567, 5819.1, -1176.0, -0.02, 0.1234, -89.95))
    assert len(changed_lines(before, prog.read_bytes())) == 6


def test_the_program_s_own_style_is_kept(tmp_path):
    """Zero-padded three decimals with a leading zero stay so; a value in
    two parentheses keeps them."""
    prog = tmp_path / "p.ls"
    shutil.copy(FANUC / "program_patch.ls", prog)
    before = prog.read_bytes()
    sol = solution(tmp_path / "s.json", 1200.0, -300.5, 0.5, -179.9999, 0.0004, -89.5)
    assert run("patch", prog, "--frame", "FIXTURE", "--measured", sol, "-o",
               tmp_path / "o.ls").returncode == 0
    lines = changed_lines(before, (tmp_path / "o.ls").read_bytes())
    # X, Y, W (180 is -180 at 0.001 deg) and P (0.0004 rounds to 0) keep their text
    assert [(n, new) for n, _, new in lines] == [
        (13, b"   5:  PR[30,3]=0.500    ;"), (16, b"   8:  PR[30,6]=((-89.500))    ;")]


def test_a_listing_gets_a_reviewed_copy_with_its_field_widths(tmp_path):
    va = tmp_path / "sysframe.va"
    shutil.copy(FANUC / "sysframe_comment.va", va)
    before = va.read_bytes()
    sol = solution(tmp_path / "s.json", 1201.25, -300.25, 0.75, 0.5, -0.25, 90.125)
    out = tmp_path / "reviewed.va"
    res = run("patch", va, "--frame", "UF1", "--measured", sol, "-o", out)
    assert res.returncode == 0 and b"does not load .va files" in res.stderr
    assert va.read_bytes() == before
    new = out.read_bytes()
    lines = changed_lines(before, new)
    assert lines and all(len(old) == len(n) for _, old, n in lines)
    close(parse(Document(new, str(out))).frame("UF1"),
          Pose.from_wpr(1201.25, -300.25, 0.75, 0.5, -0.25, 90.125))
    text = b"\n".join(n for _, _, n in lines)
    assert b".500" in text and b"-.250" in text and b"0.500" not in text
    res = run("patch", va, "--frame", "UF1", "--measured", sol, "--in-place")
    assert res.returncode == 2 and va.read_bytes() == before


@needs_corpus
def test_the_corpus_listing_copy_changes_that_entry_s_numbers_only(tmp_path):
    va = tmp_path / "sysframe.va"
    shutil.copy(corpus_file("fanuc", UB + "sysframe.va"), va)
    before = va.read_bytes()
    sol = solution(tmp_path / "s.json", 3500.4567, 5819.1, -1176.0, -0.02, 0.1234, -89.95)
    assert run("patch", va, "--frame", "UF1", "--measured", sol, "-o",
               tmp_path / "o.va").returncode == 0
    assert changed_lines(before, (tmp_path / "o.va").read_bytes()) == [
        (75, b"  X:  3495.600   Y:  5813.000   Z: -1166.400\r",
         b"  X:  3500.457   Y:  5819.100   Z: -1176.000\r"),
        (76, b"  W:      .140   P:      .080   R:   -90.040\r",
         b"  W:     -.020   P:      .123   R:   -89.950\r")]


# -- a new program ----------------------------------------------------------------------------
angle = st.one_of(st.floats(-180, 180), st.sampled_from([180.0, -180.0, 179.9996, -179.9996]),
                  st.floats(179.99, 180), st.floats(-180, -179.99))
pitch = st.one_of(st.floats(-90, 90), st.sampled_from([90.0, -90.0, 89.9996, -89.9996]),
                  st.floats(89.999, 90), st.floats(-90, -89.999))
coordinate = st.floats(-5000, 5000)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(coordinate, coordinate, coordinate, angle, pitch, angle,
       st.sampled_from(["UF3", "UF1@2", "UF20"]))
def test_a_new_program_reads_back_as_the_solution(x, y, z, w, p, r, frame):
    target = Pose.from_wpr(x, y, z, w, p, r)
    made = program(target, frame, pr=90)
    cf = parse(Document(made.data, "SET.LS"), full=True)
    (f,) = cf.frames
    assert f.name == frame and cf.lints == []
    close(f, target)
    # the values as written: three decimals, no leading zero, negatives in parentheses
    for n in f.numbers.values():
        assert n.text.lstrip("-").startswith(".") or not n.text.lstrip("-").startswith("0.") \
            or float(n.text) == 0
        assert len(n.text.split(".")[1]) == 3


def test_the_program_s_text(tmp_path):
    text = make_program(Pose.from_wpr(1500.25, -250.5, -0.4, 180, 0, -90), "UFRAME", 3, 1, 90,
                        name="SET_UF3", comment="FIXTURE")
    assert text.count("\r\n") == text.count("\n") and text.startswith("/PROG  SET_UF3\r\n/ATTR")
    mn = text.split("/MN\r\n")[1].split("/POS")[0].splitlines()
    assert mn == ["   1:  MESSAGE[UCSIO SETS UF3] ;", "   2:  PAUSE ;",
                  "   3:  PR[90]=LPOS-LPOS    ;", "   4:  PR[90,1]=1500.250    ;",
                  "   5:  PR[90,2]=(-250.500)    ;", "   6:  PR[90,3]=(-.400)    ;",
                  "   7:  PR[90,4]=180.000    ;", "   8:  PR[90,5]=0.000    ;",
                  "   9:  PR[90,6]=(-90.000)    ;", "  10:  UFRAME[3:FIXTURE]=PR[90] ;"]
    assert "LINE_COUNT\t= 10;" in text and text.endswith("/POS\r\n/END\r\n")
    assert "DEFAULT_GROUP\t= *,1,*,*,*;" in make_program(Pose.from_wpr(0, 0, 0, 0, 0, 0),
                                                         "UTOOL", 2, 2, 5, name="X")


def test_ucsio_program_and_frames_read_it_back(tmp_path):
    sol = solution(tmp_path / "s.json", 1500.25, -250.5, -0.4, 179.9999, 0.001, -90)
    res = run("program", sol, "--frame", "UF3", "--pr", "90", "--comment", "FIXTURE")
    assert res.returncode == 0 and res.stdout.startswith(b"/PROG  SET_UF3\r\n")
    out = tmp_path / "SET_UF3.LS"
    res = run("program", sol, "--frame", "UF3", "--pr", "90", "-o", out)
    assert res.returncode == 0 and b"wrote" in res.stderr and res.stdout == b""
    assert out.read_bytes().startswith(b"/PROG  SET_UF3\r\n")
    listed = json.loads(run("frames", out, "--json").stdout)["frames"]
    assert [(f["name"], f["type"]) for f in listed] == [("UF3", "UFRAME")]
    close(load(str(out)).frame("UF3"), Pose.from_wpr(1500.25, -250.5, -0.4, 179.9999, 0.001, -90))
    assert run("check", out).returncode == 0


@pytest.mark.parametrize("args, why", [
    (["--frame", "UF3"], b"--pr N, or --posreg posreg.va"),
    (["--frame", "UT1", "--pr", "5"], b"a tool frame needs a solution whose TCP was solved"),
    (["--frame", "UF3", "--pr", "5", "--comment", "A]B"], b"printable ASCII without"),
    (["--frame", "UF3", "--pr", "5", "--comment", "SEVENTEEN_LETTERS"], b"holds 16"),
    (["--frame", "XF3", "--pr", "5"], b"expected UFk or UTk"),
    (["--frame", "UF3@2", "--group", "3", "--pr", "5"], b"--group says 3"),
    (["--frame", "UF3", "--pr", "5", "-o", "1bad.LS"], b"is not a TP program name"),
])
def test_ucsio_program_refuses(tmp_path, args, why):
    sol = solution(tmp_path / "s.json", 1, 2, 3, 4, 5, 6)
    res = run("program", sol, *args, cwd=tmp_path)
    assert res.returncode == 2 and why in res.stderr, res.stderr
    assert sorted(os.listdir(tmp_path)) == ["s.json"]


@needs_corpus
def test_the_register_from_posreg_va(tmp_path):
    posreg = corpus_file("fanuc", UB + "posreg.va")
    sol = solution(tmp_path / "s.json", 1, 2, 3, 4, 5, 6, tcp=(0.5, -1.5, 250))
    res = run("program", sol, "--frame", "UT2", "--posreg", posreg, "--json")
    assert res.returncode == 0, res.stderr
    doc = json.loads(res.stdout)["program"]
    from ucsio.vendors.fanuc.va import position_registers
    regs = position_registers(Document.read(str(posreg)))
    entry = regs[(1, doc["pr"])]
    assert entry.uninit and not (entry.comment or "").strip()
    assert all(not (e.uninit and not (e.comment or "").strip())
               for (g, n), e in regs.items() if g == 1 and n > doc["pr"])
    assert doc["pose"] == {"x": 0.5, "y": -1.5, "z": 250.0, "w": 0.0, "p": 0.0, "r": 0.0}
    assert doc["warnings"] and f"UTOOL[2]=PR[{doc['pr']}] ;" in doc["text"]
    res = run("program", sol, "--frame", "UT2", "--posreg", posreg, "--pr", "16", "--wpr",
              "180,0,-90")
    assert res.returncode == 2 and b"PR[16] holds a value" in res.stderr
    res = run("program", sol, "--frame", "UT2", "--posreg", posreg, "--pr", "6", "--wpr",
              "180,0,-90")
    assert res.returncode == 0 and b"PR[6,4]=180.000" in res.stdout


def test_a_rejected_solution_is_refused(tmp_path):
    sol = tmp_path / "s.json"
    sol.write_text(json.dumps({"frame": {"x": 1, "y": 2, "z": 3, "a": 0, "b": 0, "c": 0},
                               "accepted": False, "reason": "too few points"}))
    res = run("program", sol, "--frame", "UF1", "--pr", "9")
    assert res.returncode == 1 and b"rejected" in res.stderr      # as patch: measure again


# -- start-up ---------------------------------------------------------------------------------
PROBE = """
import sys, io, contextlib
from ucsio.cli import main
with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
    code = main(sys.argv[1:])
print(__import__("json").dumps({"code": code, "heavy": sorted(
    m for m in ("numpy", "scipy", "lark") if m in sys.modules)}))
"""


def test_patching_fanuc_files_stays_light(tmp_path):
    """No numpy, no scipy; no Lark once the grammars' tables are cached (the
    frames run before each patch caches them)."""
    prog, va = tmp_path / "p.ls", tmp_path / "sysframe.va"
    shutil.copy(FANUC / "program_patch.ls", prog)
    shutil.copy(FANUC / "sysframe_comment.va", va)
    sol = solution(tmp_path / "s.json", 1, 2, 3, 4, 5, 6)
    env = dict(os.environ, PYTHONPATH=SRC, UCSIO_CACHE_DIR=str(tmp_path / "cache"))
    seen = []
    for args in (["frames", prog], ["patch", prog, "--frame", "UF1", "--measured", sol],
                 ["frames", va], ["patch", va, "--frame", "UF1", "--measured", sol, "-o",
                                  tmp_path / "o.va"]):
        res = subprocess.run([sys.executable, "-c", PROBE, *map(str, args)], env=env,
                             capture_output=True, text=True)
        seen.append(json.loads(res.stdout.strip().splitlines()[-1]))
    assert [s["code"] for s in seen] == [0] * 4
    assert seen[1]["heavy"] == [] and seen[3]["heavy"] == [], seen


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(coordinate, coordinate, coordinate, angle, pitch, angle,
       st.sampled_from(["program_patch.ls", "sysframe_comment.va"]))
def test_a_patch_reads_back_as_any_frame_and_changes_only_its_numbers(x, y, z, w, p, r, name):
    """patch_frame's own read-back check passes for every frame that can be
    written, in a program (its style) and in a listing (its widths); only
    the frame's lines change."""
    from ucsio.review.patch import patch_frame
    raw = (FANUC / name).read_bytes()
    cf = parse(Document(raw, str(FANUC / name)))
    target = Pose.from_wpr(x, y, z, w, p, r)
    result = patch_frame(cf, "UF1", target)
    again = parse(Document(result.new_bytes, str(FANUC / name))).frame("UF1")
    close(again, target)
    lines = {n for n, _, _ in changed_lines(raw, result.new_bytes)}
    allowed = {3 + 8, 4 + 8, 5 + 8, 6 + 8, 7 + 8, 8 + 8} if name.endswith(".ls") else \
        {cf.frame("UF1").line + 2, cf.frame("UF1").line + 3}
    assert lines <= allowed, (lines, allowed)


def test_a_value_that_changes_sign_keeps_the_program_s_form_and_nothing_else():
    """(-1100.3) patched to a positive value loses the pair of parentheses
    that only its sign needed (the pendant's form), and nothing else moves;
    the fuzz oracle says so too (it once took this for damage)."""
    from oracles import only_numbers_changed
    from ucsio.review.patch import patch_frame

    src = corpus_file("fanuc", UB + "tooldataub10200rbt01.ls")
    cf = load(src)
    res = patch_frame(cf, "UT1", Pose.from_wpr(1.0, 884.868, 3.0, 180, 0, -90),
                      measured=False, check_siblings=False)
    new = Document(res.new_bytes, str(src))
    text = new.text
    assert "PR[16,1]=1    ;" in text and "PR[16,2]=884.868    ;" in text
    assert "PR[16,7]" not in text and text.count("(") == cf.document.text.count("(") - 2
    again = parse(new)
    assert only_numbers_changed(cf.document.text, [cf.frame("UT1")], text, [again.frame("UT1")])
