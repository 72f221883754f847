"""The usual mistakes named (exit 2, nothing written): a laser file in metres
read as millimetres, angles in radians, an ABB quaternion written x, y, z, w;
and never a false alarm on a correct dataset (ucsio.method.mistakes)."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st
from scipy.spatial.transform import Rotation

from ucsio.cli import main
from ucsio.commands.solve import solve
from ucsio.errors import UcsioError

TCP = (-20.67, 89.73, 33.44)
TCP_ARG = "--tcp=-20.67,89.73,33.44"
COLUMNS = {"kuka": ["robot_a", "robot_b", "robot_c"], "fanuc": ["robot_w", "robot_p", "robot_r"],
           "abb": ["robot_q1", "robot_q2", "robot_q3", "robot_q4"]}
DOWN = Rotation.from_euler("ZYX", [180, 0, 180], degrees=True)      # a tool pointing down


def cell(seed=0, n=8, noise=0.02, spread=30.0, size=(1000.0, 700.0, 250.0), base=DOWN,
         tcp=TCP):
    """A known UCS, laser points and flange poses (scipy) at n points."""
    rng = np.random.default_rng(seed)
    R = Rotation.from_euler("ZYX", rng.uniform(-60, 60, 3), degrees=True)
    t = rng.uniform(-1500, 1500, 3) + [2000, 0, 500]
    laser = rng.uniform(0, 1, (n, 3)) * size
    world = R.apply(laser) + t + rng.normal(0, noise, (n, 3))
    flange = base * Rotation.from_euler("ZYX", rng.uniform(-spread, spread, (n, 3)),
                                        degrees=True)
    return laser, flange, world - flange.apply(tcp)


def orientation(form, flange, rad=False, xyzw=False):
    if form == "abb":
        return flange.as_quat(scalar_first=not xyzw)
    abc = flange.as_euler("ZYX", degrees=not rad)
    return abc[:, ::-1] if form == "fanuc" else abc


def write(path, form, laser, flange, pos, *, laser_scale=1.0, rad=False, xyzw=False,
          sides=("laser", "robot")):
    cols = ["point"] + (["laser_x", "laser_y", "laser_z"] if "laser" in sides else []) + \
        (["robot_x", "robot_y", "robot_z"] + COLUMNS[form] if "robot" in sides else [])
    ori = orientation(form, flange, rad, xyzw)
    rows = [",".join(cols)]
    for i in range(len(laser)):
        values = ((*laser[i] * laser_scale,) if "laser" in sides else ()) + \
            ((*pos[i], *ori[i]) if "robot" in sides else ())
        rows.append(",".join([f"P{i + 1}"] + [f"{v:.6f}" for v in values]))
    Path(path).write_text("\n".join(rows) + "\n", encoding="utf-8")
    return str(path)


MISTAKES = [("kuka", dict(laser_scale=0.001), "--laser-units", "m"),
            ("abb", dict(laser_scale=1 / 25.4), "--laser-units", "in"),
            ("kuka", dict(rad=True), "--angle-units", "rad"),
            ("fanuc", dict(rad=True), "--angle-units", "rad"),
            ("abb", dict(xyzw=True), "--quaternion-order", "xyzw")]


@pytest.mark.parametrize("form, mistake, opt, value", MISTAKES)
@pytest.mark.parametrize("tcp", [TCP_ARG, "--tcp=solve"])
def test_each_mistake_is_named_and_nothing_written(tmp_path, capsys, form, mistake, opt, value,
                                                   tcp):
    meas = write(tmp_path / "m.csv", form, *cell(), **mistake)
    out = tmp_path / "solution.json"
    assert main(["solve", meas, tcp, "-o", out]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"ucsio: {meas}:")
    assert f"say so with {opt} {value}" in err[0] and "measure again" not in err[0]
    assert not out.exists()
    # stated, the same file solves, accepted
    assert main(["solve", meas, tcp, opt, value, "-o", out, "--json"]) == 0
    capsys.readouterr()
    assert json.loads(out.read_text())["accepted"]


def test_the_stated_reading_gives_the_true_frame(tmp_path):
    laser, flange, pos = cell(seed=4, noise=0.0)
    right = solve(write(tmp_path / "a.csv", "kuka", laser, flange, pos), tcp=TCP)[0]
    for name, mistake, reading in [("m", dict(laser_scale=0.001), dict(laser_units="m")),
                                   ("r", dict(rad=True), dict(angle_units="rad"))]:
        got = solve(write(tmp_path / f"{name}.csv", "kuka", laser, flange, pos, **mistake),
                    tcp=TCP, **reading)[0]
        assert got.accepted
        np.testing.assert_allclose(got.pose.t, right.pose.t, atol=1e-3)
    got = solve(write(tmp_path / "q.csv", "abb", laser, flange, pos, xyzw=True), tcp=TCP,
                quaternion_order="xyzw")[0]
    np.testing.assert_allclose(got.pose.t, right.pose.t, atol=1e-3)


def test_files_where_they_live(tmp_path):
    """--laser in metres (a name x y z table) and a --robot CSV in radians."""
    laser, flange, pos = cell(seed=2)
    table = tmp_path / "laser.txt"
    table.write_text("".join(f"P{i + 1} {x / 1000:.7f} {y / 1000:.7f} {z / 1000:.7f}\n"
                             for i, (x, y, z) in enumerate(laser)))
    robot = write(tmp_path / "robot.csv", "kuka", laser, flange, pos, sides=("robot",))
    with pytest.raises(UcsioError, match="--laser-units m") as e:
        solve(laser=table, robot=robot, tcp=TCP)
    assert e.value.file == str(table)
    assert solve(laser=table, robot=robot, tcp=TCP, laser_units="m")[0].accepted
    rad = write(tmp_path / "rad.csv", "kuka", laser, flange, pos, sides=("robot",), rad=True)
    with pytest.raises(UcsioError, match="--angle-units rad"):
        solve(laser=table, robot=rad, tcp=TCP, laser_units="m")
    assert solve(laser=table, robot=rad, tcp=TCP, laser_units="m", angle_units="rad")[0].accepted


def test_a_batch_entry_names_its_manifest_key(tmp_path):
    from ucsio.fleet.batch import read_manifest, run_batch

    laser, flange, pos = cell(seed=5)
    write(tmp_path / "rad.csv", "fanuc", laser, flange, pos, rad=True)
    (tmp_path / "cfg.dat").write_text("DEFDAT $CONFIG PUBLIC\nDECL FRAME BASE_DATA[3]\n"
                                      "BASE_DATA[3]={X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0}\n"
                                      "ENDDAT\n")
    manifest = tmp_path / "m.toml"
    manifest.write_text('[defaults]\ntcp = [-20.67, 89.73, 33.44]\ncontroller = "cfg.dat"\n'
                        'frame = "BASE_DATA[3]"\n[[entry]]\nname = "as read"\n'
                        'measurement = "rad.csv"\n[[entry]]\nname = "stated"\n'
                        'measurement = "rad.csv"\nangle_units = "rad"\n')
    first, second = run_batch(read_manifest(str(manifest))).entries
    assert first.stage == "measurement", first.error
    assert 'angle_units = "rad" in the entry' in first.error
    assert second.error is None and second.accepted


# ------------------------------------------------------------------ no false alarm

@settings(max_examples=25, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(form=st.sampled_from(["kuka", "fanuc", "abb"]), seed=st.integers(0, 10**6),
       size=st.sampled_from([(1000.0, 700.0, 250.0), (60.0, 40.0, 20.0), (8.0, 6.0, 3.0)]),
       spread=st.sampled_from([0.0, 0.05, 2.0, 30.0]),
       base=st.sampled_from([DOWN, Rotation.identity()]),
       noise=st.sampled_from([0.0, 0.02, 0.5, 2.0]),
       joint=st.booleans())
def test_a_correct_dataset_is_never_refused(tmp_path, form, seed, size, spread, base, noise,
                                            joint):
    """Small fixtures, small orientation spreads, angles all within ±π
    degrees (a tool near the identity), noise that rejects: a correct
    dataset is accepted or rejected, never refused as a mistake."""
    meas = write(tmp_path / f"{form}.csv", form,
                 *cell(seed, noise=noise, spread=spread, size=size, base=base))
    try:
        solve(meas, tcp="solve" if joint else TCP)
    except UcsioError as exc:
        assert "say so with" not in exc.message, exc.message
