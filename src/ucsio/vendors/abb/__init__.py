"""ABB RAPID: modules (.mod, .modx), system modules (.sys, .sysx), programs (.prg).

``VENDOR`` is what the registry (``ucsio.vendors``) hands generic code; its
methods import the parser and the rest only when called.
"""
from __future__ import annotations


class Abb:
    name = "abb"
    title = "ABB"

    # -- reading --------------------------------------------------------------------
    def sniff(self, doc) -> bool:
        head = doc.text[:4096].lstrip("\ufeff \t\r\n").upper()
        return head.startswith(("%%%", "MODULE", "!"))

    def parse(self, doc, full: bool = False, beside: bool = True):
        from .rapid import parse
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
        from .taught import chain
        return chain(cf, frame, measured)

    def taught_in_frame(self, cf, frame, found):
        from .taught import in_frame
        return in_frame(cf, frame, found)

    def prefilled(self, frame, cf) -> bool:
        return False        # RAPID has no table of defaults: every declared frame is the user's

    def default_label(self, frame, label: str) -> bool:
        return False

    native_deltas = ()
    frames_set_by_program = False


VENDOR = Abb()
