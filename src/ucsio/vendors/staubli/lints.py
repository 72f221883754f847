"""Stäubli's lint codes: what ``check`` can report on its .dtx files, with
what each means (docs/controllers.md: "Lint codes"). A table, imported
without the reader, so ``check --ignore`` knows every code at once."""

LINT_CODES = {
    "father-missing": "a Stäubli frame, tool or point whose father (fFather, fatherId) the "
                      "file does not hold: its parent is not known",
    "father-circle": "Stäubli frames or tools whose fathers go round in a circle: their "
                     "parent is not known",
    "father-kind": "a Stäubli frame whose father is a tool, or a tool whose father is a frame "
                   "(VAL3 hangs frames from world or frames, tools from the flange or tools)",
    "entry-index": "a Stäubli datum whose entry index (key, index) is outside its size or "
                   "comes twice",
}

