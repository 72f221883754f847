"""Every command in the README and the docs runs (issue 21 point 4; the Python
examples of docs/python-api.md: tests/test_docs.py).

Each page's ```sh blocks run in order, in one sandbox per page: a fresh
folder where `ucsio demo --out demo` has written the example cells, with
`ucsio` on PATH as this Python's. A block is one bash session started in the
sandbox (a `cd` lasts to its end); each command's exit status must be the
one its comment says (`# exit N`), else 0. Blocks that install ucsio (a
virtual environment, pip, .ci/run) are what .ci/run itself does: they are
checked for their form in tests/test_readme.py, not run here."""
from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT

PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
INSTALLS = re.compile(r"pip install|python3? -m venv|\.ci/run|py -3 ")
# the benchmarks take minutes each and print their own verdicts against their
# targets: they are run by hand (docs/speed.md), not in the suite
BENCHMARKS = re.compile(r"^python benchmarks/", re.M)


def sh_blocks(page: Path) -> list[str]:
    return re.findall(r"^```sh\n(.*?)^```", page.read_text(encoding="utf-8"), re.S | re.M)


def commands(block: str) -> list[tuple[str, int]]:
    """(command, expected exit status) for each command of a block: a line,
    with its continuation lines and a here-document's body."""
    out = []
    lines = block.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        i += 1
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        while line.endswith("\\") and i < len(lines):
            line += "\n" + lines[i]
            i += 1
        heredoc = re.search(r"<<-?\s*'?(\w+)'?", line)
        if heredoc:
            end = heredoc.group(1)
            while i < len(lines):
                line += "\n" + lines[i]
                i += 1
                if lines[i - 1].strip() == end:
                    break
        m = re.search(r"#\s*exit (\d)", line.splitlines()[0])
        out.append((line, int(m.group(1)) if m else 0))
    return out


def run_page(page: Path, sandbox: Path) -> list[tuple[str, int, int, str]]:
    """(command, expected, got, output) of every command on the page."""
    bin_dir = sandbox / ".bin"
    bin_dir.mkdir(exist_ok=True)
    shim = bin_dir / "ucsio"
    shim.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m ucsio "$@"\n')
    shim.chmod(0o755)
    env = dict(os.environ, PATH=f"{bin_dir}{os.pathsep}{os.environ.get('PATH', '')}",
               NO_COLOR="1", GIT_CONFIG_NOSYSTEM="1", HOME=str(sandbox / ".home"))
    env.pop("UCSIO_PORTABLE_REGEX", None)
    (sandbox / ".home").mkdir(exist_ok=True)
    subprocess.run(["ucsio", "demo", "--out", "demo"], cwd=sandbox, env=env, check=True,
                   capture_output=True, timeout=300)
    results = []
    for block in sh_blocks(page):
        if INSTALLS.search(block) or BENCHMARKS.search(block):
            continue
        script = []
        cmds = commands(block)
        for k, (command, _) in enumerate(cmds):
            script += [f'echo "@@start {k}"', command, 'echo "@@rc $?"']
        res = subprocess.run(["bash", "-c", "\n".join(script)], cwd=sandbox, env=env,
                             capture_output=True, text=True, timeout=900)
        parts = re.split(r"@@start (\d+)\n", res.stdout)[1:]
        outputs = {int(parts[i]): parts[i + 1] for i in range(0, len(parts), 2)}
        for k, (command, expected) in enumerate(cmds):
            out, _, rc = outputs.get(k, "@@rc -1").rpartition("@@rc ")
            got = int(rc.split()[0]) if rc.split() else -1       # -1: the shell ended before it
            results.append((command, expected, got, out + res.stderr[-2000:]))
    return results


@pytest.mark.parametrize("page", PAGES, ids=[p.name for p in PAGES])
def test_every_command_on_the_page_runs(page, tmp_path):
    results = run_page(page, tmp_path)
    blocks = [b for b in sh_blocks(page) if not INSTALLS.search(b) and not BENCHMARKS.search(b)]
    assert results or not blocks
    for command, expected, got, output in results:
        assert got == expected, f"{page.name}: {command!r} exited {got}, not {expected}:\n{output}"


def test_every_page_is_linked_from_the_index_and_its_links_resolve():
    index = (ROOT / "docs" / "README.md").read_text(encoding="utf-8")
    for page in (ROOT / "docs").glob("*.md"):
        if page.name != "README.md":
            assert f"({page.name})" in index, page.name
    for page in PAGES + [ROOT / "docs" / "README.md"]:
        for target in re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", page.read_text(encoding="utf-8")):
            if "://" in target:
                continue
            assert (page.parent / target).exists(), (page.name, target)


def test_the_readme_is_what_a_newcomer_reads_first():
    """Under 200 lines: what ucsio is for, the supported Pythons, the two
    lines, a walk-through on your own cell, the commands in one table, links."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    assert len(text.splitlines()) < 200
    for needed in ("## What it is for", "CPython 3.11", "## Five minutes on your own cell",
                   "## Commands", "docs/README.md"):
        assert needed in text, needed
    from ucsio.cli import COMMANDS
    table = text.split("## Commands", 1)[1].split("\n## ", 1)[0]
    for name in COMMANDS:
        assert f"`ucsio {name}" in table, name


def test_what_users_rely_on_is_in_the_docs_not_only_in_spec():
    """SPEC is not shipped: the five groups' limits and the JSON keys are in the docs."""
    method = (ROOT / "docs" / "method.md").read_text(encoding="utf-8")
    for limit in ("below 10 mm", "from 10 below 25 mm", "from 25 below 50 mm",
                  "from 50 below 100 mm", "from 100 mm on"):
        assert limit in method
    json_page = (ROOT / "docs" / "json.md").read_text(encoding="utf-8")
    for key in ("dt_mean", "loo_residual", "points_moved", "success_rate", "schema_version"):
        assert key in json_page, key


def test_the_readme_s_python_example_runs(tmp_path):
    """The README's Python lines run as written, in the demo's folder
    (docs/python-api.md's in tests/test_docs.py)."""
    blocks = re.findall(r"^```python\n(.*?)^```", (ROOT / "README.md").read_text(encoding="utf-8"),
                        re.S | re.M)
    assert blocks
    subprocess.run([sys.executable, "-m", "ucsio", "demo", "--out", "demo"], cwd=tmp_path,
                   check=True, capture_output=True, timeout=300)
    for block in blocks:
        res = subprocess.run([sys.executable, "-c", block], cwd=tmp_path, capture_output=True,
                             text=True, timeout=300)
        assert res.returncode == 0, res.stderr[-3000:]


def test_every_benchmark_the_docs_name_exists_and_starts():
    """The benchmark lines take minutes and are run by hand (docs/speed.md):
    here each script they name exists and answers --help, so a renamed
    script or option cannot leave the docs behind."""
    named = set()
    for page in PAGES:
        for block in sh_blocks(page):
            named.update(re.findall(r"^python (benchmarks/\S+\.py)", block, re.M))
    assert named
    for script in sorted(named):
        assert (ROOT / script).is_file(), script
        res = subprocess.run([sys.executable, str(ROOT / script), "--help"], capture_output=True,
                             text=True, timeout=120, cwd=ROOT)
        assert res.returncode == 0 and "usage:" in res.stdout, (script, res.stderr[-500:])
