"""The frame a user names on the command line or in a manifest.

``find_frame(cf, name)`` is ``ControllerFile.frame`` with one better
message: an array element outside its array (``TOOL_DATA[17]`` where the file
declares ``TOOL_DATA[16]``, ``tools{5}`` of a ``tools{2}``) is said to be
outside 1…n, where the nearest-name hint would have offered an unrelated
entry (``TOOL_DATA[7]``).
"""
from __future__ import annotations

from ..errors import UcsioError
from ..parsing import regex

TYPE_CHECKING = False      # typing costs a cold start; annotations are strings
if TYPE_CHECKING:
    from ..geometry.frames import Frame
    from ..parsing.model import ControllerFile

_ELEMENT = regex.lazy(r"\s*([A-Za-z_$][\w$]*)\s*(?:\[\s*([+-]?\d+)\s*\]|\{\s*([+-]?\d+)\s*\})\s*\Z")


def find_frame(cf: ControllerFile, name: str) -> Frame:
    """The frame called ``name`` in ``cf`` (UcsioError naming the file when
    there is none, or more than one)."""
    try:
        return cf.frame(name)
    except UcsioError as exc:
        # something of that name the reader knows and does not read (a UR line feature)
        unread = (cf.extra.get("unread") or {}).get(name.strip().casefold())
        if unread is not None:
            raise UcsioError(f"no frame named {name.strip()[:40]!r}: {unread}",
                             file=exc.file) from None
        why = outside(cf, name)
        if why is None:
            raise
        raise UcsioError(why, file=exc.file) from None


def outside(cf, name: str) -> str | None:
    """Why ``name`` names no frame, where it is an element index outside its
    array: the array's declared size (KUKA ``DECL FRAME TOOL_DATA[16]``), or
    else the elements the file gives (ABB ``tools{1}`` … ``tools{n}``)."""
    m = _ELEMENT.match(name)
    if m is None:
        return None
    from ..parsing.document import small_int
    base, index = m.group(1), small_int(m.group(2) or m.group(3))
    if index is None:
        return f"no frame named {name.strip()[:40]!r}: its index is beyond 32 bits"
    kuka = m.group(2) is not None
    key = base.casefold()
    size, spelling = None, base
    for sp, dims in (cf.extra.get("arrays") or {}).items():    # KUKA: FRAME arrays declared
        if sp.casefold() == key and dims and len(dims) == 1 and isinstance(dims[0], int):
            size, spelling = dims[0], sp
    if size is None:
        present = []
        for f in cf.frames:
            e = _ELEMENT.match(f.name)
            if e and e.group(1).casefold() == key and (e.group(2) is not None) == kuka:
                present.append(small_int(e.group(2) or e.group(3)) or 0)
                spelling = e.group(1)
        if not present:
            return None
        size = max(present)
    if 1 <= index <= size:
        return None
    return (f"no frame named {name.strip()!r}: index {index} is outside 1…{size} "
            f"({spelling} has {size} entr{'y' if size == 1 else 'ies'} in this file; "
            "ucsio frames lists them)")
