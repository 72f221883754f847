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


VENDOR = Kuka()
