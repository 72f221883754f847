"""Hostile input that ucsio reads (issue 24, points 9, 15 and 17): one line
numbering for every line end, one magnitude limit for every point file, and
no text that is not what it seems (UTF-16, a NUL inside a name)."""
from __future__ import annotations

import json

import pytest

from ucsio.cli import main
from ucsio.parsing import krl
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
