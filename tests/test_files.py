"""Writes that fail leave nothing changed; backups never overwrite; links are
written through, never replaced (issue 12 points 5 and 6)."""
from __future__ import annotations

import errno
import os
import shutil
from pathlib import Path

import pytest

from conftest import FIXTURES
from ucsio.cli import main
from ucsio.parsing.controller import load
from ucsio.errors import UcsioError
from ucsio.files import atomic_write

CELL = FIXTURES / "patch" / "cell.mod"
PATCH = ["--frame", "wobjTable", "--set", "1,2,3,4,5,6"]


def listing(folder: Path) -> dict:
    """Every entry of ``folder``: a link as its target, a file as its bytes."""
    out: dict = {}
    for p in sorted(folder.iterdir()):
        out[p.name] = ("-> " + os.readlink(p) if p.is_symlink() else
                       sorted(listing(p)) if p.is_dir() else p.read_bytes())
    return out


@pytest.fixture
def cell(tmp_path) -> Path:
    f = tmp_path / "cell.mod"
    shutil.copy(CELL, f)
    return f


# ------------------------------------------------------------------ point 5: backups

def test_backup_never_overwrites_an_older_one(cell, capsys):
    cell.with_name("cell.mod.bak").write_bytes(b"last week's backup")
    cell.with_name("cell.mod.bak.1").write_bytes(b"yesterday's backup")
    before = cell.read_bytes()
    assert main(["patch", str(cell), *PATCH, "--in-place", "--backup"]) == 0
    assert "backup " + str(cell) + ".bak.2" in capsys.readouterr().err
    assert cell.with_name("cell.mod.bak").read_bytes() == b"last week's backup"
    assert cell.with_name("cell.mod.bak.1").read_bytes() == b"yesterday's backup"
    assert cell.with_name("cell.mod.bak.2").read_bytes() == before
    once = cell.read_bytes()
    assert main(["patch", str(cell), "--frame", "wobjTable", "--set", "7,8,9,0,0,0",
                 "--in-place", "--backup"]) == 0
    assert cell.with_name("cell.mod.bak.3").read_bytes() == once


def test_first_backup_is_file_bak_with_the_files_mode(cell):
    os.chmod(cell, 0o640)
    before = cell.read_bytes()
    assert main(["patch", str(cell), *PATCH, "--in-place", "--backup"]) == 0
    bak = cell.with_name("cell.mod.bak")
    assert bak.read_bytes() == before and cell.read_bytes() != before
    assert (os.stat(bak).st_mode & 0o777, os.stat(cell).st_mode & 0o777) == (0o640, 0o640)


def _fail_on(monkeypatch, name: str, call: int, err=errno.ENOSPC):
    """Make the ``call``-th call of os.<name> fail with ``err`` (1-based; 0: every call)."""
    real = getattr(os, name)
    count = {"n": 0}

    def failing(*args, **kwargs):
        count["n"] += 1
        if call in (0, count["n"]):
            raise OSError(err, os.strerror(err))
        return real(*args, **kwargs)
    monkeypatch.setattr(os, name, failing)


@pytest.mark.parametrize("name,call,no_links", [
    ("fsync", 1, False),      # disk full while the new file is written
    ("replace", 1, False),    # the rename fails after the backup was made
    ("fsync", 2, True),       # no hard links: the backup copy itself fills the disk
    ("replace", 1, True),     # ... or the rename fails after the copy
])
def test_failed_write_changes_nothing_backup_included(cell, tmp_path, capsys, monkeypatch,
                                                      name, call, no_links):
    cell.with_name("cell.mod.bak").write_bytes(b"older backup")
    before = listing(tmp_path)
    if no_links:
        _fail_on(monkeypatch, "link", 0, errno.EPERM)
    _fail_on(monkeypatch, name, call)
    rc = main(["patch", str(cell), *PATCH, "--in-place", "--backup"])
    monkeypatch.undo()
    err = capsys.readouterr().err
    assert rc == 2 and "No space left on device" in err and err.count("\n") == 1
    assert listing(tmp_path) == before           # no new backup, no temporary file


def test_copy_backup_where_the_file_system_has_no_hard_links(cell, monkeypatch):
    _fail_on(monkeypatch, "link", 0, errno.EPERM)
    before = cell.read_bytes()
    assert main(["patch", str(cell), *PATCH, "--in-place", "--backup"]) == 0
    assert cell.with_name("cell.mod.bak").read_bytes() == before


# ------------------------------------------------------------------ point 6: links

def test_output_link_is_written_through(cell, tmp_path):
    real = tmp_path / "real" / "out.mod"
    real.parent.mkdir()
    real.write_bytes(b"to be replaced")
    link = tmp_path / "out.mod"
    link.symlink_to(real)
    assert main(["patch", str(cell), *PATCH, "-o", str(link)]) == 0
    assert link.is_symlink() and os.readlink(link) == str(real)
    assert load(real).frame("wobjTable").pose.t == pytest.approx((1, 2, 3))


def test_in_place_through_a_link_keeps_the_link_and_backs_up_the_file(tmp_path, capsys):
    real = tmp_path / "controller" / "cell.mod"
    real.parent.mkdir()
    shutil.copy(CELL, real)
    link = tmp_path / "cell.mod"
    link.symlink_to(os.path.relpath(real, tmp_path))
    assert main(["patch", str(link), *PATCH, "--in-place", "--backup"]) == 0
    assert "wrote " + str(real) in capsys.readouterr().err
    assert link.is_symlink() and load(link).frame("wobjTable").pose.t == pytest.approx((1, 2, 3))
    assert real.with_name("cell.mod.bak").read_bytes() == CELL.read_bytes()


@pytest.mark.parametrize("kind", ["dangling", "loop", "self", "folder"])
def test_dangling_or_looping_link_refused(cell, tmp_path, capsys, kind):
    out = tmp_path / "out.mod"
    if kind == "dangling":
        out.symlink_to(tmp_path / "nowhere" / "x.mod")
        why = "which does not exist"
    elif kind == "loop":
        out.symlink_to(tmp_path / "other.mod")
        (tmp_path / "other.mod").symlink_to(out)
        why = "loop of symbolic links"
    elif kind == "self":
        out.symlink_to(out)
        why = "loop of symbolic links"
    else:
        (tmp_path / "dir").mkdir()
        out.symlink_to(tmp_path / "dir")
        why = "is a link to the directory"
    before = listing(tmp_path)
    rc = main(["patch", str(cell), *PATCH, "-o", str(out)])
    err = capsys.readouterr().err
    assert rc == 2 and why in err and err.count("\n") == 1 and str(out) in err
    assert listing(tmp_path) == before


def test_every_writer_follows_the_same_rule(tmp_path):
    """Solutions, CSV and reports go through atomic_write too."""
    real = tmp_path / "solution.json"
    real.write_text("{}")
    link = tmp_path / "latest.json"
    link.symlink_to(real.name)
    assert atomic_write(link, b'{"a": 1}') == (str(real), None)
    assert link.is_symlink() and real.read_bytes() == b'{"a": 1}'
    loop = tmp_path / "loop.json"
    loop.symlink_to(loop.name)
    with pytest.raises(UcsioError, match="loop"):
        atomic_write(loop, b"x")
