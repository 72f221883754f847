"""Frames: what ucsio reads from, compares and writes into controller files.

A Frame is a pose (translation in mm, rotation) with a name, the file and line
it came from, what it is relative to, and the spans of the text that hold its
numbers, so the patcher can replace exactly those and nothing else.
"""
from __future__ import annotations

import math

from . import rotations as rot
from ..parsing.document import Document, Span
from ..values import Value

TYPE_CHECKING = False      # typing costs a cold start 5-14 ms; annotations are strings
if TYPE_CHECKING:
    from typing import Any


class Pose(Value):
    """p_parent = R p_frame + t. ``q`` is canonical (w >= 0); ``abc`` is
    KUKA's A, B, C as written where the source gave them, else derived."""

    __slots__ = ("x", "y", "z", "q", "abc")

    def __init__(self, x: float, y: float, z: float, q: rot.Quat, abc: tuple[float, float, float]):
        self.x, self.y, self.z, self.q, self.abc = x, y, z, tuple(q), tuple(abc)

    @classmethod
    def from_quat(cls, x, y, z, q) -> "Pose":
        qc = rot.quat_canonical(tuple(float(v) for v in q))
        return cls(float(x) + 0.0, float(y) + 0.0, float(z) + 0.0, qc, rot.quat_to_abc(qc))

    @classmethod
    def from_abc(cls, x, y, z, a, b, c) -> "Pose":
        abc = (float(a) + 0.0, float(b) + 0.0, float(c) + 0.0)  # + 0.0: no "-0"
        return cls(float(x) + 0.0, float(y) + 0.0, float(z) + 0.0, rot.abc_to_quat(*abc), abc)

    @classmethod
    def from_wpr(cls, x, y, z, w, p, r) -> "Pose":
        """FANUC W, P, R: R = Rz(R) Ry(P) Rx(W), the KUKA matrix with A=R,
        B=P, C=W (so ``abc`` is (R, P, W) as written)."""
        return cls.from_abc(x, y, z, r, p, w)

    @classmethod
    def from_three_points(cls, org, xx, xy) -> "Pose | None":
        """A pendant's 3-point construction (origin ORG, a point XX on +X, a
        point XY in the XY plane on the +Y side): x along ORG->XX, z = x ×
        (XY - ORG), y = z × x, the origin at ORG; None where the points are
        (nearly) collinear. (``method.three_points.construct`` is the same in
        numpy, for ``solve``; readers and writers take this one, light.)"""
        x = [b - a for a, b in zip(org, xx)]
        to_xy = [b - a for a, b in zip(org, xy)]
        z = _cross(x, to_xy)
        nx, nz = _norm(x), _norm(z)
        if nx == 0.0 or nz <= 1e-9 * nx * max(_norm(to_xy), 1e-300):
            return None
        x = [c / nx for c in x]
        z = [c / nz for c in z]
        y = _cross(z, x)
        return cls.from_matrix(((x[0], y[0], z[0]), (x[1], y[1], z[1]), (x[2], y[2], z[2])),
                               tuple(org))

    @classmethod
    def from_matrix(cls, m, t) -> "Pose":
        q = rot.matrix_to_quat(m)
        return cls(float(t[0]), float(t[1]), float(t[2]), q, rot.quat_to_abc(q))

    @property
    def t(self) -> tuple[float, float, float]:
        return (self.x, self.y, self.z)

    @property
    def matrix(self) -> rot.Matrix:
        return rot.quat_to_matrix(self.q)

    @property
    def wpr(self) -> tuple[float, float, float]:
        a, b, c = self.abc
        return (c, b, a)

    def compose(self, other: "Pose") -> "Pose":
        """self * other: other expressed in self's parent."""
        m = self.matrix
        t = rot.matvec(m, other.t)
        q = rot.quat_multiply(self.q, other.q)
        qc = rot.quat_canonical(q)
        return Pose(self.x + t[0], self.y + t[1], self.z + t[2], qc, rot.quat_to_abc(qc))

    def inverse(self) -> "Pose":
        """The parent expressed in this frame: p_frame = R^T (p_parent - t)."""
        mt = rot.transpose(self.matrix)
        t = rot.matvec(mt, (-self.x, -self.y, -self.z))
        return Pose.from_matrix(mt, t)

    def apply(self, p) -> tuple[float, float, float]:
        v = rot.matvec(self.matrix, p)
        return (v[0] + self.x, v[1] + self.y, v[2] + self.z)

    def as_dict(self) -> dict[str, Any]:
        a, b, c = self.abc
        return {"x": self.x, "y": self.y, "z": self.z, "a": a, "b": b, "c": c,
                "q": list(self.q)}


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _norm(v) -> float:
    return math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])


class Number(Value):
    """One numeric component as written: its span and text, the sign included
    where only blanks part it from the digits ("-0.5", "- 0.5"). A sign that a
    comment or a line break parts from the digits (RAPID "- ! note\n670") is
    not in the span, so a patch never replaces what stands between them:
    ``signs`` holds such detached signs, outermost first, and ``value``
    counts them; ``lead`` is their characters ("-")."""

    __slots__ = ("span", "text", "value", "signs", "lead")

    def __init__(self, span: Span, text: str, value: float, signs: tuple[Span, ...] = (),
                 lead: str = ""):
        self.span, self.text, self.value = span, text, value
        self.signs, self.lead = signs, lead

    @property
    def written(self) -> str:
        """The number as a person reads it: detached signs, then the span's
        text without blanks ("-670" for "- ! note\n670")."""
        return self.lead + "".join(self.text.split())


class _NumbersMadeLater:
    """A frame's numbers (component -> Number) made only when asked for;
    reads as the dict it stands for (equal to it, same keys and values).
    Listing a file never asks: its frames' poses are read without a Number
    for each; a patch, a diff or ``check`` does. ``_numbers`` makes them."""

    __slots__ = ("_made",)

    def _numbers(self) -> dict[str, Number]:
        raise NotImplementedError

    def __getitem__(self, key: str) -> Number:
        return self._numbers()[key]

    def __iter__(self):
        return iter(self._numbers())

    def __len__(self) -> int:
        return len(self._numbers())

    def __contains__(self, key) -> bool:
        return key in self._numbers()

    def __bool__(self) -> bool:
        return bool(self._numbers())

    def keys(self):
        return self._numbers().keys()

    def values(self):
        return self._numbers().values()

    def items(self):
        return self._numbers().items()

    def get(self, key, default=None):
        return self._numbers().get(key, default)

    def __eq__(self, other) -> bool:
        if isinstance(other, _NumbersMadeLater):
            other = other._numbers()
        return self._numbers() == other

    __hash__ = None         # type: ignore[assignment]  - a mapping, as the dict it stands for

    def __repr__(self) -> str:
        return repr(self._numbers())


class ShiftedNumbers(_NumbersMadeLater):
    """A frame's numbers where its text repeats another element's (a
    sysframe.va lists hundreds of identical default entries): the other's
    Numbers moved ``delta`` characters on. ``base`` holds the values, which
    do not move, and the keys."""

    __slots__ = ("base", "delta")

    def __init__(self, base: dict[str, Number], delta: int):
        self.base, self.delta, self._made = base, delta, None

    def _numbers(self) -> dict[str, Number]:
        if self._made is None:
            d = self.delta
            self._made = {k: Number(Span(n.span.start + d, n.span.end + d), n.text, n.value)
                          for k, n in self.base.items()}
        return self._made

    def __iter__(self):
        return iter(self.base)

    def __len__(self) -> int:
        return len(self.base)

    def __contains__(self, key) -> bool:
        return key in self.base

    def __bool__(self) -> bool:
        return bool(self.base)

    def keys(self):
        return self.base.keys()


class NumbersOnDemand(_NumbersMadeLater):
    """A frame's numbers read from its text by ``read`` when first asked
    for: a reader that took the pose from the same text (a Universal
    Robots point feature) makes no Number for a listing."""

    __slots__ = ("_read",)

    def __init__(self, read):
        self._read, self._made = read, None

    def _numbers(self) -> dict[str, Number]:
        if self._made is None:
            self._made, self._read = self._read(), None
        return self._made


def number_values(numbers) -> list[float]:
    """The values of a frame's numbers, without making moved spans."""
    base = numbers.base if isinstance(numbers, ShiftedNumbers) else numbers
    return [n.value for n in base.values()]


def number_texts(numbers, memo: dict | None = None) -> dict[str, str]:
    """How a frame's numbers are written, by component, without making
    moved spans. ``memo`` (id of the numbers read -> texts) reads each of a
    listing's shared sets of numbers once, however many frames repeat it."""
    base = numbers.base if isinstance(numbers, ShiftedNumbers) else numbers
    if memo is None:
        return {k: n.text for k, n in base.items()}
    got = memo.get(id(base))
    if got is None:
        got = memo[id(base)] = {k: n.text for k, n in base.items()}
    return got


class Parent(Value):
    """What a frame's pose is relative to (p_parent = R·p_frame + t): a node
    of a controller's frame tree, vendor-free. ``kind``:

    - ``world``: the cell's world (``name`` 'world');
    - ``robot``: a robot's base, or the world a robot keeps fixed to its base
      (``name`` 'robot', 'robot@2' for a controller's motion group 2);
    - ``flange``: a robot's flange, where its tools hang ('flange', 'flange@2');
    - ``frame``: another frame of the same file, by its ``name`` (an ABB
      object frame in its work object's user frame);
    - ``unit``: a mechanical unit or external kinematic that moves the frame,
      by its ``name`` ('STN1', 'MACHINE_DEF[2]');
    - ``unknown``: the file does not say ('unknown').

    Frames defined on other frames (Yaskawa's user frame k, Stäubli's
    fFather) are ``frame`` parents; a robot's nodes carry its group."""
    __slots__ = ("kind", "name")

    def __init__(self, kind: str, name: str):
        self.kind = kind
        self.name = name

    def __str__(self) -> str:
        return self.name


WORLD = Parent("world", "world")
UNKNOWN = Parent("unknown", "unknown")
# what a frame whose parser names no Parent is relative to, by its reference
_PARENT_OF_REFERENCE = {"world": WORLD, "flange": Parent("flange", "flange")}


def robot(group: int = 1) -> Parent:
    """The base (world) of a controller's robot; group 1 is 'robot'."""
    return Parent("robot", "robot" if group == 1 else f"robot@{group}")


def flange(group: int = 1) -> Parent:
    """The flange of a controller's robot; group 1 is 'flange'."""
    return Parent("flange", "flange" if group == 1 else f"flange@{group}")


def unit(name: str | None) -> Parent:
    """A mechanical unit or external kinematic (unnamed: 'mechanical unit')."""
    return Parent("unit", name or "mechanical unit")


def frame_parent(name: str) -> Parent:
    return Parent("frame", name)


class Frame(Value):
    __slots__ = ("name", "vendor", "type", "pose", "file", "line", "reference", "label",
                 "numbers", "info", "_parent", "document")
    _compare = __slots__[:-1]   # the document is where it came from, not what it is

    def __init__(self, name: str, vendor: str, type: str, pose: Pose | None, file: str, line: int,
                 reference: str = "world", label: str | None = None,
                 numbers: dict[str, Number] | None = None, info: dict[str, Any] | None = None,
                 document: Document | None = None, parent: Parent | None = None):
        self.name = name            # 'wobj1', 'wobj1.oframe', 'tools{2}', 'BASE_DATA[3]', 'UF3@2'
        self.vendor = vendor        # 'abb' | 'kuka' | 'fanuc'
        self.type = type            # 'wobjdata', 'tooldata', 'pose', 'BASE_DATA', 'TOOL_DATA',
        #                             'FRAME', 'UFRAME', 'UTOOL'
        self.pose = pose            # None where the file gives no (complete) value
        self.file = file
        self.line = line
        self.reference = reference  # 'world', 'flange', 'uframe', 'wrist', 'machine', ...
        self.label = label          # KUKA BASE_NAME / TOOL_NAME, FANUC comment
        # component name ('x','y','z','q1'..'q4' or 'a','b','c') -> Number in the document
        self.numbers = numbers if numbers is not None else {}
        self.info = info if info is not None else {}   # robhold, ufprog, ufmec, load, storage, ...
        self._parent = parent       # None: the one its reference names (world, flange)
        self.document = document

    @property
    def parent(self) -> Parent:
        """What the frame is relative to (Parent); a parser sets it where the
        reference alone does not say (a frame, a unit, a motion group)."""
        got = self._parent
        return got if got is not None else _PARENT_OF_REFERENCE.get(self.reference, UNKNOWN)

    @parent.setter
    def parent(self, value: Parent | None) -> None:
        self._parent = value

    def __repr__(self) -> str:
        return f"Frame({self.name!r}, {self.vendor}, {self.type}, {self.pose!r}, {self.file}:{self.line})"

    def as_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {"name": self.name, "file": self.file, "line": self.line,
                             "vendor": self.vendor, "type": self.type,
                             "reference": self.reference}
        parent = self.parent
        d["parent"] = parent.name
        d["parent_kind"] = parent.kind
        if self.pose is not None:
            d.update(self.pose.as_dict())
        else:
            d.update({k: None for k in ("x", "y", "z", "a", "b", "c", "q")})
        if self.label is not None:
            d["label"] = self.label
        for k, v in self.info.items():
            d[k] = v
        return d


def tool_tcp(frame: Frame, what: str = "tool") -> tuple[float, float, float]:
    """The TCP a robot-held tool gives a measurement: its translation in
    flange coordinates. A stationary or external tool, or one without a
    complete value, is refused (``what`` names the option in the message)."""
    from ..errors import UcsioError

    if frame.info.get("robhold") is False or frame.reference != "flange":
        raise UcsioError(f"{what}: {frame.name} is not a robot-held tool (reference "
                         f"{frame.reference!r}); the TCP must be given in flange coordinates",
                         file=frame.file, line=frame.line)
    if frame.pose is None:
        raise UcsioError(f"{what}: {frame.name} has no complete value", file=frame.file,
                         line=frame.line)
    from ..defaults import MAX_MAGNITUDE
    if any(abs(v) > MAX_MAGNITUDE for v in frame.pose.t):
        raise UcsioError(f"{what}: {frame.name}'s TCP {frame.pose.t} is too large for a fit "
                         f"(at most {MAX_MAGNITUDE:.0e} mm)", file=frame.file, line=frame.line)
    return frame.pose.t
