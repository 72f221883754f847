"""Integers of thousands of digits in every reader (issue 24 point 11).

Python refuses to convert more than 4,300 digits (ValueError) and a
million digits cost seconds; every integer a reader takes from a file goes
through ``parsing.document.small_int`` instead. This test does not look
for int() calls: it feeds huge integers to every reader. From each file
(ABB, KUKA and FANUC, fixtures and corpus) it makes one variant per place
an integer stands (the text before it, digits aside, says which place: an
index, a group, ``UF :``, ``Joint 3:``), with that integer made 5,000
digits, and reads it as ``check``, ``frames`` and ``solve --robot`` do. A
variant reads, or is refused with one error naming its line; never an
internal error.
"""
from __future__ import annotations

import re
import shutil

import pytest

from conftest import CORPUS, FIXTURES
from ucsio.cli import main
from ucsio.errors import UcsioError
from ucsio.parsing import controller
from ucsio.parsing.document import Document, small_int
from ucsio.readers.laser import read_laser
from ucsio.readers.robot import read_robot

HUGE = "9" * 5000
# an integer: not part of a decimal number or an exponent, not a hex literal's
_INT = re.compile(r"(?<![\w.+-])[0-9]+(?![\w.])|(?<=[\[,:# ])[0-9]+(?=[\],:; ])")
# A TP literal value (PR[16,4]=180, =(90)) is a REAL: its range is checked as
# one (issue 24 point 10), not as an integer's
_TP_VALUE = re.compile(r"PR\[[^\]\n]*\]=\(*-?\Z")


def _corpus(vendor: str, *parts: str) -> list:
    folder = CORPUS / vendor
    if not folder.is_dir():
        return []
    return sorted(p for p in folder.iterdir() if any(part in p.name for part in parts))


FILES = [
    *sorted((FIXTURES / "fanuc").glob("*.va")), *sorted((FIXTURES / "fanuc").glob("*.ls")),
    *_corpus("fanuc", "curpos.dg", "frame.dg", "td_gun1.ls", "move_safe", "surface.ls",
             "UB10200_RBT01__posreg", "UB10200_RBT01__sysframe", "kjltvr411670r01__SYSFRAME"),
    *sorted((FIXTURES / "kuka").glob("*.dat")), *_corpus("kuka", "caja_g_m2.dat"),
    *sorted(p for p in (FIXTURES / "abb").glob("*.mod") if p.name != "encrypted.mod"),
    *sorted((FIXTURES / "measurements").glob("*.csv")),
]


def variants(text: str, suffix: str):
    """(variant text, where) for each place an integer stands in ``text``:
    the first integer with each context (the 16 characters before it, the
    digits in them made #)."""
    seen = set()
    for m in _INT.finditer(text):
        line_start = text.rfind("\n", 0, m.start()) + 1
        before = text[line_start:m.start()]
        if suffix == ".ls" and _TP_VALUE.search(before.replace(" ", "")):
            continue
        key = re.sub(r"[0-9]+", "#", before[-16:])
        if key in seen:
            continue
        seen.add(key)
        yield text[:m.start()] + HUGE + text[m.end():], before.strip()[-40:]


def _readers(suffix: str):
    """How every command that reads such a file reads it: (reader, whether
    its refusal names a line)."""
    if suffix == ".csv":
        return [(read_laser, False)]
    return [(lambda p: controller.parse(Document.read(p), full=True), True),    # check
            (lambda p: controller.parse(Document.read(p)), True),   # frames, diff, patch
            (read_robot, False)]                                    # solve --robot


@pytest.mark.parametrize("source", FILES, ids=lambda p: p.name[-48:])
def test_every_integer_made_huge_reads_or_is_refused_naming_its_line(tmp_path, source):
    text = source.read_bytes().decode("latin-1")
    path = tmp_path / source.name
    suffix = source.suffix.lower()
    bugs = []
    count = 0
    for variant, where in variants(text, suffix):
        count += 1
        path.write_bytes(variant.encode("latin-1"))
        for read, names_line in _readers(suffix):
            try:
                read(path)
            except UcsioError as exc:
                assert exc.line is not None or not names_line, (where, exc)
            except Exception as exc:        # an internal error: the place, and what
                bugs.append(f"{where!r}: {type(exc).__name__}: {str(exc)[:80]}")
    assert count, "no integer in the file"
    assert bugs == []


def test_a_huge_index_in_framevar_beside_leaves_the_sysframe_readable(tmp_path, capsys):
    """FRAMEVAR.VA labels the frames of the sysframe.va beside it: a huge
    index there costs that comment, not the frames."""
    shutil.copy(FIXTURES / "fanuc" / "sysframe_comment.va", tmp_path / "SYSFRAME.VA")
    (tmp_path / "FRAMEVAR.VA").write_bytes(
        b"[TPFDEF]SETUP_DATA  Storage: CMOS  Access: RW  : ARRAY[8,3,61] OF FRMSET_T\r\n"
        b"         Field: SETUP_DATA[1,3," + HUGE.encode() + b"].$COMMENT Access: RW: "
        b"STRING[29] = 'HUGE'\r\n"
        b"         Field: SETUP_DATA[" + HUGE.encode() + b",3,3].$COMMENT Access: RW: "
        b"STRING[29] = 'HUGE TOO'\r\n"
        b"         Field: SETUP_DATA[1,3,3].$COMMENT Access: RW: STRING[29] = 'THIRD'\r\n")
    assert main(["frames", str(tmp_path / "SYSFRAME.VA"), "--all"]) == 0
    out = capsys.readouterr().out
    assert "THIRD" in out and "HUGE" not in out


@pytest.mark.parametrize("argv", [["program", "--frame", "UF" + HUGE],
                                  ["program", "--frame", "UT1@" + HUGE]])
def test_a_huge_frame_number_on_the_command_line(tmp_path, capsys, argv):
    sol = tmp_path / "SOLUTION.json"
    sol.write_text('{"frame": {"x": 1, "y": 2, "z": 3, "a": 0, "b": 0, "c": 0}}')
    assert main([argv[0], str(sol), *argv[1:]]) == 2
    err = capsys.readouterr().err
    assert "frame number 1...999" in err and "digits)" in err and len(err) < 200


def test_small_int_judges_the_length_before_converting():
    assert small_int("  17 ") == 17 and small_int("-3") == -3 and small_int("0007") == 7
    assert small_int(str(2 ** 31 - 1)) == 2 ** 31 - 1
    assert small_int(str(2 ** 31)) is None and small_int("0" * 40 + "1") == 1
    assert small_int(HUGE) is None and small_int("9" * 10 ** 6) is None
