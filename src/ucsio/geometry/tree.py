"""A controller's frame tree: world at the top, the robots (one per motion
group), their flanges, the units that move frames, and every frame under
the node its Parent names (``frames --tree``).

Vendor-free: a frame's parser says what the frame is relative to
(``Frame.parent``); this module only hangs each frame where its parent is.
A frame whose parent frame is not in its file, or whose parents go round in
a circle, hangs under ``unknown``, a second root beside world.
"""
from __future__ import annotations

from .frames import UNKNOWN, WORLD, Parent

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from typing import Any, Callable, Iterable

    from .frames import Frame


class Node:
    """A node of the tree: a Parent (world, a robot, a flange, a unit,
    unknown) or a frame (``frame`` set, ``parent`` its Parent of kind 'frame'
    as its children name it)."""
    __slots__ = ("parent", "frame", "children", "shown")

    def __init__(self, parent: Parent, frame: Frame | None = None):
        self.parent = parent
        self.frame = frame
        self.children: list[Node] = []
        self.shown = False

    @property
    def name(self) -> str:
        return self.frame.name if self.frame is not None else self.parent.name

    @property
    def kind(self) -> str:
        return "frame" if self.frame is not None else self.parent.kind


def _group_suffix(name: str) -> str:
    """'flange@2' -> '@2'; 'flange' -> ''."""
    at = name.find("@")
    return name[at:] if at >= 0 else ""


class _Builder:
    def __init__(self) -> None:
        self.world = Node(WORLD)
        self.unknown = Node(UNKNOWN)
        self.places: dict[tuple[str, str], Node] = {}   # (kind, name) -> robot, flange, unit

    def place(self, parent: Parent) -> Node:
        """The node a Parent that is not a frame stands for, made on first use:
        a robot and a unit under world, a flange under its group's robot."""
        if parent.kind == "world":
            return self.world
        if parent.kind not in ("robot", "flange", "unit"):
            return self.unknown
        key = (parent.kind, parent.name)
        node = self.places.get(key)
        if node is None:
            node = self.places[key] = Node(parent)
            if parent.kind == "flange":
                above = self.place(Parent("robot", "robot" + _group_suffix(parent.name)))
            else:
                above = self.world
            above.children.append(node)
        return node


def build(frames: Iterable[Frame], shown: Callable[[Frame], bool]) -> list[Node]:
    """The roots (world, then unknown when anything hangs there) of the tree
    of ``frames`` (one file or one backup). A node is ``shown`` when
    ``shown(frame)`` or anything below it is; world always is."""
    b = _Builder()
    frames = list(frames)
    by_name: dict[tuple[str, str], Node] = {}
    for f in frames:
        by_name.setdefault((f.file, f.name), Node(f.parent, f))
    for f in frames:
        node = by_name[(f.file, f.name)]
        if node.frame is not f:                 # a name given twice: the first is its node
            node = Node(f.parent, f)
        _above(f, by_name, b).children.append(node)
    for root in (b.world, b.unknown):
        _mark_shown(root, shown)
    b.world.shown = True
    _robots_first(b.world)
    return [r for r in (b.world, b.unknown) if r.shown]


def _above(f: Frame, by_name: dict, b: _Builder) -> Node:
    """The node ``f`` hangs under: its parent frame in its file (unless that
    chain goes round in a circle), else the place its Parent names."""
    parent = f.parent
    if parent.kind != "frame":
        return b.place(parent)
    seen = {f.name}
    up = by_name.get((f.file, parent.name))
    step = up
    while step is not None and step.parent.kind == "frame":
        if step.frame.name in seen:
            return b.unknown                     # frames defined on each other
        seen.add(step.frame.name)
        step = by_name.get((f.file, step.parent.name))
    return up if up is not None else b.unknown


def _mark_shown(node: Node, shown: Callable[[Frame], bool]) -> bool:
    below = False
    for child in node.children:
        below = _mark_shown(child, shown) or below
    node.shown = below or (node.frame is not None and shown(node.frame))
    return node.shown


def _robots_first(world: Node) -> None:
    """The robots first, in group order, each with its flange (and the tools
    on it) first; then the rest in the files' order."""
    robots = sorted((n for n in world.children if n.kind == "robot"),
                    key=lambda n: (len(n.name), n.name))
    world.children = robots + [n for n in world.children if n.kind != "robot"]
    for r in robots:
        r.children.sort(key=lambda n: n.kind != "flange")      # stable: the rest keep order


def as_dict(node: Node, frame_dict: Callable[[Frame], dict[str, Any]]) -> dict[str, Any]:
    """The nested JSON of a shown node: ``name``, ``kind``, ``children``; a
    frame's node also holds the keys of ``frame_dict(frame)``."""
    d: dict[str, Any] = {"name": node.name, "kind": node.kind}
    if node.frame is not None:
        d.update(frame_dict(node.frame))
    d["children"] = [as_dict(c, frame_dict) for c in node.children if c.shown]
    return d


def lines(node: Node, label: Callable[[Node], str], prefix: str = "",
          last: bool = True, top: bool = True) -> Iterable[str]:
    """The text of a shown node and what is below it, drawn with tree
    characters: each line ``label(node)``."""
    if top:
        yield label(node)
        inner = ""
    else:
        yield prefix + ("└── " if last else "├── ") + label(node)
        inner = prefix + ("    " if last else "│   ")
    kids = [c for c in node.children if c.shown]
    for i, child in enumerate(kids):
        yield from lines(child, label, inner, i == len(kids) - 1, False)
