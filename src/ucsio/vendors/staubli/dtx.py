"""Stäubli VAL3 data files (``.dtx``), both dialects, read as text.

- CS8 (``<dataList xmlns="DataNameSpace">``): sections of data, each datum
  with its father and its values, one element per array entry::

      <frameSection><frame name="f" public="false">
        <fFather alias="" name="world" fatherIndex="0" />
        <valueFrame index="0"><tfValue x=".." y=".." z=".." rx=".." ry=".." rz=".." /></valueFrame>
      </frame></frameSection>

  tools alike (``toolSection``/``tool``/``tFather``/``valueTool``/``ttValue``),
  points too (``pointSection``/``point``/``pFather``/``valuePoint``/``tpValue``).
- s7 / CS9 (``<Database xmlns="http://www.staubli.com/robotics/VAL3/Data/2">``):
  ``<Datas><Data name="f" type="frame|tool|pointRx" size="n"><Value key="k"
  x=".." … fatherId="world[0]" /></Data></Datas>``, the father on each entry.

An attribute left out is 0 (a tool ``<Value key="0" fatherId="flange[0]"/>``
is the flange itself). Entry k of a datum of size > 1 is ``name[k]``; a
datum of one entry is ``name``. Each number is a span of the document (no
XML library keeps a BOM, the attribute order and the blanks), so the file
round-trips byte for byte and a malformed tag or number is one error naming
file:line:col. Tags ucsio does not use are checked for nesting only.
"""
from __future__ import annotations

import math

from ...geometry.frames import Frame, Number, Pose
from ...parsing import regex
from ...parsing.document import Document, Span
from ...parsing.model import ControllerFile
from .convention import xyz_to_quat
from .entries import COMPONENTS, Entry, father_parent

VENDOR = "staubli"
CS8, CS9 = "CS8", "CS9"
# CS8 section element -> (kind, father element, entry element, value element)
CS8_KINDS = {"frame": ("frame", "fFather", "valueFrame", "tfValue"),
             "tool": ("tool", "tFather", "valueTool", "ttValue"),
             "point": ("point", "pFather", "valuePoint", "tpValue")}
# s7/CS9 Data type -> kind
CS9_KINDS = {"frame": "frame", "tool": "tool", "pointRx": "point"}

# a comment, declaration or processing instruction (no name), or a tag: its
# attributes greedy up to '>' (an empty element's ends in '/')
_TAG = regex.lazy(
    r"(?s)<(?:!--.*?-->|\?.*?\?>|![^>]*>"
    r"|(?P<close>/)?(?P<name>[A-Za-z_][\w.:-]*)(?P<attrs>[^<>]*)>)")
_ATTR = regex.lazy(r"\s+(?P<key>[A-Za-z_][\w.:-]*)\s*=\s*(?:\"(?P<dq>[^\"<]*)\"|'(?P<sq>[^'<]*)')")
# a tag's attributes, checked for their form at once (parsed only where read)
_ATTRS = regex.lazy(r"(?:\s+[A-Za-z_][\w.:-]*\s*=\s*(?:\"[^\"<]*\"|'[^'<]*'))*\s*")
_NUMBER = regex.lazy(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?\Z")
_FATHER_ID = regex.lazy(r"(?P<name>[^\[\]]*)\[(?P<index>[0-9]+)\]\Z")
# a VAL3 name: letters, digits and _ (no blank, bracket or line break)
_NAME = regex.lazy(r"\w+\Z")


def shown(name: str, most: int = 40) -> str:
    """A name as a message shows it: a mangled file's may run for lines."""
    return name if len(name) <= most else name[:most] + "…"


def sniff(doc: Document) -> bool:
    """Whether a file begins like a .dtx (a git temporary file has no suffix)."""
    head = doc.text[:512]
    return "<dataList" in head and "DataNameSpace" in head or \
        "staubli.com/robotics/VAL3/Data" in head


class Tag:
    """One start tag: its name, where it starts, and its attributes (name ->
    (value, offset of the value)), parsed when first asked for: most tags
    of a file are checked for their form only."""

    __slots__ = ("name", "at", "attr_text", "_doc", "_text_at", "_attrs")

    def __init__(self, name: str, at: int, doc: Document, text: str, text_at: int):
        self.name, self.at = name, at
        self.attr_text, self._doc, self._text_at = text, doc, text_at
        self._attrs: dict[str, tuple[str, int]] | None = None

    @property
    def attrs(self) -> dict[str, tuple[str, int]]:
        if self._attrs is None:
            self._attrs = _attributes(self._doc, self.attr_text, self._text_at)
        return self._attrs

    def get(self, key: str, default: str | None = None) -> str | None:
        got = self.attrs.get(key)
        return got[0] if got is not None else default


# -- the tags ------------------------------------------------------------------------
def tags(doc: Document):
    """Each start tag of the document, in order (an empty element's too),
    with its nesting checked: yields (Tag, the open elements around it)."""
    text = doc.text
    stack: list[Tag] = []
    pos = 0
    attrs_ok = _ATTRS.fullmatch         # bound once: a file has thousands of tags
    for m in _TAG.finditer(text):
        i = m.start()
        if text.find("<", pos, i) >= 0:                 # skipped: it opens nothing
            raise doc.error("a '<' that opens no tag, comment or declaration",
                            text.find("<", pos, i))
        pos = m.end()
        name = m.group("name")
        if name is None:
            continue                                    # <?xml ?>, <!-- -->, <!DOCTYPE>
        if m.group("close"):
            _close(doc, stack, m, i)
            continue
        attrs = m.group("attrs")
        empty = attrs.endswith("/")
        tag = Tag(name, i, doc, attrs[:-1] if empty else attrs, m.start("attrs"))
        if attrs and attrs_ok(tag.attr_text) is None:
            tag.attrs                                   # its error, at the place
        yield tag, stack
        if not empty:
            stack.append(tag)
    if text.find("<", pos) >= 0:
        raise doc.error("a '<' that opens no tag, comment or declaration", text.find("<", pos))
    if stack:
        raise doc.error(f"<{shown(stack[-1].name)}> is never closed", stack[-1].at)
    if text[pos:].strip():
        raise doc.error("text after the last element", pos + len(text[pos:]) -
                        len(text[pos:].lstrip()))


def _close(doc: Document, stack: list[Tag], m, at: int) -> None:
    name = m.group("name")
    if m.group("attrs").strip():
        raise doc.error(f"</{shown(name)}> with something after its name", m.start("attrs"))
    if not stack:
        raise doc.error(f"</{shown(name)}> closes no element", at)
    if stack[-1].name != name:
        line = doc.line_of(stack[-1].at)
        raise doc.error(f"</{shown(name)}> where <{shown(stack[-1].name)}> (line {line}) is "
                        "still open", at)
    stack.pop()


def _attributes(doc: Document, text: str, at: int) -> dict[str, tuple[str, int]]:
    out: dict[str, tuple[str, int]] = {}
    pos = 0
    match = _ATTR.match             # bound once: a lazy pattern's lookup costs each call
    while True:
        m = match(text, pos)
        if m is None:
            break
        key = m.group("key")
        group = "dq" if m.group("dq") is not None else "sq"
        if key in out:
            raise doc.error(f"attribute {shown(key)} given twice", at + m.start("key"))
        out[key] = (m.group(group), at + m.start(group))
        pos = m.end()
    if text[pos:].strip():
        rest = len(text[pos:]) - len(text[pos:].lstrip())
        raise doc.error("not an attribute (name=\"value\")", at + pos + rest)
    return out


# -- the file ------------------------------------------------------------------------
def parse(doc: Document, full: bool = False) -> ControllerFile:
    """A .dtx: its frames and tools (``frames``), its points (``extra
    ["points"]``: solve --robot) and lints. Every byte is read on either
    path (``full`` changes nothing: the file is small and read once)."""
    cf = ControllerFile(document=doc, vendor=VENDOR)
    dialect, entries, roots = _entries(doc)
    cf.extra["dialect"] = dialect
    from .fathers import lint
    known = {e.name: e for e in entries if e.kind != "point"}
    for e in entries:
        if e.kind != "point":
            cf.frames.append(_frame(doc, e, known))
    cf.extra["points"] = [e for e in entries if e.kind == "point"]
    cf.extra["roots"] = roots
    lint(cf, entries)
    return cf


def _entries(doc: Document) -> tuple[str, list[Entry], dict[str, str]]:
    """The dialect, every frame, tool and point entry, and the data the file
    declares as VAL3's roots (CS8 lists ``world`` and ``flange`` with an
    empty father): name -> kind."""
    dialect = None
    entries: list[Entry] = []
    roots: dict[str, str] = {}
    state = _State()
    for tag, stack in tags(doc):
        if not stack:
            if dialect is not None:
                raise doc.error(f"a second top-level element <{shown(tag.name)}>", tag.at)
            dialect = _dialect(doc, tag)
            continue
        if dialect == CS8:
            _cs8_tag(doc, tag, stack, state, entries, roots)
        else:
            _cs9_tag(doc, tag, stack, entries)
    _close_cs8(state, entries, roots)          # the last datum of the file
    if dialect is None:
        raise doc.error("not a Stäubli VAL3 data file: no <dataList> or <Database> element", 0)
    return dialect, entries, roots


def _dialect(doc: Document, root: Tag) -> str:
    if root.name == "dataList":
        return CS8
    if root.name == "Database":
        return CS9
    raise doc.error(f"not a Stäubli VAL3 data file: its root element is <{shown(root.name)}>, not "
                    "<dataList> (CS8) or <Database> (s7, CS9)", root.at)


class _State:
    """The CS8 datum being read: its kind, name, father and entries."""

    __slots__ = ("data", "kind", "father", "at", "index", "entries")

    def __init__(self):
        self.data: Tag | None = None
        self.kind: str | None = None
        self.father: tuple[str, int] | None = None
        self.at = 0
        self.index: tuple[int, int] | None = None
        self.entries: list[Entry] = []


def _cs8_tag(doc: Document, tag: Tag, stack: list[Tag], state: _State, entries: list[Entry],
             roots: dict[str, str]) -> None:
    depth = len(stack)
    if depth == 2 and tag.name in CS8_KINDS and stack[1].name == tag.name + "Section":
        _close_cs8(state, entries, roots)
        state.__init__()
        state.data, state.kind, state.at = tag, tag.name, tag.at
        _name(doc, tag, "name")
        return
    if state.data is None or depth < 3 or stack[2] is not state.data:
        return
    _kind, father_el, entry_el, value_el = CS8_KINDS[state.kind]
    if depth == 3 and tag.name == father_el:
        name = _name(doc, tag, "name", empty=True) if "name" in tag.attrs else ""
        index = _index(doc, tag, "fatherIndex", default=0)
        state.father = (name, index)
    elif depth == 3 and tag.name == entry_el:
        state.index = (_index(doc, tag, "index", default=0), tag.at)
    elif depth == 4 and tag.name == value_el and state.index is not None:
        index, at = state.index
        state.entries.append(Entry(state.kind, state.data.get("name"), index, 0,
                                   _numbers(doc, tag), None, at, state.at))


def _close_cs8(state: _State, entries: list[Entry], roots: dict[str, str]) -> None:
    """A CS8 datum read whole: its entries get its size and father; ``world``
    and ``flange`` (an empty father) are VAL3's roots, not frames."""
    if state.data is None:
        return
    father = state.father
    if father is not None and father[0] == "" and state.kind != "point":
        roots[state.data.get("name")] = state.kind
        return
    size = len(state.entries)
    for e in state.entries:
        e.size, e.father = size, father
        entries.append(e)


def _cs9_tag(doc: Document, tag: Tag, stack: list[Tag], entries: list[Entry]) -> None:
    # <Database><Datas><Data type=..><Value .../>: only top-level data
    if len(stack) == 3 and tag.name == "Value" and stack[1].name == "Datas" and \
            stack[2].name == "Data":
        data = stack[2]
        kind = CS9_KINDS.get(data.get("type", ""))
        if kind is None:
            return
        size = _index(doc, data, "size", default=1)
        index = _index(doc, tag, "key", default=0)
        father = _father_id(doc, tag)
        entries.append(Entry(kind, _name(doc, data, "name"), index, size, _numbers(doc, tag),
                             father, tag.at, data.at))


def _father_id(doc: Document, tag: Tag) -> tuple[str, int] | None:
    got = tag.attrs.get("fatherId")
    if got is None:
        return None
    text, at = got
    m = _FATHER_ID.match(text)
    if m is None or _NAME.match(m.group("name")) is None:
        raise doc.error(f"fatherId {shown(text)!r} is not name[index]", at)
    return m.group("name"), doc.integer(m.group("index"), at + m.start("index"), "fatherId index")


def _require(doc: Document, tag: Tag, key: str) -> str:
    value = tag.get(key)
    if value is None:
        raise doc.error(f"<{shown(tag.name)}> without its {key}", tag.at)
    return value


def _name(doc: Document, tag: Tag, key: str, empty: bool = False) -> str:
    """A datum's or father's name, a VAL3 name (``empty``: "" allowed, a
    CS8 root's father)."""
    value = _require(doc, tag, key)
    if not (empty and value == "") and _NAME.match(value) is None:
        raise doc.error(f"{key} {shown(value)!r} is not a VAL3 name (letters, digits, _)",
                        tag.attrs[key][1])
    return value


def _index(doc: Document, tag: Tag, key: str, default: int) -> int:
    got = tag.attrs.get(key)
    if got is None:
        return default
    text, at = got
    if not text.isdigit() or not text.isascii():
        raise doc.error(f"{key} {text[:30]!r} is not a whole number", at)
    return doc.integer(text, at, key)


def _numbers(doc: Document, tag: Tag) -> dict[str, Number]:
    """x, y, z, rx, ry, rz as written, each with its span (absent: not here)."""
    out: dict[str, Number] = {}
    attrs, number = tag.attrs, _NUMBER.match
    for key in COMPONENTS:
        got = attrs.get(key)
        if got is None:
            continue
        text, at = got
        if number(text) is None:
            raise doc.error(f"{key}: not a number: {text[:30]!r}" if text else
                            f"{key}: a number is missing here", at)
        value = float(text)
        if not math.isfinite(value):
            raise doc.error(f"{key}: number out of range: {text[:30]!r}", at)
        out[key] = Number(Span(at, at + len(text)), text, value)
    return out


# -- frames --------------------------------------------------------------------------
def _frame(doc: Document, e: Entry, known: dict[str, Entry]) -> Frame:
    x, y, z, rx, ry, rz = e.values()
    pose = Pose.from_quat(x, y, z, xyz_to_quat(rx, ry, rz))
    parent = father_parent(e, known)
    info = {"rx": rx + 0.0, "ry": ry + 0.0, "rz": rz + 0.0,
            "father": _father_text(e.father)}
    absent = [k for k in COMPONENTS if k not in e.numbers]
    if absent:
        info["absent"] = absent         # 0 by VAL3's rule
    reference = {"world": "world", "flange": "flange"}.get(parent.kind, e.kind if
                                                           parent.kind == "frame" else "unknown")
    return Frame(name=e.name, vendor=VENDOR, type=e.kind, pose=pose, file=doc.path,
                 line=doc.line_of(e.at), reference=reference, numbers=e.numbers, info=info,
                 document=doc, parent=parent)


def _father_text(father: tuple[str, int] | None) -> str | None:
    return None if father is None else f"{father[0]}[{father[1]}]"
