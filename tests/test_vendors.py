"""Vendors as plug-ins (issue 26, points 2 and 3): every registered vendor
provides what ``vendors.protocol.Vendor`` names; no module outside
``src/ucsio/vendors/`` compares vendor names or branches on them; reading a
file imports its own vendor's package and no other."""
from __future__ import annotations

import ast
import importlib
import io
import re
import tokenize
import json
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import FIXTURES
from ucsio import vendors
from ucsio.vendors.protocol import Vendor

SRC = Path(vendors.__file__).resolve().parents[1]       # src/ucsio
NAMES = frozenset(e.name for e in vendors.VENDORS)


@pytest.mark.parametrize("entry", vendors.VENDORS, ids=lambda e: e.name)
def test_every_vendor_provides_the_protocol(entry):
    vendor = importlib.import_module(entry.package).VENDOR
    assert isinstance(vendor, Vendor)
    assert (vendor.name, vendor.title) == (entry.name, entry.title)
    assert vendors.get(entry.name) is vendor


# ------------------------------------------------------------- vendor names

def _vendor_name(node) -> str | None:
    if isinstance(node, ast.Constant) and isinstance(node.value, str) and node.value in NAMES:
        return node.value
    return None


def _names_in(node) -> list[str]:
    """The vendor names a comparison's operand holds: itself, or the
    elements of a tuple, list or set it tests membership in."""
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        return [n for n in map(_vendor_name, node.elts) if n]
    name = _vendor_name(node)
    return [name] if name else []


def offenders_in(path: Path, root: Path = SRC.parent) -> list[str]:
    """Every place of ``path`` that branches on a registered vendor's name:
    a comparison (==, !=, in, not in) with one, a dict literal keyed by one,
    a call passing one as an argument. "file:line: what" each (the file
    relative to ``root``)."""
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    rel = path.relative_to(root).as_posix()
    out = []
    for node in ast.walk(tree):
        found: list[str] = []
        what = ""
        if isinstance(node, ast.Compare):
            ops = (ast.Eq, ast.NotEq, ast.In, ast.NotIn)
            if any(isinstance(op, ops) for op in node.ops):
                found = [n for x in (node.left, *node.comparators) for n in _names_in(x)]
                what = "compares with"
        elif isinstance(node, ast.Dict):
            found = [n for n in map(_vendor_name, node.keys) if n]
            what = "a dict keyed by"
        elif isinstance(node, ast.Call):
            args = [*node.args, *(k.value for k in node.keywords)]
            found = [n for n in map(_vendor_name, args) if n]
            what = "a call passing"
        if found:
            out.append((node.lineno, f"{rel}:{node.lineno}: {what} {', '.join(map(repr, found))}"))
    return [text for _, text in sorted(out)]


def outside_the_vendors() -> list[Path]:
    """Every module of src/ucsio outside src/ucsio/vendors/ (the registry
    ``vendors/__init__.py`` is inside: it holds the names as its data)."""
    return [p for p in sorted(SRC.rglob("*.py"))
            if p.relative_to(SRC).parts[0] != "vendors"]


def test_no_module_outside_the_vendors_branches_on_a_vendor_name():
    paths = outside_the_vendors()
    assert len(paths) > 60
    found = [o for p in paths for o in offenders_in(p)]
    assert not found, "vendor names outside src/ucsio/vendors/:\n" + "\n".join(found)


def strings_naming_a_vendor(path: Path, root: Path = SRC) -> list[str]:
    """Where a module's code holds a vendor's name as a string of its own,
    whatever it does with it: comments and prose do not count."""
    found = []
    for tok in tokenize.generate_tokens(io.StringIO(path.read_text(encoding="utf-8")).readline):
        if tok.type == tokenize.STRING and tok.string.strip("\"'") in NAMES:
            found.append(f"{path.relative_to(root)}:{tok.start[0]}: {tok.string}")
    return found


def test_no_module_outside_the_vendors_holds_a_vendor_name():
    """Stricter than branching: not even as data (the registry holds the names)."""
    assert [hit for p in outside_the_vendors() for hit in strings_naming_a_vendor(p)] == []


def test_the_string_finder_finds_them(tmp_path):
    probe = tmp_path / "probe.py"
    probe.write_text('# "kuka" in a comment\nif form == "abb":\n    x = {\'fanuc\': 1}\n')
    assert [h.split(": ")[1] for h in strings_naming_a_vendor(probe, tmp_path)] == \
        ['"abb"', "'fanuc'"]


def test_the_check_sees_each_kind_of_branch(tmp_path):
    """The scan is not vacuous: each kind of branch is reported, in line
    order; a vendor name held as data (an assignment, a longer string) is not."""
    probe = tmp_path / "branches.py"
    text = ('def f(frame, d):\n'
            '    if frame.vendor == "abb":\n'
            '        pass\n'
            '    if frame.vendor not in ("kuka", "x"):\n'
            '        pass\n'
            '    table = {"fanuc": 1}\n'
            '    g("kuka")\n'
            '    g(vendor="abb")\n'
            '    shown = "kuka"\n'
            '    return "abb ok", d.get("vendor") == "fanuc" and "da" in d\n')
    probe.write_text(text, encoding="utf-8")
    got = offenders_in(probe, tmp_path)
    assert [o.split(": ", 1)[1] for o in got] == [
        "compares with 'abb'", "compares with 'kuka'", "a dict keyed by 'fanuc'",
        "a call passing 'kuka'", "a call passing 'abb'", "compares with 'fanuc'"]
    assert [o.split(": ")[0] for o in got] == [f"branches.py:{n}" for n in (2, 4, 6, 7, 8, 10)]


# ------------------------------------------------------------- cold imports

PROBE = """
import sys, io, contextlib, json
from ucsio.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    code = main(["frames", sys.argv[1]])
print(json.dumps({"code": code, "vendors": sorted(
    m for m in sys.modules if m.startswith("ucsio.vendors.") and m != "ucsio.vendors.protocol")}))
"""


@pytest.mark.parametrize("path, mine", [
    (FIXTURES / "abb" / "two_modules_crcrlf.prg", "abb"),
    (FIXTURES / "kuka" / "cell_config.dat", "kuka"),
    (FIXTURES / "fanuc" / "sysframe_comment.va", "fanuc"),
], ids=["abb", "kuka", "fanuc"])
def test_reading_a_file_imports_no_other_vendor(path, mine):
    assert path.is_file(), path
    res = subprocess.run([sys.executable, "-c", PROBE, str(path)],
                         capture_output=True, text=True, check=True)
    out = json.loads(res.stdout.strip().splitlines()[-1])
    assert out["code"] == 0
    loaded = {m.split(".")[2] for m in out["vendors"]}
    assert mine in loaded and loaded <= {mine, "common"}, out["vendors"]


# ------------------------------------------------------------- asked, not named

KUKA_CONFIG = FIXTURES / "taught" / "kuka" / "KRC" / "R1" / "System" / "$config.dat"


def run(*args) -> tuple[int, str, str]:
    import contextlib
    import io
    from ucsio.cli import main
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in args])
    return code, out.getvalue(), err.getvalue()


@pytest.fixture
def kuka_as(monkeypatch):
    """KUKA's vendor object with some of its answers replaced: generic code
    must follow the object, whatever the frame's vendor is called."""
    kuka = type(vendors.get("kuka"))

    def replace(**answers):
        stand_in = type("StandIn", (kuka,), answers)()
        monkeypatch.setitem(vendors._loaded, "kuka", stand_in)
    return replace


def _measured(tmp_path) -> Path:
    sol = tmp_path / "solution.json"
    sol.write_text(json.dumps({"frame": dict(x=1501.0, y=-249.0, z=600.5, a=30.5, b=-2.4, c=1.0),
                               "accepted": True}))
    return sol


def test_a_vendor_without_a_reader_of_taught_points_says_so(tmp_path, kuka_as):
    kuka_as(taught_points=None)
    code, out, err = run("diff", KUKA_CONFIG, "--frame", "weld_fixture", "--measured",
                         _measured(tmp_path), "--points")
    assert code == 2 and out == ""
    assert "KUKA has no reader of taught points yet" in err
    assert re.search(r"\$config\.dat:\d+", err), err


def test_a_vendor_without_a_frame_writer_says_so_and_writes_nothing(tmp_path, kuka_as):
    import shutil
    config = tmp_path / "$config.dat"
    shutil.copy(KUKA_CONFIG, config)
    before = config.read_bytes()
    kuka_as(plan_changes=None)
    code, out, err = run("patch", config, "--frame", "weld_fixture", "--measured",
                         _measured(tmp_path))
    assert code == 2 and out == ""
    assert re.search(r"\$config\.dat:\d+:1: \S+: KUKA has no frame writer yet: nothing written",
                     err), err
    assert config.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["$config.dat", "solution.json"]


def test_a_frames_own_deltas_are_its_vendors(tmp_path, kuka_as):
    args = ("diff", KUKA_CONFIG, "--frame", "weld_fixture", "--measured", _measured(tmp_path),
            "--json")
    plain = json.loads(run(*args)[1])
    assert "dw" not in plain
    kuka_as(native_deltas=(("dw", "dc"),))
    d = json.loads(run(*args)[1])
    assert d["dw"] == d["dc"] == plain["dc"]


def test_which_frames_can_be_unset_is_the_vendors(kuka_as):
    """TOOL_DATA[4] of a configuration is unset (zero, a blank name) and
    BASE_DATA[4] set (zero, named "gripper"); a vendor that pre-fills
    nothing has no unset frame, and names its controller gives count as none."""
    from ucsio.parsing.controller import load
    from ucsio.review.unset import is_set
    cf = load(FIXTURES / "kuka" / "cell_config.dat")
    blank, named = cf.frame("TOOL_DATA[4]"), cf.frame("BASE_DATA[4]")
    assert (is_set(blank, cf), is_set(named, cf)) == (False, True)
    kuka_as(prefilled=lambda self, frame, cf: False)
    assert is_set(blank, cf)
    kuka_as(default_label=lambda self, frame, label: label == "gripper")
    assert not is_set(named, cf)


def test_first_words_claim_a_file_whatever_its_suffix():
    """Yaskawa's RBCALIB.DAT and VAR.DAT end as KUKA's data lists do: their
    first line decides (registry Entry.heads), a whole word only."""
    assert vendors.claimed("//RBCALIB 1\r\n///MTOOL 2\r\n") == "yaskawa"
    assert vendors.claimed("\ufeff//VAR\r\n///PFNUM 6,0,0,0\r\n") == "yaskawa"
    assert vendors.claimed("//VARIABLES\r\n") is None
    assert vendors.claimed("&ACCESS RVP\r\nDEFDAT $CONFIG\r\n") is None
    assert vendors.claimed("") is None
