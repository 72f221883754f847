"""One error type for everything a user can get wrong.

The CLI prints ``str(error)`` as one line on stderr and exits 2, so the message
always leads with ``file:line:col`` when a position is known.
"""
from __future__ import annotations


class UcsioError(Exception):
    """Bad input or usage: exit status 2, nothing written."""

    exit_code = 2

    def __init__(self, message: str, file: str | None = None,
                 line: int | None = None, col: int | None = None):
        super().__init__(message)
        self.message = message
        self.file = file
        self.line = line
        self.col = col

    def as_dict(self) -> dict:
        """SPEC's JSON error object."""
        return {"file": self.file, "line": self.line, "col": self.col, "message": self.message}

    def __str__(self) -> str:
        where = ""
        if self.file is not None:
            where = str(self.file)
            if self.line is not None:
                where += f":{self.line}"
                if self.col is not None:
                    where += f":{self.col}"
            where += ": "
        return f"{where}{self.message}"


class UsageError(UcsioError):
    """A command line that does not fit the command (unknown or mistyped
    option, options that do not go together): exit 2 like any bad input."""


class RejectedDataset(UcsioError):
    """A solution whose dataset was rejected: SPEC counts that as a failed
    gate (exit 1), not as bad input."""

    exit_code = 1


def did_you_mean(word: str, names) -> str:
    """'; did you mean 'X'?' for the real name nearest a mistyped one
    (compared case-insensitively, as RAPID and KRL names are), or ''."""
    import difflib

    names = list(dict.fromkeys(str(n) for n in names))
    folded = {n.casefold(): n for n in names}
    close = difflib.get_close_matches(str(word).casefold(), list(folded), n=1, cutoff=0.6)
    return f"; did you mean {folded[close[0]]!r}?" if close else ""


#: How deep a value may nest (aggregates, signs) before a reader refuses it:
#: a wobjdata needs 3, a KUKA LOAD_DATA 2; Python's recursion would give out
#: around 1000, with a traceback instead of a line.
MAX_NESTING = 100


class TooDeep(UcsioError):
    """Raised inside a value converter, which knows no file: callers that
    know it re-raise it with file:line:col; one that does not still gets a
    clear one-line error (exit 2), never a traceback."""

    def __init__(self, pos: int):
        super().__init__(f"value nested more than {MAX_NESTING} levels deep")
        self.pos = pos
