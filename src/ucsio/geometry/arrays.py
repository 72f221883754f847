"""The vendors' rotation conventions over numpy arrays: a whole measurement
set, or a batch of fits, at once. The single-pose forms, in plain math for
the commands that must start fast, are ``rotations``; tests hold both to
scipy.spatial.transform."""
from __future__ import annotations

import numpy as np


def quat_to_matrix(q: np.ndarray) -> np.ndarray:
    """(..., 4) unit quaternions (w, x, y, z) -> (..., 3, 3) rotation matrices."""
    q0, qx, qy, qz = np.moveaxis(np.asarray(q, dtype=float), -1, 0)
    R = np.empty(q0.shape + (3, 3))
    R[..., 0, 0] = q0 * q0 + qx * qx - qy * qy - qz * qz
    R[..., 0, 1] = 2 * (qx * qy - q0 * qz)
    R[..., 0, 2] = 2 * (qx * qz + q0 * qy)
    R[..., 1, 0] = 2 * (qy * qx + q0 * qz)
    R[..., 1, 1] = q0 * q0 - qx * qx + qy * qy - qz * qz
    R[..., 1, 2] = 2 * (qy * qz - q0 * qx)
    R[..., 2, 0] = 2 * (qz * qx - q0 * qy)
    R[..., 2, 1] = 2 * (qz * qy + q0 * qx)
    R[..., 2, 2] = q0 * q0 - qx * qx - qy * qy + qz * qz
    return R


def abc_to_matrices(abc: np.ndarray) -> np.ndarray:
    """(n, 3) KUKA A, B, C (deg) -> (n, 3, 3): Rz(A) Ry(B) Rx(C)."""
    a, b, c = np.radians(np.asarray(abc, dtype=float)).T
    ca, sa, cb, sb, cc, sc = np.cos(a), np.sin(a), np.cos(b), np.sin(b), np.cos(c), np.sin(c)
    R = np.empty(a.shape + (3, 3))
    R[:, 0, 0] = ca * cb
    R[:, 0, 1] = ca * sb * sc - sa * cc
    R[:, 0, 2] = ca * sb * cc + sa * sc
    R[:, 1, 0] = sa * cb
    R[:, 1, 1] = sa * sb * sc + ca * cc
    R[:, 1, 2] = sa * sb * cc - ca * sc
    R[:, 2, 0] = -sb
    R[:, 2, 1] = cb * sc
    R[:, 2, 2] = cb * cc
    return R


def quats_to_matrices(q: np.ndarray) -> np.ndarray:
    """(n, 4) quaternions (q1 real) -> (n, 3, 3), normalising first."""
    q = np.asarray(q, dtype=float)
    return quat_to_matrix(q / np.linalg.norm(q, axis=1, keepdims=True))


def flange_matrices(convention, orientation: np.ndarray, position: np.ndarray) -> np.ndarray:
    """(n, 4, 4) flange poses from positions and orientations written in
    ``convention`` (a ``geometry.angles.AngleColumns``): its three angles
    (deg) in its order, or its quaternions (w, x, y, z)."""
    if convention.quaternion:
        R = quats_to_matrices(orientation)
    else:
        R = abc_to_matrices(_as_abc(np.asarray(orientation, dtype=float), convention.keys))
    T = np.zeros((len(R), 4, 4))
    T[:, :3, :3] = R
    T[:, :3, 3] = position
    T[:, 3, 3] = 1.0
    return T


def _as_abc(angles: np.ndarray, keys: str) -> np.ndarray:
    """(n, 3) angles written in the order ``keys`` -> (n, 3) A, B, C."""
    return angles if keys == "abc" else angles[:, [keys.index(k) for k in "abc"]]


def rotvecs_to_matrices(theta: np.ndarray) -> np.ndarray:
    """(S, 3) rotation vectors -> (S, 3, 3) matrices, through the unit
    quaternion."""
    angle = np.linalg.norm(theta, axis=-1)
    half = 0.5 * angle
    scale = np.where(angle > 1e-12, np.sin(half) / np.where(angle > 1e-12, angle, 1.0), 0.5)
    q = np.concatenate([np.cos(half)[..., None], theta * scale[..., None]], axis=-1)
    return quat_to_matrix(q)


def rotation_angle_deg(R_a: np.ndarray, R_b: np.ndarray) -> np.ndarray:
    """Angle (deg) of the rotation between R_a (..., 3, 3) and R_b, accurate
    near 0 and 180 deg (atan2 of sine and cosine parts of R_a^T R_b)."""
    D = np.einsum("...ji,...jk->...ik", R_a, R_b)
    cos = (np.trace(D, axis1=-2, axis2=-1) - 1.0) / 2.0
    axis = np.stack([D[..., 2, 1] - D[..., 1, 2], D[..., 0, 2] - D[..., 2, 0],
                     D[..., 1, 0] - D[..., 0, 1]], axis=-1)
    sin = np.linalg.norm(axis, axis=-1) / 2.0
    return np.degrees(np.arctan2(sin, cos))
