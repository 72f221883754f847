"""FANUC variable listings as a real backup writes them (issue 24 points 4
and 19): strings that run over a line end or stand on the line after their
``= `` (a real SYSTEM.VA has both), and the fast path held equal to the tree
of every byte on the corpus and on generated and mutated listings."""
from __future__ import annotations

import shutil

from conftest import FIXTURES
from ucsio.cli import main
from ucsio.parsing import controller, va
from ucsio.parsing.document import Document

FANUC = FIXTURES / "fanuc"


def snapshot(cf):
    return ([(f.as_dict(), {k: (n.span.start, n.span.end, n.text) for k, n in f.numbers.items()})
             for f in cf.frames], cf.lints, cf.extra.get("records"))


def test_strings_over_a_line_end_and_on_the_next_line_read_and_round_trip(capsys):
    path = FANUC / "system_strings.va"
    doc = Document.read(path)
    cf = controller.parse(doc, full=True)
    assert cf.lints == [] and cf.extra["records"][-1] == "$PI"
    assert doc.to_bytes() == path.read_bytes()
    assert snapshot(controller.parse(Document.read(path))) == snapshot(cf) \
        == snapshot(va.parse_whole(Document.read(path)))
    recs = {r.name: r for r in va.records(va._parse(doc, va._lines(doc)), doc)}
    assert recs["$MOTD"].value.comment == "WELCOME\r\nTO THE CELL"
    assert recs["$HOSTNAME"].value.comment.startswith("UB10200-RBT01.CELL")
    fields = {m.key: m.entry.comment for m in recs["$SCR"].members}
    assert fields["$SCR.$TITLE"].startswith("A TITLE THE LISTING")
    assert fields["$SCR.$NOTE"] == "RUNS OVER\r\nA LINE END"
    assert main(["check", str(path)]) == 0
    assert "round trip ok" in capsys.readouterr().out


def test_a_string_open_to_the_end_is_still_refused(tmp_path, capsys):
    bad = tmp_path / "system.va"
    bad.write_bytes(b"[*SYSTEM*]$MOTD  Storage: CMOS  Access: RW  : STRING[80] = 'WELCOME\r\n"
                    b"[*SYSTEM*]$PI  Storage: DRAM  Access: RO  : REAL = 3.141593e+00\r\n")
    for command in ("check", "frames"):
        assert main([command, str(bad)]) == 2
        assert f"{bad}:1:" in capsys.readouterr().err


def test_long_comments_beside_a_sysframe_va_label_its_frames(tmp_path):
    shutil.copy(FANUC / "sysframe_comment.va", tmp_path / "SYSFRAME.VA")
    (tmp_path / "FRAMEVAR.VA").write_bytes(
        b"[TPFDEF]SETUP_DATA  Storage: CMOS  Access: RW  : ARRAY[8,3,61] OF FRMSET_T\r\n"
        b"         Field: SETUP_DATA[1,3,3].$COMMENT Access: RW: STRING[29] = \r\n"
        b"  'A COMMENT ON THE NEXT LINE'\r\n"
        b"         Field: SETUP_DATA[1,3,2].$COMMENT Access: RW: STRING[29] = 'TWO\r\nLINES'\r\n")
    cf = controller.load(tmp_path / "SYSFRAME.VA")
    labels = {f.name: f.label for f in cf.frames}
    assert labels["UF3"] == "A COMMENT ON THE NEXT LINE"
    assert labels["UF2"] == "TABLE"          # the element's own comment wins
