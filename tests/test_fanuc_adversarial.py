"""Adversarial tests of FANUC write-back and reading (issue 19): generated
TP programs in every style the controller and other generators write
(spacing, CRLF/LF/mixed line endings, comments on PR, parenthesised and
doubled-parenthesised negatives, numbers without leading zero, integers,
long decimals, group prefixes, a frame of group 2 through DEFAULT_GROUP,
frames sharing registers or not), patched to random frames. The properties:
every byte outside the six values is the original's, the values read back
as the target within 0.001 mm and 0.001 deg, the other frames keep their
values, and a refusal changes nothing (exit 2, file:line:col).

Numbers are checked against independent sources: the text parsed back by
ucsio's grammar and compared with the target through scipy's Rotation
(``from_euler("xyz", [w, p, r])`` is FANUC's Rz(r)·Ry(p)·Rx(w))."""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from conftest import ROOT
from ucsio.errors import UcsioError
from ucsio.geometry.frames import Pose
from ucsio.parsing.controller import parse
from ucsio.parsing.document import Document
from ucsio.review.patch import patch_frame, patch_tcp

SRC = str(ROOT / "src")
SETTINGS = dict(deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


def run(*args, cwd=None):
    env = dict(os.environ, PYTHONPATH=SRC, NO_COLOR="1")
    return subprocess.run([sys.executable, "-m", "ucsio", *map(str, args)], cwd=cwd,
                          capture_output=True, env=env)


def matrix(x, y, z, w, p, r) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = Rotation.from_euler("xyz", [w, p, r], degrees=True).as_matrix()
    T[:3, 3] = (x, y, z)
    return T


def assert_pose(pose: Pose, x, y, z, w, p, r, mm=5e-4 + 1e-9, deg=1e-3):
    """``pose`` is X Y Z W P R within ``mm`` and ``deg`` (scipy's matrix)."""
    want = matrix(x, y, z, w, p, r)
    got = np.eye(4)
    got[:3, :3] = Rotation.from_quat([pose.q[1], pose.q[2], pose.q[3], pose.q[0]]).as_matrix()
    got[:3, 3] = pose.t
    assert np.all(np.abs(got[:3, 3] - want[:3, 3]) <= mm), (got[:3, 3], want[:3, 3])
    gap = Rotation.from_matrix(got[:3, :3].T @ want[:3, :3]).magnitude()
    assert np.degrees(gap) <= deg, np.degrees(gap)


# -- generated programs --------------------------------------------------------------------
def number_text(draw, value: float) -> str:
    """``value`` as one of the forms programs hold."""
    form = draw(st.sampled_from(["int", "short", "padded", "long", "lead0", "dot"]))
    if form == "int":
        s = str(int(round(value)))
    elif form == "short":
        s = f"{value:.3f}".rstrip("0").rstrip(".")
    elif form == "padded":
        s = f"{value:.3f}"
    elif form == "long":
        s = f"{value:.9f}"
    elif form == "lead0":
        s = f"{value:.2f}"
    else:
        s = f"{value:.1f}" + "."[:0]
        if s.startswith("0.") or s.startswith("-0."):
            s = s.replace("0.", ".", 1)
    if s in ("-0", "-0.0", "-.0", "-0.000", "-0.000000000", "-0.00"):
        s = s[1:]
    return s


def literal(draw, text: str) -> str:
    """A number as a PR[n,i]= value: bare, in parentheses, in two."""
    if text.startswith("-"):
        return draw(st.sampled_from([f"({text})", f"(({text}))", f"({text})"]))
    return draw(st.sampled_from([text, text, f"({text})", f"(({text}))"]))


values6 = st.tuples(*[st.floats(-3000, 3000, allow_nan=False)] * 3,
                    *[st.floats(-179.9, 179.9)] * 1, st.floats(-89.9, 89.9),
                    st.floats(-179.9, 179.9))


@st.composite
def programs(draw):
    """(program bytes, the frame's name, the PR lines' numbers (line index
    in /MN order), the other frames' names). The frame under test is set
    from PR[n]; other frames from their own registers, or (``share``) from
    the same one after it changed one component."""
    group = draw(st.sampled_from([1, 1, 2]))
    kind = draw(st.sampled_from(["UFRAME", "UTOOL"]))
    k = draw(st.integers(1, 30))
    n = draw(st.integers(1, 200))
    gp = draw(st.sampled_from(["", "", f"GP{group}:"]))
    prc = draw(st.sampled_from(["", "", ":frame", ": set up frame "]))
    fcomment = draw(st.sampled_from(["", ":FIXTURE", ":UF 9"]))
    refc = draw(st.sampled_from(["", ":frame"]))
    eq = draw(st.sampled_from(["=", "=", " = "]))
    pad = draw(st.sampled_from(["    ", " ", ""]))
    mn = []
    before = draw(st.lists(st.sampled_from([
        "!setting the frame", "R[1]=0", "UFRAME_NUM=0", "J P[1] 100% FINE", "PR[200]=LPOS",
        "PR[201,1]=5", "// PR[%d,1]=77" % n, "! PR[%d,2]=(-5)" % n, "PAUSE"]), max_size=3))
    mn += [b + " ;" for b in before]
    start = draw(st.sampled_from(["LPOS", "LPOS-LPOS", "LPOS - LPOS", "none"]))
    if start != "none":
        mn.append(f"PR[{gp}{n}{prc}]{eq}{start}{pad};")
    vals = draw(values6)
    order = draw(st.permutations(range(6)))
    pr_lines = []
    for i in order:
        mn.append(f"PR[{gp}{n},{i + 1}{prc}]{eq}{literal(draw, number_text(draw, vals[i]))}"
                  f"{pad};")
        pr_lines.append(len(mn) - 1)
    mn.append(f"{kind}[{k}{fcomment}]{eq}PR[{n}{refc}]{pad};")
    others = []
    share = False
    if draw(st.booleans()):                 # another frame, its own register
        m = n + 1 + draw(st.integers(0, 5))
        mn.append(f"PR[{m}]=LPOS-LPOS ;")
        for i in range(6):
            mn.append(f"PR[{m},{i + 1}]={literal(draw, number_text(draw, vals[i] / 2))} ;")
        other_k = k % 30 + 1
        mn.append(f"UFRAME[{other_k}]=PR[{m}] ;" if kind == "UTOOL" else
                  f"UTOOL[{other_k}]=PR[{m}] ;")
        others.append(("UF" if kind == "UTOOL" else "UT") + str(other_k))
    elif draw(st.booleans()):               # the same register, one value changed after
        share = True
        mn.append(f"PR[{gp}{n},1]=12.5 ;")
        other_k = k % 30 + 1
        mn.append(f"{kind}[{other_k}]=PR[{n}] ;")
        others.append(("UF" if kind == "UFRAME" else "UT") + str(other_k))
    mn += [a + " ;" for a in draw(st.lists(st.sampled_from([
        "L P[2] 500mm/sec CNT100", "!done", "UTOOL_NUM=1", "PR[202]=PR[202]-PR[202]"]),
        max_size=3))]
    endings = draw(st.sampled_from(["\r\n", "\n", "mixed"]))
    groups = ",".join("1" if g == group else "*" for g in range(1, 6))
    head = ["/PROG  GEN", "/ATTR", "OWNER\t\t= MNEDITOR;", f"DEFAULT_GROUP\t= {groups};", "/MN"]
    indent = draw(st.sampled_from(["{:4d}:  ", "{:d}:", "  {:d}:\t"]))
    lines = head + [indent.format(i) + s for i, s in enumerate(mn, 1)] + ["/POS", "/END"]
    if endings == "mixed":
        ends = draw(st.lists(st.sampled_from(["\r\n", "\n"]), min_size=len(lines),
                             max_size=len(lines)))
    else:
        ends = [endings] * len(lines)
    final = draw(st.booleans())
    text = "".join(line + end for line, end in zip(lines, ends))
    if not final:
        text = text[:-len(ends[-1])]
    name = ("UF" if kind == "UFRAME" else "UT") + str(k) + ("" if group == 1 else f"@{group}")
    others = [o + ("" if group == 1 else f"@{group}") for o in others]
    first = len(head)
    return text.encode("ascii"), name, [first + i for i in pr_lines], others, share


target_values = st.tuples(*[st.floats(-5000, 5000)] * 3,
                          st.one_of(st.floats(-180, 180), st.sampled_from([180.0, -180.0,
                                                                           179.9996])),
                          st.one_of(st.floats(-90, 90), st.sampled_from([90.0, -90.0,
                                                                         89.9996])),
                          st.one_of(st.floats(-180, 180), st.sampled_from([-179.9996, 0.0])))

_VALUE = re.compile(rb"^(.*?\]\s*=\s*)(.*?)(\s*;[^;]*)$", re.S)


def only_values_changed(old: bytes, new: bytes, pr_lines: list[int]) -> None:
    """Every line but the PR lines is the same bytes; on those, everything
    but the value (from after "=" to the ";") is too, and the new value is
    a number in at most three parentheses."""
    a, b = old.split(b"\n"), new.split(b"\n")
    assert len(a) == len(b)
    for i, (x, y) in enumerate(zip(a, b)):
        if x == y:
            continue
        assert i in pr_lines, (i, x, y)
        mx, my = _VALUE.match(x), _VALUE.match(y)
        assert mx and my and mx.group(1) == my.group(1) and mx.group(3) == my.group(3), (x, y)
        v = my.group(2).decode()
        assert re.fullmatch(r"\(*[ \t]*-?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)[ \t]*\)*", v), v
        assert v.count("(") == v.count(")") <= 3
        was = mx.group(2).decode()
        if _NUM.search(was).group().startswith("-") == _NUM.search(v).group().startswith("-"):
            assert _NUM.sub("N", was) == _NUM.sub("N", v), (x, y)    # the same parentheses
        elif _NUM.search(v).group().startswith("-"):
            assert v.startswith("(")        # a negative one in parentheses


_NUM = re.compile(r"-?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)")


@settings(max_examples=250, **SETTINGS)
@given(programs(), target_values)
def test_a_generated_program_is_patched_in_its_values_only(prog, target):
    raw, name, pr_lines, others, share = prog
    cf = parse(Document(raw, "GEN.LS"))
    frame = cf.frame(name)
    before = {f.name: f.pose for f in cf.frames}
    assert frame.pose is not None, [lint.message for lint in cf.lints]
    pose = Pose.from_wpr(*target)
    if share:
        with pytest.raises(UcsioError) as err:
            patch_frame(cf, name, pose, measured=False)
        assert err.value.line is not None and err.value.col is not None
        assert "also sets" in err.value.message
        return
    if name.startswith("UT"):           # a solved TCP: x, y, z; W P R stay
        result = patch_tcp(cf, name, target[:3])
        old = frame.info
        want = (*target[:3], old["w"], old["p"], old["r"])
    else:
        result = patch_frame(cf, name, pose)
        want = target
    only_values_changed(raw, result.new_bytes, pr_lines)
    again = parse(Document(result.new_bytes, "GEN.LS"), full=True)
    assert_pose(again.frame(name).pose, *want)
    for f in again.frames:
        if f.name != name:
            assert f.pose == before[f.name], f.name
    assert [lint.code for lint in again.lints] == [lint.code for lint in cf.lints]


def program_text(mn: list[str], group: int = 1) -> bytes:
    groups = ",".join("1" if g == group else "*" for g in range(1, 6))
    lines = ["/PROG  T", "/ATTR", f"DEFAULT_GROUP\t= {groups};", "/MN"]
    lines += [f"{i:4d}:  {s}" for i, s in enumerate(mn, 1)] + ["/POS", "/END"]
    return ("\r\n".join(lines) + "\r\n").encode()


def sets_from(n: int, values, head: str = "UFRAME[1]") -> list[str]:
    return [f"PR[{n}]=LPOS    ;"] + [f"PR[{n},{i}]={v}    ;" for i, v in enumerate(values, 1)] \
        + [f"{head}=PR[{n}] ;"]


@pytest.mark.parametrize("old, new_value, new", [
    ("(115)", 7, "(7)"),                 # a positive value the program put in parentheses
    ("(115)", -7, "(-7)"),
    ("( -5 )", -7, "( -7 )"),            # blanks inside the parentheses
    ("( -5 )", 7, "7"),
    ("( ( ( -5 ) ) )", -7, "( ( ( -7 ) ) )"),    # three deep stays three deep
    ("(((-5)))", 7, "(((7)))"),
    ("((-29))", 4, "((4))"),
    ("(-1100.3)", 5, "5"),               # the pendant's form: a positive one bare
    ("770.299", -7, "(-7)"),
])
def test_a_value_keeps_the_program_s_parentheses(old, new_value, new):
    values = ["1", "2", "3", "4", "5", old]
    raw = program_text(sets_from(16, values))
    cf = parse(Document(raw, "T.LS"))
    result = patch_frame(cf, "UF1", Pose.from_wpr(1, 2, 3, 4, 5, new_value), measured=False)
    assert result.new_bytes == raw.replace(f"PR[16,6]={old} ".encode(),
                                           f"PR[16,6]={new} ".encode())


def test_a_frame_s_name_is_never_taken_from_another_frame_s_comment(tmp_path):
    """UFRAME[1:UF2]=PR[16]: --frame UF2 names user frame 2, which the
    program does not set; it must not patch UF1, whose comment is "UF2"."""
    raw = program_text(sets_from(16, [1, 2, 3, 4, 5, 6], "UFRAME[1:UF2]"))
    prog = tmp_path / "T.LS"
    prog.write_bytes(raw)
    sol = tmp_path / "s.json"
    sol.write_text(json.dumps({"frame": {"x": 10, "y": 20, "z": 30, "a": 0, "b": 0, "c": 0},
                               "accepted": True}))
    res = run("patch", prog, "--frame", "UF2", "--measured", sol, "--in-place")
    assert res.returncode == 2 and b"no frame named 'UF2'" in res.stderr, res.stderr
    assert prog.read_bytes() == raw
    # the comment still names the frame where it is no frame's name
    raw = program_text(sets_from(16, [1, 2, 3, 4, 5, 6], "UFRAME[1:FIXTURE]"))
    prog.write_bytes(raw)
    res = run("patch", prog, "--frame", "fixture", "--measured", sol, "--in-place")
    assert res.returncode == 0, res.stderr
    assert parse(Document(prog.read_bytes(), str(prog))).frame("UF1").pose.t == (10, 20, 30)


# -- the reviewed copy of a listing ------------------------------------------------------------
from fanuc_cell import sysframe  # noqa: E402

extreme = st.one_of(st.floats(-5000, 5000), st.sampled_from(
    [-10000.0, 99999.999, -99999.999, 100000.0, -123456.789, 0.0004, -0.0004, 0.0]))
listing_target = st.tuples(extreme, extreme, extreme,
                           st.one_of(st.floats(-180, 180), st.sampled_from([180.0, -180.0])),
                           st.one_of(st.floats(-90, 90), st.sampled_from([90.0, -90.0])),
                           st.one_of(st.floats(-180, 180), st.sampled_from([180.0, -180.0])))
_FIELD = re.compile(rb"([XYZWPR]):(\s*)(\S+)")


@settings(max_examples=200, **SETTINGS)
@given(st.dictionaries(st.tuples(st.integers(1, 2), st.integers(1, 5)), values6, max_size=4),
       st.dictionaries(st.tuples(st.integers(1, 2), st.integers(1, 5)), values6, max_size=3),
       st.sampled_from(["UF", "UT"]), st.integers(1, 5), st.integers(1, 2), listing_target,
       st.sampled_from(["\r\n", "\n"]))
def test_a_listing_copy_changes_that_entry_s_numbers_only(uf, ut, kind, k, g, target, nl):
    raw = sysframe(uf, ut, groups=2, n_uf=5, n_ut=5).replace("\r\n", nl).encode()
    name = f"{kind}{k}" + ("" if g == 1 else f"@{g}")
    cf = parse(Document(raw, "sysframe.va"), beside=False)
    before = {f.name: f.pose for f in cf.frames}
    frame = cf.frame(name)
    pose = Pose.from_wpr(*target)
    if kind == "UT":
        result = patch_tcp(cf, name, target[:3])
        want = (*target[:3], frame.info["w"], frame.info["p"], frame.info["r"])
    else:
        result = patch_frame(cf, name, pose)
        want = target
    new = result.new_bytes
    a, b = raw.split(b"\n"), new.split(b"\n")
    assert len(a) == len(b)
    value_lines = {frame.line + 1, frame.line + 2}       # X Y Z, W P R (1-based: +2, +3)
    for i, (x, y) in enumerate(zip(a, b)):
        if x == y:
            continue
        assert i in value_lines, (i, x, y)
        fx, fy = _FIELD.findall(x), _FIELD.findall(y)
        assert [f[0] for f in fx] == [f[0] for f in fy]
        assert _FIELD.sub(b"", x) == _FIELD.sub(b"", y)      # the blanks between fields
        for (_, sx, vx), (_, sy, vy) in zip(fx, fy):
            assert len(sy) >= 1 and len(sx + vx) <= len(sy + vy)
            assert len(sy + vy) == len(sx + vx) or len(sy) == 1   # widened only where it must
    # the fast path and the tree of every byte read the same frames
    fast = parse(Document(new, "sysframe.va"), beside=False)
    whole = parse(Document(new, "sysframe.va"), full=True, beside=False)
    assert [(f.name, f.pose, f.line) for f in fast.frames] == \
        [(f.name, f.pose, f.line) for f in whole.frames]
    assert_pose(fast.frame(name).pose, *want)
    for f in fast.frames:
        if f.name != name:
            assert f.pose == before[f.name], f.name


@pytest.mark.parametrize("how", ["same", "dot", "symlink", "hardlink"])
def test_a_listing_is_not_written_over_itself_through_o(tmp_path, how):
    """-o OUT is a reviewed copy; OUT naming the listing itself (its path, a
    link to it) would be --in-place, which a listing refuses."""
    from conftest import FIXTURES
    va = tmp_path / "sysframe.va"
    va.write_bytes((FIXTURES / "fanuc" / "sysframe_comment.va").read_bytes())
    before = va.read_bytes()
    sol = tmp_path / "s.json"
    sol.write_text(json.dumps({"frame": {"x": 10, "y": 20, "z": 30, "a": 0, "b": 0, "c": 0},
                               "accepted": True}))
    out = {"same": va, "dot": tmp_path / "." / "sysframe.va", "symlink": tmp_path / "l.va",
           "hardlink": tmp_path / "h.va"}[how]
    if how == "symlink":
        out.symlink_to(va)
    elif how == "hardlink":
        os.link(va, out)
    res = run("patch", va, "--frame", "UF1", "--measured", sol, "-o", out)
    assert res.returncode == 2 and b"sysframe.va" in res.stderr and b"-o" in res.stderr, \
        res.stderr
    assert va.read_bytes() == before


# -- ucsio program ---------------------------------------------------------------------------------
def test_a_register_in_use_in_another_group_is_in_use(tmp_path):
    """A position register is one register for every group (posreg.va lists
    [g,n] for each, the comment on group 1's): PR[5] with a value or a
    comment in group 1 is in use for a group-2 program too, and the
    register --posreg picks is unused in every group."""
    from fanuc_cell import registers
    from ucsio.vendors.fanuc.program import program
    posreg = tmp_path / "posreg.va"
    posreg.write_text(registers([(1, 5, "", (1, 2, 3, 0, 0, 0)), (1, 20, "PERCH", None),
                                 (2, 19, "", {"J1": 1.0}), (1, 18, "", None)], groups=2, n=20),
                      newline="")
    pose = Pose.from_wpr(1, 2, 3, 0, 0, 0)
    for g, pr in ((2, 5), (2, 20), (1, 19)):
        with pytest.raises(UcsioError) as err:
            program(pose, "UF3", group=g, pr=pr, posreg=str(posreg))
        assert f"PR[{pr}]" in err.value.message and "in use" in err.value.message or \
            "holds" in err.value.message, err.value.message
    for g in (1, 2):
        made = program(pose, "UF3", group=g, posreg=str(posreg))
        assert made.pr == 18, (g, made.pr)
    assert program(pose, "UF3", group=2, pr=18, posreg=str(posreg)).pr == 18


def test_the_corpus_posreg_gives_group_2_a_register_free_in_group_1(tmp_path):
    from conftest import corpus_file
    from ucsio.vendors.fanuc.program import program
    from ucsio.vendors.fanuc.va import position_registers
    posreg = corpus_file("fanuc", "UB10200_RBT01__posreg.va")
    regs = position_registers(Document.read(str(posreg)))
    made = program(Pose.from_wpr(1, 2, 3, 0, 0, 0), "UF3@2", posreg=str(posreg))
    for g in (1, 2):
        e = regs[(g, made.pr)]
        assert e.uninit and not (e.comment or "").strip(), (g, made.pr, e.comment)
    with pytest.raises(UcsioError):          # PR[16]: the register tooldata...ls sets frames from
        program(Pose.from_wpr(1, 2, 3, 0, 0, 0), "UF3@2", pr=16, posreg=str(posreg))


@pytest.mark.parametrize("frame, group", [("UF3@0", None), ("UF3", 0), ("UT1@0", 0),
                                          ("UF3", -1), ("UF3@9", None)])
def test_a_group_outside_1_to_8_is_refused_not_taken_as_group_1(frame, group):
    from ucsio.vendors.fanuc.program import parse_frame
    with pytest.raises(UcsioError) as err:
        parse_frame(frame, group)
    assert "group 1...8" in err.value.message


def test_ucsio_program_with_group_0_writes_nothing(tmp_path):
    sol = tmp_path / "s.json"
    sol.write_text(json.dumps({"frame": {"x": 10, "y": 20, "z": 30, "a": 0, "b": 0, "c": 0},
                               "accepted": True}))
    res = run("program", sol, "--frame", "UF3@0", "--pr", "5", "-o", tmp_path / "SET.LS")
    assert res.returncode == 2 and b"group 1...8" in res.stderr
    assert sorted(os.listdir(tmp_path)) == ["s.json"]


@settings(max_examples=200, **SETTINGS)
@given(st.tuples(*[st.one_of(st.floats(-1e5, 1e5), st.sampled_from([1e5, -1e5, 99999.9996,
                                                                    -0.0004, 0.0005]))] * 3,
                 st.one_of(st.floats(-180, 180), st.sampled_from([180.0, -180.0, 179.9995,
                                                                  -179.9995])),
                 st.one_of(st.floats(-90, 90), st.sampled_from([90.0, -90.0, 89.9995,
                                                                -89.9995])),
                 st.one_of(st.floats(-180, 180), st.sampled_from([180.0, -180.0, 179.9995]))),
       st.sampled_from(["UF1", "UF9@2", "UF999", "UF2@8"]), st.integers(1, 9999))
def test_a_new_program_at_the_extremes_reads_back(values, frame, pr):
    from ucsio.vendors.fanuc.program import program
    made = program(Pose.from_wpr(*values), frame, pr=pr, comment="FIX 1")
    cf = parse(Document(made.data, "SET.LS"), full=True)
    (f,) = cf.frames
    assert f.name == frame and f.label == "FIX 1" and cf.lints == []
    assert_pose(f.pose, *values)
    assert all(abs(v) <= 180 for k, v in f.info.items() if k in "wpr")
    assert made.text.count("\r\n") == made.text.count("\n")
    assert re.search(rf"\bPR\[{pr}\]=LPOS-LPOS ", made.text)


# -- measurements from FANUC positions ----------------------------------------------------------
r3 = st.floats(-2000, 2000).map(lambda v: round(v, 3))
a3 = st.floats(-179.9, 179.9).map(lambda v: round(v, 3))
p3 = st.floats(-89.9, 89.9).map(lambda v: round(v, 3))
xyzwpr3 = st.tuples(r3, r3, r3, a3, p3, a3)


@settings(max_examples=120, **SETTINGS)
@given(xyzwpr3, xyzwpr3, xyzwpr3, xyzwpr3, st.integers(0, 3), st.integers(0, 3),
       st.lists(xyzwpr3, min_size=1, max_size=3), st.booleans())
def test_a_position_is_uf_p_ut_inverse_of_group_1_s_frames(uf, ut, decoy_uf, decoy_ut, u, t,
                                                            points, with_gp2):
    """The flange in world of a position taught in UF u with UT t is
    UF[u]·P·UT[t]⁻¹ with group 1's frames; group 2's frames of the same
    numbers (the decoys) and a GP2 block of the position play no part."""
    import tempfile

    from fanuc_cell import position, program
    from ucsio.readers.robot import read_robot
    frames_uf = {(1, k): uf if k == u else decoy_ut for k in (1, 2, 3)}
    frames_ut = {(1, k): ut if k == t else decoy_uf for k in (1, 2, 3)}
    frames_uf.update({(2, k): decoy_uf for k in (1, 2, 3)})
    frames_ut.update({(2, k): decoy_ut for k in (1, 2, 3)})
    pts = []
    for i, v in enumerate(points, 1):
        groups = [(1, u, t, v)] + ([(2, (u + 1) % 4, (t + 2) % 4, decoy_uf)] if with_gp2
                                    else [])
        pts.append(position(i, groups, decimals=3))
    with tempfile.TemporaryDirectory() as d:
        va, ls = os.path.join(d, "sysframe.va"), os.path.join(d, "MEAS.LS")
        with open(va, "w", newline="") as fh:
            fh.write(sysframe(frames_uf, frames_ut, groups=2, n_uf=3, n_ut=3))
        with open(ls, "w", newline="") as fh:
            fh.write(program("MEAS", pts))
        got = read_robot(ls, config=va)
    U = matrix(*uf) if u else np.eye(4)
    T = matrix(*ut) if t else np.eye(4)
    for rp, v in zip(got.poses, points):
        assert rp.problem is None, rp.problem
        want = U @ matrix(*v) @ np.linalg.inv(T)
        assert np.allclose(rp.flange[:3, 3], want[:3, 3], atol=1e-6)
        assert np.allclose(rp.flange[:3, :3], want[:3, :3], atol=1e-9)


def solution_file(path, x, y, z, w, p, r):
    """A SOLUTION.json whose frame is X Y Z W P R (a, b, c = r, p, w: scipy's)."""
    c, b, a = Rotation.from_matrix(matrix(x, y, z, w, p, r)[:3, :3]).as_euler("xyz",
                                                                               degrees=True)
    path.write_text(json.dumps({"frame": {"x": x, "y": y, "z": z, "a": a, "b": b, "c": c},
                                "accepted": True}))
    return path


@pytest.mark.parametrize("group, nl", [(1, "\r\n"), (2, "\n")])
def test_patch_in_place_then_frames_gives_the_solution(tmp_path, group, nl):
    mn = sets_from(16, ["(-1100.3)", "((.5))", "770", "0", "(-.04)", "((-90))"],
                   "UFRAME[3:FIX]") + sets_from(17, [1, 2, 3, 4, 5, 6], "UFRAME[4]")
    raw = program_text(mn, group).replace(b"\r\n", nl.encode())
    prog = tmp_path / "SETUF.LS"
    prog.write_bytes(raw)
    target = (1234.5678, -0.25, 99999.999, -179.9996, 89.9996, 0.0004)
    sol = solution_file(tmp_path / "s.json", *target)
    name = "UF3" if group == 1 else "UF3@2"
    res = run("patch", prog, "--frame", name, "--measured", sol, "--in-place")
    assert res.returncode == 0, res.stderr
    listed = {f["name"]: f for f in json.loads(run("frames", prog, "--json").stdout)["frames"]}
    f = listed[name]
    assert f["group"] == group and f["label"] == "FIX"
    assert_pose(Pose.from_wpr(f["x"], f["y"], f["z"], f["w"], f["p"], f["r"]), *target)
    other = "UF4" if group == 1 else "UF4@2"
    assert [listed[other][k] for k in ("x", "y", "z", "w", "p", "r")] == [1, 2, 3, 4, 5, 6]
    only_values_changed(raw, prog.read_bytes(), [4 + i for i in range(1, 7)])
    # the other group's name is no frame of this program: refused, nothing written
    after = prog.read_bytes()
    wrong = "UF3@2" if group == 1 else "UF3"
    res = run("patch", prog, "--frame", wrong, "--measured", sol, "--in-place")
    assert res.returncode == 2 and prog.read_bytes() == after
    assert res.stderr.decode().startswith(f"ucsio: {prog}"), res.stderr


def test_a_config_program_that_sets_a_frame_twice_differently_is_refused(tmp_path):
    """--config PROG.LS setting UF2 to two different values: which one the
    position was taught in is not known; ucsio took the first, silently."""
    from fanuc_cell import position, program
    from ucsio.readers.robot import read_robot
    cfg = tmp_path / "cfg.ls"
    cfg.write_bytes(program_text(sets_from(16, [100, 0, 0, 0, 0, 0], "UFRAME[2]")
                                 + sets_from(17, [200, 0, 0, 0, 0, 0], "UFRAME[2]")))
    meas = tmp_path / "meas.ls"
    meas.write_text(program("MEAS", [position(1, [(1, 2, 0, (1, 2, 3, 0, 0, 0))],
                                               decimals=3)]), newline="")
    (rp,) = read_robot(str(meas), config=str(cfg)).poses
    assert rp.flange is None and "twice with different values" in rp.problem.message, rp.problem
    assert rp.problem.line is not None and rp.problem.col is not None
    # set twice alike: one frame
    cfg.write_bytes(program_text(sets_from(16, [100, 0, 0, 0, 0, 0], "UFRAME[2]")
                                 + sets_from(17, [100, 0, 0, 0, 0, 0], "UFRAME[2]")))
    (rp,) = read_robot(str(meas), config=str(cfg)).poses
    assert rp.problem is None and np.allclose(rp.flange[:3, 3], (101, 2, 3))
