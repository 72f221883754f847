"""Issue 21 point 6: every command's --json output and SOLUTION.json validate
against the JSON Schemas shipped in docs/schema/, carry schema_version, and
a SOLUTION.json from a newer schema is refused while one without the key
(older ucsio) is still read.

The outputs are real: each command run on the demo's cells (both vendors; a
solve accepted, one rejected, a TCP solved, one with working points), the
taught-point fixtures, the synthetic fleet, two backups, the corpus, and
the error object."""
from __future__ import annotations

import contextlib
import importlib.util
import io
import json
import os
import shutil

import pytest
from jsonschema import Draft202012Validator

from conftest import CORPUS, FIXTURES, ROOT
from ucsio.cli import main
from ucsio.output import SCHEMA_VERSION

SCHEMAS = ROOT / "docs" / "schema"
NAMES = ("frames", "check", "finding", "solve", "solution", "diff-frame", "diff-files",
         "diff-backups", "patch", "program", "measurement-program", "batch", "plan", "demo",
         "error")


def schema(name: str) -> dict:
    return json.loads((SCHEMAS / f"{name}.json").read_text())


def validate(name: str, doc) -> None:
    Draft202012Validator(schema(name)).validate(doc)


def run(*args, cwd=None) -> tuple[int, str]:
    out, err = io.StringIO(), io.StringIO()
    here = os.getcwd()
    try:
        if cwd is not None:
            os.chdir(cwd)
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main([str(a) for a in args])
    finally:
        os.chdir(here)
    return code, out.getvalue()


def doc_of(*args, cwd=None, codes=(0,)):
    code, out = run(*args, cwd=cwd)
    assert code in codes, (args, code, out)
    return json.loads(out)


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    out = tmp_path_factory.mktemp("demo")
    assert run("demo", "--out", out)[0] == 0
    r02 = out / "R02_abb"
    (r02 / "working.csv").write_text("point,x,y,z\nfar_left,2600,1400,0\nfar_right,2600,-300,0\n"
                                     "above,1200,400,900\n")
    (r02 / "corner.csv").write_text("point,laser_x,laser_y,laser_z\nM1,0,0,0\nM8,480,90,55\n"
                                    "M6,250,620,140\nM4,0,800,20\nR1,150,300,0\nR2,400,500,80\n")
    (r02 / "candidates.csv").write_text("point,x,y,z\nM2,1200,0,12\nM3,1200,800,0\n"
                                        "M5,600,400,300\nM7,950,180,220\n")
    return out


def requires(name: str, doc, *path) -> None:
    """Without the key at ``path``, or with a value of the wrong type there,
    ``doc`` no longer validates: the schema holds the key scripts rely on."""
    from copy import deepcopy

    from jsonschema import ValidationError
    for change in ("delete", "retype"):
        broken = deepcopy(doc)
        *parents, key = path
        target = broken
        for p in parents:
            target = target[p]
        if change == "delete":
            del target[key]
        else:   # a text where a number, list or object goes; a number where a text goes
            target[key] = 7 if isinstance(target[key], str) else "7"
        with pytest.raises(ValidationError):
            validate(name, broken)


def check_version(doc) -> None:
    assert doc["schema_version"] == SCHEMA_VERSION == 1
    assert next(iter(doc)) == "schema_version"          # first, where a person looks


# ------------------------------------------------------------------ the schemas

def test_every_schema_is_draft_2020_12_and_valid():
    for name in NAMES:
        s = schema(name)
        assert s["$schema"] == "https://json-schema.org/draft/2020-12/schema"
        Draft202012Validator.check_schema(s)
    assert sorted(p.stem for p in SCHEMAS.glob("*.json")) == sorted(NAMES)


def test_shared_definitions_are_the_same_in_every_schema():
    """Each schema stands alone (no references between files), so the pieces
    they share are written out in each: they must not drift apart."""
    seen: dict[str, dict] = {}
    for name in NAMES:
        for key, definition in schema(name).get("$defs", {}).items():
            assert seen.setdefault(key, definition) == definition, (name, key)
    assert schema("solution")["allOf"] == schema("solve")["allOf"]


def test_the_schemas_require_spec_s_keys():
    """SPEC's "JSON keys that scripts rely on": a document missing one fails."""
    frames = schema("frames")["$defs"]["frame"]
    assert set("name file line vendor type parent x y z a b c q".split()) <= set(frames["required"])
    assert frames["then"]["required"] == ["group", "w", "p", "r"]        # FANUC items
    solve = schema("solve")["$defs"]["solve"]
    assert set("frame points n_points n_used rms mean max accepted".split()) <= \
        set(solve["required"])
    assert {"name", "residual", "loo_residual", "used"} <= \
        set(schema("solve")["$defs"]["solve_point"]["required"])
    delta = schema("diff-frame")["$defs"]["delta"]
    assert set("dx dy dz da db dc angle dist dt_mean group pass".split()) == set(delta["required"])
    batch = schema("batch")
    assert {"name", "accepted", "e", "dt_mean", "group", "pass", "frame"} <= \
        set(batch["properties"]["entries"]["items"]["required"])
    assert {"total", "passed", "rejected", "errors", "success_rate", "groups"} <= \
        set(batch["properties"]["summary"]["required"])
    plan = schema("plan")
    assert {"working_points", "worst", "verdict", "suggest"} <= set(plan["required"])
    for name in NAMES:
        if name != "finding":
            assert "schema_version" in json.dumps(schema(name)["required"]
                                                  if "required" in schema(name) else
                                                  schema(name)), name


def test_a_document_without_a_required_key_fails():
    from jsonschema import ValidationError
    good = {"schema_version": 1, "error": {"file": None, "line": None, "col": None,
                                           "message": "m"}}
    validate("error", good)
    for broken in ({"error": good["error"]}, {**good, "schema_version": 2},
                   {**good, "error": {"message": "m"}}):
        with pytest.raises(ValidationError):
            validate("error", broken)


# ------------------------------------------------------------------ real outputs

def test_frames(demo):
    for args in (["R01_kuka/$config.dat"], ["R02_abb/CellR02.mod"], ["."],
                 [FIXTURES / "abb" / "variants.mod", FIXTURES / "kuka" / "variants.dat"]):
        d = doc_of("frames", *args, "--json", cwd=demo)
        check_version(d)
        validate("frames", d)
        assert d["frames"]
    for key in ("name", "file", "line", "vendor", "type", "q"):
        requires("frames", d, "frames", 0, key)
    requires("frames", d, "schema_version")
    # many files, one missing: the others listed, the missing one in errors (exit 2)
    d = doc_of("frames", "R01_kuka/$config.dat", "missing.mod", "--json", cwd=demo, codes=(2,))
    validate("frames", d)
    assert d["errors"][0]["file"] == "missing.mod"


@pytest.mark.parametrize("vendor", ["abb", "kuka", "fanuc"])
def test_frames_and_check_of_the_corpus(vendor, tmp_path):
    folder = CORPUS / vendor
    if not folder.is_dir():
        pytest.skip(f"{folder} is absent: the shared corpus is not beside this checkout")
    code, out = run("frames", folder, "--json")
    d = json.loads(out)
    validate("frames", d)
    assert code in (0, 2) and (d["frames"] or d["errors"])
    code, out = run("check", folder, "--json")
    validate("check", json.loads(out))
    code, out = run("check", folder, "--output-format", "json-lines")
    for line in out.splitlines():
        validate("finding", json.loads(line))


def test_check(demo):
    d = doc_of("check", ".", "--json", cwd=demo, codes=(0, 1))
    check_version(d)
    validate("check", d)
    bad = sorted((FIXTURES / "abb" / "bad").iterdir())
    d = doc_of("check", FIXTURES / "abb" / "variants.mod", *bad, "--json", codes=(1, 2))
    validate("check", d)
    assert d["errors"] and any(f["lints"] for f in d["files"])


def test_solve_accepted_rejected_tcp_solved_and_working_points(demo, tmp_path):
    r01, r02, r03 = demo / "R01_kuka", demo / "R02_abb", demo / "R03_kuka"
    cases = [
        (r01, ["base3_points.csv", "--tool", "$config.dat:SMR_reflector"], (0,)),
        (r01, ["base3_points.csv", "--tool", "$config.dat:SMR_reflector", "--uncertainty", "20"],
         (0,)),
        (r01, ["base3_points.csv", "--tool", "$config.dat:SMR_reflector", "--min-points", "8"],
         (1,)),                                                     # rejected: too few left
        (r02, ["table_points.csv", "--tcp", "0,0,0"], (1,)),        # a wrong TCP, diagnosed
        (r02, ["table_points.csv", "--tool", "CellR02.mod:tReflector", "--at", "working.csv",
               "--gate", "at"], (0,)),
        (r03, ["--laser", "jig_points.txt", "--robot", "MEASURE.dat", "--config", "$config.dat",
               "--tcp", "solve", "--uncertainty", "10"], (0,)),
    ]
    seen = set()
    for cwd, args, codes in cases:
        d = doc_of("solve", *args, "--json", cwd=cwd, codes=codes)
        check_version(d)
        validate("solve", d)
        seen |= {("accepted", d["accepted"]), ("solved", d["tcp"]["solved"]),
                 ("diagnosis", "diagnosis" in d), ("at", "working_points" in d),
                 ("uncertainty", "uncertainty" in d)}
        # solve -o writes the same document: SOLUTION.json
        out = tmp_path / "s.json"
        assert run("solve", *args, "-o", out, cwd=cwd)[0] in codes
        written = json.loads(out.read_text())
        validate("solution", written)
        assert written == d
        for path in (["frame", "x"], ["frame", "q"], ["points", 0, "loo_residual"],
                     ["n_used"], ["rms"], ["accepted"]):
            if path != ["points", 0, "loo_residual"] or d["points"][0]["loo_residual"] is not None:
                requires("solve", d, *path)
    assert {("accepted", False), ("solved", True), ("diagnosis", True), ("at", True),
            ("uncertainty", True)} <= seen


def test_the_demo_s_solutions_are_solution_documents(demo):
    for cell in ("R01_kuka", "R02_abb", "R03_kuka"):
        d = json.loads((demo / cell / "solution.json").read_text())
        check_version(d)
        validate("solution", d)


def test_diff_one_frame_with_taught_points(demo, tmp_path):
    d = doc_of("diff", "$config.dat", "--frame", "weld_fixture_A", "--measured",
               "solution.json", "--json", cwd=demo / "R01_kuka")
    check_version(d)
    validate("diff-frame", d)
    for key in ("name", "simulated", "measured", "dx", "da", "angle", "dist", "dt_mean",
                "group", "pass"):
        requires("diff-frame", d, key)
    d = doc_of("diff", "CellR02.mod", "--frame", "wobjTable", "--measured", "solution.json",
               "--points", "--json", cwd=demo / "R02_abb")
    validate("diff-frame", d)
    assert d["points"] and all("at_95" in p for p in d["points"]) and d["worst"]
    # a KUKA tree's taught points, with the demo's covariance: at_95 at each one
    config = FIXTURES / "taught" / "kuka" / "KRC" / "R1" / "System" / "$config.dat"
    d = doc_of("diff", config, "--frame", "weld_fixture", "--measured",
               demo / "R01_kuka" / "solution.json", "--points", "--json", codes=(0, 1))
    validate("diff-frame", d)
    assert d["points_moved"]["count"] >= 3 and d["working_points"]
    requires("diff-frame", d, "points_moved", "count")
    requires("diff-frame", d, "points", 0, "moved")
    requires("diff-frame", d, "working_points", 0, "at_95")
    # a solution without covariance: the displacements alone
    bare = tmp_path / "bare.json"
    bare.write_text(json.dumps({"frame": {"x": 1501.0, "y": -249.0, "z": 600.5, "a": 30.5,
                                          "b": -2.4, "c": 1.0}}))
    d = doc_of("diff", config, "--frame", "weld_fixture", "--measured", bare, "--points",
               "--json", codes=(0, 1))
    validate("diff-frame", d)
    assert "working_points" not in d and d["points"]


def test_diff_two_files_and_git_s_driver(demo):
    for cell, name in (("R01_kuka", "$config.dat"), ("R02_abb", "CellR02.mod"),
                       ("R03_kuka", "$config.dat")):
        d = doc_of("diff", name, f"patched/{name}", "--json", cwd=demo / cell)
        check_version(d)
        validate("diff-files", d)
        assert d["changed"]
    # git's seven arguments: a file added (/dev/null before), and a pair it cannot read
    d = doc_of("diff", "CellR02.mod", "/dev/null", "0" * 40, "100644", "CellR02.mod",
               "1" * 40, "100644", "--json", cwd=demo / "R02_abb")
    validate("diff-files", d)
    assert d["added"] and not d["changed"] and not d["removed"]
    readme = ROOT / "README.md"
    d = doc_of("diff", "x.mod", readme, "0" * 40, "100644", readme, "1" * 40, "100644",
               "--json")
    validate("diff-files", d)
    assert set(d) == {"schema_version", "path", "error"}


def test_diff_two_backups(demo, tmp_path):
    old, new = tmp_path / "old", tmp_path / "new"
    shutil.copytree(demo / "R01_kuka", old)
    shutil.copytree(demo / "R01_kuka", new)
    shutil.copy(demo / "R01_kuka" / "patched" / "$config.dat", new / "$config.dat")
    shutil.copy(demo / "R02_abb" / "CellR02.mod", new / "CellR02.mod")
    (new / "base3_points.csv").unlink()
    (new / "patched" / "$config.dat").write_text("&ACCESS RVP\nDEFDAT $CONFIG\nBASE_DATA[1]={X 1")
    d = doc_of("diff", old, new, "--json", codes=(2,))
    check_version(d)
    validate("diff-backups", d)
    assert d["changed"] and d["files_added"] and d["errors"]


def test_patch(demo, tmp_path):
    for cell, name, frame in (("R01_kuka", "$config.dat", "weld_fixture_A"),
                              ("R02_abb", "CellR02.mod", "wobjTable"),
                              ("R03_kuka", "$config.dat", "jig_B"),
                              ("R03_kuka", "$config.dat", "SMR_adapter")):      # the solved TCP
        d = doc_of("patch", name, "--frame", frame, "--measured", "solution.json", "--json",
                   cwd=demo / cell)
        check_version(d)
        validate("patch", d)
        assert d["patch"]["changed"] and d["patch"]["written"] is None
    out = tmp_path / "out.dat"
    d = doc_of("patch", "$config.dat", "--frame", "weld_fixture_A", "--measured",
               "solution.json", "-o", out, "--json", cwd=demo / "R01_kuka")
    validate("patch", d)
    assert d["patch"]["written"] == str(out)


def test_program(demo, tmp_path):
    """UF3 from the ABB cell's measured frame, to stdout and to a file; UT2
    from the R03 cell's solved TCP."""
    d = doc_of("program", "solution.json", "--frame", "UF3", "--pr", "90", "--comment",
               "FIXTURE", "--json", cwd=demo / "R02_abb")
    check_version(d)
    validate("program", d)
    assert d["program"]["file"] is None and d["program"]["text"].endswith("/END\r\n")
    out = tmp_path / "SET_UT2.LS"
    d = doc_of("program", "solution.json", "--frame", "UT2@2", "--pr", "7", "-o", out, "--json",
               cwd=demo / "R03_kuka")
    validate("program", d)
    assert d["program"]["file"] == str(out) and d["program"]["group"] == 2
    assert d["program"]["warnings"]         # W, P, R written as 0


def test_batch_on_the_fleet(tmp_path):
    spec = importlib.util.spec_from_file_location("make_fleet",
                                                  FIXTURES / "fleet" / "make_fleet.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    mod.make_fleet(tmp_path, groups=(3, 2, 1, 1, 1), rejected=1)
    d = doc_of("batch", tmp_path / "manifest.toml", "--json", codes=(1,))
    check_version(d)
    validate("batch", d)
    for key in ("name", "accepted", "e", "dt_mean", "group", "pass", "frame"):
        requires("batch", d, "entries", 0, key)
    for key in ("total", "passed", "rejected", "errors", "success_rate", "groups"):
        requires("batch", d, "summary", key)
    requires("batch", d, "summary", "groups", 0, "std_e")
    statuses = {e["status"] for e in d["entries"]}
    assert {"pass", "rejected", "error", "over tolerance"} <= statuses


def test_plan(demo):
    r02 = demo / "R02_abb"
    for cwd, args, codes in (
            (r02, ["corner.csv", "--at", "working.csv", "--candidates", "candidates.csv",
                   "--threshold", "0.5"], (1,)),
            (r02, ["table_points.csv", "--at-taught", "CellR02.mod", "--frame", "wobjTable"],
             (0,)),
            (demo / "R03_kuka", ["jig_points.txt", "--robot", "MEASURE.dat", "--config",
                                 "$config.dat", "--tcp", "solve", "--history", ".."], (0,)),
            (demo / "R01_kuka", ["base3_points.csv"], (1,))):      # an uncalibrated robot
        d = doc_of("plan", *args, "--json", cwd=cwd, codes=codes)
        check_version(d)
        validate("plan", d)
        for key in ("working_points", "worst", "verdict", "suggest"):
            requires("plan", d, key)
        requires("plan", d, "worst", "at_95")
        requires("plan", d, "noise", "sigma")
        requires("plan", d, "noise", "source")
        if "tcp_at_95" in d or d["suggest"]["add"] is not None:
            requires("plan", d, "suggest", "add", "worst_after")


def test_demo():
    d = doc_of("demo", "--json")
    check_version(d)
    validate("demo", d)


def test_the_error_object(demo, tmp_path):
    for args, code in ((["frames", "missing.mod", "--json"], 2),
                       (["solve", "R01_kuka/base3_points.csv", "--json"], 2),       # no TCP
                       (["diff", "--json"], 2),                                     # usage
                       (["check", "missing.mod", "--output-format", "json"], 2)):
        got, out = run(*args, cwd=demo)
        assert got == code
        d = json.loads(out)
        check_version(d)
        validate("error", d)
    # a rejected solution refused: a failed gate, exit 1, the error object too
    sol = tmp_path / "rejected.json"
    assert run("solve", "R01_kuka/base3_points.csv", "--tool",
               "R01_kuka/$config.dat:SMR_reflector", "--min-points", "8", "-o", sol,
               cwd=demo)[0] == 1
    got, out = run("diff", "R01_kuka/$config.dat", "--frame", "weld_fixture_A", "--measured",
                   sol, "--json", cwd=demo)
    assert got == 1
    validate("error", json.loads(out))


# ------------------------------------------------------------------ reading it back

def test_a_solution_without_schema_version_is_read(demo, tmp_path):
    """Older ucsio wrote no schema_version: such a file still diffs and patches."""
    data = json.loads((demo / "R01_kuka" / "solution.json").read_text())
    del data["schema_version"]
    old = tmp_path / "old.json"
    old.write_text(json.dumps(data))
    new = doc_of("diff", "$config.dat", "--frame", "weld_fixture_A", "--measured",
                 "solution.json", "--json", cwd=demo / "R01_kuka")
    got = doc_of("diff", "$config.dat", "--frame", "weld_fixture_A", "--measured", old,
                 "--json", cwd=demo / "R01_kuka")
    assert got == new


@pytest.mark.parametrize("command", [["diff", "$config.dat", "--frame", "weld_fixture_A"],
                                     ["patch", "$config.dat", "--frame", "weld_fixture_A"],
                                     ["diff", "$config.dat", "--frame", "weld_fixture_A",
                                      "--points"]])
def test_a_solution_from_a_newer_schema_is_refused(demo, tmp_path, command, capsys):
    data = json.loads((demo / "R01_kuka" / "solution.json").read_text())
    data["schema_version"] = SCHEMA_VERSION + 1
    newer = tmp_path / "newer.json"
    newer.write_text(json.dumps(data))
    code, out = run(*command, "--measured", newer, "--json", cwd=demo / "R01_kuka")
    assert code == 2
    err = json.loads(out)["error"]
    assert err["file"] == str(newer)
    assert f"schema_version {SCHEMA_VERSION + 1}" in err["message"]
    assert "newer ucsio" in err["message"] and "upgrade" in err["message"]
    for bad in ("1", 0, True, 1.5):
        data["schema_version"] = bad
        newer.write_text(json.dumps(data))
        code, out = run(*command, "--measured", newer, "--json", cwd=demo / "R01_kuka")
        assert code == 2 and "schema_version" in json.loads(out)["error"]["message"]


# ------------------------------------------------------------------ FANUC

FANUC = FIXTURES / "fanuc"
UB = "irbzavalagit__UB10200_RBT01__"


def fanuc_backup(folder):
    """The corpus's UB10200 robot as a backup folder, with the binary files
    a real one has beside the ASCII ones (listed as not read)."""
    from conftest import corpus_file
    folder.mkdir(parents=True)
    for part, name in (("sysframe.va", "SYSFRAME.VA"), ("frame.dg", "FRAME.DG"),
                       ("posreg.va", "POSREG.VA"), ("td_gun1.ls", "TD_GUN1.LS")):
        shutil.copy(corpus_file("fanuc", UB + part), folder / name)
    (folder / "TD_GUN1.TP").write_bytes(b"\x00\x01TPBIN" * 10)
    (folder / "SYSFRAME.SV").write_bytes(b"\x00\x02SVBIN" * 10)
    return folder


def test_fanuc_frames_check_and_diffs(demo, tmp_path):
    files = [FANUC / "sysframe_comment.va", FANUC / "sysframe_mixed.va",
             FANUC / "program_frames.ls"]
    d = doc_of("frames", *files, "--json")
    validate("frames", d)
    fanuc = [f for f in d["frames"] if f["vendor"] == "fanuc"]
    assert {"UFRAME", "UTOOL"} <= {f["type"] for f in fanuc}
    assert all({"group", "w", "p", "r"} <= set(f) for f in fanuc)
    item = next(f for f in fanuc if f["x"] is not None)
    for key in ("group", "w", "p", "r"):            # SPEC's FANUC keys are required
        requires("frames", d, "frames", d["frames"].index(item), key)
    bad = sorted((FANUC / "bad").iterdir())
    d = doc_of("check", *files, *bad, "--json", codes=(1, 2))
    validate("check", d)
    assert d["errors"] and any(f.get("kind") for f in d["files"])
    d = doc_of("diff", files[0], files[1], "--json")
    validate("diff-files", d)
    sol = demo / "R01_kuka" / "solution.json"
    d = doc_of("diff", files[0], "--frame", "UF1", "--measured", sol, "--points", "--json",
               codes=(1,))                           # the demo frame is far from UF1
    validate("diff-frame", d)
    assert d["vendor"] == "fanuc" and d["points_warnings"]     # taught /POS not read yet
    # a reviewed copy of the listing: the patch document, saying the controller won't load it
    d = doc_of("patch", files[0], "--frame", "UF1", "--measured", sol, "--json")
    validate("patch", d)
    assert d["patch"]["vendor"] == "fanuc" and "does not load .va" in d["patch"]["warnings"][0]
    # a program frame with no literal values: the refusal is the error object
    code, out = run("patch", files[2], "--frame", "UT3", "--measured", sol, "--json")
    assert code == 2
    validate("error", json.loads(out))
    assert json.loads(out)["error"]["col"] == 8


def test_a_fanuc_backup_and_its_binaries(tmp_path):
    if not (CORPUS / "fanuc").is_dir():
        pytest.skip(f"{CORPUS / 'fanuc'} is absent: the shared corpus is not beside this checkout")
    old = fanuc_backup(tmp_path / "old")
    new = fanuc_backup(tmp_path / "new")
    text = (new / "SYSFRAME.VA").read_bytes()
    assert b"  X:  3495.600   Y:  5813.000" in text
    (new / "SYSFRAME.VA").write_bytes(text.replace(b"  X:  3495.600   Y:  5813.000",
                                                   b"  X:  3496.100   Y:  5813.000", 1))
    (new / "TD_GUN1.TP").write_bytes(b"\x00\x01TPBIN2" * 10)
    (new / "NUMREG.VR").write_bytes(b"\x00\x03VRBIN" * 10)
    for command in ("frames", "check"):
        d = doc_of(command, new, "--json")
        validate(command, d)
        assert sorted(os.path.basename(x["file"]) for x in d["not_read"]) == \
            ["NUMREG.VR", "SYSFRAME.SV", "TD_GUN1.TP"]
    d = doc_of("diff", old, new, "--json")
    validate("diff-backups", d)
    assert [c["name"] for c in d["changed"]] == ["UF1"]
    assert any(f.get("not_read") for f in d["files_added"])
    assert any(f.get("not_read") for f in d["files_changed"])
