"""Universal Robots' lint codes: what ``check`` can report on its files,
with what each means (docs/controllers.md: "Lint codes"). A table, imported
without the reader, so ``check --ignore`` knows every code at once."""

LINT_CODES = {
    "plane-points": "a Universal Robots plane feature whose frame (its firstPoint) is not the "
                    "3-point construction of its taught points, or whose taught points are "
                    "collinear",
    "gzip-stream": "info: a Universal Robots installation whose gzip stream this Python's zlib "
                   "does not reproduce at level 6 (another deflater or zlib): read, never written",
    "unread-feature": "info: a Universal Robots feature of a kind ucsio does not read (a line, "
                      "GeomLineNode): not listed, never patched",
}
