"""The method of ``ucsio solve`` (../shared/SPEC.md, "The method").

1. Robot point i = flange pose i applied to the TCP offset.
2. Fit R, t (robot = R laser + t) with Horn's closed form (``horn``).
3. Residual of a point: |robot_i - (R laser_i + t)|; leave-one-out residual:
   the same against the frame fitted from all the other used points (one
   batched Horn call for the n subsets).
4. Exclusion: while the largest leave-one-out residual among the used points
   exceeds the threshold, exclude that one point and refit; stop as soon as
   every remaining point's residual in the refit is within the threshold.
   Fewer than ``min_points`` left: rejected. With exclusion on, a set whose
   used points are still not all within the threshold when exclusion cannot
   go on (3 points left: no leave-one-out residual; every leave-one-out frame
   degenerate) is rejected too: nothing vouches for that frame.
   ``--no-exclusion`` keeps every point, and then the point count alone
   decides (``acceptance``); ``reason`` says why a set was rejected.
5. Degenerate point sets raise UcsioError (exit 2).

Also ``uncertainty`` (Monte Carlo through the batched solver, with a
first-order analytical estimate alongside). Reading a SOLUTION.json back is
``ucsio.method.solution`` (no numpy), re-exported here.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Iterable, Sequence

import numpy as np

from . import horn
from .. import defaults
from ..errors import UcsioError
from ..geometry.arrays import rotation_angle_deg
from ..geometry.frames import Pose
from .solution import load_solution, pose_from_json

DEFAULT_THRESHOLD = defaults.THRESHOLD
DEFAULT_MIN_POINTS = defaults.MIN_POINTS
DEFAULT_SIGMA_LASER = defaults.SIGMA_LASER
DEFAULT_SIGMA_ROBOT = defaults.SIGMA_ROBOT


@dataclass
class PointResult:
    name: str
    residual: float          # mm, distance to the final fitted frame
    loo_residual: float      # mm, distance to the frame fitted from the other used points (nan: undetermined)
    used: bool
    dx: float                # robot - (R laser + t), robot world, mm
    dy: float
    dz: float
    excluded_by: str | None  # 'auto' | 'hand' | None
    weight: float = 1.0
    line: int | None = None
    laser: list[float] | None = None   # the point in the UCS, mm (what the tracker measured)
    robot: list[float] | None = None   # the reflector in robot world (flange pose · TCP), mm

    def as_dict(self) -> dict[str, Any]:
        d = {"name": self.name, "residual": self.residual,
             "loo_residual": None if not math.isfinite(self.loo_residual) else self.loo_residual,
             "used": self.used, "dx": self.dx, "dy": self.dy, "dz": self.dz,
             "excluded_by": self.excluded_by, "weight": self.weight, "line": self.line}
        if self.laser is not None:      # the point pair itself: what `ucsio view` draws
            d["laser"], d["robot"] = self.laser, self.robot
        return d


@dataclass
class Solution:
    pose: Pose               # the UCS in robot world: robot = R laser + t
    points: list[PointResult]
    n_points: int
    n_used: int
    rms: float
    mean: float
    max: float
    accepted: bool
    tcp: tuple[float, float, float] = (0.0, 0.0, 0.0)
    threshold: float = DEFAULT_THRESHOLD
    min_points: int = DEFAULT_MIN_POINTS
    source: str | None = None
    tool: str | None = None
    no_exclusion: bool = False
    uncertainty: dict[str, Any] | None = None
    reason: str | None = None    # why the dataset was rejected (None when accepted)
    precision: dict[str, Any] | None = None  # the determinacy gate's numbers (SPEC point 7)
    tcp_solved: dict[str, Any] | None = None  # --tcp solve: x, y, z, std (ucsio.method.tcp_solve)
    diagnosis: dict[str, Any] | None = None   # a rejection a TCP change explains (tcp_solve)
    covariance: dict[str, Any] | None = None  # the frame's per unit noise (working.covariance_json)
    consistency: dict[str, Any] | None = None  # the noise check (ucsio.method.noise)
    working_points: list[dict[str, Any]] | None = None   # --at: each name, x, y, z, at_95
    worst: dict[str, Any] | None = None       # --at: the working point predicted worst
    gate: str = "reach"                        # what the determinacy gate judged: reach | at
    at_source: str | None = None               # where the working points came from
    three_point_frame: dict[str, Any] | None = None  # the pendant's frame (three_points.compare)
    three_points: dict[str, Any] | None = None       # the points that set it (three_points.setting)

    def __post_init__(self) -> None:
        # a Solution built elsewhere (the batched solver) without a reason still says why
        if not self.accepted and self.reason is None:
            self.reason = (f"too few points: {self.n_used} used, at least {self.min_points}"
                           " needed")

    @property
    def matrix4(self) -> list[list[float]]:
        m = self.pose.matrix
        return [[*m[0], self.pose.x], [*m[1], self.pose.y], [*m[2], self.pose.z],
                [0.0, 0.0, 0.0, 1.0]]

    def frame_dict(self) -> dict[str, Any]:
        d = self.pose.as_dict()
        w, p, r = self.pose.wpr
        d.update({"w": w, "p": p, "r": r, "matrix": self.matrix4})
        return d

    @property
    def warnings(self) -> list[str]:
        """What a reviewer must read although the set is accepted: points
        kept over the threshold (--no-exclusion keeps them on purpose)."""
        over = [p.name for p in self.points if p.used and p.residual > self.threshold]
        if not (self.accepted and over):
            return []
        return [f"{len(over)} used point{'s' if len(over) > 1 else ''} over the "
                f"{self.threshold:g} mm threshold, kept (--no-exclusion): {', '.join(over)}"]

    def as_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {
            "frame": self.frame_dict(),
            "points": [p.as_dict() for p in self.points],
            "n_points": self.n_points, "n_used": self.n_used,
            "rms": self.rms, "mean": self.mean, "max": self.max,
            "accepted": self.accepted, "reason": self.reason, "warnings": self.warnings,
            "precision": self.precision,
            "tcp": self.tcp_solved if self.tcp_solved is not None else
            {"x": self.tcp[0], "y": self.tcp[1], "z": self.tcp[2], "solved": False},
            "settings": {"tcp": list(self.tcp), "tool": self.tool, "threshold": self.threshold,
                         "min_points": self.min_points, "no_exclusion": self.no_exclusion,
                         "source": self.source},
        }
        if self.uncertainty is not None:
            d["uncertainty"] = self.uncertainty
        if self.diagnosis is not None:
            d["diagnosis"] = self.diagnosis
        if self.consistency is not None:
            d["consistency"] = self.consistency
        if self.tcp_solved is not None and self.precision:       # SPEC's keys, beside precision's
            d["tcp_at_95"] = self.precision.get("tcp_at_95")
            d["orientation_span"] = self.precision.get("orientation_span")
        if self.working_points is not None:
            d["working_points"] = self.working_points
            d["worst"] = self.worst
            d["gate"] = self.gate
            d["at"] = self.at_source
        if self.covariance is not None:
            d["covariance"] = self.covariance
        if self.three_point_frame is not None:
            d["three_point_frame"] = self.three_point_frame
        if self.three_points is not None:
            d["three_points"] = self.three_points
        return d


# ---------------------------------------------------------------- fitting

def leave_one_out(laser: np.ndarray, robot: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """(m,) distance of each point to the frame fitted from the other m-1
    points (the round of ``solve_many``: one batched Horn call); nan where
    those m-1 points cannot determine a frame (or m - 1 < 3)."""
    m = len(laser)
    data = [Dataset(names=[str(k) for k in range(m)], laser=np.asarray(laser, dtype=float),
                    robot=np.asarray(robot, dtype=float), weights=np.asarray(weights, dtype=float))]
    return _round(data, [0], {0: np.ones(m, dtype=bool)})[0][4]


def hand_marks(names: Sequence[str], exclude, path: str | None) -> list[str | None]:
    """Per point, "hand" where ``--exclude`` names it (case-insensitively),
    else None; a name that is no point is an error listing the points."""
    marks: list[str | None] = [None] * len(names)
    by_name = {nm.casefold(): k for k, nm in enumerate(names)}
    for name in exclude:
        k = by_name.get(name.strip().casefold())
        if k is None:
            raise UcsioError(f"--exclude {name!r}: no such point (points: {', '.join(names)})",
                             file=path)
        marks[k] = "hand"
    return marks


def next_exclusion(used: np.ndarray, resid: np.ndarray, loo: np.ndarray, *, first: bool,
                   threshold: float, no_exclusion: bool, fewest: int) -> int | None:
    """One step of the exclusion rule (SPEC, method point 6): None when the
    fit stands, else the point to exclude next, the used one with the
    largest leave-one-out residual above the threshold. After the first fit
    it stops once every used residual is within the threshold; it never goes
    below ``fewest`` points (what the fit itself needs: it runs to its end
    below --min-points, so a rejected set still lists every point the rule
    excludes)."""
    if not first and resid[used].max() <= threshold:
        return None
    if no_exclusion or int(used.sum()) - 1 < fewest:
        return None
    lu = np.where(used, loo, np.nan)
    if not np.isfinite(lu).any() or np.nanmax(lu) <= threshold:
        return None
    return int(np.nanargmax(lu))


def acceptance(n_used: int, max_residual: float, *, threshold: float, min_points: int,
               no_exclusion: bool = False, n_auto: int = 0) -> tuple[bool, str | None]:
    """Judge a fitted set: (accepted, reason why not).

    - fewer than ``min_points`` used points: rejected (measure again);
    - with exclusion on, the used points must all be within ``threshold`` of
      the final frame. The exclusion loop ends with points over it only when
      it cannot single out a culprit (3 points left, so no leave-one-out
      residual; or no leave-one-out frame determined), and then nothing has
      judged the frame: rejected;
    - with ``no_exclusion`` every point is kept on purpose and the residuals
      are the engineer's to read: acceptance is by the point count alone.
    """
    if n_used < min_points:
        if n_auto:
            return False, (f"too few points within the threshold: {n_used} left after excluding "
                           f"{n_auto} outlier{'s' if n_auto != 1 else ''}, at least {min_points}"
                           " needed")
        return False, f"too few points: {n_used} used, at least {min_points} needed"
    if not no_exclusion and not max_residual <= threshold:
        why = ("the leave-one-out residual needs at least 4 points" if n_used < 4
               else "no leave-one-out frame singles out an outlier")
        return False, (f"residuals over the threshold and no point can be singled out: max "
                       f"{max_residual:.3f} mm > {threshold:g} mm with {n_used} points used "
                       f"({why})")
    return True, None


def solve_points(names: Sequence[str], laser, robot, weights=None, *,
                 threshold: float = DEFAULT_THRESHOLD, min_points: int = DEFAULT_MIN_POINTS,
                 exclude: Iterable[str] = (), no_exclusion: bool = False,
                 lines: Sequence[int | None] | None = None, reach: float = defaults.REACH,
                 sigma_laser: float = DEFAULT_SIGMA_LASER,
                 sigma_robot: float = DEFAULT_SIGMA_ROBOT, at=None,
                 gate: str = "reach") -> Solution:
    """The method on points already in robot world (robot = flange * tcp):
    a batch of one through ``solve_many``, so ``solve`` and ``batch`` share
    one implementation of the exclusion rule. ``at``: working points
    (``readers.points.Points``, UCS) whose 95 % error the solution predicts;
    ``gate`` "at": the determinacy gate judges the worst of them."""
    laser = np.asarray(laser, dtype=float)
    robot = np.asarray(robot, dtype=float)
    n = len(names)
    if laser.shape != (n, 3) or robot.shape != (n, 3):
        raise ValueError("names, laser (n, 3) and robot (n, 3) must agree")
    weights = np.ones(n) if weights is None else np.asarray(weights, dtype=float)
    if not threshold > 0:
        raise UcsioError(f"threshold must be positive, got {threshold}")
    if min_points < 3:
        raise UcsioError(f"min-points must be at least 3, got {min_points}")
    if not (math.isfinite(reach) and reach >= 0):
        raise UcsioError(f"--reach {reach}: a distance must be a finite number >= 0 (mm)")
    check_sigmas(sigma_laser, sigma_robot)
    check_gate(gate, at)
    result = solve_many([Dataset(names=list(names), laser=laser, robot=robot, weights=weights,
                                 threshold=threshold, min_points=min_points,
                                 exclude=tuple(exclude), no_exclusion=no_exclusion,
                                 lines=None if lines is None else list(lines),
                                 sigma_stated=math.hypot(sigma_laser, sigma_robot),
                                 reach=float(reach), at=at, gate=gate)])[0]
    if isinstance(result, UcsioError):
        raise result
    return result


#: padded (sets x points) elements above which one round is split into
#: batched calls by point count (one 100,000-point dataset would otherwise
#: pad every 8-point one to 100,000 points).
PAD_BUDGET = 6_000_000


@dataclass
class Dataset:
    """One dataset for ``solve_many``: points already in robot world."""

    names: list[str]
    laser: np.ndarray            # (n, 3)
    robot: np.ndarray            # (n, 3)
    weights: np.ndarray          # (n,)
    threshold: float = DEFAULT_THRESHOLD
    min_points: int = DEFAULT_MIN_POINTS
    exclude: tuple[str, ...] = ()
    no_exclusion: bool = False
    lines: list[int] | None = None
    path: str | None = None      # for error messages
    sigma_stated: float = math.hypot(defaults.SIGMA_LASER, defaults.SIGMA_ROBOT)
    reach: float = defaults.REACH
    at: Any = None               # working points (readers.points.Points), UCS
    gate: str = "reach"          # "at": the gate judges the worst working point


def _round(data: list[Dataset], active: list[int], used: dict[int, np.ndarray]):
    """For every active dataset: the fit of its used points and the
    leave-one-out fit of each point, in as few batched calls as the padding
    budget allows (one, normally). The leave-one-out fits come from each
    set's sums less the point's own terms (``horn.leave_one_out``), so a
    round costs O(points) memory and time. Returns per dataset (R, t,
    status, residual (n,), loo (n,) with nan where undetermined or not used)."""
    out: dict[int, tuple] = {}
    sizes = {i: len(data[i].names) for i in active}
    n_max = max(sizes.values())
    if len(active) * n_max * 3 <= PAD_BUDGET:
        chunks = [active]
    else:   # bucket by point count (powers of two), so padding stays bounded
        buckets: dict[int, list[int]] = {}
        for i in active:
            buckets.setdefault(max(4, 1 << (sizes[i] - 1).bit_length()), []).append(i)
        chunks = [buckets[k] for k in sorted(buckets)]
    for chunk in chunks:
        A = len(chunk)
        n = max(sizes[i] for i in chunk)
        L = np.zeros((A, n, 3))
        Rb = np.zeros((A, n, 3))
        W = np.zeros((A, n))
        for a, i in enumerate(chunk):
            d = data[i]
            m = sizes[i]
            L[a, :m] = d.laser
            Rb[a, :m] = d.robot
            W[a, :m] = d.weights * used[i]
        fit = horn.horn_batch(L, Rb, W)
        resid = np.linalg.norm(Rb - fit.apply(L), axis=2)              # (A, n)
        loo, loo_status = horn.leave_one_out(L, Rb, W)
        n_used = (W > 0).sum(axis=1)
        loo = np.where((loo_status == horn.OK) & (W > 0) & (n_used[:, None] >= 4), loo, np.nan)
        for a, i in enumerate(chunk):
            m = sizes[i]
            out[i] = (fit.R[a], fit.t[a], int(fit.status[a]), resid[a, :m], loo[a, :m])
    return out


def _unusable(d: Dataset) -> UcsioError | None:
    """Numbers no fit can use (the readers name the line; this is the net for
    every other caller): not finite, or so large that float64 cannot resolve
    a micrometre; weights over the same bound. Within these, Horn's sums
    cannot overflow."""
    limit = 4 * defaults.MAX_MAGNITUDE           # a flange position through a TCP: |p| + |tcp|
    # one reduction per array (a NaN makes max/min NaN, and every comparison
    # with NaN is False, so "not <=" also catches it): this runs per dataset
    for what, arr in (("laser", d.laser), ("robot", d.robot)):
        if arr.size and not np.abs(arr).max() <= limit:
            return UcsioError(f"{what} coordinates not finite or beyond {limit:.0e} mm: "
                              "double precision cannot fit them", file=d.path)
    w = d.weights
    if w.size and not (w.min() > 0 and w.max() <= defaults.MAX_MAGNITUDE):
        return UcsioError(f"weights must be positive and at most {defaults.MAX_MAGNITUDE:.0e}",
                          file=d.path)
    return None


def _precision(data: Sequence[Dataset], final: dict[int, tuple],
               used: dict[int, np.ndarray]) -> dict[int, dict[str, Any]]:
    """The determinacy gate's numbers (``ucsio.method.precision``) for every final
    fit, in one batched call: per dataset ``precision`` (sigma, angle_std,
    reach, at_reach, ...), ``covariance`` (per unit noise, for working
    points later: ``working``), ``consistency`` (the noise check) and, for a
    dataset with working points, ``working_points`` and ``worst``."""
    from . import noise, working
    from . import precision as prec

    order = list(final)
    if not order:
        return {}
    n = max(len(data[i].names) for i in order)
    L = np.zeros((len(order), n, 3))
    W = np.zeros((len(order), n))
    Rs = np.empty((len(order), 3, 3))
    e2 = np.empty(len(order))
    for a, i in enumerate(order):
        d, u, (R, _t, _s, resid, _l) = data[i], used[i], final[i]
        m = len(d.names)
        L[a, :m] = d.laser
        W[a, :m] = d.weights * u
        Rs[a] = R
        e2[a] = float(np.sum(resid[u] ** 2))
    n_used = (W > 0).sum(axis=1)
    stated = [data[i].sigma_stated for i in order]
    p = prec.predict(L, W, Rs, e2, n_used, stated, [data[i].reach for i in order])
    # one .tolist() per array, not a float() per number (10,000 datasets in a batch)
    sigma, angle_std = p["sigma"].tolist(), p["angle_std"].tolist()
    at_reach, at_centroid, spread = (p["at_reach"].tolist(), p["at_centroid"].tolist(),
                                     p["spread"].tolist())
    s_res, dof, source = p["sigma_residual"].tolist(), p["dof"].tolist(), p["sigma_source"]
    K, centroid = p["K"], p["centroid"]
    e2l, nl = e2.tolist(), n_used.tolist()
    out = {}
    for a, i in enumerate(order):
        d = data[i]
        item = {"sigma": sigma[a], "angle_std": angle_std[a],
                "reach": float(d.reach), "at_reach": at_reach[a],
                "at_centroid": at_centroid[a], "spread": spread[a],
                "sigma_source": str(source[a]), "dof": dof[a]}
        if not item["at_reach"] <= d.threshold:
            item["reason"] = prec.reason(item["at_reach"], item["at_centroid"], d.reach,
                                         d.threshold, item["sigma"], item["angle_std"],
                                         item["spread"])
        cov = working.covariance_json(K[a], centroid[a], stated[a], s_res[a], dof[a])
        got = {"precision": item, "covariance": cov,
               "consistency": noise.consistency(e2l[a], nl[a], 6, stated[a])}
        if d.at is not None:
            got["working_points"], got["worst"] = working.predict(cov, Rs[a], d.at)
        out[i] = got
    return out


def solve_many(data: Sequence[Dataset]) -> list:
    """The method on many datasets at once (``solve_points`` is a batch of one).

    Floating-point warnings are silenced: a degenerate subset gives nan or
    inf, which the status codes and ``isfinite`` checks judge; a numpy
    warning on the terminal would tell the engineer nothing.
    """
    with np.errstate(all="ignore"):
        return _solve_many(data)


def _solve_many(data: Sequence[Dataset]) -> list:
    """``solve_many`` without the floating-point guard.

    Each round fits every still-active dataset and all its leave-one-out
    subsets in one batched Horn call; the exclusion rule then runs per
    dataset on those numbers. Rounds = 1 + the most points any dataset
    excludes. Returns, per dataset, a ``ucsio.method.solve.Solution`` or the
    ``UcsioError`` that ``solve_points`` would have raised."""
    results: list = [None] * len(data)
    used: dict[int, np.ndarray] = {}
    excluded_by: dict[int, list] = {}
    active: list[int] = []
    for i, d in enumerate(data):
        try:
            marks = hand_marks(d.names, d.exclude, d.path)
        except UcsioError as exc:
            results[i] = exc
            continue
        bad = _unusable(d)
        if bad is not None:
            results[i] = bad
            continue
        used[i] = np.array([m is None for m in marks])
        excluded_by[i] = marks
        active.append(i)

    first = {i: True for i in active}
    final: dict[int, tuple] = {}
    while active:
        fits = _round(data, active, used)
        still: list[int] = []
        for i in active:
            d = data[i]
            R, t, status, resid, loo = fits[i]
            u = used[i]
            if status != horn.OK:
                which = "" if u.all() else f" (of the {int(u.sum())} points used)"
                results[i] = UcsioError(f"cannot fit a frame{which}: {horn.REASONS[status]}",
                                        file=d.path)
                continue
            worst = next_exclusion(u, resid, loo, first=first[i], threshold=d.threshold,
                                   no_exclusion=d.no_exclusion, fewest=3)
            first[i] = False
            if worst is None:
                final[i] = fits[i]
                continue
            u[worst] = False
            excluded_by[i][worst] = "auto"
            still.append(i)
        active = still

    gate = _precision(data, final, used)
    for i, (R, t, status, resid, loo) in final.items():
        d = data[i]
        u = used[i]
        dvec = d.robot - (d.laser @ R.T + t)
        r_used = resid[u]
        n_used = len(r_used)
        r_max = float(r_used.max())
        pose = Pose.from_matrix(tuple(map(tuple, R.tolist())), t.tolist())
        accepted, reason = acceptance(n_used, r_max, threshold=d.threshold,
                                      min_points=d.min_points, no_exclusion=d.no_exclusion,
                                      n_auto=excluded_by[i].count("auto"))
        got = gate[i]
        precision = got["precision"]
        accepted, reason = judge(accepted, reason, precision, got.get("worst"), d.gate,
                                 d.threshold)
        # plain floats from one .tolist() per array: the per-number float()
        # calls were a large part of batch's bookkeeping at 10,000 datasets
        lines = d.lines if d.lines is not None else [None] * len(d.names)
        points = [PointResult(name=name, residual=r, loo_residual=lo, used=us,
                              dx=dv[0], dy=dv[1], dz=dv[2], excluded_by=ex, weight=w, line=ln,
                              laser=la, robot=ro)
                  for name, r, lo, us, dv, ex, w, ln, la, ro in zip(
                      d.names, resid.tolist(), np.where(u, loo, resid).tolist(), u.tolist(),
                      dvec.tolist(), excluded_by[i], np.asarray(d.weights, float).tolist(),
                      lines, np.asarray(d.laser, float).tolist(),
                      np.asarray(d.robot, float).tolist())]
        results[i] = Solution(pose=pose, points=points, n_points=len(d.names), n_used=n_used,
                              rms=float(np.sqrt(np.mean(r_used ** 2))),
                              mean=float(np.mean(r_used)), max=r_max,
                              accepted=accepted, reason=reason, threshold=float(d.threshold),
                              min_points=int(d.min_points), source=d.path,
                              no_exclusion=bool(d.no_exclusion), precision=precision,
                              covariance=got["covariance"], consistency=got["consistency"],
                              working_points=got.get("working_points"), worst=got.get("worst"),
                              gate=d.gate)
    return results


def judge(accepted: bool, reason: str | None, precision: dict, worst: dict | None, gate: str,
          threshold: float) -> tuple[bool, str | None]:
    """The determinacy gate on a fit that passed the point rules: at the
    generic reach (``precision``'s at_reach, its ``reason`` popped), or with
    ``gate`` "at" at the worst working point instead."""
    from .precision import at_reason

    why = precision.pop("reason", None)
    if not accepted:
        return accepted, reason
    if gate == "at":
        if worst is not None and not worst["at_95"] <= threshold:
            return False, at_reason(worst["name"], worst["at_95"], threshold,
                                    precision["sigma"])
        return accepted, reason
    if not precision["at_reach"] <= threshold:
        return False, why
    return accepted, reason


#: SPEC point 8: a TCP is never silently 0,0,0.
NO_TCP = ("no TCP given: say where the reflector sits on the flange with --tcp X,Y,Z (mm, in "
          "flange coordinates; --tcp 0,0,0 says the points are flange positions), --tool "
          "FILE:NAME (a tool in a controller file) or --tcp solve (estimate it with the frame)")


def solve(measurement, tcp, *, threshold: float = DEFAULT_THRESHOLD,
          min_points: int = DEFAULT_MIN_POINTS, exclude: Iterable[str] = (),
          no_exclusion: bool = False, tool: str | None = None, reach: float = defaults.REACH,
          sigma_laser: float = DEFAULT_SIGMA_LASER,
          sigma_robot: float = DEFAULT_SIGMA_ROBOT, at=None, gate: str = "reach") -> Solution:
    """The method on a ``measurement.Measurement``; errors name its file.
    ``tcp`` (x, y, z) has no default: None is the error SPEC asks for."""
    if tcp is None:
        raise UcsioError(NO_TCP, file=measurement.path)
    tcp = tuple(float(v) for v in tcp)
    try:
        sol = solve_points(measurement.names, measurement.laser, measurement.robot_points(tcp),
                           measurement.weights, threshold=threshold, min_points=min_points,
                           exclude=exclude, no_exclusion=no_exclusion, lines=measurement.lines,
                           reach=reach, sigma_laser=sigma_laser, sigma_robot=sigma_robot,
                           at=at, gate=gate)
    except UcsioError as exc:
        if exc.file is None:
            raise UcsioError(exc.message, file=measurement.path) from None
        raise
    sol.tcp = tcp                 # type: ignore[assignment]
    sol.tool = tool
    sol.source = measurement.path
    return sol


# ---------------------------------------------------------------- uncertainty

GATES = ("reach", "at")


def check_gate(gate: str, at) -> None:
    """--gate reach|at; "at" needs working points."""
    if gate not in GATES:
        raise UcsioError(f"--gate {gate!r}: expected reach or at")
    if gate == "at" and at is None:
        raise UcsioError("--gate at judges the working points: give them with --at FILE")


def check_sigmas(sigma_laser: float, sigma_robot: float) -> None:
    """Noise levels are standard deviations: finite and not negative."""
    for name, v in (("--sigma-laser", sigma_laser), ("--sigma-robot", sigma_robot)):
        if not (math.isfinite(v) and v >= 0):
            raise UcsioError(f"{name} {v}: a standard deviation must be a finite number >= 0 (mm)")


def uncertainty(laser, robot_poses, tcp=(0.0, 0.0, 0.0), weights=None, n_samples: int = 10000,
                sigma_laser: float = DEFAULT_SIGMA_LASER, sigma_robot: float = DEFAULT_SIGMA_ROBOT,
                seed: int = 0, sigma_residual: float = 0.0) -> dict[str, Any]:
    """Monte Carlo uncertainty of the fitted frame.

    laser (n, 3) are the used points in the UCS, robot_poses (n, 4, 4) the
    flange poses (or (n, 3) robot points, already through the TCP). Each of
    ``n_samples`` copies adds independent Gaussian noise, per axis, of
    ``sigma_laser`` to the laser points and ``sigma_robot`` to the robot
    points, and is fitted in one batched Horn call.

    Returns ``samples``, ``std`` and ``ci95`` (keys x y z angle), and
    ``analytical_std``: the first-order propagation of the same noise through
    the least-squares fit, as a cross-check. x, y, z are the frame's origin
    in robot world (std in mm, ci95 the 2.5 and 97.5 percentiles of the
    coordinate). ``angle`` is the rotation angle (deg) between a sample and
    the nominal fit: its ``std`` is the root mean square of that angle (the
    angle is a magnitude, so it is measured from 0, the nominal), and its
    ``ci95`` is [0, 95th percentile]: the orientation lies within that angle
    of the nominal one with 95 % probability.

    ``sigma_residual``: the noise the fit's own residuals show per axis,
    √(Σ|e_i|² / (3n − 6)) (SPEC point 7). Where it exceeds the stated
    √(σ_laser² + σ_robot²), both are scaled up to it, so the numbers cannot
    look small while the residuals say otherwise; ``sigma`` and
    ``sigma_source`` ('stated' or 'residuals') say which was used.
    """
    laser = np.asarray(laser, dtype=float)
    robot_poses = np.asarray(robot_poses, dtype=float)
    if robot_poses.ndim == 3:
        robot = robot_poses[:, :3, :3] @ np.asarray(tcp, dtype=float) + robot_poses[:, :3, 3]
    else:
        robot = robot_poses
    n = len(laser)
    w = np.ones(n) if weights is None else np.asarray(weights, dtype=float)
    check_sigmas(sigma_laser, sigma_robot)
    if n_samples < 2:
        raise UcsioError("--uncertainty needs at least 2 samples")
    nominal = horn.absolute_orientation(laser, robot, w)
    stated = math.hypot(sigma_laser, sigma_robot)
    source = "stated"
    if sigma_residual > stated:
        source = "residuals"
        if stated > 0:
            f = sigma_residual / stated
            sigma_laser, sigma_robot = sigma_laser * f, sigma_robot * f
        else:
            sigma_robot = sigma_residual

    rng = np.random.default_rng(seed)
    noisy_l = laser + rng.normal(0.0, sigma_laser, size=(n_samples, n, 3))
    noisy_r = robot + rng.normal(0.0, sigma_robot, size=(n_samples, n, 3))
    fits = horn.horn_batch(noisy_l, noisy_r, np.broadcast_to(w, (n_samples, n)))
    t = fits.t
    angle = rotation_angle_deg(nominal.R[None], fits.R)

    std = {axis: float(np.std(t[:, k], ddof=1)) for k, axis in enumerate("xyz")}
    std["angle"] = float(np.sqrt(np.mean(angle ** 2)))
    lo, hi = np.percentile(t, [2.5, 97.5], axis=0)
    ci95 = {axis: [float(lo[k]), float(hi[k])] for k, axis in enumerate("xyz")}
    ci95["angle"] = [0.0, float(np.percentile(angle, 95.0))]
    return {"samples": int(n_samples), "sigma_laser": float(sigma_laser),
            "sigma_robot": float(sigma_robot), "sigma": float(math.hypot(sigma_laser, sigma_robot)),
            "sigma_source": source, "seed": int(seed),
            "degenerate_samples": int(np.count_nonzero(~fits.ok)),
            "std": std, "ci95": ci95,
            "analytical_std": analytical_std(laser, nominal, w, sigma_laser, sigma_robot)}


def analytical_std(laser, fit: horn.HornFit, weights, sigma_laser: float,
                   sigma_robot: float) -> dict[str, float]:
    """First-order covariance of (t, rotation) of the weighted least-squares
    fit. Linearising robot_i = exp([dθ]x) R l_i + t + dt about the fit gives
    the Jacobian J_i = [I3, -[R l_i]x] for (dt, dθ); each point's error is
    isotropic with variance s^2 = sigma_robot^2 + sigma_laser^2 (the laser
    noise rotated by R), so cov = s^2 H^-1 (sum w_i^2 J_i^T J_i) H^-1 with
    H = sum w_i J_i^T J_i. The angle is sqrt(trace cov_θ) in degrees."""
    from .precision import fit_covariance      # the gate's covariance, about the UCS origin

    p = np.asarray(laser, dtype=float) @ fit.R.T            # R l_i
    w = np.asarray(weights, dtype=float)
    cov = (sigma_robot ** 2 + sigma_laser ** 2) * fit_covariance(p[None], w[None])[0]
    d = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    return {"x": float(d[0]), "y": float(d[1]), "z": float(d[2]),
            "angle": float(np.degrees(np.sqrt(max(np.trace(cov[3:, 3:]), 0.0))))}


def solution_uncertainty(measurement, sol: Solution, n_samples: int,
                         sigma_laser: float = DEFAULT_SIGMA_LASER,
                         sigma_robot: float = DEFAULT_SIGMA_ROBOT, seed: int = 0) -> dict[str, Any]:
    """``uncertainty`` over the used points of a solution; stored on it.
    The noise is the larger of the stated one and the residuals' estimate."""
    used = np.array([p.used for p in sol.points])
    sol.uncertainty = uncertainty(measurement.laser[used], measurement.flange[used], sol.tcp,
                                  measurement.weights[used], n_samples, sigma_laser, sigma_robot,
                                  seed, sigma_residual=residual_sigma(sol))
    return sol.uncertainty


def residual_sigma(sol: Solution) -> float:
    """Per-axis noise the used residuals show: √(Σ|e_i|² / (3n − 6))."""
    from .precision import residual_sigma as estimate

    r = [p.residual for p in sol.points if p.used]
    return float(estimate(sum(v * v for v in r), len(r)))


# ---------------------------------------------------------------- SOLUTION.json


__all__ = ["Solution", "PointResult", "acceptance", "solve", "solve_points", "leave_one_out", "uncertainty", "check_sigmas",
           "analytical_std", "solution_uncertainty", "load_solution", "pose_from_json"]
