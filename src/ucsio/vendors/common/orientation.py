"""The vendors' orientation conventions as generic code asks for them.

Each vendor declares ``angles`` (a ``geometry.angles.AngleColumns``: its
angle names and order, or its quaternion) and ``measurement_columns`` (a
``geometry.angles.MeasurementColumns``: its orientation columns in SPEC's
measurement CSV). Tables and the measurement
reader ask here, by a frame's or a file's vendor name, never naming one.
"""
from __future__ import annotations

from ... import vendors
from ...geometry.angles import POSE_ANGLES, AngleColumns, MeasurementColumns


def angle_columns(names) -> AngleColumns:
    """The angle columns of a table of frames of the vendors ``names`` (one
    name, or several): that vendor's own where they are one, else Pose.abc's
    a, b, c (also for no vendor, or one not registered)."""
    names = {names} if isinstance(names, str) or names is None else set(names)
    only = names.pop() if len(names) == 1 else None
    return vendors.get(only).angles if only in vendors.BY_NAME else POSE_ANGLES


def measurement_forms() -> list[tuple[str, MeasurementColumns]]:
    """Every vendor's measurement columns, by vendor name, in the order of
    their first column: messages list them the same whatever the registry's order."""
    forms = [(e.name, vendors.get(e.name).measurement_columns) for e in vendors.VENDORS]
    return sorted(((name, cols) for name, cols in forms if cols is not None),
                  key=lambda form: form[1].names[0])
