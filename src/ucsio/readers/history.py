"""The fleet's own noise, from its past results (``plan --history FILE``).

A robot's noise is best known from the robot: every past solve's residuals
estimate it (``consistency.sigma_residual``, the per-axis σ of the used
points' residuals, what solve prints as the residuals' σ). FILE is a
``batch --json`` result (its ``entries``), one SOLUTION.json, or a folder of
them (every ``*.json`` below it that is a solution). Entries that failed
carry no σ and are skipped; a JSON file in the folder that is not a solution
is skipped and counted.

The statistic is the one ``plan``'s default takes from the seed paper: the
mean plus one standard deviation of the per-dataset σ, a noise that few of
the fleet's datasets exceed (docs/planning.md, "The noise"). One dataset
gives its own σ.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

from ..errors import UcsioError


@dataclass
class History:
    """Per-dataset residual σ (mm per axis) read from ``path``."""

    path: str
    sigmas: list[float]
    skipped: list[str] = field(default_factory=list)

    @property
    def mean(self) -> float:
        return sum(self.sigmas) / len(self.sigmas)

    @property
    def std(self) -> float:
        """The sample standard deviation (0 for one dataset)."""
        n = len(self.sigmas)
        if n < 2:
            return 0.0
        m = self.mean
        return math.sqrt(sum((s - m) ** 2 for s in self.sigmas) / (n - 1))

    @property
    def sigma(self) -> float:
        """The noise a plan takes: mean + one standard deviation."""
        return self.mean + self.std


def read_history(path) -> History:
    """The residual σ of every dataset in FILE or the folder FILE."""
    path = os.fspath(path)
    if os.path.isdir(path):
        files = sorted(os.path.join(d, f) for d, _, names in os.walk(path)
                       for f in names if f.lower().endswith(".json"))
    else:
        files = [path]
    sigmas: list[float] = []
    skipped: list[str] = []
    for f in files:
        found = sigmas_in(_read(f))
        if found is None:
            if f == path:
                raise UcsioError("--history: neither a batch --json result nor a solution "
                                 "(no entries, no consistency.sigma_residual)", file=f)
            skipped.append(f)
        sigmas.extend(found or [])
    if not sigmas:
        raise UcsioError("--history: no past dataset with a residual σ found "
                         f"({len(files)} JSON file{'s' if len(files) != 1 else ''} read)",
                         file=path)
    if not any(s > 0 for s in sigmas):
        raise UcsioError("--history: every past residual σ is 0: no noise to plan with",
                         file=path)
    return History(path, sigmas, skipped)


def _read(path: str):
    from ..method.solution import read_json

    return read_json(path)


def sigmas_in(data) -> list[float] | None:
    """The residual σ of a batch result's entries or of one solution (None
    where ``data`` is neither)."""
    if isinstance(data, dict) and isinstance(data.get("entries"), list):
        return [s for s in map(_sigma, data["entries"]) if s is not None]
    s = _sigma(data)
    return None if s is None else [s]


def _sigma(item) -> float | None:
    """A solution's or a batch entry's ``consistency.sigma_residual``."""
    cons = item.get("consistency") if isinstance(item, dict) else None
    s = cons.get("sigma_residual") if isinstance(cons, dict) else None
    if isinstance(s, bool) or not isinstance(s, (int, float)) or not math.isfinite(s) or s < 0:
        return None
    return float(s)
