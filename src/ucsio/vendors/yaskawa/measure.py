"""Yaskawa's measurement program (``ucsio program --measure``): a job
(.JBI, CRLF) that moves the reflector to each planned point of user frame k
with tool t::

    //POS
    ///NPOS 2n,0,0,0,0,0
    ///TOOL t
    ///USER k
    ///POSTYPE USER
    ///RECTAN
    ///RCONF 0,...
    C00000=x,y,z,rx,ry,rz          the measured points, in the plan's order
    C0000n=...                     their approach (and retract) positions
    //INST
    ...
    'P1 UP
    MOVL C0000n V=100.0
    'P1
    MOVL C00000 V=100.0
    PAUSE                          (or TIMER T=2.00)
    MOVL C0000n V=100.0

V is mm/s as the controller writes it (one decimal); x y z to 0.001 mm,
rx ry rz to 0.0001 deg. A job's positions carry no names: the comment line
directly before a move names the position it moves to (``job.names_by_comment``),
so ``solve --robot`` pairs C00000 ... with the plan's points by name (and
still by C00000 or C0).
"""
from __future__ import annotations

import re

from ...errors import UcsioError
from ..common.measure import MeasureProgram, check_read_back, header
from .program import COMMENT_MAX, RCONF, _comment, _date, _row

_NAME = re.compile(r"\s*U([FT])\s*([0-9]{1,3})\s*")
UP = " UP"          # the approach position's name: the point's and this, as FANUC's


def measurement_program(frame, tool, targets, settings) -> MeasureProgram:
    """The job for ``targets`` (``common.measure.Target``) in user frame
    ``frame`` with ``tool`` (a tool of TOOL.CND: a Yaskawa job has no
    flange tool of its own, so --tcp is refused)."""
    if tool is None:
        raise UcsioError("a Yaskawa job's positions are those of a tool of TOOL.CND (tool 0 is "
                         "one too, not the flange): give --tool TOOL.CND:UTk, not --tcp")
    uf, ut = _number(frame.name, "F", "--frame"), _number(tool.name, "T", "--tool")
    if not 0.1 <= settings.speed <= 9999.9:
        raise UcsioError(f"--speed {settings.speed:g}: MOVL's V is 0.1...9999.9 mm/s")
    n = len(targets)
    rows = [f"C{k:05d}={_row((*t.at.t, *t.at.wpr))}" for k, t in enumerate(targets)]
    rows += [f"C{n + k:05d}={_row((*t.above.t, *t.above.wpr))}" for k, t in enumerate(targets)]
    speed = f"V={settings.speed:.1f}"
    stop = "PAUSE" if settings.dwell is None else f"TIMER T={settings.dwell:.2f}"
    inst = ["NOP"] + [_comment(line) for line in header(settings, frame.name, tool.name)]
    for k, t in enumerate(targets):       # a comment right before a move names its position
        inst += [_comment(t.name + UP), f"MOVL C{n + k:05d} {speed}", _comment(t.name),
                 f"MOVL C{k:05d} {speed}", stop, f"MOVL C{n + k:05d} {speed}"]
    group = frame.info.get("group") or 1
    lines = ["/JOB", f"//NAME {settings.name}", "//POS", f"///NPOS {2 * n},0,0,0,0,0",
             f"///TOOL {ut}", f"///USER {uf}", "///POSTYPE USER", "///RECTAN",
             f"///RCONF {RCONF}", *rows, "//INST", f"///DATE {_date()}", "///ATTR SC,RW",
             f"///FRAME USER {uf}", f"///GROUP1 RB{group}", *inst, "END"]
    text = "\r\n".join(lines) + "\r\n"
    unnamed = _read_back(text, settings.name, targets)
    return MeasureProgram(text=text, name=settings.name, warnings=unnamed,
                          vendor="yaskawa", frame=frame.name, tool=tool.name,
                          points=[t.name for t in targets],
                          positions=[f"C{k:05d}" for k in range(n)])


def _read_back(text: str, name: str, targets) -> list[str]:
    """The positions as ucsio's job reader reads them: the ones meant; a
    warning for each point its comment does not name (solve pairs it by its
    C number only)."""
    from ...parsing.document import Document
    from .job import names_by_comment, positions
    n = len(targets)
    wanted = [(f"C{k:05d}", t.at) for k, t in enumerate(targets)]
    wanted += [(f"C{n + k:05d}", t.above) for k, t in enumerate(targets)]
    doc = Document(text.encode("ascii"), f"{name}.JBI")
    got = [(p.name, p.xyzabc()) for p in positions(doc)]
    check_read_back(f"{name}.JBI", wanted, got)
    named = names_by_comment(doc)
    return [f"point {t.name!r}: a job's comment holds printable ASCII, up to {COMMENT_MAX} "
            f"characters, and names one position: it reads {named.get(c, _comment(t.name)[1:])!r}, "
            f"so solve pairs it as {c} (name the tracker's point so, or pair with --map)"
            for c, t in ((f"C{k:05d}", t) for k, t in enumerate(targets))
            if named.get(c) != t.name]


def _number(name: str, kind: str, option: str) -> int:
    m = _NAME.fullmatch(name)
    if m is None or m.group(1) != kind:
        what = "a user frame UFk" if kind == "F" else "a tool UTk"
        raise UcsioError(f"{option} {name}: the measurement job needs {what}")
    return int(m.group(2))
