"""Mutation fuzzing of the controller-file readers and the patcher (issue 12 point 8).

The oracle, for any bytes:

- every command ends in a result or in one UcsioError (one line, a sane
  position), never another exception, never "internal error";
- the fast path (frames, diff, patch) accepts exactly what ``check`` accepts
  for structure: where ``check`` (the whole-file grammar) accepts a file the
  fast path accepts it too, with the same frames; where the fast path
  refuses a file, ``check`` refuses it too. (``check`` may refuse more: it
  also reads every number outside frame data.)
- an unedited document writes back byte for byte, and ``check``'s round trip
  holds;
- a patch of any frame either is refused (UcsioError) or changes only that
  frame's numbers, reads back as the target, and leaves a file ``check``
  accepts if it accepted the original.

tests/test_fuzz.py runs a few hundred deterministic hypothesis examples of
this; ``python benchmarks/fuzz.py --minutes N`` runs it for longer and saves
every failing input.
"""
from __future__ import annotations

import math
import random
import re
import tempfile
from pathlib import Path

from oracles import only_numbers_changed
from ucsio.parsing import grammar
from ucsio.parsing import lalr
from ucsio.geometry import rotations as rot
from ucsio.parsing.controller import parse
from ucsio.parsing.document import Document
from ucsio.errors import UcsioError
from ucsio.geometry.frames import Pose
from ucsio.parsing.lalr import Rejected

ROOT = Path(__file__).resolve().parents[1]
CORPUS = ROOT.parent / "shared" / "corpus"

# Pieces a mutation inserts: structure tokens of both languages, trivia where
# it is legal but unusual, and the hostile shapes of issue 12.
TOKENS = [
    b"[", b"]", b"{", b"}", b"(", b")", b",", b";", b":=", b"=", b"!", b"! note\n", b";note\n",
    b'"', b"'", b"-", b"- ! note\n", b"+", b".", b"E", b"e+", b"#", b"&", b"%%%", b"$",
    b"\n", b"\r", b"\r\n", b"\r\r\n", b"\t", b" ", b" " * 300, b"\n" * 200, b"\x00", b"\x1a",
    b"\xef\xbb\xbf", b"\xff", b"\xc3\xa9", b"\xe2\x82\xac",
    b"1E400", b"-1E400", b"1E38", b"3.5E38", b"9" * 400, b"0x" + b"F" * 300, b"0d" + b"9" * 5000,
    b"1.2.3", b"12ab", b"0", b"-0", b".5", b"5.",
    b"MODULE", b"ENDMODULE", b"PERS", b"CONST", b"VAR", b"LOCAL", b"TASK", b"wobjdata",
    b"tooldata", b"pose", b"PROC p()\n", b"ENDPROC\n", b"RECORD r\n", b"ENDRECORD\n", b"<EXP>",
    b"<DDN>", b"DEFDAT X\n", b"ENDDAT\n", b"DECL", b"FRAME", b"GLOBAL", b"BASE_DATA[1]",
    b"TOOL_DATA[1]=", b"BASE_NAME[1,]=", b"MACHINE_FRAME_DAT[1]={MACH_DEF_INDEX 1E400}\n",
    b"INT MAX_BASE=1E400\n", b"X", b"X.5", b"[" * 300, b"]" * 300, b"{X " * 300, b"}" * 300,
    b"- " * 300, b"a" * 2000,
    # FANUC listings and programs
    b"[*SYSTEM*]$MNUFRAME  Storage: SHADOW  Access: RW  : ARRAY[1,2] OF POSITION\n",
    b"    [1,1] = ", b"'c'", b"  Group: 1   Config: N U T, 0, 0, 0", b"Config: ", b"  X: ",
    b"  W: ", b"********", b"Uninitialized", b"J1 = ", b" deg", b" mm", b"Field: ",
    b"/MN\n", b"/POS\n", b"/END\n", b"/PROG  P\n", b"   1:  ", b"UFRAME[", b"UTOOL[1:x]=PR[1] ;",
    b"PR[1,1]=", b"(-", b"((", b"LPOS", b"LPOS-LPOS", b"R[", b"P[1]{", b"GP1:", b"};",
    b"UF : 1, UT : 1,", b"X = ", b"    :  ", b"-.000", b".140",
    # Yaskawa condition files, jobs, RBCALIB.DAT and VAR.DAT
    b"//UFRAME 1\r\n", b"//TOOL 0\r\n", b"//UFRAME", b"///NAME ", b"///NAME \r\n", b"///TOOL ",
    b"///TOOL 1\r\n", b"///USER ", b"///USER 2\r\n", b"///GROUP 1,0,0,0\r\n", b"///GROUP ",
    b"///BASICFRM 1,19,", b"///BASICFRM 1,19,1\r\n", b"///BASICFRM 1,20,0\r\n", b"///BASEP ",
    b"////BUSER ", b"////RORG C000=", b"///CRC 12345\r\n", b"///CRC", b"/JOB\r\n", b"//NAME ",
    b"//POS\r\n", b"//INST\r\n", b"///NPOS ", b"///NPOS 1,0,0,0,0,0\r\n", b"///POSTYPE ",
    b"///POSTYPE USER\r\n", b"///POSTYPE PULSE\r\n", b"///POSTYPE BASE\r\n",
    b"///POSTYPE TOOL\r\n", b"///RECTAN\r\n", b"///PULSE\r\n", b"///RCONF ", b"///RCONF 0,0,0\r\n",
    b"C00003=", b"P00012=", b"BC00001=", b"EX001=", b"C00000=1,2,3,4,5,6\r\n", b"1,2,3,4,5,6,7",
    b"//VAR\r\n", b"///P\r\n", b"///R\r\n", b'"RECTAN"', b'"UNUSED"', b'"PULSE"', b'""',
    b'"RECTAN"0,0,4,000000000000000000000000,0,16,1,2,3,4,5,6,0.0000,0.0000\r\n',
    b"//RBCALIB 1\r\n", b"////SRANG ", b"///MGROUP ", b"///SGROUP 0,1,0\r\n", b"///MTOOL ",
    b"////MRBC1 ", b"MFRAME UF#(2) P010 P011 P012\r\n", b"MOVL P", b"P[", b"'", b",,",
]


DEMO_DATA = ROOT / "src" / "ucsio" / "demo" / "data"


def seed_files(max_size: int | None = None) -> list[Path]:
    """Real files first (the corpus, where it is beside the checkout), then
    our fixtures and the demo's cells; optionally only those up to
    ``max_size`` bytes."""
    from ucsio.vendors import BACKUP_SUFFIXES, VENDORS   # every registered vendor's files

    found = []
    for folder in [CORPUS / e.name for e in VENDORS] + [ROOT / "fixtures", DEMO_DATA]:
        if folder.is_dir():
            for p in sorted(folder.rglob("*")):
                if p.is_file() and p.suffix.lower() in BACKUP_SUFFIXES:
                    if max_size is None or p.stat().st_size <= max_size:
                        found.append(p)
    return found


# ------------------------------------------------------------------ mutations

def mutate(raw: bytes, ops: list[tuple[int, int, int]]) -> bytes:
    """Apply ``ops``, each (kind, a, b) with a, b arbitrary non-negative
    integers read modulo what they index, so any integers make a mutation
    (what hypothesis and a random generator both need)."""
    for kind, a, b in ops:
        n = len(raw)
        pos = a % (n + 1)
        kind %= KINDS
        if kind == 0:                                   # flip one byte
            if n:
                raw = raw[:pos % n] + bytes([b % 256]) + raw[pos % n + 1:]
        elif kind == 1:                                 # delete a range
            raw = raw[:pos] + raw[pos + 1 + b % 64:]
        elif kind == 2:                                 # insert a token
            raw = raw[:pos] + TOKENS[b % len(TOKENS)] + raw[pos:]
        elif kind == 3:                                 # truncate
            raw = raw[:pos]
        elif kind == 4:                                 # duplicate a range
            raw = raw[:pos] + raw[pos:pos + 1 + b % 200] + raw[pos:]
        elif kind == 5:                                 # every line ending CR alone
            raw = raw.replace(b"\r\n", b"\n").replace(b"\n", b"\r")
        elif kind == 6:                                 # a BOM in front (or a second one)
            raw = b"\xef\xbb\xbf" + raw
        elif kind == 7:                                 # a number made huge
            digits = [i for i in range(n) if 48 <= raw[i] <= 57]
            if digits:
                i = digits[b % len(digits)]
                raw = raw[:i] + TOKENS[TOKENS.index(b"1E400") + b % 4] + raw[i + 1:]
        elif kind == 8:                                 # nest the value at a bracket
            opens = [i for i in range(n) if raw[i] in b"[{"]
            if opens:
                i = opens[b % len(opens)]
                depth = 1 + a % 400
                close = b"]" if raw[i] == 91 else b"}"
                inner = b"X " if raw[i] == 123 else b""
                raw = raw[:i] + (raw[i:i + 1] + inner) * depth + b"1" + close * depth + raw[i:]
        elif kind == 9:                                 # swap two lines
            lines = raw.split(b"\n")
            if len(lines) > 1:
                i, j = a % len(lines), b % len(lines)
                lines[i], lines[j] = lines[j], lines[i]
                raw = b"\n".join(lines)
        else:                                           # trivia where a word ends or starts
            edges = [i for i in range(1, n) if _WORD[raw[i - 1]] != _WORD[raw[i]]]
            if edges:
                i = edges[a % len(edges)]
                raw = raw[:i] + TRIVIA[b % len(TRIVIA)] + raw[i:]
    return raw


KINDS = 11
# trivia both languages allow between tokens (RAPID: all; KRL: blanks, a comment at a line's end)
TRIVIA = [b" ", b"\t", b"\n", b"\r\n", b" ! note\n", b"!\n", b"; note\n", b"\n\n", b"  \t "]
_WORD = [chr(c).isalnum() or chr(c) in "_.$" for c in range(256)]


def mutate_inside_gzip(raw: bytes, ops: list[tuple[int, int, int]]) -> bytes:
    """A gzip file (Universal Robots' .installation) with its content
    mutated and deflated again as PolyScope does (zlib level 6, the header
    kept): the XML's reader sees the mutation, not gzip's CRC check."""
    import zlib
    try:
        body = zlib.decompress(raw, 31)
    except zlib.error:
        return mutate(raw, ops)
    body = mutate(body, ops)
    deflate = zlib.compressobj(6, zlib.DEFLATED, -15, 8, zlib.Z_DEFAULT_STRATEGY)
    stream = deflate.compress(body) + deflate.flush()
    return (raw[:10] + stream + zlib.crc32(body).to_bytes(4, "little")
            + (len(body) & 0xFFFFFFFF).to_bytes(4, "little"))


# ------------------------------------------------------------------ the oracle

class Finding(AssertionError):
    """What the oracle found wrong, with the input that shows it."""


def _parse(doc: Document, full: bool):
    """(ControllerFile, None) or (None, UcsioError); any other exception is a finding."""
    try:
        return parse(doc, full=full), None
    except UcsioError as exc:
        _sane_error(doc, exc, "check" if full else "frames")
        return None, exc
    except Exception as exc:  # noqa: BLE001 - exactly what the oracle looks for
        raise Finding(f"{'check' if full else 'frames'}: {type(exc).__name__}: {exc}"[:300]) \
            from exc


def _sane_error(doc: Document, exc: UcsioError, what: str) -> None:
    msg = str(exc)
    if "internal error" in msg:
        raise Finding(f"{what}: {msg[:300]}")
    if "\n" in msg or "\r" in msg or len(msg) > 400 or not exc.message:
        raise Finding(f"{what}: not one short line: {msg[:300]!r}")
    if exc.line is not None:
        lines = len(doc.line_starts)
        if not 1 <= exc.line <= lines or exc.col is None or exc.col < 1:
            raise Finding(f"{what}: position {exc.line}:{exc.col} outside the file "
                          f"({lines} lines): {msg[:200]}")


def outcome(cf, err) -> tuple:
    """What ``check`` shows of a file: its error, or its frames and lints."""
    from ucsio.commands.check import check_parsed

    if cf is None:
        return ("error", str(err))
    return ("parsed", check_parsed(cf), _frames_of(cf))


def lark_tree(module, text: str, start: str = "file"):
    """Lark's tree of ``text``, or None where Lark rejects it."""
    from lark.exceptions import LarkError

    try:
        return grammar.lark_parser(module.__name__.rsplit(".")[-1], module.START).parse(
            text, start=start)
    except LarkError:
        return None


def same_tree(ours, theirs) -> bool:
    """Node for node, token for token (type, text, offsets), no recursion."""
    from lark import Tree as LarkTree

    stack = [(ours, theirs)]
    while stack:
        a, b = stack.pop()
        if isinstance(b, LarkTree):
            if not isinstance(a, lalr.Tree) or a.data != b.data or len(a.children) != len(b.children):
                return False
            stack.extend(zip(a.children, b.children))
        elif not (isinstance(a, lalr.Token) and (a.type, a.value, a.start_pos, a.end_pos)
                  == (b.type, b.value, b.start_pos, b.end_pos)):
            return False
    return True


def same_as_whole_tree(doc: Document, full, full_err) -> None:
    """``check`` (the recogniser over every byte, the fast path for frames)
    shows exactly what Lark's tree of every byte shows (``parse_whole``)."""
    from ucsio.vendors.fanuc import base as fanuc
    from ucsio.vendors.kuka import krl
    from ucsio.vendors.abb import rapid
    from ucsio.vendors.fanuc import tp
    from ucsio.vendors.fanuc import va
    from ucsio.vendors import BY_NAME, detect as detect_vendor
    from ucsio.parsing.controller import Unsupported
    from ucsio.parsing.document import looks_binary, lf_lines

    if looks_binary(doc.raw) or isinstance(full_err, Unsupported):
        return          # refused by its first line (another controller's) before any grammar
    vendor = detect_vendor(doc)
    if not BY_NAME[vendor].grammars:
        return          # a vendor read line by line: no whole-file tree to compare with
    if vendor == "fanuc":
        kind = fanuc.kind_of(doc)
        text = lf_lines(doc.text)
        if kind == "dg" or not text.strip() or (kind == "ls" and not tp.is_program(text)):
            return          # no grammar: a diagnostic listing, a log, an empty file
        module = va if kind == "va" else tp
    else:
        module = rapid if vendor == "abb" else krl
        text = krl._lines(doc) if module is krl and doc.text.strip() else doc.text
    want = lark_tree(module, text)
    try:
        got = module._parser().parse(text, "file")
    except Rejected:
        got = None
    if (got is None) != (want is None) or (want is not None and not same_tree(got, want)):
        raise Finding("ucsio.parsing.lalr's tree is not Lark's" if want is not None and got is not None
                      else f"ucsio.parsing.lalr {'accepts' if got is not None else 'rejects'} what "
                           f"Lark {'rejects' if want is None else 'accepts'}")
    try:
        ref = module.parse_whole(doc), None
    except UcsioError as exc:
        ref = None, exc
    if outcome(full, full_err) != outcome(*ref):
        raise Finding(f"check and the whole-file tree differ: {outcome(full, full_err)!r:.300} "
                      f"!= {outcome(*ref)!r:.300}")


def _frames_of(cf) -> list:
    return [(f.as_dict(), {k: (n.span.start, n.span.end, n.signs) for k, n in f.numbers.items()})
            for f in cf.frames]


def target_for(pose: Pose, name: str) -> Pose:
    """A pose near ``pose`` (deterministic in the frame's name), some values
    crossing zero so that signs change."""
    rng = random.Random(name)
    d = rot.abc_to_quat(rng.uniform(-20, 20), rng.uniform(-20, 20), rng.uniform(-20, 20))
    q = rot.quat_multiply(pose.q, d)
    t = [c + rng.choice([-1, 1]) * rng.uniform(0, 2 * abs(c) + 1) for c in pose.t]
    return Pose.from_quat(*t, q)


def check_bytes(name: str, raw: bytes, patches: int = 2) -> str:
    """Run the oracle on one input; raise Finding on anything wrong. Returns
    a short word for statistics ('refused', 'accepted', 'check-only')."""
    from ucsio.commands.check import round_trip

    doc = Document(raw, name)
    if doc.to_bytes() != raw:
        raise Finding("the unedited document does not write back byte for byte")
    fast, fast_err = _parse(doc, full=False)
    full, full_err = _parse(Document(raw, name), full=True)
    same_as_whole_tree(Document(raw, name), full, full_err)
    if full is not None and fast is None:
        raise Finding(f"check accepts, the fast path refuses: {fast_err}")
    if fast is not None and full is not None:
        if _frames_of(fast) != _frames_of(full):
            raise Finding("the fast path and check give different frames")
        if not round_trip(full):
            raise Finding("check's round trip fails on a file it accepts")
    robot_positions_oracle(name, raw, doc, fast)
    if fast is None:
        return "refused"
    free_p_oracle(name, raw, fast)
    # patches: each refused cleanly, or confined to the frame's numbers
    done = 0
    for frame in fast.frames:
        if done >= patches:
            break
        if frame.pose is None:
            continue
        done += 1
        target = target_for(frame.pose, frame.name)
        _patch_oracle(doc, fast, full, frame, target, measured=False)
        if frame.vendor == "yaskawa" and frame.type == "UFRAME":
            # a measured frame in the robot base, taken into the frame's parent
            # (a frame on user frame k: UFk^-1 * target; a circle refused)
            _patch_oracle(doc, fast, full, frame, target, measured=True)
    return "accepted" if full is not None else "check-only"


def _patch_oracle(doc: Document, fast, full, frame, target: Pose, measured: bool) -> None:
    """One patch of ``frame``: refused cleanly, or confined to its numbers."""
    from ucsio.review.patch import patch_frame

    name = doc.path
    try:
        res = patch_frame(fast, frame.name, target, measured=measured, check_siblings=False)
    except UcsioError as exc:
        _sane_error(doc, exc, f"patch {frame.name}")
        return
    except Exception as exc:  # noqa: BLE001
        raise Finding(f"patch {frame.name}: {type(exc).__name__}: {exc}"[:300]) from exc
    never_written(doc, frame)
    new = Document(res.new_bytes, name)
    again, err = _parse(new, full=False)
    if again is None:
        raise Finding(f"patch {frame.name}: the patched file is refused: {err}")
    # a TP program may set the frame twice alike: the patch writes both
    # (tests/test_fanuc_write.py), so the name's every setting is compared
    before = [f for f in fast.frames if f.name == frame.name]
    got = [f for f in again.frames if f.name == frame.name]
    if len(got) != len(before):
        raise Finding(f"patch {frame.name}: set {len(before)} times before the patch, "
                      f"{len(got)} after")
    if not only_numbers_changed(doc.text, before, new.text, got):
        raise Finding(f"patch {frame.name}: bytes outside the frame's numbers changed")
    if full is not None:
        checked, err = _parse(Document(res.new_bytes, name), full=True)
        if checked is None:
            raise Finding(f"patch {frame.name}: check refuses the patched file: {err}")


# ------------------------------------------------------------------ Yaskawa's own oracles

# a TOOL.CND line ucsio cannot recompute: a file with one is never written
_CRC_LINE = re.compile(r"^/{3,4}CRC", re.M)
# the tools and user frames a fuzzed job's positions are resolved through
R05 = DEMO_DATA / "R05_yaskawa"


def never_written(doc: Document, frame) -> None:
    """A patch that went through on what must never be written: a
    condition file with a ///CRC line anywhere (its checksum is not known),
    RBCALIB.DAT's calibration, a Universal Robots feature a safety plane
    names, a gzip stream this zlib does not reproduce."""
    if frame.vendor == "ur":
        if frame.info.get("safety"):
            raise Finding(f"patch {frame.name}: a feature the safety configuration uses was "
                          "written")
        if doc.gzip is not None and doc.gzip.refusal is not None:
            raise Finding(f"patch {frame.name}: a gzip stream zlib does not reproduce was "
                          "written")
        return
    if frame.vendor != "yaskawa":
        return
    if frame.type == "RBCALIB":
        raise Finding(f"patch {frame.name}: RBCALIB.DAT's calibration was written")
    if _CRC_LINE.search(doc.text):
        raise Finding(f"patch {frame.name}: a file with a ///CRC line was written")


def _in_temp(name: str, raw: bytes, use):
    """``use(path)`` with ``raw`` written to a fresh folder as ``name``."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / name
        path.write_bytes(raw)
        return use(str(path))


def robot_positions_oracle(name: str, raw: bytes, doc: Document, fast) -> None:
    """solve --robot's reader of a job (.JBI) or a .dtx's points: a clean
    error where check refuses the file, else one robot position per C and P
    row (per point), each a finite flange pose or a clean problem; never
    another exception."""
    from ucsio import vendors
    from ucsio.parsing.controller import load

    if name.lower().endswith(".installation"):
        _taught_poses_oracle(name, raw, doc, fast)
        return
    suffix = name.lower().rsplit(".", 1)[-1]
    if suffix not in ("jbi", "dtx"):
        return
    who = "yaskawa" if suffix == "jbi" else "staubli"
    vendor = vendors.get(who)
    configs = (str(R05 / "TOOL.CND"), str(R05 / "UFRAME.CND")) if who == "yaskawa" else None
    try:
        got = _in_temp(name, raw, lambda path: vendor.robot_positions(
            path, config=configs, tool="tool0", wobj="wobj0", load=load))
    except UcsioError as exc:
        _sane_error(doc, exc, "solve --robot")
        if fast is not None and fast.vendor == who:
            raise Finding(f"solve --robot refuses a file check reads: {exc.message}"[:300]) \
                from exc
        return
    except Exception as exc:  # noqa: BLE001
        raise Finding(f"solve --robot: {type(exc).__name__}: {exc}"[:300]) from exc
    if who == "yaskawa" and (fast is None or fast.extra.get("kind") != "job"):
        raise Finding("solve --robot reads a job check refuses")
    if fast is None or fast.vendor != who:
        raise Finding("solve --robot reads a file check refuses")
    rows = [p for p in fast.extra["positions"] if p.kind in ("C", "P")] if who == "yaskawa" \
        else fast.extra["points"]
    if len(got.poses) != len(rows):
        raise Finding(f"solve --robot: {len(got.poses)} positions, check reads {len(rows)}")
    for rp in got.poses:
        if rp.problem is not None:
            _sane_error(doc, rp.problem, f"solve --robot {rp.name}")
        elif not all(math.isfinite(v) for row in rp.flange for v in row):
            raise Finding(f"solve --robot {rp.name}: a flange pose that is not finite")


def _taught_poses_oracle(name: str, raw: bytes, doc: Document, fast) -> None:
    """solve --robot's reader of a Universal Robots installation: refuses
    exactly what check refuses, else each taught pose a finite flange pose
    or a clean problem."""
    from ucsio import vendors
    from ucsio.parsing.controller import load

    try:
        got = _in_temp(name, raw, lambda path: vendors.get("ur").robot_positions(
            path, config=None, tool="tool0", wobj="wobj0", load=load))
    except UcsioError as exc:
        _sane_error(doc, exc, "solve --robot")
        if fast is not None and fast.vendor == "ur":
            raise Finding(f"solve --robot refuses an installation check reads: {exc.message}"
                          [:300]) from exc
        return
    except Exception as exc:  # noqa: BLE001
        raise Finding(f"solve --robot: {type(exc).__name__}: {exc}"[:300]) from exc
    if fast is None:
        raise Finding("solve --robot reads an installation check refuses")
    for rp in got.poses:
        if rp.problem is not None:
            _sane_error(doc, rp.problem, f"solve --robot {rp.name}")
        elif not all(math.isfinite(v) for row in rp.flange for v in row):
            raise Finding(f"solve --robot {rp.name}: a flange pose that is not finite")


def free_p_oracle(name: str, raw: bytes, cf) -> None:
    """ucsio program --var VAR.DAT: three free P variables the file says are
    unused (and the controller has), or a clean error."""
    from ucsio.vendors.yaskawa import program, var

    if cf.vendor != "yaskawa" or cf.extra.get("kind") != "global variables":
        return
    try:
        chosen = _in_temp(name, raw, lambda path: program.choose_p(None, path, [])[0])
    except UcsioError as exc:
        _sane_error(cf.document, exc, "program --var")
        return
    except Exception as exc:  # noqa: BLE001
        raise Finding(f"program --var: {type(exc).__name__}: {exc}"[:300]) from exc
    used = set(var.in_use(cf))
    if len(set(chosen)) != 3 or any(n in used or not 0 <= n < var.p_count(cf) for n in chosen):
        raise Finding(f"program --var: P variables {chosen} are not three free ones")
