"""Files ucsio recognises but does not read.

Two kinds:

- other controllers' files: Yaskawa Motoman's that ucsio does not read yet
  (the ``.CND`` condition files other than UFRAME.CND and
  TOOL.CND, and the ``SYSTEM.SYS`` of its backups, whose suffix is
  ABB's: its first line decides), Stäubli VAL3's programs and projects
  (``.pgx``/``.pjx``: ucsio reads its data files, ``.dtx``), Universal Robots' programs
  (``.urp``; its ``.installation`` is read by ucsio.vendors.ur);
- a FANUC backup's own ``.DAT`` files (``ORDERFIL.DAT``, ``UPDATES.DAT``):
  a ``.dat`` is KUKA data by its suffix only where its text or its folder
  does not say otherwise. A folder holding ``SYSFRAME.VA`` and ``.LS``
  programs is a FANUC backup; a ``.dat`` in it that does not read as KRL
  (``&ACCESS``, ``DEFDAT``) is FANUC's.

Named on its own such a file is refused with what it is (exit 2); found in
a folder or an archive it is listed as not read, as a FANUC backup's
binaries are (ucsio.parsing.backup).
"""
from __future__ import annotations

import os

from . import regex

# (what it is, whose files ucsio does not read, suffixes that say it, a
# pattern its first characters match where its suffix is another vendor's).
# A Yaskawa .CND is read by its vendor (ucsio.vendors.yaskawa) where it is a
# UFRAME.CND or TOOL.CND (//UFRAME n, //TOOL n), as are an RBCALIB.DAT
# (//RBCALIB n) and a VAR.DAT (//VAR), and refused by its first line where it
# is another condition file.
KNOWN = (
    ("a Yaskawa Motoman file", "Yaskawa", (".prm",),
     r"/SYSTEM\b|//(?!UFRAME\b|TOOL\b|RBCALIB\b|VAR\b)[A-Z]+"),
    ("a Stäubli VAL3 file", "Stäubli", (".pgx", ".pjx"), None),
    ("a Universal Robots file", "Universal Robots", (".urp",), None),
)
# what ucsio reads of a vendor's files, where it reads some: the refusal says so
READS = {"Yaskawa": "UFRAME.CND, TOOL.CND, RBCALIB.DAT, VAR.DAT and jobs (.JBI)",
         "Stäubli": "VAL3 data files (.dtx)",
         "Universal Robots": "installations (.installation)"}
_HEADS = [(what, whose, regex.lazy(pattern)) for what, whose, _s, pattern in KNOWN if pattern]
# a KUKA .dat: its header lines or its DEFDAT, before anything else
_KRL = regex.lazy(r"(?im)^[ \t]*(?:&(?:ACCESS|REL|PARAM|COMMENT)\b|(?:GLOBAL[ \t]+)?DEFDAT\b)")
FANUC_DATA = "a FANUC backup's data file (.DAT); ucsio reads its ASCII listings (.va, .ls, .dg)"


def other_vendor(name: str, head: str) -> str | None:
    """What ``name`` is, where it is another controller's file ucsio does not
    read (by its suffix, or by ``head``, its first characters); else None."""
    suffix = os.path.splitext(name)[1].lower()
    for what, whose, suffixes, _p in KNOWN:
        if suffix in suffixes:
            return f"{what} ({suffix.upper()[1:]}): {_not_read(whose)}"
    text = head.lstrip("\ufeff \t\r\n")
    for what, whose, pattern in _HEADS:
        if pattern.match(text):
            return f"{what}: {_not_read(whose)}"
    return None


def _not_read(whose: str) -> str:
    """'ucsio does not read Stäubli files yet', or, of a vendor ucsio reads
    some files of, which ones."""
    reads = READS.get(whose)
    if reads is None:
        return f"ucsio does not read {whose} files yet"
    return f"ucsio does not read this {whose} file yet (of {whose}'s files it reads {reads})"


def is_fanuc_backup(names) -> bool:
    """Whether a folder holding ``names`` is a FANUC backup: a SYSFRAME.VA
    and at least one .LS program."""
    low = [n.lower() for n in names]
    return "sysframe.va" in low and any(n.endswith(".ls") for n in low)


def fanuc_data(name: str, head: str, folder_names) -> str | None:
    """Why a ``.dat`` in a folder holding ``folder_names`` is not read: it
    is a FANUC backup's and its text is not KRL. None for any other file."""
    if not name.lower().endswith(".dat") or not is_fanuc_backup(folder_names):
        return None
    return None if _KRL.search(head) else FANUC_DATA


def beside(path: str) -> list[str]:
    """The names in ``path``'s folder (none where it cannot be listed)."""
    try:
        return os.listdir(os.path.dirname(path) or ".")
    except OSError:
        return []
