"""Files ucsio recognises and does not read (issue 24 points 3 and 8).

- Another controller's file named on its own (Yaskawa's
  SYSTEM.SYS whose suffix is ABB's, a .CND other than UFRAME.CND and
  TOOL.CND, which ucsio reads (as it reads jobs, RBCALIB.DAT and VAR.DAT), a Stäubli
  .dtx, a Universal Robots program .urp: its .installation is read,
  tests/test_ur.py) is refused with what it is, exit 2, never "syntax
  error at 1:1"; in a folder it is listed as not read.
- A FANUC backup's own .DAT files (ORDERFIL.DAT, UPDATES.DAT:
  fixtures/fanuc/backup_data, written in their style) are not KUKA data: in
  a folder with SYSFRAME.VA and .LS programs they are listed as not read,
  never refused; a .dat whose text is KRL is read as KRL wherever it is.
"""
from __future__ import annotations

import json
import shutil
import zipfile

import pytest

from conftest import CORPUS, FIXTURES, corpus_file
from ucsio.cli import main

DATA = FIXTURES / "fanuc" / "backup_data"
UB = "irbzavalagit__UB10200_RBT01__"
KRL_DAT = b"&ACCESS RVP\r\nDEFDAT MYDATA\r\nDECL FRAME F1={X 1.0,Y 2.0,Z 3.0,A 0,B 0,C 0}\r\nENDDAT\r\n"
# (Yaskawa's UFRAME.CND, TOOL.CND, jobs, RBCALIB.DAT and VAR.DAT are read: tests/test_yaskawa*.py;
# Stäubli's .dtx: tests/test_staubli.py; Universal Robots' .installation: tests/test_ur.py)
FOREIGN = sorted(p for vendor in ("yaskawa", "staubli", "ur") if (CORPUS / vendor).is_dir()
                 for p in (CORPUS / vendor).iterdir()
                 if p.suffix not in (".md", ".tsv")
                 and ".CND" not in p.name.upper() and ".JBI" not in p.name.upper()
                 and "RBCALIB.DAT" not in p.name.upper()
                 and p.suffix.lower() not in (".dtx", ".installation")
                 and not p.name.upper().endswith("VAR.DAT"))
# what a refusal says of the vendor's files
NOT_READ = {"yaskawa": "does not read this Yaskawa file yet (of Yaskawa's files it reads "
                       "UFRAME.CND, TOOL.CND, RBCALIB.DAT, VAR.DAT and jobs (.JBI))",
            "staubli": "does not read Stäubli files yet",
            "ur": "does not read this Universal Robots file yet (of Universal Robots's files it "
                  "reads installations (.installation))"}


def cli(capsys, *args):
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("path", FOREIGN or [pytest.param(None, marks=pytest.mark.skip(
    reason="the shared corpus is absent"))], ids=lambda p: p and p.name[-40:])
def test_a_corpus_file_of_another_controller_says_what_it_is(capsys, path):
    code, out, err = cli(capsys, "frames", path)
    assert code == 2 and out == ""
    assert "does not read" in err and "syntax error" not in err, err
    assert NOT_READ[path.parent.name] in err


@pytest.mark.parametrize("name, text, what", [
    # the suffixes are ABB's and KUKA's: the first line says whose they are
    ("SYSTEM.SYS", "/SYSTEM 8\r\n//DATE      : 2023/09/19 17:45:46\r\n", "Yaskawa Motoman file"),
    # a condition file other than UFRAME.CND and TOOL.CND: its first line says so
    ("ARCSRT.CND", "//ARCSRT 1\r\n///NAME\r\n", "Yaskawa Motoman file"),
])
def test_another_controllers_file_named_on_its_own(tmp_path, capsys, name, text, what):
    path = tmp_path / name
    path.write_bytes(text.encode())
    for command in ("frames", "check"):
        code, out, err = cli(capsys, command, path)
        assert code == 2, (command, out, err)
        assert f"{path}: a {what}" in err and NOT_READ["yaskawa"] in err
        assert "1:1" not in err


def test_another_controllers_files_in_a_folder_are_listed_not_read(tmp_path, capsys):
    (tmp_path / "SYSTEM.SYS").write_bytes(b"/SYSTEM 8\r\n")
    (tmp_path / "VAR.DAT").write_bytes(b"//VAR\r\n///P\r\n\"UNUSED\"\r\n")
    (tmp_path / "base.dat").write_bytes(KRL_DAT)
    code, out, err = cli(capsys, "check", tmp_path, "--json")
    doc = json.loads(out)
    assert code == 0, err
    assert {r["file"].rpartition("/")[2] for r in doc["not_read"]} == {"SYSTEM.SYS"}
    # VAR.DAT is read as Yaskawa's by its first line, base.dat as KUKA's
    assert {r["file"].rpartition("/")[2]: r["vendor"] for r in doc["files"]} == \
        {"VAR.DAT": "yaskawa", "base.dat": "kuka"}
    assert all("Yaskawa" in r["reason"] for r in doc["not_read"]) and doc["errors"] == []


def fanuc_backup(folder):
    """A FANUC backup folder: SYSFRAME.VA, a program, and its .DAT files."""
    folder.mkdir(parents=True)
    shutil.copy(corpus_file("fanuc", UB + "sysframe.va"), folder / "SYSFRAME.VA")
    shutil.copy(corpus_file("fanuc", UB + "td_gun1.ls"), folder / "TD_GUN1.LS")
    for name in ("ORDERFIL.DAT", "UPDATES.DAT"):
        shutil.copy(DATA / name, folder / name)
    return folder


def test_a_fanuc_backups_dat_files_are_listed_not_refused(tmp_path, capsys):
    folder = fanuc_backup(tmp_path / "backup")
    (folder / "BINARY.DAT").write_bytes(b"\x00\x01\x02DAT" * 20)
    code, out, err = cli(capsys, "check", folder)
    assert code == 0, out + err
    for name in ("ORDERFIL.DAT", "UPDATES.DAT", "BINARY.DAT"):
        assert f"{folder / name}: not read: a FANUC backup's data file" in out
    code, out, err = cli(capsys, "frames", folder, "--json")
    assert code == 0 and json.loads(out)["errors"] == []
    assert len(json.loads(out)["not_read"]) == 3


def test_a_fanuc_backups_dat_files_in_an_archive(tmp_path, capsys):
    folder = fanuc_backup(tmp_path / "backup")
    archive = tmp_path / "backup.zip"
    with zipfile.ZipFile(archive, "w") as zf:
        for p in folder.iterdir():
            zf.write(p, f"RBT01/{p.name}")
        zf.writestr("other/ORDERFIL.DAT", KRL_DAT)    # no FANUC backup there: KRL, read
    code, out, err = cli(capsys, "check", archive, "--json")
    doc = json.loads(out)
    assert code == 0, out + err
    assert sorted(r["file"].rpartition("/")[2] for r in doc["not_read"]) == [
        "ORDERFIL.DAT", "UPDATES.DAT"]
    assert any(r["file"].endswith("other/ORDERFIL.DAT") for r in doc["files"])


def test_a_dat_is_decided_by_its_text_and_its_folder_not_its_suffix(tmp_path, capsys):
    folder = fanuc_backup(tmp_path / "backup")
    # named on its own, beside SYSFRAME.VA and .LS: it says what it is
    code, out, err = cli(capsys, "frames", folder / "ORDERFIL.DAT")
    assert code == 2 and "a FANUC backup's data file" in err and "syntax error" not in err
    # KRL text is KUKA data, wherever it stands
    (folder / "MYDATA.DAT").write_bytes(KRL_DAT)
    code, out, err = cli(capsys, "frames", folder / "MYDATA.DAT")
    assert code == 0 and "F1" in out
    # the same ORDERFIL.DAT with no FANUC backup around it is read as KUKA data, and refused
    alone = tmp_path / "alone"
    alone.mkdir()
    shutil.copy(DATA / "ORDERFIL.DAT", alone / "ORDERFIL.DAT")
    code, out, err = cli(capsys, "frames", alone / "ORDERFIL.DAT")
    assert code == 2 and "FANUC" not in err and "syntax error" in err


def test_a_universal_robots_program_is_refused_with_what_ucsio_reads_of_theirs(tmp_path, capsys):
    """A .urp (gzip, as the .installation beside it) is a program: refused,
    naming the installation as what ucsio reads."""
    path = tmp_path / "weld.urp"
    path.write_bytes(bytes.fromhex("1f8b0800000000000000") + b"\x03\x00" + bytes(8))
    code, out, err = cli(capsys, "frames", path)
    assert code == 2 and out == "" and NOT_READ["ur"] in err, err
