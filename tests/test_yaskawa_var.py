"""Yaskawa's VAR.DAT (issue 27 point 1): the global variables, read line by
line and byte-exact. Its ///P rows (P000, P001, ... in order) are read with
spans; every other section is kept as it is. A P variable is a position, not
a frame: `frames` lists none and says what the file holds; `check` reads it.
Fixtures are written here in the corpus's style (CRLF, as controllers write).
"""
from __future__ import annotations

import json

import pytest

from conftest import corpus_file
from ucsio.cli import main
from ucsio.parsing.controller import parse
from ucsio.parsing.document import Document
from ucsio.vendors.yaskawa import var

KOMATSU_VAR = "lukelalondePZ__Komatsu-Press-Demo__VAR.DAT"
RECTAN = '"RECTAN"0,0,4,000000000000000000000000,0,16,{}'
PULSE = '"PULSE"0,0,3,000000000000000000000000,0,0,182486,-16527,-36319,-44059,18956,22828,0,0'


def var_dat(*p_rows: str, tail: str = "///BP\n///EX\n") -> bytes:
    """A VAR.DAT as a YRC1000 writes it: header items, the other sections, ///P."""
    text = ("//VAR\n///PFNUM 6,0,0,0\n///SHARE 250,250,250,250,250,250,0,0\n///B\n"
            "1,0,1,0,0,0,0,0,0,0\n///I\n5,0,35,5,0,0,0,0,0,0\n///S\n\n\n///P\n"
            + "".join(r + "\n" for r in p_rows) + tail)
    return text.replace("\n", "\r\n").encode()


def cli(capsys, *args):
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


def read(raw: bytes, name: str = "VAR.DAT"):
    return parse(Document(raw, name))


def test_the_corpus_file_reads_its_p_rows_in_order_with_spans():
    path = corpus_file("yaskawa", KOMATSU_VAR)
    raw = path.read_bytes()
    cf = read(raw, str(path))
    assert cf.vendor == "yaskawa" and cf.frames == [] and cf.document.to_bytes() == raw
    rows = cf.extra["p_variables"]
    assert len(rows) == 250 and [r.number for r in rows] == list(range(250))
    # P000..P032 are the cell's (the jobs beside it name them), the rest "UNUSED"
    assert var.in_use(cf) == list(range(33)) and var.p_count(cf) == 250
    p3, p0 = rows[3], rows[0]
    assert (p3.kind, p3.tool, p3.coordinate) == ("RECTAN", 3, 16)
    assert [n.value for n in p3.values] == [-863.111, 979.613, 492.219, 178.9297, -0.1487,
                                            123.0482]
    assert p0.kind == "PULSE" and [n.value for n in p0.values] == [2, -76037, -66182, 0, 4682, 0]
    for row in rows:
        for n in row.values:
            assert cf.document.slice(n.span) == n.text
    assert cf.document.line_of(cf.document.line_starts[p3.line - 1]) == p3.line
    assert cf.document.text.splitlines()[p3.line - 1].startswith('"RECTAN"0,0,3,')


def test_check_and_frames_on_the_corpus_file(capsys):
    path = corpus_file("yaskawa", KOMATSU_VAR)
    code, out, err = cli(capsys, "check", path, "--json")
    doc = json.loads(out)
    assert code == 0, err
    assert doc["files"][0]["round_trip"] is True and doc["files"][0]["frames"] == 0
    assert doc["files"][0]["kind"] == "global variables" and doc["files"][0]["lints"] == []
    code, out, err = cli(capsys, "frames", path)
    assert code == 0, err
    assert "no frames" in out
    assert "250 position variables (P), 33 in use; positions, not frames" in out
    code, out, err = cli(capsys, "frames", path, "--json")
    assert code == 0 and json.loads(out)["frames"] == []


def test_crlf_and_every_other_section_round_trip_byte_for_byte(tmp_path, capsys):
    raw = var_dat(RECTAN.format("1.000,2.000,3.000,0.0000,0.0000,90.0000,0.0000,0.0000"),
                  '"UNUSED"', PULSE, '"UNUSED"', tail="///BP\n\"UNUSED\"\n///EX\n\"UNUSED\"\n")
    cf = read(raw)
    assert cf.document.to_bytes() == raw
    assert [r.kind for r in cf.extra["p_variables"]] == ["RECTAN", "UNUSED", "PULSE", "UNUSED"]
    assert var.in_use(cf) == [0, 2]          # ///BP's and ///EX's rows are not P variables
    path = tmp_path / "VAR.DAT"
    path.write_bytes(raw)
    code, out, err = cli(capsys, "check", path)
    assert code == 0 and "round trip ok" in out, out + err
    assert path.read_bytes() == raw


def test_a_row_ucsio_does_not_know_is_kept_and_counted_in_use():
    raw = var_dat('"UNUSED"', '"USER"0,0,0,1,2', "garbage", '"UNUSED"')
    cf = read(raw)
    assert var.in_use(cf) == [1, 2]
    assert [l.code for l in cf.lints] == ["unknown-line", "unknown-line"]
    assert all(l.severity == "info" for l in cf.lints)
    assert [l.line for l in cf.lints] == [13, 14]


@pytest.mark.parametrize("row, col, says", [
    (RECTAN.format("1.000,2.0x0,3.000,0.0000,0.0000,0.0000,0.0000,0.0000"), 51, "not a number"),
    (RECTAN.format("1.000,2.000,3.000"), 62, "6 flags and at least 6 numbers"),
    (RECTAN.format("1.000,,3.000,0.0000,0.0000,0.0000,0.0000,0.0000"), 51, "number is missing"),
    ('"RECTAN"0,0,T,000000000000000000000000,0,16,1,2,3,4,5,6,0,0', 13, "tool is an integer"),
    (RECTAN.format("1e9,0,0,0,0,0,0,0"), 45, "not a number"),
    (RECTAN.format("9" * 400 + ",0,0,0,0,0,0,0"), 45, "out of range"),
])
def test_a_broken_p_row_is_one_error_at_its_field(tmp_path, capsys, row, col, says):
    path = tmp_path / "VAR.DAT"
    raw = var_dat('"UNUSED"', row)
    path.write_bytes(raw)
    code, out, err = cli(capsys, "check", path)
    assert code == 2
    assert f"{path}:13:{col}:" in err and says in err and "P001" in err, err
    assert path.read_bytes() == raw


def test_a_dat_that_is_not_a_var_dat_stays_krl_and_var_dat_is_claimed_by_its_first_line():
    cf = read(var_dat('"UNUSED"'), "anything.dat")
    assert cf.vendor == "yaskawa" and var.in_use(cf) == []
    assert read(b"\xef\xbb\xbf//VAR\r\n///P\r\n\"UNUSED\"\r\n").vendor == "yaskawa"
    assert read(b"&ACCESS RVP\r\nDEFDAT D\r\nENDDAT\r\n", "x.dat").vendor == "kuka"
