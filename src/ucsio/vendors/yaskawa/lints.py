"""Yaskawa's lint codes: what ``check`` can report on its files, with what
each means (docs/controllers.md: "Lint codes"). A table, imported without
the reader, so ``check --ignore`` knows every code at once."""

LINT_CODES = {
    "lf-only": "a Yaskawa UFRAME.CND with LF line endings: reported to load on the controller "
               "as empty (controllers write CRLF)",
    "group-flags": "a Yaskawa user frame whose ///GROUP (an RBCALIB.DAT's ///MGROUP, "
                   "///SGROUP) sets no flag or several: its robot is not known",
    "angle-range": "a Yaskawa frame angle rx, ry or rz outside [-180, 180]",
    "duplicate-block": "a Yaskawa //UFRAME n, //TOOL n or //RBCALIB n block that comes twice "
                       "in its file",
    "track-position": "info: a Yaskawa user frame taught with the robot at a track position "
                      "(///BASEP not zero)",
    "unknown-line": "info: a line or block of a Yaskawa condition file, job or RBCALIB.DAT "
                    "ucsio does not read, kept as it is",
    "basicfrm-parent": "a Yaskawa user frame defined on a user frame (///BASICFRM 1,19,k) "
                       "the file does not hold, or on itself through others: parent unknown",
    "npos-count": "a Yaskawa job whose ///NPOS does not count the positions that follow it",
}
