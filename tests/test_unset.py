"""Unset frames (issue 18, point 8).

A real $config.dat lists some 69 frames, most of them the controller's
default: all six values zero and no name. ``frames`` lists the set ones and
one line counting the rest (``--all`` lists every one; JSON always holds all,
each with ``"set"``); ``diff``, ``batch`` and the report warn when the
simulated frame is unset, because the difference is then the whole measured
pose, not a correction.
"""
from __future__ import annotations

import json
import shutil


from conftest import FIXTURES, corpus_file
from ucsio.cli import main

CELL_CONFIG = FIXTURES / "kuka" / "cell_config.dat"
MEAS = FIXTURES / "measurements" / "kuka_base3.csv"
TCP = [-20.67, 89.73, 33.44]


def frames_json(path, capsys) -> dict:
    assert main(["frames", str(path), "--json"]) == 0
    return {f["name"]: f for f in json.loads(capsys.readouterr().out)["frames"]}


def test_unset_is_a_zero_unnamed_entry_of_the_configuration(capsys):
    got = frames_json(CELL_CONFIG, capsys)
    assert all(isinstance(f["set"], bool) for f in got.values())
    assert got["TOOL_DATA[4]"]["set"] is False           # zero, TOOL_NAME[4,]=" "
    assert got["BASE_DATA[4]"]["set"] is True            # zero, but named "gripper"
    assert got["TOOL_DATA[1]"]["set"] is True            # values
    zin = frames_json(corpus_file("kuka", "Zinkerreka__KRC__R1__System"), capsys)
    assert zin["TOOL_DATA[2]"]["set"] is False and zin["BASE_DATA[6]"]["set"] is False
    assert zin["REF_PT[1]"]["set"] is False and zin["TOOL_CORR"]["set"] is False
    assert zin["BASE_DATA[2]"]["set"] is True and zin["RECIPE_TCP[1]"]["set"] is True
    # a label that only repeats the entry's own name is the default one
    tfg = frames_json(corpus_file("kuka", "luciagumbau228"), capsys)
    assert tfg["TOOL_DATA[2]"]["label"] == "TOOL_DATA[2]" and tfg["TOOL_DATA[2]"]["set"] is False
    # a named zero base is someone's choice
    kam = frames_json(corpus_file("kuka", "KamWisa__BPF2PLTZPK2__$config"), capsys)
    assert kam["BASE_DATA[10]"]["label"] == "KukaReburn" and kam["BASE_DATA[10]"]["set"] is True
    # a program's own zero FRAMEs were declared by someone: set
    prog = frames_json(corpus_file("kuka", "C1_pickConveyorBP"), capsys)
    assert prog["hmiOffsetFrame"]["set"] is True and prog["hmiOffsetFrame"]["x"] == 0
    # and so is an ABB identity frame (tool0, wobj0 alike)
    abb = frames_json(FIXTURES / "patch" / "cell.mod", capsys)
    assert abb["wobjPlain"]["set"] is True and abb["wobjPlain"]["x"] == 0


def test_frames_lists_the_set_ones_and_counts_the_rest(capsys):
    cfg = corpus_file("kuka", "Zinkerreka__KRC__R1__System")
    every = frames_json(cfg, capsys)
    unset = [n for n, f in every.items() if not f["set"]]
    assert len(every) == 76 and len(unset) == 62
    assert main(["frames", str(cfg)]) == 0
    out = capsys.readouterr().out
    rows = [ln.split()[0] for ln in out.splitlines()[2:] if ln.strip()]
    assert "BASE_DATA[1]" in rows and "RECIPE_TCP[1]" in rows
    assert not set(rows) & set(unset)
    assert out.rstrip().splitlines()[-1] == (
        "62 unset frames not listed (all six values 0 and no name: the controller's "
        "defaults; --all lists them)")
    assert main(["frames", str(cfg), "--all"]) == 0
    out = capsys.readouterr().out
    assert "unset frames not listed" not in out
    assert {ln.split()[0] for ln in out.splitlines()[2:] if ln.strip()} == set(every)


def test_diff_warns_when_the_simulated_frame_is_unset(tmp_path, capsys):
    cfg = corpus_file("kuka", "Zinkerreka__KRC__R1__System")
    sol = tmp_path / "sol.json"
    sol.write_text(json.dumps({"accepted": True, "frame": {"x": 1200, "y": 300, "z": 650,
                                                          "a": 30, "b": 0, "c": 0}}))
    assert main(["diff", str(cfg), "--frame", "BASE_DATA[6]", "--measured", str(sol),
                 "--tolerance", "5000"]) == 0
    err = capsys.readouterr().err
    assert "BASE_DATA[6] is unset" in err and "whole measured pose" in err, err
    assert main(["diff", str(cfg), "--frame", "BASE_DATA[6]", "--measured", str(sol),
                 "--json"]) == 1
    d = json.loads(capsys.readouterr().out)
    assert d["set"] is False and "unset" in d["warning"]
    assert main(["diff", str(cfg), "--frame", "BASE_DATA[1]", "--measured", str(sol),
                 "--json"]) == 1
    d = json.loads(capsys.readouterr().out)
    assert d["set"] is True and "warning" not in d


def test_batch_and_its_report_warn_when_the_simulated_frame_is_unset(tmp_path, capsys):
    shutil.copy(corpus_file("kuka", "Zinkerreka__KRC__R1__System"), tmp_path / "$config.dat")
    shutil.copy(MEAS, tmp_path / "m.csv")
    (tmp_path / "station.toml").write_text(
        f'[defaults]\ncontroller = "$config.dat"\nmeasurement = "m.csv"\ntcp = {TCP}\n'
        'tolerance = 100000.0\n'
        '[[entry]]\nname = "unused base"\nframe = "BASE_DATA[6]"\n'
        '[[entry]]\nname = "named base"\nframe = "pickBP"\n')
    report = tmp_path / "report.html"
    assert main(["batch", str(tmp_path / "station.toml"), "--report", str(report)]) == 0
    out = capsys.readouterr().out
    assert "unused base: BASE_DATA[6] is unset" in out and "whole measured pose" in out
    assert "named base:" not in out
    html = report.read_text().split('<script type="application/json"', 1)[0]   # what is shown
    actions = html.split('id="actions"', 1)[1].split("</section>", 1)[0]
    assert "BASE_DATA[6] is unset" in actions and 'data-name="unused base"' in actions
    assert 'data-name="named base"' not in actions
    detail = html.split('<details id="e0"', 1)[1].split("</details>", 1)[0]
    assert "BASE_DATA[6] is unset" in detail
    assert main(["batch", str(tmp_path / "station.toml"), "--json"]) == 0
    unused, named = json.loads(capsys.readouterr().out)["entries"]
    assert unused["simulated_set"] is False
    assert any("is unset" in w for w in unused["warnings"])
    assert named["simulated_set"] is True and "warnings" not in named


# -- FANUC: sysframe.va's entries are the same kind of table -----------------------------
def test_fanuc_unset_is_a_zero_entry_without_a_comment(capsys):
    from conftest import corpus_file as corpus
    got = frames_json(corpus("fanuc", "irbzavalagit__UB10200_RBT01__sysframe.va"), capsys)
    set_ = sorted(name for name, f in got.items() if f["set"])
    assert set_ == sorted(["UF1", "UF9", "UF19", "UF20", "UT1", "UT10", "UT31", "UT32"])
    assert got["UF2"]["set"] is False and got["UT1@2"]["set"] is False
    labelled = frames_json(FIXTURES / "fanuc" / "sysframe_comment.va", capsys)
    assert labelled["UF3"]["set"] is False              # zero, and its comment is ''
    assert labelled["UF1@2"]["set"] is True             # values (and 'RAIL')
    assert main(["frames", str(FIXTURES / "fanuc" / "sysframe_comment.va")]) == 0
    out = capsys.readouterr().out
    assert "UF3 " not in out and "5 unset frames not listed" in out and "FIXTURE_A" in out


def test_a_frame_a_program_sets_is_set_whatever_its_values(tmp_path, capsys):
    prog = tmp_path / "zero.ls"
    prog.write_text("/PROG  ZERO\n/ATTR\n/MN\n   1:  PR[1]=LPOS-LPOS    ;\n"
                    "   2:  UFRAME[3]=PR[1] ;\n/POS\n/END\n")
    got = frames_json(prog, capsys)
    assert got["UF3"]["set"] is True and got["UF3"]["x"] == 0.0


def test_diff_warns_on_an_unset_fanuc_frame(tmp_path, capsys):
    sol = tmp_path / "sol.json"
    sol.write_text(json.dumps({"frame": {"x": 1, "y": 2, "z": 3, "a": 0, "b": 0, "c": 0}}))
    va = FIXTURES / "fanuc" / "sysframe_comment.va"
    assert main(["diff", str(va), "--frame", "UF3", "--measured", str(sol), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["set"] is False and "UF3 is unset" in d["warning"]


# -- a TCP taken from an unset tool (issue 25, point 6) ----------------------------------
def test_a_tcp_from_an_unset_tool_is_warned_about(tmp_path, capsys):
    """TOOL_DATA[4] is zero and unnamed: used as TCP 0,0,0, but not without a word."""
    assert main(["solve", str(MEAS), "--tool", f"{CELL_CONFIG}:TOOL_DATA[4]", "--json"]) == 1
    captured = capsys.readouterr()
    said = "--tool: TOOL_DATA[4] is unset (all six values 0 and no name"
    assert said in captured.err and "--tcp 0,0,0" in captured.err
    assert any(said in w for w in json.loads(captured.out)["warnings"])
    main(["solve", str(MEAS), "--tool", f"{CELL_CONFIG}:TOOL_DATA[1]", "--json"])
    assert "is unset" not in capsys.readouterr().err
    # plan takes the same --tool
    main(["plan", str(MEAS), "--tool", f"{CELL_CONFIG}:TOOL_DATA[4]", "--json"])
    captured = capsys.readouterr()
    assert said in captured.err and any(said in w for w in json.loads(captured.out)["warnings"])
    # batch: the entry's warnings, in the manifest's words
    shutil.copy(CELL_CONFIG, tmp_path / "$config.dat")
    shutil.copy(MEAS, tmp_path / "m.csv")
    (tmp_path / "m.toml").write_text(
        '[defaults]\ncontroller = "$config.dat"\nmeasurement = "m.csv"\nframe = "BASE_DATA[1]"\n'
        '[[entry]]\nname = "unset tool"\ntool = "$config.dat:TOOL_DATA[4]"\n'
        '[[entry]]\nname = "set tool"\ntool = "$config.dat:TOOL_DATA[1]"\n')
    main(["batch", str(tmp_path / "m.toml"), "--json"])
    unset, set_ = json.loads(capsys.readouterr().out)["entries"]
    assert any(w.startswith("tool: TOOL_DATA[4] is unset") and "tcp = [0, 0, 0]" in w
               for w in unset["warnings"])
    assert not any("is unset" in w for w in set_.get("warnings", []))


# FANUC names the frames nobody named: UFrame7, Eoat2 (issue 24 point 5)
ZERO = ("  X:     0.000   Y:     0.000   Z:     0.000\r\n"
        "  W:     0.000   P:     0.000   R:     0.000\r\n")
SET = ("  X:  1200.500   Y:  -300.250   Z:      .750\r\n"
       "  W:      .140   P:     -.080   R:    90.000\r\n")


def _element(g: int, n: int, comment: str, values: str) -> str:
    return f"    [{g},{n}] =   '{comment}' \r\n  Group: {g}   Config: N U T, 0, 0, 0\r\n" + values


def _sysframe(frames, tools) -> str:
    def record(name, elements, size):
        return (f"[*SYSTEM*]$MNU{name}  Storage: SHADOW  Access: RW  : ARRAY[2,{size}] OF "
                "POSITION\r\n" + "".join(_element(*e) for e in elements) + "\r\n")
    return record("FRAME", frames, 9) + record("TOOL", tools, 9)


def test_fanuc_default_comments_are_no_name(tmp_path, capsys):
    va = tmp_path / "sysframe.va"
    va.write_bytes(_sysframe(
        [(1, 1, "UFrame1", ZERO), (1, 2, "UFrame2", SET), (1, 3, "UFrame7", ZERO),
         (2, 7, "UFRAME 7", ZERO), (1, 4, "TABLE", ZERO)],
        [(1, 1, "Eoat1", ZERO), (2, 2, "Eoat2", ZERO), (1, 3, "UTool3", ZERO),
         (1, 4, "Eoat4x", ZERO)]).encode())
    got = frames_json(va, capsys)
    unset = sorted(n for n, f in got.items() if not f["set"])
    # the default comment of the frame itself; not UF3's 'UFrame7' (it names
    # another frame: someone wrote it), not 'TABLE', not a word after the number
    assert unset == ["UF1", "UF7@2", "UT1", "UT2@2", "UT3"]
    assert got["UF2"]["set"] is True and got["UF2"]["label"] == "UFrame2"
    assert main(["frames", str(va)]) == 0
    out = capsys.readouterr().out
    assert "5 unset frames not listed" in out and "Eoat1" not in out and "UFrame7" in out
    assert main(["frames", str(va), "--all"]) == 0
    assert "Eoat1" in capsys.readouterr().out


def test_fanuc_default_comments_from_framevar_beside(tmp_path, capsys):
    (tmp_path / "SYSFRAME.VA").write_bytes(_sysframe(
        [(1, 1, "", ZERO), (1, 2, "", ZERO)], [(1, 1, "", ZERO)]).encode())
    (tmp_path / "FRAMEVAR.VA").write_bytes(
        b"[TPFDEF]SETUP_DATA  Storage: CMOS  Access: RW  : ARRAY[8,3,61] OF FRMSET_T\r\n"
        b"         Field: SETUP_DATA[1,1,1].$COMMENT Access: RW: STRING[29] = 'Eoat1'\r\n"
        b"         Field: SETUP_DATA[1,3,1].$COMMENT Access: RW: STRING[29] = 'UFrame1'\r\n"
        b"         Field: SETUP_DATA[1,3,2].$COMMENT Access: RW: STRING[29] = 'CAR 0'\r\n")
    got = frames_json(tmp_path / "SYSFRAME.VA", capsys)
    assert got["UF1"]["label"] == "UFrame1" and got["UF1"]["set"] is False
    assert got["UT1"]["label"] == "Eoat1" and got["UT1"]["set"] is False
    assert got["UF2"]["set"] is True
