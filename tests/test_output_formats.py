"""check --output-format (issue 21, points 1 and 3): the formats CI systems
and editors read. One backup with every kind of finding (warnings, infos,
a syntax error, an encrypted module, a missing file, an archive, --ignore)
is checked in every format; each format is read back the way its reader
reads it and must say the same as the others: SARIF against the SARIF 2.1.0
JSON schema, GitHub's workflow commands with the runner's own parsing
rules, GitLab's Code Quality fields, and the README's VS Code problem
matcher against the concise lines."""
from __future__ import annotations

import contextlib
import io
import json
import os
import re
import shutil
import subprocess
import sys
import zipfile
from urllib.parse import unquote

import pytest

from conftest import FIXTURES, ROOT

SRC = str(ROOT / "src")
FORMATS = ("full", "concise", "json", "json-lines", "github", "gitlab", "sarif")

# A KUKA $config.dat whose name holds the characters GitHub's properties
# must encode (',' ':' '%'), with a label holding them too: a finding that
# names other lines (duplicate-frame), a label given twice (duplicate-label).
ODD_NAME = "cell,1:A%25.dat"
ODD_DAT = ("DEFDAT $config PUBLIC\r\nDECL FRAME BASE_DATA[32]\r\n"
           "BASE_DATA[1]={X 1,Y 0,Z 0,A 0,B 0,C 0}\r\nBASE_DATA[1]={X 2,Y 0,Z 0,A 0,B 0,C 0}\r\n"
           "BASE_DATA[2]={X 2,Y 0,Z 0,A 0,B 0,C 0}\r\nBASE_DATA[3]={X 3,Y 0,Z 0,A 0,B 0,C 0}\r\n"
           "DECL CHAR BASE_NAME[32,24]\r\n"
           'BASE_NAME[2,]="a%0A:b,c"\r\nBASE_NAME[3,]="a%0A:b,c"\r\nENDDAT\r\n')


def main(args, cwd) -> tuple[int, str, str]:
    """ucsio in this process (many runs; the output is the command's own)."""
    from ucsio.cli import main as ucsio_main
    out, err = io.StringIO(), io.StringIO()
    here = os.getcwd()
    os.chdir(cwd)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = ucsio_main([str(a) for a in args])
    finally:
        os.chdir(here)
    return code, out.getvalue(), err.getvalue()


def run(*args, cwd):
    env = dict(os.environ, PYTHONPATH=SRC)
    env.pop("NO_COLOR", None)
    return subprocess.run([sys.executable, "-m", "ucsio", *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, env=env)


@pytest.fixture(scope="module")
def cell(tmp_path_factory):
    """A working folder with a backup folder (good, lint, info, syntax error,
    encrypted), an archive, and a file with an awkward name."""
    root = tmp_path_factory.mktemp("cell")
    bk = root / "R01 backup"                    # a space: SARIF's URI encodes it
    (bk / "RAPID").mkdir(parents=True)
    (bk / "KRC").mkdir()
    shutil.copy(FIXTURES / "abb" / "bom.mod", bk / "RAPID" / "Good.mod")
    shutil.copy(FIXTURES / "abb" / "variants.mod", bk / "RAPID" / "Variants.mod")    # infos
    shutil.copy(FIXTURES / "abb" / "bad" / "badnumber.mod", bk / "RAPID" / "Broken.mod")
    shutil.copy(FIXTURES / "abb" / "encrypted.mod", bk / "RAPID" / "Secret.mod")
    shutil.copy(FIXTURES / "kuka" / "cell_config.dat", bk / "KRC" / "$config.dat")  # warnings
    with zipfile.ZipFile(root / "R02.zip", "w") as zf:
        zf.write(FIXTURES / "kuka" / "cell_config.dat", "KRC/R1/System/$config.dat")
        zf.write(FIXTURES / "kuka" / "variants.dat", "KRC/R1/Program/variants.dat")
    (root / ODD_NAME).write_bytes(ODD_DAT.encode())
    return root


INPUTS = ["R01 backup", "R02.zip", ODD_NAME, "missing.mod", "--ignore", "label-too-long"]


@pytest.fixture(scope="module")
def outputs(cell):
    """Every format's (exit code, stdout, stderr) on the same inputs."""
    return {fmt: main(["check", *INPUTS, "--output-format", fmt], cell) for fmt in FORMATS}


@pytest.fixture(scope="module")
def reference(outputs):
    """The findings as JSON lines say them: the list every format must show."""
    code, out, _ = outputs["json-lines"]
    return [json.loads(line) for line in out.splitlines()]


def test_every_format_exits_as_check_does(outputs):
    codes = {fmt: code for fmt, (code, _, _) in outputs.items()}
    assert set(codes.values()) == {2}, codes                  # files not read: exit 2
    for fmt, (_, out, err) in outputs.items():
        assert "Broken.mod:2:30: bad number '1.2.3'" in err    # and each on stderr, as ever
        assert "could not be read (exit 2)" in err


def test_the_findings_cover_every_kind(reference):
    codes = {f["code"] for f in reference}
    assert {"syntax-error", "unreadable", "duplicate-frame", "duplicate-label", "no-value",
            "base-not-world", "missing-component"} <= codes
    assert "label-too-long" not in codes                      # --ignore holds in every format
    files = {f["file"] for f in reference}
    assert "R02.zip!KRC/R1/System/$config.dat" in files       # archive members
    assert os.path.join("R01 backup", "KRC", "$config.dat") in files    # folders
    assert "missing.mod" in files and ODD_NAME in files
    unread = {f["file"]: f for f in reference if f["code"] == "unreadable"}
    assert unread["missing.mod"]["line"] is None and unread["missing.mod"]["severity"] == "error"
    syntax = next(f for f in reference if f["code"] == "syntax-error")
    assert (syntax["line"], syntax["col"]) == (2, 30)


def expected(reference, levels=None):
    """(path, line, col, code, level) of each finding, in order; a finding
    about a whole file at 1:1."""
    return [(f["file"], f["line"] or 1, f["col"] or 1, f["code"],
             (levels or {}).get(f["severity"], f["severity"])) for f in reference]


def test_json_is_todays_json_with_a_code_on_each_error(outputs, cell):
    code, out, _ = outputs["json"]
    doc = json.loads(out)
    assert set(doc) == {"schema_version", "files", "errors", "not_read", "ok"} and doc["ok"] is False
    assert doc["not_read"] == []           # a FANUC backup's binary files, listed
    assert {e["code"] for e in doc["errors"]} == {"syntax-error", "unreadable"}
    assert all({"file", "line", "col", "message", "code"} <= set(e) for e in doc["errors"])
    assert main(["check", *INPUTS, "--json"], cell) == outputs["json"]
    assert main(["check", *INPUTS, "--json", "--output-format", "json"], cell) == outputs["json"]


def test_full_is_the_default(outputs, cell):
    assert main(["check", *INPUTS], cell) == outputs["full"]


def test_json_with_another_format_is_a_usage_error(cell):
    code, out, err = main(["check", ODD_NAME, "--json", "--output-format", "sarif"], cell)
    assert code == 2 and "--json is --output-format json" in err
    assert json.loads(out)["error"]["message"].endswith("--output-format sarif")
    code, out, err = main(["check", ODD_NAME, "--output-format", "sarf"], cell)
    assert code == 2 and "did you mean 'sarif'" in err


def test_concise_lines(outputs, reference):
    code, out, _ = outputs["concise"]
    got = []
    for line in out.splitlines():
        m = re.fullmatch(r"(.+?):(\d+):(\d+): (error|warning|info): ([a-z-]+): (.*)", line)
        assert m, line
        got.append((m[1], int(m[2]), int(m[3]), m[5], m[4]))
    assert got == expected(reference)


def test_full_shows_the_same_findings(outputs, reference):
    """full's lint lines are the concise lines; its files not read are its
    NOT READ lines."""
    _, full, _ = outputs["full"]
    _, concise, _ = outputs["concise"]
    lints = [line for line in concise.splitlines()
             if not re.search(r": error: (syntax-error|unreadable): ", line)]
    assert lints == [line for line in full.splitlines() if line in set(lints)]
    for f in reference:
        if f["code"] in ("syntax-error", "unreadable"):
            assert f"{f['file']}: NOT READ: {f['message']}" in full


# -- GitHub ----------------------------------------------------------------------------

def runner_parse(line: str):
    """A workflow command as GitHub's runner reads it (actions/runner,
    src/Runner.Common/ActionCommand.cs, TryParseV2): after the leading '::',
    the command info runs to the next '::'; its first space ends the command
    name; the properties are split on ',' and each on its first '='; the
    values and the data are unescaped by plain replacement, '%25' last."""
    line = line.lstrip()
    if not line.startswith("::"):
        return None
    end = line.find("::", 2)
    if end < 0:
        return None
    info = line[2:end]
    name, _, props = info.partition(" ")
    properties = {}
    for prop in filter(None, props.strip().split(",")):
        pair = [p for p in prop.split("=", 1) if p]
        if len(pair) == 2:
            properties[pair[0]] = unescape(pair[1], ("%0D", "\r"), ("%0A", "\n"), ("%3A", ":"),
                                           ("%2C", ","))
    data = unescape(line[end + 2:], ("%0D", "\r"), ("%0A", "\n"))
    return name, properties, data


def unescape(text, *pairs):
    for code, char in (*pairs, ("%25", "%")):
        text = text.replace(code, char)
    return text


def test_github_commands_read_back_exactly(outputs, reference):
    code, out, _ = outputs["github"]
    lines = out.split("\n")
    assert lines[-1] == "" and len(lines) - 1 == len(reference)
    levels = {"error": "error", "warning": "warning", "info": "notice"}
    for line, f in zip(lines, reference):
        name, props, data = runner_parse(line)
        assert name == levels[f["severity"]]
        assert props == {"file": f["file"].replace(os.sep, "/"), "line": str(f["line"] or 1),
                         "col": str(f["col"] or 1), "title": f["code"]}
        assert data == f["message"]
    assert any("a%0A:b,c" in f["message"] for f in reference)    # the awkward label came through


@pytest.mark.parametrize("text", ["50% of 100%", "two\r\nlines\nand\rmore", "a:b,c=d::e",
                                  "%0A%25%3A%2C", "", "::warning file=x::y"])
def test_github_escapes_round_trip_through_the_runner(text):
    from ucsio.findings import github_escape_data, github_escape_property
    line = (f"::warning file={github_escape_property(text + 'f')},"
            f"title={github_escape_property(text + 't')}::{github_escape_data(text)}")
    assert "\n" not in line and "\r" not in line
    name, props, data = runner_parse(line)
    assert (name, props, data) == ("warning", {"file": text + "f", "title": text + "t"}, text)


# -- GitLab ----------------------------------------------------------------------------

GITLAB_SEVERITIES = {"info", "minor", "major", "critical", "blocker"}


def test_gitlab_code_quality_report(outputs, reference):
    """GitLab's Code Quality report: a JSON array; each issue with
    description, check_name, fingerprint (unique), severity, location.path
    (relative) and the line where the issue begins."""
    code, out, _ = outputs["gitlab"]
    report = json.loads(out)
    assert isinstance(report, list) and len(report) == len(reference)
    levels = {"error": "blocker", "warning": "major", "info": "info"}
    got = []
    for issue in report:
        assert isinstance(issue["description"], str) and issue["description"]
        assert issue["severity"] in GITLAB_SEVERITIES
        assert re.fullmatch(r"[0-9a-f]{32}", issue["fingerprint"])
        path = issue["location"]["path"]
        assert not os.path.isabs(path) and ".." not in path.split("/")
        begin = issue["location"]["positions"]["begin"]
        got.append((path, begin["line"], begin["column"], issue["check_name"], issue["severity"]))
    assert got == [(p.replace(os.sep, "/"), *rest) for p, *rest in expected(reference, levels)]
    assert len({i["fingerprint"] for i in report}) == len(report)
    assert [i["fingerprint"] for i in report] == [f["fingerprint"] for f in reference]


def fingerprints(folder, *files):
    code, out, _ = main(["check", *files, "--output-format", "gitlab"], folder)
    return {(i["check_name"], i["description"]): i for i in json.loads(out)}


def test_gitlab_fingerprints_survive_lines_added_above(tmp_path):
    dat = tmp_path / "$config.dat"
    dat.write_bytes(ODD_DAT.encode())
    before = fingerprints(tmp_path, dat.name)
    dat.write_bytes(ODD_DAT.replace("DECL FRAME", ";a comment\r\n;another\r\nDECL FRAME", 1)
                    .encode())
    after = fingerprints(tmp_path, dat.name)
    line = lambda i: i["location"]["positions"]["begin"]["line"]    # noqa: E731
    # duplicate-frame names its lines: the message changed, the fingerprint did not
    (b,) = [i for (code, _), i in before.items() if code == "duplicate-frame"]
    (a,) = [i for (code, _), i in after.items() if code == "duplicate-frame"]
    assert "(lines 3 and 4)" in b["description"] and "(lines 5 and 6)" in a["description"]
    assert line(a) == line(b) + 2 and a["fingerprint"] == b["fingerprint"]
    assert sorted(i["fingerprint"] for i in before.values()) == \
        sorted(i["fingerprint"] for i in after.values())
    # a different finding is a different fingerprint; so is the same one in another file
    dat.write_bytes(ODD_DAT.replace("a%0A:b,c", "other").encode())
    changed = fingerprints(tmp_path, dat.name)
    assert {i["fingerprint"] for i in changed.values()} != {i["fingerprint"] for i in before.values()}
    shutil.copy(dat, tmp_path / "copy.dat")
    both = json.loads(main(["check", dat.name, "copy.dat", "--output-format", "gitlab"],
                           tmp_path)[1])
    assert len({i["fingerprint"] for i in both}) == len(both) == 2 * len(changed)


def test_equal_findings_get_distinct_fingerprints():
    from ucsio.findings import Finding, fingerprints as fps
    f = Finding("a.mod", 3, 1, "duplicate", "warning", "x: declared twice in module m "
                                                         "(first at line 1)")
    g = Finding("a.mod", 9, 1, "duplicate", "warning", "x: declared twice in module m "
                                                         "(first at line 7)")
    one, two = fps([f, g])
    assert one != two and fps([g]) == [one]        # the first of its kind, wherever it is


# -- SARIF -----------------------------------------------------------------------------

@pytest.fixture(scope="module")
def sarif_schema():
    schema = json.loads((FIXTURES / "schemas" / "sarif-2.1.0.json").read_text(encoding="utf-8"))
    assert schema["$id"].endswith("/sarif-schema-2.1.0.json")
    assert schema["title"] == "Static Analysis Results Format (SARIF) Version 2.1.0 JSON Schema"
    return schema


def sarif_errors(schema, log) -> list[str]:
    from jsonschema.validators import validator_for
    validator = validator_for(schema)(schema)
    return [f"{'/'.join(map(str, e.absolute_path))}: {e.message}"
            for e in validator.iter_errors(log)]


def test_sarif_is_valid_sarif_2_1_0(outputs, sarif_schema):
    code, out, _ = outputs["sarif"]
    log = json.loads(out)
    assert sarif_errors(sarif_schema, log) == []
    # and the schema is no rubber stamp: a level SARIF does not have fails it
    bad = json.loads(out)
    bad["runs"][0]["results"][0]["level"] = "info"
    assert sarif_errors(sarif_schema, bad)


def test_sarif_results_are_the_findings(outputs, reference, cell):
    from ucsio.parsing.controller import FILE_CODES, LINT_CODES
    log = json.loads(outputs["sarif"][1])
    assert log["version"] == "2.1.0"
    (run_,) = log["runs"]
    rules = run_["tool"]["driver"]["rules"]
    assert run_["tool"]["driver"]["name"] == "ucsio"
    assert [r["id"] for r in rules] == [*LINT_CODES, *FILE_CODES]
    assert all(r["shortDescription"]["text"] for r in rules)
    assert run_["columnKind"] == "unicodeCodePoints"
    root = run_["originalUriBaseIds"]["%SRCROOT%"]["uri"]
    assert root.startswith("file:///") and unquote(root[7:]) == str(cell.resolve()) + "/"
    levels = {"error": "error", "warning": "warning", "info": "note"}
    got = []
    for r in run_["results"]:
        assert rules[r["ruleIndex"]]["id"] == r["ruleId"]
        (loc,) = r["locations"]
        art = loc["physicalLocation"]["artifactLocation"]
        assert art["uriBaseId"] == "%SRCROOT%"
        assert re.fullmatch(r"[A-Za-z0-9/!$&'()*+,;=@._~%-]+", art["uri"]), art["uri"]
        region = loc["physicalLocation"]["region"]
        got.append((unquote(art["uri"]), region["startLine"], region["startColumn"],
                    r["ruleId"], r["level"]))
        assert r["message"]["text"]
    assert got == [(p.replace(os.sep, "/"), *rest) for p, *rest in expected(reference, levels)]
    texts = [r["message"]["text"] for r in run_["results"]]
    assert texts == [f["message"] for f in reference]
    assert "R01%20backup/KRC/$config.dat" in {r["locations"][0]["physicalLocation"]
                                              ["artifactLocation"]["uri"] for r in run_["results"]}


def test_sarif_paths_are_relative_to_the_current_folder(cell, sarif_schema):
    """Run from inside the backup, the same file is named from there."""
    code, out, _ = main(["check", "KRC", "--output-format", "sarif"], cell / "R01 backup")
    log = json.loads(out)
    assert sarif_errors(sarif_schema, log) == []
    uris = {r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]
            for r in log["runs"][0]["results"]}
    assert uris == {"KRC/$config.dat"} and code == 1


def test_sarif_without_findings_is_valid_and_exits_0(cell, sarif_schema):
    code, out, _ = main(["check", "R01 backup/RAPID/Good.mod", "--output-format", "sarif"], cell)
    log = json.loads(out)
    assert code == 0 and log["runs"][0]["results"] == [] and sarif_errors(sarif_schema, log) == []


# -- one file, and the exit codes ------------------------------------------------------

@pytest.mark.parametrize("fmt", ["concise", "json-lines", "github", "gitlab", "sarif"])
def test_one_unreadable_file_is_a_finding_too(cell, fmt):
    """A single plain file that cannot be read: full and json keep SPEC's one
    error; the formats CI reads list it like any other finding."""
    code, out, err = main(["check", "R01 backup/RAPID/Broken.mod", "--output-format", fmt], cell)
    assert code == 2 and "syntax-error" in out and "Broken.mod" in out
    assert "Broken.mod:2:30: bad number '1.2.3'" in err


def test_one_unreadable_file_in_full_and_json_is_spec_s_single_error(cell):
    code, out, err = main(["check", "missing.mod", "--output-format", "json"], cell)
    assert code == 2 and json.loads(out) == {"schema_version": 1,
                                             "error": {"file": "missing.mod", "line": None,
                                                       "col": None, "message": "no such file (the controller file)"}}
    code, out, err = main(["check", "missing.mod"], cell)
    assert code == 2 and out == "" and err.count("\n") == 1


@pytest.mark.parametrize("fmt", FORMATS)
def test_exit_codes_are_the_same_in_every_format(cell, fmt):
    warn = ["R01 backup/KRC/$config.dat"]
    info = ["R01 backup/RAPID/Variants.mod"]
    assert main(["check", *warn, "--output-format", fmt], cell)[0] == 1
    assert main(["check", *info, "--output-format", fmt], cell)[0] == 0
    quiet = ["--ignore", "missing-component,label-too-long,base-not-world,duplicate-label"]
    assert main(["check", *warn, *quiet, "--output-format", fmt], cell)[0] == 0


def test_a_failed_round_trip_is_a_finding(monkeypatch, cell):
    from ucsio.commands import check
    monkeypatch.setattr(check, "round_trip", lambda cf: False)
    code, out, _ = main(["check", "R01 backup/RAPID/Good.mod", "--output-format", "json-lines"],
                        cell)
    (f,) = [json.loads(line) for line in out.splitlines()]
    assert code == 1 and f["code"] == "round-trip" and f["severity"] == "error"
    assert f["line"] is None
    code, out, _ = main(["check", "R01 backup/RAPID/Good.mod", "--output-format", "github"], cell)
    assert out.startswith("::error file=R01 backup/RAPID/Good.mod,line=1,col=1,title=round-trip::")


# -- the codes -------------------------------------------------------------------------

# Every code check has ever reported. A code keeps its meaning for ever: it may
# move from LINT_CODES to RETIRED, never disappear, and never come back as
# something else. Add new codes here; never remove one.
CODES_EVER = [
    "unnormalized-quaternion", "quaternion-rounding", "zero-quaternion", "tool-mass",
    "moving-uframe", "no-value", "incomplete", "not-literal", "bad-shape", "array-size",
    "long-name", "duplicate", "bad-label", "bad-type", "unknown-type", "index-out-of-range",
    "duplicate-frame", "duplicate-label", "not-a-frame", "duplicate-component",
    "unknown-component", "not-a-number", "missing-component", "label-too-long", "label-quote",
    "base-not-world",
    "not-a-frame-array", "group-mismatch", "out-of-range", "unread-frame-set", "label-source",
    "after-end", "unread-line",
    "lf-only", "group-flags", "angle-range", "duplicate-block", "track-position", "unknown-line",
    "npos-count", "basicfrm-parent",
    "plane-points", "gzip-stream", "unread-feature",
    "father-missing", "father-circle", "father-kind", "entry-index",
    "syntax-error", "unreadable", "round-trip",
]


def test_codes_are_never_lost_or_reused():
    from ucsio.parsing.controller import FILE_CODES, LINT_CODES, RETIRED
    known = set(LINT_CODES) | set(FILE_CODES) | set(RETIRED)
    assert set(CODES_EVER) <= known, set(CODES_EVER) - known           # none disappeared
    assert known <= set(CODES_EVER), known - set(CODES_EVER)           # new ones are listed here
    assert not set(LINT_CODES) & set(FILE_CODES)
    assert not set(RETIRED) & (set(LINT_CODES) | set(FILE_CODES))     # retired stays retired
    for code in known:
        assert re.fullmatch(r"[a-z][a-z0-9]*(-[a-z0-9]+)*", code), code


def test_every_code_is_in_the_docs_table():
    from ucsio.parsing.controller import FILE_CODES, RETIRED
    page = (ROOT / "docs" / "controllers.md").read_text(encoding="utf-8")
    section = page.split("## Lint codes", 1)[1].split("\n## ", 1)[0]
    for code in [*FILE_CODES, *RETIRED]:
        assert f"`{code}`" in section, code


def test_file_codes_cannot_be_ignored_and_retired_ones_are_accepted(monkeypatch, cell):
    code, _, err = main(["check", ODD_NAME, "--ignore", "syntax-error"], cell)
    assert code == 2 and "'syntax-error' cannot be ignored" in err
    from ucsio.parsing import controller
    monkeypatch.setitem(controller.RETIRED, "old-code", "retired in 0.0.9: example")
    code, _, err = main(["check", ODD_NAME, "--ignore", "old-code", "--output-format", "concise"],
                        cell)
    assert code == 1 and "'old-code' is retired (retired in 0.0.9: example)" in err


# -- VS Code ---------------------------------------------------------------------------

def vscode_task() -> dict:
    page = (ROOT / "docs" / "git-and-ci.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```json\n(.*?)```", page, re.S)
    (block,) = [b for b in blocks if '"problemMatcher"' in b]
    return json.loads(block)


def test_docs_problem_matcher_reads_real_concise_output(cell):
    """The docs' tasks.json is valid JSON, runs check in the concise
    format, and its problem matcher's regular expression (JavaScript syntax;
    Python reads this one alike) takes file, line, column, severity, code
    and message from every line check prints."""
    (task,) = vscode_task()["tasks"]
    assert task["command"] == "ucsio" and task["args"][:3] == ["check", "--output-format", "concise"]
    matcher = task["problemMatcher"]
    assert matcher["owner"] == "ucsio"
    pattern = matcher["pattern"]
    regexp = re.compile(pattern["regexp"])
    res = run("check", *INPUTS, "--output-format", "concise", cwd=cell)   # the real command
    assert res.returncode == 2
    ref = [json.loads(line) for line in
           run("check", *INPUTS, "--output-format", "json-lines", cwd=cell).stdout.splitlines()]
    lines = res.stdout.splitlines()
    assert len(lines) == len(ref) > 5
    for line, f in zip(lines, ref):
        m = regexp.search(line)
        assert m, line
        assert m.group(pattern["file"]) == f["file"]
        assert int(m.group(pattern["line"])) == (f["line"] or 1)
        assert int(m.group(pattern["column"])) == (f["col"] or 1)
        assert m.group(pattern["severity"]) == f["severity"]
        assert m.group(pattern["code"]) == f["code"]
        assert m.group(pattern["message"]) == f["message"]
    # and it takes nothing else: full's per-file lines and total are not problems
    full = run("check", *INPUTS, cwd=cell).stdout.splitlines()
    assert [l for l in full if regexp.search(l)] == [l for l in lines if l in full]



def test_a_tables_lines_are_its_cells_padded_one_by_one():
    """``output.table`` formats a line at once where every row has a cell
    for each column: the same text as padding cell by cell (the way it
    pads a ragged table), on random cells, widths and alignments."""
    import random

    from ucsio.output import table

    def by_cell(headers, rows, right):
        rows = [[str(c) for c in r] for r in rows]
        widths = [len(h) for h in headers]
        for r in rows:
            for i, c in enumerate(r):
                widths[i] = max(widths[i], len(c))
        def line(cells):
            return "  ".join(c.rjust(widths[i]) if i in right else c.ljust(widths[i])
                             for i, c in enumerate(cells)).rstrip()
        return "\n".join([line(headers), line(["-" * w for w in widths])]
                         + [line(r) for r in rows])

    rng = random.Random(30)
    cells = ["", "x", "{}", "{0}", "Stäubli", "-1.250", " a ", "UF1@2", None, 3.5, 12]
    for _ in range(300):
        n = rng.randint(1, 7)
        headers = [rng.choice(["name", "x", "", "{y}", "roll"]) for _ in range(n)]
        rows = [[rng.choice(cells) for _ in range(n)] for _ in range(rng.randint(0, 6))]
        right = {i for i in range(n) if rng.random() < 0.5}
        assert table(headers, rows, right) == by_cell(headers, rows, right)
