"""Malformed numbers in a syntax error, for the vendors' listings.

Where a grammar rejects a file at a word such as '1.2.3', '1e' or '12ab',
the message says "malformed number" rather than what the grammar expected
after the part it took: the words are the same in KRL and in FANUC's
listings.
"""
from __future__ import annotations

import re

# a complete decimal number, as every grammar here writes one
NUMBER = r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?\Z"


def bad_number(text: str, pos: int) -> tuple[int, int] | None:
    """(start, end) of a malformed number around ``pos`` ('1.2.3', '1e', '12ab')."""
    n = len(text)
    s = pos
    while s > 0 and (text[s - 1].isalnum() or text[s - 1] in "._+-$"):
        s -= 1
    e = pos
    while e < n and (text[e].isalnum() or text[e] in "._+-$"):
        e += 1
    word = text[s:e]
    if not word or not (word[0].isdigit() or word[0] in ".+-"):
        return None
    if not any(c.isdigit() for c in word) or re.match(NUMBER, word):
        return None
    return s, e
