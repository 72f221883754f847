"""KUKA's robot positions for ``solve --robot``: a program ``.dat`` (the
measurement program's data list).

Each E6POS/POS/FRAME is the pose of ``$TOOL`` in ``$BASE``, named by its
FDAT's TOOL_NO and BASE_NO; the flange in world is base * position *
tool^-1, with TOOL_DATA[n] and BASE_DATA[n] read from ``--config
$config.dat`` (needed where either number is not 0; 0 is the flange, and
the world). The positions go through ``krl.positions``: the same grammar as
``frames``. A position that cannot be resolved (its tool or base unknown or
not a plain one, a value that is not literal) carries its problem, raised
only if the point is paired: a program's other data do not stop a measurement.
"""
from __future__ import annotations

import numpy as np

from ...errors import UcsioError
from ...geometry.arrays import flange_matrices
from ...geometry.frames import Pose
from ...parsing.document import Document
from ..common.robot import RobotPose, RobotPoses, matrix
from .krl import positions


def read(vendor, path: str, config: str | None, tool: str, wobj: str, load) -> RobotPoses:
    """A program .dat's positions as flange poses in world, in ``vendor``'s
    convention (the package's VENDOR, handed in: this module does not import
    its package back). ``tool`` and ``wobj`` are not asked: each position
    names its own (its FDAT); ``load`` reads ``--config``, a file of any vendor."""
    doc = Document.read(path)
    cfg = None
    poses = []
    warnings: list[str] = []
    for p in positions(doc):
        rp = RobotPose(p.name, p.point, p.line, p.col, None)
        poses.append(rp)
        if p.pose is None:
            rp.problem = p.problem
            continue
        if p.fdat is None:
            rp.note = "no FDAT: taken as the flange in world (TOOL_NO 0, BASE_NO 0)"
        where = {"file": path, "line": p.line, "col": p.col}
        if p.ipo_frame == "#TCP":
            rp.problem = UcsioError(f"{p.name}: IPO_FRAME #TCP in {p.fdat}: taught with an "
                                    "external (fixed) TCP, not a flange pose", **where)
            continue
        tool_no, base_no = p.tool_no or 0, p.base_no or 0
        if not tool_no and not base_no:
            x, y, z = p.pose.t
            # the numbers as written, through the same conversion as the CSV
            rp.flange = flange_matrices(vendor.angles, np.array([p.pose.abc]),
                                        np.array([[x, y, z]]))[0]
            continue
        if config is None:
            rp.problem = UcsioError(f"{p.name}: TOOL_NO {tool_no}, BASE_NO {base_no} in "
                                    f"{p.fdat}: give --config $config.dat, the controller's "
                                    "TOOL_DATA and BASE_DATA", **where)
            continue
        if cfg is None:
            cfg = load(config)
        try:
            flange = p.pose
            if base_no:
                flange = _kuka_entry(cfg, "BASE", base_no, p.name).compose(flange)
            if tool_no:
                flange = flange.compose(_kuka_entry(cfg, "TOOL", tool_no, p.name).inverse())
        except UcsioError as exc:
            rp.problem = UcsioError(exc.message, **where)
            continue
        rp.flange = matrix(flange)
    return RobotPoses(path, vendor.name, poses, vendor.name, warnings)


def _kuka_entry(cfg, kind: str, n: int, who: str) -> Pose:
    """TOOL_DATA[n] (in the flange) or BASE_DATA[n] (in world) of $config.dat,
    refused where it is not that: an external TCP, a base on an external
    kinematic, an entry without a value."""
    name = f"{kind}_DATA[{n}]"
    found = [f for f in cfg.frames if f.name.upper() == name]
    if not found:
        raise UcsioError(f"{who}: {kind}_NO {n}, but {cfg.path} has no {name}")
    f = found[0]
    want = "flange" if kind == "TOOL" else "world"
    if f.reference != want or f.info.get("role") not in ("tool", "base"):
        raise UcsioError(f"{who}: {kind}_NO {n}: {name} ({cfg.path}:{f.line}) is "
                         f"{f.info.get('role') or f.reference} relative to {f.reference}, not a "
                         f"plain {'robot-held tool' if kind == 'TOOL' else 'base in world'}")
    if f.pose is None:
        raise UcsioError(f"{who}: {kind}_NO {n}: {name} ({cfg.path}:{f.line}) has no complete "
                         "value")
    return f.pose
