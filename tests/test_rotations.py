"""ucsio.geometry.rotations against two independent references:
scipy.spatial.transform.Rotation and robodk.robomath."""
from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from ucsio.geometry import rotations as rot
from ucsio.geometry.frames import Pose

robomath = pytest.importorskip("robodk.robomath")

N = 2000
ATOL = 1e-12


def rng(seed=0):
    return np.random.default_rng(seed)


def random_rotations(n=N, seed=0) -> Rotation:
    return Rotation.random(n, random_state=seed)


def near_180(n=300, seed=1, eps_deg=(0.0, 1e-9, 1e-6, 1e-3, 0.1)) -> Rotation:
    """Rotations of 180 deg minus tiny amounts, about random axes (including
    the coordinate axes, where quaternion components vanish)."""
    g = rng(seed)
    axes = g.normal(size=(n, 3))
    axes[:6] = np.vstack([np.eye(3), -np.eye(3)])
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    eps = np.array(eps_deg)[g.integers(len(eps_deg), size=n)]
    eps[:6] = 0.0
    return Rotation.from_rotvec(axes * np.radians(180.0 - eps)[:, None])


def gimbal_abc(n=300, seed=2):
    """A, C random; B at or within tiny amounts of +-90."""
    g = rng(seed)
    b = np.where(g.random(n) < 0.5, 90.0, -90.0)
    off = np.array([0.0, 1e-12, 1e-10, 1e-8, 1e-6, 1e-4])[g.integers(6, size=n)]
    b = b - np.sign(b) * off
    return np.column_stack([g.uniform(-180, 180, n), b, g.uniform(-180, 180, n)])


def as_t(m):
    return tuple(tuple(float(v) for v in row) for row in m)


def scipy_quat(r: Rotation) -> np.ndarray:
    q = r.as_quat(scalar_first=True)
    return np.where(q[..., :1] < 0, -q, q)


def same_rotation_quat(q1, q2, tol):
    """Equal as rotations: q1 = +-q2 (the sign only matters when w != 0)."""
    q1, q2 = np.asarray(q1), np.asarray(q2)
    return min(np.abs(q1 - q2).max(), np.abs(q1 + q2).max()) <= tol


# ------------------------------------------------------------------ wrap180

@pytest.mark.parametrize("angle, expected", [
    (0.0, 0.0), (-0.0, 0.0), (180.0, 180.0), (-180.0, 180.0), (540.0, 180.0),
    (-540.0, 180.0), (360.0, 0.0), (-360.0, 0.0), (190.0, -170.0), (-190.0, 170.0),
    (179.999999, 179.999999), (-179.999999, -179.999999), (720.5, 0.5), (-720.5, -0.5),
    (1e-300, 1e-300), (359.9999999999, -1e-10),
])
def test_wrap180_cases(angle, expected):
    got = rot.wrap180(angle)
    assert got == pytest.approx(expected, abs=1e-9)
    assert -180.0 < got <= 180.0
    assert math.copysign(1.0, got) == 1.0 or got < 0


@given(st.floats(min_value=-1e6, max_value=1e6, allow_nan=False))
@settings(max_examples=300, deadline=None)
def test_wrap180_property(a):
    w = rot.wrap180(a)
    assert -180.0 < w <= 180.0
    k = (a - w) / 360.0
    assert abs(k - round(k)) < 1e-9 * max(1.0, abs(a))


# ------------------------------------------------------------------ quaternions

def test_quat_normalize_and_canonical():
    assert rot.quat_normalize((2.0, 0.0, 0.0, 0.0)) == (1.0, 0.0, 0.0, 0.0)
    with pytest.raises(ValueError):
        rot.quat_normalize((0.0, 0.0, 0.0, 0.0))
    with pytest.raises(ValueError):
        rot.quat_normalize((float("nan"), 0.0, 0.0, 1.0))
    assert rot.quat_canonical((-1.0, 0.0, 0.0, 0.0)) == (1.0, 0.0, 0.0, 0.0)
    assert rot.quat_canonical((-0.5, 0.5, -0.5, 0.5)) == (0.5, -0.5, 0.5, -0.5)
    # w == 0: the first non-zero of x, y, z positive (scipy's canonical rule)
    for q in [(0.0, 0.0, -1.0, 0.0), (0.0, -0.6, 0.8, 0.0), (0.0, 0.0, 0.0, -1.0)]:
        ref = Rotation.from_quat(q, scalar_first=True).as_quat(canonical=True, scalar_first=True)
        np.testing.assert_allclose(rot.quat_canonical(q), ref, atol=ATOL)
    # no negative zeros leak out
    assert all(math.copysign(1.0, v) == 1.0 for v in rot.quat_canonical((-1.0, -0.0, 0.0, -0.0)))


def test_quat_to_matrix_vs_scipy():
    r = random_rotations()
    q = r.as_quat(scalar_first=True)
    for qi, mi in zip(q, r.as_matrix()):
        np.testing.assert_allclose(rot.quat_to_matrix(tuple(qi)), mi, atol=ATOL)
        # non-unit input is normalised
        np.testing.assert_allclose(rot.quat_to_matrix(tuple(3.7 * qi)), mi, atol=ATOL)


@pytest.mark.parametrize("which", ["random", "near180", "small"])
def test_matrix_to_quat_vs_scipy(which):
    if which == "random":
        r = random_rotations()
    elif which == "near180":
        r = near_180()
    else:
        g = rng(5)
        r = Rotation.from_rotvec(g.normal(size=(300, 3)) * 10.0 ** g.uniform(-12, -1, (300, 1)))
    ref = scipy_quat(r)
    for mi, qi in zip(r.as_matrix(), ref):
        got = rot.matrix_to_quat(as_t(mi))
        assert got[0] >= 0.0
        assert abs(sum(v * v for v in got) - 1.0) < 1e-14
        if abs(qi[0]) > 1e-9:
            np.testing.assert_allclose(got, qi, atol=1e-12)
        else:    # at 180 deg q and -q both have w ~ 0
            assert same_rotation_quat(got, qi, 1e-12)
        np.testing.assert_allclose(rot.quat_to_matrix(got), mi, atol=1e-12)


def test_exact_180_canonical_sign():
    for axis in np.vstack([np.eye(3), -np.eye(3), [[0.6, -0.8, 0.0]], [[0.0, -0.6, 0.8]]]):
        r = Rotation.from_rotvec(axis * math.pi)
        got = rot.matrix_to_quat(as_t(r.as_matrix()))
        ref = r.as_quat(canonical=True, scalar_first=True)
        assert same_rotation_quat(got, ref, 1e-12)
    # exact matrices (w exactly 0): the first non-zero vector component is positive
    for m, q in [(((1, 0, 0), (0, -1, 0), (0, 0, -1)), (0, 1, 0, 0)),
                 (((-1, 0, 0), (0, 1, 0), (0, 0, -1)), (0, 0, 1, 0)),
                 (((-1, 0, 0), (0, -1, 0), (0, 0, 1)), (0, 0, 0, 1)),
                 (((0, 1, 0), (1, 0, 0), (0, 0, -1)), (0, math.sqrt(0.5), math.sqrt(0.5), 0))]:
        got = rot.matrix_to_quat(tuple(tuple(float(v) for v in row) for row in m))
        np.testing.assert_allclose(got, q, atol=1e-15)
        ref = Rotation.from_matrix(m).as_quat(canonical=True, scalar_first=True)
        np.testing.assert_allclose(got, ref, atol=1e-15)


def test_quat_multiply_vs_scipy():
    a, b = random_rotations(500, 1), random_rotations(500, 2)
    qa, qb = a.as_quat(scalar_first=True), b.as_quat(scalar_first=True)
    ref = (a * b).as_quat(scalar_first=True)
    for x, y, z in zip(qa, qb, ref):
        assert same_rotation_quat(rot.quat_multiply(tuple(x), tuple(y)), z, 1e-12)


def test_quat_angle_vs_scipy():
    a, b = random_rotations(1000, 3), random_rotations(1000, 4)
    ref = np.degrees((a.inv() * b).magnitude())
    for x, y, r in zip(a.as_quat(scalar_first=True), b.as_quat(scalar_first=True), ref):
        assert rot.quat_angle(tuple(x), tuple(y)) == pytest.approx(r, abs=1e-9)
        assert rot.quat_angle(tuple(x), tuple(-y)) == pytest.approx(r, abs=1e-9)   # sign-blind


def test_quat_angle_tiny_and_near_180():
    q = scipy_quat(random_rotations(1, 9))[0]
    for angle in [1e-9, 1e-6, 1e-3, 90.0, 179.999, 179.999999, 180.0]:
        d = Rotation.from_rotvec(np.radians(angle) * np.array([0.0, 0.6, 0.8]))
        q2 = scipy_quat(d * Rotation.from_quat(q, scalar_first=True))
        assert rot.quat_angle(tuple(q), tuple(q2)) == pytest.approx(angle, abs=1e-9)


# ------------------------------------------------------------------ KUKA / Fanuc

def test_abc_to_matrix_and_quat_vs_scipy():
    g = rng(6)
    abc = np.column_stack([g.uniform(-180, 180, N), g.uniform(-90, 90, N), g.uniform(-180, 180, N)])
    abc = np.vstack([abc, gimbal_abc(), [[180, 0, 180], [-180, 90, 0], [0, -90, 180], [0, 0, 0]]])
    r = Rotation.from_euler("ZYX", abc, degrees=True)
    for (a, b, c), m, q in zip(abc, r.as_matrix(), scipy_quat(r)):
        np.testing.assert_allclose(rot.abc_to_matrix(a, b, c), m, atol=ATOL)
        got = rot.abc_to_quat(a, b, c)
        assert got[0] >= 0
        if abs(q[0]) > 1e-9:
            np.testing.assert_allclose(got, q, atol=ATOL)
        else:
            assert same_rotation_quat(got, q, ATOL)
        np.testing.assert_allclose(rot.wpr_to_matrix(c, b, a), m, atol=ATOL)
        # Fanuc reference straight from scipy: R = Rz(R) Ry(P) Rx(W)
        np.testing.assert_allclose(
            rot.wpr_to_matrix(c, b, a),
            Rotation.from_euler("ZYX", [a, b, c], degrees=True).as_matrix(), atol=ATOL)


def test_matrix_to_abc_vs_scipy_random():
    r = random_rotations(N, 7)
    ref = r.as_euler("ZYX", degrees=True)
    for m, (a, b, c) in zip(r.as_matrix(), ref):
        got = rot.matrix_to_abc(as_t(m))
        assert -90.0 <= got[1] <= 90.0
        assert -180.0 < got[0] <= 180.0 and -180.0 < got[2] <= 180.0
        if abs(abs(b) - 90.0) > 1e-3:
            np.testing.assert_allclose([rot.wrap180(got[0] - a), got[1] - b,
                                        rot.wrap180(got[2] - c)], 0.0, atol=1e-9)
        np.testing.assert_allclose(rot.abc_to_matrix(*got), m, atol=1e-12)
        w, p, rr = rot.matrix_to_wpr(as_t(m))
        assert (w, p, rr) == (got[2], got[1], got[0])


def test_matrix_to_abc_gimbal_lock():
    """B at +-90 deg: our convention is C = 0 and A takes the rest, like
    scipy's ('third angle set to zero'); near it the matrix round-trips."""
    for a, b, c in gimbal_abc():
        m = rot.abc_to_matrix(a, b, c)
        got = rot.matrix_to_abc(m)
        np.testing.assert_allclose(rot.abc_to_matrix(*got), m, atol=1e-9)
        if b in (90.0, -90.0):
            assert got[2] == 0.0
            assert got[1] == pytest.approx(b, abs=1e-6)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                ref = Rotation.from_euler("ZYX", [a, b, c], degrees=True).as_euler("ZYX", degrees=True)
            assert rot.wrap180(got[0] - ref[0]) == pytest.approx(0.0, abs=1e-6)


def test_matrix_to_abc_near_180():
    for m in near_180().as_matrix():
        got = rot.matrix_to_abc(as_t(m))
        np.testing.assert_allclose(rot.abc_to_matrix(*got), m, atol=1e-12)
        assert -180.0 < got[0] <= 180.0 and -90.0 <= got[1] <= 90.0 and -180.0 < got[2] <= 180.0


@pytest.mark.parametrize("abc", [(180.0, 0.0, 180.0), (-180.0, 0.0, -180.0), (0.0, 0.0, 180.0),
                                 (180.0, 0.0, 0.0), (90.0, 0.0, -180.0), (-180.0, 45.0, -180.0)])
def test_abc_180_written_as_plus_180(abc):
    """A and C are in (-180, 180]: a half turn comes out as +180, never -180."""
    m = rot.abc_to_matrix(*abc)
    got = rot.matrix_to_abc(m)
    np.testing.assert_allclose(rot.abc_to_matrix(*got), m, atol=1e-12)
    for v in (got[0], got[2]):
        assert -180.0 < v <= 180.0
    for v, want in zip((got[0], got[2]), (abc[0], abc[2])):
        if abs(abs(want) - 180.0) < 1e-12 and abs(abs(v) - 180.0) < 1e-9:
            assert v > 0


def test_quat_to_abc_vs_scipy():
    r = random_rotations(1000, 8)
    for q, e in zip(r.as_quat(scalar_first=True), r.as_euler("ZYX", degrees=True)):
        got = rot.quat_to_abc(tuple(q))
        np.testing.assert_allclose([rot.wrap180(got[0] - e[0]), got[1] - e[1],
                                    rot.wrap180(got[2] - e[2])], 0.0, atol=1e-9)


@given(st.floats(-180, 180), st.floats(-89.9, 89.9), st.floats(-180, 180))
@settings(max_examples=300, deadline=None)
def test_abc_roundtrip_property(a, b, c):
    got = rot.quat_to_abc(rot.abc_to_quat(a, b, c))
    assert rot.wrap180(got[0] - a) == pytest.approx(0.0, abs=1e-8)
    assert got[1] == pytest.approx(b, abs=1e-8)
    assert rot.wrap180(got[2] - c) == pytest.approx(0.0, abs=1e-8)


# ------------------------------------------------------------------ small helpers

def test_matmul_matvec_transpose_vs_numpy():
    g = rng(10)
    for _ in range(200):
        a, b, v = g.normal(size=(3, 3)), g.normal(size=(3, 3)), g.normal(size=3)
        np.testing.assert_allclose(rot.matmul(as_t(a), as_t(b)), a @ b, atol=1e-12)
        np.testing.assert_allclose(rot.matvec(as_t(a), tuple(v)), a @ v, atol=1e-12)
        np.testing.assert_allclose(rot.transpose(as_t(a)), a.T, atol=0)


# ------------------------------------------------------------------ robodk

def robodk_safe(r: Rotation) -> Rotation:
    """robodk.pose_2_quaternion snaps rotations within ~0.026 deg of 180
    (and ~0.0026 deg of 0) to exact values: keep clear of those bands."""
    mag = np.degrees(r.magnitude())
    return r[(mag < 179.9) & (mag > 0.01)]


def test_kuka_vs_robodk():
    g = rng(11)
    r = random_rotations(N, 12)
    xyz = g.uniform(-3000, 3000, size=(len(r), 3))
    for t, m in zip(xyz, r.as_matrix()):
        abc = rot.matrix_to_abc(as_t(m))
        # our A, B, C -> robodk's KUKA pose is our matrix
        H = np.array(robomath.KUKA_2_Pose([*t, *abc]).rows)
        np.testing.assert_allclose(H[:3, :3], m, atol=1e-12)
        np.testing.assert_allclose(H[:3, 3], t, atol=0)
        # robodk's pose -> KUKA is our A, B, C
        H = robomath.Mat(np.vstack([np.column_stack([m, t]), [0, 0, 0, 1]]).tolist())
        ref = robomath.Pose_2_KUKA(H)
        np.testing.assert_allclose([rot.wrap180(abc[0] - ref[3]), abc[1] - ref[4],
                                    rot.wrap180(abc[2] - ref[5])], 0.0, atol=1e-9)


def test_kuka_gimbal_vs_robodk():
    for a, b, c in gimbal_abc(200, 13):
        m = rot.abc_to_matrix(a, b, c)
        H = robomath.KUKA_2_Pose([0, 0, 0, a, b, c])
        np.testing.assert_allclose(np.array(H.rows)[:3, :3], m, atol=1e-12)
        got = rot.matrix_to_abc(m)
        ref = robomath.Pose_2_KUKA(H)
        # Both write C = 0 at exactly +-90. In between, robodk already snaps
        # (|r20| > 1 - 1e-10, i.e. within ~1.4e-5 rad of B = +-90) where we
        # still split A and C (cos B > 1e-9): compare what the angles mean.
        # Ours reproduce the matrix; robodk's only to its snapping band.
        np.testing.assert_allclose(np.array(robomath.KUKA_2_Pose([0, 0, 0, *got]).rows)[:3, :3],
                                   m, atol=1e-9)
        np.testing.assert_allclose(np.array(robomath.KUKA_2_Pose([0, 0, 0, *ref[3:]]).rows)[:3, :3],
                                   m, atol=3e-5)
        if b in (90.0, -90.0):
            assert got[2] == 0.0 and ref[5] == 0.0
            assert rot.wrap180(got[0] - ref[3]) == pytest.approx(0.0, abs=1e-6)


def test_abb_vs_robodk():
    r = robodk_safe(random_rotations(N, 14))
    r = Rotation.concatenate([r, robodk_safe(near_180(300, 15, eps_deg=(0.03, 0.1, 1.0)))])
    for m, q in zip(r.as_matrix(), r.as_quat(scalar_first=True)):
        ours = rot.matrix_to_quat(as_t(m))
        H = robomath.Mat(np.vstack([np.column_stack([m, [0, 0, 0]]), [0, 0, 0, 1]]).tolist())
        ref = robomath.pose_2_quaternion(H)
        # robodk computes components from square roots: ~1e-8 near zero
        assert same_rotation_quat(ours, ref, 1e-7)
        back = np.array(robomath.quaternion_2_pose(list(ours)).rows)[:3, :3]
        np.testing.assert_allclose(back, m, atol=1e-12)
        np.testing.assert_allclose(rot.quat_to_matrix(tuple(q)), back, atol=1e-12)


def test_fanuc_vs_robodk():
    r = random_rotations(500, 16)
    for m in r.as_matrix():
        w, p, rr = rot.matrix_to_wpr(as_t(m))
        H = robomath.Fanuc_2_Pose([0, 0, 0, w, p, rr])
        np.testing.assert_allclose(np.array(H.rows)[:3, :3], m, atol=1e-12)


# -- the same conventions over arrays (ucsio.geometry.arrays) ---------------------
def test_array_conventions_vs_scipy_and_the_single_pose_forms():
    from ucsio import vendors
    from ucsio.geometry import arrays

    rng = np.random.default_rng(7)
    r = Rotation.random(200, random_state=rng)
    abc = r.as_euler("ZYX", degrees=True)
    np.testing.assert_allclose(arrays.abc_to_matrices(abc), r.as_matrix(), atol=1e-12)
    q = r.as_quat(scalar_first=True) * rng.uniform(0.5, 2.0, (200, 1))   # not normalised
    np.testing.assert_allclose(arrays.quats_to_matrices(q), r.as_matrix(), atol=1e-12)
    np.testing.assert_allclose(arrays.quat_to_matrix(r.as_quat(scalar_first=True)),
                               r.as_matrix(), atol=1e-12)
    for k in range(0, 200, 40):
        np.testing.assert_allclose(arrays.abc_to_matrices(abc[k:k + 1])[0],
                                   np.array(rot.abc_to_matrix(*abc[k])), atol=1e-12)
    # FANUC W, P, R: fixed axes x, y, z, i.e. Rz(R) Ry(P) Rx(W)
    wpr = abc[:, ::-1]
    pos = rng.normal(0, 500, (200, 3))
    T = arrays.flange_matrices(vendors.get("fanuc").angles, wpr, pos)
    np.testing.assert_allclose(T[:, :3, :3], Rotation.from_euler("xyz", wpr, degrees=True).as_matrix(),
                               atol=1e-12)
    np.testing.assert_array_equal(T[:, :3, 3], pos)
    np.testing.assert_array_equal(T[:, 3], np.tile([0, 0, 0, 1.0], (200, 1)))
    theta = Rotation.random(50, random_state=rng).as_rotvec()
    np.testing.assert_allclose(arrays.rotvecs_to_matrices(theta),
                               Rotation.from_rotvec(theta).as_matrix(), atol=1e-12)
    a, b = Rotation.random(50, random_state=rng), Rotation.random(50, random_state=rng)
    np.testing.assert_allclose(arrays.rotation_angle_deg(a.as_matrix(), b.as_matrix()),
                               np.degrees((a.inv() * b).magnitude()), atol=1e-9)


def test_the_three_point_construction_gives_the_frame_its_points_came_from():
    """``Pose.from_three_points`` (the readers' and writers' construction)
    against scipy: the origin, a point on +X and any point on the +Y side
    of the XY plane give the frame back; collinear points give None; and it
    agrees with ``method.three_points.construct`` (solve's, in numpy)."""
    from ucsio.method.three_points import construct
    rng = np.random.default_rng(3)
    for _ in range(200):
        r = Rotation.random(random_state=rng)
        t = rng.uniform(-2000, 2000, 3)
        m = r.as_matrix()
        d, a, b = rng.uniform(1, 500), rng.uniform(-500, 500), rng.uniform(1, 500)
        org, xx, xy = t, t + d * m[:, 0], t + a * m[:, 0] + b * m[:, 1]
        pose = Pose.from_three_points(org.tolist(), xx.tolist(), xy.tolist())
        assert np.allclose(pose.t, t, atol=1e-9)
        assert (r.inv() * Rotation.from_quat(np.roll(pose.q, -1))).magnitude() < 1e-9
        R, origin = construct(org, xx, xy)
        assert np.allclose(np.array(pose.matrix), R, atol=1e-12) and np.allclose(origin, t)
        assert Pose.from_three_points(org.tolist(), xx.tolist(), (t + 3 * (xx - t)).tolist()) \
            is None
    assert Pose.from_three_points((1, 2, 3), (1, 2, 3), (4, 5, 6)) is None
