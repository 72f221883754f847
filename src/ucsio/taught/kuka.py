"""KUKA: the E6POS/POS points taught in a base.

An inline-form motion keeps its point as ``DECL E6POS XP1={...}`` and its
frame data as ``DECL FDAT FP1={TOOL_NO 1,BASE_NO 3,IPO_FRAME #BASE,...}`` in
the program's .dat. A point is taught in BASE_DATA[n] when its FDAT has
BASE_NO n (and IPO_FRAME #BASE: with #TCP the base is an external TCP and
the point is a robot-held workpiece's, which the base's change moves
differently). Points are searched in every .dat file of the controller's
tree: the KRC folder around $config.dat (KRC/R1/System/$config.dat ->
KRC/), else R1/ for R1/System/$config.dat, else the file's own folder.

Each .dat is read as the fast path reads frames: the E6POS/POS/FDAT
declaration lines and the layout lines kept, the rest blanked, one Lark
parse of the masked text (grammars/krl.lark, start ``file``).
"""
from __future__ import annotations

import os
import re
from pathlib import Path

from .. import krl
from ..controller import ControllerFile
from ..document import Document
from ..errors import UcsioError
from ..frames import Frame
from . import Found, TaughtPoint

_WS = r"[ \t\f\r]"
_POINT_LINE = re.compile(r"\n(" + _WS + r"*(?:(?:DECL|GLOBAL|CONST)" + _WS + r"+)*"
                         r"(?:E6POS|POS|FDAT)" + _WS + r"[^\n]*)", re.I)
_BASE_ENTRY = re.compile(r"BASE_DATA\[(\d+)\]\Z", re.I)
MAX_DEPTH = 3        # how far up from $config.dat a KRC folder is looked for


def tree_root(config: str) -> Path:
    """The controller's tree around ``config``."""
    folder = Path(os.path.abspath(config)).parent
    for up in [folder, *list(folder.parents)[:MAX_DEPTH]]:
        if up.name.upper() == "KRC":
            return up
    if folder.name.upper() == "SYSTEM" and folder.parent.name.upper().startswith("R"):
        return folder.parent
    return folder


def dat_files(root: Path) -> list[Path]:
    out = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames.sort()
        out.extend(_shown(Path(dirpath) / f) for f in sorted(filenames)
                   if f.lower().endswith(".dat"))
    return out


def _shown(path: Path) -> Path:
    """A path as a person reads it: relative to the current folder when below it."""
    rel = os.path.relpath(path)
    return Path(rel) if not rel.startswith("..") else path


def declarations(doc: Document) -> list[tuple[str, str, int, object]]:
    """(type, name, line, value) of every E6POS, POS and FDAT declared with a
    value (scalars; arrays are filled element by element and carry no FDAT)."""
    text = doc.text
    nl_text = "\n" + text
    spans = [(m.start(1) - 1, m.end(1) - 1) for m in _POINT_LINE.finditer(nl_text)]
    if not spans:
        return []
    spans += krl._layout_lines(text, nl_text)
    tree = krl._parse(doc, krl.masked(text, sorted(set(spans))), "file")
    out = []
    for s in krl._statements(tree, doc):
        if s.kind != "decl" or s.type not in ("E6POS", "POS", "FDAT"):
            continue
        for name, dims, val in s.vars:
            if dims is None and val is not None:
                out.append((s.type, name.value, s.line, krl._value(val)))
    return out


def _number(fields: dict, key: str):
    got = fields.get(key)
    if got is None or got[1].kind != "number":
        return None
    return got[1].value


def points_in(doc: Document, base_no: int, found: Found) -> None:
    decls = declarations(doc)
    fdat = {name.upper(): v for t, name, _, v in decls if t == "FDAT" and v.kind == "struct"}
    for t, name, line, v in decls:
        if t == "FDAT" or v.kind != "struct" or not name.upper().startswith("X"):
            continue
        f = fdat.get("F" + name[1:].upper())
        if f is None or _number(f.value, "BASE_NO") != base_no:
            continue
        ipo = f.value.get("IPO_FRAME")
        if ipo is not None and ipo[1].kind == "enum" and ipo[1].value == "#TCP":
            found.warnings.append(f"{doc.path}:{line}: {name} is taught with IPO_FRAME #TCP "
                                  "(an external TCP): not counted")
            continue
        xyz = tuple(_number(v.value, k) for k in "XYZ")
        if None in xyz:
            found.warnings.append(f"{doc.path}:{line}: {name} has no complete X, Y, Z: "
                                  "not counted")
            continue
        found.points.append(TaughtPoint(name, doc.path, line, xyz))  # type: ignore[arg-type]


def find(cf: ControllerFile, frame: Frame, load=None) -> Found:
    found = Found()
    m = _BASE_ENTRY.match(frame.name)
    if frame.type != "BASE_DATA" or m is None:
        found.warnings.append(f"{frame.name} is not a base (BASE_DATA[n]): points are taught "
                              "in bases (FDAT BASE_NO)")
        return found
    base_no = int(m.group(1))
    for path in dat_files(tree_root(frame.file)):
        try:
            same = path.resolve() == Path(frame.file).resolve()
            doc = cf.document if same else Document.read(path)
            points_in(doc, base_no, found)
        except UcsioError as exc:
            found.warnings.append(f"could not read {path} ({exc}); its points are not counted")
    return found
