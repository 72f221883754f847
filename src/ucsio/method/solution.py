"""SOLUTION.json: the file ``ucsio solve -o`` writes and ``diff``/``patch`` read.

Kept apart from the solver so that reading a solution imports no numpy:
``diff`` and ``patch`` start in a blink.
"""
from __future__ import annotations

import math
import os

from ..errors import RejectedDataset, UcsioError
from ..files import read_bytes
from ..geometry import rotations as rot
from ..geometry.frames import Pose

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from typing import Any


def solution_text(doc: dict[str, Any]) -> str:
    """What ``solve -o`` (and ``demo --out``) writes: ``solve --json``'s
    document with ``schema_version``, indented, NaN and inf as null."""
    from ..output import _clean, versioned
    import json
    return json.dumps(_clean(versioned(doc)), indent=2, ensure_ascii=False) + "\n"


def check_schema_version(data: Any, path: str | None = None) -> None:
    """A SOLUTION.json without ``schema_version`` (older ucsio) is read as it
    is; one from a newer schema is refused: its keys may mean something this
    ucsio does not know."""
    from ..output import SCHEMA_VERSION
    if not isinstance(data, dict) or "schema_version" not in data:
        return
    v = data["schema_version"]
    if isinstance(v, bool) or not isinstance(v, int) or v < 1:
        raise UcsioError(f"schema_version {v!r}: expected a whole number from 1", file=path)
    if v > SCHEMA_VERSION:
        raise UcsioError(f"written with schema_version {v} by a newer ucsio; this one reads up "
                         f"to {SCHEMA_VERSION}: upgrade ucsio (pip install -U ucsio) or solve "
                         "again with this one", file=path)


def load_solution(path: str | os.PathLike, allow_rejected: bool = False) -> Pose:
    """The frame of a SOLUTION.json written by ``ucsio solve -o``, or of a
    plain JSON object with x, y, z and either a, b, c (KUKA) or q (ABB order).
    A solution whose dataset was rejected is refused unless
    ``allow_rejected``; q and a, b, c given together must agree. A file that
    is not UTF-8 (a BOM is allowed) is a UcsioError, like bad JSON."""
    path = os.fspath(path)
    return pose_from_json(read_json(path), path, allow_rejected)


def solved_tcp(data: Any, path: str | None = None,
               allow_rejected: bool = False) -> tuple[float, float, float] | None:
    """The TCP a ``solve --tcp solve`` found (``"tcp": {x, y, z, "solved":
    true}``), or None where the solution gives the TCP it was handed. A
    rejected dataset's TCP is refused unless ``allow_rejected``."""
    tcp = data.get("tcp") if isinstance(data, dict) else None
    if not isinstance(tcp, dict) or tcp.get("solved") is not True:
        return None
    pose_from_json(data, path, allow_rejected)          # the same refusals as the frame's
    vals = []
    for k in "xyz":
        v = tcp.get(k)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise UcsioError(f"tcp key {k!r} missing or not a finite number", file=path)
        vals.append(float(v))
    return tuple(vals)  # type: ignore[return-value]


def read_json(path: str) -> Any:
    """A SOLUTION.json's data; not UTF-8 or not JSON is a UcsioError."""
    raw = read_bytes(path, "solution file")
    bom = 3 if raw.startswith(b"\xef\xbb\xbf") else 0
    try:
        text = raw[bom:].decode("utf-8")
    except UnicodeDecodeError as exc:
        at = bom + exc.start
        raise UcsioError(f"not UTF-8 text: byte 0x{raw[at]:02x} at offset {at} cannot be decoded "
                         "(a SOLUTION.json is UTF-8)", file=path,
                         line=raw[:at].count(b"\n") + 1) from None
    import json
    try:
        data = json.loads(text)
    except ValueError as exc:           # json.JSONDecodeError
        raise UcsioError(f"not valid JSON: {getattr(exc, 'msg', exc)}", file=path,
                         line=getattr(exc, "lineno", None), col=getattr(exc, "colno", None)) \
            from None
    return data


def pose_from_json(data: Any, path: str | None = None, allow_rejected: bool = False) -> Pose:
    """The Pose of a solution object (``{"frame": {...}}``) or of a bare
    ``{x, y, z, a, b, c | q}`` object; errors name ``path``."""
    if not isinstance(data, dict):
        raise UcsioError("expected a JSON object with a 'frame' or x, y, z ...", file=path)
    check_schema_version(data, path)
    if data.get("accepted") is False and not allow_rejected:
        # the solver's own reason (SOLUTION.json "reason"); an older or
        # hand-made file without one gets the generic wording
        reason = data.get("reason")
        why = (f"the dataset was rejected: {reason.strip()}"
               if isinstance(reason, str) and reason.strip() else "the dataset was rejected")
        if not data.get("diagnosis"):   # a wrong TCP: the reason says what to check instead
            why += "; measure again"
        raise RejectedDataset(why, file=path)
    frame = data.get("frame", data)
    if not isinstance(frame, dict):
        raise UcsioError("'frame' is not a JSON object", file=path)

    def num(key):
        v = frame.get(key)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise UcsioError(f"frame key {key!r} missing or not a finite number", file=path)
        return float(v)

    x, y, z = num("x"), num("y"), num("z")
    has_q = frame.get("q") is not None
    has_abc = all(frame.get(k) is not None for k in "abc")
    if not has_q and not has_abc:
        raise UcsioError("frame needs either q [q1, q2, q3, q4] or a, b, c", file=path)
    pose_q = None
    if has_q:
        q = frame["q"]
        if (not isinstance(q, list) or len(q) != 4
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                           and math.isfinite(v) for v in q)):
            raise UcsioError("frame key 'q' must be a list of 4 numbers", file=path)
        if abs(math.sqrt(sum(v * v for v in q)) - 1.0) > 1e-3:
            raise UcsioError("frame key 'q' is not a unit quaternion", file=path)
        pose_q = Pose.from_quat(x, y, z, q)
    if has_abc:
        pose_abc = Pose.from_abc(x, y, z, num("a"), num("b"), num("c"))
        if pose_q is not None and rot.quat_angle(pose_q.q, pose_abc.q) > 1e-4:
            raise UcsioError("frame's q and a, b, c disagree "
                             f"({rot.quat_angle(pose_q.q, pose_abc.q):.4f} deg apart)", file=path)
        if pose_q is not None:
            # Both agree: keep the full-precision quaternion with a, b, c as written.
            return Pose(x, y, z, pose_q.q, pose_abc.abc)
        return pose_abc
    return pose_q  # type: ignore[return-value]
