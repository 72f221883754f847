"""Commands that only read, list, diff or patch files run once per file under
``git diff``: they must not pay for numpy or scipy."""
from __future__ import annotations

import json
import subprocess
import sys

from conftest import FIXTURES

PROBE = """
import sys, io, contextlib
from ucsio.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    code = main(sys.argv[1:])
heavy = sorted(m for m in ("numpy", "scipy") if m in sys.modules)
print(__import__("json").dumps({"code": code, "heavy": heavy}))
"""


def probe(*args):
    res = subprocess.run([sys.executable, "-c", PROBE, *map(str, args)],
                         capture_output=True, text=True, check=True)
    return json.loads(res.stdout.strip().splitlines()[-1])


def test_light_commands_import_no_numpy_or_scipy(tmp_path):
    mod = FIXTURES / "abb" / "two_modules_crcrlf.prg"
    sol = tmp_path / "sol.json"
    sol.write_text(json.dumps({"frame": {"x": 101, "y": 200, "z": 300, "a": 0, "b": 0, "c": 0}}))
    for args in (["frames", mod], ["frames", "--tree", mod], ["check", mod], ["diff", mod, mod],
                 ["diff", "--textconv", mod],
                 ["diff", mod, "--frame", "wobjA", "--measured", sol],
                 ["diff", mod, "--frame", "wobjA", "--measured", sol, "--points"],
                 ["patch", mod, "--frame", "wobjA", "--measured", sol]):
        out = probe(*args)
        assert out["heavy"] == [], (args, out)
        assert out["code"] == 0, (args, out)


def test_solve_does_not_import_scipy():
    out = probe("solve", FIXTURES / "measurements" / "abb_wobj.csv", "--tcp", "1.5,-2,182.3")
    assert "scipy" not in out["heavy"]


SLOW_TO_IMPORT = ("typing", "pathlib", "shutil", "json", "difflib", "lark", "numpy", "scipy",
                  "dataclasses", "inspect", "hashlib", "tempfile")

MODULES_PROBE = """
import sys, io, contextlib
from ucsio.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    main(sys.argv[1:])
print(" ".join(sorted(m for m in sys.modules if m in %r)))
""" % (SLOW_TO_IMPORT,)


def test_listing_a_file_imports_nothing_it_does_not_need(tmp_path):
    """issue 18 point 10: a cold `frames` in a plain venv was 2.7-4x a bare
    python reading the file. typing, pathlib, shutil (argparse's help width),
    json (the grammars' tables and the JSON printer), difflib (the patch
    preview) each cost a cold start milliseconds; none is needed to list a
    file's frames, and only json (the solution) to diff one frame."""
    mod = FIXTURES / "abb" / "two_modules_crcrlf.prg"
    dat = FIXTURES / "kuka" / "cell_config.dat"
    va = FIXTURES / "fanuc" / "sysframe_comment.va"
    ls = FIXTURES / "fanuc" / "program_frames.ls"
    sol = tmp_path / "sol.json"
    sol.write_text(json.dumps({"frame": {"x": 101, "y": 200, "z": 300, "a": 0, "b": 0, "c": 0}}))
    import os
    env = dict(os.environ, UCSIO_CACHE_DIR=str(tmp_path / "cache"))
    for args, allowed in ((["frames", mod], ()), (["frames", dat], ()), (["frames", va], ()),
                          (["frames", ls], ()),
                          (["diff", mod, "--frame", "wobjA", "--measured", sol], ("json",)),
                          (["diff", va, "--frame", "UF1", "--measured", sol], ("json",))):
        for _ in range(2):          # the first run builds the caches
            res = subprocess.run([sys.executable, "-c", MODULES_PROBE, *map(str, args)],
                                 capture_output=True, text=True, env=env, check=True)
        imported = set(res.stdout.split())
        assert imported <= set(allowed), (args, imported)


def test_compiled_patterns_come_back_from_the_cache(tmp_path):
    """The second run reads the compiled patterns from the disk cache and
    lists the same; a damaged cache is ignored (and rebuilt)."""
    import os
    mod = FIXTURES / "abb" / "two_modules_crcrlf.prg"
    env = dict(os.environ, UCSIO_CACHE_DIR=str(tmp_path / "cache"))
    run = lambda: subprocess.run([sys.executable, "-m", "ucsio", "frames", str(mod), "--json"],  # noqa: E731
                                 capture_output=True, text=True, env=env, check=True).stdout
    first = run()
    (store,) = (tmp_path / "cache").glob("re2-*.marshal")
    assert store.stat().st_size > 1000
    assert run() == first
    store.write_bytes(b"\x00not marshal at all")
    assert run() == first
    assert store.stat().st_size > 1000                 # rebuilt


def test_yaskawa_reading_commands_import_nothing_slow(tmp_path):
    """frames, frames --tree, check, diff and textconv of a Yaskawa
    UFRAME.CND, TOOL.CND and RBCALIB.DAT: none of numpy, scipy, lark, nor
    the other slow modules but difflib for a diff of two files, as for
    every vendor (RBCALIB.DAT's .dat suffix is KUKA's: its first line sends
    it to Yaskawa's reader, without KUKA's grammar)."""
    import os
    group = "1" + ",0" * 31
    files = {
        "UFRAME.CND": f"//UFRAME 1\r\n///GROUP {group}\r\n///BASICFRM 1,16,0\r\n"
                      "////BUSER 1.000,2.000,3.000,0.0000,0.0000,0.0000\r\n",
        "TOOL.CND": "//TOOL 0\r\n///NAME GUN\r\n0.000,0.000,365.400,0.0000,0.0000,0.0000\r\n",
        "RBCALIB.DAT": f"//RBCALIB 1\r\n///MTOOL 2\r\n///MGROUP {group}\r\n///SGROUP 0,1\r\n"
                       "////SRANG -2135.959,-4.939,-6.363,-0.0003,0.3284,-179.9991\r\n"}
    env = dict(os.environ, UCSIO_CACHE_DIR=str(tmp_path / "cache"))
    for name, text in files.items():
        (tmp_path / name).write_bytes(text.encode())
    # the first run builds the caches
    subprocess.run([sys.executable, "-m", "ucsio", "check", *files], cwd=tmp_path, env=env,
                   capture_output=True, check=True)
    for name in files:
        path = tmp_path / name
        for args in (["frames", path], ["frames", "--tree", path], ["check", path],
                     ["diff", path, path], ["diff", "--textconv", path]):
            res = subprocess.run([sys.executable, "-c", MODULES_PROBE, *map(str, args)],
                                 capture_output=True, text=True, env=env, check=True)
            allowed = ["difflib"] if args[0] == "diff" and len(args) == 3 else []
            assert res.stdout.split() in ([], allowed), (args, res.stdout)


def test_a_yaskawa_job_is_read_light(tmp_path):
    """frames, check and diff of a .JBI, and diff --points over a backup's jobs,
    import none of numpy, scipy, lark (issue 27: jobs are read line by line)."""
    from conftest import FIXTURES as FIX
    backup = FIX / "yaskawa" / "taught_backup"
    jbi, uframe = backup / "WELD.JBI", backup / "UFRAME.CND"
    sol = tmp_path / "sol.json"
    sol.write_text(json.dumps({"frame": {"x": 1200.5, "y": 300, "z": 150, "a": 90, "b": 0,
                                         "c": 0}}))
    for args in (["frames", jbi], ["check", jbi], ["diff", jbi, backup / "HOME.JBI"],
                 ["diff", uframe, "--frame", "UF2", "--measured", sol, "--points"]):
        out = subprocess.run([sys.executable, "-c", MODULES_PROBE, *map(str, args)],
                             capture_output=True, text=True, check=True).stdout.split()
        assert not set(out) & {"numpy", "scipy", "lark"}, (args, out)


def test_a_universal_robots_installation_is_read_and_patched_light(tmp_path):
    """frames, its tree, check, diff, textconv and patch (a plane, with its
    points) of an .installation: none of numpy, scipy, lark nor the other
    slow modules (but difflib for a diff of two files; a patch's diff and
    its solution's json);
    the gzip stream goes through zlib alone."""
    import os
    import shutil
    path = tmp_path / "cell.installation"
    shutil.copy(FIXTURES / "ur" / "cell.installation", path)
    sol = tmp_path / "sol.json"
    sol.write_text(json.dumps({"frame": {"x": 401, "y": -200, "z": 50, "a": 30, "b": 0,
                                         "c": 0.1}}))
    env = dict(os.environ, UCSIO_CACHE_DIR=str(tmp_path / "cache"))
    subprocess.run([sys.executable, "-m", "ucsio", "check", path], env=env,
                   capture_output=True, check=True)         # the first run builds the caches
    probe_gzip = MODULES_PROBE.replace("%r)))" % (SLOW_TO_IMPORT,),
                                       "%r)))" % (SLOW_TO_IMPORT + ("gzip",),))
    for args in (["frames", path], ["frames", "--tree", path], ["check", path],
                 ["diff", path, path], ["diff", "--textconv", path],
                 ["patch", path, "--frame", "Table", "--measured", sol]):
        res = subprocess.run([sys.executable, "-c", probe_gzip, *map(str, args)],
                             capture_output=True, text=True, env=env, check=True)
        # a patch reads its solution's JSON and shows its diff
        allowed = (["difflib", "json"] if args[0] == "patch" else
                   ["difflib"] if len(args) == 3 else [])
        assert res.stdout.split() in ([], allowed), (args, res.stdout)
