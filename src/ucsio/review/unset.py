"""Unset frames: the defaults a KUKA or FANUC controller's configuration is full of.

A real ``$config.dat`` declares 16 tools, 32 bases, 16 reference points and
a few correction frames, and most of them hold the controller's default: all
six values 0 and a blank name. Nobody taught or named them. A frame is
**unset** when all of these hold:

- it is KUKA data the configuration pre-fills: a ``BASE_DATA[n]`` or
  ``TOOL_DATA[n]`` entry, or another FRAME of the ``DEFDAT $CONFIG`` data
  list (``REF_PT[n]``, ``TOOL_CORR``, ...);
- its six values X, Y, Z, A, B, C are all exactly 0;
- it has no name: no ``BASE_NAME[n,]``/``TOOL_NAME[n,]`` entry, a blank one
  (the controller writes ``" "``), or one that only repeats the entry's own
  name (``TOOL_NAME[2,]="TOOL_DATA[2]"`` stands in a real $config.dat).

FANUC's sysframe.va is the same kind of table: ``$MNUFRAME`` and
``$MNUTOOL`` list every user and tool frame of every group, and an entry
whose six values X, Y, Z, W, P, R are all exactly 0 and that has no comment
(its own, or from frame.dg / FRAMEVAR.VA beside it) or only the comment the
controller gives a frame nobody named (``UFrame7``, ``Eoat2``) is unset too. A frame a
TP program sets is set, whatever its values: the program says so.

A vendor's package may judge its own frames (``is_set``): Yaskawa's
TOOL.CND lists all 64 tools, and one all zeros without a name is unset.

Everything else is set: a named zero base (someone chose it), the FRAMEs a
program's ``.dat`` declares (a ``NULLFRAME`` someone wrote), every ABB frame
(RAPID has no table of defaults; a declared tool0-like identity is the
user's), and a frame without a value (that is the ``no-value`` lint's case).
"""
from __future__ import annotations

from ..geometry.frames import number_values

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from typing import Any


TABLES = ("BASE_DATA", "TOOL_DATA")


def configuration(cf) -> bool:
    """Whether ``cf`` is the controller's configuration (``DEFDAT $CONFIG``)."""
    defdat = cf.extra.get("defdat") if cf is not None else None
    return isinstance(defdat, dict) and str(defdat.get("name") or "").upper() == "$CONFIG"


def is_set(frame, cf=None) -> bool:
    """False for an unset frame (module docstring); ``cf``: the file it is in."""
    if frame.pose is None:
        return True
    if frame.vendor not in ("kuka", "fanuc"):
        # a vendor that judges its own tables says so (vendors.yaskawa: TOOL.CND)
        from .. import vendors
        judge = getattr(vendors.get(frame.vendor), "is_set", None)
        return True if judge is None else judge(frame)
    if frame.vendor == "fanuc":
        if "set_from" in frame.info:        # a program's UFRAME[k]=PR[n]
            return True
    elif frame.type not in TABLES and not (frame.type == "FRAME" and configuration(cf)):
        return True
    values = number_values(frame.numbers)
    if len(values) != 6 or any(v != 0 for v in values):
        return True
    label = (frame.label or "").strip()
    return bool(label) and not _default_name(frame, label)


def _default_name(frame, label: str) -> bool:
    """Whether ``label`` is a name the controller gave, not a person: the
    frame's own name (TOOL_NAME[2,]="TOOL_DATA[2]"), or FANUC's default
    comment (UFrame7, Eoat2: parsing.fanuc.default_comment)."""
    if label.casefold() == frame.name.casefold():
        return True
    if frame.vendor == "fanuc":
        from ..vendors.fanuc.base import default_comment
        return default_comment(frame.type, frame.name, label)
    return False


def as_dict(frame, cf=None) -> dict[str, Any]:
    """``frame.as_dict()`` with ``set`` (``frames --json``)."""
    d = frame.as_dict()
    d["set"] = is_set(frame, cf)
    return d


def tool_warning(frame, what: str = "--tool", zero: str = "--tcp 0,0,0") -> str:
    """What solve and batch say about a TCP taken from an unset tool
    (``zero``: how the user says the points are flange positions)."""
    return (f"{what}: {frame.name} is unset (all six values 0 and no name: the controller's "
            "default, not a tool anyone taught): its TCP 0,0,0 takes the points as flange "
            f"positions; name the reflector's tool, or say so with {zero}")


def warning(frame) -> str:
    """What diff, batch and the report say about an unset simulated frame."""
    return (f"{frame.name} is unset (all six values 0 and no name: the controller's default, "
            "not a frame anyone taught): the difference is the whole measured pose, not a "
            "correction")
