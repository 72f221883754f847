"""The vendors' rotation conventions, in plain math.

Commands that only list, diff or patch files run once per file under
``git diff``; importing scipy costs them a quarter of a second, so single
conversions are written out here and tested against
``scipy.spatial.transform.Rotation`` (tests/test_rotations.py). Batched work
(the solver) uses numpy.

Conventions (../shared/SPEC.md):
- matrix R maps frame coordinates to parent coordinates: p_P = R p_F + t.
- ABB quaternion (q1, q2, q3, q4) = (w, x, y, z), written with q1 >= 0.
- KUKA A, B, C: R = Rz(A) Ry(B) Rx(C), B in [-90, 90], A and C in (-180, 180].
- Fanuc W, P, R: R = Rz(R) Ry(P) Rx(W): KUKA's matrix with A=R, B=P, C=W.
"""
from __future__ import annotations

import math

Matrix = tuple[tuple[float, float, float], tuple[float, float, float], tuple[float, float, float]]
Quat = tuple[float, float, float, float]

# Below this |cos B| the split between A and C is undetermined (gimbal lock):
# we put the whole rotation about the vertical in A and write C = 0.
GIMBAL_EPS = 1e-9


def wrap180(angle: float) -> float:
    """Wrap degrees into (-180, 180]."""
    a = math.fmod(angle, 360.0)
    if a > 180.0:
        a -= 360.0
    elif a <= -180.0:
        a += 360.0
    return a + 0.0  # turns -0.0 into 0.0


def quat_normalize(q: Quat) -> Quat:
    # spelled out, not sum() over a generator: called for every pose a
    # reader builds and every delta (tens of thousands in a batch); the same
    # additions in the same order, so the same bits
    w, x, y, z = q
    n = math.sqrt(w * w + x * x + y * y + z * z)
    if n == 0.0 or not math.isfinite(n):
        raise ValueError("quaternion has zero or non-finite norm")
    return (w / n, x / n, y / n, z / n)


def quat_canonical(q: Quat) -> Quat:
    """Unit quaternion with w >= 0 (ABB writes q1 >= 0)."""
    w, x, y, z = quat_normalize(q)
    if w < 0 or (w == 0 and (x, y, z) < (0.0, 0.0, 0.0)):
        w, x, y, z = -w, -x, -y, -z
    return (w + 0.0, x + 0.0, y + 0.0, z + 0.0)


def quat_to_matrix(q: Quat) -> Matrix:
    w, x, y, z = quat_normalize(q)
    return (
        (1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)),
        (2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)),
        (2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)),
    )


def matrix_to_quat(m: Matrix) -> Quat:
    """Shepperd's method: divide by the largest of the four candidates."""
    (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = m
    tr = r00 + r11 + r22
    cands = (tr, r00, r11, r22)
    k = max(range(4), key=cands.__getitem__)
    if k == 0:
        s = 2.0 * math.sqrt(max(1.0 + tr, 0.0))
        q = (0.25 * s, (r21 - r12) / s, (r02 - r20) / s, (r10 - r01) / s)
    elif k == 1:
        s = 2.0 * math.sqrt(max(1.0 + r00 - r11 - r22, 0.0))
        q = ((r21 - r12) / s, 0.25 * s, (r01 + r10) / s, (r02 + r20) / s)
    elif k == 2:
        s = 2.0 * math.sqrt(max(1.0 + r11 - r00 - r22, 0.0))
        q = ((r02 - r20) / s, (r01 + r10) / s, 0.25 * s, (r12 + r21) / s)
    else:
        s = 2.0 * math.sqrt(max(1.0 + r22 - r00 - r11, 0.0))
        q = ((r10 - r01) / s, (r02 + r20) / s, (r12 + r21) / s, 0.25 * s)
    return quat_canonical(q)


def abc_to_matrix(a: float, b: float, c: float) -> Matrix:
    """KUKA: R = Rz(A) Ry(B) Rx(C), degrees."""
    ca, sa = math.cos(math.radians(a)), math.sin(math.radians(a))
    cb, sb = math.cos(math.radians(b)), math.sin(math.radians(b))
    cc, sc = math.cos(math.radians(c)), math.sin(math.radians(c))
    return (
        (ca * cb, ca * sb * sc - sa * cc, ca * sb * cc + sa * sc),
        (sa * cb, sa * sb * sc + ca * cc, sa * sb * cc - ca * sc),
        (-sb, cb * sc, cb * cc),
    )


def matrix_to_abc(m: Matrix) -> tuple[float, float, float]:
    """KUKA A, B, C in degrees; at B = +-90 deg, C = 0 and A takes the rest."""
    (r00, r01, _r02), (r10, r11, _r12), (r20, r21, r22) = m
    cb = math.hypot(r00, r10)
    b = math.degrees(math.atan2(-r20, cb))
    if cb < GIMBAL_EPS:
        a = math.degrees(math.atan2(-r01, r11))
        c = 0.0
    else:
        a = math.degrees(math.atan2(r10, r00))
        c = math.degrees(math.atan2(r21, r22))
    return wrap180(a), max(-90.0, min(90.0, b)) + 0.0, wrap180(c)


def canonical_abc(abc: tuple[float, float, float], q: Quat) -> tuple[float, float, float]:
    """A, B, C as given when they are in SPEC's ranges (B in [-90, 90], A and
    C in (-180, 180], and C = 0 at B = +-90), else the canonical angles of
    the same rotation ``q``."""
    a, b, c = abc
    locked = abs(abs(b) - 90.0) < 1e-9 and c != 0.0
    if -90.0 <= b <= 90.0 and -180.0 < a <= 180.0 and -180.0 < c <= 180.0 and not locked:
        return abc
    return quat_to_abc(q)


def abc_in_range(abc: tuple[float, float, float], q: Quat) -> tuple[float, float, float]:
    """A, B, C as given when they are in SPEC's written ranges (B in [-90,
    90], A and C in (-180, 180]), at B = +-90 too; else the canonical angles
    of the same rotation ``q``: what a file holds, as a reviewer reads it."""
    a, b, c = abc
    if -90.0 <= b <= 90.0 and -180.0 < a <= 180.0 and -180.0 < c <= 180.0:
        return abc
    return quat_to_abc(q)


def nearest_abc(q: Quat, near: tuple[float, float, float],
                tolerance: float) -> tuple[float, float, float]:
    """Of the A, B, C triples in SPEC's ranges that give rotation ``q``
    within ``tolerance`` degrees, the one nearest ``near`` (the values a file
    holds now), so that a small correction looks small to a reviewer.

    Away from B = +-90 the triple is unique and this is ``quat_to_abc``. At
    B = +90 only A - C matters (R = Rz(A - C) Ry(90)), at B = -90 only A + C:
    moving along (t, 0, +-t) keeps the rotation, and near the lock changes it
    by a little, growing with t; so the shift towards ``near`` is the whole
    one at the lock and shrinks (bisected) until the rotation is within
    ``tolerance`` next to it."""
    a1, b1, c1 = quat_to_abc(q)
    sign = 1.0 if b1 > 0.0 else -1.0
    da, dc = wrap180(near[0] - a1), wrap180(near[2] - c1)

    def farness(t: float) -> float:
        return wrap180(t - da) ** 2 + wrap180(sign * t - dc) ** 2

    # nearest to (da, dc) on the line (t, sign t): their mean, or 180 from it
    # where the wraps put it on the other side
    mean = (da + sign * dc) / 2.0
    t = min((mean, wrap180(mean + 180.0)), key=farness)
    if t == 0.0:
        return a1, b1, c1

    def shifted(f: float) -> tuple[float, float, float]:
        return wrap180(a1 + f * t), b1, wrap180(c1 + sign * f * t)

    if quat_angle(abc_to_quat(*shifted(1.0)), q) <= tolerance:
        return shifted(1.0)
    lo, hi = 0.0, 1.0       # shifted(lo) is within tolerance (lo = 0: q's own triple)
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        if quat_angle(abc_to_quat(*shifted(mid)), q) <= tolerance:
            lo = mid
        else:
            hi = mid
    # away from the lock the room is a few tolerances wide: not worth a
    # triple that differs from q's own in the last digits
    return shifted(lo) if lo * abs(t) > 10.0 * tolerance else (a1, b1, c1)


def abc_to_quat(a: float, b: float, c: float) -> Quat:
    ha, hb, hc = (math.radians(v) / 2 for v in (a, b, c))
    ca, sa = math.cos(ha), math.sin(ha)
    cb, sb = math.cos(hb), math.sin(hb)
    cc, sc = math.cos(hc), math.sin(hc)
    # q = qz(A) * qy(B) * qx(C)
    return quat_canonical((
        ca * cb * cc + sa * sb * sc,
        ca * cb * sc - sa * sb * cc,
        ca * sb * cc + sa * cb * sc,
        sa * cb * cc - ca * sb * sc,
    ))


def quat_to_abc(q: Quat) -> tuple[float, float, float]:
    return matrix_to_abc(quat_to_matrix(q))


def wpr_to_matrix(w: float, p: float, r: float) -> Matrix:
    """Fanuc: R = Rz(R) Ry(P) Rx(W), the KUKA matrix with A=R, B=P, C=W."""
    return abc_to_matrix(r, p, w)


def matrix_to_wpr(m: Matrix) -> tuple[float, float, float]:
    a, b, c = matrix_to_abc(m)
    return c, b, a


def quat_multiply(p: Quat, q: Quat) -> Quat:
    pw, px, py, pz = p
    qw, qx, qy, qz = q
    return (
        pw * qw - px * qx - py * qy - pz * qz,
        pw * qx + px * qw + py * qz - pz * qy,
        pw * qy - px * qz + py * qw + pz * qx,
        pw * qz + px * qy - py * qx + pz * qw,
    )


def rotvec_to_quat(v) -> Quat:
    """A rotation vector (radians: the axis times the angle, Universal
    Robots' rx, ry, rz) as a unit quaternion; sin(θ/2)/θ by its series near
    0, where the division loses digits."""
    x, y, z = (float(c) for c in v)
    theta = math.sqrt(x * x + y * y + z * z)
    half = 0.5 * theta
    k = 0.5 - theta * theta / 48.0 if theta < 1e-4 else math.sin(half) / theta
    return (math.cos(half), x * k, y * k, z * k)


def quat_to_rotvec(q: Quat) -> tuple[float, float, float]:
    """The rotation vector (radians) of a quaternion: angle in [0, π], the
    angle from atan2 (accurate near 0 and π, unlike acos)."""
    w, x, y, z = quat_normalize(q)
    if w < 0.0:
        w, x, y, z = -w, -x, -y, -z
    s = math.sqrt(x * x + y * y + z * z)
    theta = 2.0 * math.atan2(s, w)
    k = theta / s if s > 0.0 else 2.0     # atan2 keeps theta / s accurate for a small s
    return (x * k + 0.0, y * k + 0.0, z * k + 0.0)


def quat_angle(p: Quat, q: Quat) -> float:
    """Degrees of the single rotation taking orientation p to q."""
    pw, px, py, pz = quat_normalize(p)
    qw, qx, qy, qz = quat_normalize(q)
    # p^-1 q = (w, v); 2*atan2(|v|, |w|) stays accurate near 0 and 180 deg,
    # where acos of the dot product does not.
    w = pw * qw + px * qx + py * qy + pz * qz
    vx = pw * qx - px * qw - py * qz + pz * qy
    vy = pw * qy + px * qz - py * qw - pz * qx
    vz = pw * qz - px * qy + py * qx - pz * qw
    return math.degrees(2.0 * math.atan2(math.sqrt(vx * vx + vy * vy + vz * vz), abs(w)))


def matmul(a: Matrix, b: Matrix) -> Matrix:
    return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3))
                 for i in range(3))  # type: ignore[return-value]


def matvec(a: Matrix, v) -> tuple[float, float, float]:
    return tuple(sum(a[i][k] * v[k] for k in range(3)) for i in range(3))  # type: ignore[return-value]


def transpose(a: Matrix) -> Matrix:
    return tuple(tuple(a[j][i] for j in range(3)) for i in range(3))  # type: ignore[return-value]
