"""Parse every byte with the grammar, prove the byte-exact round trip, and lint
(unnormalised quaternions, robot-held tools without mass, moving user frames,
KUKA labels and references). Every finding names its code; --ignore CODE,...
silences codes (docs/controllers.md lists them). Exit 1 when there is any
warning or a failed round trip; an "info" (legal code worth knowing, such as a
PERS whose value another module gives) does not fail the check.

FILE may be a controller file, a backup folder (every .mod .modx .sys .sysx
.prg .dat .va .dg .ls .cnd .jbi below it) or a .zip archive (members named
ARCHIVE.zip!path). A file that cannot be read (an encrypted module, a syntax
error) is listed with its error and every other file is still checked; exit 2
at the end. A FANUC backup's binary files (.tp .sv .vr) are listed as not
read (full and json), which is no finding.

--output-format FORMAT (ruff's names) prints the findings for a person or a
CI system: full (the default: each file, its findings, a total), concise
(file:line:col: severity: code: message, for editors' problem matchers),
json (= --json), json-lines, github (workflow commands: annotations on a
pull request), gitlab (a Code Quality report) or sarif (SARIF 2.1.0, for
code scanning). Every format lists lints, failed round trips and the files
not read (codes syntax-error, unreadable, round-trip); the exit status is
the same in all."""
from __future__ import annotations

from ..output import emit_json


def add_arguments(p) -> None:
    p.add_argument("files", nargs="+", metavar="FILE",
                   help="RAPID module, KRL .dat file, FANUC .va/.ls/.dg file, Yaskawa "
                        ".CND/.JBI/.DAT file, backup folder or .zip archive")
    p.add_argument("--ignore", action="append", default=[], metavar="CODE,...",
                   help="silence these lint codes (comma-separated, repeatable)")
    from ..findings import FORMATS
    p.add_argument("--output-format", choices=FORMATS, default=None, metavar="FORMAT",
                   help="how findings are printed: " + ", ".join(FORMATS)
                   + " (default full; --json is --output-format json)")


def round_trip(cf) -> bool:
    """What a patch relies on: the bytes ucsio writes for the unedited
    document are the file's bytes, and every frame number's span holds
    exactly that number, so a patch replaces the number and nothing beside
    it. (Parsing the written bytes again would prove nothing more: they are
    the bytes just parsed, and the parser is a function of its input.)"""
    doc = cf.document
    if doc.to_bytes() != doc.raw:
        return False
    for f in cf.frames:
        for n in f.numbers.values():
            if doc.slice(n.span) != n.text:   # the span holds the number exactly as written
                return False
    return True


def check_parsed(cf, ignore: frozenset = frozenset()) -> dict:
    doc = cf.document
    out = {"file": cf.path, "vendor": cf.vendor,
           "encoding": doc.encoding + ("-bom" if doc.bom else ""),
           "frames": len(cf.frames), "round_trip": round_trip(cf),
           "lints": [l.as_dict() for l in cf.lints if l.code not in ignore]}
    if "kind" in cf.extra:      # FANUC: sysframe, program, posreg, listing, ...
        out["kind"] = cf.extra["kind"]
    return out


def ignored_codes(values: list[str]) -> frozenset:
    """--ignore a,b --ignore c -> {a, b, c}; an unknown code is a usage error
    with the nearest real one suggested (a typo must not silence nothing).
    A retired code is accepted with a note (it silences nothing now); a file
    that was not read or did not round-trip cannot be silenced."""
    import sys
    from ..parsing.controller import FILE_CODES, LINT_CODES, RETIRED
    from ..errors import UsageError, did_you_mean
    codes = {c.strip().lower() for v in values for c in v.split(",") if c.strip()}
    for c in sorted(codes):
        if c in FILE_CODES:
            raise UsageError(f"ucsio check: --ignore: {c!r} cannot be ignored: it is not a lint "
                             "but a file that was not checked")
        if c in RETIRED:
            print(f"ucsio check: --ignore: {c!r} is retired ({RETIRED[c]}); it silences nothing",
                  file=sys.stderr)
        elif c not in LINT_CODES:
            hint = did_you_mean(c, LINT_CODES) or " (docs/controllers.md lists the codes)"
            raise UsageError(f"ucsio check: --ignore: no lint code {c!r}{hint}")
    return frozenset(codes)


def output_format(args) -> str:
    """--json is --output-format json; given with another format it is a
    usage error (which of the two was meant cannot be guessed)."""
    fmt = getattr(args, "output_format", None)
    if args.json and fmt not in (None, "json"):
        from ..errors import UsageError
        raise UsageError(f"ucsio check: --json is --output-format json: it cannot go with "
                         f"--output-format {fmt}")
    return "json" if args.json else fmt or "full"


def check_files(files: list, ignore: frozenset = frozenset(), fmt: str = "json"):
    """(results, errors, not_read, exit status): each file read checked
    (``check_parsed``), the files that could not be read, and those listed as
    not read (a FANUC backup's binary files). With ``fmt`` full or json one
    plain file that cannot be read is raised (SPEC's single error); the
    formats CI reads list it as a finding, like any file not read."""
    from . import load_inputs
    if fmt in ("full", "json"):
        parsed, errors, not_read = load_inputs(files, full=True)
    else:
        from ..parsing.backup import load_all
        parsed, errors, not_read = load_all(files, full=True)
    results = [check_parsed(cf, ignore) for _, cf in parsed]
    bad = any(not r["round_trip"] or any(l["severity"] != "info" for l in r["lints"])
              for r in results)
    return results, errors, not_read, 2 if errors else 1 if bad else 0


def document(results: list, errors: list, not_read: list, status: int) -> dict:
    """--json's document (``api.check`` too)."""
    from ..findings import error_code
    return {"files": results,
            "errors": [{**e.as_dict(), "code": error_code(e)} for e in errors],
            "not_read": [{"file": s.name, "reason": s.reason} for s in not_read],
            "ok": status == 0}


def run(args) -> int:
    from ..output import paint
    from . import report_failures

    fmt = output_format(args)
    ignore = ignored_codes(args.ignore)
    results, errors, not_read, status = check_files(args.files, ignore, fmt)
    if fmt == "json":
        emit_json(document(results, errors, not_read, status))
        report_failures(errors)
        return status
    if fmt != "full":
        from ..findings import collect, render
        render(fmt, collect(results, errors))
        report_failures(errors)
        return status
    for r in results:
        state = paint("round trip ok", "pass") if r["round_trip"] else \
            paint("ROUND TRIP FAILED", "fail")
        vendor = r["vendor"] + (f" {r['kind']}" if r.get("kind") else "")
        print(f"{r['file']}: {vendor}, {r['encoding']}, {r['frames']} frames, {state}")
        for l in r["lints"]:
            sev = paint(l["severity"], "fail" if l["severity"] == "warning" else "info")
            print(f"{r['file']}:{l['line']}:{l['col']}: {sev}: {l['code']}: {l['message']}")
    for e in errors:    # listed with the others: an unreadable file is part of the check
        print(f"{e.file}: {paint('NOT READ', 'fail')}: {e.message}"
              + (f" (line {e.line}, col {e.col})" if e.line is not None else ""))
    for s in not_read:
        print(f"{s.name}: not read: {s.reason}")
    if len(results) + len(errors) + len(not_read) > 1:
        n_warn = sum(l["severity"] == "warning" for r in results for l in r["lints"])
        from ..parsing.backup import Foreign
        what = "listed, not read" if any(isinstance(s, Foreign) for s in not_read) else \
            "binary (not read)"
        binary = f", {len(not_read)} {what}" if not_read else ""
        print(f"{len(results) + len(errors) + len(not_read)} files: {len(results)} read, "
              f"{len(errors)} not read{binary}, "
              f"{sum(not r['round_trip'] for r in results)} round trips failed, {n_warn} warnings")
    report_failures(errors)
    return status
