"""`.ci/run` and the README's test line (issue 18, point 2): the test line
passes on a machine without Chromium, the browser tests saying in pytest's
summary that they were skipped and why; under .ci/run (UCSIO_REQUIRE_BROWSER)
a missing browser is a failure."""
from __future__ import annotations

import os
import subprocess
import sys

from conftest import ROOT

CI = ROOT / ".ci" / "run"


def _pytest_without_chromium(tmp_path, **env_extra) -> subprocess.CompletedProcess:
    """The browser tests with no Chromium on PATH (only this Python's folder)."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "python").symlink_to(sys.executable)
    env = {k: v for k, v in os.environ.items() if k != "UCSIO_REQUIRE_BROWSER"}
    env.update(PATH=str(bin_dir), **env_extra)
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-n", "0", "-p", "no:cacheprovider",
                           str(ROOT / "tests" / "test_report_browser.py")],
                          capture_output=True, text=True, env=env, cwd=tmp_path, timeout=300)


def test_browser_tests_are_skipped_with_the_reason_where_chromium_is_absent(tmp_path):
    proc = _pytest_without_chromium(tmp_path)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    summary = proc.stdout.split("short test summary info", 1)[-1]
    assert "SKIPPED" in summary and "Chromium is not installed" in summary, proc.stdout
    assert "apt-get install chromium" in summary
    assert " failed" not in proc.stdout and " error" not in proc.stdout


def test_under_ci_a_missing_browser_is_a_failure(tmp_path):
    proc = _pytest_without_chromium(tmp_path, UCSIO_REQUIRE_BROWSER="1")
    assert proc.returncode == 1, proc.stdout + proc.stderr
    assert "UCSIO_REQUIRE_BROWSER is set" in proc.stdout


def test_ci_runs_the_readme_test_line_on_every_python():
    text = CI.read_text()
    assert os.access(CI, os.X_OK)
    assert subprocess.run(["bash", "-n", str(CI)]).returncode == 0
    assert "export UCSIO_REQUIRE_BROWSER=1" in text
    # the interpreters of issue 18: the main one, Debian's own, pyenv's 3.12 and 3.13
    for needle in ('command -v python3', '/usr/bin/python3', 'newest 3.12', 'newest 3.13'):
        assert needle in text
    # the line it runs is the README's, found the way .ci/run finds it
    line = subprocess.run(
        ["awk", '/^```sh$/ {inside=1; next} inside {n++; if (n == 2) {print; exit}}',
         str(ROOT / "README.md")], capture_output=True, text=True).stdout.strip()
    assert line == ("python3 -m venv .venv && . .venv/bin/activate && "
                    "python -m pip install '.[test]' && python -m pytest -q")
