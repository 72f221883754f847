"""Issue 21 point 5: docs/python-api.md's examples run, in order, in an empty
folder against the shipped example cells, and type-check under mypy --strict
as a user's script would (ucsio found as an installed package: its py.typed
marker makes mypy read the API's hints); the API itself passes the strict
settings in pyproject.toml."""
from __future__ import annotations

import os
import re
import subprocess
import sys

import pytest

from conftest import ROOT

PAGE = ROOT / "docs" / "python-api.md"


def examples() -> str:
    blocks = re.findall(r"```python\n(.*?)```", PAGE.read_text(), re.S)
    assert len(blocks) >= 8
    return "\n".join(blocks)


@pytest.fixture(scope="module")
def script(tmp_path_factory):
    folder = tmp_path_factory.mktemp("docs")
    path = folder / "examples.py"
    path.write_text(examples())
    return path


def env(tmp_path) -> dict:
    return dict(os.environ, UCSIO_CACHE_DIR=os.environ.get("UCSIO_CACHE_DIR",
                                                           str(tmp_path / "cache")))


def test_the_examples_run(script, tmp_path):
    work = tmp_path / "work"
    work.mkdir()
    res = subprocess.run([sys.executable, str(script)], cwd=work, capture_output=True,
                         text=True, env=env(tmp_path))
    assert res.returncode == 0, res.stderr[-3000:]
    out = res.stdout
    assert "['P5']" in out                           # the blunder the demo's cell holds
    assert (work / "solution.json").exists() and (work / "demo" / "fleet.html").exists()
    assert (work / "demo" / "R01_kuka" / "reviewed.dat").exists()
    assert "2 no TCP given" in out                    # the error example


def mypy(*args: str, cwd, tmp_path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "mypy", "--cache-dir", str(tmp_path / "mypy"),
                           *args], cwd=cwd, capture_output=True, text=True, env=env(tmp_path))


def test_the_api_passes_mypy_strict(tmp_path):
    """pyproject.toml's [tool.mypy]: ucsio.api and ucsio.results, strict."""
    res = mypy("--config-file", str(ROOT / "pyproject.toml"), cwd=ROOT, tmp_path=tmp_path)
    assert res.returncode == 0, res.stdout + res.stderr
    assert "Success" in res.stdout


def test_the_examples_type_check_as_a_user_s_script(script, tmp_path):
    """mypy --strict on the page's examples, with ucsio found where pip put it
    (no path to the sources): py.typed must be there and the hints must
    hold. A script that misreads a key's type is caught."""
    config = tmp_path / "mypy.ini"
    config.write_text("[mypy]\nstrict = True\n")
    res = mypy("--config-file", str(config), str(script), cwd=tmp_path, tmp_path=tmp_path)
    assert res.returncode == 0, res.stdout + res.stderr
    wrong = tmp_path / "wrong.py"
    wrong.write_text("from ucsio import api\n"
                     "sol = api.solve('m.csv', tcp=(0, 0, 0))\n"
                     "rms: str = sol.rms\n"
                     "name: int = sol.points[0].name\n"
                     "ok: str = api.plan('p.csv').worst.at_95\n")
    res = mypy("--config-file", str(config), str(wrong), cwd=tmp_path, tmp_path=tmp_path)
    assert res.returncode == 1
    assert res.stdout.count("[assignment]") == 3, res.stdout
    assert "missing library stubs or py.typed" not in res.stdout
