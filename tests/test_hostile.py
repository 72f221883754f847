"""Hostile but legal input (issue 12): a patch never damages a file, and bad
input is one clear line, exit 2, never a traceback.

The files under fixtures/hostile/ are the inputs that broke ucsio once."""
from __future__ import annotations

import random

import pytest

from conftest import FIXTURES
from oracles import only_numbers_changed
from ucsio.geometry import rotations as rot
from ucsio.cli import main
from ucsio.parsing.controller import load, parse
from ucsio.parsing.document import Document
from ucsio.errors import UcsioError
from ucsio.geometry.frames import Pose
from ucsio.review.patch import patch_frame

HOSTILE = FIXTURES / "hostile"
SIGNS = HOSTILE / "detached_signs.mod"
GLUED = HOSTILE / "glued_components.dat"


def close(a: Pose, b: Pose) -> bool:
    return (all(abs(u - v) <= 0.0005 + 1e-9 for u, v in zip(a.t, b.t))
            and rot.quat_angle(a.q, b.q) <= 5e-4)


def random_pose(rng: random.Random) -> Pose:
    """Values of both signs, some below 1 (KUKA's leading-dot form), some 0."""
    def coord():
        return rng.choice([0.0, rng.uniform(-1, 1), rng.uniform(-2000, 2000)])
    return Pose.from_abc(coord(), coord(), coord(), rng.uniform(-179, 179),
                         rng.uniform(-89, 89), rng.uniform(-179, 179))


def patched_and_checked(path, name: str, target: Pose) -> Document:
    cf = load(path)
    res = patch_frame(cf, name, target, measured=False, check_siblings=False)
    new = Document(res.new_bytes, path)
    again = parse(new, full=True)               # what `check` reads: every byte
    got = again.frame(name)
    assert close(got.pose, target), (name, got.pose, target)
    # nothing but the frame's numbers (and a detached sign it had to drop) moved
    assert only_numbers_changed(cf.document.text, [cf.frame(name)], new.text, [got])
    assert new.text.count("\n") == cf.document.text.count("\n")
    return new


# ------------------------------------------------------------------ point 0

@pytest.mark.parametrize("name", ["wobjSign", "tSign", "pSign"])
def test_detached_sign_keeps_comment_and_line_break(name):
    """`- ! note` newline `670`: the comment and the line break stay; the
    digits carry the new value, the sign goes only where it must."""
    rng = random.Random(name)
    comments = [ln.split("!", 1)[1] for ln in SIGNS.read_text().splitlines() if "!" in ln]
    for _ in range(25):
        new = patched_and_checked(SIGNS, name, random_pose(rng))
        assert [ln.split("!", 1)[1] for ln in new.text.splitlines() if "!" in ln] == comments


def test_detached_sign_spans_hold_digits_only():
    f = load(SIGNS).frame("wobjSign")
    assert (f.numbers["y"].text, f.numbers["y"].written, f.numbers["y"].value) == \
        ("670", "-670", -670.0)
    assert (f.numbers["z"].text, f.numbers["z"].written) == ("35.5", "-35.5")
    t = load(SIGNS).frame("tSign")
    assert (t.numbers["y"].text, t.numbers["y"].signs) == ("- 20", ())   # blanks only: one span
    assert t.numbers["x"].written == "+10"


def test_detached_sign_cli_diff_moves_no_line(tmp_path, capsys):
    f = tmp_path / "m.mod"
    f.write_bytes(SIGNS.read_bytes())
    assert main(["patch", str(f), "--frame", "wobjSign", "--set", "1200,700,-35.5,0,0,0",
                 "--in-place"]) == 0
    text = f.read_text()
    assert "[[1200, ! note\n700,-\n\t35.5]" in text
    assert main(["check", str(f)]) == 0


@pytest.mark.parametrize("name", ["fGlued", "fGlued2"])
def test_kuka_glued_component_reads_back_as_the_same_component(name):
    rng = random.Random(name)
    for _ in range(25):
        patched_and_checked(GLUED, name, random_pose(rng))


@pytest.mark.parametrize("x,written", [(0.5, "{X.500,"), (-0.5, "{X-0.500,"), (2.5, "{X 2.500,"),
                                       (0.0, "{X.00000,"), (-12.0, "{X-12.000,")])
def test_kuka_glued_component_written_forms(x, written):
    res = patch_frame(load(GLUED), "fGlued", Pose.from_abc(x, -0.5, 3, 0, 0, 90), measured=False)
    line = Document(res.new_bytes).text.splitlines()[3]
    assert line.startswith("DECL FRAME fGlued=" + written), line


# ------------------------------------------------------------------ point 1

def _shapes():
    import sys
    sys.path.insert(0, str(FIXTURES.parent / "benchmarks"))
    import bench_linear
    return bench_linear


@pytest.mark.parametrize("shape", ["rapid many PERS", "rapid blanks around decl",
                                   "rapid long word at EOF", "rapid unterminated decl, blanks",
                                   "rapid comment of numbers", "rapid dotted digits",
                                   "krl long word", "krl spaces lines",
                                   # issue 18: quadratic until fixed
                                   "rapid CONST long word", "rapid VAR long digits",
                                   "rapid routine of blanks", "krl many & lines",
                                   "krl no DEFDAT, many lines",
                                   # issue 27: Yaskawa's line readers
                                   "yaskawa job many positions", "yaskawa var many UNUSED",
                                   "yaskawa job blank lines first"])
def test_hostile_shapes_take_linear_time(shape):
    """Shapes that once took quadratic time (a 40 KB file ~20 s, 80 KB over
    90 s). At 200 KB a quadratic pass would take minutes; linear is well under
    a second (benchmarks/bench_linear.py measures the ratios)."""
    import time
    bench = _shapes()
    name, text = bench.SHAPES[shape](200_000)
    t0 = time.perf_counter()
    bench.run_commands(name, text)
    assert time.perf_counter() - t0 < 10.0


def test_error_messages_quote_a_bounded_piece_of_the_input():
    bench = _shapes()
    for shape in ("rapid dotted digits", "rapid digits then letter", "krl long word",
                  "krl digits dots", "rapid long word"):
        name, text = bench.SHAPES[shape](100_000)
        with pytest.raises(UcsioError) as exc:
            for full in (False, True):
                parse(Document(text.encode(), name), full=full)
        assert len(str(exc.value)) < 200 and "\n" not in str(exc.value)


# ------------------------------------------------------------------ points 2 and 3

BAD = [  # fixture, line:col, message part
    ("deep_wobj.mod", "3:355", "nested more than 100 levels deep"),
    ("deep_signs.mod", "3:257", "nested more than 100 levels deep"),
    ("deep_frame.dat", "3:317", "nested more than 100 levels deep"),
    ("deep_load.dat", "4:324", "nested more than 100 levels deep"),
    ("huge_dim.mod", "3:19", "array dimension 1E400 is not a size"),
    ("huge_radix.mod", "4:37", "out of range for a RAPID num"),
    ("huge_max.dat", "3:14", "1E400 is out of range for a KRL INT"),
    ("huge_index.dat", "4:11", "out of range for a KRL INT"),
    ("huge_machine.dat", "5:38", "1E400 is out of range for a KRL INT"),
    ("huge_real.dat", "3:17", "1E400 is out of range for a KRL REAL"),
]


@pytest.mark.parametrize("name,where,message", BAD, ids=[b[0] for b in BAD])
@pytest.mark.parametrize("command", ["frames", "check", "patch"])
def test_deep_and_huge_input_is_one_clear_line(capsys, name, where, message, command):
    path = HOSTILE / name
    before = path.read_bytes()
    args = [command, str(path)]
    if command == "patch":
        args += ["--frame", "w" if name.endswith(".mod") else "BASE_DATA[1]", "--set",
                 "1,2,3,0,0,0", "--in-place"]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err == f"ucsio: {path}:{where}: " + err.split(f"{where}: ", 1)[1]
    assert message in err and err.count("\n") == 1 and len(err) < 200
    assert path.read_bytes() == before


def test_deep_nesting_outside_frame_data_is_accepted_by_both_paths():
    path = HOSTILE / "deep_record.mod"
    fast, full = load(path), load(path, full=True)
    assert [f.name for f in fast.frames] == [f.name for f in full.frames] == ["w", "w.oframe"]
    assert main(["check", str(path)]) == 0


def test_huge_number_outside_frame_data_is_kept_as_written():
    text = (HOSTILE / "huge_radix.mod").read_text()
    text = text[:text.index("  PERS wobjdata")] + "ENDMODULE\n"     # without the bad frame
    cf = parse(Document(text.encode(), "big.mod"), full=True)
    big = [d for d in cf.extra["declarations"] if d.name == "big"][0]
    assert big.value.value == float("inf") and big.value.text.startswith("0d999")


def test_unreadable_sibling_module_is_a_warning(tmp_path, capsys):
    for p in (HOSTILE / "siblings").iterdir():
        (tmp_path / p.name).write_bytes(p.read_bytes())
    rc = main(["patch", str(tmp_path / "Cell.mod"), "--frame", "wShared", "--set", "1,2,4,0,0,0"])
    err = capsys.readouterr().err
    assert rc == 0 and "warning: could not read sibling module Broken.mod" in err
    assert "nested more than 100 levels deep" in err and "Traceback" not in err


# ------------------------------------------------------------------ point 4

@pytest.mark.parametrize("head", ["MODULE M ! comment\n", "MODULE M! c\n", "MODULE M\t!c\r\n",
                                  "MODULE M (SYSMODULE) ! c\n", "MODULE ! c\n M\n"])
def test_comment_after_module_name_accepted_by_every_command(head, tmp_path):
    text = head + '  PERS wobjdata w:=[FALSE,TRUE,"",[[1,2,3],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n' \
                  "  ! PERS wobjdata x := [\n  PERS num n:=1;\nENDMODULE\n"
    f = tmp_path / "m.mod"
    f.write_text(text)
    assert main(["check", str(f)]) == 0
    assert main(["frames", str(f)]) == 0
    assert main(["patch", str(f), "--frame", "w", "--set", "1,2,4,0,0,0", "--in-place"]) == 0
    assert load(f).frame("w").pose.t == (1, 2, 4)
