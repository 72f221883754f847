"""Whole backups (SPEC: Many files and whole backups; issue 11 points 1-3):
folders and .zip archives read in place, one bad file never hiding the rest,
and the backup-to-backup review. Every test drives the real command line on
backup trees built from the real corpus files."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import zipfile

import pytest

from conftest import CORPUS, FIXTURES, ROOT

SRC = str(ROOT / "src")
needs_corpus = pytest.mark.skipif(not CORPUS.is_dir(), reason="the shared corpus is absent")


def run(*args, cwd=None):
    env = dict(os.environ, PYTHONPATH=SRC)
    env.pop("NO_COLOR", None)
    return subprocess.run([sys.executable, "-m", "ucsio", *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, env=env)


def abb_backup(root, small: bool = False):
    """An ABB backup tree: every ABB corpus file (``small``: those under 12 KB,
    for the slow full-grammar check) under RAPID/TASK1/PROGMOD, plus the
    encrypted module every real backup has."""
    prog = root / "RAPID" / "TASK1" / "PROGMOD"
    prog.mkdir(parents=True)
    files = sorted(p for p in (CORPUS / "abb").iterdir()
                   if not small or p.stat().st_size < 12_000)
    for p in files:
        shutil.copy(p, prog / p.name)
    shutil.copy(FIXTURES / "abb" / "encrypted.mod", prog / "TuneMasterLib.mod")
    (root / "BACKINFO").mkdir()
    (root / "BACKINFO" / "backinfo.txt").write_text("not a controller file\n")
    return [prog / p.name for p in files]


def kuka_backup(root):
    """A KUKA KRC tree: a real $config.dat and program .dat files."""
    system = root / "KRC" / "R1" / "System"
    program = root / "KRC" / "R1" / "Program"
    system.mkdir(parents=True)
    program.mkdir(parents=True)
    shutil.copy(CORPUS / "kuka" / "Aleynikovich__Zinkerreka__KRC__R1__System__$config.dat",
                system / "$config.dat")
    shutil.copy(CORPUS / "kuka" / "Aleynikovich__Zinkerreka__KRC__R1__Program__Work__C1_pickConveyorBP.dat",
                program / "C1_pickConveyorBP.dat")
    shutil.copy(CORPUS / "kuka" / "HugoDanielson__ChinaMilling__KRC__R1__Program__KukaMiling__Dat__fFrame.dat",
                program / "fFrame.dat")
    (program / "fFrame.src").write_text("DEF fFrame()\nEND\n")   # no frames: not read
    return root


def zip_tree(folder, archive):
    with zipfile.ZipFile(archive, "w", zipfile.ZIP_DEFLATED) as zf:
        for p in sorted(folder.rglob("*")):
            if p.is_file():
                zf.write(p, p.relative_to(folder).as_posix())
    return archive


# -------------------------------------------------------------- folders and archives

@needs_corpus
def test_check_a_folder_with_an_encrypted_module_reports_every_file(tmp_path):
    files = abb_backup(tmp_path / "bk", small=True)
    assert len(files) >= 8
    res = run("check", tmp_path / "bk", "--json")
    assert res.returncode == 2
    out = json.loads(res.stdout)
    assert sorted(r["file"] for r in out["files"]) == sorted(map(str, files))
    assert all(r["round_trip"] for r in out["files"])
    (err,) = out["errors"]
    assert err["file"].endswith("TuneMasterLib.mod") and "encrypted" in err["message"]
    assert out["ok"] is False
    assert "TuneMasterLib.mod" in res.stderr and "1 file could not be read" in res.stderr
    # the text form lists every file too, the bad one with its error
    res = run("check", tmp_path / "bk")
    assert res.returncode == 2
    for f in files:
        assert f"{f}: abb, " in res.stdout
    assert "TuneMasterLib.mod: NOT READ: binary or encrypted" in res.stdout
    assert f"{len(files) + 1} files: {len(files)} read, 1 not read" in res.stdout


@needs_corpus
def test_shell_glob_with_one_bad_file_lists_the_others(tmp_path):
    files = abb_backup(tmp_path / "bk")
    bad = files[0].parent / "TuneMasterLib.mod"
    res = run("frames", *files[:3], bad, *files[3:6], "--json")
    assert res.returncode == 2
    out = json.loads(res.stdout)
    listed = {f["file"] for f in out["frames"]}
    from ucsio import load
    with_frames = {str(f) for f in files[:6] if load(f).frames}
    assert listed == with_frames and len(with_frames) >= 4
    assert [e["file"] for e in out["errors"]] == [str(bad)]


@needs_corpus
def test_frames_of_a_folder_are_the_frames_of_its_files(tmp_path):
    files = abb_backup(tmp_path / "bk")
    kuka_backup(tmp_path / "bk")
    res = run("frames", tmp_path / "bk", "--json")
    assert res.returncode == 2                      # the encrypted module
    whole = json.loads(res.stdout)
    assert [e["file"].endswith("TuneMasterLib.mod") for e in whole["errors"]] == [True]
    from ucsio import load
    from ucsio.review.unset import as_dict     # the frame's keys and "set"
    singles = []                                    # each file on its own, in process
    for f in sorted((tmp_path / "bk").rglob("*")):
        if f.suffix.lower() in (".mod", ".sys", ".prg", ".modx", ".dat") and f.name != "TuneMasterLib.mod":
            cf = load(f)
            singles.extend(json.loads(json.dumps(as_dict(x, cf))) for x in cf.frames)
    assert sorted(json.dumps(x, sort_keys=True) for x in whole["frames"]) == \
        sorted(json.dumps(x, sort_keys=True) for x in singles)
    assert not any(f["file"].endswith((".src", ".txt")) for f in whole["frames"])
    read = whole["files"]                        # every file read, with frames or without
    assert len(read) == len(files) + 3 and not any(f.endswith("TuneMasterLib.mod") for f in read)
    assert len(files) > 30 and len(whole["frames"]) > 100


@needs_corpus
def test_zip_archive_is_read_in_place_with_member_names(tmp_path):
    tree = kuka_backup(tmp_path / "tree")
    archive = zip_tree(tree, tmp_path / "R1_archive.zip")
    before = sorted(p.name for p in tmp_path.iterdir())
    res = run("frames", archive, "--json")
    assert res.returncode == 0, res.stderr
    frames = json.loads(res.stdout)["frames"]
    assert sorted(p.name for p in tmp_path.iterdir()) == before       # nothing extracted
    member = f"{archive}!KRC/R1/System/$config.dat"
    ours = [f for f in frames if f["file"] == member]
    direct = json.loads(run("frames", tree / "KRC/R1/System/$config.dat", "--json").stdout)["frames"]
    assert len(ours) == len(direct) > 40
    for a, b in zip(ours, direct):
        assert {k: v for k, v in a.items() if k != "file"} == {k: v for k, v in b.items() if k != "file"}
    assert {f["file"] for f in frames} >= {member, f"{archive}!KRC/R1/Program/fFrame.dat"}
    # the member name printed is accepted back as an input
    res = run("frames", member, "--json")
    assert res.returncode == 0 and json.loads(res.stdout)["frames"] == ours
    res = run("check", archive)
    assert res.returncode in (0, 1) and f"{member}: kuka," in res.stdout


@needs_corpus
def test_patch_refuses_an_archive_member(tmp_path):
    archive = zip_tree(kuka_backup(tmp_path / "tree"), tmp_path / "a.zip")
    before = archive.read_bytes()
    for target in (f"{archive}!KRC/R1/System/$config.dat", archive):
        res = run("patch", target, "--frame", "BASE_DATA[1]", "--set", "1,2,3,0,0,0", "--in-place")
        assert res.returncode == 2 and res.stdout == ""
        assert "archive" in res.stderr and "extract" in res.stderr
        assert res.stderr.count("\n") == 1
    assert archive.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.zip", "tree"]


def test_broken_archive_and_missing_path_are_listed_not_fatal(tmp_path):
    broken = tmp_path / "broken.zip"
    broken.write_bytes(b"PK\x03\x04 this is not a zip")
    good = FIXTURES / "abb" / "variants.mod"
    res = run("frames", broken, tmp_path / "missing.mod", good, "--json")
    assert res.returncode == 2
    out = json.loads(res.stdout)
    assert {f["file"] for f in out["frames"]} == {str(good)}
    assert [e["file"] for e in out["errors"]] == [str(broken), str(tmp_path / "missing.mod")]
    assert "not a readable zip archive" in out["errors"][0]["message"]


def test_a_single_bad_file_is_one_json_error(tmp_path):
    res = run("frames", FIXTURES / "abb" / "encrypted.mod", "--json")
    assert res.returncode == 2
    err = json.loads(res.stdout)["error"]
    assert err["file"].endswith("encrypted.mod") and "encrypted" in err["message"]


# -------------------------------------------------------------- backup-to-backup review

def _edit(path, old: bytes, new: bytes):
    data = path.read_bytes()
    assert old in data
    path.write_bytes(data.replace(old, new, 1))


@pytest.fixture(scope="module")
def two_backups(tmp_path_factory):
    """OLD and NEW backups of a cell: in NEW a base and a work object moved,
    one module removed, one added, a comment edited, and the encrypted module
    unchanged (no error: equal bytes are not parsed)."""
    if not CORPUS.is_dir():
        pytest.skip("the shared corpus is absent")
    tmp_path = tmp_path_factory.mktemp("backups")
    old = tmp_path / "old"
    abb_backup(old)
    kuka_backup(old)
    new = tmp_path / "new"
    shutil.copytree(old, new)
    prog = new / "RAPID" / "TASK1" / "PROGMOD"
    res = run("patch", new / "KRC/R1/System/$config.dat", "--frame", "BASE_DATA[1]",
              "--set", "1000.5,0,500,90,0,0", "--in-place")
    assert res.returncode == 0, res.stderr
    mbuffer = prog / "SDEBEUL__Kraker1__RAPID__TASK1__PROGMOD__mBuffer.mod"
    res = run("patch", mbuffer, "--frame", "Wobj_Buffer2", "--set", "2895,12,0,0,0,0", "--in-place")
    assert res.returncode == 0, res.stderr
    (prog / "wsierrad__Lab5_Robotica__Module1_2_Tarea1.mod").unlink()
    shutil.copy(FIXTURES / "abb" / "variants.mod", prog / "Fixture.mod")
    spindle = prog / "SDEBEUL__Kraker1__RAPID__TASK1__SYSMOD__mSettings_Spindle.sys"
    _edit(spindle, b"!", b"! reviewed")
    return old, new


def test_backup_diff_lists_files_and_frames(two_backups):
    old, new = two_backups
    res = run("diff", old, new, "--json")
    assert res.returncode == 0, res.stderr
    d = json.loads(res.stdout)
    assert [f["path"] for f in d["files_added"]] == ["RAPID/TASK1/PROGMOD/Fixture.mod"]
    assert "tools{1}" in d["files_added"][0]["frames"]
    assert [f["path"] for f in d["files_removed"]] == \
        ["RAPID/TASK1/PROGMOD/wsierrad__Lab5_Robotica__Module1_2_Tarea1.mod"]
    changed = {(c["path"], c["name"]): c for c in d["changed"]}
    assert set(changed) == {("KRC/R1/System/$config.dat", "BASE_DATA[1]"),
                            ("RAPID/TASK1/PROGMOD/SDEBEUL__Kraker1__RAPID__TASK1__PROGMOD__mBuffer.mod",
                             "Wobj_Buffer2")}
    base = changed[("KRC/R1/System/$config.dat", "BASE_DATA[1]")]
    assert base["dx"] == pytest.approx(1000.5 - base["old"]["x"])
    wobj = [c for c in d["changed"] if c["name"] == "Wobj_Buffer2"][0]
    assert wobj["dy"] == pytest.approx(12.0) and wobj["dx"] == pytest.approx(0.0)
    assert d["added"] == [] and d["removed"] == [] and d["errors"] == []
    by_path = {f["path"]: f for f in d["files_changed"]}
    spindle = by_path["RAPID/TASK1/PROGMOD/SDEBEUL__Kraker1__RAPID__TASK1__SYSMOD__mSettings_Spindle.sys"]
    assert spindle["frames_changed"] == 0 and spindle["other_lines"] is True
    assert len(by_path) == 3
    assert d["files_unchanged"] > 30      # the encrypted module among them, unparsed


def test_backup_diff_text_reads_in_ten_seconds(two_backups):
    old, new = two_backups
    res = run("diff", old, new)
    assert res.returncode == 0 and res.stderr == ""
    lines = res.stdout.splitlines()
    assert lines[0] == f"ucsio diff {old} {new}"
    assert lines[1].startswith("  files:  3 changed, 1 added, 1 removed, ")
    assert lines[2] == "  frames: 2 changed, 0 added, 0 removed (in files present in both)"
    assert "+ RAPID/TASK1/PROGMOD/Fixture.mod: file added (12 frames: " in res.stdout
    assert "- RAPID/TASK1/PROGMOD/wsierrad__Lab5_Robotica__Module1_2_Tarea1.mod: file removed" in res.stdout
    assert "~ KRC/R1/System/$config.dat: 1 frame changed, 0 added, 0 removed" in res.stdout
    assert '    ~ BASE_DATA[1] "pickBP" (BASE_DATA): value changed' in res.stdout
    assert "lines changed, no frame" in res.stdout
    assert "\033[" not in res.stdout                       # piped: no colour


def test_backup_diff_exit_code(two_backups, tmp_path):
    old, new = two_backups
    assert run("diff", old, new, "--exit-code").returncode == 1
    assert run("diff", old, old, "--exit-code").returncode == 0
    assert run("diff", old, new).returncode == 0           # as git: only --exit-code says
    # an archive of OLD against the folder OLD: nothing differs
    archive = zip_tree(old, tmp_path / "old.zip")
    res = run("diff", archive, old, "--exit-code")
    assert res.returncode == 0 and "no difference" in res.stdout
    res = run("diff", archive, new, "--exit-code", "--json")
    assert res.returncode == 1 and len(json.loads(res.stdout)["changed"]) == 2
    # two single files: --exit-code too
    f_old, f_new = old / "KRC/R1/System/$config.dat", new / "KRC/R1/System/$config.dat"
    assert run("diff", f_old, f_new, "--exit-code").returncode == 1
    assert run("diff", f_old, f_old, "--exit-code").returncode == 0


def test_backup_diff_pairs_paths_case_insensitively(two_backups, tmp_path):
    old, new = two_backups
    new = shutil.copytree(new, tmp_path / "new")
    (new / "KRC").rename(new / "krc_tmp")
    (new / "krc_tmp").rename(new / "Krc")
    d = json.loads(run("diff", old, new, "--json").stdout)
    assert d["files_added"] == [f for f in d["files_added"] if not f["path"].lower().startswith("krc")]
    assert any(c["name"] == "BASE_DATA[1]" for c in d["changed"])


def test_backup_diff_with_a_changed_unreadable_file_exits_2(two_backups, tmp_path):
    old, new = two_backups
    new = shutil.copytree(new, tmp_path / "new")
    enc = new / "RAPID" / "TASK1" / "PROGMOD" / "TuneMasterLib.mod"
    enc.write_bytes(enc.read_bytes() + b"\x00\x01")
    res = run("diff", old, new, "--json")
    assert res.returncode == 2
    d = json.loads(res.stdout)
    assert [e["file"].endswith("TuneMasterLib.mod") for e in d["errors"]] == [True]
    assert len(d["changed"]) == 2                          # the rest is still reported
    assert "TuneMasterLib.mod" in res.stderr


def test_diff_of_a_folder_and_a_file_is_a_usage_error(tmp_path):
    res = run("diff", tmp_path, FIXTURES / "abb" / "variants.mod")
    assert res.returncode == 2 and res.stderr.count("\n") == 1
    assert f"{tmp_path} is a backup" in res.stderr and "two files or two backups" in res.stderr


# -------------------------------------------------------------- start-up

PROBE = """
import sys, io, contextlib
from ucsio.cli import main
with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
    code = main(sys.argv[1:])
print(__import__("json").dumps({"code": code,
      "heavy": sorted(m for m in ("numpy", "scipy") if m in sys.modules)}))
"""


def test_backup_commands_stay_light(tmp_path):
    """Reading folders and archives and diffing backups only reads and
    lists: no numpy, no scipy; zipfile is imported where an archive is read."""
    tree = tmp_path / "tree"
    (tree / "RAPID").mkdir(parents=True)
    shutil.copy(FIXTURES / "abb" / "variants.mod", tree / "RAPID" / "variants.mod")
    archive = zip_tree(tree, tmp_path / "a.zip")
    env = dict(os.environ, PYTHONPATH=SRC)
    for args in (["frames", tree], ["check", archive], ["diff", tree, archive, "--exit-code"]):
        res = subprocess.run([sys.executable, "-c", PROBE, *map(str, args)], env=env,
                             capture_output=True, text=True, check=True)
        out = json.loads(res.stdout.strip().splitlines()[-1])
        assert out == {"code": 0, "heavy": []}, (args, out)
    source = (ROOT / "src" / "ucsio" / "parsing" / "sources.py").read_text()
    assert "\nimport zipfile" not in source and "    import zipfile" in source


def test_empty_folder_or_archive_is_named_not_silently_empty(tmp_path):
    (tmp_path / "empty").mkdir()
    with zipfile.ZipFile(tmp_path / "docs.zip", "w") as zf:
        zf.writestr("readme.txt", "no controller files here")
    for target in (tmp_path / "empty", tmp_path / "docs.zip"):
        res = run("frames", target)
        assert res.returncode == 2 and "no controller files" in res.stderr
    res = run("diff", tmp_path / "empty", tmp_path / "docs.zip")
    assert res.returncode == 2 and res.stderr.count("\n") == 1


def test_an_archive_of_the_backup_folder_pairs_with_its_contents(two_backups, tmp_path):
    """A zip of the backup folder itself (everything under R1_BACKUP/) against
    the folder's contents: the wrapping folder is set aside when pairing."""
    old, new = two_backups
    archive = tmp_path / "R1_BACKUP.zip"
    with zipfile.ZipFile(archive, "w") as zf:
        for p in sorted(old.rglob("*")):
            if p.is_file():
                zf.write(p, "R1_BACKUP/" + p.relative_to(old).as_posix())
    res = run("diff", archive, old, "--exit-code")
    assert res.returncode == 0 and "no difference" in res.stdout
    d = json.loads(run("diff", archive, new, "--json").stdout)
    assert len(d["changed"]) == 2 and len(d["files_added"]) == 1 and len(d["files_removed"]) == 1
    assert d["files_added"][0]["path"] == "RAPID/TASK1/PROGMOD/Fixture.mod"
