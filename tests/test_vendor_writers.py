"""Writing frames through the vendor objects (issue 26, points 1-3): the
orchestration in review/ (plan, verify, save, diff) and the batch ask the
frame's vendor how to write it; each vendor's writer lives in its folder."""
from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import FIXTURES
from ucsio import vendors
from ucsio.errors import UcsioError
from ucsio.geometry.frames import Pose
from ucsio.parsing.controller import load
from ucsio.review.patch import patch_frame, same_rotation_tolerance
from ucsio.review.save import save
from ucsio.vendors.protocol import Vendor

SRC = Path(vendors.__file__).resolve().parent.parent
CAPABILITIES = ("declaration_end", "assignments", "check_patchable", "check_siblings",
                "check_readback", "in_place_refusal", "program_writer")


@pytest.mark.parametrize("name", [e.name for e in vendors.VENDORS])
def test_every_vendor_writes_frames(name):
    vendor = vendors.get(name)
    assert isinstance(vendor, Vendor)
    for member in CAPABILITIES:          # a capability a vendor lacks is None
        value = getattr(vendor, member)
        assert value is None or callable(value), (name, member)
    assert set("xyz") <= set(vendor.native_keys) and len(vendor.native_keys) in (6, 7)


def test_tolerances_are_a_quarter_of_the_written_step():
    """The values the vendor-name branches gave: 0.0001 deg (ABB, KUKA) and
    0.001 deg (FANUC) written; read back within 5e-4 and 1e-3 deg."""
    from ucsio.vendors.common.write import READBACK_ANGLE_DEG
    from ucsio.vendors.fanuc.write import READBACK_FANUC_ANGLE_DEG
    from ucsio.vendors.fanuc.write import SAME_ROTATION as FANUC_SAME
    from ucsio.vendors.kuka.write import SAME_ROTATION as KUKA_SAME

    assert same_rotation_tolerance("abb") == same_rotation_tolerance("kuka") == \
        KUKA_SAME == 0.25 * 10.0 ** -4
    assert same_rotation_tolerance("fanuc") == FANUC_SAME == 0.25 * 10.0 ** -3
    assert vendors.get("abb").readback_angle == vendors.get("kuka").readback_angle == \
        READBACK_ANGLE_DEG == 5e-4
    assert vendors.get("fanuc").readback_angle == READBACK_FANUC_ANGLE_DEG == 1e-3


def test_only_fanuc_writes_a_program():
    assert vendors.get("abb").program_writer is None
    assert vendors.get("kuka").program_writer is None
    assert callable(vendors.get("fanuc").program_writer)
    assert vendors.missing("kuka", "program writer") == "KUKA has no program writer yet"


def test_save_asks_the_frame_s_vendor(tmp_path, monkeypatch):
    """A vendor whose files are patched only as reviewed copies says so
    through its own ``in_place_refusal``: save refuses, nothing written."""
    src = tmp_path / "$config.dat"
    shutil.copy(FIXTURES / "patch" / "refs" / "$config.dat", src)
    cf = load(str(src))
    res = patch_frame(cf, "BASE_DATA[7]", Pose.from_abc(1, 2, 3, 0, 0, 0), measured=False,
                      check_siblings=False)
    kuka = vendors.get("kuka")

    class CopyOnly(type(kuka)):
        def in_place_refusal(self, frame, out):
            return f"{frame.name}: reviewed copies only ({out})"
    monkeypatch.setitem(vendors._loaded, "kuka", CopyOnly())
    before = src.read_bytes()
    with pytest.raises(UcsioError, match=r"BASE_DATA\[7\]: reviewed copies only \(None\)"):
        save(res)
    with pytest.raises(UcsioError, match="reviewed copies only"):
        save(res, str(src))
    assert src.read_bytes() == before
    out = tmp_path / "out.dat"
    save(res, str(out))                 # a copy elsewhere is written
    assert out.read_bytes() == res.new_bytes


PROBE = """
import sys, io, contextlib
from ucsio.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    code = main(sys.argv[1:])
print(__import__("json").dumps({"code": code, "vendors": sorted(
    m for m in sys.modules if m.startswith("ucsio.vendors."))}))
"""


@pytest.mark.parametrize("file, frame, others", [
    ("abb/two_modules_crcrlf.prg", "wobjA", ("kuka", "fanuc")),
    ("fanuc/program_patch.ls", "UF1", ("abb", "kuka")),
])
def test_a_patch_imports_only_its_vendor(tmp_path, file, frame, others):
    alone = tmp_path / Path(file).name     # no sibling modules to read
    shutil.copy(FIXTURES / file, alone)
    res = subprocess.run([sys.executable, "-c", PROBE, "patch", str(alone), "--frame",
                          frame, "--set", "101,200,300,0,0,0"],
                         capture_output=True, text=True, check=True)
    out = json.loads(res.stdout.strip().splitlines()[-1])
    assert out["code"] == 0, res.stderr
    # the registry's lint tables (``vendors.lint_codes``) are all read; no
    # other vendor's reader or writer is
    loaded = [m for m in out["vendors"] if m.split(".")[2] in others
              and m.count(".") > 2 and not m.endswith(".lints")]
    assert loaded == [], loaded
    assert any(m.endswith(".write") for m in out["vendors"])
