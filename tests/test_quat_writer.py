"""The ABB quaternion writer (SPEC, "Files ucsio writes"; issue 9 point 2).

Plain rounding to 6 decimals where that gives |sum q^2 - 1| <= 1e-6, else the
6-decimal quaternion within that bound nearest in rotation. Fixtures sit at
90 and 180 degrees far more often than anywhere else, so the generated
orientations here are concentrated at and near axis-aligned rotations (q1 ~ 0,
components of 0.5 and 0.707107, compositions of them, small corrections).
``benchmarks/stress_quaternions.py`` runs the full 20,000 through ``patch``.
"""
from __future__ import annotations

import itertools
import math
import random

import pytest

from conftest import FIXTURES
from ucsio.geometry import rotations as rot
from ucsio.parsing.controller import load, parse
from ucsio.parsing.document import Document
from ucsio.geometry.frames import Pose
from ucsio.review.patch import patch_frame
from ucsio.vendors.abb.write import QUAT_NORM_MAX, quat_to_write, rotation_gap as _rotation_gap

STEP = 1e-6
MAX_ANGLE_DEG = 1.2e-4          # what 6 decimals allow: |dq| <= 4 x 5e-7 -> 2e-6 rad
CELL = FIXTURES / "patch" / "cell.mod"


def axis_aligned() -> list[tuple[float, float, float, float]]:
    """Every composition of two quarter/half turns (and 45/135 deg) about
    the axes: the 24 axis-aligned orientations and their neighbours."""
    singles = []
    for axis in range(3):
        for deg in (0, 45, 90, 135, 180, -45, -90, -135):
            h = math.radians(deg) / 2
            singles.append((math.cos(h), *(math.sin(h) if k == axis else 0.0 for k in range(3))))
    return [rot.quat_multiply(a, b) for a in singles for b in singles]


def orientations(n: int, seed: int = 0):
    """``n`` unit quaternions (q1 >= 0): axis-aligned ones, some exactly, most
    with a correction of 1e-9 ... 1e-2 rad, and a few uniform ones."""
    rng = random.Random(seed)
    base = axis_aligned()
    for i in range(n):
        if i % 10 == 9:
            q = tuple(rng.gauss(0, 1) for _ in range(4))
        else:
            q = rng.choice(base)
            if i % 5:
                s = 10 ** rng.uniform(-9, -2)
                q = rot.quat_multiply(q, (1.0, rng.gauss(0, s), rng.gauss(0, s), rng.gauss(0, s)))
        q = rot.quat_normalize(q)
        yield [-c for c in q] if q[0] < 0 else list(q)


def test_orientations_reach_the_hard_cases():
    qs = list(orientations(3000))
    assert sum(abs(q[0]) < 1e-6 for q in qs) > 100                   # q1 ~ 0 (180 deg)
    plain_fails = [q for q in qs
                   if abs(sum(round(c, 6) ** 2 for c in q) - 1) > QUAT_NORM_MAX]
    assert plain_fails          # the fallback is exercised, not only plain rounding


@pytest.mark.parametrize("seed", [0, 1])
def test_written_quaternion_bound_rotation_and_steps(seed):
    for q in orientations(2500, seed):
        w = quat_to_write(q)
        assert abs(sum(c * c for c in w) - 1.0) <= QUAT_NORM_MAX
        assert math.degrees(_rotation_gap(w, q)) <= MAX_ANGLE_DEG
        plain = [round(c, 6) for c in q]
        if abs(sum(c * c for c in plain) - 1.0) <= QUAT_NORM_MAX:
            assert w == plain                                   # plain rounding where it fits
        else:   # within one 1e-6 step of the exact value (floor or ceiling)
            assert all(abs(a - b) < STEP * (1 + 1e-6) for a, b in zip(w, q))


def test_fallback_is_the_nearest_in_rotation():
    """Brute force over every 6-decimal quaternion within two steps of q:
    none inside the bound is nearer in rotation than what is written."""
    checked = 0
    for q in orientations(4000, seed=7):
        plain = [round(c, 6) for c in q]
        if abs(sum(c * c for c in plain) - 1.0) <= QUAT_NORM_MAX:
            continue
        w = quat_to_write(q)
        gap = _rotation_gap(w, q)
        grids = [[round(p + k * STEP, 6) for k in range(-2, 3)] for p in plain]
        for cand in itertools.product(*grids):
            if abs(sum(c * c for c in cand) - 1.0) <= QUAT_NORM_MAX:
                assert _rotation_gap(list(cand), q) >= gap - 1e-15
        checked += 1
    assert checked > 50


TINY = ('MODULE Tiny\n  TASK PERS wobjdata wobjA:=[FALSE,TRUE,"",[[0,0,0],[1,0,0,0]],'
        '[[0,0,0],[1,0,0,0]]];\n  PERS tooldata toolA:=[TRUE,[[0,0,100],[0,0,0,-1]],'
        '[1,[0,0,1],[1,0,0,0],0,0,0]];\nENDMODULE\n')
NAMES = ("wobjA", "wobjA.oframe", "toolA")


def patch_everywhere(path, qs, seed=5):
    """Plan, edit, parse back and verify a patch for each orientation, on
    the user frame, object frame and tool frame in turn; return the worst
    rotation (deg) and norm error written. Raises on any refusal."""
    cf = load(path)
    rng = random.Random(seed)
    worst_angle = worst_norm = 0.0
    for i, q in enumerate(qs):
        target = Pose.from_quat(rng.uniform(-2000, 2000), rng.uniform(-2000, 2000),
                                rng.uniform(-2000, 2000), q)
        name = NAMES[i % 3]
        res = patch_frame(cf, name, target, measured=False, check_siblings=False)
        again = parse(Document(res.new_bytes, path)).frame(name)
        written = [again.numbers[k].value for k in ("q1", "q2", "q3", "q4")]
        worst_norm = max(worst_norm, abs(sum(c * c for c in written) - 1.0))
        worst_angle = max(worst_angle,
                          rot.quat_angle(Pose.from_quat(0, 0, 0, written).q, target.q))
    return worst_angle, worst_norm


def test_patch_never_refuses_axis_aligned_orientations(tmp_path):
    """The whole way (plan, edit, parse back, verify): no 'internal error',
    the rotation within 1.2e-4 deg, the norm within 1e-6."""
    path = tmp_path / "Tiny.mod"
    path.write_text(TINY)
    angle, norm = patch_everywhere(path, orientations(300, seed=3))
    assert angle <= MAX_ANGLE_DEG and norm <= QUAT_NORM_MAX
