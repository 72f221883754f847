"""`ucsio program S.json --frame UF2 -o SETUF2.JBI` (issue 27 point 5, first
route): a Yaskawa job that sets user frame 2 by MFRAME from three positions
of the measured frame it loads into free global P variables.

The frame is rebuilt here from the written points with the 3-point
construction (numpy) and compared with the solution through scipy's
Rotation: independent of ucsio's own read-back. The job reader
(vendors/yaskawa/job.py) is being written in parallel: until it lands, the
job is checked line by line here; once it does, the job must read back
through it (a test to add then). The vendor is chosen by -o's suffix or
--vendor through the registry; FANUC stays the default.
"""
from __future__ import annotations

import json
import re
import shutil

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from conftest import ROOT, corpus_file
from ucsio import api
from ucsio.cli import main

KOMATSU = "lukelalondePZ__Komatsu-Press-Demo__"
SOLUTION = {"frame": {"x": 1523.4567, "y": -412.1234, "z": 801.9876,
                      "a": 33.3, "b": -12.5, "c": 178.25}}


def cli(capsys, *args):
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


def solution(tmp_path, frame=None, name="S.json"):
    path = tmp_path / name
    path.write_text(json.dumps({"frame": frame} if frame else SOLUTION))
    return path


def var_dat(*kinds: str) -> bytes:
    """A VAR.DAT of len(kinds) P rows: R a RECTAN position, P a PULSE one, U unused."""
    rows = {"R": '"RECTAN"0,0,0,000000000000000000000000,0,16,1.000,2.000,3.000,0.0000,0.0000,'
                 '0.0000,0.0000,0.0000',
            "P": '"PULSE"0,0,3,000000000000000000000000,0,0,1,2,3,4,5,6,0,0',
            "U": '"UNUSED"'}
    text = "//VAR\n///PFNUM 6,0,0,0\n///B\n0,0,0\n///P\n" + "".join(rows[k] + "\n" for k in kinds)
    return (text + "///BP\n///EX\n").replace("\n", "\r\n").encode()


JOB = ("/JOB\n//NAME PICK\n//POS\n///NPOS 0,0,0,1,0,0\n///TOOL 0\n///POSTYPE BASE\n///RECTAN\n"
       "///RCONF 0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n"
       "P00006=0.000,0.000,75.000,0.0000,0.0000,0.0000\n//INST\n///DATE 2023/09/01 11:13\n"
       "///ATTR SC,RW\n///GROUP1 RB1\nNOP\n'MOVJ P007 in a comment names nothing\n"
       "MOVJ P006\nSFTON P005\nMOVL LP003 BP004\nEND\n").replace("\n", "\r\n").encode()


def pos_rows(text: str) -> list[tuple[int, list[float]]]:
    """The //POS P rows of a job (its own line checks: the job reader is not here yet)."""
    pos = text.split("\r\n//INST\r\n")[0]
    return [(int(m.group(1)), [float(v) for v in m.group(2).split(",")])
            for m in re.finditer(r"^P([0-9]{5})=([^\r\n]*)\r?$", pos, re.M)]


def three_point_frame(org, xx, xy):
    """The README's verified construction: origin ORG, X along ORG->XX, XY
    fixing the plane and +Y (numpy)."""
    org, xx, xy = (np.array(p, float) for p in (org, xx, xy))
    x = (xx - org) / np.linalg.norm(xx - org)
    z = np.cross(x, xy - org)
    z /= np.linalg.norm(z)
    return org, np.column_stack([x, np.cross(z, x), z])


def solution_rotation(frame) -> Rotation:
    # SPEC's a, b, c (R = Rz(a)·Ry(b)·Rx(c)) = Yaskawa's rz, ry, rx
    return Rotation.from_euler("xyz", [frame["c"], frame["b"], frame["a"]], degrees=True)


# -- the frame the controller builds from the written points -------------------------------
FRAMES = [SOLUTION["frame"],
          {"x": 0.0004, "y": 0.0, "z": -0.0004, "a": 0.0, "b": 0.0, "c": 0.0},
          {"x": -2500.25, "y": 1999.9996, "z": 12.5, "a": -179.99, "b": 89.9, "c": -45.0},
          {"x": 100.0, "y": 200.0, "z": 300.0, "a": 180.0, "b": -89.99995, "c": 180.0}]
rng = np.random.default_rng(27)
FRAMES += [{"x": float(x), "y": float(y), "z": float(z), "a": float(a), "b": float(b),
            "c": float(c)}
           for x, y, z, a, b, c in zip(*rng.uniform(-3000, 3000, (3, 6)),
                                       *rng.uniform(-180, 180, (1, 6)),
                                       *rng.uniform(-90, 90, (1, 6)),
                                       *rng.uniform(-180, 180, (1, 6)))]


@pytest.mark.parametrize("frame", FRAMES, ids=range(len(FRAMES)))
def test_the_three_points_rebuild_the_solution_within_a_thousandth(tmp_path, capsys, frame):
    code, out, err = cli(capsys, "program", solution(tmp_path, frame), "--frame", "UF2",
                         "--p", "100", "--vendor", "yaskawa")
    assert code == 0, err
    text = out
    rows = pos_rows(text)
    assert [n for n, _ in rows] == [100, 101, 102]
    org, xx, xy = (v[:3] for _, v in rows)
    origin, matrix = three_point_frame(org, xx, xy)
    assert np.abs(origin - [frame["x"], frame["y"], frame["z"]]).max() <= 0.001
    want = solution_rotation(frame)
    assert (Rotation.from_matrix(matrix) * want.inv()).magnitude() * 180 / np.pi <= 0.001
    # 200 mm apart, and each with the frame's own orientation to 4 decimals
    assert np.linalg.norm(np.subtract(xx, org)) == pytest.approx(200.0, abs=0.002)
    assert np.linalg.norm(np.subtract(xy, org)) == pytest.approx(200.0, abs=0.002)
    for _, v in rows:
        assert all(re.fullmatch(r"-?[0-9]+\.[0-9]{3}", t) for t in text_fields(text, v)[:3])
        written = Rotation.from_euler("xyz", v[3:], degrees=True)
        assert (written * want.inv()).magnitude() * 180 / np.pi <= 1e-4
        assert all(-180 < a <= 180 for a in (v[3], v[5])) and -90 <= v[4] <= 90


def text_fields(text: str, values) -> list[str]:
    line = next(l for l in text.split("\r\n") if l.startswith("P") and "=" in l
                and [float(x) for x in l.split("=")[1].split(",")] == values)
    return line.split("=")[1].split(",")


def test_the_job_reads_back_through_the_job_reader(tmp_path, capsys):
    """The written job is one ucsio's own job reader takes: a byte-exact round
    trip, no finding, and its //POS rows are the three positions written, as
    BASE positions of P variables in tool 0 (what MFRAME is given)."""
    from ucsio.parsing.controller import load
    out_path = tmp_path / "SETUF2.JBI"
    code, _out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF2", "--p", "100",
                          "-o", out_path)
    assert code == 0, err
    cf = load(out_path, full=True)
    assert cf.vendor == "yaskawa" and cf.extra["kind"] == "job" and cf.frames == []
    assert cf.document.to_bytes() == out_path.read_bytes()
    assert [(f.code, f.message) for f in cf.lints] == []
    found = cf.extra["positions"]
    assert [(p.point, p.postype, p.tool, p.pulse) for p in found] == \
        [("P100", "BASE", 0, False), ("P101", "BASE", 0, False), ("P102", "BASE", 0, False)]
    assert [list(p.xyzabc()) for p in found] == [v for _, v in pos_rows(out_path.read_text())]
    code, out, err = cli(capsys, "check", out_path)
    assert code == 0 and "round trip ok" in out, (out, err)


# -- the job's lines -------------------------------------------------------------------------
def test_the_job_is_crlf_with_the_lines_a_controller_expects(tmp_path, capsys):
    out_path = tmp_path / "SETUF2.JBI"
    code, out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF2", "--p", "247",
                         "--group", "2", "-o", out_path)
    assert code == 0, err
    raw = out_path.read_bytes()
    assert raw.count(b"\r\n") == raw.count(b"\n") and raw.endswith(b"END\r\n")
    lines = raw.decode("ascii").split("\r\n")[:-1]
    assert lines[:8] == ["/JOB", "//NAME SETUF2", "//POS", "///NPOS 0,0,0,3,0,0", "///TOOL 0",
                         "///POSTYPE BASE", "///RECTAN", "///RCONF " + ",".join(["0"] * 24)]
    assert [l.split("=")[0] for l in lines[8:11]] == ["P00247", "P00248", "P00249"]
    assert lines[11] == "//INST" and re.fullmatch(r"///DATE \d{4}/\d\d/\d\d \d\d:\d\d", lines[12])
    assert lines[13:16] == ["///ATTR SC,RW", "///GROUP1 RB2", "NOP"]
    comments = lines[16:18]
    assert comments == ["'generated by ucsio: sets UF2", "'from S.json"]
    assert lines[18:] == ["MFRAME UF#(2) P247 P248 P249", "END"]
    assert f"wrote {out_path}: job SETUF2 sets UF2 by MFRAME from P247 P248 P249" in err
    # an INFORM comment holds 32 characters: a long solution name is cut, not refused
    long = solution(tmp_path, name="a_very_long_solution_name_from_the_tracker.json")
    code, out, err = cli(capsys, "program", long, "--frame", "UF12", "--p", "0",
                         "--vendor", "yaskawa")
    assert code == 0 and "\r\n'from a_very_long_solution_name_f\r\n" in out
    assert all(len(l) <= 33 for l in out.split("\r\n") if l.startswith("'"))
    assert "//NAME SETUF12\r\n" in out


# -- the P variables ---------------------------------------------------------------------------
def backup(tmp_path, var: bytes, *jobs: tuple[str, bytes]):
    folder = tmp_path / "backup"
    folder.mkdir()
    (folder / "VAR.DAT").write_bytes(var)
    for name, raw in jobs:
        (folder / name).write_bytes(raw)
    return folder / "VAR.DAT"


def test_the_corpus_backup_leaves_p247_to_p249(tmp_path, capsys):
    """The Komatsu cell uses P000..P032 (VAR.DAT and its jobs): the highest
    run of three free P variables is P247..P249."""
    folder = tmp_path / "komatsu"
    folder.mkdir()
    shutil.copy(corpus_file("yaskawa", KOMATSU + "VAR.DAT"), folder / "VAR.DAT")
    for job in ("R1_PRESS", "R1_RESET", "R2_TABLE", "MAIN"):
        shutil.copy(corpus_file("yaskawa", KOMATSU + job + ".JBI"), folder / f"{job}.JBI")
    code, out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF2", "--var",
                         folder / "VAR.DAT", "-o", tmp_path / "SETUF2.JBI", "--json")
    assert code == 0, err
    doc = json.loads(out)["program"]
    assert doc["p"] == [247, 248, 249] and doc["p_from"] == str(folder / "VAR.DAT")
    code, out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF2", "--var",
                         folder / "VAR.DAT", "--p", "12", "--vendor", "yaskawa")
    assert code == 2 and out == ""
    assert f"{folder / 'VAR.DAT'}:372:" in err and "P012 is in use" in err


def test_free_p_variables_from_var_dat_and_the_jobs_beside_it(tmp_path, capsys):
    # P000 a position, P001..P007 unused in VAR.DAT; the job names P006 (//POS) and P005
    # (SFTON); LP003 and BP004 are other variables, P007 only in a comment
    var = backup(tmp_path, var_dat("R", "U", "U", "U", "U", "U", "U", "U"), ("PICK.JBI", JOB))
    args = ("program", solution(tmp_path), "--frame", "UF1", "--vendor", "yaskawa", "--var", var)
    code, out, err = cli(capsys, *args, "--json")
    assert code == 0, err
    assert json.loads(out)["program"]["p"] == [2, 3, 4]       # 5 and 6 taken, 7 the last
    code, out, err = cli(capsys, *args, "--p", "4")
    assert code == 2 and f"{var.parent / 'PICK.JBI'}:17:" in err, err
    assert "P005 is in use (PICK.JBI: SFTON P005)" in err
    code, out, err = cli(capsys, *args, "--p", "6")
    assert code == 2 and "P000...P007" in err
    code, out, err = cli(capsys, *args, "--p", "1")
    assert code == 0 and "MFRAME UF#(1) P001 P002 P003\r\n" in out


def test_the_three_highest_free_ones_where_no_three_in_a_row_are_free(tmp_path, capsys):
    var = backup(tmp_path, var_dat("U", "R", "U", "P", "U", "R", "U"))
    code, out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF1", "--var", var,
                         "--vendor", "yaskawa")
    assert code == 0 and "MFRAME UF#(1) P002 P004 P006\r\n" in out, err


def test_no_free_p_variables_is_an_error(tmp_path, capsys):
    var = backup(tmp_path, var_dat("R", "U", "P", "U", "R"))
    target = tmp_path / "SETUF1.JBI"
    code, out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF1", "--var", var,
                         "-o", target)
    assert code == 2 and "no three free P variables: 3 of 5 are in use" in err
    assert not target.exists()


def test_a_var_dat_without_p_rows_is_an_error(tmp_path, capsys):
    var = backup(tmp_path, b"//VAR\r\n///B\r\n0,0\r\n")
    code, out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF1", "--var", var,
                         "--vendor", "yaskawa")
    assert code == 2 and "has no ///P rows" in err and out == ""


def test_an_indirect_p_variable_is_warned_about(tmp_path, capsys):
    job = JOB.replace(b"SFTON P005", b"MOVJ P[I000]")
    var = backup(tmp_path, var_dat(*"U" * 10), ("PICK.JBI", job))
    code, out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF1", "--var", var,
                         "--vendor", "yaskawa")
    assert code == 0 and "PICK.JBI line 17: a P variable by index" in err
    assert "MFRAME UF#(1) P007 P008 P009" in out


def test_without_a_var_dat_p_is_needed_and_unchecked(tmp_path, capsys):
    code, out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF1",
                         "--vendor", "yaskawa")
    assert code == 2 and "which P variables? --p N" in err
    code, out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF1", "--p", "90",
                         "--vendor", "yaskawa")
    assert code == 0 and "not checked against the cell" in err


# -- choosing the vendor, refusals, writing ----------------------------------------------------
@pytest.mark.parametrize("args, says", [
    (("--frame", "UT2", "--p", "5", "-o", "T.JBI"), "a Yaskawa tool has no program yet"),
    (("--frame", "UF2", "--pr", "5", "-o", "T.JBI"), "--pr does not go with a Yaskawa program"),
    (("--frame", "UF2", "--p", "5", "-o", "T.LS"), "--p is for a Yaskawa program: -o NAME.JBI"),
    (("--frame", "UF2", "--p", "5", "-o", "T.LS", "--vendor", "yaskawa"),
     "-o T.LS is a FANUC program's name"),
    (("--frame", "UF2", "--p", "5", "--vendor", "kuka"), "KUKA has no program writer yet"),
    (("--frame", "UF2", "--p", "5", "--vendor", "motoman"), "--vendor 'motoman': one of"),
    (("--frame", "UF64", "--p", "5", "-o", "T.JBI"), "user frame 1...63"),
    (("--frame", "UF2", "--p", "5", "-o", "SET UF2.JBI"), "is not a job name"),
    (("--frame", "UF2", "--p", "998", "-o", "T.JBI"), "P998...P1000 are not all"),
])
def test_refusals_exit_2_and_write_nothing(tmp_path, capsys, monkeypatch, args, says):
    monkeypatch.chdir(tmp_path)
    solution(tmp_path)
    (tmp_path / "T.JBI").write_bytes(b"old")
    code, out, err = cli(capsys, "program", "S.json", *args)
    assert code == 2 and out == "" and says in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["S.json", "T.JBI"]
    assert (tmp_path / "T.JBI").read_bytes() == b"old"


def test_an_existing_job_is_replaced_atomically_as_a_fanuc_program_is(tmp_path, capsys):
    target = tmp_path / "SETUF2.JBI"
    target.write_bytes(b"old")
    code, out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF2", "--p", "5",
                         "-o", target)
    assert code == 0 and target.read_bytes().startswith(b"/JOB\r\n//NAME SETUF2\r\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["S.json", "SETUF2.JBI"]


def test_fanuc_stays_the_default_and_ls_picks_it(tmp_path, capsys):
    for extra in ((), ("-o", tmp_path / "SET_UF2.LS"), ("--vendor", "fanuc")):
        code, out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF2", "--pr",
                             "90", *extra)
        assert code == 0, err
        text = out or (tmp_path / "SET_UF2.LS").read_text()
        assert text.startswith("/PROG") and "UFRAME[2]=PR[90]" in text


def test_json_and_the_api(tmp_path, capsys):
    import jsonschema
    schema = json.loads((ROOT / "docs" / "schema" / "program.json").read_text())
    code, out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF2", "--p", "5",
                         "--vendor", "yaskawa", "--json")
    doc = json.loads(out)
    jsonschema.Draft202012Validator(schema).validate(doc)
    prog = doc["program"]
    assert prog["file"] is None and prog["p"] == [5, 6, 7] and prog["p_from"] == "--p"
    assert "pr" not in prog and prog["type"] == "UFRAME" and prog["group"] == 1
    assert prog["pose"]["rz"] == pytest.approx(33.3, abs=1e-3)
    assert prog["points"]["ORG"][:3] == [1523.457, -412.123, 801.988]
    target = tmp_path / "SETUF3.JBI"
    made = api.program(str(tmp_path / "S.json"), "UF3", p=5, output=target)
    assert made.program.p == [5, 6, 7] and made.program.file == str(target)
    assert target.read_bytes() == made.text.encode()
    assert made.program.pose.rx == pytest.approx(178.25, abs=1e-3)


def test_source_date_epoch_makes_the_job_reproducible(tmp_path, capsys, monkeypatch):
    """///DATE is now, or SOURCE_DATE_EPOCH's time in UTC where it is set:
    one solution made twice gives the same bytes (a job kept in git)."""
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1764763200")      # 2025-12-03 12:00 UTC
    jobs = []
    for _ in range(2):
        code, out, err = cli(capsys, "program", solution(tmp_path), "--frame", "UF2", "--p",
                             "100", "--vendor", "yaskawa")
        assert code == 0, err
        jobs.append(out)
    assert jobs[0] == jobs[1] and "\r\n///DATE 2025/12/03 12:00\r\n" in jobs[0]
