"""Issue 28 point 1, the orientations a TCP solved with the frame needs:
``program --measure --spread DEG`` turns the tool point by point, and
``plan --tcp solve`` without planned flange poses predicts that very
program (its ``spread``: the one given, or the least that holds the
threshold).

Checked against scipy's Rotation (the angle between two flange
orientations), the plan against the fits of the program it leads to.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from test_measure_program import SYSFRAME, UF1, UT1, cli, matrix
from ucsio import api
from ucsio.readers.robot import read_robot

POINTS = [(0, 0, 0), (900, 0, 40), (0, 700, 0), (900, 700, 120), (450, -50, 200),
          (-40, 350, 90), (450, 760, 10), (940, 350, 180)]
NOMINAL = (1.2, -0.8, 210.4)             # the reflector's TCP the program aims with
WORK = (450.0, 350.0, 60.0)


@pytest.fixture
def cell(tmp_path):
    (tmp_path / "sysframe.va").write_bytes(SYSFRAME.format(*UF1, *UT1).replace("\n", "\r\n")
                                           .encode())
    (tmp_path / "plan.csv").write_text(
        "point,laser_x,laser_y,laser_z\n" +
        "".join(f"M{k},{x},{y},{z}\n" for k, (x, y, z) in enumerate(POINTS)))
    (tmp_path / "at.csv").write_text("point,x,y,z\nW1,{},{},{}\n".format(*WORK))
    return tmp_path


def span(rotations) -> float:
    """The largest angle (deg) between two of the rotations, by scipy."""
    r = Rotation.from_matrix(np.asarray(rotations))
    return max((r[i].inv() * r[j]).magnitude() for i in range(len(r))
               for j in range(i + 1, len(r))) * 180 / np.pi


def program(capsys, cell, spread, name="M.LS", *more):
    out = cell / name
    code, _, err = cli(capsys, "program", "--measure", cell / "plan.csv", cell / "sysframe.va",
                       "--frame", "UF1", "--tcp", ",".join(map(str, NOMINAL)), "--spread",
                       spread, *more, "-o", out)
    assert code == 0, err
    return read_robot(out, config=str(cell / "sysframe.va"))


def test_the_pattern_spans_what_it_says():
    from ucsio.method.spread import tilts
    for spread in (5.0, 20.0, 37.5, 90.0):
        t = tilts(8, spread)
        assert span(t) == pytest.approx(spread, abs=1e-9)
        assert np.allclose(t[0], np.eye(3))
        # turns about the tool's x and y axes only: its z stays in the x=0 or y=0 plane
        for k, axis in ((1, 0), (2, 1), (3, 0), (4, 1)):
            assert Rotation.from_matrix(t[k]).as_rotvec()[[2, 1 - axis]] == \
                pytest.approx([0, 0], abs=1e-12)
    assert span(tilts(3, 30.0)) < 30.0        # +x and +y only: the span needs -x too


def test_the_program_turns_the_flange_round_the_reflector(cell, capsys):
    """Every reflector stays on its planned point (the written 0.001 mm and
    0.001 deg over 210 mm); the flange orientations span --spread."""
    robot = program(capsys, cell, "30")
    inv = np.linalg.inv(matrix(*UF1))
    tcp = np.append(NOMINAL, 1.0)
    points = {p.point: p for p in robot.poses}
    for k, xyz in enumerate(POINTS):
        assert np.allclose((inv @ points[f"M{k}"].flange @ tcp)[:3], xyz, atol=3e-3)
    measured = [points[f"M{k}"].flange[:3, :3] for k in range(len(POINTS))]
    assert span(measured) == pytest.approx(30.0, abs=2e-3)


def test_spread_is_refused_where_it_cannot_hold(cell, capsys):
    oriented = cell / "oriented.csv"
    oriented.write_text("point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_w,"
                        "robot_p,robot_r\n" + "".join(
                            f"M{k},{x},{y},{z},0,0,0,180,{k},0\n"
                            for k, (x, y, z) in enumerate(POINTS)))
    for plan, spread in ((cell / "plan.csv", "0"), (cell / "plan.csv", "120"),
                         (cell / "plan.csv", "nan"), (oriented, "20")):
        code, _, err = cli(capsys, "program", "--measure", plan, cell / "sysframe.va",
                           "--frame", "UF1", "--tcp", "0,0,200", "--spread", spread, "-o",
                           cell / "X.LS")
        assert code == 2 and "--spread" in err
        assert not (cell / "X.LS").exists()
    for args in (["--spread", "20"], ["--tcp", "solve", "--spread", "0"]):
        code, _, err = cli(capsys, "plan", cell / "plan.csv", *args)
        assert code == 2 and "--spread" in err
    code, _, err = cli(capsys, "plan", oriented, "--tcp", "solve", "--spread", "20")
    assert code == 2 and "oriented.csv" in err


def test_the_plan_takes_the_least_spread_that_holds(cell):
    """Without --spread the plan takes the least step that holds the
    threshold: the step below it does not."""
    noise = {"sigma_laser": 0.02, "sigma_robot": 0.2}
    chosen = api.plan(cell / "plan.csv", tcp="solve", at=cell / "at.csv", **noise).as_dict()
    spread = chosen["spread"]
    assert chosen["verdict"] == "pass" and 5 < spread < 90
    assert chosen["orientation_span"] == pytest.approx(spread)
    below = api.plan(cell / "plan.csv", tcp="solve", at=cell / "at.csv", spread=spread - 5,
                     **noise).as_dict()
    assert below["verdict"] == "fail" and below["spread"] == spread - 5
    wider = api.plan(cell / "plan.csv", tcp="solve", at=cell / "at.csv", spread=spread + 20,
                     **noise).as_dict()
    assert wider["tcp_at_95"] < chosen["tcp_at_95"] <= 1.5


def test_the_whole_loop_with_the_tcp_solved(cell, capsys):
    """plan --tcp solve -> program --spread (aimed with a nominal TCP) -> a
    simulated tracker (the true frame 1.5 mm and 0.1 deg off, the true TCP
    2.9 mm off the nominal; the planned noise) -> solve --tcp solve: the true
    frame at the working point and the true TCP within the plan's predicted
    95 %, each in at least 15 of 20 trials (at the stated 95 %, fewer fails
    with probability 3e-4)."""
    sigma_laser, sigma_robot = 0.02, 0.2
    planned = api.plan(cell / "plan.csv", tcp="solve", at=cell / "at.csv",
                       sigma_laser=sigma_laser, sigma_robot=sigma_robot).as_dict()
    at_95, tcp_95 = planned["working_points"][0]["at_95"], planned["tcp_at_95"]
    robot = program(capsys, cell, f"{planned['spread']:g}", "LOOP.LS")
    flanges = {p.point: p.flange for p in robot.poses}
    true = matrix(*UF1) @ matrix(1.2, -0.9, 0.5, 0.05, -0.08, 0.06)
    true_tcp = np.add(NOMINAL, (2.0, -1.5, 1.4))
    rng = np.random.default_rng(2028)
    w = np.append(WORK, 1.0)
    frame_in = tcp_in = 0
    for trial in range(20):
        rows = []
        for k in range(len(POINTS)):
            reflector = (flanges[f"M{k}"] @ np.append(true_tcp, 1.0))[:3]
            reflector += rng.normal(0, sigma_robot, 3)
            seen = (np.linalg.inv(true) @ np.append(reflector, 1.0))[:3]
            seen += rng.normal(0, sigma_laser, 3)
            rows.append(f"M{k},{seen[0]:.4f},{seen[1]:.4f},{seen[2]:.4f}\n")
        laser = cell / "tracker.csv"
        laser.write_text("point,x,y,z\n" + "".join(rows))
        got = api.solve(laser=laser, robot=cell / "LOOP.LS", config=cell / "sysframe.va",
                        tcp="solve", no_exclusion=True, sigma_laser=sigma_laser,
                        sigma_robot=sigma_robot).as_dict()
        assert got["n_used"] == len(POINTS)
        measured = np.asarray(got["frame"]["matrix"])
        frame_in += np.linalg.norm((measured @ w - true @ w)[:3]) <= at_95
        tcp = got["tcp"]
        tcp_in += np.linalg.norm([tcp["x"], tcp["y"], tcp["z"]] - true_tcp) <= tcp_95
    assert frame_in >= 15 and tcp_in >= 15
