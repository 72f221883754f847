"""Yaskawa Motoman: user frames (UFRAME.CND) and tools (TOOL.CND).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the reader (``cnd``) only when called. Jobs (.JBI),
RBCALIB.DAT, VAR.DAT and SYSTEM.SYS are not read yet: parsing.foreign
refuses them with what ucsio reads of Yaskawa's files.
"""
from __future__ import annotations


class Yaskawa:
    name = "yaskawa"
    title = "Yaskawa"

    # -- reading --------------------------------------------------------------------
    def sniff(self, doc) -> bool:
        from .cnd import sniff
        return sniff(doc)

    def parse(self, doc, full: bool = False, beside: bool = True):
        from .cnd import parse
        return parse(doc, full=full)

    def binary_refusal(self, path: str) -> str | None:
        return None

    # -- orientation and numbers ------------------------------------------------------

    # -- robot positions (solve --robot) ------------------------------------------------

    # -- writing frames and programs (patch, program) -----------------------------------
    program_writer = None
    frame_writer = None     # patch: not yet (a TOOL.CND's ///CRC cannot be recomputed)

    # -- taught points, unset frames, comparing frames (diff) ---------------------------
    def is_set(self, frame) -> bool:
        """TOOL.CND lists all 64 tools: one all zeros without a name is the
        controller's default, nobody's tool. Every user frame is set (the
        file lists only defined ones)."""
        if frame.type != "TOOL":
            return True
        return bool((frame.label or "").strip()) or \
            any(n.value != 0 for n in frame.numbers.values())


VENDOR = Yaskawa()
