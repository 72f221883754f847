"""The pre-commit hook (issue 21, point 2): .pre-commit-hooks.yaml is a valid
manifest whose hook takes exactly the controller files ucsio reads from a
backup, in any case; and `pre-commit try-repo` on a throw-away repository
with a good and a bad module fails, naming the bad one and not the good.

try-repo installs this repository into a fresh virtual environment with
pip, as pre-commit does for its users (about 40 s here); it needs git and
pip's package index (this machine's mirror or PyPI)."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys

import pytest

from conftest import FIXTURES, ROOT

MANIFEST = ROOT / ".pre-commit-hooks.yaml"
pytest.importorskip("pre_commit", reason="pre-commit is in the test extras: pip install '.[test]'")


def pre_commit(*args, cwd, env=None, timeout=600):
    return subprocess.run([sys.executable, "-m", "pre_commit", *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, env=env, timeout=timeout)


def hook() -> dict:
    from pre_commit.clientlib import load_manifest
    (h,) = load_manifest(str(MANIFEST))
    return h


def test_manifest_is_valid():
    res = pre_commit("validate-manifest", MANIFEST, cwd=ROOT)
    assert res.returncode == 0, res.stdout + res.stderr
    h = hook()
    assert h["id"] == "ucsio-check" and h["language"] == "python"
    assert h["entry"].startswith("ucsio check")
    assert "binary" in h["exclude_types"]


def test_hook_takes_the_files_a_backup_folder_is_read_for():
    """The hook's pattern and BACKUP_SUFFIXES name the same extensions (FANUC's
    .va and .ls join both once ucsio reads them), in any case."""
    from ucsio.parsing.backup import BACKUP_SUFFIXES
    pattern = re.compile(hook()["files"])
    m = re.fullmatch(r"\(\?i\)\\\.\(([a-z|]+)\)\$", hook()["files"])
    assert m and {"." + e for e in m.group(1).split("|")} == set(BACKUP_SUFFIXES)
    for name in ("R01/RAPID/TASK1/PROGMOD/Main.mod", "CALIB.SYS", "x.MODX", "a.Sysx",
                 "Cell.prg", "KRC/R1/System/$config.dat", "$CONFIG.DAT"):
        assert pattern.search(name), name
    for name in ("Main.mod.bak", "prog.src", "x.datx", "notes.txt", "mod"):
        assert not pattern.search(name), name


def _git(*args, cwd):
    subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True,
                   env=dict(os.environ, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@example.invalid",
                            GIT_COMMITTER_NAME="t", GIT_COMMITTER_EMAIL="t@example.invalid"))


def test_try_repo_fails_on_the_bad_file_and_names_it(tmp_path):
    if shutil.which("git") is None:
        pytest.skip("git is not installed: pre-commit needs it")
    if not (ROOT / ".git").exists():
        pytest.skip(f"{ROOT} is not a git checkout (an sdist?): try-repo needs one")
    repo = tmp_path / "cell"
    (repo / "RAPID").mkdir(parents=True)
    shutil.copy(FIXTURES / "abb" / "bom.mod", repo / "RAPID" / "Good.MOD")
    shutil.copy(FIXTURES / "abb" / "bad" / "badnumber.mod", repo / "RAPID" / "Bad.mod")
    shutil.copy(FIXTURES / "abb" / "encrypted.mod", repo / "RAPID" / "Secret.mod")
    (repo / "notes.txt").write_text("not a controller file\n")
    _git("init", "-q", cwd=repo)
    _git("add", ".", cwd=repo)
    env = dict(os.environ, PRE_COMMIT_HOME=str(tmp_path / "pre-commit-home"),
               PIP_DISABLE_PIP_VERSION_CHECK="1")
    env.pop("NO_COLOR", None)
    res = pre_commit("try-repo", ROOT, "ucsio-check", "--all-files", "--color", "never",
                     cwd=repo, env=env)
    out = res.stdout + res.stderr
    if res.returncode != 0 and re.search(r"No matching distribution found|Failed to establish "
                                         r"a new connection|Could not find a version", out):
        pytest.skip("pip could not reach a package index to install the hook's environment:\n"
                    + out[-2000:])
    assert res.returncode == 1, out
    assert re.search(r"ucsio check\.+Failed", out), out
    assert "- exit code: 2" in out
    assert "RAPID/Bad.mod:2:30: error: syntax-error: bad number '1.2.3'" in out
    assert "Good.MOD" not in out                       # checked, and nothing to say
    assert "Secret.mod" not in out                     # binary: left out
    assert "notes.txt" not in out                      # not a controller file

    # fixed, the same hook passes
    shutil.copy(FIXTURES / "abb" / "bom.mod", repo / "RAPID" / "Bad.mod")
    _git("add", ".", cwd=repo)
    res = pre_commit("try-repo", ROOT, "ucsio-check", "--all-files", "--color", "never",
                     cwd=repo, env=env)
    assert res.returncode == 0, res.stdout + res.stderr
    assert re.search(r"ucsio check\.+Passed", res.stdout), res.stdout
