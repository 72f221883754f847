"""The demo's Stäubli and Universal Robots cells (issue 30 point 5): R06, a
CS9 .dtx frame measured with a tool of the same file, whose patch step is
reported as not run with the vendor's reason; R07, a plane feature of an
.installation measured with one of its TCPs, whose patched copy reads back.
The truth is make_demo.py's (scipy's rotations, independent of ucsio)."""
from __future__ import annotations

import importlib.util
import re
import zlib
from importlib import resources
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from ucsio import vendors
from ucsio.demo import CELLS, data_root, run_cell
from ucsio.parsing.controller import load

ROOT = Path(__file__).resolve().parents[1]


def make_demo():
    spec = importlib.util.spec_from_file_location("make_demo",
                                                  ROOT / "fixtures" / "demo" / "make_demo.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def cell_named(name: str):
    return next(c for c in CELLS if c.name == name)


def run(name: str, out=None) -> dict:
    with resources.as_file(data_root()) as root:
        return run_cell(cell_named(name), Path(root), out)


def rotation(frame: dict) -> Rotation:
    w, x, y, z = frame["q"]
    return Rotation.from_quat([x, y, z, w])


def test_shipped_data_is_what_make_demo_writes(tmp_path):
    """The two cells' files are the generator's (no copy of a corpus file)."""
    gen = make_demo()
    gen.r06(tmp_path / "R06_staubli")
    gen.r07(tmp_path / "R07_ur")
    data = resources.files("ucsio.demo").joinpath("data")
    for rel in ("R06_staubli/CellR06.dtx", "R06_staubli/battery_points.csv",
                "R07_ur/cell.installation", "R07_ur/fixture_points.csv"):
        assert (tmp_path / rel).read_bytes() == data.joinpath(rel).read_bytes(), rel


def test_staubli_cell_solves_and_reports_the_refused_patch(tmp_path):
    gen = make_demo()
    cell = run("R06", tmp_path)
    assert cell["vendor"] == "staubli" and cell["ok"] is True
    assert cell["tool"]["name"] == "tSMR" and cell["tool"]["tcp"] == [0.42, -0.65, 128.3]
    m = cell["solve"]["frame"]
    assert [m[k] for k in "xyz"] == pytest.approx(gen.R06_TRUE[:3], abs=0.15)
    truth = Rotation.from_euler("XYZ", gen.R06_TRUE[3:], degrees=True)
    assert (rotation(m) * truth.inv()).magnitude() < np.radians(0.02)
    assert [p["name"] for p in cell["solve"]["points"] if not p["used"]] == ["B3"]
    # the patch step: not run, with the vendor's own reason; nothing patched
    assert cell["patch"] is None
    why = vendors.get("staubli").patch_refusal
    assert {"step": "patch", "why": why} in cell["skipped"] and "rotation order" in why
    folder = tmp_path / "R06_staubli"
    assert not (folder / "patched").exists()
    replay = (folder / "replay.sh").read_text(encoding="utf-8")
    assert f"# 3. patch: not run ({why}):" in replay
    assert not [line for line in replay.splitlines() if line.startswith("ucsio patch")]


def three_point_rotation(points) -> Rotation:
    """PolyScope's plane: origin, a point on +X, one in the XY half-plane of +Y."""
    p1, p2, p3 = (np.asarray(p) for p in points)
    x = (p2 - p1) / np.linalg.norm(p2 - p1)
    z = np.cross(x, p3 - p1)
    z /= np.linalg.norm(z)
    return Rotation.from_matrix(np.column_stack([x, np.cross(z, x), z]))


def values(xml: str, tag: str, field: str) -> list[float]:
    block = re.search(rf"<{tag}>.*?<{field} value=\"([^\"]+)\"", xml, re.S).group(1)
    return [float(v) for v in block.split(",")]


def test_ur_cell_patches_the_plane_and_its_copy_reads_back(tmp_path):
    gen = make_demo()
    cell = run("R07", tmp_path)
    assert cell["vendor"] == "ur" and cell["ok"] is True
    assert cell["tool"]["tcp"] == pytest.approx([1.2, -1.8, 62.5])     # metres in the file
    m = cell["solve"]["frame"]
    assert [m[k] for k in "xyz"] == pytest.approx(gen.R07_TRUE_T, abs=0.15)
    assert (rotation(m) * gen.R07_TRUE_ROT.inv()).magnitude() < np.radians(0.02)
    assert [p["name"] for p in cell["solve"]["points"] if not p["used"]] == ["F5"]
    written = Path(cell["patch"]["written"])
    assert written == tmp_path / "R07_ur" / "patched" / "cell.installation"
    plane = load(written).frame("Fixture").pose
    assert [plane.x, plane.y, plane.z] == pytest.approx([m["x"], m["y"], m["z"]], abs=5e-4)
    # the file itself, inflated here: the plane's frame and its taught points are the solution's
    with resources.as_file(data_root()) as root:
        before = zlib.decompress((Path(root) / cell["controller"]).read_bytes(), 31).decode()
    after = zlib.decompress(written.read_bytes(), 31).decode()
    first = values(after, "firstPoint", "toolPosition")
    assert [1000 * v for v in first] == pytest.approx([m["x"], m["y"], m["z"]], abs=1e-6)
    frame = Rotation.from_rotvec(values(after, "firstPoint", "toolAxisAngle"))
    assert (frame * rotation(m).inv()).magnitude() < 1e-8
    taught = [values(after, tag, "toolPosition")
              for tag in ("userFirstPoint", "userSecondPoint", "userThirdPoint")]
    assert (three_point_rotation(taught) * rotation(m).inv()).magnitude() < 1e-8
    # nothing else in the XML changes: only the points' positions and rotation vectors
    old, new = before.split("\n"), after.split("\n")
    assert len(old) == len(new)
    changed = {re.sub(r'value="[^"]*"', "", b).strip() for a, b in zip(old, new) if a != b}
    assert changed == {"<toolPosition />", "<toolAxisAngle />"}


def test_a_vendor_that_refuses_patch_is_reported_by_capability(monkeypatch, tmp_path):
    """Any vendor's stated refusal, not Stäubli's name: the UR cell, told to
    refuse, reports its patch step as not run with that reason, writes no
    copy, and its replay comments the patch out."""
    monkeypatch.setattr(vendors.get("ur"), "patch_refusal", "a reason of the vendor's own")
    cell = run("R07", tmp_path)
    assert cell["patch"] is None and cell["ok"] is True
    assert {"step": "patch", "why": "a reason of the vendor's own"} in cell["skipped"]
    assert not (tmp_path / "R07_ur" / "patched").exists()
    assert "# 3. patch: not run (a reason of the vendor's own):" in \
        (tmp_path / "R07_ur" / "replay.sh").read_text()


def test_a_stream_this_zlib_does_not_reproduce_still_runs_the_demo(monkeypatch, tmp_path):
    """The UR cell's installation is written back only where this Python's
    zlib reproduces its stream; where another zlib does not (zlib-ng, say),
    the demo still runs: the patch step is not run, with the reason, and no
    copy is written."""
    from ucsio.parsing.document import Gzip
    why = "this gzip stream is not what zlib X writes at level 6 (stand-in)"
    monkeypatch.setattr(Gzip, "refusal", property(lambda self: why))
    cell = run("R07", tmp_path)
    assert cell["patch"] is None and cell["ok"] is True
    assert {"step": "patch", "why": why} in cell["skipped"]
    assert not (tmp_path / "R07_ur" / "patched").exists()
