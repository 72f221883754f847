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
    for args in (["frames", mod], ["check", mod], ["diff", mod, mod],
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
