"""An orientation convention, vendor-free: how a table names a frame's three
angles, in which order they are written, whether the orientation is written
as a quaternion, and its columns in SPEC's measurement CSV. Each vendor
declares its own (``vendors.<name>``: ``angles``, ``measurement_columns``);
geometry and the readers read only this description, never a vendor's name.

Every convention here is the one matrix R = Rz(A)·Ry(B)·Rx(C) (``Pose.abc``
is A, B, C); a convention differs in the names of the three angles and the
order it writes them: FANUC's W, P, R is C, B, A.
"""
from __future__ import annotations


class AngleColumns:
    """A convention's three angles: their ``names`` in a table, the ``keys``
    of Pose.abc / a pose dict (``a b c``) each written angle is, in the order
    written (``"cba"``: the first written angle is C), and whether the
    vendor writes a ``quaternion`` (w, x, y, z) rather than the angles: its
    positions and measurement columns are quaternions, and its tables show
    the quaternion beside the angles."""

    __slots__ = ("names", "keys", "quaternion")

    def __init__(self, names: tuple[str, str, str], keys: str, quaternion: bool = False):
        self.names, self.keys, self.quaternion = names, keys, quaternion


class MeasurementColumns:
    """A vendor's flange orientation columns in SPEC's measurement CSV: their
    ``names`` in the order read, how messages name them (``short``:
    ``robot_a/b/c``), and that name with the vendor's (``label``:
    ``robot_a/b/c (KUKA)``)."""

    __slots__ = ("names", "short", "label")

    def __init__(self, names: tuple[str, ...], short: str, who: str):
        self.names, self.short, self.label = names, short, f"{short} ({who})"


#: Pose.abc's own names: a table of frames of several conventions shows these.
POSE_ANGLES = AngleColumns(("a", "b", "c"), "abc")
