"""Frames know their parent; ``frames --tree`` (issue 26, point 5).

Every frame says what it is relative to (``parent`` and ``parent_kind`` in
``frames --json``): world, a robot's base or flange (``robot@2`` for FANUC
motion group 2), another frame (an ABB object frame in its work object's
user frame), a unit that moves it (an ABB mechanical unit, a KUKA external
kinematic), or unknown. ``frames --tree`` hangs each frame under its parent.
"""
from __future__ import annotations

import json

import pytest

from conftest import CORPUS, FIXTURES
from ucsio.cli import main
from ucsio.geometry.frames import Frame, Parent, frame_parent
from ucsio.geometry.tree import build

CELL = FIXTURES / "patch" / "cell.mod"
REFS = FIXTURES / "patch" / "refs" / "$config.dat"
GROUPS = FIXTURES / "fanuc" / "sysframe_mixed.va"


def listing(capsys, *args) -> dict:
    assert main(["frames", *map(str, args), "--json", "--all"]) == 0
    return {f["name"]: f for f in json.loads(capsys.readouterr().out)["frames"]}


def parents(capsys, *args) -> dict:
    return {n: (f["parent_kind"], f["parent"]) for n, f in listing(capsys, *args).items()}


def test_abb_parents(capsys):
    got = parents(capsys, CELL)
    assert got["wobjSpec"] == ("world", "world")                 # robhold FALSE, ufprog TRUE
    assert got["wobjSpec.oframe"] == ("frame", "wobjSpec")       # in its user frame
    assert got["wobjHeld"] == ("flange", "flange")               # robhold TRUE: on the wrist
    assert got["wobjHeld.oframe"] == ("frame", "wobjHeld")
    assert got["wobjMoving"] == ("unit", "STN_1")                # ufprog FALSE, ufmec STN_1
    assert got["tHeld"] == ("flange", "flange")                  # tooldata robhold TRUE
    assert got["tFixed"] == ("world", "world")                   # robhold FALSE: stationary
    assert got["pCorr"] == ("unknown", "unknown")                # pose data: the file says not
    # reference is kept as it was (scripts use it)
    assert listing(capsys, CELL)["wobjHeld"]["reference"] == "wrist"


def test_abb_moving_user_frame_without_a_unit_name(tmp_path, capsys):
    mod = tmp_path / "Moving.mod"
    mod.write_text('MODULE Moving\n  PERS wobjdata wMoving:=[FALSE,FALSE,"",'
                   '[[0,0,0],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\nENDMODULE\n')
    got = parents(capsys, mod)
    assert got["wMoving"] == ("unit", "mechanical unit")
    assert got["wMoving.oframe"] == ("frame", "wMoving")


def test_parents_inside_an_archive(tmp_path, capsys):
    """A backup's frames carry their parent too (here a .zip member)."""
    import zipfile
    archive = tmp_path / "backup.zip"
    with zipfile.ZipFile(archive, "w") as z:
        z.write(CELL, "RAPID/TASK1/PROGMOD/cell.mod")
        z.write(GROUPS, "FANUC/sysframe.va")
    got = parents(capsys, archive)
    assert got["wobjSpec.oframe"] == ("frame", "wobjSpec")
    assert got["UT1@2"] == ("flange", "flange@2")
    assert main(["frames", "--tree", str(archive)]) == 0
    out = capsys.readouterr().out
    assert "├── robot@2" in out and "├── STN_1 (moves the frames below)" in out


def test_kuka_parents(capsys):
    got = parents(capsys, REFS)
    assert got["BASE_DATA[1]"] == ("world", "world")
    assert got["BASE_DATA[2]"] == ("world", "world")             # BASE_TYPE #TCP: fixed, in world
    assert got["BASE_DATA[3]"] == ("unit", "MACHINE_DEF[2]")     # on the external kinematic
    assert got["TOOL_DATA[1]"] == ("flange", "flange")


def test_kuka_held_workpiece_and_program_frames(tmp_path, capsys):
    dat = tmp_path / "$config.dat"
    dat.write_text("DEFDAT $CONFIG\nDECL FRAME TOOL_DATA[2]\n"
                   "TOOL_DATA[1]={X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0}\n"
                   "DECL IPO_M_T TOOL_TYPE[2]\nTOOL_TYPE[1]=#TCP\n"
                   "DECL FRAME XAPPROACH={X 0.0,Y 0.0,Z 10.0,A 0.0,B 0.0,C 0.0}\nENDDAT\n")
    got = listing(capsys, dat)
    assert got["TOOL_DATA[1]"]["role"] == "workpiece"
    assert (got["TOOL_DATA[1]"]["parent_kind"], got["TOOL_DATA[1]"]["parent"]) == \
        ("flange", "flange")
    assert got["XAPPROACH"]["parent_kind"] == "unknown"


def test_fanuc_groups(capsys):
    got = parents(capsys, GROUPS)
    assert got["UF1"] == ("robot", "robot")
    assert got["UF1@2"] == ("robot", "robot@2")
    assert got["UT1"] == ("flange", "flange")
    assert got["UT1@2"] == ("flange", "flange@2")


def test_every_fanuc_frame_names_its_group(capsys):
    """Also the listing's fast path (an element repeating another's values,
    in another group): the parent follows the element's own group."""
    folder = CORPUS / "fanuc"
    if not folder.is_dir():
        pytest.skip(f"{folder} is absent: the shared corpus is not beside this checkout")
    assert main(["frames", str(folder), "--json"]) == 0
    frames = json.loads(capsys.readouterr().out)["frames"]
    assert {f["group"] for f in frames} >= {1, 2, 3}
    for f in frames:
        suffix = "" if f["group"] == 1 else f"@{f['group']}"
        want = ("robot" if f["type"] == "UFRAME" else "flange") + suffix
        assert f["parent"] == want, f


# --------------------------------------------------------------- the tree

def test_tree_text_of_an_abb_module(capsys):
    assert main(["frames", "--tree", str(CELL)]) == 0
    out = capsys.readouterr().out
    at = f"  {CELL}:"
    assert "\033[" not in out                        # not a terminal: no colour
    want = [
        "world",
        "├── robot",
        "│   └── flange",
        f"│       ├── wobjHeld  wobjdata{at}8",
        f"│       │   └── wobjHeld.oframe  wobjdata{at}8",
        f"│       └── tHeld  tooldata{at}13",
        f"├── wobjSpec  wobjdata{at}4",
        f"│   └── wobjSpec.oframe  wobjdata{at}4",
    ]
    lines = out.splitlines()
    assert lines[:len(want)] == want
    assert "├── STN_1 (moves the frames below)" in lines
    assert f"│   └── wobjMoving  wobjdata{at}9" in lines
    assert lines[-2:] == ["unknown (the file does not say what these are relative to)",
                          f"└── pCorr  pose{at}16"]


def test_tree_text_of_fanuc_groups_hides_unset_unless_all(capsys):
    assert main(["frames", "--tree", str(GROUPS)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[:2] == ["world", "├── robot"]
    assert "└── robot@2" in out
    assert any(line.endswith(f"UF1@2  UFRAME  \"RAIL\"  {GROUPS}:13") for line in out)
    assert not any("UF3 " in line for line in out)                 # unset
    assert out[-1].startswith("5 unset frames not shown")
    assert main(["frames", "--tree", "--all", str(GROUPS)]) == 0
    out = capsys.readouterr().out
    assert f"UF3  UFRAME  (unset)  {GROUPS}:" in out
    assert "not shown" not in out


def _walk(node, above=None):
    yield node, above
    for child in node["children"]:
        yield from _walk(child, node)


def test_tree_json_nests_each_frame_under_its_parent(capsys):
    assert main(["frames", "--tree", "--json", "--all", str(CELL), str(REFS)]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert [t["input"] for t in doc["tree"]] == [str(CELL), str(REFS)]
    items = {(f["file"], f["name"]): f for f in doc["frames"]}
    placed = []
    for t in doc["tree"]:
        assert [r["name"] for r in t["roots"]][0] == "world"
        for root in t["roots"]:
            for node, above in _walk(root):
                if node["kind"] != "frame":
                    continue
                f = items[(node["file"], node["name"])]
                placed.append((node["file"], node["name"]))
                assert above["name"] == f["parent"] or f["parent_kind"] == "unknown", node
                assert above["kind"] == f["parent_kind"] or f["parent_kind"] == "unknown"
    assert sorted(placed) == sorted(items)                 # every frame once, with --all
    kuka = doc["tree"][1]["roots"][0]
    unit = next(n for n in kuka["children"] if n["kind"] == "unit")
    assert unit["name"] == "MACHINE_DEF[2]"
    assert [c["name"] for c in unit["children"]] == ["BASE_DATA[3]"]


def test_tree_of_a_corpus_backup_folder(capsys):
    """The KUKA corpus read as one backup: each set frame placed once, under
    its parent; unset ones only with --all."""
    folder = CORPUS / "kuka"
    if not folder.is_dir():
        pytest.skip(f"{folder} is absent: the shared corpus is not beside this checkout")
    assert main(["frames", "--tree", "--json", str(folder)]) == 0
    doc = json.loads(capsys.readouterr().out)
    (tree,) = doc["tree"]
    shown = [n for r in tree["roots"] for n, _ in _walk(r) if n["kind"] == "frame"]
    assert len(shown) == sum(f["set"] for f in doc["frames"])
    assert all(n["set"] for n in shown)
    kinds = {n["kind"] for r in tree["roots"] for n, _ in _walk(r)}
    assert {"world", "robot", "flange", "frame", "unknown"} <= kinds


def test_tree_of_an_unreadable_file_is_one_error(capsys):
    bad = FIXTURES / "abb" / "bad" / "garbage.mod"
    assert main(["frames", "--tree", str(bad)]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert f"{bad}:" in captured.err


def _frame(name, parent: Parent, file="cell.mod") -> Frame:
    return Frame(name, "abb", "wobjdata", None, file, 1, parent=parent)


def test_a_missing_or_circular_parent_frame_hangs_under_unknown():
    """Frames defined on frames (later vendors: Yaskawa's user frame k,
    Stäubli's fFather) may name one the file lacks, or go round in a circle."""
    frames = [_frame("a", frame_parent("b")), _frame("b", frame_parent("a")),
              _frame("orphan", frame_parent("nowhere")), _frame("c", frame_parent("d")),
              _frame("d", Parent("world", "world")), _frame("e", frame_parent("c"), "other.mod")]
    world, unknown = build(frames, lambda f: True)
    assert [n.name for n in world.children] == ["d"]
    assert [n.name for n in world.children[0].children] == ["c"]
    assert [n.name for n in unknown.children] == ["a", "b", "orphan", "e"]   # e: not its file


def test_tree_is_bold_on_a_terminal_unless_no_color(monkeypatch):
    import io
    import sys

    class Terminal(io.StringIO):
        def isatty(self) -> bool:
            return True

    def run() -> str:
        out = Terminal()
        monkeypatch.setattr(sys, "stdout", out)
        assert main(["frames", "--tree", str(CELL)]) == 0
        return out.getvalue()

    monkeypatch.delenv("NO_COLOR", raising=False)
    monkeypatch.setenv("TERM", "xterm")
    assert run().startswith("\033[1mworld\033[0m\n")
    monkeypatch.setenv("NO_COLOR", "1")
    assert run().startswith("world\n├── robot\n")
