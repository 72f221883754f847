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
