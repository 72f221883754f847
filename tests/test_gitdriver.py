"""`git diff` of a folder of controller backups shows frame changes, through
ucsio as an external diff driver (diff.<driver>.command) or as a textconv."""
from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys

import pytest

from conftest import FIXTURES

pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")

UCSIO = f"{shlex.quote(sys.executable)} -m ucsio diff"


def git(repo, *args, check=True) -> str:
    env = dict(os.environ, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@example.com",
               GIT_COMMITTER_NAME="t", GIT_COMMITTER_EMAIL="t@example.com",
               GIT_CONFIG_NOSYSTEM="1", HOME=str(repo), GIT_PAGER="cat", PAGER="cat")
    env.pop("GIT_EXTERNAL_DIFF", None)
    r = subprocess.run(["git", *args], cwd=repo, env=env, capture_output=True, text=True,
                       check=check)
    return r.stdout


@pytest.fixture
def repo(tmp_path):
    r = tmp_path / "backups"
    (r / "R01").mkdir(parents=True)
    (r / "R02").mkdir()
    shutil.copy(FIXTURES / "patch" / "cell.mod", r / "R01" / "cell.mod")
    shutil.copy(FIXTURES / "patch" / "refs" / "$config.dat", r / "R02" / "$config.dat")
    (r / ".gitattributes").write_text("*.mod diff=ucsio\n*.sys diff=ucsio\n*.dat diff=ucsio\n")
    git(r, "init", "-q", ".")
    git(r, "add", ".")
    git(r, "commit", "-q", "-m", "backup 1")
    return r


def patch(repo, *args):
    subprocess.run([sys.executable, "-m", "ucsio", "patch", *args, "--in-place"], cwd=repo,
                   check=True, capture_output=True)


def test_external_diff_driver(repo):
    git(repo, "config", "diff.ucsio.command", UCSIO)
    patch(repo, "R01/cell.mod", "--frame", "wobjSpec",
          "--set=6125.39,2445.56,1168.99,90.529,-24.476,-0.313")
    patch(repo, "R02/$config.dat", "--frame", "table", "--set=2500,-1200,805,180,0,0")
    out = git(repo, "diff")
    assert "ucsio diff a/R01/cell.mod b/R01/cell.mod" in out
    assert "~ wobjSpec (wobjdata): value changed" in out
    assert "dt_mean 5.892 mm (group 1)" in out
    assert "ucsio diff a/R02/$config.dat b/R02/$config.dat" in out
    assert '~ BASE_DATA[1] "table" (BASE_DATA): value changed' in out and "dz +5.000" in out
    # a new backup file: git passes /dev/null as the old side
    shutil.copy(repo / "R01" / "cell.mod", repo / "R01" / "cell_copy.mod")
    git(repo, "add", "R01/cell_copy.mod")
    out = git(repo, "diff", "--cached")
    assert "ucsio diff a/R01/cell_copy.mod" in out and "19 added" in out
    # a deleted one
    git(repo, "commit", "-q", "-am", "backup 2")
    git(repo, "rm", "-q", "R01/cell_copy.mod")
    out = git(repo, "diff", "--cached")
    assert "19 removed" in out


def test_textconv_driver(repo):
    git(repo, "config", "diff.ucsio.textconv", f"{UCSIO} --textconv")
    patch(repo, "R01/cell.mod", "--frame", "wobjSpec",
          "--set=6125.39,2445.56,1168.99,90.529,-24.476,-0.313")
    out = git(repo, "diff")
    minus = [ln for ln in out.splitlines() if ln.startswith("-wobjSpec ")]
    plus = [ln for ln in out.splitlines() if ln.startswith("+wobjSpec ")]
    assert minus == ["-wobjSpec wobjdata ref=world x=6130 y=2444.711 z=1156.772 "
                     "q1=0.690346 q2=0.153046 q3=-0.153046 q4=0.690346 robhold=False ufprog=True "
                     "storage=TASK PERS"]
    assert len(plus) == 1 and "x=6125.39 y=2445.56 z=1168.99" in plus[0]
    # that frame's line, and the file's own line below it: nothing else changed
    changed = [ln for ln in out.splitlines()
               if ln[:1] in "+-" and not ln.startswith(("+++", "---"))]
    assert len(changed) == 4
    assert [ln for ln in changed if "TASK PERS wobjdata wobjSpec:=" in ln][0].startswith("-")


def test_textconv_never_hides_a_change_outside_frames(repo):
    git(repo, "config", "diff.ucsio.textconv", f"{UCSIO} --textconv")
    path = repo / "R02" / "$config.dat"
    path.write_bytes(path.read_bytes().replace(b"INT MAX_TOOL=2", b"INT MAX_TOOL=3", 1))
    out = git(repo, "diff")
    assert "-INT MAX_TOOL=2" in out and "+INT MAX_TOOL=3" in out


def test_external_diff_never_hides_other_changes(repo):
    git(repo, "config", "diff.ucsio.command", UCSIO)
    # only a frame moved: the frame summary says it all, no text diff appended
    patch(repo, "R01/cell.mod", "--frame", "wobjPlain", "--set=1,2,3,0,0,0")
    out = git(repo, "diff")
    assert "~ wobjPlain.oframe" not in out and "~ wobjPlain (wobjdata): value changed" in out
    assert "lines changed beyond the frame values" not in out
    # a comment changed as well: the text diff follows the frame summary
    path = repo / "R01" / "cell.mod"
    path.write_bytes(path.read_bytes().replace(b"one frame per refusal rule", b"one frame per rule"))
    out = git(repo, "diff")
    assert "lines changed beyond the frame values above" in out
    assert "+    ! ucsio patch fixture: one frame per rule, and SPEC's diff example." in out
    # no frame changed at all, but a routine did: still shown
    git(repo, "checkout", "--", ".")
    path.write_bytes(path.read_bytes().replace(b"v1000, fine", b"v500, fine"))
    out = git(repo, "diff")
    assert "no frame changed" in out and "+        MoveL Offs(pHome,0,0,100), v500, fine" in out


# -- Yaskawa: UFRAME.CND, TOOL.CND, RBCALIB.DAT -------------------------------------------
@pytest.fixture
def yaskawa_repo(tmp_path):
    """A Yaskawa backup under git: .CND files and RBCALIB.DAT (CRLF, as the
    controller writes them), each through the driver by its attributes."""
    from test_yaskawa import TOOLS, UFRAMES
    from test_yaskawa_rbcalib import rbcalib
    from test_yaskawa import crlf
    r = tmp_path / "yaskawa"
    (r / "R05").mkdir(parents=True)
    (r / "R05" / "UFRAME.CND").write_bytes(UFRAMES)
    (r / "R05" / "TOOL.CND").write_bytes(TOOLS.replace(b"///CRC 3243358777\r\n", b""))
    (r / "R05" / "RBCALIB.DAT").write_bytes(crlf(rbcalib(
        "21.194,911.779,30.780,-0.7153,2.0659,-0.4335")))
    (r / ".gitattributes").write_text("*.CND diff=ucsio\nRBCALIB.DAT diff=ucsio\n")
    git(r, "init", "-q", ".")
    git(r, "add", ".")
    git(r, "commit", "-q", "-m", "backup 1")
    return r


def _move_yaskawa(repo):
    patch(repo, "R05/UFRAME.CND", "--frame", "UF2", "--set=100.5,20,5,90,0,0")
    path = repo / "R05" / "RBCALIB.DAT"
    path.write_bytes(path.read_bytes().replace(b"21.194,911.779,30.780", b"21.194,912.779,30.780"))


def test_yaskawa_external_diff_driver(yaskawa_repo):
    """git hands the old side as a temporary file: its first line says what it is."""
    git(yaskawa_repo, "config", "diff.ucsio.command", UCSIO)
    _move_yaskawa(yaskawa_repo)
    out = git(yaskawa_repo, "diff")
    assert "ucsio diff a/R05/UFRAME.CND b/R05/UFRAME.CND" in out
    assert '~ UF2 "FIXTURE" (UFRAME): value changed' in out and "dx +0.500" in out
    assert "ucsio diff a/R05/RBCALIB.DAT b/R05/RBCALIB.DAT" in out
    assert '~ RBCALIB1 "R2 base in R1 base" (RBCALIB): value changed' in out
    assert "dy +1.000" in out and "error" not in out.lower()
    assert "lines changed beyond the frame values" not in out


def test_yaskawa_textconv_driver(yaskawa_repo):
    git(yaskawa_repo, "config", "diff.ucsio.textconv", f"{UCSIO} --textconv")
    _move_yaskawa(yaskawa_repo)
    out = git(yaskawa_repo, "diff")
    changed = [ln for ln in out.splitlines()
               if ln[:1] in "+-" and not ln.startswith(("+++", "---"))]
    assert [ln[:9] for ln in changed if ln[1:].startswith(("UF2 ", "RBCALIB1 "))] == [
        "-RBCALIB1", "+RBCALIB1", "-UF2 UFRA", "+UF2 UFRA"]
    assert any("y=912.779" in ln for ln in changed if ln.startswith("+RBCALIB1"))
    assert any("x=100.5" in ln for ln in changed if ln.startswith("+UF2"))


@pytest.mark.parametrize("source", ["UFRAME.CND", "TOOL.CND", "RBCALIB.DAT"])
def test_yaskawa_file_without_a_suffix_is_known_by_its_first_line(yaskawa_repo, source):
    """A temporary copy under a name that says nothing (as git may hand
    one over) reads as what it is, for both drivers."""
    bare = yaskawa_repo / "tmp_Xq1z"
    shutil.copy(yaskawa_repo / "R05" / source, bare)
    res = subprocess.run([sys.executable, "-m", "ucsio", "diff", "--textconv", str(bare)],
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    first = res.stdout.splitlines()[1].split()
    assert first[0] in ("UF1", "UT0", "RBCALIB1") and first[1] in ("UFRAME", "TOOL", "RBCALIB")
    res = subprocess.run([sys.executable, "-m", "ucsio", "diff", str(bare),
                          str(yaskawa_repo / "R05" / source)], capture_output=True, text=True)
    assert res.returncode == 0 and "no frame changed" in res.stdout, res.stderr


# -- Stäubli: .dtx of both dialects ---------------------------------------------------------
@pytest.fixture
def staubli_repo(tmp_path):
    """A Stäubli cell under git: a CS8 .dtx (BOM, CRLF) and an s7/CS9 one
    (BOM, LF). patch does not write .dtx (the rotation order is not proved):
    the pendant's new values arrive as an edited file."""
    r = tmp_path / "staubli"
    (r / "R06").mkdir(parents=True)
    for name in ("cell_cs8.dtx", "cell_cs9.dtx"):
        shutil.copy(FIXTURES / "staubli" / name, r / "R06" / name)
    (r / ".gitattributes").write_text("*.dtx diff=ucsio\n")
    git(r, "init", "-q", ".")
    git(r, "add", ".")
    git(r, "commit", "-q", "-m", "backup 1")
    return r


def _move_staubli(repo):
    for name, old, new in (("cell_cs8.dtx", b'z="12.5" rx="180"', b'z="13.5" rx="180"'),
                           ("cell_cs9.dtx", b'x="25" y="25"', b'x="25.5" y="25"')):
        path = repo / "R06" / name
        path.write_bytes(path.read_bytes().replace(old, new))


def test_staubli_external_diff_driver(staubli_repo):
    git(staubli_repo, "config", "diff.ucsio.command", UCSIO)
    _move_staubli(staubli_repo)
    out = git(staubli_repo, "diff")
    assert "ucsio diff a/R06/cell_cs8.dtx b/R06/cell_cs8.dtx" in out
    assert "~ fFixture[1] (frame): value changed" in out and "dz +1.000" in out
    assert "~ fPart (frame): value changed" in out and "dx +0.500" in out
    assert "error" not in out.lower() and "lines changed beyond the frame values" not in out


def test_staubli_textconv_driver(staubli_repo):
    git(staubli_repo, "config", "diff.ucsio.textconv", f"{UCSIO} --textconv")
    _move_staubli(staubli_repo)
    out = git(staubli_repo, "diff")
    changed = [ln for ln in out.splitlines()
               if ln[:1] in "+-" and not ln.startswith(("+++", "---"))]
    frames = [ln.split()[0] for ln in changed if ln[1:].startswith(("fFixture[1] ", "fPart "))]
    assert frames == ["-fFixture[1]", "+fFixture[1]", "-fPart", "+fPart"]
    assert any("z=13.5" in ln for ln in changed if ln.startswith("+fFixture[1]"))
    assert any("x=25.5" in ln for ln in changed if ln.startswith("+fPart"))
