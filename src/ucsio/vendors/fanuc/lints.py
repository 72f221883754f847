"""FANUC's lint codes: what ``check`` can report on its files, with what
each means (docs/controllers.md: "Lint codes"). A table, imported without
the parser, so ``check --ignore`` knows every code at once."""

LINT_CODES = {
    "not-a-frame-array": "a $MNUFRAME/$MNUTOOL record that is not ARRAY[groups,frames] OF POSITION",
    "group-mismatch": "a frame whose Group: line is not the group of its index [g,n]",
    "out-of-range": "a frame value the controller does not hold: W, P or R outside [-180, 180], "
                    "or a translation of 1 km or more",
    "unread-frame-set": "a program's UFRAME/UTOOL assignment in a form ucsio does not read",
    "label-source": "info: frame.dg or FRAMEVAR.VA beside a sysframe.va could not be read; "
                    "frames listed without their comments",
    "after-end": "info: text after a program's /END on its line",
    "unread-line": "info: a program's /MN line that is no numbered statement, kept as it is",
}
