"""The usual mistakes behind a rejected measurement, named (exit 2).

A tracker file in metres read as millimetres, angles written in radians, an
ABB quaternion written x, y, z, w: each makes a good measurement fit badly,
and "measure again" would be the wrong advice. Each is cheap to recognise:

- the laser side's spread (RMS distance from its centroid) differs from the
  robot side's by the factor between two units: a rigid motion keeps
  distances, so a correct dataset's ratio is about 1;
- every angle within ±π (the range of radians);
- a quaternion read with the real part last.

A suspicion alone never refuses a dataset: only a rejected fit is looked at,
and a mistake is named only when the other reading fits, accepted by the
same rules with at most half the residuals. A correct dataset is then never
refused: an accepted one is not looked at, and a rejected one is not
rescued by reading its numbers another way.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from .. import vendors
from ..defaults import LENGTH_UNITS
from ..errors import UcsioError
from ..geometry.arrays import flange_matrices
from .measurement import Measurement, spec_orientation

#: A laser/robot spread ratio this close (as a factor) to the ratio of two
#: units suggests the other unit.
SPREAD_FACTOR = 1.5
#: Radians written to 4 decimals: π rounds up to 3.1416.
PI_WRITTEN = 3.1416
#: The other reading must fit with at most this fraction of the residuals' RMS.
BETTER = 0.5


@dataclass
class Reading:
    """How the files were read: the options that state it."""

    laser_units: str = "mm"
    angle_units: str = "deg"
    quaternion_order: str = "wxyz"


@dataclass
class Alternative:
    measurement: Measurement
    key: str             # the setting that states it: "laser_units"
    value: str           # "m"
    mistake: str         # what the numbers look like


def option(key: str, value: str) -> str:
    """How the command line states a reading: ``--laser-units m``."""
    return f"--{key.replace('_', '-')} {value}"


def named_mistake(meas: Measurement, rejected, refit: Callable[[Measurement], object],
                  reading: Reading = Reading(),
                  spelled: Callable[[str, str], str] = option) -> UcsioError | None:
    """The error naming the mistake a rejected fit comes from, or None.
    ``refit``: the same solve (its TCP, settings) on another reading;
    ``spelled``: how the user states it (an option, a manifest key)."""
    for alt in alternatives(meas, reading):
        try:
            other = refit(alt.measurement)
        except UcsioError:
            continue
        if other.accepted and other.rms <= BETTER * rejected.rms:
            return UcsioError(
                f"{alt.mistake}: read that way the points fit (rms {other.rms:.3f} mm, against "
                f"{rejected.rms:.3f} mm as read); say so with {spelled(alt.key, alt.value)}",
                file=meas.path)
    return None


def alternatives(meas: Measurement, reading: Reading) -> list[Alternative]:
    """The other readings worth a refit."""
    found = []
    units = _laser_units(meas, reading.laser_units)
    if units:
        found.append(units)
    if meas.orientation is not None and meas.orientation.shape[1]:
        orientation = _orientation(meas, reading)
        if orientation:
            found.append(orientation)
    return found


def spread(points: np.ndarray) -> float:
    """RMS distance from the centroid."""
    return float(np.sqrt(np.mean(np.sum((points - points.mean(axis=0)) ** 2, axis=1))))


def _laser_units(meas: Measurement, current: str) -> Alternative | None:
    laser = spread(meas.laser)
    if not laser > 0:
        return None
    ratio = spread(meas.flange[:, :3, 3]) / laser
    for unit, size in LENGTH_UNITS.items():
        factor = size / LENGTH_UNITS[current]
        if unit != current and abs(math.log(ratio / factor)) <= math.log(SPREAD_FACTOR):
            return Alternative(
                _replace(meas, laser=meas.laser * factor), "laser_units", unit,
                f"the robot's points spread {ratio:.4g} times as wide as the laser's: the "
                f"laser coordinates look written in {unit}, read as {current}")
    return None


def _orientation(meas: Measurement, reading: Reading) -> Alternative | None:
    written = meas.orientation
    position = meas.flange[:, :3, 3]
    vendor = vendors.get(meas.form)
    convention, columns = vendor.angles, vendor.measurement_columns.short
    if convention.quaternion:
        other = "xyzw" if reading.quaternion_order == "wxyz" else "wxyz"
        flange = flange_matrices(convention,
                                 spec_orientation(convention, written, quaternion_order=other),
                                 position)
        real = "last (x, y, z, w)" if other == "xyzw" else "first (w, x, y, z)"
        return Alternative(_replace(meas, flange=flange), "quaternion_order", other,
                           f"{columns} look written with the real part {real}")
    if reading.angle_units == "deg" and np.all(np.abs(written) <= PI_WRITTEN):
        flange = flange_matrices(convention, spec_orientation(convention, written, "rad"),
                                 position)
        return Alternative(_replace(meas, flange=flange), "angle_units", "rad",
                           f"every angle of {columns} lies within ±π: they look written in "
                           "radians, read as degrees")
    return None


def _replace(meas: Measurement, **changes) -> Measurement:
    from dataclasses import replace
    return replace(meas, **changes)
