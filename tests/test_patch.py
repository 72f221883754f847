"""ucsio patch: native formatting, byte-exact edits, refusals, atomic writes."""
from __future__ import annotations

import json
import math
import os
import random
import shutil
import stat
from pathlib import Path

import numpy as np
import pytest

from conftest import FIXTURES, corpus_files
from ucsio.geometry import rotations as rot
from ucsio.cli import main
from ucsio.parsing.controller import load, parse
from ucsio.parsing.document import Document
from ucsio.errors import UcsioError
from ucsio.geometry.frames import Pose
from ucsio.review.patch import edits_for, patch_frame, plan
from ucsio.review.save import save
from ucsio.vendors.abb.write import QUAT_NORM_MAX
from ucsio.vendors.common.write import format_number

PATCH = FIXTURES / "patch"
CELL = PATCH / "cell.mod"
REFS = PATCH / "refs" / "$config.dat"

TRANS_TOL = 0.0005 + 1e-9      # half a written step (0.001 mm)
ANGLE_TOL = 5e-4               # deg: what 6-decimal quaternions / 0.0001 deg angles allow


def close_pose(a: Pose, b: Pose) -> bool:
    return (all(abs(u - v) <= TRANS_TOL for u, v in zip(a.t, b.t))
            and rot.quat_angle(a.q, b.q) <= ANGLE_TOL)


def temp_files(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.endswith(".ucsio-tmp"))


def perturbed(p: Pose, rng: random.Random, move=50.0, turn=5.0) -> Pose:
    d = rot.abc_to_quat(rng.uniform(-turn, turn), rng.uniform(-turn, turn), rng.uniform(-turn, turn))
    q = rot.quat_multiply(p.q, d)
    return Pose.from_quat(p.x + rng.uniform(-move, move), p.y + rng.uniform(-move, move),
                          p.z + rng.uniform(-move, move), q)


def spliced_out(text: str, spans) -> str:
    out, pos = [], 0
    for s in sorted(spans, key=lambda s: s.start):
        out.append(text[pos:s.start])
        out.append("\0")
        pos = s.end
    out.append(text[pos:])
    return "".join(out)


# ------------------------------------------------------------------ numbers

@pytest.mark.parametrize("value,decimals,point,old,expected", [
    (6125.39, 3, False, None, "6125.39"),
    (6125.39, 3, True, None, "6125.39"),
    (6130.0, 3, False, None, "6130"),
    (6130.0, 3, True, None, "6130.0"),
    (-0.0001, 3, False, None, "0"),
    (-0.0001, 3, True, None, "0.0"),
    (-0.00004, 4, True, "0.0", "0.0"),
    (100.5, 3, True, "0.000", "100.500"),
    (2087.5, 3, True, "2087.50", "2087.50"),
    (0.1234567, 6, False, None, "0.123457"),
    (1e-7, 6, False, None, "0"),
    (5e-6, 6, False, "5.01292E-06", "0.000005"),
    (-61.6, 3, False, "-61.6146", "-61.6"),
])
def test_format_number(value, decimals, point, old, expected):
    assert format_number(value, decimals, point=point, old_text=old) == expected


def test_format_number_never_negative_zero_or_exponent():
    rng = random.Random(3)
    for _ in range(2000):
        v = rng.choice([1e-9, 1e-5, 0.3, 7.0, 1234.5]) * rng.uniform(-1, 1)
        for point in (False, True):
            s = format_number(v, 3, point=point)
            assert "e" not in s.lower() and s not in ("-0", "-0.0")
            assert abs(float(s) - v) <= 0.0005 + 1e-12
            assert ("." in s) or not point


def test_quaternion_written_normalised_and_on_the_old_side():
    """FORMATS 1.6: normalise after rounding, re-parse, |sum q^2 - 1| <= 1e-6."""
    cf = load(CELL)
    rng = random.Random(11)
    for i in range(1000):
        q = rot.quat_normalize(tuple(rng.gauss(0, 1) for _ in range(4)))
        if i % 2:   # near the old values too, where some components keep their text
            q = rot.quat_normalize(tuple(c + rng.gauss(0, 2e-6) for c in (0.965926, 0, 0, 0.258819)))
        target = Pose.from_quat(rng.uniform(-2000, 2000), rng.uniform(-2000, 2000),
                                rng.uniform(-2000, 2000), q)
        for name in ("wobjTable", "wobjNeg"):
            frame = cf.frame(name)
            changes = plan(frame, target)
            by = {c.component: c.new for c in changes}
            texts = [by.get(k, frame.numbers[k].text) for k in ("q1", "q2", "q3", "q4")]
            written = [float(t.replace(" ", "")) for t in texts]
            if i % 50 == 0:    # the whole way: edit, parse back
                new = Document(cf.document.edited_bytes(edits_for(frame, changes)), CELL)
                again = parse(new).frame(name)
                assert [again.numbers[k].value for k in ("q1", "q2", "q3", "q4")] == written
                assert close_pose(again.pose, target)
            assert abs(sum(c * c for c in written) - 1) <= QUAT_NORM_MAX
            old = [frame.numbers[k].value for k in ("q1", "q2", "q3", "q4")]
            if abs(written[0]) > 5e-7:
                assert written[0] > 0                                 # SPEC: q1 >= 0
            else:
                assert sum(a * b for a, b in zip(old, written)) >= 0  # q1 = 0: the old side
            for c in changes:
                if c.component.startswith("q"):
                    assert len(c.new.split(".")[-1]) <= 6 and "e" not in c.new.lower()
            w = Pose.from_quat(0, 0, 0, written)
            assert rot.quat_angle(w.q, target.q) <= ANGLE_TOL


def test_kuka_angles_and_translations_native():
    cf = load(REFS)
    target = Pose.from_abc(6125.39, 2445.56, 1168.99, 90.529, -24.476, -0.313)
    res = patch_frame(cf, "spec_base", target)
    line = [ln for ln in Document(res.new_bytes).text.splitlines() if ln.startswith("BASE_DATA[7]")][0]
    assert line == "BASE_DATA[7]={X 6125.390,Y 2445.560,Z 1168.990,A 90.5290,B -24.4760,C -0.3130}"


def test_kuka_minus_180_kept_and_gimbal_lock_unchanged():
    cf = load(REFS)
    table = cf.frame("table")                       # A -180.000
    same = Pose.from_abc(2500, -1200, 800, 180.0, 0, 0)
    assert plan(table, same) == []
    gimbal = cf.frame("gimbal")                     # B -90: A and C coupled
    p = gimbal.pose
    other_split = Pose.from_abc(p.x, p.y, p.z, 30.0, -90.0, -30.0)   # A + C fixed at B = -90
    assert rot.quat_angle(other_split.q, p.q) < 1e-6
    assert plan(gimbal, other_split) == []


# ------------------------------------------------------------------ read back

@pytest.mark.parametrize("path,name", [(CELL, "wobjTable"), (CELL, "wobjPlain.oframe"),
                                       (CELL, "tFixed"), (REFS, "table"), (REFS, "BASE_DATA[7]")])
def test_patch_reads_back_and_touches_only_the_numbers(path, name):
    cf = load(path)
    frame = cf.frame(name)
    target = perturbed(frame.pose, random.Random(name))
    res = patch_frame(cf, name, target)
    assert res.changed
    again = parse(Document(res.new_bytes, path)).frame(name)
    assert close_pose(again.pose, target)
    old_text, new_text = cf.document.text, Document(res.new_bytes).text
    assert spliced_out(old_text, [n.span for n in frame.numbers.values()]) == \
        spliced_out(new_text, [n.span for n in again.numbers.values()])
    # only the changed components' text differs
    changed = {c.component for c in res.changes}
    for k, n in frame.numbers.items():
        if k not in changed:
            assert again.numbers[k].text == n.text


def test_unchanged_components_keep_their_text():
    cf = load(CELL)
    f = cf.frame("wobjTable")                 # "- 430.25" with a space, "705", q of 30 deg about z
    target = Pose.from_quat(1200.5, -430.25, 712.0, f.pose.q)
    res = patch_frame(cf, "wobjTable", target)
    assert [c.component for c in res.changes] == ["z"]
    assert "[ [ 1200.5, - 430.25, 712 ], [ 0.965926, 0, 0, 0.258819 ] ]" in Document(res.new_bytes).text


@pytest.mark.parametrize("path", corpus_files("abb") + corpus_files("kuka"))
def test_corpus_every_frame_patched_confined(path):
    """Every frame of every corpus file, patched with a perturbed copy of
    itself: the bytes change only inside that frame's numbers, and read back
    within the written precision. With its own values: no byte changes."""
    cf = load(path)
    doc = cf.document
    rng = random.Random(path.name)
    all_edits, targets = [], {}
    for frame in cf.frames:
        if frame.pose is None or frame.info.get("ufprog") is False and \
                frame.info.get("component") == "uframe":
            continue                                  # refused: no value / moving
        # with its own values: nothing changes
        assert plan(frame, frame.pose) == [], frame.name
        target = perturbed(frame.pose, rng)
        edits = edits_for(frame, plan(frame, target))
        # this frame alone: bytes outside its numbers identical
        new_text = doc.apply(edits)
        spans = [n.span for n in frame.numbers.values()]
        assert len(spans) == (7 if cf.vendor == "abb" else 6)
        head, tail = min(s.start for s in spans), max(s.end for s in spans)
        assert new_text[:head] == doc.text[:head]
        assert new_text[len(new_text) - (len(doc.text) - tail):] == doc.text[tail:]
        all_edits += edits
        targets[frame.name] = (frame, target)
    if not targets:
        return                                        # no frame with a value: nothing to patch
    # every frame at once: one parse checks them all
    new_doc = Document(doc.edited_bytes(all_edits), doc.path)
    assert new_doc.encoding == doc.encoding and new_doc.bom == doc.bom
    again = parse(new_doc)
    old_spans = [n.span for f, _ in targets.values() for n in f.numbers.values()]
    new_spans = [n.span for name in targets for n in again.frame(name).numbers.values()]
    assert spliced_out(doc.text, old_spans) == spliced_out(new_doc.text, new_spans)
    for name, (frame, target) in targets.items():
        got = again.frame(name)
        assert close_pose(got.pose, target), name
        if cf.vendor == "abb":
            q = [got.numbers[k].value for k in ("q1", "q2", "q3", "q4")]
            assert abs(sum(c * c for c in q) - 1) <= QUAT_NORM_MAX, name
    # and through patch_frame itself (refusal checks, verify) for one frame
    name, (frame, target) = next(iter(targets.items()))
    res = patch_frame(cf, name, target, measured=False, check_siblings=False)
    assert res.changed and parse(Document(res.new_bytes, doc.path)).frame(name).pose is not None


def test_patch_with_own_values_changes_no_byte(tmp_path):
    f = tmp_path / "cell.mod"
    shutil.copy(CELL, f)
    before = f.read_bytes()
    st = f.stat()
    cf = load(f)
    for frame in cf.frames:
        if frame.pose is None or frame.info.get("ufprog") is False:
            continue
        res = patch_frame(cf, frame.name, frame.pose, measured=False, check_siblings=False)
        assert not res.changed and res.changes == []
    p = cf.frame("wobjTable").pose
    rc = main(["patch", str(f), "--frame", "wobjTable", "--in-place",
               "--set-q", ",".join(str(v) for v in (*p.t, *p.q))])
    assert rc == 0
    assert f.read_bytes() == before and f.stat().st_mtime_ns == st.st_mtime_ns


# ------------------------------------------------------------------ refusals

def solution(tmp_path, pose: Pose, accepted=True) -> Path:
    p = tmp_path / "SOLUTION.json"
    p.write_text(json.dumps({"frame": pose.as_dict(), "accepted": accepted}))
    return p


@pytest.mark.parametrize("path,name,fragment", [
    (CELL, "nosuch", "no frame named"),
    (REFS, "dup", "ambiguous"),
    (CELL, "wobjMoving", "moving user frame"),
    (CELL, "wNoValue", "no literal value"),
    (REFS, "partial", "no literal value"),
])
def test_refusals_always(tmp_path, capsys, path, name, fragment):
    sol = solution(tmp_path, Pose.from_abc(1, 2, 3, 0, 0, 0))
    before = path.read_bytes()
    for force in ([], ["--force"]):
        rc = main(["patch", str(path), "--frame", name, "--measured", str(sol), *force])
        assert rc == 2
        err = capsys.readouterr().err
        assert fragment in err and err.count("\n") == 1
    assert path.read_bytes() == before


@pytest.mark.parametrize("path,name,fragment", [
    (CELL, "tHeld", "held by the robot"),
    (CELL, "wobjHeld", "robhold TRUE"),
    (CELL, "wobjMoving.oframe", "not a fixed frame in robot world"),
    (CELL, "wobjHeld.oframe", "not a fixed frame in robot world"),
    (CELL, "pCorr", "not robot world"),
    (REFS, "nozzle", "BASE_TYPE #TCP"),
    (REFS, "positioner", "external kinematic"),
    (REFS, "gripper", "flange"),
])
def test_reference_refusals_unless_force(tmp_path, capsys, path, name, fragment):
    sol = solution(tmp_path, Pose.from_abc(1, 2, 3, 0, 0, 0))
    rc = main(["patch", str(path), "--frame", name, "--measured", str(sol)])
    assert rc == 2
    err = capsys.readouterr().err
    assert fragment in err and "--force" in err
    rc = main(["patch", str(path), "--frame", name, "--measured", str(sol), "--force"])
    assert rc == 0
    out, err = capsys.readouterr()
    assert out.startswith("--- a/") and "warning" in err
    # explicit values are taken in the frame's own reference: no refusal
    assert main(["patch", str(path), "--frame", name, "--set", "1,2,3,0,0,0"]) == 0


def test_measured_fits_world_frames(tmp_path, capsys):
    sol = solution(tmp_path, Pose.from_abc(1, 2, 3, 10, 0, 0))
    for path, name in [(CELL, "wobjTable"), (CELL, "tFixed"), (CELL, "wobjPlain.oframe"),
                       (CELL, "wobjPlain"), (REFS, "table")]:
        assert main(["patch", str(path), "--frame", name, "--measured", str(sol)]) == 0, name
    assert main(["patch", str(CELL), "--frame", "wobjPlain", "--oframe", "--measured", str(sol)]) == 0
    capsys.readouterr()


def test_measured_object_frame_is_written_in_its_user_frame(tmp_path, capsys):
    """world = uframe * oframe, so a measured world frame W goes into the
    object frame as uframe^-1 * W; diff compares it there too."""
    from ucsio import api

    world = Pose.from_abc(620.0, 75.0, 12.5, 30.0, 0.0, 0.0)
    result = api.patch(CELL, "wobjOffset.oframe", world, measured=True)
    assert result.warnings == []
    patched = parse(Document(result.new_bytes, CELL))
    back = patched.frame("wobjOffset.oframe")
    uframe = patched.frame("wobjOffset").pose
    assert (back.pose.x, back.pose.y, back.pose.z) == pytest.approx((120.0, 75.0, 12.5), abs=1e-9)
    assert uframe.compose(back.pose).abc == pytest.approx(world.abc, abs=1e-4)
    d = api.diff_frame(CELL, "wobjOffset.oframe", world)
    assert (d["dx"], d["dy"], d["dz"]) == pytest.approx((20.0, 25.0, 12.5), abs=1e-9)


def test_rejected_solution_refused(tmp_path, capsys):
    sol = solution(tmp_path, Pose.from_abc(1, 2, 3, 0, 0, 0), accepted=False)
    before = CELL.read_bytes()
    # a rejected dataset is a failed gate (SPEC: exit 1), for patch and diff alike
    assert main(["patch", str(CELL), "--frame", "wobjTable", "--measured", str(sol)]) == 1
    assert "rejected" in capsys.readouterr().err
    assert main(["diff", str(CELL), "--frame", "wobjTable", "--measured", str(sol)]) == 1
    assert "rejected" in capsys.readouterr().err and CELL.read_bytes() == before


def test_shared_pers_refused(tmp_path, capsys):
    for folder, same in (("shared_diff", "different value"), ("shared_same", "same value")):
        f = PATCH / folder / "MainModule.mod"
        rc = main(["patch", str(f), "--frame", "wobjShared", "--set", "1,2,3,0,0,0"])
        assert rc == 2
        err = capsys.readouterr().err
        assert "Pallet.mod" in err and same in err
        assert main(["patch", str(f), "--frame", "wobjShared", "--set", "1,2,3,0,0,0",
                     "--force"]) == 0
        assert "warning" in capsys.readouterr().err
    # LOCAL PERS is the module's own
    f = PATCH / "shared_diff" / "MainModule.mod"
    assert main(["patch", str(f), "--frame", "wobjLocal", "--set", "1,2,3,0,0,0"]) == 0
    capsys.readouterr()


def test_usage_errors(capsys):
    assert main(["patch", str(CELL), "--frame", "wobjTable", "--set", "1,2,3"]) == 2
    assert main(["patch", str(CELL), "--frame", "wobjTable", "--set-q", "1,2,3,0,0,0,0"]) == 2
    assert main(["patch", str(CELL), "--frame", "wobjTable", "--set", "1,2,3,0,0,0",
                 "--backup"]) == 2
    assert main(["patch", str(CELL), "--frame", "wobjTable"]) == 2   # a usage error returns 2
    capsys.readouterr()


# ------------------------------------------------------------------ writing

def crlf_variants(tmp_path) -> list[Path]:
    """The same module with UTF-8 BOM + CRLF, Latin-1 + CR CR LF, and LF without a final newline."""
    text = CELL.read_text()
    out = []
    for sub in ("a", "b", "c"):       # one folder each: the same PERS in siblings is refused
        (tmp_path / sub).mkdir()
    a = tmp_path / "a" / "bom_crlf.mod"
    a.write_bytes(b"\xef\xbb\xbf" + text.replace("\n", "\r\n").replace("fixture:", "fixture \u00e9:").encode("utf-8"))
    b = tmp_path / "b" / "latin1_crcrlf.mod"
    b.write_bytes(text.replace("\n", "\r\r\n").replace("fixture:", "fixture \u00f1:").encode("latin-1"))
    c = tmp_path / "c" / "nofinal.mod"
    c.write_bytes(text.rstrip("\n").encode())
    out += [a, b, c]
    return out


def test_in_place_keeps_encoding_line_endings_and_permissions(tmp_path, capsys):
    for f in crlf_variants(tmp_path):
        os.chmod(f, 0o640)
        before = f.read_bytes()
        rc = main(["patch", str(f), "--frame", "wobjTable", "--set", "1200.5,-430.25,710,31,0,0",
                   "--in-place", "--backup"])
        assert rc == 0
        after = f.read_bytes()
        assert Path(str(f) + ".bak").read_bytes() == before
        assert stat.S_IMODE(f.stat().st_mode) == 0o640
        assert after[:3] == before[:3]
        assert after.count(b"\r\r\n") == before.count(b"\r\r\n")
        assert after.count(b"\r\n") == before.count(b"\r\n")
        assert after.endswith(b"\n") == before.endswith(b"\n")
        old_doc, new_doc = Document(before, f), Document(after, f)
        assert old_doc.encoding == new_doc.encoding
        again = load(f).frame("wobjTable")
        assert close_pose(again.pose, Pose.from_abc(1200.5, -430.25, 710, 31, 0, 0))
        # only the changed numbers differ
        old_f = parse(old_doc).frame("wobjTable")
        assert spliced_out(old_doc.text, [n.span for n in old_f.numbers.values()]) == \
            spliced_out(new_doc.text, [n.span for n in again.numbers.values()])
        assert temp_files(f.parent) == []
    capsys.readouterr()


def test_output_elsewhere_and_preview_writes_nothing(tmp_path, capsys):
    f = tmp_path / "cell.mod"
    shutil.copy(CELL, f)
    before = f.read_bytes()
    assert main(["patch", str(f), "--frame", "wobjTable", "--set", "1,2,3,4,5,6"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("--- a/") and "\n+++ b/" in out and "\n-" in out and "\n+" in out
    assert f.read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == ["cell.mod"]
    (tmp_path / "out").mkdir()
    o = tmp_path / "out" / "cell.mod"
    assert main(["patch", str(f), "--frame", "wobjTable", "--set", "1,2,3,4,5,6", "-o", str(o)]) == 0
    assert f.read_bytes() == before
    assert close_pose(load(o).frame("wobjTable").pose, Pose.from_abc(1, 2, 3, 4, 5, 6))
    capsys.readouterr()
    assert main(["patch", str(f), "--frame", "wobjTable", "--set", "1,2,3,4,5,6", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)["patch"]
    assert d["changed"] and d["written"] is None and d["diff"].startswith("--- a/")
    assert {c["component"] for c in d["changes"]} >= {"x", "y", "z"}


def test_write_failure_leaves_original_and_no_temp(tmp_path, capsys, monkeypatch):
    """Running as root, a chmod-read-only folder does not stop writes; make
    the rename itself fail instead, and write into a folder that does not exist."""
    f = tmp_path / "cell.mod"
    shutil.copy(CELL, f)
    before = f.read_bytes()

    def refuse(src, dst):
        raise PermissionError(13, "Permission denied")
    monkeypatch.setattr(os, "replace", refuse)
    rc = main(["patch", str(f), "--frame", "wobjTable", "--set", "1,2,3,4,5,6", "--in-place"])
    assert rc == 2 and "Permission denied" in capsys.readouterr().err
    assert f.read_bytes() == before and temp_files(tmp_path) == []
    monkeypatch.undo()
    rc = main(["patch", str(f), "--frame", "wobjTable", "--set", "1,2,3,4,5,6",
               "-o", str(tmp_path / "missing" / "out.mod")])
    assert rc == 2 and "does not exist" in capsys.readouterr().err
    assert f.read_bytes() == before and temp_files(tmp_path) == []


def test_file_changed_between_read_and_write(tmp_path, capsys, monkeypatch):
    f = tmp_path / "cell.mod"
    shutil.copy(CELL, f)
    # API: plan, then someone saves the file on the controller PC
    cf = load(f)
    res = patch_frame(cf, "wobjTable", Pose.from_abc(1, 2, 3, 0, 0, 0))
    edited = f.read_bytes().replace(b"wobjHeld", b"wobjHELD")
    f.write_bytes(edited)
    with pytest.raises(UcsioError, match="changed on disk"):
        save(res)
    assert f.read_bytes() == edited and temp_files(tmp_path) == []
    # CLI: the change lands while the patch is being planned
    import ucsio.review.patch as patch_mod
    real_verify = patch_mod.verify_patch

    def verify_and_touch(result):
        real_verify(result)
        f.write_bytes(edited + b"\n")
    monkeypatch.setattr(patch_mod, "verify_patch", verify_and_touch)
    rc = main(["patch", str(f), "--frame", "wobjTable", "--set", "1,2,3,4,5,6",
               "--in-place", "--backup"])
    assert rc == 2 and "changed on disk" in capsys.readouterr().err
    assert f.read_bytes() == edited + b"\n"
    assert temp_files(tmp_path) == [] and not Path(str(f) + ".bak").exists()


def test_api_round_trip(tmp_path):
    from ucsio import api
    f = tmp_path / "cell.mod"
    shutil.copy(CELL, f)
    target = Pose.from_abc(1201, -431, 706, 30.5, 0.2, -0.1)
    res = api.patch(f, "wobjTable", target)
    assert res.diff.startswith("--- a/") and res.changed
    assert api.save(res, backup=True) == str(f)
    assert close_pose(api.frame(f, "wobjTable").pose, target)
    assert Path(str(f) + ".bak").read_bytes() == CELL.read_bytes()
    assert math.isclose(api.diff_frame(f, "wobjTable", target)["dt_mean"], 0, abs_tol=1e-3)


def test_quaternion_written_with_q1_not_negative():
    cf = load(CELL)
    neg = cf.frame("wobjNeg")                      # the file has q1 < 0
    assert neg.numbers["q1"].value < 0
    same = Pose.from_quat(neg.pose.x, neg.pose.y, neg.pose.z, neg.pose.q)
    assert plan(neg, same) == []                   # same orientation: no byte changes
    turned = Pose.from_abc(neg.pose.x, neg.pose.y, neg.pose.z, 30.0, 0.0, 0.0)
    by = {c.component: c.new for c in plan(neg, turned)}
    assert float(by["q1"]) > 0


# at B = 90 only A - C matters: of the triples with A - C = -30, the one
# nearest the old A 90, B -25, C 0 (issue 24, the reviewer's diff)
@pytest.mark.parametrize("given,written", [((10.0, 100.0, 0.0), (-170.0, 80.0, 180.0)),
                                           ((0.0, 90.0, 30.0), (30.0, 90.0, 60.0)),
                                           ((370.0, 0.0, 0.0), (10.0, 0.0, 0.0)),
                                           ((0.0, 0.0, -180.0), (0.0, 0.0, 180.0))])
def test_kuka_angles_written_in_spec_ranges(given, written):
    cf = load(REFS)
    res = patch_frame(cf, "spec_base", Pose.from_abc(1, 2, 3, *given), measured=False)
    back = parse(Document(res.new_bytes, REFS)).frame("spec_base")
    assert [back.numbers[k].value for k in "abc"] == pytest.approx(written, abs=1e-9)
    assert rot.quat_angle(back.pose.q, rot.abc_to_quat(*given)) < 1e-4


def test_only_siblings_that_name_the_pers_are_parsed(tmp_path, monkeypatch):
    """The shared-PERS check parses a sibling module only when its bytes
    hold the data's name (any case); the refusal still finds the real one."""
    import ucsio.vendors.abb.rapid

    decl = 'PERS wobjdata wobjA:=[FALSE,TRUE,"",[[1,2,3],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n'
    (tmp_path / "cell.mod").write_text("MODULE cell\n  " + decl + "ENDMODULE\n")
    (tmp_path / "same.mod").write_text("MODULE same\n  " + decl.replace("wobjA", "WOBJA")
                                       + "ENDMODULE\n")
    (tmp_path / "other.mod").write_text("MODULE other\n  " + decl.replace("wobjA", "wobjAB")
                                        + "ENDMODULE\n")
    parsed = []
    real = ucsio.vendors.abb.rapid.parse
    monkeypatch.setattr(ucsio.vendors.abb.rapid, "parse",
                        lambda doc, *a, **k: parsed.append(Path(doc.path).name) or real(doc, *a, **k))
    cf = load(tmp_path / "cell.mod")
    with pytest.raises(UcsioError, match="also declared in same.mod"):
        patch_frame(cf, "wobjA.oframe", Pose.from_abc(1, 2, 4, 0, 0, 0), measured=False)
    assert "other.mod" not in parsed and "same.mod" in parsed


# -- the diff a patch shows ------------------------------------------------------
def _whole_file_diff(doc, new_bytes, label, n=1):
    """The diff from every line of both files, trimmed to the changed lines
    and their context before difflib matches them (what unified_diff did
    before it split only the changed window into lines): the reference."""
    import difflib
    import re

    from ucsio.parsing.document import text_lines

    new_text = Document(new_bytes, doc.path).text
    a, b = text_lines(doc.text), text_lines(new_text)
    lo, limit = 0, min(len(a), len(b))
    while lo < limit and a[lo] == b[lo]:
        lo += 1
    hi = 0
    while hi < limit - lo and a[-1 - hi] == b[-1 - hi]:
        hi += 1
    lo, hi = max(0, lo - n), max(0, hi - n)
    out = difflib.unified_diff(a[lo:len(a) - hi], b[lo:len(b) - hi], f"a/{label}", f"b/{label}",
                               n=n, lineterm="")
    hunk = re.compile(r"^@@ -(\d+)(,\d+)? \+(\d+)(,\d+)? @@")
    out = [hunk.sub(lambda m: f"@@ -{int(m[1]) + lo}{m[2] or ''} +{int(m[3]) + lo}{m[4] or ''} @@",
                    line, count=1) if line.startswith("@@") and lo else line for line in out]
    return "\n".join(out) + ("\n" if new_text != doc.text else "")


from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@settings(max_examples=300, deadline=None, derandomize=True, database=None)
@given(lines=st.lists(st.sampled_from(["a", "b", "PERS x:=1;", "", "  ! c", "9E9"]),
                      min_size=0, max_size=30),
       eol=st.sampled_from(["\n", "\r\n", "\r\r\n", "\r"]), final=st.booleans(),
       edits=st.lists(st.tuples(st.integers(0, 10 ** 6), st.integers(0, 3),
                                st.sampled_from(["", "1", "x\n", "\n", "-0.5", "b"])),
                      min_size=1, max_size=3))
def test_patch_diff_from_the_changed_window_equals_the_whole_file_diff(lines, eol, final, edits):
    from ucsio.review.unified import unified_diff

    text = eol.join(lines) + (eol if final and lines else "")
    new = text
    for at, cut, put in edits:
        at = at % (len(new) + 1)
        new = new[:at] + put + new[at + cut:]
    if eol == "\r":
        new = new.replace("\n", "\r")       # a bare-CR file stays one
    doc = Document(text.encode(), "m.mod")
    assert unified_diff(doc, new.encode(), "m.mod") == _whole_file_diff(doc, new.encode(), "m.mod")


@pytest.mark.parametrize("head,why", [('FALSE,FALSE,"STN_1"', "moves"),
                                      ('TRUE,TRUE,""', "wrist")])
def test_forced_object_frame_under_a_moving_or_held_user_frame(tmp_path, capsys, head, why):
    """Issue 18, point 5: --force on the object frame of a moving (ufprog
    FALSE) or robot-held wobj wrote the world pose unchanged; the README says
    an object frame gets uframe^-1 * world. It does, with the user frame the
    file holds, checked against scipy, and the warning says so."""
    from scipy.spatial.transform import Rotation

    u_rot = Rotation.from_euler("ZYX", [30.0, 10.0, -20.0], degrees=True)
    x, y, z, w = u_rot.as_quat()
    q = [round(float(v), 6) for v in (w, x, y, z)]
    u_t = np.array([400.0, -250.0, 120.0])
    mod = tmp_path / "cell.mod"
    mod.write_text("MODULE Cell\n  TASK PERS wobjdata wobjX:=[" + head + ",[[400,-250,120],["
                   + ",".join(repr(v) for v in q) + "]],[[0,0,0],[1,0,0,0]]];\nENDMODULE\n")
    world = Pose.from_abc(1200.0, 300.0, 650.0, 75.0, -5.0, 12.0)
    sol = solution(tmp_path, world)
    args = ["patch", str(mod), "--frame", "wobjX.oframe", "--measured", str(sol)]
    assert main(args) == 2
    assert "--force" in capsys.readouterr().err
    out = tmp_path / "out.mod"
    assert main([*args, "--force", "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert "uframe⁻¹ · world" in err and why in err and "--force" in err, err
    # scipy: oframe = uframe^-1 * world, with the user frame as the file holds it
    u = Rotation.from_quat([q[1], q[2], q[3], q[0]])
    w_rot = Rotation.from_quat([world.q[1], world.q[2], world.q[3], world.q[0]])
    want_t = u.inv().apply(np.array(world.t) - u_t)
    want_r = u.inv() * w_rot
    back = load(out).frame("wobjX.oframe").pose
    assert np.allclose(back.t, want_t, atol=TRANS_TOL), (back.t, want_t)
    got_r = Rotation.from_quat([back.q[1], back.q[2], back.q[3], back.q[0]])
    assert np.degrees((want_r.inv() * got_r).magnitude()) <= ANGLE_TOL
    # and diff compares it there too, with the same warning
    from ucsio import api
    d = api.diff_frame(mod, "wobjX.oframe", world)
    assert [d["measured"][k] for k in "xyz"] == pytest.approx(list(want_t), abs=1e-6)
    assert "uframe⁻¹ · world" in d["warning"] and why in d["warning"]


def test_object_frame_under_a_user_frame_without_value_is_refused_even_forced(tmp_path, capsys):
    mod = tmp_path / "cell.mod"
    mod.write_text('MODULE Cell\n  TASK PERS wobjdata wobjZ:=[FALSE,FALSE,"STN_1",'
                   '[[0,0,0],[1,0,0,"x"]],[[1,2,3],[1,0,0,0]]];\nENDMODULE\n')
    sol = solution(tmp_path, Pose.from_abc(1200.0, 300.0, 650.0, 75.0, -5.0, 12.0))
    before = mod.read_bytes()
    for force in ([], ["--force"]):
        assert main(["patch", str(mod), "--frame", "wobjZ.oframe", "--measured", str(sol),
                     "--in-place", *force]) == 2
        err = capsys.readouterr().err
        assert "no literal value" in err and err.count("\n") == 1
    assert mod.read_bytes() == before


@settings(max_examples=400, derandomize=True, deadline=None)
@given(st.lists(st.sampled_from("abcdef"), max_size=12), st.lists(st.sampled_from("abcdefgh"),
                                                                  max_size=12),
       st.integers(0, 3), st.integers(0, 50))
def test_a_patch_s_hunk_is_the_one_difflib_writes(a, b, n, shift):
    """The hunk written without difflib (a patch's rewritten lines, none of
    which the other side holds) is byte for byte difflib's, header included;
    where lines could be matched, difflib writes it."""
    from ucsio.review.unified import _difflib_lines, common_ends, unified_lines

    lo, hi = common_ends(a, b)
    want = list(_difflib_lines(a, b, lo, hi, "a/x", "b/x", n, shift))
    assert list(unified_lines(a, b, "a/x", "b/x", n, shift=shift)) == want


@pytest.mark.parametrize("a, b", [(["c1", "c2", "X 1", "W 1", "c3"], ["c1", "c2", "X 2", "W 2", "c3"]),
                                  (["c", "old"], ["c"]), ([], ["new"]), (["x"], ["y"]),
                                  (["c", "a", "c"], ["c", "b", "c"])])
def test_a_patch_s_usual_hunk_is_written_without_difflib(a, b):
    from ucsio.review.unified import _difflib_lines, _one_hunk, common_ends

    lo, hi = common_ends(a, b)
    got = _one_hunk(a, b, lo, hi, "a/x", "b/x", 1, 7)
    assert got is not None and got == list(_difflib_lines(a, b, lo, hi, "a/x", "b/x", 1, 7))
