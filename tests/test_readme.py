"""The README and the docs document what ucsio does (issue 11 point 7; since
issue 21 the reference lives in docs/): the README's first line is a
virtual-environment line, the measurement CSV example is read as written,
the manifest example names every key batch accepts and is a valid manifest,
every lint code is in the table, and the backup review is shown."""
from __future__ import annotations

import re
import tomllib

from conftest import ROOT

README = (ROOT / "README.md").read_text(encoding="utf-8")
DOCS = ROOT / "docs"


def page(name: str) -> str:
    return (DOCS / name).read_text(encoding="utf-8")


def code_blocks(lang: str, text: str = README) -> list[str]:
    return re.findall(r"```" + lang + r"\n(.*?)```", text, re.S)


def test_first_two_lines_make_a_virtual_environment_with_python3():
    """Stock Debian and Ubuntu have python3 and no python: each line starts
    with python3 and stands on its own."""
    first, second = code_blocks("sh")[0].splitlines()[:2]
    for line in (first, second):
        assert line.startswith("python3 -m venv .venv && . .venv/bin/activate && python -m pip ")
    assert first.endswith("python -m pip install . && ucsio demo")
    assert second.endswith("python -m pip install '.[test]' && python -m pytest -q")
    assert "ucsio demo --out DIR" in README and "replay.sh" in README


def test_readme_says_which_pythons_and_how_on_windows():
    import tomllib
    head = README[:3000]
    requires = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["requires-python"]
    assert requires == ">=3.11"
    assert "CPython 3.11 or later" in head
    for version in ("3.11.2", "3.12", "3.13"):
        assert version in head
    assert "py -3 -m venv .venv" in head and ".venv\\Scripts\\activate" in head


def test_measurement_example_is_read_as_written(tmp_path):
    from ucsio.readers.measurement import KNOWN, read_measurement
    measurements = page("measurements.md")
    (csv,) = code_blocks("csv", measurements)
    path = tmp_path / "points.csv"
    path.write_text(csv)
    m = read_measurement(path)
    assert m.names == ["P1", "P2"] and m.form == "kuka"
    assert m.laser[1].tolist() == [800.0, 0.0, 0.0] and m.weights.tolist() == [1.0, 1.0]
    section = measurements.split("## The measurement CSV", 1)[1].split("\n## ", 1)[0]
    documented = set(re.findall(r"`([a-z_0-9]+)`", section))
    if "`robot_q1` … `robot_q4`" in section:
        documented |= {"robot_q2", "robot_q3"}
    assert KNOWN <= documented, KNOWN - documented      # every column the reader knows


def test_manifest_example_names_every_key_and_is_valid():
    from ucsio.fleet import batch
    blocks = [b for b in code_blocks("toml", page("batch.md")) if "[[entry]]" in b]
    example = max(blocks, key=len)
    data = tomllib.loads(example)
    keys = set(data["defaults"]) | {k for e in data["entry"] for k in e}
    assert set(batch.ENTRY_KEYS) <= keys, set(batch.ENTRY_KEYS) - keys
    batch._check_table(data["defaults"], "[defaults]", batch.DEFAULT_KEYS, "README")
    batch._check_values(data["defaults"], "[defaults]", "README")
    for e in data["entry"]:
        batch._check_table(e, "[[entry]]", batch.ENTRY_KEYS, "README")
        batch._check_values(e, "[[entry]]", "README")


def test_every_lint_code_is_in_the_table():
    from ucsio.parsing.controller import LINT_CODES
    section = page("controllers.md").split("## Lint codes", 1)[1].split("\n## ", 1)[0]
    for code in LINT_CODES:
        assert f"`{code}`" in section, code


def test_the_docs_show_a_backup_to_backup_review():
    """A review of two whole backups, run by tests/test_docs_commands.py."""
    diff = page("commands.md").split("\n## diff", 1)[1].split("\n## ", 1)[0]
    (block,) = [b for b in code_blocks("sh", diff) if "backup_old/ backup_new/" in b]
    assert "ucsio diff backup_old/ backup_new/ --exit-code       # exit 1" in block


def test_planning_walk_through_runs_as_written(tmp_path):
    """Issue 20 point 7: docs/planning.md's walk-through,
    line by line in bash on the demo cells; each exit status as annotated
    (`# exit N`, else 0), and the first plan's output as the page shows it."""
    import os
    import subprocess
    import sys

    section = page("planning.md").split("\n## ", 1)[0]
    script = re.findall(r"```sh\n(.*?)```", section, re.S)[0]
    shown = re.findall(r"```text\n(.*?)```", section, re.S)[0]
    lines = [f'ucsio() {{ "{sys.executable}" -m ucsio "$@"; }}']
    expected = []
    for k, line in enumerate(script.splitlines()):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        m = re.search(r"\s+#\s*(exit (\d))?.*$", line)
        code = int(m.group(2)) if m and m.group(2) else 0
        command = line[:m.start()] if m else line
        expected.append((command, code))
        lines += [f'echo "@@start {len(expected) - 1}"', command, 'echo "@@rc $?"']
    env = dict(os.environ)
    res = subprocess.run(["bash", "-c", "\n".join(lines)], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=600)
    parts = re.split(r"@@start (\d+)\n", res.stdout)[1:]
    outputs = {int(parts[i]): parts[i + 1] for i in range(0, len(parts), 2)}
    assert len(outputs) == len(expected), res.stderr
    first_fail = None
    for i, (command, code) in enumerate(expected):
        out, rc = outputs[i].rsplit("@@rc ", 1)
        assert int(rc) == code, (command, out, res.stderr)
        if code == 1 and first_fail is None:
            first_fail = out
    assert first_fail == shown
    assert "planning.md" in README and "bench_plan.py" in page("planning.md")
