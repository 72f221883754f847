"""Issue 19 point 7: the positions taught in a FANUC user frame
(`diff sysframe.va --frame UF2 --measured S.json --points`): the Cartesian
/POS positions whose group says UF : k, in the .ls programs of the backup
(the folder of the sysframe.va and below; another robot's tree left out),
each moved = |T_measured·p − T_simulated·p|, checked against numpy; joint
positions counted as skipped; other frames and groups not included."""
from __future__ import annotations

import json
import re
import subprocess
import sys

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from conftest import ROOT
from fanuc_cell import Cell, position, program
from ucsio import api
from ucsio.cli import main

JOINT = {"J1": 10, "J2": -20, "J3": 30, "J4": 0, "J5": -90, "J6": 0}


def cli(capsys, *args):
    code = main([str(a) for a in args])
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.fixture
def backup(tmp_path):
    """backup/ (sysframe.va, two programs, one in a subfolder, a log that
    shares the suffix) beside another robot's backup inside it."""
    c = Cell()
    root = tmp_path / "backup"
    (root / "sub").mkdir(parents=True)
    (root / "other").mkdir()
    (root / "sysframe.va").write_text(c.sysframe_text(), newline="")
    rng = np.random.default_rng(3)
    taught = [tuple(rng.uniform(-1500, 1500, 3)) + tuple(rng.uniform(-170, 170, 3))
              for _ in range(6)]
    a = [position(1, [(1, 2, 3, taught[0])], comment="APP"),
         position(2, [(1, 2, 3, taught[1])]),
         position(3, [(1, 2, 3, JOINT)], comment="HOME"),                 # skipped
         position(4, [(1, 1, 3, taught[2])]),                             # UF1: not UF2's
         position(5, [(1, 1, 1, taught[3]), (2, 2, 1, {"J1": -100})]),    # GP2 in UF2: group 2's
         re.sub(r"Z = +[-0-9.]+", "Z = ********", position(6, [(1, 2, 3, taught[4])]))]
    (root / "prog_a.ls").write_text(program("PROG_A", a), newline="")
    (root / "sub" / "PROG_B.LS").write_text(
        program("PROG_B", [position(7, [(1, 2, 0, taught[5])])]), newline="")
    (root / "errall.ls").write_text("ERRALL.LS   Robot Name ROBOT\n\n")
    (root / "other" / "SYSFRAME.VA").write_text(c.sysframe_text(), newline="")
    (root / "other" / "prog_c.ls").write_text(
        program("PROG_C", [position(1, [(1, 2, 3, taught[0])])]), newline="")
    f = c.ucs
    a_, b_, c_ = Rotation.from_matrix(f[:3, :3]).as_euler("ZYX", degrees=True)
    sol = tmp_path / "s.json"
    sol.write_text(json.dumps({"frame": dict(zip("xyzabc", [*f[:3, 3], a_, b_, c_]))}))
    c.root, c.sol, c.taught_values = root, sol, taught
    return c


def expected_moved(cell, xyz):
    p = np.append(np.asarray(xyz, dtype=float), 1.0)
    return float(np.linalg.norm((cell.ucs @ p)[:3] - (cell.uf @ p)[:3]))


def test_diff_points_in_a_user_frame(backup, capsys):
    c = backup
    code, out, err = cli(capsys, "diff", c.root / "sysframe.va", "--frame", "UF2", "--measured",
                         c.sol, "--points", "--json")
    assert code == 0, err
    d = json.loads(out)
    got = {(r["name"], r["file"].replace("\\", "/").rsplit("/", 1)[-1]): r for r in d["points"]}
    assert sorted(got) == [("P[1]", "prog_a.ls"), ("P[2]", "prog_a.ls"), ("P[7]", "PROG_B.LS")]
    for (name, _), row in got.items():
        k = {"P[1]": 0, "P[2]": 1, "P[7]": 5}[name]
        assert abs(row["moved"] - expected_moved(c, c.taught_values[k][:3])) < 1e-5
    assert got[("P[1]", "prog_a.ls")]["line"] == 17     # its GP1: line (7 head lines, /MN of 6)
    pm = d["points_moved"]
    assert pm["count"] == 3 and pm["max"] == max(r["moved"] for r in d["points"])
    assert d["points_skipped"] == 1
    assert any("P[6] has no complete X Y Z W P R" in w for w in d["points_warnings"])
    # the text says how many were skipped
    code, out, err = cli(capsys, "diff", c.root / "sysframe.va", "--frame", "uf2", "--measured",
                         c.sol, "--points")
    assert "taught points in UF2: 3" in out
    assert "1 joint position taught in UF2 skipped" in out


def test_group_2_and_a_tool_frame(backup, capsys):
    c = backup
    code, out, err = cli(capsys, "diff", c.root / "sysframe.va", "--frame", "UF2@2",
                         "--measured", c.sol, "--points", "--json", "--tolerance", "1e6")
    d = json.loads(out)
    assert d["points"] == [] and d["points_skipped"] == 1      # P[5]'s GP2, joint values
    code, out, err = cli(capsys, "diff", c.root / "sysframe.va", "--frame", "UT3",
                         "--measured", c.sol, "--points", "--json", "--tolerance", "1e6")
    d = json.loads(out)
    assert d["points"] == [] and "not a user frame" in d["points_warnings"][0]


def test_api_and_working_points(backup):
    c = backup
    tp = api.taught_points(c.root / "sysframe.va", "UF2", c.sol)
    assert tp.points_moved["count"] == 3 and tp.points_skipped == 1
    d = api.diff_frame(c.root / "sysframe.va", "UF2", c.sol, points=True)
    assert d.points_skipped == 1 and d.points_moved["worst"] == tp.points_moved["worst"]


def test_the_points_path_imports_no_numpy_scipy_or_lark(backup, tmp_path):
    probe = ("import sys, io, contextlib\nfrom ucsio.cli import main\n"
             "with contextlib.redirect_stdout(io.StringIO()):\n    code = main(sys.argv[1:])\n"
             "print(code, sorted(m for m in ('numpy', 'scipy', 'lark') if m in sys.modules))")
    import os
    env = dict(os.environ, UCSIO_CACHE_DIR=str(tmp_path / "cache"),
               PYTHONPATH=str(ROOT / "src"))
    args = ["diff", backup.root / "sysframe.va", "--frame", "UF2", "--measured", backup.sol,
            "--points"]
    for _ in range(2):          # the first run builds the grammars' caches
        res = subprocess.run([sys.executable, "-c", probe, *map(str, args)],
                             capture_output=True, text=True, env=env, check=True)
    assert res.stdout.split()[0] == "0" and res.stdout.strip().endswith("[]"), res.stdout
