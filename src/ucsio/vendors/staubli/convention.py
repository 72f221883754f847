"""Stäubli's rx, ry, rz: how ucsio reads them, and why it does not write them.

x, y, z are millimetres and rx, ry, rz degrees (the .dtx files' own
values: ../shared/corpus/staubli/README.md). The order of the three
rotations is not written in the files, and Stäubli's own VAL3 documentation
was not found to quote: searched for (VAL3 reference manual, "trsf", rx ry
rz rotation order) in documentation, pages, code and issue threads, the
only statements found are third parties' (RoboDK; COMPAS's example names
Stäubli's angles Euler XYZ on moving axes; a robotics Q&A that asks and is
not answered). So the convention is NOT proved:

- ucsio READS rx, ry, rz as RoboDK does, successive rotations about the
  moving X, Y', Z'' (R = Rx(rx)·Ry(ry)·Rz(rz)), to show a frame's
  orientation (a, b, c and q), compose the frame tree and turn points into
  flange poses. Positions and the values as written (JSON's rx, ry, rz) do
  not depend on it; orientations and rotation deltas do, and the docs say so
  (docs/controllers.md, "Stäubli");
- ucsio does NOT WRITE them: ``patch`` on a .dtx is refused with this
  reason (``REFUSAL``), nothing written, until Stäubli's documentation or
  real data that shows one pose two ways proves the order.
"""
from __future__ import annotations

import math

from ...geometry import rotations as rot

READING = "R = Rx(rx)·Ry(ry)·Rz(rz), RoboDK's reading"
REFUSAL = ("Stäubli's rotation order (rx, ry, rz) is not proved from Stäubli's VAL3 "
           "documentation or real data: ucsio does not write .dtx frames, nothing written "
           "(set the frame on the pendant)")


def xyz_to_quat(rx: float, ry: float, rz: float) -> rot.Quat:
    """q = qx(rx)·qy(ry)·qz(rz): rotations about the moving X, Y', Z''."""
    hx, hy, hz = (math.radians(v) / 2 for v in (rx, ry, rz))
    qx = (math.cos(hx), math.sin(hx), 0.0, 0.0)
    qy = (math.cos(hy), 0.0, math.sin(hy), 0.0)
    qz = (math.cos(hz), 0.0, 0.0, math.sin(hz))
    return rot.quat_canonical(rot.quat_multiply(rot.quat_multiply(qx, qy), qz))
