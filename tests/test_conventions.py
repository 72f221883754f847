"""The command line behaves like git and ruff (SPEC: Many files and whole
backups; issue 11 point 6): no abbreviated options, suggestions for typos,
JSON errors with --json, stderr for messages and stdout for data, colour only
on a terminal."""
from __future__ import annotations

import json
import shutil
import subprocess
import sys

import pytest

from conftest import FIXTURES, ROOT

SRC = str(ROOT / "src")


def run(*args, stdin=None, env=None):
    import os
    e = dict(os.environ, PYTHONPATH=SRC)
    e.pop("NO_COLOR", None)
    e.update(env or {})
    return subprocess.run([sys.executable, "-m", "ucsio", *map(str, args)], input=stdin,
                          capture_output=True, text=True, env=e)


def test_abbreviated_option_is_refused_and_writes_nothing(tmp_path):
    mod = tmp_path / "variants.mod"
    shutil.copy(FIXTURES / "abb" / "variants.mod", mod)
    before = mod.read_bytes()
    res = run("patch", mod, "--frame", "pShift", "--set", "1,2,3,0,0,0", "--in-plac")
    assert res.returncode == 2 and res.stdout == ""
    assert res.stderr.count("\n") == 1
    assert "--in-plac" in res.stderr and "did you mean '--in-place'" in res.stderr
    assert mod.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["variants.mod"]


@pytest.mark.parametrize("args", [["frames", "--jso", "x.mod"], ["solve", "m.csv", "--thresh", "2"],
                                  ["diff", "a", "b", "--exit"]])
def test_no_command_takes_an_abbreviation(args):
    res = run(*args)
    assert res.returncode == 2 and "unrecognized arguments" in res.stderr


def test_mistyped_subcommand_gets_the_nearest():
    res = run("frmes", "x.mod")
    assert res.returncode == 2 and res.stdout == ""
    assert "did you mean 'frames'" in res.stderr and res.stderr.count("\n") == 1


def test_json_error_is_json_on_stdout_and_a_line_on_stderr(tmp_path):
    bad = tmp_path / "bad.mod"
    bad.write_text("MODULE m\n  PERS wobjdata w:=[FALSE,TRUE,\"\",[[0,0,0],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n"
                   "  PERS num x:=[1,2;\nENDMODULE\n")
    for args in (["patch", bad, "--frame", "w", "--set", "1,2,3,0,0,0"],
                 ["diff", bad, "--frame", "w", "--measured", tmp_path / "none.json"]):
        res = run(*args, "--json")
        assert res.returncode == 2
        err = json.loads(res.stdout)["error"]
        assert set(err) == {"file", "line", "col", "message"}
        assert err["file"] and err["message"]
        assert res.stderr.count("\n") == 1 and err["message"] in res.stderr
    # a usage error too
    res = run("patch", bad, "--frame", "w", "--json")
    assert res.returncode == 2
    assert "required" in json.loads(res.stdout)["error"]["message"]


def test_textconv_with_json_is_a_usage_error():
    mod = FIXTURES / "abb" / "variants.mod"
    res = run("diff", "--textconv", mod, "--json")
    assert res.returncode == 2
    assert "--json" in json.loads(res.stdout)["error"]["message"]
    assert res.stderr.count("\n") == 1 and "textconv" in res.stderr


# -------------------------------------------------------------- lints (issue 11 point 5)

def _module(tmp_path, q: str, name: str = "q.mod"):
    p = tmp_path / name
    p.write_text("MODULE m\n  PERS wobjdata w:=[FALSE,TRUE,\"\",[[0,0,0],[" + q + "]],"
                 "[[0,0,0],[1,0,0,0]]];\nENDMODULE\n")
    return p


@pytest.mark.parametrize("q, expected", [
    ("0.7071,0,0,0.7071", [("quaternion-rounding", "info")]),       # RobotWare writes this: 1.9e-5
    ("0.70711,0,0,0.70711", []),                                     # 2.3e-6: nothing to say
    ("0.99998,0,0,0", [("quaternion-rounding", "info")]),            # 4.0e-5
    ("0.99994,0,0,0", [("unnormalized-quaternion", "warning")]),     # 1.2e-4
    ("0.9,0,0,0", [("unnormalized-quaternion", "warning")]),
])
def test_quaternion_lint_fits_what_controllers_write(tmp_path, q, expected):
    res = run("check", _module(tmp_path, q), "--json")
    out = json.loads(res.stdout)
    got = [(l["code"], l["severity"]) for l in out["files"][0]["lints"]]
    assert got == expected
    assert res.returncode == (1 if ("unnormalized-quaternion", "warning") in got else 0)


def test_check_ignore_silences_codes_and_knows_them(tmp_path):
    bad = _module(tmp_path, "0.9,0,0,0")
    assert run("check", bad).returncode == 1
    res = run("check", bad, "--ignore", "unnormalized-quaternion,no-value")
    assert res.returncode == 0 and "unnormalized" not in res.stdout
    res = run("check", bad, "--ignore", "no-value", "--ignore", "unnormalized-quaternion", "--json")
    assert res.returncode == 0 and json.loads(res.stdout)["files"][0]["lints"] == []
    res = run("check", bad, "--ignore", "unnormalised-quaternion")      # a typo silences nothing
    assert res.returncode == 2 and "did you mean 'unnormalized-quaternion'" in res.stderr


def test_every_lint_code_is_registered_and_every_finding_names_one():
    """check --ignore accepts exactly the registered codes: a code emitted
    anywhere in the parsers must be in controller.LINT_CODES."""
    import re
    from ucsio.parsing.controller import LINT_CODES
    emitted = set()
    for path in (ROOT / "src" / "ucsio").rglob("*.py"):
        text = path.read_text()
        for m in re.finditer(r"\blint\(", text):
            code = re.search(r'"([a-z][a-z0-9-]+)",', text[m.end():m.end() + 200])
            if code:
                emitted.add(code.group(1))
    emitted.discard("warning")
    assert emitted and emitted <= set(LINT_CODES), emitted - set(LINT_CODES)
    res = run("check", FIXTURES / "kuka" / "cell_config.dat", "--json")
    lints = json.loads(res.stdout)["files"][0]["lints"]
    assert lints and all(l["code"] in LINT_CODES for l in lints)


def test_kuka_frame_declared_without_value_is_listed(tmp_path):
    dat = tmp_path / "user.dat"
    dat.write_bytes(b"DEFDAT user PUBLIC\r\nDECL GLOBAL FRAME fixture_A\r\n"
                    b"DECL FRAME later\r\nlater={X 1,Y 2,Z 3,A 0,B 0,C 0}\r\nENDDAT\r\n")
    res = run("frames", dat, "--json")
    assert res.returncode == 0
    frames = {f["name"]: f for f in json.loads(res.stdout)["frames"]}
    assert list(frames) == ["fixture_A", "later"]
    assert frames["fixture_A"]["line"] == 2 and frames["fixture_A"]["x"] is None
    assert frames["later"]["x"] == 1.0
    res = run("check", dat)
    assert res.returncode == 0 and "user.dat:2:19: info: no-value: fixture_A" in res.stdout
    res = run("patch", dat, "--frame", "fixture_a", "--set", "1,2,3,0,0,0")
    assert res.returncode == 2 and "no literal value" in res.stderr


# -------------------------------------------------------------- bare CR (issue 11 point 8)

def test_kuka_file_with_bare_cr_line_endings(tmp_path):
    lf = (FIXTURES / "kuka" / "cell_config.dat").read_bytes().replace(b"\r\n", b"\n")
    cr = tmp_path / "cr.dat"
    cr.write_bytes(lf.replace(b"\n", b"\r"))
    ref = tmp_path / "lf.dat"
    ref.write_bytes(lf)
    got = json.loads(run("frames", cr, "--json").stdout)["frames"]
    want = json.loads(run("frames", ref, "--json").stdout)["frames"]
    assert len(got) == len(want) > 5
    assert [{**f, "file": None} for f in got] == [{**f, "file": None} for f in want]
    res = run("check", cr)
    assert "round trip ok" in res.stdout
    assert [ln.split(":", 1)[1] for ln in res.stdout.splitlines()[1:]] == \
        [ln.split(":", 1)[1] for ln in run("check", ref).stdout.splitlines()[1:]]
    # a patch keeps the CRs and shows one changed line
    out = tmp_path / "patched.dat"
    res = run("patch", cr, "--frame", "BASE_DATA[1]", "--set", "1,2,3,4,5,6", "-o", out)
    assert res.returncode == 0
    assert res.stdout.count("\n-BASE_DATA[1]=") == 1 and res.stdout.count("\n+BASE_DATA[1]=") == 1
    assert b"\n" not in out.read_bytes() and out.read_bytes().count(b"\r") == cr.read_bytes().count(b"\r")
    # an error names the right line
    lines = lf.split(b"\n")
    bad_line = next(i for i, ln in enumerate(lines) if ln.startswith(b"BASE_DATA[2]")) + 1
    lines[bad_line - 1] = b"BASE_DATA[2]={X 1,Y 2"
    bad = tmp_path / "bad.dat"
    bad.write_bytes(b"\r".join(lines))
    res = run("frames", bad)
    assert res.returncode == 2 and f"bad.dat:{bad_line}:" in res.stderr


# -------------------------------------------------------------- suggestions

def test_mistyped_frame_name_gets_the_nearest(tmp_path):
    mod = FIXTURES / "abb" / "variants.mod"
    res = run("patch", mod, "--frame", "wobjSpaces", "--set", "1,2,3,0,0,0")
    assert res.returncode == 2 and "did you mean 'wobjSpaced'" in res.stderr
    res = run("patch", FIXTURES / "kuka" / "cell_config.dat", "--frame", "Positoner",
              "--set", "1,2,3,0,0,0")
    assert res.returncode == 2 and "did you mean 'Positioner'" in res.stderr   # a KUKA label
    res = run("patch", mod, "--frame", "zzz", "--set", "1,2,3,0,0,0")
    assert res.returncode == 2 and "did you mean" not in res.stderr


def test_mistyped_manifest_key_gets_the_nearest(tmp_path):
    shutil.copy(FIXTURES / "measurements" / "kuka_base3.csv", tmp_path / "points.csv")
    shutil.copy(FIXTURES / "kuka" / "cell_config.dat", tmp_path / "config.dat")
    entry = ('[[entry]]\nname = "a"\nmeasurement = "points.csv"\ncontroller = "config.dat"\n'
             'frame = "BASE_DATA[1]"\n')
    (tmp_path / "m.toml").write_text('[defaults]\ntcp = [0, 0, 0]\ntolerence = 5.0\n\n' + entry)
    res = run("batch", tmp_path / "m.toml")
    assert res.returncode == 2 and "'tolerence'; did you mean 'tolerance'?" in res.stderr
    (tmp_path / "m.toml").write_text('[defaults]\ntcp = [0, 0, 0]\n\n' + entry + 'treshold = 2\n')
    res = run("batch", tmp_path / "m.toml", "--json")
    assert res.returncode == 1
    (e,) = json.loads(res.stdout)["entries"]
    assert "did you mean 'threshold'" in e["error"]


# -------------------------------------------------------------- - for stdin and stdout

KUKA_CSV = FIXTURES / "measurements" / "kuka_base3.csv"
TCP = "-20.67,89.73,33.44"


def test_dash_is_stdin_for_measurement_and_solution_and_stdout_for_o(tmp_path):
    ref = run("solve", KUKA_CSV, "--tcp", TCP, "--json")
    assert ref.returncode == 0
    res = run("solve", "-", "--tcp", TCP, "--json", stdin=KUKA_CSV.read_text())
    assert res.returncode == 0
    a, b = json.loads(ref.stdout), json.loads(res.stdout)
    assert a["frame"] == b["frame"] and a["rms"] == b["rms"]
    # -o -: the solution on stdout, the readable table on stderr
    res = run("solve", KUKA_CSV, "--tcp", TCP, "-o", "-")
    assert res.returncode == 0
    sol = res.stdout
    assert json.loads(sol)["frame"] == a["frame"]
    assert "measured frame" in res.stderr and not (tmp_path / "-").exists()
    # the solution from stdin into diff and patch; a patched file to stdout
    dat = tmp_path / "config.dat"
    shutil.copy(FIXTURES / "kuka" / "cell_config.dat", dat)
    before = dat.read_bytes()
    res = run("diff", dat, "--frame", "BASE_DATA[1]", "--measured", "-", "--json", stdin=sol)
    assert res.returncode in (0, 1) and json.loads(res.stdout)["measured"]["x"] == \
        pytest.approx(a["frame"]["x"])
    res = run("patch", dat, "--frame", "BASE_DATA[1]", "--measured", "-", "-o", "-", stdin=sol)
    assert res.returncode == 0, res.stderr
    assert "+BASE_DATA[1]=" in res.stderr and dat.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["config.dat"]
    (tmp_path / "sol.json").write_text(sol)
    assert run("patch", dat, "--frame", "BASE_DATA[1]", "--measured", tmp_path / "sol.json",
               "-o", tmp_path / "out.dat").returncode == 0
    assert res.stdout == (tmp_path / "out.dat").read_text() != before.decode()
    # one stdin only
    res = run("diff", "-", "--frame", "x", "--measured", "-",
              stdin='{"x": 0, "y": 0, "z": 0, "a": 0, "b": 0, "c": 0}')
    assert res.returncode == 2 and "already read" in res.stderr
    res = run("patch", dat, "--frame", "BASE_DATA[1]", "--set", "1,2,3,0,0,0", "-o", "-", "--json")
    assert res.returncode == 2 and json.loads(res.stdout)["error"]["message"]


def test_backup_never_overwrites_a_backup(tmp_path):
    dat = tmp_path / "config.dat"
    shutil.copy(FIXTURES / "kuka" / "cell_config.dat", dat)
    originals = []
    for i, x in enumerate((1, 2, 3)):
        originals.append(dat.read_bytes())
        res = run("patch", dat, "--frame", "BASE_DATA[1]", "--set", f"{x},0,0,0,0,0",
                  "--in-place", "--backup")
        assert res.returncode == 0 and res.stdout.startswith("---")
        bak = tmp_path / ("config.dat.bak" + (f".{i}" if i else ""))
        assert f"wrote {dat} (backup {bak})" in res.stderr
    assert (tmp_path / "config.dat.bak").read_bytes() == originals[0]
    assert (tmp_path / "config.dat.bak.1").read_bytes() == originals[1]
    assert (tmp_path / "config.dat.bak.2").read_bytes() == originals[2]


# -------------------------------------------------------------- stdout vs stderr

def test_messages_on_stderr_data_on_stdout(tmp_path):
    sol = tmp_path / "sol.json"
    res = run("solve", KUKA_CSV, "--tcp", TCP, "-o", sol, "--json")
    assert json.loads(res.stdout)["accepted"] is True          # stdout: only the JSON
    assert res.stderr == f"wrote {sol}\n"
    res = run("solve", KUKA_CSV, "--tcp", TCP, "-o", sol)
    assert "wrote" not in res.stdout and res.stderr == f"wrote {sol}\n"
    dat = tmp_path / "config.dat"
    shutil.copy(FIXTURES / "kuka" / "cell_config.dat", dat)
    res = run("patch", dat, "--frame", "BASE_DATA[1]", "--measured", sol, "-o", tmp_path / "out.dat")
    assert res.stdout.startswith("---") and res.stderr == f"wrote {tmp_path / 'out.dat'}\n"
    res = run("demo", "--out", tmp_path / "demo")
    assert "wrote" not in res.stdout and "wrote" in res.stderr


# -------------------------------------------------------------- colour

def run_on_terminal(*args, env=None):
    """The command with stdout on a pseudo-terminal, as a user sees it."""
    import os
    import pty
    master, slave = pty.openpty()
    e = dict(os.environ, PYTHONPATH=SRC, TERM="xterm")
    e.pop("NO_COLOR", None)
    e.update(env or {})
    proc = subprocess.Popen([sys.executable, "-m", "ucsio", *map(str, args)], stdout=slave,
                            stderr=subprocess.PIPE, env=e)
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 65536)
        except OSError:          # the terminal closed: the command ended
            break
        if not data:
            break
        chunks.append(data)
    proc.wait(timeout=60)
    os.close(master)
    return proc.returncode, b"".join(chunks).decode()


@pytest.mark.skipif(sys.platform == "win32", reason="pseudo-terminals are POSIX")
def test_colour_on_a_terminal_only_and_never_with_no_color(tmp_path):
    sol = tmp_path / "sol.json"
    assert run("solve", KUKA_CSV, "--tcp", TCP, "-o", sol).returncode == 0
    dat = FIXTURES / "kuka" / "cell_config.dat"
    args = ("diff", dat, "--frame", "BASE_DATA[1]", "--measured", sol, "--tolerance", "1")
    rc, out = run_on_terminal(*args)
    assert rc == 1 and "\033[1;31mFAIL\033[0m" in out
    rc, out = run_on_terminal("patch", dat, "--frame", "BASE_DATA[1]", "--measured", sol)
    assert rc == 0 and "\033[32m+BASE_DATA[1]=" in out and "\033[31m-BASE_DATA[1]=" in out
    rc, out = run_on_terminal("solve", KUKA_CSV, "--tcp", TCP)
    assert rc == 0 and "\033[32maccepted\033[0m" in out
    for env in ({"NO_COLOR": "1"}, {"TERM": "dumb"}):
        rc, out = run_on_terminal(*args, env=env)
        assert rc == 1 and "FAIL" in out and "\033[" not in out
    res = run(*args)                                    # piped
    assert res.returncode == 1 and "FAIL" in res.stdout and "\033[" not in res.stdout


# -------------------------------------------------------------- --help tells the truth

def test_patch_help_and_exit_status_agree_on_a_rejected_solution(tmp_path):
    """patch --help said a rejected solution exits 2; it is a failed gate, 1."""
    help_text = " ".join(run("patch", "--help").stdout.split())
    assert "Exit 1, nothing written: a rejected solution" in help_text
    sol = tmp_path / "rejected.json"
    res = run("solve", KUKA_CSV, "--tcp", TCP, "--min-points", "20", "-o", sol)
    assert res.returncode == 1 and json.loads(sol.read_text())["accepted"] is False
    dat = tmp_path / "config.dat"
    shutil.copy(FIXTURES / "kuka" / "cell_config.dat", dat)
    before = dat.read_bytes()
    res = run("patch", dat, "--frame", "BASE_DATA[1]", "--measured", sol, "--in-place")
    assert res.returncode == 1 and dat.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["config.dat", "rejected.json"]


@pytest.mark.parametrize("command, inputs", [
    ("frames", ["FILE", "backup folder", ".zip archive"]),
    ("check", ["FILE", "backup folder", ".zip archive", "--ignore"]),
    ("solve", ["MEAS.csv", "laser_x", "--laser", "--robot", "--tcp", "--tool"]),
    ("diff", ["SOLUTION.json", "OLD NEW", "folders or .zip archives", "--exit-code"]),
    ("patch", ["FILE", "--frame", "--measured", "--set", "standard input"]),
    ("batch", ["MANIFEST.toml", "measurement, controller, frame"]),
    ("demo", ["--out", "replay.sh"]),
])
def test_every_help_names_its_inputs(command, inputs):
    res = run(command, "--help")
    assert res.returncode == 0
    text = " ".join(res.stdout.split())
    for word in inputs:
        assert word in text, (command, word)


@pytest.mark.skipif(sys.platform == "win32", reason="pseudo-terminals are POSIX")
def test_batch_status_coloured_without_shifting_columns(tmp_path):
    import re
    shutil.copy(KUKA_CSV, tmp_path / "points.csv")
    shutil.copy(FIXTURES / "kuka" / "cell_config.dat", tmp_path / "config.dat")
    (tmp_path / "m.toml").write_text(
        f'[defaults]\ntcp = [{TCP}]\n\n'
        '[[entry]]\nname = "far"\nmeasurement = "points.csv"\ncontroller = "config.dat"\n'
        'frame = "BASE_DATA[1]"\n\n'
        '[[entry]]\nname = "tight tolerance"\nmeasurement = "points.csv"\n'
        'controller = "config.dat"\nframe = "BASE_DATA[1]"\ntolerance = 1e-3\n')
    piped = run("batch", tmp_path / "m.toml", "--no-progress")
    rc, out = run_on_terminal("batch", tmp_path / "m.toml", "--no-progress")
    assert rc == piped.returncode == 1
    assert "\033[1;31mover tolerance\033[0m" in out and "\033[" not in piped.stdout
    plain = re.sub(r"\033\[[0-9;]*m", "", out).replace("\r\n", "\n")
    assert plain == piped.stdout
