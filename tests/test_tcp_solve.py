"""The TCP solved with the frame (ucsio.method.tcp_solve, ``solve --tcp solve``),
checked on synthetic truth: the UCS, the TCP and the flange poses are drawn
with scipy, the measurement gets SPEC's default noise (0.015 mm laser, 0.05
mm robot, per axis)."""
from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from ucsio.method import tcp_solve
from ucsio.cli import main
from ucsio.errors import UcsioError
from ucsio.geometry.arrays import rotation_angle_deg
from ucsio.method.measurement import Measurement
from ucsio.method.solve import solve

TCP = np.array([12.5, -30.25, 180.0])


def cell(seed, spread, n=8, noise=True, tcp=TCP, axes="ZYX", flat=False):
    """A measurement of n points: flange orientations a downward flange
    turned by up to +-spread deg about each of ``axes``."""
    rng = np.random.default_rng(seed)
    R_ucs = Rotation.from_euler("ZYX", rng.uniform(-60, 60, 3), degrees=True)
    t_ucs = rng.uniform(-1500, 1500, 3) + [2000, 0, 500]
    laser = rng.uniform(0, 1, (n, 3)) * [1000, 700, 0 if flat else 250]
    world = R_ucs.apply(laser) + t_ucs
    flange = np.tile(np.eye(4), (n, 1, 1))
    for i in range(n):
        R = Rotation.from_euler("ZYX", [180, 0, 180], degrees=True) * Rotation.from_euler(
            axes, rng.uniform(-spread, spread, len(axes)), degrees=True)
        flange[i, :3, :3] = R.as_matrix()
        flange[i, :3, 3] = world[i] - R.apply(tcp)
    if noise:
        laser = laser + rng.normal(0, 0.015, laser.shape)
        flange[:, :3, 3] += rng.normal(0, 0.05, (n, 3))
    meas = Measurement(path="synthetic", names=[f"P{i + 1}" for i in range(n)],
                       lines=list(range(2, n + 2)), laser=laser, flange=flange,
                       weights=np.ones(n), form="kuka", orientation=None)
    return meas, R_ucs, t_ucs


@pytest.mark.parametrize("seed", range(8))
def test_thirty_degrees_of_spread_gives_the_tcp_within_half_a_millimetre(seed):
    meas, R_ucs, t_ucs = cell(seed, 30)
    joint = tcp_solve.solve_joint(meas)
    fixed = solve(meas, TCP)                     # the TCP known exactly
    assert joint.accepted and joint.n_used == 8
    assert np.linalg.norm(np.array(joint.tcp) - TCP) < 0.5
    # the frame as good as the fixed-TCP solve claims for itself: within its
    # 95 % doubt at reach, and its orientation within 3 of its standard deviations
    assert np.linalg.norm(np.array(joint.pose.t) - t_ucs) <= fixed.precision["at_reach"]
    angle = float(rotation_angle_deg(np.array(joint.pose.matrix), R_ucs.as_matrix()))
    assert angle <= 3 * fixed.precision["angle_std"]
    d = joint.as_dict()["tcp"]
    assert d["solved"] is True and set(d["std"]) == {"x", "y", "z"}
    assert all(0 < d["std"][k] < 0.5 for k in "xyz")


@pytest.mark.parametrize("seed", range(12))
def test_two_degrees_is_rejected_never_returned_millimetres_off(seed):
    meas, _, _ = cell(seed, 2)
    joint = tcp_solve.solve_joint(meas)
    assert not joint.accepted
    assert "span" in joint.reason and "deg" in joint.reason and "turn the flange" in joint.reason
    span = joint.precision["orientation_span"]
    assert f"{span:.1f} deg" in joint.reason
    assert joint.precision["tcp_at_95"] > joint.threshold


def test_orientations_about_one_axis_leave_the_tcp_undetermined():
    meas, _, _ = cell(1, 40, axes="Z")
    joint = tcp_solve.solve_joint(meas)
    assert not joint.accepted and "fewer than two axes" in joint.reason


def test_exact_data_give_exact_answers():
    meas, R_ucs, t_ucs = cell(5, 25, noise=False)
    joint = tcp_solve.solve_joint(meas)
    np.testing.assert_allclose(joint.tcp, TCP, atol=1e-6)
    np.testing.assert_allclose(joint.pose.t, t_ucs, atol=1e-6)
    np.testing.assert_allclose(np.array(joint.pose.matrix), R_ucs.as_matrix(), atol=1e-9)
    assert joint.max < 1e-6


@pytest.mark.parametrize("flat", [False, True])
def test_linear_first_solution_is_exact_on_exact_data(flat):
    """Also for a flat fixture (every point on one plane): the first solution
    then uses the two directions the points spread in."""
    meas, _, _ = cell(6, 20, noise=False, flat=flat)
    x = tcp_solve.linear_tcp(meas.laser, meas.flange[:, :3, :3], meas.flange[:, :3, 3],
                             np.ones(8))
    np.testing.assert_allclose(x, TCP, atol=1e-6)
    assert np.linalg.norm(np.array(tcp_solve.solve_joint(meas).tcp) - TCP) < 1e-6


def test_leave_one_out_is_the_joint_fit_of_the_others():
    meas, _, _ = cell(7, 30)
    joint = tcp_solve.solve_joint(meas)
    for k in (0, 4):
        keep = np.arange(8) != k
        sub = Measurement(path="s", names=[n for i, n in enumerate(meas.names) if keep[i]],
                          lines=None, laser=meas.laser[keep], flange=meas.flange[keep],
                          weights=np.ones(7), form="kuka", orientation=None)
        other = tcp_solve.solve_joint(sub, no_exclusion=True)
        R, t = np.array(other.pose.matrix), np.array(other.pose.t)
        robot = meas.flange[k, :3, :3] @ np.array(other.tcp) + meas.flange[k, :3, 3]
        assert joint.points[k].loo_residual == pytest.approx(
            np.linalg.norm(robot - (R @ meas.laser[k] + t)), abs=1e-7)


def test_an_outlier_is_excluded_with_the_joint_model():
    meas, _, _ = cell(8, 30, n=9)
    meas.laser[3] += [4.0, -3.0, 0.0]
    joint = tcp_solve.solve_joint(meas)
    assert [p.name for p in joint.points if not p.used] == ["P4"]
    assert joint.points[3].excluded_by == "auto" and joint.accepted
    assert np.linalg.norm(np.array(joint.tcp) - TCP) < 0.5
    kept = tcp_solve.solve_joint(meas, no_exclusion=True)
    assert kept.n_used == 9
    hand = tcp_solve.solve_joint(meas, exclude=["p4"])
    assert hand.points[3].excluded_by == "hand"


motions = st.tuples(st.floats(-180, 180), st.floats(-89, 89), st.floats(-180, 180),
                    st.floats(-3000, 3000), st.floats(-3000, 3000), st.floats(-3000, 3000))


@settings(max_examples=25, deadline=None, derandomize=True)
@given(world=motions, ucs=motions, seed=st.integers(0, 50))
def test_rigid_motions_move_the_frame_and_leave_the_tcp(world, ucs, seed):
    """Moving robot world by G and the laser's UCS by H: the frame becomes
    G T H^-1, the TCP (in the flange) and every residual stay."""
    meas, _, _ = cell(seed, 25)
    base = tcp_solve.solve_joint(meas)

    def rigid(m):
        T = np.eye(4)
        T[:3, :3] = Rotation.from_euler("ZYX", m[:3], degrees=True).as_matrix()
        T[:3, 3] = m[3:]
        return T

    G, H = rigid(world), rigid(ucs)
    moved = Measurement(path="m", names=meas.names, lines=meas.lines,
                        laser=meas.laser @ H[:3, :3].T + H[:3, 3], flange=G @ meas.flange,
                        weights=meas.weights, form="kuka", orientation=None)
    sol = tcp_solve.solve_joint(moved)
    T0 = np.eye(4)
    T0[:3, :3], T0[:3, 3] = base.pose.matrix, base.pose.t
    want = G @ T0 @ np.linalg.inv(H)
    np.testing.assert_allclose(sol.tcp, base.tcp, atol=1e-6)
    np.testing.assert_allclose(sol.pose.t, want[:3, 3], atol=1e-6)
    np.testing.assert_allclose(np.array(sol.pose.matrix), want[:3, :3], atol=1e-9)
    for p, q in zip(sol.points, base.points):
        assert p.residual == pytest.approx(q.residual, abs=1e-7)
        assert p.loo_residual == pytest.approx(q.loo_residual, abs=1e-7)
    assert sol.accepted == base.accepted


def test_too_few_points_for_nine_unknowns():
    meas, _, _ = cell(9, 30, n=3)
    with pytest.raises(UcsioError) as e:
        tcp_solve.solve_joint(meas)
    assert "at least 4" in e.value.message


# ------------------------------------------------------------------ diagnosis, CLI

def csv_of(meas, path):
    rows = ["point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c"]
    for nm, l, T in zip(meas.names, meas.laser, meas.flange):
        a = Rotation.from_matrix(T[:3, :3]).as_euler("ZYX", degrees=True)
        rows.append(",".join([nm] + [repr(float(v)) for v in (*l, *T[:3, 3], *a)]))
    path.write_text("\n".join(rows) + "\n")
    return path


def test_a_wrong_tcp_is_diagnosed_not_blamed_on_the_measurement(tmp_path, capsys):
    meas, _, _ = cell(3, 30)
    wrong = solve(meas, TCP + [2.5, 0.0, 5.0])
    assert not wrong.accepted
    found = tcp_solve.diagnose(meas, wrong)
    assert found is not None
    np.testing.assert_allclose(found["tcp"], TCP, atol=0.5)
    assert "--tcp solve" in found["message"] and "--tool" in found["message"]
    # the right TCP is not diagnosed, and a bad measurement is not either
    assert tcp_solve.diagnose(meas, solve(meas, TCP)) is None
    csv = csv_of(meas, tmp_path / "m.csv")
    assert main(["solve", str(csv), "--tcp", "15,-30.25,185", "--json"]) == 1
    out = json.loads(capsys.readouterr().out)
    assert out["accepted"] is False and "--tcp solve" in out["reason"]
    assert out["diagnosis"]["tcp"] == pytest.approx(list(TCP), abs=0.5)
    assert main(["solve", str(csv), "--tcp", "15,-30.25,185"]) == 1
    text = capsys.readouterr().out
    assert "wrong TCP" in text and "measure again" not in text


def test_cli_tcp_solve(tmp_path, capsys):
    meas, _, _ = cell(4, 30)
    csv = csv_of(meas, tmp_path / "m.csv")
    out = tmp_path / "sol.json"
    assert main(["solve", str(csv), "--tcp", "solve", "--json", "-o", str(out)]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["tcp"]["solved"] is True
    assert [got["tcp"][k] for k in "xyz"] == pytest.approx(list(TCP), abs=0.5)
    assert json.loads(out.read_text())["tcp"] == got["tcp"]
    assert main(["solve", str(csv), "--tcp", "solve"]) == 0
    assert "solved with the frame" in capsys.readouterr().out
    meas2, _, _ = cell(4, 2)
    csv2 = csv_of(meas2, tmp_path / "m2.csv")
    assert main(["solve", str(csv2), "--tcp", "solve"]) == 1
    assert "turn the flange" in capsys.readouterr().out


def test_monte_carlo_agrees_with_the_first_order_numbers(tmp_path, capsys):
    """--uncertainty with --tcp solve: N noisy copies refitted by Gauss-Newton;
    their spread matches the first-order covariance (the model is nearly
    linear at this noise), and the TCP's std the solution's own tcp.std."""
    meas, _, _ = cell(4, 30)
    sol = tcp_solve.solve_joint(meas)
    u = tcp_solve.uncertainty(meas, sol, 4000, seed=1)
    assert u["samples"] == 4000 and u["sigma_source"] in ("stated", "residuals")
    for k in "xyz":
        assert u["std"][k] == pytest.approx(u["analytical_std"][k], rel=0.1)
        assert u["tcp"]["std"][k] == pytest.approx(u["tcp"]["analytical_std"][k], rel=0.1)
        lo, hi = u["tcp"]["ci95"][k]
        assert lo < sol.tcp["xyz".index(k)] < hi
    assert u["std"]["angle"] == pytest.approx(u["analytical_std"]["angle"], rel=0.15)
    csv = csv_of(meas, tmp_path / "m.csv")
    assert main(["solve", str(csv), "--tcp", "solve", "--uncertainty", "200", "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["uncertainty"]["samples"] == 200 and set(got["uncertainty"]["tcp"]["std"]) == set("xyz")


# ------------------------------------------------------------------ writing the TCP back

ABB_TOOLS = ("MODULE Tools\n"
             "  ! the reflector holder\n"
             "  PERS tooldata tReflector:=[TRUE,[[10.2,-29.8,179.1],[0.707107,0,0.707107,0]],"
             "[2.5,[0,0,80],[1,0,0,0],0.01,0.01,0.02]];\n"
             "  PERS tooldata tGun:=[TRUE,[[0,0,250],[1,0,0,0]],[3,[0,0,100],[1,0,0,0],0,0,0]];\n"
             "  PERS wobjdata wFix:=[FALSE,TRUE,\"\",[[1000,0,0],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n"
             "ENDMODULE\n")
KUKA_CONFIG = ("DEFDAT  $CONFIG\r\n"
               "DECL TOOL_DATA[16]\r\n"
               "FRAME TOOL_DATA[16]\r\n"
               "TOOL_DATA[1]={X 10.2000,Y -29.8000,Z 179.100,A 90.0000,B 0.0,C -180.000}\r\n"
               "TOOL_DATA[2]={X 0.0,Y 0.0,Z 0.0,A 0.0,B 0.0,C 0.0}\r\n"
               "DECL LOAD_DATA[16]\r\n"
               "LOAD_DATA[1]={M 2.50000,CM {X 0.0,Y 0.0,Z 80.0,A 0.0,B 0.0,C 0.0},"
               "J {X 0.01,Y 0.01,Z 0.02}}\r\n"
               "ENDDAT\r\n")


def solved_solution(tmp_path, capsys, spread=30, name="sol.json"):
    meas, _, _ = cell(4, spread)
    csv = csv_of(meas, tmp_path / "m.csv")
    out = tmp_path / name
    main(["solve", str(csv), "--tcp", "solve", "-o", str(out)])
    capsys.readouterr()
    return out, json.loads(out.read_text())["tcp"]


@pytest.mark.parametrize("vendor", ["abb", "kuka"])
def test_patch_writes_the_solved_tcp_into_a_tool_and_nothing_else(tmp_path, capsys, vendor):
    from ucsio.parsing.controller import load

    sol, tcp = solved_solution(tmp_path, capsys)
    if vendor == "abb":
        f, text, name = tmp_path / "Tools.mod", ABB_TOOLS, "tReflector"
    else:
        f, text, name = tmp_path / "$config.dat", KUKA_CONFIG, "TOOL_DATA[1]"
    f.write_bytes(text.encode())
    before = load(f).frame(name)
    assert main(["patch", str(f), "--frame", name, "--measured", str(sol)]) == 0
    preview = capsys.readouterr().out
    body = preview.splitlines()[2:]
    assert sum(ln.startswith("-") for ln in body) == sum(ln.startswith("+") for ln in body) == 1
    out = tmp_path / ("new" + f.suffix)
    assert main(["patch", str(f), "--frame", name, "--measured", str(sol), "-o", str(out)]) == 0
    after = load(out).frame(name)
    assert after.pose.t == pytest.approx((tcp["x"], tcp["y"], tcp["z"]), abs=5e-4)
    assert after.pose.q == before.pose.q and after.info.get("load") == before.info.get("load")
    changed = {k for k in after.numbers if after.numbers[k].text != before.numbers[k].text}
    assert changed == {"x", "y", "z"}
    # every byte outside the three numbers is the original's
    old, new = f.read_bytes(), out.read_bytes()
    spans = sorted((before.numbers[k].span.start, before.numbers[k].span.end) for k in "xyz")
    kept = old.decode()
    for s0, s1 in reversed(spans):
        kept = kept[:s0] + kept[s1:]
    rest = new.decode()
    for k in sorted("xyz", key=lambda k: -after.numbers[k].span.start):
        sp = after.numbers[k].span
        rest = rest[:sp.start] + rest[sp.end:]
    assert rest == kept


def test_patch_tool_refusals(tmp_path, capsys):
    f = tmp_path / "Tools.mod"
    f.write_text(ABB_TOOLS)
    sol, _ = solved_solution(tmp_path, capsys)
    meas, _, _ = cell(4, 30)
    fixed = tmp_path / "fixed.json"
    main(["solve", str(tmp_path / "m.csv"), "--tcp", "12.5,-30.25,180", "-o", str(fixed)])
    capsys.readouterr()
    # a solution with a given TCP has no TCP to write into a tool
    assert main(["patch", str(f), "--frame", "tReflector", "--measured", str(fixed)]) == 2
    assert "--tcp solve" in capsys.readouterr().err
    # a rejected solve (+-2 deg) is refused, as for frames (exit 1)
    bad, _ = solved_solution(tmp_path, capsys, spread=2, name="bad.json")
    assert main(["patch", str(f), "--frame", "tReflector", "--measured", str(bad)]) == 1
    # a solved solution on a work object writes the frame, as before
    assert main(["patch", str(f), "--frame", "wFix", "--measured", str(sol)]) == 0
    assert "wFix" in capsys.readouterr().out


# ------------------------------------------------------------------ batch

def test_batch_entry_with_laser_robot_and_tcp_solve(tmp_path, capsys):
    from ucsio.fleet.batch import read_manifest, run_batch

    meas, _, _ = cell(4, 30)
    csv = csv_of(meas, tmp_path / "m.csv")
    (tmp_path / "laser.txt").write_text("".join(
        f"{nm};{l[0]!r};{l[1]!r};{l[2]!r}\n".replace(".", ",")
        for nm, l in zip(meas.names, meas.laser.tolist())))
    rows = ["point,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c"]
    for nm, T in zip(meas.names, meas.flange):
        a = Rotation.from_matrix(T[:3, :3]).as_euler("ZYX", degrees=True)
        rows.append(",".join([nm] + [repr(float(v)) for v in (*T[:3, 3], *a)]))
    (tmp_path / "robot.csv").write_text("\n".join(rows) + "\n")
    (tmp_path / "Cell.mod").write_text(ABB_TOOLS)
    (tmp_path / "station.toml").write_text(
        '[defaults]\ncontroller = "Cell.mod"\nframe = "wFix"\ntolerance = 5000.0\n\n'
        '[[entry]]\nname = "paired, solved"\nlaser = "laser.txt"\nrobot = "robot.csv"\n'
        'tcp = "solve"\n\n'
        '[[entry]]\nname = "merged, solved"\nmeasurement = "m.csv"\ntcp = "solve"\n\n'
        '[[entry]]\nname = "merged, given"\nmeasurement = "m.csv"\ntcp = [12.5, -30.25, 180.0]\n\n'
        '[[entry]]\nname = "half"\nlaser = "laser.txt"\ntcp = "solve"\n')
    res = run_batch(read_manifest(tmp_path / "station.toml"))
    paired, merged, given, half = res.entries
    assert paired.accepted and merged.accepted and given.accepted
    assert paired.solution.tcp == pytest.approx(merged.solution.tcp, abs=1e-9)
    assert np.linalg.norm(np.array(paired.solution.tcp) - TCP) < 0.5
    d = paired.as_dict()
    assert d["tcp_solved"]["solved"] is True and d["sources"]["robot"].endswith("robot.csv")
    assert given.solution.tcp == (12.5, -30.25, 180.0)
    # a wrong TCP in a manifest: rejected, and the reason names the TCP that fits
    (tmp_path / "wrong.toml").write_text(
        '[[entry]]\nname = "wrong"\nmeasurement = "m.csv"\ncontroller = "Cell.mod"\n'
        'frame = "wFix"\ntcp = [15.0, -30.25, 185.0]\n')
    (wrong,) = run_batch(read_manifest(tmp_path / "wrong.toml")).entries
    assert not wrong.accepted and 'tcp = "solve"' in wrong.reason   # the manifest's words
    assert half.error and "laser and robot" in half.error
    assert main(["solve", str(csv), "--tcp", "solve"]) == 0


def test_api_solve_with_tcp_solve(tmp_path):
    from ucsio import api

    meas, _, _ = cell(4, 30)
    sol = api.solve(csv_of(meas, tmp_path / "m.csv"), tcp="solve")
    assert sol.accepted and sol.tcp.solved is True          # solve --json's tcp object
    assert np.linalg.norm(np.array([sol.tcp.x, sol.tcp.y, sol.tcp.z]) - TCP) < 0.5
    assert sol.solution.tcp_solved["solved"] is True        # the solver's own object


def test_a_wrong_tcp_is_not_told_to_measure_again(tmp_path, capsys):
    """Issue 18, point 7: the wrong-TCP diagnosis says to check the TCP; the
    batch table, its report and a patch of the rejected solution must not
    then end with "measure again", which contradicts it."""
    meas, _, _ = cell(4, 30)
    csv = csv_of(meas, tmp_path / "m.csv")
    (tmp_path / "Cell.mod").write_text(ABB_TOOLS)
    (tmp_path / "wrong.toml").write_text(
        '[[entry]]\nname = "wrong"\nmeasurement = "m.csv"\ncontroller = "Cell.mod"\n'
        'frame = "wFix"\ntcp = [15.0, -30.25, 185.0]\n')
    report = tmp_path / "report.html"
    assert main(["batch", str(tmp_path / "wrong.toml"), "--report", str(report)]) == 1
    out = capsys.readouterr().out
    assert "wrong TCP" in out and 'tcp = "solve"' in out and "measure again" not in out
    html = report.read_text()
    assert "wrong TCP" in html and "measure again" not in html
    assert main(["batch", str(tmp_path / "wrong.toml"), "--json"]) == 1
    (entry,) = json.loads(capsys.readouterr().out)["entries"]
    assert entry["diagnosis"]["tcp"] == pytest.approx(list(TCP), abs=0.5)
    # the rejected solution of `solve`: patch and diff refuse it without "measure again"
    sol = tmp_path / "wrong.json"
    assert main(["solve", str(csv), "--tcp", "15,-30.25,185", "-o", str(sol)]) == 1
    capsys.readouterr()
    for cmd in ("patch", "diff"):
        assert main([cmd, str(tmp_path / "Cell.mod"), "--frame", "wFix", "--measured",
                     str(sol)]) == 1
        err = capsys.readouterr().err
        assert "wrong TCP" in err and "measure again" not in err, err
    # a dataset rejected for its points is still told to measure again
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"accepted": False, "reason": "too few points",
                               "frame": {"x": 0, "y": 0, "z": 0, "a": 0, "b": 0, "c": 0}}))
    assert main(["patch", str(tmp_path / "Cell.mod"), "--frame", "wFix", "--measured",
                 str(bad)]) == 1
    assert "measure again" in capsys.readouterr().err


# ------------------------------------------------------------------ batch: the solved TCP

def _solve_station(tmp_path, entries: str, defaults: str = ""):
    meas, _, _ = cell(4, 30)
    csv_of(meas, tmp_path / "m.csv")
    (tmp_path / "Cell.mod").write_text(ABB_TOOLS)
    (tmp_path / "Other.mod").write_text(    # its own data: a PERS shared with Cell.mod is refused
        ABB_TOOLS.replace("MODULE Tools", "MODULE Other").replace("wFix", "wOther")
        .replace("tReflector", "tOther").replace("tGun", "tGun2"))
    m = tmp_path / "station.toml"
    m.write_text('[defaults]\nmeasurement = "m.csv"\nframe = "wFix"\ntolerance = 5000.0\n'
                 + defaults + entries)
    return m


def _shown(html: str) -> str:
    return html.split('<script type="application/json"', 1)[0]


def test_batch_shows_the_solved_tcp_and_patches_it_into_the_named_tool(tmp_path, capsys):
    """Issue 18, point 6: with tcp = "solve" the solved TCP (and its 95 %
    doubt) is in the table and the report, not only the JSON; --patch-dir
    writes it into the entry's tool (tool = "FILE:NAME" beside tcp = "solve")
    as `patch` does, and says where no tool was named."""
    from ucsio.parsing.controller import load

    m = _solve_station(tmp_path, '[[entry]]\nname = "into tool"\ncontroller = "Cell.mod"\n'
                                 'tcp = "solve"\ntool = "Cell.mod:tReflector"\n'
                                 '[[entry]]\nname = "no tool"\ncontroller = "Other.mod"\n'
                                 'frame = "wOther"\ntcp = "solve"\n')
    report, patched = tmp_path / "report.html", tmp_path / "patched"
    assert main(["batch", str(m), "--patch-dir", str(patched), "--report", str(report)]) == 0
    out = capsys.readouterr().out
    assert main(["batch", str(m), "--json", "--patch-dir", str(tmp_path / "again")]) == 0
    into, none = json.loads(capsys.readouterr().out)["entries"]
    assert into["tool_patched"] == str(tmp_path / "again" / "Cell.mod")
    t = into["tcp_solved"]
    assert np.linalg.norm(np.array([t["x"], t["y"], t["z"]]) - TCP) < 0.5
    # the table: the TCP and its 95 % doubt, and where it went
    assert "tcp (95 %)" in out
    assert f"{t['x']:.3f}, {t['y']:.3f}, {t['z']:.3f} ±{t['at_95']:.3f}" in out
    assert "solved TCPs:" in out
    assert "into tool: written into Cell.mod:tReflector" in out.replace(str(tmp_path) + "/", "")
    assert "no tool: not written into any tool" in out and 'tcp = "solve"' in out
    # the tool in the patched copy: the solved x, y, z and nothing else of it
    before, after = load(tmp_path / "Cell.mod"), load(patched / "Cell.mod")
    tool = after.frame("tReflector")
    assert tool.pose.t == pytest.approx((t["x"], t["y"], t["z"]), abs=5e-4)
    assert tool.pose.q == before.frame("tReflector").pose.q
    assert tool.info["load"] == before.frame("tReflector").info["load"]
    assert not after.frame("wFix").pose.t == pytest.approx(before.frame("wFix").pose.t)
    assert load(patched / "Other.mod").frame("tOther").pose.t == \
        load(tmp_path / "Other.mod").frame("tOther").pose.t
    # the report shows the TCP, its doubt, the tool written and the tool not patched
    html = _shown(report.read_text())
    assert f"{t['x']:.3f}, {t['y']:.3f}, {t['z']:.3f}" in html and "95 %" in html
    assert "tReflector" in html and "no tool was patched" in html
    # JSON: where it went
    assert into["tool"].endswith("Cell.mod:tReflector")
    held = into["tool_tcp"]                  # the tool's TCP as the file holds it, and how far
    assert (held["x"], held["y"], held["z"]) == pytest.approx((10.2, -29.8, 179.1))
    assert held["distance"] == pytest.approx(
        float(np.linalg.norm(np.array([t["x"], t["y"], t["z"]]) - [10.2, -29.8, 179.1])))
    assert "tool_not_patched" in none and none.get("tool") is None
    # the CSV too (issue 25, point 9): the TCP used, solved or given, and its doubt
    import csv
    given = tmp_path / "given.toml"
    given.write_text(m.read_text() + '[[entry]]\nname = "given"\ncontroller = "Other.mod"\n'
                     'frame = "wOther"\ntcp = [12.5, -30.25, 180.0]\n')
    main(["batch", str(given), "--csv", str(tmp_path / "fleet.csv")])
    capsys.readouterr()
    solved, _, fixed = csv.DictReader((tmp_path / "fleet.csv").open(encoding="utf-8"))
    assert [float(solved[f"tcp_{k}"]) for k in "xyz"] == pytest.approx([t[k] for k in "xyz"])
    assert [float(solved[f"tcp_std_{k}"]) for k in "xyz"] == \
        pytest.approx([t["std"][k] for k in "xyz"])
    assert solved["tcp_solved"] == "true"
    assert float(solved["tcp_at_95"]) == pytest.approx(t["at_95"])
    assert float(solved["tool_tcp_distance"]) == pytest.approx(held["distance"])
    assert [fixed[f"tcp_{k}"] for k in "xyz"] == ["12.5", "-30.25", "180.0"]
    assert fixed["tcp_solved"] == "false" and fixed["tcp_std_x"] == fixed["tcp_at_95"] == ""


def test_manifest_tool_beside_tcp(tmp_path, capsys):
    m = _solve_station(tmp_path,
                       '[[entry]]\nname = "given and tool"\ncontroller = "Cell.mod"\n'
                       'tcp = [1.0, 2.0, 3.0]\ntool = "Cell.mod:tReflector"\n'
                       '[[entry]]\nname = "not a tool"\ncontroller = "Cell.mod"\n'
                       'tcp = "solve"\ntool = "Cell.mod:wFix"\n'
                       '[[entry]]\nname = "no such tool"\ncontroller = "Cell.mod"\n'
                       'tcp = "solve"\ntool = "Cell.mod:tReflectr"\n')
    assert main(["batch", str(m), "--json"]) == 1
    given, wobj, typo = json.loads(capsys.readouterr().out)["entries"]
    assert given["stage"] == "manifest" and "either tcp or tool" in given["error"]
    assert 'tcp = "solve"' in given["error"]
    assert wobj["stage"] == "tool" and "robot-held tool" in wobj["error"]
    assert typo["stage"] == "tool" and "did you mean 'tReflector'" in typo["error"]
    # in [defaults] too: a given TCP and a tool is a bad manifest; solve and a tool is not
    bad = tmp_path / "bad.toml"
    bad.write_text('[defaults]\ntcp = [1.0, 2.0, 3.0]\ntool = "Cell.mod:tReflector"\n'
                   '[[entry]]\nname = "x"\nmeasurement = "m.csv"\ncontroller = "Cell.mod"\n'
                   'frame = "wFix"\n')
    assert main(["batch", str(bad)]) == 2
    assert "either tcp or tool" in capsys.readouterr().err
    good = _solve_station(tmp_path, '[[entry]]\nname = "x"\ncontroller = "Cell.mod"\n',
                          'tcp = "solve"\ntool = "Cell.mod:tReflector"\n')
    assert main(["batch", str(good), "--json"]) == 0
    (x,) = json.loads(capsys.readouterr().out)["entries"]
    assert x["tcp_solved"]["solved"] is True and x["tool"].endswith("Cell.mod:tReflector")


def test_two_entries_solving_one_tool_patch_neither(tmp_path, capsys):
    m = _solve_station(tmp_path, '[[entry]]\nname = "a"\ncontroller = "Cell.mod"\n'
                                 'tcp = "solve"\ntool = "Cell.mod:tReflector"\n'
                                 '[[entry]]\nname = "b"\ncontroller = "Other.mod"\n'
                                 'frame = "wOther"\ntcp = "solve"\ntool = "Cell.mod:tReflector"\n')
    patched = tmp_path / "patched"
    assert main(["batch", str(m), "--patch-dir", str(patched), "--json"]) == 1
    a, b = json.loads(capsys.readouterr().out)["entries"]
    assert "both" in a["patch_error"] and "tReflector" in a["patch_error"]
    assert b["patch_error"] and not (patched / "Cell.mod").exists()
