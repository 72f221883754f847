"""ucsio batch: manifest, batched solving, the group summary, CSV, patched
copies, on a synthetic fleet with known truth (fixtures/fleet/make_fleet.py,
generated into a temporary folder)."""
from __future__ import annotations

import csv
import hashlib
import importlib.util
import io
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from ucsio.fleet import batch as B
from ucsio.cli import main

ROOT = Path(__file__).resolve().parents[1]


def _load_make_fleet():
    spec = importlib.util.spec_from_file_location("make_fleet", ROOT / "fixtures/fleet/make_fleet.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


make_fleet = _load_make_fleet()


@pytest.fixture(scope="module")
def fleet(tmp_path_factory):
    dest = tmp_path_factory.mktemp("fleet")
    truth = make_fleet.make_fleet(dest)
    return dest, truth


def run_cli(args, capsys):
    code = main(args)
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture(scope="module")
def fleet_json(fleet):
    dest, truth = fleet
    buf = io.StringIO()
    old = sys.stdout
    sys.stdout = buf
    try:
        code = main(["batch", str(dest / "manifest.toml"), "--json"])
    finally:
        sys.stdout = old
    return code, json.loads(buf.getvalue())


# ---------------------------------------------------------------- the fleet

def test_fleet_is_big_and_spread(fleet):
    _, truth = fleet
    s = truth["summary"]
    assert s["total"] >= 100
    assert all(g["count"] > 0 for g in s["groups"])
    assert s["rejected"] > 0 and s["errors"] > 0
    vendors = {Path(e["controller"]).name for e in _manifest_entries(fleet[0])}
    assert vendors == {"cell.mod", "$config.dat"}


def _manifest_entries(dest):
    import tomllib
    return tomllib.loads((dest / "manifest.toml").read_text())["entry"]


def test_generator_is_deterministic(tmp_path):
    a = make_fleet.make_fleet(tmp_path / "a", groups=(3, 2, 1, 1, 1), rejected=1)
    b = make_fleet.make_fleet(tmp_path / "b", groups=(3, 2, 1, 1, 1), rejected=1)
    assert a == b
    for p in (tmp_path / "a").rglob("*"):
        if p.is_file() and p.name != "truth.json":
            assert p.read_bytes() == (tmp_path / "b" / p.relative_to(tmp_path / "a")).read_bytes()


def test_summary_matches_truth_exactly(fleet, fleet_json):
    _, truth = fleet
    code, data = fleet_json
    assert code == 1                        # some entries fail: a gate failed
    s, t = data["summary"], truth["summary"]
    for key in ("total", "passed", "rejected", "errors"):
        assert s[key] == t[key], key
    assert s["success_rate"] == t["success_rate"] == s["passed"] / s["total"]
    assert [g["group"] for g in s["groups"]] == [1, 2, 3, 4, 5]
    for g, tg in zip(s["groups"], t["groups"]):
        assert g["count"] == tg["count"]
        assert g["percent"] == tg["percent"]
    assert s["accepted"] == sum(g["count"] for g in s["groups"])


def test_entries_match_truth(fleet, fleet_json):
    _, truth = fleet
    _, data = fleet_json
    assert [e["name"] for e in data["entries"]] == [e["name"] for e in truth["entries"]]
    for e, t in zip(data["entries"], truth["entries"]):
        for key in ("name", "accepted", "e", "dt_mean", "group", "pass", "frame"):
            assert key in e
        assert e["pass"] == t["pass"], e["name"]
        assert e["accepted"] == t["accepted"], e["name"]
        if t["kind"] == "error":
            assert e["status"] == "error" and e["error"], e["name"]
            assert e["e"] is None and e["dt_mean"] is None and e["group"] is None
            continue
        assert "error" not in e
        if t["kind"] == "rejected":
            assert e["status"] == "rejected"
            assert e["group"] is None and e["dt_mean"] is None
            assert e["n_used"] < e["min_points"]
            continue
        assert e["group"] == t["group"], e["name"]
        assert e["dt_mean"] == pytest.approx(t["dt_mean"], abs=0.1)
        assert 0.02 < e["e"] < 0.2          # the noise the fleet was made with
        for k in "xyz":
            assert e["frame"][k] == pytest.approx(t["true"][k], abs=0.15)
        assert sorted(p["name"] for p in e["points"] if not p["used"]) == sorted(t["excluded"])


def test_every_way_to_fail_is_reported(fleet_json):
    _, data = fleet_json
    errors = {e["name"]: e for e in data["entries"] if e["status"] == "error"}
    msgs = " | ".join(e["error"] for e in errors.values())
    assert "no_such_file.csv" in msgs                        # missing measurement
    assert "not a number: '12.3.4'" in msgs                  # bad CSV, with line and column
    assert "R99" in msgs                                     # missing controller
    assert "one line" in msgs                                # collinear points
    assert "tool " in msgs                                   # unknown tool
    assert "not terminated" in msgs or "BROKEN" in msgs      # a controller that does not parse
    assert {e["stage"] for e in errors.values()} >= {"controller", "measurement", "tool", "solve"}


def test_group_statistics(fleet_json):
    _, data = fleet_json
    acc = [e for e in data["entries"] if e["accepted"]]
    for g in data["summary"]["groups"]:
        es = [e["e"] for e in acc if e["group"] == g["group"]]
        assert g["count"] == len(es)
        assert g["mean_e"] == pytest.approx(np.mean(es))
        assert g["std_e"] == pytest.approx(np.std(es, ddof=1))
    passing = [e for e in data["entries"] if e["pass"]]
    for k in "xyz":
        r = np.corrcoef([e["simulated"][k] for e in passing], [e["frame"][k] for e in passing])[0, 1]
        assert data["summary"]["correlation"][k] == pytest.approx(r)


def test_batch_solutions_equal_solve(fleet):
    """The batched solver gives what `ucsio solve` gives, entry by entry."""
    from ucsio.method import solve
    from ucsio.readers.measurement import read_measurement

    dest, _ = fleet
    res = B.run_batch(B.read_manifest(dest / "manifest.toml"))
    n = 0
    for r in res.entries:
        if r.solution is None or r.error:
            continue
        s = solve.solve(read_measurement(r.entry.measurement), r.solution.tcp,
                        threshold=r.entry.threshold, min_points=r.entry.min_points,
                        exclude=r.entry.exclude, no_exclusion=r.entry.no_exclusion)
        a = r.solution
        assert a.accepted == s.accepted and a.n_used == s.n_used
        assert [p.used for p in a.points] == [p.used for p in s.points]
        assert [p.excluded_by for p in a.points] == [p.excluded_by for p in s.points]
        assert a.pose.t == pytest.approx(s.pose.t, abs=1e-9)
        assert a.pose.q == pytest.approx(s.pose.q, abs=1e-12)
        assert a.mean == pytest.approx(s.mean, abs=1e-9)
        for p, q in zip(a.points, s.points):
            assert p.residual == pytest.approx(q.residual, abs=1e-9)
            if math.isfinite(q.loo_residual):
                assert p.loo_residual == pytest.approx(q.loo_residual, abs=1e-9)
        n += 1
    assert n >= 95


def test_solve_many_errors_like_solve():
    from ucsio.method import solve
    rng = np.random.default_rng(1)
    laser = rng.uniform(-300, 300, size=(7, 3))
    names = [f"P{i}" for i in range(7)]
    line = np.outer(np.linspace(-1, 1, 7), (300.0, 100.0, 10.0))
    ok = B.Dataset(names, laser, laser + 10.0, np.ones(7))
    hand_bad = B.Dataset(names, laser, laser + 10.0, np.ones(7), exclude=("P9",))
    collinear = B.Dataset(names, line, line + 5.0, np.ones(7))
    out = B.solve_many([ok, hand_bad, collinear])
    assert out[0].accepted and out[0].pose.t == pytest.approx((10.0, 10.0, 10.0))
    with pytest.raises(Exception) as exc:
        solve.solve_points(names, laser, laser + 10.0, exclude=("P9",))
    assert str(out[1]) == str(exc.value)
    with pytest.raises(Exception) as exc:
        solve.solve_points(names, line, line + 5.0)
    assert str(out[2]) == str(exc.value)


def test_one_horn_call_per_round_and_one_parse_per_file(fleet, monkeypatch):
    import ucsio.parsing.controller
    import ucsio.method.horn

    dest, truth = fleet
    calls = []
    real = ucsio.method.horn.leave_one_out
    monkeypatch.setattr(ucsio.method.horn, "leave_one_out",
                        lambda *a, **k: calls.append(len(a[0])) or real(*a, **k))
    loads = []
    real_load = ucsio.parsing.controller.load
    monkeypatch.setattr(ucsio.parsing.controller, "load", lambda p, *a, **k: loads.append(p) or real_load(p, *a, **k))
    res = B.run_batch(B.read_manifest(dest / "manifest.toml"))
    most_excluded = max(sum(p.excluded_by == "auto" for p in r.solution.points)
                        for r in res.entries if r.solution is not None)
    assert len(calls) == 1 + most_excluded <= 4             # rounds, not entries
    solved = sum(r.solution is not None for r in res.entries)
    assert calls[0] >= solved                               # every set's leave-one-out fits at once
    assert len(loads) == len(set(loads))                    # each controller file parsed once
    assert res.timings["controllers"] == len(set(r.entry.controller for r in res.entries))


def test_padding_budget_buckets_by_point_count(monkeypatch):
    from ucsio.method import solve
    monkeypatch.setattr(solve, "PAD_BUDGET", 10)
    rng = np.random.default_rng(2)
    data = []
    for n in (6, 7, 20):
        laser = rng.uniform(-300, 300, size=(n, 3))
        data.append(B.Dataset([f"P{i}" for i in range(n)], laser,
                              laser + 3.0 + rng.normal(scale=0.01, size=(n, 3)), np.ones(n)))
    out = B.solve_many(data)
    assert all(s.accepted for s in out)
    assert all(s.pose.t == pytest.approx((3, 3, 3), abs=0.05) for s in out)


def test_no_scipy_import(fleet):
    dest, _ = fleet
    code = ("import sys; from ucsio.cli import main; "
            f"rc = main(['batch', {str(dest / 'manifest.toml')!r}, '--json']); "
            "assert 'scipy' not in sys.modules, 'scipy imported'; sys.exit(0)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


# ---------------------------------------------------------------- output

def test_table_output(fleet, capsys):
    dest, truth = fleet
    code, out, err = run_cli(["batch", str(dest / "manifest.toml")], capsys)
    assert code == 1
    assert err == ""                                          # no progress bar: not a terminal
    assert "success rate" in out and "group" in out
    assert f"total {truth['summary']['total']}" in out


def test_progress_bar_only_on_a_terminal(fleet, capsys, monkeypatch):
    dest, _ = fleet

    class Tty(io.StringIO):
        def isatty(self):
            return True

    tty = Tty()
    monkeypatch.setattr(sys, "stderr", tty)
    main(["batch", str(dest / "manifest.toml"), "--json"])
    out = capsys.readouterr().out
    assert "[####" in tty.getvalue()
    json.loads(out)                                           # stdout stays pure JSON


def test_csv(fleet, fleet_json, tmp_path, capsys):
    dest, _ = fleet
    out = tmp_path / "fleet.csv"
    run_cli(["batch", str(dest / "manifest.toml"), "--csv", str(out)], capsys)
    rows = list(csv.DictReader(out.open(encoding="utf-8")))
    _, data = fleet_json
    assert len(rows) == len(data["entries"])
    for row, e in zip(rows, data["entries"]):
        assert row["name"] == e["name"] and row["status"] == e["status"]
        assert row["pass"] == ("true" if e["pass"] else "false")
        if e["dt_mean"] is None:
            assert row["dt_mean"] == ""
        else:
            assert float(row["dt_mean"]) == e["dt_mean"]
            assert int(row["group"]) == e["group"]
        assert (row["error"] != "") == (e["status"] == "error")


def test_all_pass_exits_0(fleet, tmp_path, capsys):
    dest, truth = fleet
    good = [t["name"] for t in truth["entries"] if t["pass"]][:12]
    entries = [e for e in _manifest_entries(dest) if e["name"] in good]
    text = ["[defaults]", "tcp = [-20.67, 89.73, 33.44]", ""]
    for e in entries:
        text.append("[[entry]]")
        for k, v in e.items():
            v = str(dest / v) if k in ("measurement", "controller") else v
            if k == "tool":
                v = str(dest / v)
            text.append(f"{k} = {json.dumps(v)}")
    m = tmp_path / "good.toml"
    m.write_text("\n".join(text) + "\n")
    code, out, _ = run_cli(["batch", str(m), "--json"], capsys)
    s = json.loads(out)["summary"]
    assert code == 0 and s["passed"] == s["total"] == 12 and s["success_rate"] == 1.0


def test_uncertainty(fleet, tmp_path, capsys):
    dest, truth = fleet
    name = next(t["name"] for t in truth["entries"] if t["pass"])
    e = next(e for e in _manifest_entries(dest) if e["name"] == name)
    m = tmp_path / "one.toml"
    m.write_text(f"[defaults]\ntcp = [-20.67, 89.73, 33.44]\n[[entry]]\nname = {json.dumps(name)}\n"
                 + "".join(f"{k} = {json.dumps(str(dest / v) if k in ('measurement', 'controller', 'tool') else v)}\n"
                           for k, v in e.items() if k != "name"))
    code, out, _ = run_cli(["batch", str(m), "--json", "--uncertainty", "200"], capsys)
    u = json.loads(out)["entries"][0]["uncertainty"]
    assert u["samples"] == 200
    assert set(u["std"]) >= {"x", "y", "z", "angle"} and set(u["ci95"]) >= {"x", "y", "z", "angle"}
    assert 0.005 < u["std"]["x"] < 0.2


# ---------------------------------------------------------------- patched copies

def _digest(folder: Path) -> dict:
    return {p: hashlib.sha256(p.read_bytes()).hexdigest() for p in folder.rglob("*") if p.is_file()}


def test_patch_dir_writes_copies_only(fleet, fleet_json, tmp_path, capsys):
    import ucsio

    dest, _ = fleet
    before = _digest(dest)
    out = tmp_path / "patched"
    code, text, _ = run_cli(["batch", str(dest / "manifest.toml"), "--json", "--patch-dir", str(out)],
                            capsys)
    assert _digest(dest) == before                           # originals untouched
    data = json.loads(text)
    assert data["summary"]["patch_errors"] == 0
    passing = [e for e in data["entries"] if e["pass"]]
    assert data["summary"]["patched"] == len(passing)
    for e in passing:
        copy = Path(e["patched"])
        assert copy.is_file() and out in copy.parents
        f = ucsio.load(copy).frame(e["frame_name"])
        for k in "xyz":
            assert getattr(f.pose, k) == pytest.approx(e["frame"][k], abs=0.0006)
    for e in data["entries"]:
        if not e["pass"]:
            assert "patched" not in e


# ---------------------------------------------------------------- the manifest

def _bad(tmp_path, capsys, text):
    m = tmp_path / "m.toml"
    m.write_text(text)
    code, out, err = run_cli(["batch", str(m)], capsys)
    assert code == 2 and out == ""
    assert err.startswith("ucsio: ") and str(m) in err and err.count("\n") == 1
    return err


ENTRY = 'measurement = "a.csv"\ncontroller = "c.mod"\nframe = "wobj1"\n'


def test_duplicate_name(tmp_path, capsys):
    err = _bad(tmp_path, capsys, f'[[entry]]\nname = "R01"\n{ENTRY}[[entry]]\nname = "r01"\n{ENTRY}')
    assert "duplicate entry name 'r01'" in err


@pytest.mark.parametrize("text, words", [
    ("[[entry]\nname = 'x'\n", "not valid TOML"),
    (f"[[entry]]\n{ENTRY}", "needs a name"),
    (f"[[entry]]\nname = ''\n{ENTRY}", "needs a name"),
    ("[defaults]\nname = 'x'\n", "unknown key 'name'"),
    ("[defaults]\ntcp = [0, 0, 0]\n", "no [[entry]]"),
    (f"[defaults]\nthreshold = -1\n[[entry]]\nname = 'x'\n{ENTRY}", "threshold must be positive"),
    (f"[defaults]\nmin_points = '6'\n[[entry]]\nname = 'x'\n{ENTRY}", "min_points"),
    (f"[defaults]\ntool = 'tool1'\n[[entry]]\nname = 'x'\n{ENTRY}", "FILE:NAME"),
    (f"[defaults]\ntcp = [0, 0, 0]\ntool = 'c.mod:t'\n[[entry]]\nname = 'x'\n{ENTRY}",
     "either tcp or tool"),
    (f"nonsense = 1\n[[entry]]\nname = 'x'\n{ENTRY}", "unknown top-level key"),
])
def test_bad_manifest(tmp_path, capsys, text, words):
    """Problems of the manifest as a whole stay exit 2, one line, nothing run."""
    assert words in _bad(tmp_path, capsys, text)


@pytest.mark.parametrize("text, words", [
    ("[[entry]]\nname = 'x'\nmeasurment = 'a.csv'\n", "unknown key 'measurment'"),
    (f"[[entry]]\nname = 'x'\ntcp = [1, 2]\n{ENTRY}", "tcp must be a list of three numbers"),
    (f"[[entry]]\nname = 'x'\ntcp = [1, 2, 3]\ntool = 'c.mod:t'\n{ENTRY}", "either tcp or tool"),
    (f"[[entry]]\nname = 'x'\ntool = 'tool1'\n{ENTRY}", "FILE:NAME"),
    (f"[[entry]]\nname = 'x'\nmin_points = 2\n{ENTRY}", "min_points"),
    (f"[[entry]]\nname = 'x'\nmin_points = '6'\n{ENTRY}", "min_points must be an integer"),
    (f"[[entry]]\nname = 'x'\nthreshold = -1\n{ENTRY}", "threshold must be positive"),
    ("[[entry]]\nname = 'x'\nmeasurement = 'a.csv'\n", "needs controller"),
    ("[[entry]]\nname = 'x'\nmeasurement = 'a.csv'\ncontroller = 'c.mod'\n", "needs frame"),
])
def test_bad_entry_is_an_entry_error(tmp_path, capsys, text, words):
    """A problem inside one [[entry]] makes that entry an error, counted;
    the other entries still run (SPEC: one entry's failure never stops the
    run)."""
    _abb_cell(tmp_path)
    (tmp_path / "m.toml").write_text(f"{_GOOD}\n{text}")
    code, out, err = run_cli(["batch", str(tmp_path / "m.toml"), "--json"], capsys)
    assert code == 1 and err == ""
    data = json.loads(out)
    good, bad = data["entries"]
    assert good["name"] == "good" and good["pass"]
    assert bad["name"] == "x" and bad["status"] == "error" and bad["stage"] == "manifest"
    assert words in bad["error"] and str(tmp_path / "m.toml") in bad["error"]
    s = data["summary"]
    assert (s["total"], s["passed"], s["errors"], s["success_rate"]) == (2, 1, 1, 0.5)
    # the text table, the CSV and the report carry it too
    code, out, _ = run_cli(["batch", str(tmp_path / "m.toml"), "--csv", str(tmp_path / "o.csv"),
                            "--report", str(tmp_path / "o.html")], capsys)
    assert code == 1 and words in out and "exit 1: 1 entry failed" in out
    rows = list(csv.DictReader((tmp_path / "o.csv").open()))
    assert rows[1]["status"] == "error" and words in rows[1]["error"]
    assert "error" in (tmp_path / "o.html").read_text()


def test_bad_entries_do_not_hide_duplicates(tmp_path, capsys):
    err = _bad(tmp_path, capsys, f"[[entry]]\nname = 'x'\nbogus = 1\n[[entry]]\nname = 'X'\n{ENTRY}")
    assert "duplicate entry name 'X'" in err


def test_missing_manifest(tmp_path, capsys):
    code, _, err = run_cli(["batch", str(tmp_path / "nope.toml")], capsys)
    assert code == 2 and "nope.toml" in err


def test_defaults_and_paths(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub/m.toml").write_text(
        "[defaults]\ntool = 'cells/r1.mod:tool1'\nthreshold = 2.0\ntolerance = 50\n"
        "exclude = ['P3']\n"
        f"[[entry]]\nname = 'a'\n{ENTRY}"
        f"[[entry]]\nname = 'b'\ntcp = [1, 2, 3]\nthreshold = 1.0\nexclude = []\n{ENTRY}"
        "[[entry]]\nname = 'c'\nmeasurement = '/abs/x.csv'\ncontroller = 'C:/x.mod'\nframe = 'f'\n"
        "tool = 'C:/x.mod:t'\n")
    m = B.read_manifest(tmp_path / "sub/m.toml")
    a, b, c = m.entries
    assert a.tool == f"{tmp_path / 'sub/cells/r1.mod'}:tool1" and a.tcp is None
    assert a.threshold == 2.0 and a.tolerance == 50.0 and a.exclude == ("P3",)
    assert a.measurement == str(tmp_path / "sub/a.csv")
    assert b.tool is None and b.tcp == (1.0, 2.0, 3.0) and b.threshold == 1.0 and b.exclude == ()
    assert c.measurement == "/abs/x.csv" and c.tool.endswith(":t")


# ---------------------------------------------------------------- summary math

def test_summarize_conventions():
    from types import SimpleNamespace as NS

    from ucsio.geometry.frames import Pose

    def res(group, e, passed=True, accepted=True, error=None, x=0.0):
        r = B.EntryResult(entry=None)
        r.solution = NS(accepted=accepted, mean=e) if error is None else None
        r.error = error
        if accepted and error is None:
            r.delta = {"group": group, "dt_mean": 1.0, "pass": passed}
            r.simulated = Pose.from_quat(x, 2 * x, 0.0, (1, 0, 0, 0))
            r.measured = Pose.from_quat(x + 1, 2 * x - 1, 0.0, (1, 0, 0, 0))
        return r

    rs = [res(1, 0.1, x=1), res(1, 0.3, x=2), res(2, 0.2, x=3), res(5, 0.5, passed=False),
          res(None, 0.4, accepted=False), res(None, None, accepted=False, error="boom")]
    s = B.summarize(rs)
    assert (s["total"], s["passed"], s["rejected"], s["errors"]) == (6, 3, 1, 1)
    assert s["success_rate"] == 0.5
    g = {x["group"]: x for x in s["groups"]}
    assert g[1]["count"] == 2 and g[1]["mean_e"] == pytest.approx(0.2)
    assert g[1]["std_e"] == pytest.approx(math.sqrt(0.02))          # sample std, n - 1
    assert g[2]["count"] == 1 and g[2]["std_e"] is None              # below 2: null
    assert g[3]["count"] == 0 and g[3]["mean_e"] is None
    assert g[5]["percent"] == pytest.approx(100 / 6)
    assert s["correlation"]["x"] == pytest.approx(1.0) and s["correlation"]["y"] == pytest.approx(1.0)
    assert s["correlation"]["z"] is None                             # no variation


def _abb_cell(folder: Path, *, sibling: bool = False, csv_name: str = "m.csv"):
    """cell.mod: wobj1 (user frame U in world, object frame [40,20,5]) and
    the exact points of a measurement of the object frame's true pose
    (m.csv) and of the user frame (u.csv). With ``sibling``, other.mod
    declares the same PERS (patch_frame refuses to patch one of them)."""
    from ucsio.geometry.frames import Pose

    U = Pose.from_abc(1000.0, 200.0, 300.0, 90.0, 0.0, 0.0)
    O_true = Pose.from_abc(50.0, 20.0, 5.0, 10.0, 0.0, 0.0)
    world = U.compose(O_true)
    q = ",".join(f"{v:.6f}" for v in U.q)
    decl = ("  PERS wobjdata wobj1 := [FALSE,TRUE,\"\",[[1000,200,300],[" + q + "]],"
            "[[40,20,5],[1,0,0,0]]];\n")
    (folder / "cell.mod").write_text("MODULE cell\n" + decl + "ENDMODULE\n")
    if sibling:
        (folder / "other.mod").write_text("MODULE other\n" + decl + "ENDMODULE\n")
    laser = [(0, 0, 0), (500, 0, 0), (0, 400, 0), (500, 400, 0), (0, 0, 200), (500, 400, 200)]
    lines = ["point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_q1,robot_q2,robot_q3,robot_q4"]
    for i, p in enumerate(laser):
        r = world.apply(p)
        lines.append(f"P{i + 1},{p[0]},{p[1]},{p[2]},{r[0]:.6f},{r[1]:.6f},{r[2]:.6f},1,0,0,0")
    (folder / csv_name).write_text("\n".join(lines) + "\n")
    lines = [lines[0]]   # the user frame itself, measured: points of U
    for i, p in enumerate(laser):
        r = U.apply(p)
        lines.append(f"P{i + 1},{p[0]},{p[1]},{p[2]},{r[0]:.6f},{r[1]:.6f},{r[2]:.6f},1,0,0,0")
    (folder / "u.csv").write_text("\n".join(lines) + "\n")
    return U, O_true


_GOOD = ("[[entry]]\nname = 'good'\nmeasurement = 'm.csv'\ncontroller = 'cell.mod'\n"
         "frame = 'wobj1.oframe'\ntcp = [0, 0, 0]\n")


def test_oframe_is_diffed_in_its_user_frame(tmp_path, capsys):
    """An ABB object frame is relative to its user frame: the measured UCS
    (robot world) is expressed there before the diff."""
    _abb_cell(tmp_path)
    (tmp_path / "m.toml").write_text(
        "[[entry]]\nname = 'o'\nmeasurement = 'm.csv'\ncontroller = 'cell.mod'\n"
        "frame = 'wobj1.oframe'\ntcp = [0, 0, 0]\n")
    code, out, _ = run_cli(["batch", str(tmp_path / "m.toml"), "--json"], capsys)
    e = json.loads(out)["entries"][0]
    assert code == 0 and e["pass"]
    assert (e["frame"]["x"], e["frame"]["y"], e["frame"]["z"]) == pytest.approx((50, 20, 5), abs=1e-5)
    assert e["frame"]["a"] == pytest.approx(10.0, abs=1e-6)
    assert e["dt_mean"] == pytest.approx(10.0 / 3, abs=1e-5)


# ---------------------------------------------------------------- acceptance findings

KUKA = ROOT / "src/ucsio/demo/data/R01_kuka"


def _tcp_base_manifest(tmp_path) -> Path:
    """An entry solved, then refused at the diff: BASE_TYPE #TCP (an external
    TCP base): e is None but n_used, rms, points are there."""
    cfg = json.dumps(str(KUKA / "$config.dat"))
    m = tmp_path / "m.toml"
    m.write_text(f"[[entry]]\nname = 'tcp base'\ncontroller = {cfg}\nframe = 'fixed_spindle'\n"
                 f"measurement = {json.dumps(str(KUKA / 'base3_points.csv'))}\n"
                 f"tool = {json.dumps(str(KUKA / '$config.dat') + ':TOOL_DATA[2]')}\n")
    return m


def test_failure_after_solve_in_every_output(tmp_path, capsys):
    m = _tcp_base_manifest(tmp_path)
    code, out, err = run_cli(["batch", str(m), "--report", str(tmp_path / "r.html"),
                              "--csv", str(tmp_path / "r.csv")], capsys)
    assert code == 1 and err == (f"wrote {tmp_path / 'r.csv'} (--csv)\n"
                                 f"wrote {tmp_path / 'r.html'} (--report)\n")
    assert "#TCP" in out and "exit 1: 1 entry failed" in out
    html = (tmp_path / "r.html").read_text()
    assert "#TCP" in html and "at the diff stage" in html
    row = next(csv.DictReader((tmp_path / "r.csv").open()))
    assert row["status"] == "error" and row["e"] == "" and int(row["n_used"]) > 0
    code, out, _ = run_cli(["batch", str(m), "--json"], capsys)
    e = json.loads(out)["entries"][0]
    assert e["stage"] == "diff" and e["e"] is None and e["n_used"] > 0 and e["rms"] is not None


def test_outputs_survive_any_missing_value(tmp_path):
    """Every output of one entry, with each of its values in turn missing."""
    from types import SimpleNamespace as NS

    from ucsio.commands.batch import render
    from ucsio.output import _clean
    from ucsio.fleet.report import render_report

    _abb_cell(tmp_path)
    (tmp_path / "m.toml").write_text(_GOOD)
    res = B.run_batch(B.read_manifest(tmp_path / "m.toml"), uncertainty=20)
    full = res.as_dict()
    entry = full["entries"][0]
    assert "uncertainty" in entry and "points" in entry
    variants = []
    for key in entry:
        for value in (None, "drop"):
            e = dict(entry)
            if value == "drop":
                del e[key]
            else:
                e[key] = None
            variants.append(e)
    for nested in ("frame", "simulated", "diff", "uncertainty"):
        for k in entry[nested]:
            variants.append(dict(entry, **{nested: dict(entry[nested], **{k: None})}))
    variants.append(dict(entry, points=[{k: None for k in p} for p in entry["points"]]))
    variants.append(dict(entry, points=[{} for _ in entry["points"]]))
    variants.append(dict(entry, uncertainty={"std": None}))
    variants.append({})
    sm = dict(full["summary"])
    sparse = {"groups": [{} for _ in range(5)], "correlation": None}
    for e in variants:
        render_report({"manifest": "m", "summary": sm, "entries": [e]})
        render_report({"manifest": "m", "summary": sparse, "entries": [e]})
    render_report({})

    # EntryResult: the text table and the CSV, with any combination of parts missing
    r0 = res.entries[0]
    parts = {"solution": [r0.solution, None, NS(n_points=None, n_used=None, rms=None, max=None,
                                                  mean=None, accepted=True, points=[],
                                                  uncertainty=None, tcp=None, precision=None)],
             "delta": [r0.delta, None], "measured": [r0.measured, None],
             "simulated": [r0.simulated, None], "error": [None, "boom"],
             "patch_error": [None, "refused"], "patched": [None, "x.mod"]}
    import itertools
    for combo in itertools.product(*parts.values()):   # 3 * 2**6 results
        r = B.EntryResult(entry=r0.entry, **dict(zip(parts, combo)))
        result = B.BatchResult(manifest=res.manifest, entries=[r, r0],
                               summary=B.summarize([r, r0]))
        render(result)
        B.csv_rows([r])
        render_report(_clean(result.as_dict()))


def test_refused_patch_is_shown(tmp_path, capsys):
    """patch_frame refuses (the PERS is also declared in a sibling module):
    the table, the summary lines, the exit line, the CSV and the report all
    say so, and no "written" line claims a copy."""
    _abb_cell(tmp_path, sibling=True)
    (tmp_path / "m.toml").write_text(
        _GOOD + "[[entry]]\nname = 'u'\nmeasurement = 'u.csv'\ncontroller = 'cell.mod'\n"
        "frame = 'wobj1'\ntcp = [0, 0, 0]\n")
    out_dir = tmp_path / "patched"
    code, out, err = run_cli(["batch", str(tmp_path / "m.toml"), "--patch-dir", str(out_dir),
                              "--csv", str(tmp_path / "o.csv"), "--report", str(tmp_path / "o.html")],
                             capsys)
    assert code == 1
    assert err.splitlines() == [f"wrote {tmp_path / 'o.csv'} (--csv)",       # messages only
                                f"wrote {tmp_path / 'o.html'} (--report)",
                                f"no patched copy written under {out_dir}"]
    assert not out_dir.exists() or not any(out_dir.rglob("*.mod"))
    lines = out.splitlines()
    for name in ("good ", "u "):
        row = next(ln for ln in lines if ln.startswith(name))
        assert " pass " in row and row.endswith("REFUSED")
    assert "success rate 100.0 %" in out                       # they did pass; the patch did not
    assert "patch errors (no patched copy written for these):" in out
    assert "  good: " + str(tmp_path / "cell.mod") in out and "other.mod" in out
    assert "  u: not written: the patch of entry 'good' in the same file was refused" in out
    assert "patched 0   patch errors 2" in out
    assert "wrote" not in out
    assert lines[-1] == "exit 1: 2 patched copies not written (patch errors above)"
    rows = list(csv.DictReader((tmp_path / "o.csv").open()))
    assert all(r["pass"] == "true" and r["patched"] == "" for r in rows)
    assert "also declared" in rows[0]["patch_error"] and "'good'" in rows[1]["patch_error"]
    html = (tmp_path / "o.html").read_text()
    assert 'id="patch-errors"' in html and html.count("patched copy NOT written") == 2
    assert 'data-key="patch_errors" data-value="2"' in html
    assert html.count('data-patch-error="') == 2


def test_written_patch_is_listed(tmp_path, capsys):
    _abb_cell(tmp_path)
    (tmp_path / "m.toml").write_text(_GOOD)
    out_dir = tmp_path / "patched"
    code, out, err = run_cli(["batch", str(tmp_path / "m.toml"), "--patch-dir", str(out_dir)], capsys)
    assert code == 0
    assert f"wrote 1 patched copy under {out_dir}:" in err     # messages on stderr
    assert f"  {out_dir / 'cell.mod'}" in err and (out_dir / "cell.mod").is_file()
    assert "patched 1   patch errors 0" in out and out.splitlines()[-1] == "exit 0: every entry passed (1)"


def test_oframe_uncertainty_in_user_frame_axes(tmp_path, capsys):
    """--uncertainty of an object frame is in the axes (and coordinates) of
    its ``frame``, the user frame: U turns 90 deg about z, so x and y swap."""
    from ucsio.method.solve import uncertainty

    U, O_true = _abb_cell(tmp_path)
    (tmp_path / "m.toml").write_text(
        _GOOD + "[[entry]]\nname = 'u'\nmeasurement = 'u.csv'\ncontroller = 'cell.mod'\n"
        "frame = 'wobj1'\ntcp = [0, 0, 0]\n")
    code, out, _ = run_cli(["batch", str(tmp_path / "m.toml"), "--json", "--uncertainty", "400"],
                           capsys)
    o, u = json.loads(out)["entries"]
    assert o["pass"] and u["pass"]
    assert o["uncertainty_axes"] == "uframe" and u["uncertainty_axes"] == "world"
    for k in "xyz":                             # ci95 brackets the frame's own coordinates
        lo, hi = o["uncertainty"]["ci95"][k]
        assert lo < o["frame"][k] < hi, k
        assert hi - lo < 1.0
    # the same points in world: std x of the user-frame result is std y of the world one
    import csv as _csv
    rows = list(_csv.DictReader((tmp_path / "m.csv").open()))
    laser = np.array([[float(r[f"laser_{a}"]) for a in "xyz"] for r in rows])
    robot = np.array([[float(r[f"robot_{a}"]) for a in "xyz"] for r in rows])
    w = uncertainty(laser, robot, n_samples=400)
    an, aw = o["uncertainty"]["analytical_std"], w["analytical_std"]
    assert an["x"] == pytest.approx(aw["y"], rel=1e-6)
    assert an["y"] == pytest.approx(aw["x"], rel=1e-6)
    assert an["z"] == pytest.approx(aw["z"], rel=1e-6)
    assert an["angle"] == pytest.approx(aw["angle"], rel=1e-6)
    assert abs(aw["x"] - aw["y"]) > 0.01 * aw["x"]     # the swap is visible
    assert o["uncertainty"]["std"]["angle"] == pytest.approx(w["std"]["angle"], rel=0.15)


@pytest.mark.parametrize("opt, value", [("--sigma-laser", "-0.01"), ("--sigma-robot", "nan"),
                                        ("--sigma-robot", "inf")])
def test_bad_sigma_fails_fast(tmp_path, capsys, opt, value):
    """Checked before the run: even when no entry gets as far as the Monte Carlo."""
    _abb_cell(tmp_path)
    (tmp_path / "m.toml").write_text(_GOOD.replace("m.csv", "missing.csv"))
    code, out, err = run_cli(["batch", str(tmp_path / "m.toml"), "--uncertainty", "10",
                              opt, value, "--report", str(tmp_path / "r.html")], capsys)
    assert code == 2 and out == "" and err.count("\n") == 1 and opt in err
    assert not (tmp_path / "r.html").exists()


def test_unjudged_three_point_set_is_rejected_as_solve_rejects_it(tmp_path, capsys):
    """With 3 points no leave-one-out residual exists: residuals over the
    threshold then reject the set, in batch exactly as in `ucsio solve`."""
    (tmp_path / "three.csv").write_text(
        "point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c\n"
        "A,0,0,0,1000,0,0,0,0,0\nB,500,0,0,1500,0,0,0,0,0\nC,0,500,0,1000,520,0,0,0,0\n")
    (tmp_path / "cell.mod").write_text(
        'MODULE cell\n  PERS wobjdata w:=[FALSE,TRUE,"",[[1000,0,0],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n'
        "ENDMODULE\n")
    (tmp_path / "m.toml").write_text("[defaults]\nmin_points = 3\n[[entry]]\nname = 'three'\n"
                                     "measurement = 'three.csv'\ncontroller = 'cell.mod'\nframe = 'w'\ntcp = [0, 0, 0]\n")
    code, out, _ = run_cli(["batch", str(tmp_path / "m.toml"), "--json"], capsys)
    data = json.loads(out)
    e = data["entries"][0]
    assert code == 1 and e["accepted"] is False and data["summary"]["rejected"] == 1
    code, out, _ = run_cli(["solve", str(tmp_path / "three.csv"), "--tcp", "0,0,0", "--min-points", "3", "--json"], capsys)
    assert code == 1 and json.loads(out)["accepted"] is False


# ---------------------------------------------------------------- rejection reasons

_THREE = ("point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c\n"
          "A,0,0,0,1000,0,0,0,0,0\nB,500,0,0,1500,0,0,0,0,0\nC,0,500,0,1000,520,0,0,0,0\n")


def _two_rejections(tmp_path):
    """'three': 3 points, residuals over the threshold, nothing to single out
    (n_used 3 >= min_points 3); 'few': 5 good points, 6 needed."""
    _abb_cell(tmp_path)
    (tmp_path / "three.csv").write_text(_THREE)
    (tmp_path / "cell.mod").write_text(
        'MODULE cell\n  PERS wobjdata w:=[FALSE,TRUE,"",[[1000,0,0],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n'
        "ENDMODULE\n")
    few = (tmp_path / "m.csv").read_text().splitlines()[:6]          # header + 5 points
    (tmp_path / "few.csv").write_text("\n".join(few) + "\n")
    (tmp_path / "m.toml").write_text(
        "[[entry]]\nname = 'three'\nmeasurement = 'three.csv'\ncontroller = 'cell.mod'\n"
        "frame = 'w'\ntcp = [0, 0, 0]\nmin_points = 3\n"
        "[[entry]]\nname = 'few'\nmeasurement = 'few.csv'\ncontroller = 'cell.mod'\nframe = 'w'\ntcp = [0, 0, 0]\n")


def test_rejection_reason_in_json_csv_and_report(tmp_path, capsys):
    """Each rejected entry says why: the solver's reason, not a guess that
    assumes too few points (here 'three' has 3 of 3 needed points)."""
    _two_rejections(tmp_path)
    code, out, _ = run_cli(["batch", str(tmp_path / "m.toml"), "--json", "--csv",
                            str(tmp_path / "o.csv"), "--report", str(tmp_path / "o.html")], capsys)
    three, few = json.loads(out)["entries"]
    assert code == 1 and three["status"] == few["status"] == "rejected"
    assert three["reason"].startswith("residuals over the threshold and no point can be singled out")
    assert "with 3 points used" in three["reason"]
    assert few["reason"] == "too few points: 5 used, at least 6 needed"

    with (tmp_path / "o.csv").open(encoding="utf-8") as fh:
        header = next(csv.reader(fh))
    assert "reason" in header
    rows = list(csv.DictReader((tmp_path / "o.csv").open(encoding="utf-8")))
    assert [r["reason"] for r in rows] == [three["reason"], few["reason"]]

    html = (tmp_path / "o.html").read_text(encoding="utf-8")
    assert "points left, at least" not in html          # the old, wrong wording
    assert "REJECTED: residuals over the threshold and no point can be singled out" in html
    assert "REJECTED: too few points: 5 used, at least 6 needed; measure again" in html
    assert html.count('data-reason="') == 2

    # an accepted entry has no reason: null in the JSON, empty in the CSV
    _abb_cell(tmp_path)
    (tmp_path / "m.toml").write_text(_GOOD)
    code, out, _ = run_cli(["batch", str(tmp_path / "m.toml"), "--json"], capsys)
    assert code == 0 and json.loads(out)["entries"][0]["reason"] is None


def test_rejected_solution_file_gives_its_reason(tmp_path, capsys):
    """diff/patch refuse a rejected SOLUTION.json with the reason it holds;
    a file without one gets the generic wording."""
    from ucsio.errors import UcsioError
    from ucsio.method.solution import load_solution, pose_from_json

    (tmp_path / "three.csv").write_text(_THREE)
    sol = tmp_path / "s.json"
    code, _, _ = run_cli(["solve", str(tmp_path / "three.csv"), "--tcp", "0,0,0", "--min-points", "3",
                          "-o", str(sol)], capsys)
    data = json.loads(sol.read_text())
    assert code == 1 and data["accepted"] is False and data["reason"]
    with pytest.raises(UcsioError) as exc:
        load_solution(sol)
    assert "residuals over the threshold and no point can be singled out" in str(exc.value)
    assert "too few points" not in str(exc.value) and str(sol) in str(exc.value)
    del data["reason"]
    with pytest.raises(UcsioError, match=r"^the dataset was rejected; measure again$"):
        pose_from_json(data)
    data["reason"] = "too few points: 4 used, at least 6 needed"
    with pytest.raises(UcsioError, match="rejected: too few points: 4 used"):
        pose_from_json(data)
    assert pose_from_json(data, allow_rejected=True).x == data["frame"]["x"]


# ---------------------------------------------------------------- not UTF-8

def test_manifest_not_utf8_is_exit_2(tmp_path, capsys):
    m = tmp_path / "m.toml"
    m.write_bytes(b"[[entry]]\nname = 'Stra\xdfe'\nmeasurement = 'm.csv'\n")     # cp1252
    with pytest.raises(B.UcsioError) as exc:
        B.read_manifest(m)
    assert exc.value.file == str(m) and exc.value.line == 2
    assert exc.value.message.startswith("not UTF-8 text: byte 0xdf")
    code, out, err = run_cli(["batch", str(m)], capsys)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert f"{m}:2: not UTF-8 text" in err and "Traceback" not in err


def test_solution_not_utf8_is_exit_2(tmp_path, capsys):
    from ucsio.method.solution import load_solution

    _abb_cell(tmp_path)
    s = tmp_path / "s.json"
    s.write_bytes(b'\xef\xbb\xbf{"note": "caf\xe9",\n "x": 1, "y": 2, "z": 3, "a": 0, "b": 0, "c": 0}')
    with pytest.raises(B.UcsioError) as exc:
        load_solution(s)
    assert exc.value.file == str(s) and exc.value.line == 1
    assert exc.value.message.startswith("not UTF-8 text: byte 0xe9")
    code, out, err = run_cli(["diff", str(tmp_path / "cell.mod"), "--frame", "wobj1",
                              "--measured", str(s)], capsys)
    assert code == 2 and f"{s}:1: not UTF-8 text" in err and "Traceback" not in err
    s.write_bytes(b'\xef\xbb\xbf{"x": 1, "y": 2, "z": 3, "a": 0, "b": 0, "c": 0}')   # a BOM is fine
    assert load_solution(s).x == 1.0


# ---------------------------------------------------------------- --patch-dir: parsing, races

def _two_frames_one_file(tmp_path):
    """cell.mod with two passing entries (the user frame and the object
    frame of wobj1) and an unrelated sibling module in the folder."""
    _abb_cell(tmp_path)
    (tmp_path / "other.mod").write_text(
        'MODULE other\n  PERS wobjdata wobj9 := [FALSE,TRUE,"",[[0,0,0],[1,0,0,0]],'
        "[[0,0,0],[1,0,0,0]]];\nENDMODULE\n")
    (tmp_path / "m.toml").write_text(
        _GOOD + "[[entry]]\nname = 'u'\nmeasurement = 'u.csv'\ncontroller = 'cell.mod'\n"
        "frame = 'wobj1'\ntcp = [0, 0, 0]\n")


def test_patch_dir_parses_each_file_once(tmp_path, monkeypatch):
    """The source and its sibling modules are parsed once (through the run's
    cache), and the combined copy once: no per-entry sibling or read-back parse."""
    import ucsio.vendors.abb.rapid

    _two_frames_one_file(tmp_path)
    parsed = []
    real = ucsio.vendors.abb.rapid.parse
    monkeypatch.setattr(ucsio.vendors.abb.rapid, "parse",
                        lambda doc, *a, **k: parsed.append(Path(doc.path).name) or real(doc, *a, **k))
    res = B.run_batch(B.read_manifest(tmp_path / "m.toml"), patch_dir=str(tmp_path / "out"))
    assert all(r.passed and r.patch_error is None for r in res.entries)
    copy = tmp_path / "out" / "cell.mod"
    assert {r.patched for r in res.entries} == {str(copy)}
    # source, combined copy; other.mod never names wobj1, so it cannot declare it: not parsed
    assert sorted(parsed) == ["cell.mod", "cell.mod"]
    assert res.timings["controllers"] == 1
    from ucsio.parsing.controller import load
    again = load(copy)
    for r in res.entries:
        assert again.frame(r.entry.frame).pose is not None
    # the run keeps its temporary state to itself
    assert all(not k.startswith("_") for r in res.entries for k in vars(r))


def test_patch_dir_combined_copy_is_verified(tmp_path, monkeypatch):
    """patch_frame no longer parses each frame's copy: the combined copy's
    read-back (verify.reads_back, through verify.verify) still guards the write."""
    import ucsio.review.verify as patcher

    _two_frames_one_file(tmp_path)
    monkeypatch.setattr(patcher, "reads_back", lambda frame, pose: False)
    res = B.run_batch(B.read_manifest(tmp_path / "m.toml"), patch_dir=str(tmp_path / "out"))
    assert all(r.patched is None and "reads back as" in r.patch_error for r in res.entries)
    assert not (tmp_path / "out" / "cell.mod").exists()


def test_patch_dir_refuses_a_source_changed_during_the_run(tmp_path, monkeypatch):
    """The copy holds the patched bytes of the source as it was read: if the
    source changed on disk since, the copy is not written (patch error)."""
    import ucsio.files as patcher

    _two_frames_one_file(tmp_path)
    src = tmp_path / "cell.mod"
    edited = src.read_bytes().replace(b"MODULE cell", b"MODULE cell2", 1)
    real = patcher.atomic_write

    def touch_then_write(path, data, *a, **k):
        src.write_bytes(edited)           # someone saves the source meanwhile
        return real(path, data, *a, **k)
    monkeypatch.setattr(patcher, "atomic_write", touch_then_write)
    res = B.run_batch(B.read_manifest(tmp_path / "m.toml"), patch_dir=str(tmp_path / "out"))
    assert all(r.passed and r.patched is None for r in res.entries)
    assert all("changed on disk since it was read" in r.patch_error for r in res.entries)
    assert not (tmp_path / "out" / "cell.mod").exists()
    assert not [p for p in (tmp_path / "out").iterdir() if p.name.endswith(".ucsio-tmp")]
    assert src.read_bytes() == edited and res.summary["patch_errors"] == 2
