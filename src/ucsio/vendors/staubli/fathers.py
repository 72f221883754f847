"""check's lints of a .dtx's fathers and entries (codes: ``lints``)."""
from __future__ import annotations

from .entries import father_parent


def lint(cf, entries) -> None:
    """The codes above over a .dtx's entries (``dtx.Entry``)."""
    by_name = {e.name: e for e in entries if e.kind != "point"}
    _fathers(cf, entries, by_name)
    _indices(cf, entries)


def _father_of(e, by_name):
    """The father entry of ``e`` in the file, 'root' for world/flange, or None."""
    parent = father_parent(e, by_name)
    if parent.kind == "frame":
        return by_name.get(parent.name)
    return "root" if parent.kind in ("world", "flange") else None


def _fathers(cf, entries, by_name) -> None:
    for e in entries:
        father = _father_of(e, by_name)
        what = f"{e.kind} {e.name}"
        if e.father is None or father is None:
            said = "no father" if e.father is None else f"father {e.father[0]}[{e.father[1]}]"
            cf.lint(e.at, "father-missing", f"{what}: {said}, which this file does not hold: "
                    "its parent is not known")
            continue
        if father == "root":
            name = e.father[0]
            if (e.kind == "tool") != (name == "flange"):
                cf.lint(e.at, "father-kind", f"{what} hangs from {name}: VAL3 hangs frames "
                        "and points from world or frames, tools from the flange or tools")
            continue
        if (e.kind == "tool") != (father.kind == "tool"):
            cf.lint(e.at, "father-kind", f"{what} hangs from {father.kind} {father.name}: VAL3 "
                    "hangs frames and points from world or frames, tools from the flange or tools")
        if e.kind != "point":
            _circle(cf, e, by_name)


def _circle(cf, e, by_name) -> None:
    chain, node = [e.name], _father_of(e, by_name)
    while node is not None and node != "root":
        if node.name == e.name:
            cf.lint(e.at, "father-circle", f"{e.kind} {e.name}: its fathers go round in a "
                    f"circle ({' on '.join(chain + [e.name])}): its parent is not known")
            return
        if node.name in chain:
            return              # a circle further up: reported at its own members
        chain.append(node.name)
        node = _father_of(node, by_name)


def _indices(cf, entries) -> None:
    seen: dict[tuple[str, str, int], bool] = {}
    for e in entries:
        key = (e.kind, e.data, e.index)
        if key in seen:
            cf.lint(e.at, "entry-index", f"{e.kind} {e.data}: entry {e.index} comes twice")
        elif e.index >= max(e.size, 1):
            cf.lint(e.at, "entry-index", f"{e.kind} {e.data}: entry {e.index} is outside its "
                    f"size {e.size}")
        seen[key] = True
