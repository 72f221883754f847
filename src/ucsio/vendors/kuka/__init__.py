"""KUKA KRL: data lists ($config.dat and a program's .dat), programs (.src, .sub).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the parser and the rest only when called.
"""
from __future__ import annotations


class Kuka:
    name = "kuka"
    title = "KUKA"

    # -- reading --------------------------------------------------------------------
    def sniff(self, doc) -> bool:
        return True         # the registry's fallback: a data list has no first word of its own

    def parse(self, doc, full: bool = False, beside: bool = True):
        from .krl import parse
        return parse(doc, full=full)

    def binary_refusal(self, path: str) -> str | None:
        return None

    # -- orientation and numbers ------------------------------------------------------

    # -- robot positions (solve --robot) ------------------------------------------------

    # -- writing frames and programs (patch, program) -----------------------------------
    program_writer = None

    # -- taught points, unset frames, comparing frames (diff) ---------------------------
    def taught_points(self, cf, frame, cache=None):
        from .taught import find
        return find(cf, frame, cache)

    def taught_chain(self, cf, frame, measured):
        from ..common.taught import alone
        return alone(frame, measured)

    def taught_in_frame(self, cf, frame, found):
        from ..common.taught import as_written
        return as_written(found)

    def prefilled(self, frame, cf) -> bool:
        """A BASE_DATA[n] or TOOL_DATA[n] entry, or another FRAME of the
        controller's configuration (REF_PT[n], TOOL_CORR, ...); not the
        FRAMEs a program's .dat declares."""
        return frame.type in ("BASE_DATA", "TOOL_DATA") or (
            frame.type == "FRAME" and _configuration(cf))

    def default_label(self, frame, label: str) -> bool:
        return False        # only the entry's own name, which every vendor's check sees

    native_deltas = ()
    frames_set_by_program = False


def _configuration(cf) -> bool:
    """Whether ``cf`` is the controller's configuration (``DEFDAT $CONFIG``)."""
    defdat = cf.extra.get("defdat") if cf is not None else None
    return isinstance(defdat, dict) and str(defdat.get("name") or "").upper() == "$CONFIG"


VENDOR = Kuka()
