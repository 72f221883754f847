"""Issue 21 point 5: the Python API does what the command line does. Each
api function runs the command's own code and returns its --json document:
``json.dumps(result)`` parses to what ``ucsio COMMAND --json`` prints, for
every command, on the demo's cells and the fixtures; keys are attributes;
every option of a command is a keyword of its function."""
from __future__ import annotations

import argparse
import ast
import json
import shutil

import pytest

from conftest import FIXTURES, ROOT
from test_schemas import run, validate
from ucsio import Pose, UcsioError, api
from ucsio.results import Result


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    out = tmp_path_factory.mktemp("demo")
    result = api.demo(out=out)
    assert result.ok and [c.cell for c in result.cells] == ["R01", "R02", "R03", "R04", "R05", "R06",
                                                                  "R07"]
    (out / "R02_abb" / "working.csv").write_text(
        "point,x,y,z\nfar_left,2600,1400,0\nfar_right,2600,-300,0\nabove,1200,400,900\n")
    return out


def same(result: Result, *args, cwd=None, codes=(0,)) -> dict:
    """``result`` is the document ``ucsio ARGS --json`` prints."""
    code, out = run(*args, "--json", cwd=cwd)
    assert code in codes, (args, code, out)
    cli = json.loads(out)
    assert json.loads(json.dumps(result)) == cli
    return cli


def test_frames_and_check(demo, monkeypatch):
    monkeypatch.chdir(demo)
    f = api.frames("R01_kuka/$config.dat")
    same(f, "frames", "R01_kuka/$config.dat")
    assert f.frames[0].name == f["frames"][0]["name"] and f.frames[0].set is True
    same(api.frames(["R01_kuka", "R02_abb/CellR02.mod"]), "frames", "R01_kuka",
         "R02_abb/CellR02.mod")
    assert api.frames(api.load("R02_abb/CellR02.mod")).frames == \
        api.frames("R02_abb/CellR02.mod").frames
    bad = [str(p) for p in sorted((FIXTURES / "abb" / "bad").iterdir())]
    files = [str(FIXTURES / "abb" / "variants.mod"), *bad]
    c = api.check(files)
    same(c, "check", *files, codes=(2,))
    assert c.ok is False and c.errors[0].code in ("syntax-error", "unreadable")
    # the findings are the json-lines output, line for line
    code, out = run("check", *files, "--output-format", "json-lines")
    assert [json.loads(line) for line in out.splitlines()] == c.findings
    for finding in c.findings:
        validate("finding", finding)
    silenced = api.check(files, ignore=[c.files[0].lints[0].code])
    same(silenced, "check", *files, "--ignore", c.files[0].lints[0].code, codes=(1, 2))
    with pytest.raises(UcsioError, match="no lint code"):
        api.check(files, ignore="not-a-code")


def test_solve_in_its_forms(demo, monkeypatch):
    r01, r02, r03 = demo / "R01_kuka", demo / "R02_abb", demo / "R03_kuka"
    monkeypatch.chdir(r01)
    sol = api.solve("base3_points.csv", tool="$config.dat:SMR_reflector", uncertainty=10)
    same(sol, "solve", "base3_points.csv", "--tool", "$config.dat:SMR_reflector",
         "--uncertainty", "10")
    # keys as attributes, typed objects inside, the old conveniences
    assert sol.accepted and sol.rms == sol["rms"] and sol.frame.x == sol.pose.x
    assert [p.name for p in sol.points if not p.used] == ["P5"]
    assert sol.points[4].excluded_by == "auto" and sol.uncertainty.samples == 10
    assert sol.precision.at_reach > 0 and sol.tcp.solved is False
    assert sol.solution.pose == sol.pose                   # the solver's own object
    assert sol.worst is None and sol.diagnosis is None     # declared keys it leaves out
    with pytest.raises(AttributeError):
        sol.no_such_key
    # a rejected dataset is a result, not an exception
    rejected = api.solve("base3_points.csv", tcp=(-20.67, 89.73, 33.44), min_points=8)
    same(rejected, "solve", "base3_points.csv", "--tcp", "-20.67,89.73,33.44", "--min-points",
         "8", codes=(1,))
    assert rejected.accepted is False and "too few points" in rejected.reason
    assert api.solve("base3_points.csv", tcp="-20.67,89.73,33.44") == \
        api.solve("base3_points.csv", tcp=[-20.67, 89.73, 33.44])
    monkeypatch.chdir(r02)
    at = api.solve("table_points.csv", tool="CellR02.mod:tReflector", at="working.csv",
                   gate="at", exclude=["M1"])
    same(at, "solve", "table_points.csv", "--tool", "CellR02.mod:tReflector", "--at",
         "working.csv", "--gate", "at", "--exclude", "M1")
    assert at.worst.name in {w.name for w in at.working_points}
    monkeypatch.chdir(r03)
    joint = api.solve(laser="jig_points.txt", robot="MEASURE.dat", config="$config.dat",
                      tcp="solve")
    same(joint, "solve", "--laser", "jig_points.txt", "--robot", "MEASURE.dat", "--config",
         "$config.dat", "--tcp", "solve")
    assert joint.tcp.solved and joint.tcp.std.z > 0 and joint.tcp_at_95 == joint.tcp.at_95
    # the same refusals as the command line
    for kwargs, message in ((dict(), "no TCP given"),
                            (dict(tcp=(1, 2)), "three"),
                            (dict(tcp=(0, 0, 0), tool="$config.dat:SMR_adapter"), "not both"),
                            (dict(tcp=(0, 0, 0), gate="at"), "--gate at"),
                            (dict(tcp=(0, 0, 0), uncertainty=1), "at least 2")):
        with pytest.raises(UcsioError, match=message):
            api.solve(laser="jig_points.txt", robot="MEASURE.dat", config="$config.dat",
                      **kwargs)


def test_a_saved_solution_is_solve_o_s_file(demo, monkeypatch, tmp_path):
    monkeypatch.chdir(demo / "R01_kuka")
    sol = api.solve("base3_points.csv", tool="$config.dat:SMR_reflector")
    api.save_solution(sol, tmp_path / "api.json")
    assert run("solve", "base3_points.csv", "--tool", "$config.dat:SMR_reflector", "-o",
               tmp_path / "cli.json")[0] == 0
    assert (tmp_path / "api.json").read_bytes() == (tmp_path / "cli.json").read_bytes()
    assert api.read_solution(tmp_path / "api.json") == sol.pose


def test_diff_frame_taught_points_files_and_backups(demo, monkeypatch, tmp_path):
    monkeypatch.chdir(demo / "R02_abb")
    sol = api.solve("table_points.csv", tool="CellR02.mod:tReflector")
    api.save_solution(sol, "mine.json")
    for solution in (sol, "mine.json", json.loads(open("mine.json").read())):
        d = api.diff_frame("CellR02.mod", "wobjTable", solution, points=True)
        same(d, "diff", "CellR02.mod", "--frame", "wobjTable", "--measured", "mine.json",
             "--points")
    assert d.passed is d["pass"] is True and d.dt_mean < 10 and d.points_moved.count == 2
    assert d.worst.at_95 > 0 and d.points[0].at_95 is not None
    tp = api.taught_points("CellR02.mod", "wobjTable", sol)
    assert {k: v for k, v in tp.items() if k != "schema_version"} == \
        {k: d[k] for k in tp if k != "schema_version"}
    assert set(tp) >= {"points", "points_moved", "points_warnings", "working_points", "worst"}
    # a Pose has no covariance: the displacements alone
    bare = api.taught_points("CellR02.mod", "wobjTable", sol.pose)
    assert "working_points" not in bare and bare.points_moved == d.points_moved
    same(api.diff_frame("CellR02.mod", "wobjTable", sol, tolerance=5), "diff", "CellR02.mod",
         "--frame", "wobjTable", "--measured", "mine.json", "--tolerance", "5", codes=(0, 1))
    with pytest.raises(UcsioError, match="--tolerance must be positive"):
        api.diff_frame("CellR02.mod", "wobjTable", sol, tolerance=0)
    files = api.diff_files("CellR02.mod", "patched/CellR02.mod")
    same(files, "diff", "CellR02.mod", "patched/CellR02.mod")
    assert files.changed[0].name == "wobjTable" and files.changed[0].passed
    old, new = tmp_path / "old", tmp_path / "new"
    shutil.copytree(demo / "R01_kuka", old)
    shutil.copytree(demo / "R01_kuka", new)
    shutil.copy(demo / "R01_kuka" / "patched" / "$config.dat", new / "$config.dat")
    backups = api.diff_backups(old, new)
    same(backups, "diff", old, new)
    assert backups.files_changed[0].path == "$config.dat" and backups.changed[0].path
    with pytest.raises(UcsioError, match="give two files or two backups"):
        api.diff_backups(old, "CellR02.mod")


def test_patch_and_save(demo, monkeypatch, tmp_path):
    monkeypatch.chdir(demo / "R03_kuka")
    for frame in ("jig_B", "SMR_adapter"):          # the base, and the tool's solved TCP
        out = api.patch("$config.dat", frame, "solution.json")
        same(out, "patch", "$config.dat", "--frame", frame, "--measured", "solution.json")
        assert out.changed and out.diff == out.patch.diff and out.warnings == []
    assert [c.component for c in out.patch.changes] == ["x", "y", "z"]
    target = tmp_path / "patched.dat"
    assert api.save(out, target) == str(target)
    assert out.patch.written == str(target)
    cli_target = tmp_path / "cli.dat"
    cli = json.loads(run("patch", "$config.dat", "--frame", "SMR_adapter", "--measured",
                         "solution.json", "-o", cli_target, "--json")[1])
    assert target.read_bytes() == cli_target.read_bytes()
    assert {k: v for k, v in out.patch.items() if k != "written"} == \
        {k: v for k, v in cli["patch"].items() if k != "written"}
    # a rejected solution is refused as the command refuses it (exit 1 there)
    rejected = api.solve(laser="jig_points.txt", robot="MEASURE.dat", config="$config.dat",
                         tcp="solve", min_points=11)
    with pytest.raises(UcsioError, match="rejected") as info:
        api.patch("$config.dat", "jig_B", rejected)
    assert info.value.exit_code == 1
    assert api.patch("$config.dat", "jig_B", rejected, force=True).changed
    # a Pose is written as given, in the frame's own reference
    pose = Pose.from_abc(1, 2, 3, 0, 0, 0)
    assert api.patch("$config.dat", "jig_B", pose).patch.new["x"] == 1


def test_batch(tmp_path):
    import importlib.util
    spec = importlib.util.spec_from_file_location("make_fleet",
                                                  FIXTURES / "fleet" / "make_fleet.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    mod.make_fleet(tmp_path, groups=(3, 2, 1, 1, 1), rejected=1)
    seen = []
    b = api.batch(tmp_path / "manifest.toml", csv=tmp_path / "fleet.csv",
                  progress=lambda stage, done, total: seen.append((stage, done, total)))
    same(b, "batch", tmp_path / "manifest.toml", codes=(1,))
    assert b.summary.total == len(b.entries) == seen[-1][2]
    assert (tmp_path / "fleet.csv").read_text().count("\n") == len(b.entries) + 1
    assert b.result.all_passed is False
    failed = [e for e in b.entries if e.status == "error"]
    assert failed and all(e.error and e.passed is False for e in failed)
    assert sum(g.count for g in b.summary.groups) == b.summary.total - \
        b.summary.errors - b.summary.rejected


def test_plan(demo, monkeypatch):
    monkeypatch.chdir(demo / "R02_abb")
    p = api.plan("table_points.csv", at_taught="CellR02.mod", frame="wobjTable")
    same(p, "plan", "table_points.csv", "--at-taught", "CellR02.mod", "--frame", "wobjTable")
    assert p.verdict == "pass" and p.worst.file == "CellR02.mod" and p.at == "CellR02.mod:wobjTable"
    p = api.plan("table_points.csv", at="working.csv", threshold=0.1)
    same(p, "plan", "table_points.csv", "--at", "working.csv", "--threshold", "0.1",
         codes=(1,))
    assert p.verdict == "fail" and p.suggest.add is not None
    monkeypatch.chdir(demo / "R03_kuka")
    p = api.plan("jig_points.txt", robot="MEASURE.dat", config="$config.dat", tcp="solve",
                 history="..")
    same(p, "plan", "jig_points.txt", "--robot", "MEASURE.dat", "--config", "$config.dat",
         "--tcp", "solve", "--history", "..")
    assert p.noise.source == "history" and p.noise.datasets >= 4     # the demo's solutions
    assert p.tcp_at_95 > 0 and p.orientation_span > 90


def test_demo_result_is_demo_json():
    same(api.demo(), "demo")


def test_results_are_dicts_that_print_as_json_and_copy(demo, monkeypatch):
    import copy
    import pickle
    monkeypatch.chdir(demo / "R01_kuka")
    sol = api.solve("base3_points.csv", tool="$config.dat:SMR_reflector")
    assert isinstance(sol, dict) and isinstance(sol.points[0], dict)
    assert copy.deepcopy(sol) == sol and pickle.loads(pickle.dumps(sol)) == sol
    assert type(sol.as_dict()["frame"]) is dict and sol.as_dict() == sol
    assert "rms" in dir(sol) and repr(sol).startswith("SolveResult({")
    assert api.as_pose(sol) == sol.pose


# ------------------------------------------------------------------ one code path

COMMAND_FUNCTIONS = {           # the command, its work, the api function
    "solve": ("ucsio.commands.solve", "solve", "solve"),
    "batch": ("ucsio.commands.batch", "batch", "batch"),
    "plan": ("ucsio.commands.plan", "plan_measurement", "plan"),
    "program": ("ucsio.commands.program", "make", "program"),
    "view": ("ucsio.commands.view", "view", "view"),
}
CLI_ONLY = {"json", "output", "no_progress", "command", "_module", "help"}


@pytest.mark.parametrize("command", sorted(COMMAND_FUNCTIONS))
def test_every_option_is_a_keyword_of_the_command_s_function_and_the_api(command):
    """run() hands the parsed options to the command's function by name, and
    api's function takes the same names: an option added to the command line
    and not to the API fails here."""
    import importlib
    import inspect
    from ucsio.cli import build_parser

    module, work, api_name = COMMAND_FUNCTIONS[command]
    parser = build_parser(command)
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    dests = {a.dest for a in sub.choices[command]._actions} - CLI_ONLY - \
        set(measure_options(sub.choices[command]))
    params = set(inspect.signature(getattr(importlib.import_module(module), work)).parameters)
    api_params = set(inspect.signature(getattr(api, api_name)).parameters)
    assert dests <= params, dests - params
    assert params - {"progress"} <= api_params | {"measurement"}, params - api_params


def measure_options(parser) -> list[str]:
    """The options of `program --measure` (their own group): another code
    path, programs.measure.make and api.measurement_program."""
    return [a.dest for g in parser._action_groups if g.title.startswith("the measurement program")
            for a in g._group_actions]


def test_every_measure_option_is_a_keyword_of_measure_and_the_api():
    import inspect
    from ucsio.cli import build_parser
    from ucsio.programs import measure
    parser = build_parser("program")
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    dests = set(measure_options(sub.choices["program"])) - {"measure"}   # the plan
    params = set(inspect.signature(measure.make).parameters)
    assert dests and dests <= params, dests - params
    assert params <= set(inspect.signature(api.measurement_program).parameters)


def test_no_command_imports_the_api():
    """ucsio.api and ucsio.results import typing: a command never loads them
    (tests/test_startup.py keeps the light commands' imports)."""
    for path in [ROOT / "src" / "ucsio" / "cli.py",
                 *(ROOT / "src" / "ucsio" / "commands").glob("*.py")]:
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                names = {node.module or ""} | {a.name for a in node.names}
                assert not names & {"api", "results", "ucsio.api", "ucsio.results"}, path
            elif isinstance(node, ast.Import):
                assert not {a.name for a in node.names} & {"ucsio.api", "ucsio.results"}, path


def test_fanuc_files_and_backups(tmp_path):
    from test_schemas import FANUC, fanuc_backup
    files = [str(FANUC / "sysframe_comment.va"), str(FANUC / "program_frames.ls")]
    f = api.frames(files)
    same(f, "frames", *files)
    uf = next(x for x in f.frames if x.name == "UF1")
    assert (uf.group, uf.w, uf.p, uf.r) == (1, uf.c, uf.b, uf.a) and uf.label == "FIXTURE_A"
    same(api.check(files), "check", *files, codes=(0, 1))
    if not (ROOT.parent / "shared" / "corpus" / "fanuc").is_dir():
        pytest.skip("the shared corpus (../shared/corpus/fanuc) is absent")
    old, new = fanuc_backup(tmp_path / "old"), fanuc_backup(tmp_path / "new")
    (new / "NUMREG.VR").write_bytes(b"\x00\x03VRBIN" * 10)
    listed = api.frames(new)
    same(listed, "frames", new)
    assert sorted(n.file.rsplit("/", 1)[-1] for n in listed.not_read) == \
        ["NUMREG.VR", "SYSFRAME.SV", "TD_GUN1.TP"]
    d = api.diff_backups(old, new)
    same(d, "diff", old, new)
    assert [x.not_read for x in d.files_added if x.path == "NUMREG.VR"][0]


def test_program(demo, monkeypatch, tmp_path):
    """api.program is ``ucsio program --json``; with ``output`` it writes the
    program there, as -o does."""
    monkeypatch.chdir(demo / "R02_abb")
    out = api.program("solution.json", "UF3", pr=90, comment="FIXTURE")
    same(out, "program", "solution.json", "--frame", "UF3", "--pr", "90", "--comment", "FIXTURE")
    sol = api.read_solution("solution.json")
    assert out.program.pose.x == pytest.approx(sol.x, abs=5e-4)
    assert "UFRAME[3:FIXTURE]=PR[90] ;\r\n" in out.text
    target = tmp_path / "SET_UF3.LS"
    written = api.program(api.solve("table_points.csv", tool="CellR02.mod:tReflector"), "UF3",
                          pr=90, output=target)
    assert written.program.file == str(target) and target.read_bytes() == \
        written.text.encode("ascii")
    with pytest.raises(UcsioError, match="TCP was solved"):
        api.program("solution.json", "UT1", pr=90)
