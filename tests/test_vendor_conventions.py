"""Issue 26 point 3, orientation and robot positions: each vendor declares
its rotation convention, its measurement columns and its reader of robot
positions; geometry, the method and the readers take the vendor-free
description and never branch on a vendor's name."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from ucsio import vendors
from ucsio.errors import UcsioError
from ucsio.geometry.angles import POSE_ANGLES, AngleColumns
from ucsio.geometry.arrays import flange_matrices
from ucsio.method.measurement import spec_orientation
from ucsio.method.mistakes import Reading, alternatives
from ucsio.readers.measurement import parse_measurement
from ucsio.readers.robot import read_robot
from ucsio.vendors import angle_columns, measurement_forms
from ucsio.vendors.protocol import Vendor

SRC = Path(__file__).resolve().parent.parent / "src" / "ucsio"
NAMES = [e.name for e in vendors.VENDORS]


def random_poses(n=50, seed=3):
    rng = np.random.default_rng(seed)
    return Rotation.random(n, random_state=rng), rng.normal(0, 800, (n, 3))


def test_every_vendor_provides_its_convention_and_positions_reader():
    for name in NAMES:
        v = vendors.get(name)
        assert isinstance(v, Vendor)
        assert isinstance(v.angles, AngleColumns) and sorted(v.angles.keys) == ["a", "b", "c"]
        columns = v.measurement_columns          # None: SPEC's CSV has no columns of its own
        assert columns is None or columns.label.startswith(columns.short + " (")
        # a vendor reads robot positions only from files of its own kinds
        assert set(v.robot_suffixes) <= set(vendors.BY_NAME[name].suffixes)


@pytest.mark.parametrize("name, written", [
    # KUKA A, B, C: intrinsic Z, Y', X''
    ("kuka", lambda r: r.as_euler("ZYX", degrees=True)),
    # FANUC W, P, R: fixed axes x, y, z
    ("fanuc", lambda r: r.as_euler("xyz", degrees=True)),
    # ABB: quaternions, the real part first
    ("abb", lambda r: r.as_quat(scalar_first=True)),
    # Yaskawa rx, ry, rz: fixed axes x, y, z (R = Rz(rz)·Ry(ry)·Rx(rx))
    ("yaskawa", lambda r: r.as_euler("xyz", degrees=True)),
])
def test_each_vendors_convention_against_scipy(name, written):
    r, pos = random_poses()
    T = flange_matrices(vendors.get(name).angles, written(r), pos)
    np.testing.assert_allclose(T[:, :3, :3], r.as_matrix(), atol=1e-12)
    np.testing.assert_array_equal(T[:, :3, 3], pos)


def test_geometry_reads_only_the_description():
    """A convention no vendor has (B, C, A written in that order) is read by
    its keys alone: geometry knows no vendor."""
    r, pos = random_poses(seed=5)
    a, b, c = r.as_euler("ZYX", degrees=True).T
    odd = AngleColumns(("u", "v", "w"), "bca")
    T = flange_matrices(odd, np.stack([b, c, a], axis=1), pos)
    np.testing.assert_allclose(T[:, :3, :3], r.as_matrix(), atol=1e-12)


def test_spec_orientation_follows_the_convention():
    quat = AngleColumns(("rx", "ry", "rz"), "cba", quaternion=True)
    xyzw = np.array([[0.1, 0.2, 0.3, 0.9]])
    assert spec_orientation(quat, xyzw, quaternion_order="xyzw").tolist() == [[0.9, 0.1, 0.2, 0.3]]
    assert spec_orientation(quat, xyzw, "rad").tolist() == xyzw.tolist()   # units: angles only
    angles = AngleColumns(("w", "p", "r"), "cba")
    np.testing.assert_allclose(spec_orientation(angles, np.array([[np.pi, 0, -np.pi / 2]]), "rad"),
                               [[180, 0, -90]])


def test_a_table_shows_its_vendors_angle_names():
    assert angle_columns("fanuc").names == ("w", "p", "r")
    assert angle_columns({"abb"}).names == ("rx", "ry", "rz") and angle_columns("abb").quaternion
    assert angle_columns(["kuka", "kuka"]).names == ("a", "b", "c")
    # several vendors, none, or one not registered: Pose.abc's own a, b, c
    for names in ({"abb", "fanuc"}, set(), None, "staubli"):
        assert angle_columns(names) is POSE_ANGLES


def test_measurement_forms_keep_their_order_whatever_the_registry(monkeypatch):
    expected = ["kuka", "abb", "fanuc"]         # by first column: robot_a, robot_q1, robot_w
    assert [name for name, _ in measurement_forms()] == expected
    monkeypatch.setattr(vendors, "VENDORS", tuple(reversed(vendors.VENDORS)))
    assert [name for name, _ in measurement_forms()] == expected


@pytest.mark.parametrize("header, message", [
    ("laser_x,laser_y,laser_z,robot_x,robot_y,robot_z",
     "no flange orientation columns: need robot_a/b/c (KUKA), robot_q1..q4 (ABB) or "
     "robot_w/p/r (Fanuc)"),
    ("laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_w,robot_p,robot_r,"
     "robot_q1,robot_q2,robot_q3,robot_q4",
     "flange orientation given in two forms: robot_q1..q4 (ABB) and robot_w/p/r (Fanuc); "
     "keep exactly one"),
])
def test_measurement_messages_name_the_vendors_columns(header, message):
    with pytest.raises(UcsioError) as e:
        parse_measurement(header + "\n1,2,3,4,5,6,0,0,0,1,0,0,0\n", "m.csv")
    assert e.value.message == message


@pytest.mark.parametrize("name, columns, mistake", [
    ("kuka", "robot_a,robot_b,robot_c", "every angle of robot_a/b/c lies within ±π"),
    ("fanuc", "robot_w,robot_p,robot_r", "every angle of robot_w/p/r lies within ±π"),
    ("abb", "robot_q1,robot_q2,robot_q3,robot_q4",
     "robot_q1..q4 look written with the real part last (x, y, z, w)"),
])
def test_a_mistake_names_the_vendors_columns(name, columns, mistake):
    rows = ["0.1,0.2,0.3", "0.5,-0.2,1.0", "-1.0,0.3,0.2"] if name != "abb" else \
        ["1,0,0,0", "0.6,0.8,0,0", "0,0,0.6,0.8"]
    text = f"point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,{columns}\n" + "".join(
        f"P{i},{i},0,0,{i},0,0,{r}\n" for i, r in enumerate(rows))
    meas = parse_measurement(text, "m.csv")
    assert meas.form == name
    found = [alt for alt in alternatives(meas, Reading()) if alt.key != "laser_units"]
    assert len(found) == 1 and found[0].mistake.startswith(mistake)


def test_a_vendor_without_a_positions_reader_leaves_the_file_to_the_csv(tmp_path, monkeypatch):
    dat = tmp_path / "meas.dat"
    dat.write_text("DEFDAT meas\nDECL E6POS XP1={X 1,Y 2,Z 3,A 0,B 0,C 0}\nENDDAT\n")
    assert read_robot(dat).format == "kuka"
    monkeypatch.setattr(vendors.get("kuka"), "robot_positions", None)
    with pytest.raises(UcsioError) as e:
        read_robot(dat)
    assert e.value.file == str(dat) and "orientation" in e.value.message     # read as a CSV


def test_a_kuka_program_is_no_file_of_positions(tmp_path):
    """A .src is KUKA's, but holds no positions: read as a CSV, as before."""
    src = tmp_path / "meas.src"
    src.write_text("DEF meas()\nEND\n")
    assert vendors.by_suffix(str(src)) == "kuka"
    with pytest.raises(UcsioError) as e:
        read_robot(src)
    assert "robot_" in e.value.message
