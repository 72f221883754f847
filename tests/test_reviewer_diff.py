"""The reviewer's diff (issue 24): at B = +-90 (KUKA) or P = +-90 (FANUC)
many A, B, C triples write one rotation; patch writes the one nearest the
old values, so a 0.01 deg correction looks like one in the diff and in
``diff``'s delta, and what it writes still reads back as the solution.

Checked against scipy's Rotation (intrinsic ZYX: R = Rz(A) Ry(B) Rx(C), the
KUKA matrix, FANUC's with A = R, B = P, C = W), exactly at the lock, near it,
away from it, and across the +-180 wrap."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from conftest import FIXTURES
from ucsio.geometry import rotations as rot
from ucsio.geometry.frames import Pose
from ucsio.parsing.controller import parse
from ucsio.parsing.document import Document
from ucsio.review.diff import frame_delta
from ucsio.review.patch import patch_frame, same_rotation_tolerance
from ucsio.vendors.common.write import READBACK_ANGLE_DEG
from ucsio.vendors.fanuc.write import READBACK_FANUC_ANGLE_DEG

KUKA = FIXTURES / "patch" / "refs" / "$config.dat"
FANUC = FIXTURES / "fanuc" / "program_patch.ls"
STEP = {"kuka": 1e-4, "fanuc": 1e-3}


def kuka_file(abc) -> tuple[Document, str]:
    text = KUKA.read_text()
    a, b, c = (f"{v:.4f}" for v in abc)
    new = re.sub(r"BASE_DATA\[7\]=\{(X [^,]+,Y [^,]+,Z [^,]+),A [^,]+,B [^,]+,C [^}]+\}",
                 lambda m: f"BASE_DATA[7]={{{m[1]},A {a},B {b},C {c}}}", text)
    assert new != text
    return Document(new.encode(), str(KUKA)), "BASE_DATA[7]"


def fanuc_file(abc) -> tuple[Document, str]:
    """UF1 of the OEM program with W, P, R = C, B, A."""
    text = FANUC.read_bytes().decode()
    wpr = {4: abc[2], 5: abc[1], 6: abc[0]}

    def value(m):
        v = wpr[int(m[1])]
        return f"PR[30,{m[1]}]=" + (f"({v:.3f})" if v < 0 else f"{v:.3f}")
    new = re.sub(r"PR\[30,([456])\]=\S+", value, text)
    return Document(new.encode(), str(FANUC)), "UF1"


FILES = {"kuka": kuka_file, "fanuc": fanuc_file}


def written(vendor: str, old, target: Pose):
    """(old triple as read, new triple as read back from the patched bytes)."""
    doc, name = FILES[vendor](old)
    cf = parse(doc)
    before = cf.frame(name)
    res = patch_frame(cf, name, target, measured=False, check_siblings=False)
    after = parse(Document(res.new_bytes, doc.path)).frame(name)
    keys = "abc" if vendor == "kuka" else "rpw"
    return (tuple(before.numbers[k].value for k in keys),
            tuple(after.numbers[k].value for k in keys), before.pose)


def scipy_angle(abc, q) -> float:
    """Degrees between R = Rz(a) Ry(b) Rx(c) and quaternion q (w first), by scipy."""
    r1 = Rotation.from_euler("ZYX", abc, degrees=True)
    r2 = Rotation.from_quat([q[1], q[2], q[3], q[0]])
    return float(np.degrees((r1.inv() * r2).magnitude()))


def far(u, v) -> float:
    return math.sqrt(sum(rot.wrap180(a - b) ** 2 for a, b in zip(u, v)))


def on_grid(v: float, step: float) -> float:
    return round(round(v / step) * step, 4) + 0.0


angle = st.floats(-179.9, 180.0)
lock_b = st.one_of(st.sampled_from([90.0, -90.0]),                       # at the lock
                   st.floats(0.001, 0.5).map(lambda d: 90.0 - d),         # near it
                   st.floats(0.001, 0.5).map(lambda d: d - 90.0),
                   st.floats(-89.0, 89.0))                                # away from it
axis = st.tuples(*[st.floats(-1, 1)] * 3).filter(lambda v: sum(x * x for x in v) > 0.01)


@pytest.mark.parametrize("vendor", ["kuka", "fanuc"])
@given(a=st.one_of(angle, st.sampled_from([180.0, -179.999, 179.999])),
       b=lock_b, c=st.one_of(angle, st.sampled_from([180.0, -179.999, 179.999])),
       turn=st.one_of(st.just(None), axis), sign=st.sampled_from([1.0, -1.0]))
@example(a=30.0, b=90.0, c=40.0, turn=None, sign=1.0)
@example(a=180.0, b=-90.0, c=-179.999, turn=None, sign=-1.0)
@example(a=144.0, b=0.0, c=179.999, turn=(-0.125, 0.0, 1.0), sign=1.0)   # W rounds to -180
@settings(max_examples=30, deadline=None)
def test_the_written_triple_is_the_rotation_nearest_the_old_values(vendor, a, b, c, turn, sign):
    step = STEP[vendor]
    old = tuple(on_grid(v, step) for v in (a, b, c))
    q_old = rot.abc_to_quat(*old)
    # a 0.01 deg correction: about the axis the lock leaves free (world z, which
    # turns A - C or A + C only) or about any axis
    if turn is None:
        dq = rot.abc_to_quat(0.01 * sign, 0.0, 0.0)
    else:
        n = math.sqrt(sum(x * x for x in turn))
        h = math.radians(0.01 * sign) / 2
        dq = (math.cos(h), *(math.sin(h) * x / n for x in turn))
    q = rot.quat_canonical(rot.quat_multiply(dq, q_old))
    target = Pose(1.0, 2.0, 3.0, q, rot.quat_to_abc(q))

    before, new, old_pose = written(vendor, old, target)
    # 1. the rotation written is the solution's, within the written precision (scipy)
    limit = READBACK_FANUC_ANGLE_DEG if vendor == "fanuc" else READBACK_ANGLE_DEG
    assert scipy_angle(new, q) <= limit, (old, new)
    # 2. in SPEC's ranges
    assert -90.0 <= new[1] <= 90.0 and -180.0 < new[0] <= 180.0 and -180.0 < new[2] <= 180.0
    # 3. never farther from the old values than q's own triple (rounded)
    own = tuple(on_grid(v, step) for v in rot.quat_to_abc(q))
    assert far(new, before) <= far(own, before) + 3 * step, (before, new, own)
    # 4. exactly at the lock, turned about the free axis: the diff shows 0.01 deg
    if turn is None and abs(old[1]) == 90.0:
        assert max(abs(rot.wrap180(n - o)) for n, o in zip(new, before)) <= 0.01 + 2 * step
    # 5. diff's delta is what patch writes (each wrapped to (-180, 180])
    d = frame_delta(old_pose, target, same_rotation=same_rotation_tolerance(vendor))
    for k, n, o in zip(("da", "db", "dc"), new, before):
        assert -180.0 < d[k] <= 180.0
        assert abs(rot.wrap180(d[k] - rot.wrap180(n - o))) <= 2 * step, (k, d[k], n, o)


def test_a_small_correction_at_the_lock_is_small_in_the_patch_diff(tmp_path, capsys):
    """The issue's case: A 30, B 90, C 40 turned by 0.01 deg about the
    vertical used to be written as A -9.99, C 0 (a 40 deg jump on both)."""
    from ucsio.cli import main

    doc, name = kuka_file((30.0, 90.0, 40.0))
    f = tmp_path / "$config.dat"
    f.write_bytes(doc.raw)
    assert main(["patch", str(f), "--frame", name, "--set",
                 "6130,2444.711,1156.772,-9.99,90,0"]) == 0
    out = capsys.readouterr().out
    assert "+BASE_DATA[7]={X 6130.000,Y 2444.711,Z 1156.772,A 30.0050,B 90.0000,C 39.9950}" in out
