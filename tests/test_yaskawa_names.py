"""A Yaskawa job's positions carry no names: the comment line directly
before a move names the position it moves to, as the pendant shows the job
(``job.names_by_comment``). ``program --measure`` writes its points so, and
``solve --robot`` pairs them by the plan's names; a position commented with
two names, or a name that comments two positions, names nothing (and the C
number still pairs)."""
from __future__ import annotations

import pytest

from conftest import CORPUS, ROOT
from ucsio.parsing.document import Document
from ucsio.readers.robot import read_robot
from ucsio.vendors.yaskawa.job import names_by_comment

YASKAWA = ROOT / "src/ucsio/demo/data/R05_yaskawa"
JOB = """/JOB\r
//NAME NAMED\r
//POS\r
///NPOS 4,0,0,0,0,0\r
///TOOL 3\r
///POSTYPE BASE\r
///RECTAN\r
///RCONF 0,0,0,0,0,0,0,0\r
C00000=1000.000,0.000,500.000,180.0000,0.0000,0.0000\r
C00001=1100.000,0.000,500.000,180.0000,0.0000,0.0000\r
C00002=1000.000,200.000,500.000,180.0000,0.0000,0.0000\r
C00003=1100.000,200.000,540.000,180.0000,0.0000,0.0000\r
//INST\r
///DATE 2026/12/03 12:00\r
///ATTR SC,RW\r
///GROUP1 RB1\r
NOP\r
'APPROACH\r
MOVJ C00000 VJ=25.00\r
' PICK \r
MOVL C00001 V=100.0 PL=0\r
'APPROACH\r
MOVJ C00002 VJ=25.00\r
'PLACE\r
MOVL C00003 V=100.0\r
'OTHER\r
MOVL C00003 V=100.0\r
'DONE\r
TIMER T=1.00\r
MOVL C00002 V=100.0\r
END\r
"""


def test_a_comment_names_the_position_of_the_move_after_it():
    named = names_by_comment(Document(JOB.encode(), "NAMED.JBI"))
    # APPROACH comments two positions, C00003 has two comments; 'DONE is before a TIMER
    assert named == {"C00001": "PICK"}


def test_solve_pairs_a_named_position_by_its_name_and_its_number(tmp_path):
    job = tmp_path / "NAMED.JBI"
    job.write_bytes(JOB.encode())
    robot = read_robot(job, config=(str(YASKAWA / "TOOL.CND"),))
    by_name = {p.name: p for p in robot.poses}
    assert by_name["C00001"].point == "PICK" and "C1" in by_name["C00001"].aliases
    assert by_name["C00000"].point == "C0"                   # its comment names two
    from ucsio import api
    laser = tmp_path / "laser.csv"
    rows = [("PICK", 100, 0, 0), ("C0", 0, 0, 0), ("C00002", 0, 200, 0), ("C3", 100, 200, 40)]
    laser.write_text("point,x,y,z\n" + "".join(f"{n},{x},{y},{z}\n" for n, x, y, z in rows))
    got = api.solve(laser=laser, robot=job, config=[str(YASKAWA / "TOOL.CND")], tool=f"{YASKAWA / 'TOOL.CND'}:UT3",
                    min_points=3, no_exclusion=True).as_dict()
    assert [p["name"] for p in got["points"]] == ["PICK", "C0", "C00002", "C3"]
    assert got["n_used"] == 4 and got["rms"] < 1e-3


@pytest.mark.skipif(not (CORPUS / "yaskawa").is_dir(), reason="../shared/corpus is absent")
def test_corpus_jobs_keep_every_position_pairable():
    """On the corpus's real jobs the comment names are one per position and
    never taken twice; every position still answers to its C number."""
    for path in sorted((CORPUS / "yaskawa").rglob("*.JBI")):
        named = names_by_comment(Document.read(str(path)))
        assert len(set(v.casefold() for v in named.values())) == len(named), path
        assert all(k.startswith(("C", "P", "BC", "EC", "BP", "EX")) for k in named), path
    # a real press job comments its pick and place right above their moves
    press = next((CORPUS / "yaskawa").rglob("*R1_PRESS.JBI"), None)
    if press is not None:
        assert names_by_comment(Document.read(str(press))) == {
            "C00000": "PRESS PICK", "C00001": "PRESS PLACE"}
