"""One rule for where a line ends, in every language (issue 18, point 3):
LF, CRLF and ABB's CR CR LF end a line, and so does a bare CR. Files with
mixed endings (a conversion script's program .dat: 68 lines end in CR, 24 in
LF) read, list, check and patch with the right line numbers; a lone CR
inside a comment ends the comment, in KRL as in RAPID."""
from __future__ import annotations

import io
import random
from contextlib import redirect_stderr, redirect_stdout

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ucsio.cli import main
from ucsio.errors import UcsioError
from ucsio.parsing import controller
from ucsio.vendors.kuka import krl
from ucsio.vendors.abb import rapid
from ucsio.parsing.document import Document, line_starts, lf_lines, text_lines

ENDINGS = ["\n", "\r\n", "\r", "\r\r\n"]


def reference_starts(text: str) -> list[int]:
    """The rule spelt out character by character."""
    starts = [0]
    i = 0
    while i < len(text):
        if text[i] == "\n":
            starts.append(i + 1)
        elif text[i] == "\r":
            j = i
            while j < len(text) and text[j] == "\r":
                j += 1
            if j < len(text) and text[j] == "\n":      # CR ... CR LF: one ending
                starts.append(j + 1)
                i = j
            else:                                      # a bare CR: one ending
                starts.append(i + 1)
        i += 1
    return starts


@settings(max_examples=500)
@given(st.text(alphabet="ab\r\n", max_size=40))
def test_line_starts_follow_the_rule(text):
    assert line_starts(text) == reference_starts(text)
    assert Document(text.encode()).line_starts == reference_starts(text)
    lines = text_lines(text)
    assert all("\r" not in ln and "\n" not in ln for ln in lines)
    assert "".join(lines) == text.replace("\r", "").replace("\n", "")
    bare = lf_lines(text)
    assert len(bare) == len(text) and line_starts(bare) == line_starts(text)


def test_line_starts_is_linear_on_runs_of_cr():
    # 200,000 bare CRs: each a line; a quadratic rule would not finish
    text = "x" + "\r" * 200_000 + "y\r\r\r\n"
    starts = line_starts(text)
    assert len(starts) == 1 + 200_000 + 1 and starts[-1] == len(text)


def mix(lines: list[str], rng: random.Random, endings=ENDINGS) -> str:
    return "".join(line + rng.choice(endings) for line in lines)


KRL_PROGRAM = [
    "&ACCESS RVP", "&REL 1", "DEFDAT  SEAM",
    ";FOLD EXTERNAL DECLARATIONS;%{PE}%MKUKATPBASIS,%CEXT,%VCOMMON,%P",
    ";ENDFOLD (EXTERNAL DECLARATIONS)",
] + [line for k in range(1, 31) for line in (
    f"DECL E6POS XP{k}={{X {100.0 + k},Y {-20.5 * k},Z {300.25},A {k}.0,B -2.0,C 1.5,S 6,T 27,"
    "E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}",
    f"DECL FDAT FP{k}={{TOOL_NO 1,BASE_NO 3,IPO_FRAME #BASE,POINT2[] \" \"}} ; point {k}",
    f"DECL PDAT PPDAT{k}={{VEL 100.0,ACC 100.0,APO_DIST 100.0}}",
)] + ["ENDDAT"]


def listing(doc: Document):
    return [(p.name, p.line, p.col, p.pose.as_dict() if p.pose else None)
            for p in krl.positions(doc)]


@pytest.mark.parametrize("seed", range(6))
def test_a_program_dat_with_mixed_endings_reads_as_with_lf(seed):
    rng = random.Random(seed)
    lf = Document(mix(KRL_PROGRAM, rng, ["\n"]).encode(), "seam.dat")
    mixed_text = mix(KRL_PROGRAM, rng)
    mixed = Document(mixed_text.encode(), "seam.dat")
    assert len(mixed.line_starts) == len(KRL_PROGRAM) + 1
    assert listing(mixed) == listing(lf)
    assert krl.parse(mixed, full=True).lints == krl.parse(lf, full=True).lints
    assert mixed.to_bytes() == mixed_text.encode()


def test_the_conversion_script_file_of_the_issue(tmp_path):
    """68 lines end in a bare CR, 24 in LF: check passes, frames and positions
    carry the lines a text editor shows."""
    lines = KRL_PROGRAM[:92]
    lines[-1] = "ENDDAT"
    endings = ["\r"] * 68 + ["\n"] * 24
    random.Random(1).shuffle(endings)
    path = tmp_path / "seam.dat"
    path.write_bytes("".join(ln + e for ln, e in zip(lines, endings)).encode())
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        assert main(["check", str(path)]) == 0, err.getvalue()
    doc = Document.read(path)
    for p in krl.positions(doc):
        k = int(p.name[2:])
        assert lines[p.line - 1].startswith(f"DECL E6POS XP{k}=")


def test_an_error_in_a_mixed_file_names_its_line():
    rng = random.Random(7)
    lines = list(KRL_PROGRAM)
    lines[40] = "DECL E6POS XBAD={X 1.0,Y 2.0,Z 3.0,A 4.0,B 5.0,C 6.0"     # no closing brace
    doc = Document(mix(lines, rng).encode(), "bad.dat")
    with pytest.raises(UcsioError) as e:
        krl.parse(doc, full=True)
    assert e.value.line == 41, str(e.value)


def test_a_lone_cr_ends_a_krl_comment():
    """An LF file where a comment is followed by a bare CR and a frame: the
    frame is the next line's, listed and patchable, not swallowed."""
    text = ("DEFDAT  $CONFIG\nDECL FRAME BASE_DATA[2]\n; note\rBASE_DATA[1]={X 1.0,Y 2.0,Z 3.0,"
            "A 0.0,B 0.0,C 0.0}\nBASE_DATA[2]={X 4.0,Y 5.0,Z 6.0,A 0.0,B 0.0,C 0.0}\nENDDAT\n")
    doc = Document(text.encode(), "$config.dat")
    for cf in (krl.parse(doc), krl.parse(doc, full=True), krl.parse_whole(doc)):
        fr = cf.frame("BASE_DATA[1]")
        assert fr.line == 4 and fr.pose.as_dict()["x"] == 1.0
        assert cf.frame("BASE_DATA[2]").line == 5


def test_a_lone_cr_ends_a_rapid_comment():
    text = ("MODULE m\n  ! note\r  PERS wobjdata w1:=[FALSE,TRUE,\"\",[[1,2,3],[1,0,0,0]],"
            "[[0,0,0],[1,0,0,0]]];\n  ! a\r\r  PERS tooldata t1:=[TRUE,[[0,0,100],[1,0,0,0]],"
            "[1,[0,0,1],[1,0,0,0],0,0,0]];\nENDMODULE\n")
    doc = Document(text.encode(), "m.mod")
    for cf in (rapid.parse(doc), rapid.parse(doc, full=True), rapid.parse_whole(doc)):
        assert cf.frame("w1").line == 3
        assert cf.frame("t1").line == 6


@pytest.mark.parametrize("seed", range(4))
def test_patch_of_a_mixed_file_changes_only_the_numbers(tmp_path, seed):
    rng = random.Random(seed)
    lines = ["DEFDAT  $CONFIG", "; bases", "DECL FRAME BASE_DATA[3]",
             "BASE_DATA[1]={X 0.0,Y 0.0,Z 0.0,A 0.0,B 0.0,C 0.0}",
             "BASE_DATA[3]={X 1500.00,Y -250.000,Z 600.000,A 30.0000,B -2.50000,C 1.20000}",
             "DECL CHAR BASE_NAME[3,24]", 'BASE_NAME[3,]="fixture"', "ENDDAT"]
    raw = mix(lines, rng).encode()
    path = tmp_path / "$config.dat"
    path.write_bytes(raw)
    cf = controller.load(path)
    from ucsio.geometry.frames import Pose
    from ucsio.review.patch import patch_frame

    result = patch_frame(cf, "fixture", Pose.from_abc(1501.5, -249.0, 601.0, 30.5, -2.0, 1.0))
    new = result.new_bytes
    assert new.replace(b"\r", b"").count(b"\n") == raw.replace(b"\r", b"").count(b"\n")
    old_lines, new_lines = text_lines(raw.decode()), text_lines(new.decode())
    changed = [i for i, (a, b) in enumerate(zip(old_lines, new_lines)) if a != b]
    assert changed == [4]
    # every line ending is where it was
    assert [raw[s - 1:s] for s in line_starts(raw.decode())[1:]] == \
        [new[s - 1:s] for s in line_starts(new.decode())[1:]]
    back = krl.parse(Document(new, path)).frame("fixture")
    assert back.pose.as_dict()["x"] == pytest.approx(1501.5) and back.line == 5


@pytest.mark.parametrize("ending", ENDINGS)
def test_measurement_files_count_lines_by_the_same_rule(tmp_path, ending):
    """A bad number on line 3 of a measurement CSV and of a tracker export is
    named on line 3, whatever ends the lines (str.splitlines counted CR CR LF
    as two)."""
    from ucsio.readers.measurement import read_measurement
    from ucsio.readers.laser import read_laser

    rows = ["point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c",
            "P1,0,0,0,100,0,0,0,0,0", "P2,1,x,0,101,0,0,0,0,0"]
    path = tmp_path / "m.csv"
    path.write_bytes(ending.join(rows).encode() + ending.encode())
    with pytest.raises(UcsioError) as e:
        read_measurement(path)
    assert e.value.line == 3, str(e.value)
    table = tmp_path / "t.txt"
    table.write_bytes(ending.join(["P1 0 0 0", "P2 1 0 0", "P3 1 x 0"]).encode())
    with pytest.raises(UcsioError) as e:
        read_laser(table)
    assert e.value.line == 3, str(e.value)
