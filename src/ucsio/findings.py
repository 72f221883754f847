"""What ``check`` found, as one list, and that list in each output format.

A Finding is one thing ``check`` reports: a lint (its code from
``LINT_CODES``), a failed round trip, or a file that could not be read
(``FILE_CODES``: ``syntax-error`` where the error names a line, else
``unreadable``). ``collect`` makes the list from check's results and
errors; ``render`` writes it in one of ruff's formats that CI systems and
editors read:

- ``concise``: ``file:line:col: severity: code: message``, one a line (the
  lines ``full`` prints under each file);
- ``json-lines``: one JSON object a line, ``Finding.as_dict`` and its
  ``fingerprint``;
- ``github``: GitHub Actions workflow commands (``::warning file=…::…``);
- ``gitlab``: a GitLab Code Quality report (a JSON array);
- ``sarif``: a SARIF 2.1.0 log.

(``full`` and ``json``, check's table and its JSON, go file by file and are
written by the command itself.)

A finding about a whole file (unreadable, a failed round trip) has no
position: ``line`` and ``col`` are None in JSON lines, and the formats that
need a position put it at 1:1, the file's start (as ruff reports a file it
cannot read).
"""
from __future__ import annotations

import os
import sys

from .parsing import regex
from .values import Value

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Iterable, TextIO

#: Every value of ``check --output-format``, ruff's names; ``full`` is the default.
FORMATS = ("full", "concise", "json", "json-lines", "github", "gitlab", "sarif")

#: Each format's word for each severity. A warning or an error fails the
#: check; an info does not.
LEVELS = {
    "github": {"error": "error", "warning": "warning", "info": "notice"},
    "gitlab": {"error": "blocker", "warning": "major", "info": "info"},
    "sarif": {"error": "error", "warning": "warning", "info": "note"},
}


class Finding(Value):
    """One finding of ``check``: ``file`` as check shows it, a 1-based
    ``line`` and ``col`` (in characters) or None for the whole file, the
    ``code``, ``severity`` (``error``, ``warning`` or ``info``) and
    ``message``."""

    __slots__ = ("file", "line", "col", "code", "severity", "message")

    def __init__(self, file: str, line: int | None, col: int | None, code: str,
                 severity: str, message: str):
        self.file, self.line, self.col = file, line, col
        self.code, self.severity, self.message = code, severity, message

    def as_dict(self) -> dict:
        return {"file": self.file, "line": self.line, "col": self.col, "code": self.code,
                "severity": self.severity, "message": self.message}

    @property
    def position(self) -> tuple[int, int]:
        """(line, col), the file's start for a finding about the whole file."""
        return (self.line, self.col or 1) if self.line is not None else (1, 1)


def error_code(exc) -> str:
    """A file that could not be read: ``syntax-error`` where the error names a
    place in it, ``unreadable`` where it could not be read at all."""
    return "syntax-error" if exc.line is not None else "unreadable"


ROUND_TRIP_MESSAGE = ("round trip failed: the bytes ucsio would write for the unedited file are "
                      "not the file's, or a frame number's span does not hold that number")


def collect(results: Iterable[dict], errors: Iterable) -> list[Finding]:
    """``check_parsed`` results and the files not read -> findings, file by
    file in check's order (the files read, then the rest)."""
    out = []
    for r in results:
        if not r["round_trip"]:
            out.append(Finding(r["file"], None, None, "round-trip", "error", ROUND_TRIP_MESSAGE))
        for l in r["lints"]:
            out.append(Finding(r["file"], l["line"], l["col"], l["code"], l["severity"],
                               l["message"]))
    for e in errors:
        out.append(Finding(str(e.file), e.line, e.col if e.line is not None else None,
                           error_code(e), "error", e.message))
    return out


# -- paths and fingerprints -----------------------------------------------------------

def relative_path(name: str) -> str:
    """A finding's file relative to the current folder, with '/' (what CI
    systems match against the repository); a member of an archive as
    ``ARCHIVE.zip!member`` with the archive's path made relative."""
    i = name.lower().find(".zip!")
    archive, member = (name[:i + 4], name[i + 4:]) if i >= 0 else (name, "")
    if archive != "-":
        try:
            archive = os.path.relpath(archive)
        except ValueError:              # another drive (Windows): keep it absolute
            archive = os.path.abspath(archive)
    return archive.replace(os.sep, "/") + member


# "(first at line 12)", "(lines 3 and 9)": where another line is named, the
# fingerprint must not change when lines are added above it.
_LINE_REFERENCE = regex.lazy(r"\b(?P<word>lines?) \d+(?P<more>(?: and \d+)?)")


def fingerprints(findings: list[Finding]) -> list[str]:
    """A fingerprint per finding that stays the same when lines are added or
    removed elsewhere in the file: a hash of the path relative to the current
    folder, the code and the message (which names the frame or declaration),
    with line numbers in the message masked, and which of equal ones it is
    (the first, the second, ...). It changes when the file is renamed, or the
    finding's frame or message changes."""
    import hashlib
    seen: dict[tuple, int] = {}
    out = []
    for f in findings:
        message = _LINE_REFERENCE.sub(lambda m: m.group("word") + " #"
                                      + (" and #" if m.group("more") else ""), f.message)
        key = (relative_path(f.file), f.code, message)
        n = seen.get(key, 0)
        seen[key] = n + 1
        text = "\0".join((*key, str(n)))
        out.append(hashlib.sha256(text.encode("utf-8", "surrogateescape")).hexdigest()[:32])
    return out


# -- the formats ----------------------------------------------------------------------

def render(fmt: str, findings: list[Finding], stream: TextIO | None = None) -> None:
    """``findings`` in ``fmt`` (any of FORMATS but ``full`` and ``json``) on
    ``stream`` (stdout)."""
    stream = stream or sys.stdout
    _RENDERERS[fmt](findings, stream)


def _one_line(text: str) -> str:
    return " ".join(text.splitlines()) if ("\n" in text or "\r" in text) else text


def concise_line(f: Finding, stream=None) -> str:
    """``file:line:col: severity: code: message``, as ``full`` prints a lint."""
    from .output import paint
    line, col = f.position
    sev = paint(f.severity, "info" if f.severity == "info" else "fail", stream)
    return f"{f.file}:{line}:{col}: {sev}: {f.code}: {_one_line(f.message)}"


def _concise(findings, stream) -> None:
    for f in findings:
        stream.write(concise_line(f, stream) + "\n")


def json_lines(findings: list[Finding]) -> list[dict]:
    """The objects ``json-lines`` prints, one a finding: ``as_dict`` and its
    ``fingerprint`` (``api.check(...).findings`` too)."""
    return [{**f.as_dict(), "fingerprint": fp} for f, fp in zip(findings, fingerprints(findings))]


def _json_lines(findings, stream) -> None:
    import json
    for line in json_lines(findings):
        stream.write(json.dumps(line, ensure_ascii=False) + "\n")


def github_escape_data(text: str) -> str:
    """A workflow command's message: '%', CR and LF percent-encoded (the
    runner decodes exactly these)."""
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def github_escape_property(text: str) -> str:
    """A workflow command's property value: also ':' and ',', which would
    end the properties or the value."""
    return github_escape_data(text).replace(":", "%3A").replace(",", "%2C")


def _github(findings, stream) -> None:
    levels = LEVELS["github"]
    for f in findings:
        line, col = f.position
        props = ",".join(f"{k}={github_escape_property(str(v))}" for k, v in (
            ("file", relative_path(f.file)), ("line", line), ("col", col), ("title", f.code)))
        stream.write(f"::{levels[f.severity]} {props}::{github_escape_data(f.message)}\n")


def _gitlab(findings, stream) -> None:
    from .output import emit_json
    levels = LEVELS["gitlab"]
    report = []
    for f, fp in zip(findings, fingerprints(findings)):
        line, col = f.position
        at = {"line": line, "column": col}
        report.append({"description": f"{f.code}: {f.message}", "check_name": f.code,
                       "fingerprint": fp, "severity": levels[f.severity],
                       "location": {"path": relative_path(f.file),
                                    "positions": {"begin": at, "end": at}}})
    emit_json(report, stream, document=False)


def code_severity(code: str) -> str:
    """The severity a code usually has (a finding carries its own: a KUKA
    ``missing-component`` is an info outside TOOL_DATA and BASE_DATA)."""
    from .parsing.controller import FILE_CODES, LINT_CODES
    if code in FILE_CODES:
        return "error"
    return "info" if LINT_CODES.get(code, "").startswith("info:") else "warning"


def all_codes() -> dict[str, str]:
    """Every code check reports, with what it means."""
    from .parsing.controller import FILE_CODES, LINT_CODES
    return {**LINT_CODES, **FILE_CODES}


def _meaning(text: str) -> str:
    head, sep, rest = text.partition(": ")
    return rest if sep and head in ("info", "error") else text


SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"


def sarif_log(findings: list[Finding]) -> dict:
    """The SARIF 2.1.0 log: one run, every code ucsio reports as a rule,
    each finding a result whose location is relative to the current folder
    (``%SRCROOT%``); columns count characters (Unicode code points)."""
    from urllib.parse import quote
    from . import __version__
    levels = LEVELS["sarif"]
    codes = all_codes()
    index = {code: i for i, code in enumerate(codes)}
    rules = [{"id": code, "shortDescription": {"text": _meaning(meaning)},
              "defaultConfiguration": {"level": levels[code_severity(code)]}}
             for code, meaning in codes.items()]
    results = []
    for f, fp in zip(findings, fingerprints(findings)):
        line, col = f.position
        uri = quote(relative_path(f.file), safe="/!$&'()*+,;=@")
        results.append({
            "ruleId": f.code, "ruleIndex": index[f.code], "level": levels[f.severity],
            "message": {"text": f.message},
            "locations": [{"physicalLocation": {
                "artifactLocation": {"uri": uri, "uriBaseId": "%SRCROOT%"},
                "region": {"startLine": line, "startColumn": col}}}],
            "partialFingerprints": {"ucsioFingerprint/v1": fp}})
    root = os.getcwd().replace(os.sep, "/")
    root_uri = "file://" + ("" if root.startswith("/") else "/") + quote(root.rstrip("/") + "/", safe="/:")
    return {"$schema": SARIF_SCHEMA, "version": "2.1.0", "runs": [{
        "tool": {"driver": {"name": "ucsio", "version": __version__, "rules": rules}},
        "originalUriBaseIds": {"%SRCROOT%": {"uri": root_uri}},
        "columnKind": "unicodeCodePoints",
        "results": results}]}


def _sarif(findings, stream) -> None:
    from .output import emit_json
    emit_json(sarif_log(findings), stream, document=False)


_RENDERERS = {"concise": _concise, "json-lines": _json_lines, "github": _github,
              "gitlab": _gitlab, "sarif": _sarif}
