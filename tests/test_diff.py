"""ucsio diff: one frame vs a measured solution (SPEC's keys), and two files."""
from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from conftest import FIXTURES
from ucsio import api
from ucsio.cli import main
from ucsio.parsing.controller import load
from ucsio.review.diff import frame_delta
from ucsio.geometry.frames import Pose
from ucsio.review.compare import diff_files, frame_line, textconv

PATCH = FIXTURES / "patch"
CELL = PATCH / "cell.mod"
REFS = PATCH / "refs" / "$config.dat"

SIMULATED = Pose.from_abc(6130.000, 2444.711, 1156.772, 90, -25, 0)
MEASURED = Pose.from_abc(6125.390, 2445.560, 1168.990, 90.529, -24.476, -0.313)
SPEC_KEYS = {"name", "simulated", "measured", "dx", "dy", "dz", "da", "db", "dc", "angle",
             "dist", "dt_mean", "group", "pass"}


def write_solution(tmp_path, pose: Pose, **extra) -> Path:
    p = tmp_path / "SOLUTION.json"
    p.write_text(json.dumps({"frame": pose.as_dict(), "accepted": True, **extra}))
    return p


def test_spec_example_delta():
    d = frame_delta(SIMULATED, MEASURED)
    assert d["dt_mean"] == pytest.approx(5.892, abs=5e-4)
    assert d["group"] == 1 and d["pass"] is True
    assert (d["dx"], d["dy"], d["dz"]) == pytest.approx((-4.61, 0.849, 12.218), abs=1e-9)
    assert (d["da"], d["db"], d["dc"]) == pytest.approx((0.529, 0.524, -0.313), abs=1e-9)


@pytest.mark.parametrize("path,name", [(REFS, "spec_base"), (REFS, "BASE_DATA[7]"),
                                       (CELL, "wobjSpec")])
def test_spec_example_command(tmp_path, capsys, path, name):
    sol = write_solution(tmp_path, MEASURED)
    assert main(["diff", str(path), "--frame", name, "--measured", str(sol), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert SPEC_KEYS <= d.keys()
    assert d["dt_mean"] == pytest.approx(5.892, abs=5e-4)
    assert d["group"] == 1 and d["pass"] is True
    for side in ("simulated", "measured"):
        assert set("xyzabcq") <= d[side].keys()
    # over tolerance: exit 1, and the table says FAIL
    assert main(["diff", str(path), "--frame", name, "--measured", str(sol),
                 "--tolerance", "5"]) == 1
    out = capsys.readouterr().out
    assert "FAIL" in out and "dt_mean 5.892" in out


def test_diff_frame_usage_errors(tmp_path, capsys):
    sol = write_solution(tmp_path, MEASURED)
    assert main(["diff", str(CELL), "--frame", "wobjSpec"]) == 2
    assert main(["diff", str(CELL), "--frame", "nosuch", "--measured", str(sol)]) == 2
    assert main(["diff", str(CELL), "--frame", "wobjSpec", "--measured", str(sol),
                 "--tolerance", "0"]) == 2
    assert main(["diff", str(CELL)]) == 2
    assert main(["diff", str(CELL), str(CELL), "--tolerance", "3"]) == 2
    capsys.readouterr()


def test_diff_frame_warns_about_reference(tmp_path):
    d = api.diff_frame(CELL, "tHeld", MEASURED)
    assert "flange" in d["warning"]
    assert "warning" not in api.diff_frame(CELL, "wobjSpec", MEASURED)


def edited(tmp_path, name: str, old: str, new: str, src: Path = CELL) -> Path:
    folder = tmp_path / name
    folder.mkdir()
    f = folder / src.name
    text = src.read_text()
    assert old in text
    f.write_text(text.replace(old, new))
    return f


def test_two_files_changed_added_removed(tmp_path, capsys):
    new = edited(tmp_path, "new", "[[6130,2444.711,1156.772]", "[[6125.39,2445.56,1168.99]")
    text = new.read_text()
    text = text.replace("PERS pose pCorr:=[[0,0,0],[1,0,0,0]];",
                        "PERS pose pShift:=[[0,0,5],[1,0,0,0]];")
    new.write_text(text)
    r = diff_files(load(CELL), load(new))
    assert [c["name"] for c in r["changed"]] == ["wobjSpec"]
    c = r["changed"][0]
    assert c["changes"] == ["value"]
    assert c["dx"] == pytest.approx(-4.61) and c["dz"] == pytest.approx(12.218)
    assert {"dx", "dy", "dz", "da", "db", "dc", "angle", "dist", "dt_mean", "group"} <= c.keys()
    assert [a["name"] for a in r["added"]] == ["pShift"]
    assert [a["name"] for a in r["removed"]] == ["pCorr"]
    assert r["unchanged"] == 17
    assert main(["diff", str(CELL), str(new), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert {"changed", "added", "removed"} <= d.keys()
    assert main(["diff", str(CELL), str(new)]) == 0
    out = capsys.readouterr().out
    assert "~ wobjSpec" in out and "+ pShift" in out and "- pCorr" in out


def test_two_files_float32_noise_and_equivalent_forms_unchanged(tmp_path):
    # 1156.772 and 1156.77200001 are the same float32; q and -q the same rotation;
    # names match case-insensitively
    new = edited(tmp_path, "noise", "[[6130,2444.711,1156.772],[0.690346,0.153046,-0.153046,0.690346]]",
                 "[[6130.0000001,2444.711,1156.77200001],[-0.690346,-0.153046,0.153046,-0.690346]]")
    new.write_text(new.read_text().replace("wobjTable", "WOBJTABLE"))
    r = diff_files(load(CELL), load(new))
    assert r["changed"] == [] and r["added"] == [] and r["removed"] == []
    # a real change at the written precision is seen
    moved = edited(tmp_path, "moved", "1156.772]", "1156.773]")
    assert [c["name"] for c in diff_files(load(CELL), load(moved))["changed"]] == ["wobjSpec"]


def test_two_files_flags_and_labels(tmp_path):
    new = edited(tmp_path, "flags", "wobjPlain:=[FALSE,TRUE,", "wobjPlain:=[TRUE,TRUE,")
    c = diff_files(load(CELL), load(new))["changed"]
    assert [(x["name"], x["changes"]) for x in c] == [("wobjPlain", ["reference", "robhold"]),
                                                      ("wobjPlain.oframe", ["robhold"])]
    kuka = edited(tmp_path, "label", 'BASE_NAME[1,]="table"', 'BASE_NAME[1,]="table_2"', REFS)
    c = diff_files(load(REFS), load(kuka))["changed"]
    assert [(x["name"], x["changes"]) for x in c] == [("BASE_DATA[1]", ["label"])]


def test_kuka_two_files(tmp_path):
    new = edited(tmp_path, "kuka", "Z 1156.772,A 90.0000,B -25.0000,C 0.0}",
                 "Z 1168.990,A 90.5290,B -24.4760,C -0.3130}", REFS)
    c = api.diff_files(REFS, new)["changed"]
    assert len(c) == 1 and c[0]["name"] == "BASE_DATA[7]" and c[0]["label"] == "spec_base"
    assert c[0]["dz"] == pytest.approx(12.218) and c[0]["dc"] == pytest.approx(-0.313)


def test_textconv_stable(tmp_path, capsys):
    cf = load(CELL)
    text = textconv(cf)
    head = text.split("# ucsio: the file\n")[0].splitlines()
    assert len(head) == 1 + len(cf.frames)
    assert "wobjSpec wobjdata ref=world x=6130 y=2444.711 z=1156.772 " \
           "q1=0.690346 q2=0.153046 q3=-0.153046 q4=0.690346" in text
    assert text.endswith(cf.document.text.replace("\r\n", "\n"))
    # no positions in the frame lines: inserting a comment line changes none of them
    moved = edited(tmp_path, "moved", "MODULE PatchCell\n", "MODULE PatchCell\n    ! reviewed\n")
    assert textconv(load(moved)).split("# ucsio: the file")[0] == text.split("# ucsio: the file")[0]
    assert "label='spec_base'" in frame_line(load(REFS).frame("spec_base"))
    assert main(["diff", "--textconv", str(CELL)]) == 0
    assert capsys.readouterr().out == text
    # not a controller file: passed through
    other = tmp_path / "notes.txt"
    other.write_text("hello\n")
    assert main(["diff", "--textconv", str(other)]) == 0
    assert capsys.readouterr().out == "hello\n"


def test_git_seven_arguments(tmp_path, capsys):
    new = edited(tmp_path, "new", "[[6130,2444.711,1156.772]", "[[6125.39,2445.56,1168.99]")
    args = ["diff", "R1/cell.mod", str(CELL), "1" * 40, "100644", str(new), "2" * 40, "100644"]
    assert main(args) == 0
    out = capsys.readouterr().out
    assert out.startswith("ucsio diff a/R1/cell.mod b/R1/cell.mod")
    assert "~ wobjSpec" in out and "dt_mean 5.892" in out
    # added and removed files come as /dev/null
    assert main(["diff", "R1/cell.mod", "/dev/null", ".", ".", str(CELL), "1" * 40, "100644",
                 "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert len(d["added"]) == 19 and d["removed"] == [] and d["old"] is None
    assert main(["diff", "R1/cell.mod", str(CELL), "1" * 40, "100644", "/dev/null", ".", "."]) == 0
    assert "0 added, 19 removed" in capsys.readouterr().out
    # a file ucsio cannot read: a plain text diff, still exit 0
    junk = tmp_path / "junk.mod"
    junk.write_text("not rapid at all\n")
    assert main(["diff", "R1/junk.mod", "/dev/null", ".", ".", str(junk), "1" * 40, "100644"]) == 0
    out = capsys.readouterr().out
    assert "plain text diff" in out and "+not rapid at all" in out


def test_api_solution_forms(tmp_path):
    sol = write_solution(tmp_path, MEASURED)
    for form in (MEASURED, str(sol), sol, {"frame": MEASURED.as_dict()},
                 {"x": 6125.390, "y": 2445.560, "z": 1168.990, "a": 90.529, "b": -24.476,
                  "c": -0.313}):
        d = api.diff_frame(REFS, "spec_base", form)
        assert d["dt_mean"] == pytest.approx(5.892, abs=5e-4)
    shutil.copy(sol, tmp_path / "copy.json")


def test_per_axis_deltas_use_canonical_angles():
    from ucsio.review.diff import frame_delta
    from ucsio.geometry.frames import Pose
    # the same rotation written out of SPEC's ranges: no per-axis difference
    d = frame_delta(Pose.from_abc(1, 2, 3, 200, 100, -181), Pose.from_abc(1, 2, 3, 20, 80, -1))
    assert (d["da"], d["db"], d["dc"], d["angle"]) == pytest.approx((0, 0, 0, 0), abs=1e-9)


def test_two_file_review_shows_what_frame_values_cannot(tmp_path, capsys):
    import shutil
    src = FIXTURES / "patch" / "refs" / "$config.dat"
    old = tmp_path / "old.dat"
    shutil.copy(src, old)
    text = old.read_bytes()
    line = next(ln for ln in text.split(b"\n") if ln.startswith(b"BASE_DATA[1]="))
    # a rewrite within float32 noise is no frame change, but its text still shows
    noisy = tmp_path / "noisy.dat"
    noisy.write_bytes(text.replace(line, line.replace(b"{X ", b"{X 0000", 1)))
    assert main(["diff", str(old), str(noisy)]) == 0
    out = capsys.readouterr().out
    assert "no frame changed" in out and "lines changed beyond the frame values above" in out
    assert "+BASE_DATA[1]={X 0000" in out


# ------------------------------------------------------------- messages (issue 18, point 7)

def test_diff_of_a_folder_and_a_missing_path_names_the_missing_one(tmp_path, capsys):
    folder = tmp_path / "old"
    folder.mkdir()
    shutil.copy(CELL, folder / "cell.mod")
    missing = tmp_path / "missing"
    for args in ([folder, missing], [missing, folder], [CELL, missing]):
        assert main(["diff", *map(str, args)]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1, err
        assert f"{missing}: does not exist" in err and "both" not in err, err


KUKA_CELL = FIXTURES / "kuka" / "cell_config.dat"


@pytest.mark.parametrize("path,name,words", [
    (KUKA_CELL, "TOOL_DATA[5]", "outside 1…4"),
    (KUKA_CELL, "tool_data[0]", "outside 1…4"),
    (KUKA_CELL, "BASE_DATA[17]", "outside 1…4"),
    (FIXTURES / "abb" / "variants.mod", "tools{5}", "outside 1…2"),
])
def test_an_index_outside_the_table_is_named_not_a_nearest_name(tmp_path, capsys, path, name,
                                                                  words):
    sol = write_solution(tmp_path, MEASURED)
    for args in (["diff", str(path), "--frame", name, "--measured", str(sol)],
                 ["patch", str(path), "--frame", name, "--measured", str(sol)],
                 ["patch", str(path), "--frame", name, "--set", "1,2,3,0,0,0"]):
        assert main(args) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1, err
        assert words in err and "did you mean" not in err, err
    # a name that is merely mistyped still gets the nearest one
    assert main(["patch", str(path), "--frame", name.replace("[", "X[").replace("{", "X{"),
                 "--set", "1,2,3,0,0,0"]) == 2
    assert "did you mean" in capsys.readouterr().err


def test_corpus_tool_table_of_sixteen(tmp_path, capsys):
    from conftest import corpus_file
    cfg = corpus_file("kuka", "Zinkerreka__KRC__R1__System")
    sol = write_solution(tmp_path, MEASURED)
    assert main(["diff", str(cfg), "--frame", "TOOL_DATA[17]", "--measured", str(sol)]) == 2
    err = capsys.readouterr().err
    assert "TOOL_DATA[17]" in err and "outside 1…16" in err and "TOOL_DATA[7]" not in err


def test_two_file_and_git_diffs_show_a_kuka_label(tmp_path, capsys):
    new = edited(tmp_path, "kuka", "Z 1156.772,A 90.0000,B -25.0000,C 0.0}",
                 "Z 1168.990,A 90.5290,B -24.4760,C -0.3130}", REFS)
    assert main(["diff", str(REFS), str(new)]) == 0
    out = capsys.readouterr().out
    assert '~ BASE_DATA[7] "spec_base" (BASE_DATA): value changed' in out
    assert main(["diff", "$config.dat", str(REFS), "0" * 40, "100644", str(new), "1" * 40,
                 "100644"]) == 0
    assert '~ BASE_DATA[7] "spec_base" (BASE_DATA)' in capsys.readouterr().out
    # added and removed frames too; an ABB frame has no label and keeps its type alone
    gone = edited(tmp_path, "gone", "BASE_DATA[7]={X 6130.000,Y 2444.711,Z 1156.772,A 90.0000,"
                  "B -25.0000,C 0.0}\n", "", REFS)
    assert main(["diff", str(REFS), str(gone)]) == 0
    out = capsys.readouterr().out
    assert '- BASE_DATA[7] "spec_base" (BASE_DATA) removed' in out
    moved = edited(tmp_path, "abb", "[[6130,2444.711", "[[6131,2444.711")
    assert main(["diff", str(CELL), str(moved)]) == 0
    assert "~ wobjSpec (wobjdata): value changed" in capsys.readouterr().out
