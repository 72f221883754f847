"""Universal Robots installation files (``.installation``, PolyScope 5):
gzip around XML (../shared/corpus/ur/README.md). The document layer reads
the gzip stream (``parsing.document.Gzip``); this module reads its XML.

What ucsio takes from it, each value an attribute's number as a span of
the XML, so a patch replaces exactly it:

- TCPs: ``<TCPSettings><availablePoses><tcp name=".." offset="x, y, z, rx,
  ry, rz"/>``, metres and a rotation vector in radians, in the flange;
- features, in the robot base: ``<GeomPoseNode name="..">`` points (their
  ``toolPosition`` metres, ``toolAxisAngle`` a rotation vector) and
  ``<GeomPlaneNode name="..">`` planes, whose frame is their derived
  ``firstPoint``; their taught points (``userFirstPoint`` ... ) and the
  other derived points (``secondPoint``: the origin plus 1 m along y,
  ``thirdPoint``) are numbers of the same frame, written together.

The XML is scanned, not parsed into objects ucsio writes back: tags with
their attributes, checked for nesting, every other character kept. The
safety settings' ``sourceFeatureId`` lines name the features the safety
configuration uses.
"""
from __future__ import annotations

import math

from ...geometry import rotations as rot
from ...geometry.frames import Frame, Number, NumbersOnDemand, Pose, flange, robot
from ...parsing import regex
from ...parsing.document import Document, Span
from ...parsing.model import ControllerFile

VENDOR = "ur"
COMPONENTS = ("x", "y", "z", "rx", "ry", "rz")
# a plane's points beside its frame (firstPoint): derived, then taught
PLANE_POINTS = ("secondPoint", "thirdPoint", "userFirstPoint", "userSecondPoint",
                "userThirdPoint")
TAUGHT = ("userFirstPoint", "userSecondPoint", "userThirdPoint")
FEATURES = {"GeomPoseNode": "POINT", "GeomPlaneNode": "PLANE"}

_MARKUP = regex.lazy(
    r"<(?:!--.*?-->|\?.*?\?>|!\[CDATA\[.*?\]\]>|!DOCTYPE[^>]*>"
    r"|(?P<close>/)?(?P<tag>[A-Za-z_][\w.:-]*)"
    r"(?P<attrs>(?:[^<>\"'/]|\"[^\"<]*\"|'[^'<]*'|/(?!>))*+)(?P<empty>/)?>)", 16)   # re.S
_ATTR = regex.lazy(r"\s+(?P<name>[A-Za-z_][\w.:-]*)\s*=\s*(?:\"(?P<dq>[^\"<]*)\"|'(?P<sq>[^'<]*)')")
# a tag whose attributes are well formed (nearly every one), matched once, its
# attributes read when asked for; a '<' that begins no such tag matches alone,
# and _MARKUP reads it
_TAG = regex.lazy(r"<(?:(?P<close>/)?(?P<tag>[A-Za-z_][\w.:-]*)"
                  r"(?P<attrs>(?:\s+[A-Za-z_][\w.:-]*\s*=\s*(?:\"[^\"<]*\"|'[^'<]*'))*+)"
                  r"\s*(?P<empty>/)?>|)")     # or a '<' alone: _MARKUP reads it
_NUMBER_TEXT = r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
_NUMBER = regex.lazy(_NUMBER_TEXT)
# a whole value of 3 or 6 numbers (a position, a rotation vector, a TCP's offset), one
# match for all: a file holds hundreds; any other value is read number by number
_VALUES = {n: regex.lazy(",".join([rf"\s*({_NUMBER_TEXT})\s*"] * n)) for n in (3, 6)}
# a tag whose one attribute is such a value (a point's toolPosition, toolAxisAngle):
# its name and numbers read from the tag's text, with no dict of its attributes
_ONLY_VALUE = {n: regex.lazy(r"\s+([A-Za-z_][\w.:-]*)\s*=\s*\"" + ",".join(
    [rf"\s*({_NUMBER_TEXT})\s*"] * n) + '"') for n in (3, 6)}
_SOURCE_FEATURE = regex.lazy(r"(?m)^[ \t]*sourceFeatureId[ \t]*=[ \t]*(?P<id>[^\s]+)")
_ENTITIES = {"&lt;": "<", "&gt;": ">", "&amp;": "&", "&quot;": '"', "&apos;": "'"}


class Element:
    """One XML element: its tag, its attributes (name -> (value, offset of
    the value's first character)), where its start tag stands, its children.
    The attributes are kept as text and made a dict when first read (a name
    given twice is an error then, as the .dtx reader does): most (joint
    values, the points' TCPs, the safety settings) never are, and a file
    has thousands. ``check`` reads every one."""

    __slots__ = ("tag", "_attrs", "start", "children", "parent", "_doc")

    def __init__(self, tag: str, attrs, start: int, parent: "Element | None", doc=None):
        self.tag, self._attrs, self.start, self.parent, self._doc = tag, attrs, start, parent, doc
        self.children: list[Element] = []

    @property
    def attrs(self) -> dict[str, tuple[str, int]]:
        if type(self._attrs) is tuple:
            self._attrs = _attributes(self._doc, *self._attrs)
        return self._attrs

    def get(self, name: str) -> str | None:
        got = self.attrs.get(name)
        return None if got is None else got[0]

    def child(self, tag: str) -> "Element | None":
        for c in self.children:
            if c.tag == tag:
                return c
        return None


def sniff(doc: Document) -> bool:
    """An installation's root element, after an XML declaration if any."""
    head = doc.text[:256].lstrip("\ufeff \t\r\n")
    if head.startswith("<?xml"):
        head = head[head.find("?>") + 2:].lstrip()
    return head.startswith("<Installation") and head[13:14] in (" ", ">", "/", "\t", "\n", "\r")


def scan(doc: Document) -> tuple[Element, list[Element]]:
    """The element tree of the XML, its root <Installation>, and every
    element below the root in document order (a list, not a walk of the
    tree: hostile XML may nest deeper than Python's stack); an error at the
    first tag out of place. Well-formed tags (nearly every one) are found by
    one pass of ``_TAG``; a '<' that begins none goes to ``_MARKUP`` (a
    comment, a declaration, a tag whose attributes are not well formed:
    checked at once), and the pass goes on after it."""
    text = doc.text
    root = Element("", {}, 0, None)
    top = root
    every: list[Element] = []
    add = every.append
    tags, markup = _TAG.finditer, _MARKUP.match      # bound once: a file has thousands of tags
    pos = 0
    while True:
        for m in tags(text, pos):
            tag, close, empty = m.group("tag", "close", "empty")
            if tag is None:                     # a '<' that begins no well-formed tag
                at = m.start()
                m = markup(text, at)
                if m is None:
                    raise doc.error("malformed XML: a '<' that begins no tag, comment or "
                                    "declaration", at)
                pos = m.end()
                tag, close, empty = m.group("tag", "close", "empty")
                if tag is None:                 # a comment, a declaration
                    break
                attrs = _attributes_checked(doc, m.group("attrs"), m.start("attrs"))
            else:
                attrs = None
            if close:
                if top is root or top.tag != tag:
                    want = f"</{top.tag}>" if top is not root else "no end tag"
                    raise doc.error(f"malformed XML: </{tag}> where {want} belongs", m.start())
                top = top.parent
            else:
                element = Element(tag, attrs if attrs is not None else
                                  (m.group("attrs"), m.start("attrs")), m.start(), top, doc)
                top.children.append(element)
                add(element)
                if not empty:
                    top = element
            if attrs is not None:
                break                           # on after the tag read the careful way
        else:
            break
    if top is not root:
        raise doc.error(f"malformed XML: <{top.tag}> is never closed", top.start)
    if len(root.children) != 1 or root.children[0].tag != "Installation":
        raise doc.error("not a Universal Robots installation: its root element is not "
                        "<Installation>", root.children[0].start if root.children else 0)
    return root.children[0], every[1:]


def _attributes(doc: Document, text: str, start: int) -> dict[str, tuple[str, int]]:
    """A well-formed tag's attributes (``_TAG``'s): name -> (value, its
    offset); where a name is given twice (or a value holds an "="), the
    careful path, which says where."""
    if not text:
        return {}
    attrs = _attribute_dict(text, start)
    if len(attrs) < text.count("="):
        return _attributes_checked(doc, text, start)
    return attrs


def _attribute_dict(text: str, start: int) -> dict[str, tuple[str, int]]:
    """Well-formed attributes (``_TAG``'s): name -> (value, its offset)."""
    attrs: dict[str, tuple[str, int]] = {}
    for a in _ATTR.finditer(text):
        name, dq = a.group("name", "dq")
        attrs[name] = (dq, start + a.start("dq")) if dq is not None else \
            (a.group("sq"), start + a.start("sq"))
    return attrs


def _attributes_checked(doc: Document, text: str, start: int) -> dict:
    """The attributes one by one (the slow path: a tag not well formed, a
    name given twice, an "=" in a value): an error at the first fault."""
    attrs: dict[str, tuple[str, int]] = {}
    pos = 0
    for a in _ATTR.finditer(text):
        if text[pos:a.start()].strip():
            break
        group = "dq" if a.group("dq") is not None else "sq"
        if a.group("name") in attrs:
            raise doc.error(f"malformed XML: attribute {a.group('name')} given twice",
                            start + a.start("name"))
        attrs[a.group("name")] = (a.group(group), start + a.start(group))
        pos = a.end()
    if text[pos:].strip():
        raise doc.error("malformed XML: an attribute that is not name=\"value\"",
                        start + pos + len(text[pos:]) - len(text[pos:].lstrip()))
    return attrs


def _numbers_matched(m, at: int, keys: tuple[str, ...], prefix: str,
                     first: int = 1) -> dict | None:
    """The Numbers of a value ``_VALUES`` (or ``_ONLY_VALUE``) matched, the
    first number its group ``first``; None where one is not finite (1e999:
    the slow path says which)."""
    out: dict[str, Number] = {}
    for group, key in enumerate(keys, first):
        body = m.group(group)
        value = float(body)
        if not math.isfinite(value):
            return None
        start = at + m.start(group)
        out[prefix + key] = Number(Span(start, start + len(body)), body, value)
    return out


def unescape(value: str) -> str:
    if "&" not in value:
        return value
    for entity, char in _ENTITIES.items():
        value = value.replace(entity, char)
    return value


def _only_value(element: Element | None, attr: str, n: int):
    """``_ONLY_VALUE``'s match where ``element``'s one attribute is ``attr``
    holding ``n`` numbers and its attributes are still text; else None."""
    raw = element._attrs if element is not None else None
    only = _ONLY_VALUE.get(n) if type(raw) is tuple else None
    m = only.fullmatch(raw[0]) if only is not None else None
    return m if m is not None and m.group(1) == attr else None


def numbers_of(doc: Document, element: Element, attr: str, keys: tuple[str, ...],
               prefix: str = "") -> dict[str, Number]:
    """The comma-separated numbers of ``element``'s ``attr`` as Numbers,
    one per key; an error at the attribute where they are not so many
    finite numbers."""
    m = _only_value(element, attr, len(keys))
    if m is not None:
        out = _numbers_matched(m, element._attrs[1], keys, prefix, 2)
        if out is not None:
            return out
    got = element.attrs.get(attr)
    if got is None:
        raise doc.error(f"<{element.tag}> without its {attr} attribute", element.start)
    value, at = got
    whole = _VALUES.get(len(keys))
    m = whole.fullmatch(value) if whole is not None else None
    if m is not None:
        out = _numbers_matched(m, at, keys, prefix)
        if out is not None:
            return out
    out = {}
    parts = value.split(",")
    if len(parts) != len(keys):
        raise doc.error(f"{attr}: {len(keys)} numbers expected, {len(parts)} found", at)
    offset = at
    number = _NUMBER.fullmatch
    for key, part in zip(keys, parts):
        body = part.strip()
        start = offset + len(part) - len(part.lstrip())
        value = float(body) if number(body) is not None else math.nan
        if not math.isfinite(value):
            raise doc.error(f"{attr}: {body!r} is not a finite number", start)
        out[prefix + key] = Number(Span(start, start + len(body)), body, value)
        offset += len(part) + 1
    return out


def pose_of(numbers: dict[str, Number], prefix: str = "") -> Pose:
    """Metres and a rotation vector (radians) as ucsio's pose: mm, a quaternion."""
    return pose_of_values([numbers[prefix + k].value for k in COMPONENTS])


def pose_of_values(values) -> Pose:
    x, y, z, rx, ry, rz = values
    return Pose.from_quat(x * 1000.0, y * 1000.0, z * 1000.0, rot.rotvec_to_quat((rx, ry, rz)))


def point_numbers(doc: Document, node: Element, prefix: str = "") -> dict[str, Number]:
    """A GeomPoseNode's toolPosition and toolAxisAngle, keyed x ... rz."""
    out = {}
    for attr_tag, keys in (("toolPosition", COMPONENTS[:3]), ("toolAxisAngle", COMPONENTS[3:])):
        child = node.child(attr_tag)
        if child is None:
            raise doc.error(f"<{node.tag}> without <{attr_tag}>", node.start)
        out.update(numbers_of(doc, child, "value", keys, prefix))
    return out


def point_values(doc: Document, node: Element) -> list[float]:
    """``point_numbers``' six values without a Number for each (what a
    listing needs): each tag's one attribute ``value`` of three finite
    numbers read at once; ``point_numbers`` reads anything else, and says
    what is wrong with it."""
    out: list[float] = []
    for attr_tag in ("toolPosition", "toolAxisAngle"):
        m = _only_value(node.child(attr_tag), "value", 3)
        if m is None:
            return [n.value for n in point_numbers(doc, node).values()]
        out += map(float, m.group(2, 3, 4))
    if not max(map(abs, out)) < math.inf:     # 1e999: point_numbers says where
        return [n.value for n in point_numbers(doc, node).values()]
    return out


def parse(doc: Document, full: bool = False) -> ControllerFile:
    """An installation's TCPs and features. ``full`` (check) reads the same,
    the scan checking every tag either way, and also says whether this
    Python's zlib writes the stream back (``gzip-stream``)."""
    cf = ControllerFile(doc, VENDOR)
    root, every = scan(doc)
    # check's (``full``): whether this zlib writes the stream back costs a deflate of
    # the whole text, which a command that only reads the file does not need
    if full and doc.gzip is not None and doc.gzip.refusal is not None:
        cf.lint(0, "gzip-stream", doc.gzip.refusal, "info")
    if full:                    # every tag's attributes, a name given twice an error
        for element in every:
            element.attrs
    cf.extra["safety_features"] = _safety_features(root, doc)
    for element in every:
        if element.tag == "tcp" and element.parent is not None \
                and element.parent.tag == "availablePoses":
            cf.frames.append(_tcp(doc, element))
        elif element.tag in FEATURES:
            if element.get("name") is not None and element.get("hiddenSubFeature") != "true":
                cf.frames.append(_feature(doc, cf, element))
        elif element.tag[:4] == "Geom" and element.tag[-4:] == "Node" \
                and element.get("name") is not None:
            # a line feature (GeomLineNode), or a kind PolyScope may add: named, so that
            # a frame ucsio does not list is not taken for one the file does not hold
            kind = element.tag[4:-4].lower() or element.tag
            name = unescape(element.get("name"))
            what = f"a {kind} ({element.tag}): ucsio reads point and plane features"
            cf.lint(element.start, "unread-feature", f"feature {name!r} is {what}; not listed",
                    "info")
            cf.extra.setdefault("unread", {})[name.strip().casefold()] = \
                f"it is {what} (line {doc.line_of(element.start)})"
    return cf


def _safety_features(root: Element, doc: Document) -> set[str]:
    """The feature ids the safety settings' planes name (``sourceFeatureId``)."""
    safety = root.child("SafetySettings")
    if safety is None:
        return set()
    end = doc.text.find("</SafetySettings>", safety.start)
    return {m.group("id") for m in _SOURCE_FEATURE.finditer(doc.text, safety.start, end)}


def _frame(doc: Document, element: Element, type_: str, numbers: dict, pose: Pose,
           reference: str, parent, info: dict) -> Frame:
    name = unescape(element.get("name") or "")
    return Frame(name, VENDOR, type_, pose, doc.path, doc.line_of(element.start),
                 reference=reference, numbers=numbers, info=info, document=doc, parent=parent)


def _tcp(doc: Document, element: Element) -> Frame:
    numbers = numbers_of(doc, element, "offset", COMPONENTS)
    return _frame(doc, element, "TCP", numbers, pose_of(numbers), "flange", flange(), {})


def _feature(doc: Document, cf: ControllerFile, element: Element) -> Frame:
    type_ = FEATURES[element.tag]
    if type_ == "POINT":
        pose = pose_of_values(point_values(doc, element))
        numbers = NumbersOnDemand(lambda: point_numbers(doc, element))
    else:
        numbers = point_numbers(doc, point_node(doc, element, "firstPoint"))
        for tag in PLANE_POINTS:
            numbers.update(point_numbers(doc, point_node(doc, element, tag), tag + "."))
        pose = pose_of(numbers)
    ident = element.get("id")
    info = {"id": ident}
    if ident in cf.extra["safety_features"]:
        info["safety"] = True
    frame = _frame(doc, element, type_, numbers, pose, "world", robot(), info)
    if type_ == "PLANE":
        _check_plane(cf, frame, element)
    return frame


def point_node(doc: Document, plane: Element, tag: str) -> Element:
    holder = plane.child(tag)
    node = holder.child("GeomPoseNode") if holder is not None else None
    if node is None:
        raise doc.error(f"plane {plane.get('name')!r} without its <{tag}> point", plane.start)
    return node


def taught_positions(frame: Frame) -> list[tuple[float, float, float]]:
    """A plane's three taught points (mm, robot base)."""
    return [tuple(frame.numbers[f"{tag}.{k}"].value * 1000.0 for k in "xyz")
            for tag in TAUGHT]


def _check_plane(cf: ControllerFile, frame: Frame, element: Element) -> None:
    """The plane's frame (firstPoint) is the 3-point construction of its
    taught points: a lint where it is not (a file edited by hand, a frame
    written without its points)."""
    built = Pose.from_three_points(*taught_positions(frame))
    if built is None:
        cf.lint(element.start, "plane-points", f"plane {frame.name}: its taught points are "
                "collinear: they define no frame")
        return
    moved = max(abs(a - b) for a, b in zip(built.t, frame.pose.t))
    turned = rot.quat_angle(built.q, frame.pose.q)
    if moved > 1e-3 or turned > 1e-4:
        cf.lint(element.start, "plane-points",
                f"plane {frame.name}: its frame (firstPoint) is {moved:.3f} mm and "
                f"{turned:.4f} deg from the 3-point construction of its taught points")
