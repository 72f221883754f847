"""KUKA KRL's lint codes: what ``check`` can report on its files, with what
each means (docs/controllers.md: "Lint codes"). A table, imported without
the parser, so ``check --ignore`` knows every code at once."""

LINT_CODES = {
    "bad-label": "a TOOL_NAME/BASE_NAME entry that is not a string",
    "bad-type": "a TOOL_TYPE/BASE_TYPE entry that is not an #ENUM value",
    "unknown-type": "a TOOL_TYPE/BASE_TYPE value ucsio does not know",
    "index-out-of-range": "a FRAME array element outside its declared size",
    "duplicate-frame": "a frame initialised twice",
    "duplicate-label": "two tools or two bases with the same label",
    "not-a-frame": "a FRAME variable whose value is not {X ..,Y ..,Z ..,A ..,B ..,C ..}",
    "duplicate-component": "a FRAME component given twice",
    "unknown-component": "a FRAME component other than X Y Z A B C",
    "not-a-number": "a FRAME component that is not a number",
    "missing-component": "a FRAME value missing one of X Y Z A B C",
    "label-too-long": "a TOOL_NAME/BASE_NAME label longer than the controller allows",
    "label-quote": "a label containing a double quote",
    "base-not-world": "a base on an external kinematic: not relative to world",
}
