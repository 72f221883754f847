"""FANUC controller files: what the three readers share.

A FANUC backup keeps its data as ASCII listings beside the binary files
the controller loads (../shared/SPEC.md "FANUC"):

- ``.va`` variable listings (ucsio.vendors.fanuc.va, grammars/va.lark):
  ``sysframe.va`` holds the frames, ``$MNUFRAME[g,n]`` (user frames,
  relative to world) and ``$MNUTOOL[g,n]`` (tool frames, relative to the
  faceplate); ``posreg.va`` the position registers; ``FRAMEVAR.VA`` the
  frame set-up data with the frames' comments;
- ``.ls`` TP programs (ucsio.vendors.fanuc.tp, grammars/tp.lark), which may set
  frames (``UFRAME[1:FIXTURE]=PR[16]``), and the controller's logs that
  share the suffix (``errall.ls``);
- ``.dg`` diagnostic listings (ucsio.vendors.fanuc.dg): ``frame.dg`` (the frame
  tables with their comments, one decimal), ``curpos.dg`` (the current
  position, in world and in the user frame).

Names: ``UF3`` and ``UT2`` in motion group 1, ``UF3@2`` in group 2; the
frame's comment is its label. W, P, R give R = Rz(R)·Ry(P)·Rx(W): the KUKA
matrix with A = R, B = P, C = W (ucsio.geometry.rotations).
"""
from __future__ import annotations

import os

from ...errors import UcsioError
from ...geometry.frames import Frame, Number, Pose, flange, robot
from ...parsing.document import Document
from ...parsing.model import ControllerFile

VENDOR = "fanuc"
SUFFIXES = (".va", ".dg", ".ls")
# binary files of a FANUC backup: programs (.tp), system files (.sv), variable
# files (.vr). ucsio reads their ASCII twins (.ls, .va) and lists these as not read.
BINARY_SUFFIXES = (".tp", ".sv", ".vr")
COMPONENTS = ("x", "y", "z", "w", "p", "r")
KINDS = {"UFRAME": ("UF", "world"), "UTOOL": ("UT", "flange")}


def parent(ftype: str, group: int):
    """UFk@g is relative to group g's robot (its world, fixed to its base),
    UTk@g to group g's faceplate."""
    return robot(group) if ftype == "UFRAME" else flange(group)
ANGLE_MAX = 180.0
REACH_MAX = 1e6         # mm: a translation of 1 km or more is not a frame of a cell
REAL_MAX = 3.4028235e38  # FANUC REAL is float32


def frame_name(ftype: str, number, group: int = 1) -> str:
    """UF3, UT2 (group 1), UF3@2 (group 2); ``number`` may be text (R[9])."""
    prefix = KINDS[ftype][0]
    number = f"[{number}]" if isinstance(number, str) else str(number)
    return prefix + number + ("" if group == 1 else f"@{group}")


def is_frame_name(name: str) -> bool:
    """Whether ``name`` has the form of a frame's name (UF3, ut2, UF3@2,
    UF[R[9]])."""
    import re
    return re.fullmatch(r"\s*u[ft]\s*(?:[0-9]+|\[.*\])\s*(?:@\s*[0-9]+)?\s*", name,
                        re.I | re.S) is not None


def controller_file(doc: Document) -> ControllerFile:
    """An empty FANUC ControllerFile: a name of a frame's form (UF2) names
    that frame only, never a frame commented so."""
    cf = ControllerFile(document=doc, vendor=VENDOR)
    cf.name_form = is_frame_name
    return cf


def make_frame(doc: Document, ftype: str, number, group: int, line: int,
               numbers: dict[str, Number] | None, values: dict[str, float] | None = None,
               label: str | None = None, info: dict | None = None,
               pose: Pose | None = None) -> Frame:
    """A FANUC frame. ``values``: the six components x, y, z, w, p, r where
    they are all known (``numbers`` holds those the file writes: a program's
    LPOS-LPOS gives zeros that stand nowhere), else None. ``pose``: theirs,
    where the caller has it already."""
    if values is None and numbers is not None and len(numbers) == 6:
        values = {k: n.value for k, n in numbers.items()}
    extra = {"group": group}
    if values is not None:
        x, y, z, w, p, r = (values[k] for k in COMPONENTS)
        if pose is None:
            pose = Pose.from_wpr(x, y, z, w, p, r)
        extra.update(w=w + 0.0, p=p + 0.0, r=r + 0.0)
    else:
        extra.update(w=None, p=None, r=None)
    if info:
        extra.update(info)
    return Frame(name=frame_name(ftype, number, group), vendor=VENDOR, type=ftype, pose=pose,
                 file=doc.path, line=line, reference=KINDS[ftype][1], label=label,
                 numbers=dict(numbers or {}), info=extra, document=doc,
                 parent=parent(ftype, group))


# The comments a controller gives frames nobody named (UFrame7, Eoat2): a
# frame's number after one of these words; ucsio.review.unset counts such a
# comment as no name, as it counts KUKA's TOOL_NAME[2,]="TOOL_DATA[2]".
DEFAULT_COMMENTS = {"UFRAME": ("uframe",), "UTOOL": ("eoat", "utool")}


def default_comment(ftype: str, name: str, label: str) -> bool:
    """Whether ``label`` is the controller's default comment of the frame
    called ``name`` (UF7@2: 'UFrame7'; UT2: 'Eoat2'), case and blanks aside."""
    import re
    number = re.match(r"U[FT]([0-9]+)(?:@|\Z)", name)
    words = DEFAULT_COMMENTS.get(ftype, ())
    if number is None or not words:
        return False
    said = re.fullmatch(r"([a-z]+)[ _]*0*([0-9]+)", label.strip().casefold())
    return said is not None and said.group(1) in words and \
        said.group(2) == number.group(1).lstrip("0")


def range_problem(key: str, value: float) -> str | None:
    """Why a frame component is out of what the controller holds, or None."""
    if key in ("w", "p", "r"):
        if abs(value) > ANGLE_MAX:
            return f"{key.upper()} {value:g} is outside [-180, 180]"
    elif abs(value) >= REACH_MAX:
        return f"{key.upper()} {value:g} mm is 1 km or more from the origin"
    return None


# -- which reader -----------------------------------------------------------------
def kind_of(doc: Document) -> str:
    """'va', 'ls' or 'dg': by the suffix, else by the first words (a git
    temporary file: git's external diff hands ucsio the path shown beside it,
    textconv only the temporary file)."""
    suffix = os.path.splitext(doc.path)[1].lower()
    if suffix in SUFFIXES:
        return suffix[1:]
    head = doc.text[:256].lstrip("\ufeff \t\r\n")
    return "ls" if head.startswith("/PROG") else "va"


def sniff(doc: Document) -> bool:
    """Whether a file without a FANUC suffix begins like one: a TP program
    (/PROG) or a variable listing ([*SYSTEM*]$NAME  Storage: ...)."""
    head = doc.text[:512].lstrip("\ufeff \t\r\n")
    if head.startswith("/PROG"):
        return True
    if head.startswith("[") and "]" in head[:64]:
        line = head.split("\n", 1)[0]
        return "Storage:" in line or "Access:" in line
    return False


# -- the frames' comments, from the files beside sysframe.va -------------------------
LABEL_FILES = ("framevar.va", "frame.dg")


def labels_beside(path: str, readers: dict) -> tuple[dict, list[UcsioError]]:
    """The frames' comments the files beside ``path`` give: ``FRAMEVAR.VA``
    (SETUP_DATA[g,1,n].$COMMENT for tool n, [g,3,n] for user frame n) and
    ``frame.dg`` (its Tool Frame and User Frame tables, group 1), names
    matched case-insensitively. Returns ({(type, n, group): label}, errors
    of files that could not be read); FRAMEVAR.VA wins where both give one.
    ``readers`` maps each of LABEL_FILES to the function that reads its
    Document's comments (the va and dg readers, which import this module)."""
    found = _beside(path) if os.path.isfile(path) or ".zip!" in path.lower() else {}
    labels: dict = {}
    errors: list[UcsioError] = []
    for name in reversed(LABEL_FILES):           # frame.dg first: FRAMEVAR.VA overrides
        src = found.get(name)
        if src is None:
            continue
        try:
            labels.update(_labels_of(src, readers[name]))
        except UcsioError as exc:
            if exc.file is None:
                exc.file = src.name
            errors.append(exc)
    return labels, errors


def _beside(path: str) -> dict:
    """{lower-case name: Source} of the label files in ``path``'s folder (or,
    for ``ARCHIVE.zip!dir/file``, beside it in the archive)."""
    from ...parsing.sources import Source, open_zip, split_member
    member = split_member(path) if ".zip" in path.lower() else None
    if member is not None:
        archive, inner = member
        folder = inner.replace("\\", "/").rpartition("/")[0]
        out = {}
        for info in open_zip(archive).infolist():
            n = info.filename.replace("\\", "/")
            d, _, base = n.rpartition("/")
            if d.casefold() == folder.casefold() and base.lower() in LABEL_FILES:
                out[base.lower()] = Source(f"{archive}!{info.filename}", n, archive=archive,
                                           member=info.filename)
        return out
    folder = os.path.dirname(path) or "."
    try:
        names = os.listdir(folder)
    except OSError:
        return {}
    out = {}
    for n in sorted(names):
        low = n.lower()
        if low in LABEL_FILES and low not in out:
            full = os.path.join(folder, n)
            out[low] = Source(full, n, path=full)
    return out


_LABEL_CACHE: dict = {}


def _labels_of(src, read) -> dict:
    """A label file's comments, read once per run for each (file, size, time):
    the sysframe.va of every robot in a folder of backups asks for its own."""
    key = src.name
    stamp = None
    if src.path is not None:
        try:
            st = os.stat(src.path)
            stamp = (st.st_size, st.st_mtime_ns)
        except OSError:
            stamp = None
    got = _LABEL_CACHE.get(key)
    if got is not None and got[0] == stamp and stamp is not None:
        return got[1]
    labels = read(Document(src.read(), src.name))
    _LABEL_CACHE[key] = (stamp, labels)
    return labels


# -- the grammars' trees; syntax errors: Lark's diagnosis, worded for people -----------
def tree(name: str, doc: Document, text: str, readable: dict, what: str,
         lark_first: bool = False):
    """The tree of ``text`` (the grammar's copy of ``doc``) from
    grammars/NAME.lark's ``file``; where the grammar rejects it, one
    UcsioError naming file:line:col (``syntax_error``). ``lark_first``: the
    recogniser has rejected it already."""
    from ...parsing.grammar import SyntaxFailure, parse
    try:
        return parse(name, ("file",), text, "file", lark_first)
    except SyntaxFailure as failure:
        raise syntax_error(doc, text, failure.error, readable, what) from None


def syntax_error(doc: Document, text: str, exc: Exception, readable: dict, what: str):
    """The UcsioError for Lark's exception ``exc`` on ``text`` (the grammar's
    copy of ``doc``): file:line:col and what was expected there."""
    from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedToken

    if isinstance(exc, (UnexpectedCharacters, UnexpectedToken)):
        from ...parsing.numbers import bad_number
        bad = bad_number(text, exc.pos_in_stream if isinstance(exc, UnexpectedCharacters)
                          else exc.token.start_pos if exc.token.type != "$END" else len(text))
        if bad is not None:
            return doc.error(f"{what}: malformed number {text[bad[0]:bad[1]][:30]!r}", bad[0])
    if isinstance(exc, UnexpectedCharacters):
        pos = exc.pos_in_stream
        expected = _expecting(set(exc.allowed or ()), readable)
        return doc.error(f"{what}: unexpected {_shown(text, pos)}{expected}", pos)
    if isinstance(exc, UnexpectedEOF):
        return doc.error(f"{what}: unexpected end of file", len(text))
    if isinstance(exc, UnexpectedToken):
        tok = exc.token
        expected = _expecting(set(exc.expected or ()), readable)
        if tok.type == "$END":
            return doc.error(f"{what}: unexpected end of file{expected}", len(text))
        pos = tok.start_pos
        if tok.type == "_NL":
            return doc.error(f"{what}: unexpected end of line{expected}", pos)
        return doc.error(f"{what}: unexpected {_shown(text, pos)}{expected}", pos)
    raise exc


def _shown(text: str, pos: int) -> str:
    """The rest of the line at ``pos``, quoted, at most 30 characters."""
    end = text.find("\n", pos, pos + 40)
    s = text[pos:end if end >= 0 else pos + 40].rstrip("\r")
    if not s:
        return "end of line"
    return repr(s if len(s) <= 30 else s[:30] + "...")


def _expecting(expected: set, readable: dict) -> str:
    words = sorted({readable.get(e, "a keyword" if e.startswith("__") else e.lower())
                    for e in expected if e not in ("WS",)})
    if not words or len(words) > 7:
        return ""
    return "; expected " + " or ".join(words)
