"""Reviewing FANUC files (issue 19 point 3): ``diff`` of two sysframe.va, two
TP programs, two FANUC backup folders (binary .tp .sv .vr listed as not
read, never hiding the rest), and git's external diff driver and textconv
for .va and .ls. Rotations are compared, not numbers: W 180 and W -180 are
one frame.

Backups are built in temporary folders from the corpus files (read in
place from ../shared/corpus/fanuc, copied only into the test's folder)."""
from __future__ import annotations

import json
import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import CORPUS, FIXTURES, ROOT, corpus_file

SRC = str(ROOT / "src")
UB = "irbzavalagit__UB10200_RBT01__"
needs_corpus = pytest.mark.skipif(not (CORPUS / "fanuc").is_dir(),
                                  reason="the shared corpus (../shared/corpus/fanuc) is absent")


def run(*args, cwd=None, env=None):
    env = dict(env or os.environ, PYTHONPATH=SRC)
    env.pop("NO_COLOR", None)
    return subprocess.run([sys.executable, "-m", "ucsio", *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, env=env)


def edit(path, old: bytes, new: bytes):
    data = path.read_bytes()
    assert data.count(old) >= 1, old
    path.write_bytes(data.replace(old, new, 1))


def old_and_new(tmp_path, source, suffix: str):
    """Two copies of ``source`` to edit one of: (old, new)."""
    old, new = tmp_path / f"old{suffix}", tmp_path / f"new{suffix}"
    shutil.copy(source, old)
    shutil.copy(source, new)
    return old, new


def ub_backup(folder):
    """The UB10200 robot's backup as the controller names its files, with
    the binary files every real backup has beside the ASCII ones."""
    folder.mkdir(parents=True)
    for part, name in (("sysframe.va", "SYSFRAME.VA"), ("frame.dg", "FRAME.DG"),
                       ("curpos.dg", "CURPOS.DG"), ("posreg.va", "POSREG.VA"),
                       ("tooldataub10200rbt01.ls", "TOOLDATAUB10200RBT01.LS"),
                       ("td_gun1.ls", "TD_GUN1.LS")):
        shutil.copy(corpus_file("fanuc", UB + part), folder / name)
    (folder / "TD_GUN1.TP").write_bytes(b"\x00\x01TPBIN" * 10)
    (folder / "SYSFRAME.SV").write_bytes(b"\x00\x02SVBIN" * 10)
    (folder / "NUMREG.VR").write_bytes(b"\x00\x03VRBIN" * 10)
    return folder


# -- two sysframe.va ---------------------------------------------------------------------
@needs_corpus
def test_two_sysframes_frames_changed_and_rotations_compared(tmp_path):
    old, new = old_and_new(tmp_path, corpus_file("fanuc", UB + "sysframe.va"), ".va")
    # UF1 moves 0.5 mm in X (the field width kept); UF2 gets a value;
    # UT31's W 180 becomes -180: the same rotation, no frame change
    edit(new, b"  X:  3495.600   Y:  5813.000", b"  X:  3496.100   Y:  5813.000")
    edit(new, b"    [1,2] = \r\n  Group: 1   Config: N D B, 0, 0, 0\r\n"
              b"  X:     0.000   Y:     0.000   Z:     0.000",
         b"    [1,2] = \r\n  Group: 1   Config: N D B, 0, 0, 0\r\n"
         b"  X:   100.000   Y:     0.000   Z:     0.000")
    data = new.read_bytes()
    ut31 = data.index(b"[1,31] = ", data.index(b"$MNUTOOL "))
    w = data.index(b"W:   180.000", ut31)
    new.write_bytes(data[:w] + b"W:  -180.000" + data[w + len(b"W:   180.000"):])
    res = run("diff", old, new, "--json")
    assert res.returncode == 0, res.stderr
    d = json.loads(res.stdout)
    assert [c["name"] for c in d["changed"]] == ["UF1", "UF2"]
    uf1 = d["changed"][0]
    assert uf1["changes"] == ["value"] and uf1["vendor"] == "fanuc"
    assert uf1["dx"] == pytest.approx(0.5) and uf1["angle"] == pytest.approx(0.0, abs=1e-9)
    assert (uf1["dw"], uf1["dp"], uf1["dr"]) == (uf1["dc"], uf1["db"], uf1["da"])
    assert d["added"] == [] and d["removed"] == [] and d["unchanged"] == 126
    text = run("diff", old, new).stdout
    assert "~ UF1 (UFRAME): value changed" in text
    assert "dw +0.0000  dp +0.0000  dr +0.0000 deg" in text
    assert "- x 3495.600  y 5813.000  z -1166.400  w 0.1400  p 0.0800  r -90.0400" in text
    # the W line of UT31 changed: shown as text, never as a frame change
    assert "lines changed beyond the frame values" in text
    assert "-  W:   180.000   P:     0.000   R:   -90.000" in text
    assert "+  W:  -180.000   P:     0.000   R:   -90.000" in text
    assert "UT31" not in text
    assert run("diff", old, new, "--exit-code").returncode == 1
    assert run("diff", old, old, "--exit-code").returncode == 0


def test_w_180_against_minus_180_alone_is_no_frame_change(tmp_path):
    old, new = old_and_new(tmp_path, FIXTURES / "fanuc" / "sysframe_comment.va", ".va")
    edit(new, b"  W:   180.000   P:     0.000   R:   -90.000\r\n    [1,3]",
         b"  W:  -180.000   P:     0.000   R:   -90.000\r\n    [1,3]")
    d = json.loads(run("diff", old, new, "--json").stdout)
    assert d["changed"] == [] and d["unchanged"] == 10


# -- two programs --------------------------------------------------------------------------
@needs_corpus
def test_two_programs(tmp_path):
    old, new = old_and_new(tmp_path, corpus_file("fanuc", UB + "tooldataub10200rbt01.ls"), ".ls")
    edit(new, b"PR[16,1]=3500    ;", b"PR[16,1]=3500.5    ;")
    edit(new, b"UFRAME[19:TIPDRESS]", b"UFRAME[19:TIP DRESS]")
    d = json.loads(run("diff", old, new, "--json").stdout)
    got = {c["name"]: c["changes"] for c in d["changed"]}
    assert got == {"UF1": ["value"], "UF19": ["label"]}
    assert [c["dx"] for c in d["changed"] if c["name"] == "UF1"] == [pytest.approx(0.5)]


# -- two backups ---------------------------------------------------------------------------
@needs_corpus
def test_a_fanuc_backup_folder_lists_frames_and_what_it_does_not_read(tmp_path):
    folder = ub_backup(tmp_path / "UB10200_RBT01")
    res = run("frames", folder, "--json")
    assert res.returncode == 0, res.stderr
    out = json.loads(res.stdout)
    assert len(out["files"]) == 6 and out["errors"] == []
    assert sorted(os.path.basename(x["file"]) for x in out["not_read"]) == [
        "NUMREG.VR", "SYSFRAME.SV", "TD_GUN1.TP"]
    labelled = {(os.path.basename(f["file"]), f["name"]): f.get("label") for f in out["frames"]}
    assert labelled[("SYSFRAME.VA", "UF1")] == "UB10200_FXT01"        # frame.dg beside it
    assert labelled[("TOOLDATAUB10200RBT01.LS", "UF1")] == "UB10200_FXT01"
    assert len(out["frames"]) == 128 + 4
    text = run("frames", folder).stdout
    assert "3 binary FANUC files not read (1 .sv, 1 .tp, 1 .vr)" in text
    res = run("check", folder)
    assert res.returncode == 0, res.stdout + res.stderr
    assert f"{folder / 'TD_GUN1.TP'}: not read: binary FANUC file (a TP program" in res.stdout
    assert f"{folder / 'CURPOS.DG'}: fanuc current position" in res.stdout
    assert "9 files: 6 read, 0 not read, 3 binary (not read)" in res.stdout


@needs_corpus
def test_two_fanuc_backups(tmp_path):
    old = ub_backup(tmp_path / "old")
    new = tmp_path / "new"
    shutil.copytree(old, new)
    edit(new / "SYSFRAME.VA", b"  X:  3495.600   Y:  5813.000", b"  X:  3495.900   Y:  5813.000")
    (new / "TD_GUN1.TP").write_bytes(b"\x00\x01TPBIN changed")
    (new / "NUMREG.VR").unlink()
    (new / "MAIN.TP").write_bytes(b"\x00\x04TP")
    shutil.copy(FIXTURES / "fanuc" / "program_frames.ls", new / "SET_FRAMES.LS")
    res = run("diff", old, new, "--json")
    assert res.returncode == 0, res.stderr
    d = json.loads(res.stdout)
    assert [c["name"] for c in d["changed"]] == ["UF1"] and d["errors"] == []
    added = {f["path"]: f for f in d["files_added"]}
    assert set(added) == {"MAIN.TP", "SET_FRAMES.LS"}
    assert "not_read" in added["MAIN.TP"] and "UF2" in added["SET_FRAMES.LS"]["frames"]
    (removed,) = d["files_removed"]
    assert removed["path"] == "NUMREG.VR" and "binary FANUC file" in removed["not_read"]
    changed = {f["path"]: f for f in d["files_changed"]}
    assert set(changed) == {"SYSFRAME.VA", "TD_GUN1.TP"}
    assert "binary FANUC file" in changed["TD_GUN1.TP"]["not_read"]
    assert d["files_unchanged"] == 6
    text = run("diff", old, new).stdout
    assert "~ TD_GUN1.TP: changed, not read: binary FANUC file" in text
    assert "- NUMREG.VR: file removed (not read: binary FANUC file" in text
    assert "~ SYSFRAME.VA: 1 frame changed, 0 added, 0 removed" in text
    assert run("diff", old, new, "--exit-code").returncode == 1
    assert run("diff", old, old, "--exit-code").returncode == 0


# -- git ---------------------------------------------------------------------------------
UCSIO = f"{shlex.quote(sys.executable)} -m ucsio diff"


def git(repo, *args):
    env = dict(os.environ, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@example.com",
               GIT_COMMITTER_NAME="t", GIT_COMMITTER_EMAIL="t@example.com",
               GIT_CONFIG_NOSYSTEM="1", HOME=str(repo), GIT_PAGER="cat", PAGER="cat",
               PYTHONPATH=SRC)
    env.pop("GIT_EXTERNAL_DIFF", None)
    return subprocess.run(["git", *args], cwd=repo, env=env, capture_output=True, text=True,
                          check=True).stdout


@pytest.fixture
def repo(tmp_path):
    if shutil.which("git") is None:
        pytest.skip("git is not installed")
    r = tmp_path / "backups"
    ub_backup(r / "R01")
    (r / ".gitattributes").write_text("*.va diff=ucsio\n*.VA diff=ucsio\n*.ls diff=ucsio\n"
                                      "*.LS diff=ucsio\n")
    git(r, "init", "-q", ".")
    git(r, "add", ".")
    git(r, "commit", "-q", "-m", "backup 1")
    edit(r / "R01" / "SYSFRAME.VA", b"  X:  3495.600   Y:  5813.000",
         b"  X:  3495.100   Y:  5813.000")
    edit(r / "R01" / "TOOLDATAUB10200RBT01.LS", b"PR[16,3]=770.299", b"PR[16,3]=771.299")
    return r


@needs_corpus
def test_git_external_diff_driver(repo):
    git(repo, "config", "diff.ucsio.command", UCSIO)
    out = git(repo, "diff")
    assert "ucsio diff a/R01/SYSFRAME.VA b/R01/SYSFRAME.VA" in out
    # labelled from FRAME.DG beside the file in the work tree, both sides alike
    assert '~ UF1 "UB10200_FXT01" (UFRAME): value changed' in out and "dx -0.500" in out
    assert "ucsio diff a/R01/TOOLDATAUB10200RBT01.LS b/R01/TOOLDATAUB10200RBT01.LS" in out
    assert '~ UT1 "SSW" (UTOOL): value changed' in out and "dz +1.000" in out
    assert "lines changed beyond" not in out


@needs_corpus
def test_git_textconv(repo):
    git(repo, "config", "diff.ucsio.textconv", f"{UCSIO} --textconv")
    out = git(repo, "diff")
    minus = [ln for ln in out.splitlines() if ln.startswith("-UF1 ")]
    plus = [ln for ln in out.splitlines() if ln.startswith("+UF1 ")]
    # one side is git's temporary copy, the other the work tree's file: the
    # comments of frame.dg beside only one of them must not show as a change
    assert minus == ["-UF1 UFRAME ref=world x=3495.600 y=5813.000 z=-1166.400 w=.140 p=.080 "
                     "r=-90.040 group=1 config=N U T, 0, 0, 0"]
    assert plus == [minus[0].replace("-UF1", "+UF1").replace("3495.600", "3495.100")]
    assert any(ln.startswith("-UT1 UTOOL label='SSW'") and "z=770.299" in ln
               for ln in out.splitlines())
    changed = [ln for ln in out.splitlines() if ln[:1] in "+-" and not ln.startswith(("+++", "---"))]
    assert len(changed) == 2 + 2 + 2 + 2   # UF1 and its X line; UT1 and its PR[16,3] line


# -- start-up --------------------------------------------------------------------------------
PROBE = """
import sys, io, contextlib
from ucsio.cli import main
with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
    code = main(sys.argv[1:])
print(__import__("json").dumps({"code": code, "heavy": sorted(
    m for m in ("numpy", "scipy", "lark") if m in sys.modules)}))
"""


@needs_corpus
def test_reading_listing_and_diffing_fanuc_files_stays_light(tmp_path):
    """No numpy, no scipy, and no Lark once the grammars' tables are cached
    (the first run of each grammar builds them with Lark)."""
    folder = ub_backup(tmp_path / "R01")
    other = tmp_path / "R02"
    shutil.copytree(folder, other)
    edit(other / "SYSFRAME.VA", b"  X:  3495.600", b"  X:  3495.700")
    env = dict(os.environ, PYTHONPATH=SRC, UCSIO_CACHE_DIR=str(tmp_path / "cache"))
    va, ls = folder / "SYSFRAME.VA", folder / "TOOLDATAUB10200RBT01.LS"
    runs = [["frames", va], ["frames", ls], ["frames", va], ["check", folder],
            ["diff", va, other / "SYSFRAME.VA"], ["diff", folder, other],
            ["diff", "--textconv", ls]]
    seen = []
    for args in runs:
        res = subprocess.run([sys.executable, "-c", PROBE, *map(str, args)], env=env,
                             capture_output=True, text=True)
        seen.append(json.loads(res.stdout.strip().splitlines()[-1]))
    assert [s["code"] for s in seen] == [0] * len(runs)
    assert all(not set(s["heavy"]) & {"numpy", "scipy"} for s in seen), seen
    # the grammars the probes read (PYTHONPATH=src: the checkout's, even where
    # the test itself runs from an installed wheel, which ships tables)
    where = subprocess.run([sys.executable, "-c", "from ucsio.parsing import grammar; "
                            "print(grammar.grammar_dir())"], env=env, capture_output=True,
                           text=True, check=True).stdout.strip()
    if any(Path(where).glob("*.tables.marshal")):     # a wheel ships them
        assert all(s["heavy"] == [] for s in seen), seen
    else:
        assert [s["heavy"] for s in seen] == [["lark"], ["lark"]] + [[]] * 5, seen


# -- one frame against a measurement ----------------------------------------------------------
def test_one_fanuc_frame_against_a_measurement(tmp_path):
    sol = tmp_path / "sol.json"
    # the measured UF1 of sysframe_comment.va, 0.4 mm further in X: SPEC's a, b, c = R, P, W
    sol.write_text(json.dumps({"frame": {"x": 1200.9, "y": -300.25, "z": 0.75, "a": 90,
                                         "b": -0.08, "c": 0.14}}))
    va = FIXTURES / "fanuc" / "sysframe_comment.va"
    res = run("diff", va, "--frame", "fixture_a", "--measured", sol)
    assert res.returncode == 0, res.stderr
    lines = res.stdout.splitlines()
    assert lines[0].startswith("UF1 (FIXTURE_A)  UFRAME  ")
    assert lines[1].split() == ["x", "y", "z", "w", "p", "r"]
    assert lines[3].split()[4:] == ["0.1400", "-0.0800", "90.0000"]
    d = json.loads(run("diff", va, "--frame", "UF1", "--measured", sol, "--json").stdout)
    assert d["vendor"] == "fanuc" and d["dx"] == pytest.approx(0.4)
    assert d["angle"] == pytest.approx(0, abs=1e-9) and (d["dw"], d["dp"], d["dr"]) == \
        (d["dc"], d["db"], d["da"])
    # the positions taught in UF1: the /POS of the .ls beside it and below (tests/
    # test_fanuc_taught.py checks the numbers); a broken program there is a warning
    res = run("diff", va, "--frame", "UF1", "--measured", sol, "--points")
    assert res.returncode == 0 and "taught points in UF1" in res.stdout
    assert "broken_position.ls" in res.stderr and "its points are not counted" in res.stderr


@needs_corpus
def test_a_zipped_fanuc_backup_is_read_in_place_with_its_labels(tmp_path):
    import zipfile
    folder = ub_backup(tmp_path / "UB10200_RBT01")
    archive = tmp_path / "UB10200.zip"
    with zipfile.ZipFile(archive, "w") as zf:
        for p in sorted(folder.iterdir()):
            zf.write(p, "UB10200_RBT01/" + p.name)
    out = json.loads(run("frames", archive, "--json").stdout)
    member = f"{archive}!UB10200_RBT01/SYSFRAME.VA"
    uf1 = [f for f in out["frames"] if f["file"] == member and f["name"] == "UF1"][0]
    assert uf1["label"] == "UB10200_FXT01"                  # FRAME.DG beside it in the archive
    assert len(out["not_read"]) == 3 and out["errors"] == []
    res = run("diff", archive, folder, "--exit-code")
    assert res.returncode == 0 and "no difference" in res.stdout
