"""A new FANUC TP program that sets a measured frame (``ucsio program``).

The controller does not load ``.va`` listings; a frame reaches it through a
TP program (``UFRAME[3]=PR[90]``). ``program(...)`` writes one, as the
controller writes its ``.LS`` files (CRLF, ``/PROG`` ``/ATTR`` ``/MN``
``/POS`` ``/END``):

    /MN
       1:  MESSAGE[UCSIO SETS UF3] ;
       2:  PAUSE ;
       3:  PR[90]=LPOS-LPOS    ;
       4:  PR[90,1]=1500.250    ;
       ...
       9:  PR[90,6]=(-90.000)    ;
      10:  UFRAME[3:FIXTURE]=PR[90] ;

Values to 0.001 mm and 0.001 deg (``write.fanuc_number``: negatives
in parentheses, no leading zero; W, P, R by ``write.wpr_to_write``,
so the three angles' rounding errors do not add up). The text is parsed
back through ucsio's own TP grammar (``tp``) before anything is
written: the frame must read back as the solution within 0.001 mm and
0.001 deg. A group other than 1 is the program's DEFAULT_GROUP, so PR[N]
and the frame are that group's.
"""
from __future__ import annotations

import os

from ...errors import UcsioError
from ...geometry.frames import Pose
from ...parsing.document import Document
from ..common.program import ProgramMade
from ..common.readback import cannot_hold, reads_back, refuse_flagged_values
from .write import fanuc_number, tp_literal, wpr_to_write

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

FRAME_TYPES = {"UF": "UFRAME", "UT": "UTOOL"}
COMMENT_MAX = 16        # a frame's comment on the pendant
NAME_MAX = 36           # a TP program's name
ATTR = ("OWNER\t\t= MNEDITOR;", 'COMMENT\t\t= "{comment}";', "PROG_SIZE\t= 0;", "FILE_NAME\t= ;",
        "VERSION\t\t= 0;", "LINE_COUNT\t= {lines};", "MEMORY_SIZE\t= 0;",
        "PROTECT\t\t= READ_WRITE;", "TCD:  STACK_SIZE\t= 0,", "      TASK_PRIORITY\t= 50,",
        "      TIME_SLICE\t= 0,", "      BUSY_LAMP_OFF\t= 0,", "      ABORT_REQUEST\t= 0,",
        "      PAUSE_REQUEST\t= 0;", "DEFAULT_GROUP\t= {groups};",
        "CONTROL_CODE\t= 00000000 00000000;")


class ProgramResult(ProgramMade):
    """A program made, not yet written: its ``text`` (CRLF), ``name``
    (/PROG), the frame it sets (``frame`` UF3 / UT2 / UF3@2, ``type``,
    ``number``, ``group``), the register ``pr`` and where it came from
    (``pr_from``: "--pr" or the posreg.va), the ``comment``, the ``values``
    written (x y z w p r), the target ``pose``, ``warnings`` and where it
    was ``written``."""

    __slots__ = ("text", "name", "frame", "type", "number", "group", "pr", "pr_from", "comment",
                 "values", "pose", "warnings", "written")

    def summary(self) -> str:
        """What ``ucsio program -o`` says it wrote."""
        v = self.values
        source = "chosen: --pr" if self.pr_from == "--pr" else "unused in " + self.pr_from
        return (f"wrote {self.written}: /PROG {self.name} sets {self.frame} from PR[{self.pr}] "
                f"({source})\n  x {v['x']:.3f}  y {v['y']:.3f}  z {v['z']:.3f}  "
                f"w {v['w']:.3f}  p {v['p']:.3f}  r {v['r']:.3f}")

    def as_dict(self) -> dict[str, Any]:
        return {"file": self.written, "name": self.name, "frame": self.frame, "type": self.type,
                "number": self.number, "group": self.group, "pr": self.pr,
                "pr_from": self.pr_from, "comment": self.comment, "pose": dict(self.values),
                "warnings": list(self.warnings), "text": self.text}


def parse_frame(name: str, group: int | None) -> tuple[str, int, int]:
    """``UF3``, ``UT2``, ``UF3@2`` (and ``--group``) -> (UFRAME|UTOOL, k, group)."""
    import re
    m = re.fullmatch(r"\s*(U[FT])\s*([0-9]+)\s*(?:@\s*([0-9]+))?\s*", name, re.I)
    if m is None:
        raise UcsioError(f"--frame {name!r}: expected UFk or UTk (UF3, UT2; UF3@2 for group 2)")
    from ...parsing.document import shown_digits, small_int
    kind, number = FRAME_TYPES[m.group(1).upper()], small_int(m.group(2))
    at = small_int(m.group(3)) if m.group(3) else None
    if number is None or (m.group(3) and at is None):
        raise UcsioError(f"--frame {shown_digits(name)}: frame number 1...999 and group 1...8")
    if at is not None and group is not None and at != group:
        raise UcsioError(f"--frame {name!r} names group {at}, --group says {group}")
    g = at if at is not None else group if group is not None else 1    # 0 is no group
    if not 1 <= number <= 999 or not 1 <= g <= 8:
        raise UcsioError(f"--frame {name!r}: frame number 1...999 and group 1...8")
    return kind, number, g


def program_name(out: str | None, kind: str, number: int, group: int) -> str:
    """The /PROG name: OUT's file name without its suffix, upper-case (the
    controller names a program after its file); SET_UF3 (SET_UF3_G2) on
    standard output."""
    import re
    if out is None or out == "-":
        return f"SET_{'UF' if kind == 'UFRAME' else 'UT'}{number}" + \
            (f"_G{group}" if group != 1 else "")
    stem = os.path.splitext(os.path.basename(out))[0].upper()
    if not re.fullmatch(r"[A-Z][A-Z0-9_]*", stem) or len(stem) > NAME_MAX:
        raise UcsioError(f"-o {out}: {stem!r} is not a TP program name (a letter, then letters, "
                         f"digits and _, up to {NAME_MAX}): the controller names the program "
                         "after its file")
    return stem


def check_comment(comment: str | None) -> str | None:
    if comment is None:
        return None
    bad = [c for c in comment if not " " <= c <= "~" or c in "[]:;\"'"]
    if bad or not comment.strip():
        raise UcsioError(f"--comment {comment!r}: printable ASCII without [ ] : ; \" ' (the "
                         "frame's comment in UFRAME[k:comment])")
    if len(comment) > COMMENT_MAX:
        raise UcsioError(f"--comment {comment!r}: {len(comment)} characters; a frame's comment "
                         f"holds {COMMENT_MAX}")
    return comment


def unused_register(posreg: str, group: int) -> int:
    """The highest-numbered position register of ``group`` that ``posreg``
    (posreg.va) shows unused: Uninitialized and without a comment in every
    group (the highest: programs number their own from the bottom up). A
    register is one for all groups: posreg.va lists its part of each group
    ([1,n], [2,n]) and its comment on group 1's, so PR[n] with a value or a
    name in group 1 is in use for a group-2 program too."""
    regs = _registers(posreg)
    free = [n for (g, n), e in regs.items() if g == group and _unused_everywhere(regs, n)]
    if not free:
        raise UcsioError(f"no unused position register of group {group} (Uninitialized, without "
                         "a comment): give --pr N", file=posreg)
    return max(free)


def _registers(posreg: str) -> dict:
    from .va import position_registers
    doc = Document.read(posreg) if posreg != "-" else None
    if doc is None:
        from ...files import read_bytes
        doc = Document(read_bytes("-", "posreg.va"), "<stdin>")
    regs = position_registers(doc)
    if not regs:
        raise UcsioError("no $POSREG in this file: not a posreg.va", file=posreg)
    return regs


def _unused(entry) -> bool:
    return bool(entry.uninit) and not (entry.comment or "").strip()


def _unused_everywhere(regs: dict, n: int) -> bool:
    return all(_unused(e) for (g, k), e in regs.items() if k == n)


def check_register(posreg: str, group: int, pr: int) -> None:
    """--pr N with --posreg: refused where the listing shows PR[N] in use
    (a value or a comment, in any group: ``unused_register``), or has no
    such register."""
    regs = _registers(posreg)
    entry = regs.get((group, pr))
    if entry is None:
        size = max((n for (g, n) in regs if g == group), default=0)
        raise UcsioError(f"--pr {pr}: posreg.va has no PR[{pr}] in group {group} (1...{size})",
                         file=posreg)
    for (g, n), e in sorted(regs.items(), key=lambda item: (item[0][0] != group, item[0])):
        if n != pr or _unused(e):
            continue
        what = (f"comment {e.comment.strip()!r}" if (e.comment or "").strip() else "a value")
        where = "" if g == group else f" (group {g}: a register is one for every group)"
        raise UcsioError(f"--pr {pr}: PR[{pr}] holds {what} in this posreg.va{where}: the "
                         "program would overwrite it; choose another --pr (or leave it out to "
                         "take an unused one)", file=posreg)


def make_program(pose: Pose, kind: str, number: int, group: int, pr: int, *,
                 name: str, comment: str | None = None) -> str:
    """The program's text (CRLF line endings)."""
    short = ("UF" if kind == "UFRAME" else "UT") + str(number) + \
        (f"@{group}" if group != 1 else "")
    values = [fanuc_number(v) for v in pose.t] + [t or "" for t, _ in wpr_to_write(pose)]
    at = f"[{number}" + (f":{comment}" if comment else "") + "]"
    mn = [f"MESSAGE[UCSIO SETS {short}] ;", "PAUSE ;",
          f"PR[{pr}]=LPOS-LPOS    ;"]
    mn += [f"PR[{pr},{i}]={tp_literal(v)}    ;" for i, v in enumerate(values, 1)]
    mn.append(f"{kind}{at}=PR[{pr}] ;")
    groups = ",".join("1" if g == group else "*" for g in range(1, max(5, group) + 1))
    head = [f"/PROG  {name}", "/ATTR"] + [
        a.format(comment=f"UCSIO {short}"[:COMMENT_MAX], lines=len(mn), groups=groups)
        for a in ATTR]
    lines = head + ["/MN"] + [f"{i:4d}:  {s}" for i, s in enumerate(mn, 1)] + ["/POS", "/END"]
    return "\r\n".join(lines) + "\r\n"


def from_solution(pose: Pose, frame: str, *, tcp=None, source: str | None = None,
                  output: str | None = None, group: int | None = None, pr: int | None = None,
                  posreg: str | None = None, comment: str | None = None,
                  wpr: tuple[float, float, float] | None = None) -> ProgramResult:
    """``ucsio program``'s FANUC program (the vendor's ``frame_program``):
    ``pose`` the solution's frame, ``tcp`` its solved TCP (None: given)."""
    return program(pose, frame, group=group, pr=pr, comment=comment, posreg=posreg,
                   out=output, tcp=tcp, wpr=wpr)


def program(pose: Pose, frame: str, *, group: int | None = None, pr: int | None = None,
            comment: str | None = None, posreg: str | None = None, out: str | None = None,
            tcp: tuple[float, float, float] | None = None,
            wpr: tuple[float, float, float] | None = None) -> ProgramResult:
    """The program that sets ``frame`` (UFk, UTk, UFk@g) to ``pose`` (a
    measured user frame in robot world), or for UTk to ``tcp`` (a solved
    TCP, flange coordinates) with the tool's ``wpr`` (default 0, 0, 0, the
    faceplate's axes). ``pr``: the register, else an unused one of
    ``posreg``. ``out``: where it will be written (its name is the
    program's). Read back through the TP reader (``tp``) before it is returned."""
    kind, number, g = parse_frame(frame, group)
    comment = check_comment(comment)
    warnings: list[str] = []
    if kind == "UTOOL":
        if tcp is None:
            raise UcsioError(f"{frame}: a tool frame needs a solution whose TCP was solved "
                             "(`ucsio solve --tcp solve`); this one's TCP was given, so it holds "
                             "no tool to write")
        w, p, r = wpr if wpr is not None else (0.0, 0.0, 0.0)
        if wpr is None:
            warnings.append(f"{frame}: W, P, R written as 0 (the faceplate's axes); --wpr W,P,R "
                            "gives the tool's orientation")
        pose = Pose.from_wpr(tcp[0], tcp[1], tcp[2], w, p, r)
    elif wpr is not None:
        raise UcsioError("--wpr goes with a tool frame (UTk); a user frame's W, P, R are the "
                         "solution's")
    if pr is None:
        if posreg is None:
            raise UcsioError("which position register? --pr N, or --posreg posreg.va to take one "
                             "it shows unused")
        pr, pr_from = unused_register(posreg, g), os.fspath(posreg)
    else:
        if not 1 <= pr <= 9999:
            raise UcsioError(f"--pr {pr}: a position register number is 1 or more")
        if posreg is not None:
            check_register(posreg, g, pr)
        pr_from = "--pr"
    name = program_name(out, kind, number, g)
    text = make_program(pose, kind, number, g, pr, name=name, comment=comment)
    short = ("UF" if kind == "UFRAME" else "UT") + str(number) + (f"@{g}" if g != 1 else "")
    values = _read_back(text, name, short, pose)
    return ProgramResult(text=text, name=name, frame=short, type=kind, number=number, group=g,
                         pr=pr, pr_from=pr_from, comment=comment, values=values, pose=pose,
                         warnings=warnings, written=None)


def _read_back(text: str, name: str, short: str, pose: Pose) -> dict[str, float]:
    """The frame as ucsio's TP grammar reads the program: it must give
    ``pose`` within 0.001 mm and 0.001 deg (else an internal error)."""
    from . import tp
    try:
        cf = tp.parse(Document(text.encode("ascii"), f"{name}.LS"), full=True)
    except UcsioError as exc:      # the reader refuses a value (a REAL out of range)
        raise cannot_hold(f"{short}: {exc.message}") from None
    found = [f for f in cf.frames if f.name == short]
    if len(found) == 1:
        refuse_flagged_values(cf, found[0], "xyzwpr", positioned=False)
    if len(found) != 1 or not reads_back(found[0], pose):
        got = found[0].pose.as_dict() if found and found[0].pose else None
        raise UcsioError(f"internal error: the program reads back as {got}, not "
                         f"{pose.as_dict()}")
    f = found[0]
    return {k: f.info[k] if k in "wpr" else getattr(f.pose, k) for k in "xyzwpr"}


def save(result: ProgramResult, path: str) -> str:
    """Write the program atomically (``files.atomic_write``)."""
    from ...files import atomic_write, write_target
    target = write_target(path)
    written, _ = atomic_write(target, result.data)
    result.written = written
    return written


def posreg_beside(path: str) -> str | None:
    """A posreg.va (any case) in the folder of ``path``: where a backup keeps
    the registers a program may take one of."""
    folder = os.path.dirname(os.path.abspath(path))
    try:
        names = sorted(n for n in os.listdir(folder) if n.casefold() == "posreg.va")
    except OSError:
        return None
    return os.path.join(folder, names[0]) if names else None


def write_beside(pose: Pose, frame, folder: str, *, pr: int | None = None,
                 posreg: str | None = None) -> ProgramResult:
    """The program that sets ``frame`` (a frame of a listing) to ``pose``,
    written into ``folder`` as SET_UF1.LS (the program's name): what ``batch
    --patch-dir`` writes beside the listing's reviewed copy. The register:
    ``pr``, else an unused one of ``posreg`` (default: the posreg.va beside
    the listing). The frame's comment is kept where the pendant can hold it."""
    try:
        comment = check_comment(frame.label)
    except UcsioError:
        comment = None
    if pr is None and posreg is None:
        posreg = posreg_beside(frame.file)
        if posreg is None:
            raise UcsioError(f"{frame.name}: no TP program written: no posreg.va beside "
                             f"{os.path.basename(frame.file)} to take an unused register from; "
                             "give pr = N or posreg = \"FILE\" in the entry")
    result = program(pose, frame.name, pr=pr, posreg=posreg, comment=comment)
    save(result, os.path.join(folder, f"{result.name}.LS"))
    return result

