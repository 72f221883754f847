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


VENDOR = Abb()
