"""Hostile input that ucsio reads (issue 24, points 9, 15 and 17): one line
numbering for every line end, one magnitude limit for every point file, and
no text that is not what it seems (UTF-16, a NUL inside a name)."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from ucsio.cli import main
from ucsio.vendors.kuka import krl
from ucsio.parsing.controller import parse
from ucsio.parsing.document import Document

# ------------------------------------------------------------------ point 9

KRL = ("&ACCESS RVP{0}&PARAM EDITMASK = *{1}DEFDAT  $CONFIG{0}DECL FRAME BASE_DATA[2]{0}"
       "BASE_DATA[1]={{X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0}}{0}"
       "DECL E6POS XP1={{X 1,Y 2,Z 3,A 0,B 0,C 0,S 2,T 2,E1 0,E2 0,E3 0,E4 0,E5 0,E6 0}}{0}"
       "BASE_DATA[3]={{X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0}}{0}{2}ENDDAT{0}")


def _lines_read(tmp_path, capsys, text: str) -> dict:
    path = tmp_path / "$config.dat"
    path.write_bytes(text.encode())
    out = {}
    main(["frames", str(path), "--json"])
    out["frames"] = [f["line"] for f in json.loads(capsys.readouterr().out)["frames"]]
    main(["check", str(path), "--json"])
    out["lints"] = [(l["line"], l["code"]) for f in json.loads(capsys.readouterr().out)["files"]
                    for l in f["lints"]]
    out["positions"] = [p.line for full in (False, True)
                        for p in krl.positions(Document(text.encode(), str(path)), full)]
    return out


@pytest.mark.parametrize("eol", ["\n", "\r\n", "\r"])
def test_a_header_ended_by_a_bare_cr_counts_as_a_line(tmp_path, capsys, eol):
    """`&PARAM EDITMASK = *` CR `DEFDAT`: the frames, lints, positions and
    errors after it are on the lines an editor shows, as in the same file
    with that header ended like the others."""
    plain = _lines_read(tmp_path, capsys, KRL.format(eol, eol, ""))
    bare = _lines_read(tmp_path, capsys, KRL.format(eol, "\r", ""))
    assert bare == plain
    assert plain["frames"] == [5, 7] and plain["positions"] == [6, 6]
    assert (7, "index-out-of-range") in plain["lints"]
    # and an error: the line after BASE_DATA[3]
    path = tmp_path / "bad.dat"
    path.write_bytes(KRL.format(eol, "\r", "BASE_DATA[2]={X 1,Y 2 Z 3}" + eol).encode())
    assert main(["frames", str(path)]) == 2
    assert f"{path}:8:23: syntax error" in capsys.readouterr().err
    with pytest.raises(Exception, match=r":8:23:"):
        parse(Document.read(path), full=True)


# ------------------------------------------------------------------ point 15

ROWS = [("P1", "0", "0", "0"), ("P2", "100", "0", "0"), ("P3", "0", "100", "0"),
        ("P4", "{big}", "0", "5"), ("P5", "100", "100", "30"), ("P6", "50", "50", "90")]


def _tracker_files(tmp_path, big: str) -> dict:
    rows = [tuple(v.format(big=big) for v in r) for r in ROWS]
    files = {
        "table.txt": "".join(" ".join(r) + "\n" for r in rows),
        "table.csv": "name;x;y;z\n" + "".join(";".join(r) + "\n" for r in rows),
        "export.txt": "// SpatialAnalyzer export\n" + "".join(
            f"UCS,G1,{','.join(r)}\n" for r in rows),
    }
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    return {name: tmp_path / name for name in files}


@pytest.mark.parametrize("big", ["1e100", "-1e155", "1e300", "1000000001"])
def test_plan_refuses_huge_coordinates_as_solve_does(tmp_path, capsys, big):
    """One line naming the value's line and column, exit 2, no numpy
    warning: the readers hold every tracker number to the fit's limit."""
    import warnings
    kuka = str(tmp_path.parent / "x")  # never read: the laser file fails first
    for name, path in _tracker_files(tmp_path, big).items():
        line = 5 if name != "table.txt" else 4
        for args in (["plan", str(path)],
                     ["solve", "--laser", str(path), "--robot", kuka, "--tcp", "0,0,0"]):
            with warnings.catch_warnings():
                warnings.simplefilter("error")
                assert main(args) == 2, (name, args)
            err = capsys.readouterr().err
            assert err.count("\n") == 1, err
            assert f"{path}:{line}:" in err and f"{big} is too large for a fit" in err, err


# ------------------------------------------------------------------ point 17

MEAS = Path(__file__).resolve().parents[1] / "fixtures" / "measurements" / "kuka_base3.csv"
TCP = "--tcp=-20.67,89.73,33.44"


def _solved(capsys, path) -> dict:
    assert main(["solve", str(path), TCP, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("codec", ["utf-16", "utf-16-be"])
def test_a_utf16_measurement_with_its_mark_reads_as_utf8_does(tmp_path, capsys, codec):
    text = MEAS.read_text()
    f = tmp_path / "m.csv"
    f.write_bytes(("\ufeff" + text).encode(codec) if codec.endswith("be") else text.encode(codec))
    assert f.read_bytes()[:2] in (b"\xff\xfe", b"\xfe\xff")
    assert _solved(capsys, f)["frame"] == _solved(capsys, MEAS)["frame"]


def test_a_utf16_file_without_its_mark_says_so(tmp_path, capsys):
    f = tmp_path / "m.csv"
    f.write_bytes(MEAS.read_text().encode("utf-16-le"))
    for args in (["solve", str(f), TCP], ["plan", str(f)]):
        assert main(args) == 2
        err = capsys.readouterr().err
        assert err == f"ucsio: {f}: UTF-16 text without a byte-order mark: save it as UTF-8\n"


def test_a_nul_inside_a_point_name_is_refused_where_it_stands(tmp_path, capsys):
    """P3 and P\\x003 would be two names: the point would silently lose
    its pair. Every table reader refuses it at its line and column."""
    lines = MEAS.read_text().splitlines(keepends=True)
    row = next(i for i, ln in enumerate(lines) if ln.startswith("P3"))
    lines[row] = "P\x00" + lines[row][1:]
    f = tmp_path / "m.csv"
    f.write_text("".join(lines))
    table = tmp_path / "t.txt"
    table.write_text("P1 0 0 0\nP\x002 1 0 0\n")
    at = tmp_path / "at.csv"
    at.write_text("name,x,y,z\nW1,0,0,0\nW\x002,1,2,3\n")
    pairs = tmp_path / "map.csv"
    pairs.write_text("laser,robot\nP1,XP1\nP\x002,XP2\n")
    cases = [(["solve", str(f), TCP], f, row + 1),
             (["plan", str(f)], f, row + 1),
             (["plan", str(table)], table, 2),
             (["solve", "--laser", str(table), "--robot", str(f), TCP], table, 2),
             (["plan", str(MEAS), "--at", str(at)], at, 3),
             (["solve", "--laser", str(MEAS), "--robot", str(MEAS), "--map", str(pairs), TCP],
              pairs, 3)]
    for args, where, line in cases:
        assert main(args) == 2, args
        err = capsys.readouterr().err
        assert err.startswith(f"ucsio: {where}:{line}:2: control character 0x00"), (args, err)
        assert err.count("\n") == 1


def test_a_utf16_controller_file_says_so(tmp_path, capsys):
    f = tmp_path / "$config.dat"
    f.write_bytes(KRL.format("\r\n", "\r\n", "").encode("utf-16"))
    assert main(["frames", str(f)]) == 2
    assert capsys.readouterr().err == (f"ucsio: {f}: UTF-16 text: ucsio reads controller files "
                                       "as UTF-8 or Windows-1252; save it as UTF-8\n")


def test_a_gzip_bomb_is_refused_before_it_fills_the_memory(tmp_path, capsys):
    """A small .installation whose stream unpacks to more than 64 MiB (here
    80 MiB of blanks in 80 KB) is one clear error, never read into memory
    whole; check, frames and patch alike, nothing written."""
    import gzip

    from ucsio.cli import main
    from ucsio.parsing.document import GZIP_MAX
    body = b'<?xml version="1.0"?><Installation>' + b" " * (GZIP_MAX + (16 << 20)) + \
        b"</Installation>"
    bomb = tmp_path / "bomb.installation"
    bomb.write_bytes(gzip.compress(body, compresslevel=1))
    before = bomb.read_bytes()
    for args in (["check", bomb], ["frames", bomb],
                 ["patch", bomb, "--frame", "P", "--set", "0,0,0,0,0,0", "--in-place"]):
        assert main([str(a) for a in args]) == 2
        err = capsys.readouterr().err
        assert "unpacks to more than 64 MiB" in err and "bomb.installation:1:1" in err
    assert bomb.read_bytes() == before and sorted(tmp_path.iterdir()) == [bomb]
