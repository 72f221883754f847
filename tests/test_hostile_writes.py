"""What ucsio writes, on hostile targets and values (issue 24, points 12-14, 16).

One rule in the shared writer (files.atomic_write) for every file ucsio
writes: a target that exists and is not a regular file (a named pipe, a
device) is refused, never replaced by a file; a file that is replaced keeps
its mode; and the written bytes read back through the same checks as the
input."""
from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest

from conftest import FIXTURES
from ucsio.cli import main
from ucsio.errors import UcsioError
from ucsio.files import atomic_write, write_target

KUKA_CSV = FIXTURES / "measurements" / "kuka_base3.csv"
KUKA = FIXTURES / "kuka" / "cell_config.dat"
CELL = FIXTURES / "patch" / "cell.mod"
TCP = "--tcp=-20.67,89.73,33.44"


@pytest.fixture(scope="module")
def solution(tmp_path_factory) -> Path:
    sol = tmp_path_factory.mktemp("sol") / "S.json"
    assert main(["solve", str(KUKA_CSV), TCP, "-o", str(sol)]) == 0
    return sol


def writers(solution: Path, tmp_path: Path, out: Path) -> dict:
    """Each command that writes a file, aimed at ``out``."""
    manifest = tmp_path / "m.toml"
    manifest.write_text(f'[[entry]]\nname = "r1"\nmeasurement = "{KUKA_CSV}"\n'
                        f'controller = "{KUKA}"\nframe = "BASE_DATA[3]"\n'
                        'tcp = [-20.67, 89.73, 33.44]\n')
    return {
        "patch": ["patch", str(CELL), "--frame", "wobjTable", "--set", "1,2,3,4,5,6",
                  "-o", str(out)],
        "program": ["program", str(solution), "--frame", "UF3", "--pr", "90", "-o", str(out)],
        "solve": ["solve", str(KUKA_CSV), TCP, "-o", str(out)],
        "batch --csv": ["batch", str(manifest), "--csv", str(out)],
        "batch --report": ["batch", str(manifest), "--report", str(out)],
    }


COMMANDS = ["patch", "program", "solve", "batch --csv", "batch --report"]


# ------------------------------------------------------------------ point 12

@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes on this OS")
@pytest.mark.parametrize("command", COMMANDS)
def test_a_pipe_as_the_output_is_refused_and_stays_a_pipe(solution, tmp_path, capsys, command):
    out = tmp_path / "out"
    os.mkfifo(out)
    rc = main(writers(solution, tmp_path, out)[command])
    err = capsys.readouterr().err
    assert rc == 2 and "not a regular file (a named pipe (FIFO))" in err, err
    assert str(out) in err and err.count("\n") == 1
    assert stat.S_ISFIFO(os.lstat(out).st_mode)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.toml", "out"]   # no temporary


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes on this OS")
def test_a_link_to_a_pipe_is_refused_too(tmp_path):
    os.mkfifo(tmp_path / "pipe")
    (tmp_path / "out.json").symlink_to("pipe")
    with pytest.raises(UcsioError, match="not a regular file"):
        atomic_write(tmp_path / "out.json", b"{}")
    assert stat.S_ISFIFO(os.lstat(tmp_path / "pipe").st_mode)


def test_a_device_node_is_never_a_target():
    """Only asked, never written: the suite may run as root, where a broken
    rule would replace the machine's /dev/null."""
    if not os.path.exists("/dev/null"):
        pytest.skip("no /dev/null")
    with pytest.raises(UcsioError, match=r"not a regular file \(a character device\)"):
        write_target("/dev/null")


# ------------------------------------------------------------------ point 16

@pytest.mark.parametrize("command", ["patch", "program", "solve", "batch --csv"])
def test_a_replaced_file_keeps_its_mode(solution, tmp_path, command):
    out = tmp_path / "out"
    out.write_bytes(b"an older result")
    os.chmod(out, 0o444)
    assert main(writers(solution, tmp_path, out)[command]) in (0, 1)
    assert out.read_bytes() != b"an older result"
    assert stat.S_IMODE(os.stat(out).st_mode) == 0o444


def test_a_new_file_gets_the_usual_mode_and_a_replaced_one_its_own(tmp_path):
    umask = os.umask(0o022)
    try:
        atomic_write(tmp_path / "new.csv", b"a")
        assert stat.S_IMODE(os.stat(tmp_path / "new.csv").st_mode) == 0o644
        os.chmod(tmp_path / "new.csv", 0o600)
        atomic_write(tmp_path / "new.csv", b"b", mode=0o666)    # mode: a new file's only
        assert stat.S_IMODE(os.stat(tmp_path / "new.csv").st_mode) == 0o600
    finally:
        os.umask(umask)


# ------------------------------------------------------------------ point 14

def _module_with_a_nul_at(tmp_path: Path, pad_lines: int) -> Path:
    """cell.mod with ``pad_lines`` comment lines, then a NUL in a comment,
    before ENDMODULE: past the first 4,096 bytes for 500 lines."""
    text = CELL.read_bytes()
    end = text.rindex(b"ENDMODULE")
    body = text[:end] + b"    ! pad\n" * pad_lines + b"    ! a NUL \x00 in a comment\n" + text[end:]
    out = tmp_path / "cell.mod"
    out.write_bytes(body)
    return out


@pytest.mark.parametrize("pad_lines", [0, 500])
def test_a_nul_anywhere_is_refused_at_its_line(tmp_path, capsys, pad_lines):
    """The sniff looks at every byte, so a file that reads is one whose
    patched copy reads too (the edits only move bytes, never add a NUL)."""
    mod = _module_with_a_nul_at(tmp_path, pad_lines)
    assert (mod.stat().st_size > 4096) == (pad_lines == 500)
    line = CELL.read_bytes()[:CELL.read_bytes().rindex(b"ENDMODULE")].count(b"\n") \
        + pad_lines + 1
    for args in (["frames", str(mod)], ["check", str(mod)],
                 ["patch", str(mod), "--frame", "wobjTable", "--set", "1,2,3,4,5,6",
                  "-o", str(tmp_path / "out.mod")]):
        assert main(args) == 2
        err = capsys.readouterr().err
        assert f"{mod}:{line}:13: binary or encrypted file (byte 0x00 here)" in err, err
        assert err.count("\n") == 1
    assert not (tmp_path / "out.mod").exists()


# ------------------------------------------------------------------ point 13

FANUC_PROGRAM = FIXTURES / "fanuc" / "program_patch.ls"


def _check_says(tmp_path, capsys, text: str) -> str:
    """What ``check`` prints for a program holding ``text``."""
    f = tmp_path / "CHECKED.LS"
    f.write_bytes(text.encode())
    assert main(["check", str(f)]) == 1
    return capsys.readouterr().out


def _check_refuses(tmp_path, capsys, text: str) -> str:
    """The error ``check`` gives for a program holding ``text``."""
    f = tmp_path / "CHECKED.LS"
    f.write_bytes(text.encode())
    assert main(["check", str(f)]) == 2
    return capsys.readouterr().err


# 2e6 a REAL holds and check flags (a lint); 1e308 no REAL holds, and check
# refuses the file (the reader's error): the patch gives the same reason
@pytest.mark.parametrize("x, reason, check_says", [
    ("2e6", "UF1: X 2e+06 mm is 1 km or more from the origin (out-of-range)",
     ":11:17: warning: out-of-range: UF1: X 2e+06 mm is 1 km or more from the origin"),
    ("1e308", "UF1: number 100000000000000001097906362944 is out of range for a FANUC REAL "
     "(float32)", ":11:17: number 100000000000000001097906362944 is out of range for a FANUC "
     "REAL (float32)")])
def test_patch_refuses_a_fanuc_value_check_would_flag(tmp_path, capsys, x, reason, check_says):
    prog = tmp_path / "P.LS"
    prog.write_bytes(FANUC_PROGRAM.read_bytes())
    for args in (["-o", str(tmp_path / "out.ls")], ["--in-place"]):
        rc = main(["patch", str(prog), "--frame", "UF1", "--set", f"{x},0,0,0,0,0", *args])
        err = capsys.readouterr().err
        assert rc == 2 and err.count("\n") == 1, err
        assert f"{prog}:11:17: {reason}: the controller cannot hold" in err
    assert prog.read_bytes() == FANUC_PROGRAM.read_bytes()
    assert not (tmp_path / "out.ls").exists()
    # check's own words for the same value in the same place
    text = FANUC_PROGRAM.read_bytes().decode().replace("PR[30,1]=1200.000",
                                                       f"PR[30,1]={float(x):.3f}")
    said = (_check_says if x == "2e6" else _check_refuses)(tmp_path, capsys, text)
    assert check_says in said


def test_program_refuses_a_value_check_would_flag(solution, tmp_path, capsys):
    import json
    data = json.loads(solution.read_text())
    data["frame"]["x"] = 2e6
    data["frame"]["matrix"][0][3] = 2e6
    far = tmp_path / "far.json"
    far.write_text(json.dumps(data))
    out = tmp_path / "SET_UF3.LS"
    assert main(["program", str(far), "--frame", "UF3", "--pr", "90", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err == ("ucsio: UF3: X 2e+06 mm is 1 km or more from the origin (out-of-range): "
                   "the controller cannot hold this value; nothing written\n")
    assert not out.exists()


@pytest.mark.parametrize("source, frame, reader", [
    (KUKA, "BASE_DATA[1]", "out of range for a KRL REAL (float32)"),
    (CELL, "wobjTable", "out of range for a RAPID num (float32)"),
])
def test_a_value_the_vendor_reader_refuses_is_not_written(tmp_path, capsys, source, frame,
                                                          reader):
    """Every writer's values read back through its own reader: what that
    reader refuses is refused before writing, in its words, never as an
    internal error."""
    f = tmp_path / source.name
    f.write_bytes(source.read_bytes())
    rc = main(["patch", str(f), "--frame", frame, "--set", "1e300,0,0,0,0,0", "--in-place"])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and "internal error" not in err, err
    assert f"{frame}: number 1000000000000000052504760255" in err and reader in err
    assert "the controller cannot hold this value; nothing written" in err
    assert f.read_bytes() == source.read_bytes()
