"""Loading the Lark grammars that ship with ucsio.

The grammars are data (grammars/*.lark at the top of the repository, copied
into the wheel as ucsio/grammars). Lark's analysis is cached on disk
(``cache=True``) so a command pays it once per machine, not once per run.
"""
from __future__ import annotations

import functools
from pathlib import Path


def grammar_dir() -> Path:
    here = Path(__file__).resolve().parent
    inside = here / "grammars"          # installed wheel
    if inside.is_dir():
        return inside
    return here.parent.parent / "grammars"  # source checkout / editable install


@functools.lru_cache(maxsize=None)
def parser(name: str, start: tuple[str, ...], positions: bool = True):
    """A cached LALR parser. ``positions=False`` skips Lark's position
    propagation to rule nodes (a third of the parse time); tokens always keep
    theirs, which is all a grammar that keeps its sign tokens needs."""
    from lark import Lark  # lazy: only commands that parse pay for it

    path = grammar_dir() / f"{name}.lark"
    return Lark(path.read_text(encoding="utf-8"), parser="lalr", lexer="contextual",
                start=list(start), propagate_positions=positions, maybe_placeholders=False,
                cache=True)
