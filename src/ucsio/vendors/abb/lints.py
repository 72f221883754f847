"""ABB RAPID's lint codes: what ``check`` can report on its files, with what
each means (docs/controllers.md: "Lint codes"). A table, imported without
the parser, so ``check --ignore`` knows every code at once."""

LINT_CODES = {
    "unnormalized-quaternion": "an orient with |sum q^2 - 1| above 1e-4: wrong positions on the controller",
    "quaternion-rounding": "info: |sum q^2 - 1| between 1e-5 and 1e-4, as RobotWare writes itself",
    "zero-quaternion": "an orient that is all zeros",
    "tool-mass": "a robot-held tool whose load mass is not above 0",
    "moving-uframe": "a work object with ufprog FALSE: the controller overwrites its uframe",
    "no-value": "info: declared without a value (given elsewhere); listed, not patchable",
    "incomplete": "an editor placeholder (<EXP> ...) in frame data; not patchable",
    "not-literal": "info: frame data computed from other names; listed without numbers",
    "bad-shape": "frame data with the wrong number of components",
    "array-size": "an array value whose element count differs from its declared size",
    "long-name": "an identifier longer than RAPID's 32 characters",
    "duplicate": "a name declared twice in one module",
}
