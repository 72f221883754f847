"""A patched listing's frame is read back from its element under its
record's head (``vendors.fanuc.write.as_module``), not from the whole file
again: what the whole file's read-back accepts and refuses, it accepts and
refuses, on sampled frames of every corpus listing; where the element alone
does not read back, the whole file is read as before."""
from __future__ import annotations

import random

import pytest

from conftest import CORPUS
from ucsio.errors import UcsioError
from ucsio.geometry import rotations as rot
from ucsio.geometry.frames import Pose
from ucsio.parsing.controller import load
from ucsio.review import verify
from ucsio.review.patch import patch_frame

LISTINGS = sorted(p for p in (CORPUS / "fanuc").glob("*") if p.name.lower() == "sysframe.va"
                  or p.name.lower().endswith("__sysframe.va")) if (CORPUS / "fanuc").is_dir() \
    else []
needs_corpus = pytest.mark.skipif(not LISTINGS, reason="../shared/corpus/fanuc is not here")


def near(pose: Pose, rng: random.Random, x: float | None = None) -> Pose:
    """A pose near ``pose``; ``x``: its X instead (one the controller cannot
    hold: 1e7 mm, which the read-back's range lint refuses; 1e39, beyond a
    REAL, which the reader itself refuses)."""
    q = rot.quat_multiply(pose.q, rot.abc_to_quat(*(rng.uniform(-30, 30) for _ in range(3))))
    t = [c + rng.uniform(-50, 50) for c in pose.t]
    if x is not None:
        t[0] = x
    return Pose.from_quat(*t, q)


def outcome(cf, name: str, pose: Pose, whole: bool, monkeypatch) -> str:
    """'ok' or the refusal's message, read back by the element (or the whole file)."""
    with monkeypatch.context() as m:
        if whole:
            m.setattr(verify, "_reread_declaration", lambda result: None)
        try:
            patch_frame(cf, name, pose, measured=False, force=True)
        except UcsioError as exc:
            return exc.message
    return "ok"


@needs_corpus
@pytest.mark.parametrize("path", LISTINGS, ids=lambda p: p.name[-40:])
def test_every_frame_of_the_corpus_reads_back_alike_by_its_element(path, monkeypatch):
    cf = load(path)
    rng = random.Random(path.name)
    frames = [f for f in cf.frames if f.pose is not None]
    assert frames
    # the first and last frame of each record (user frames, tools), and some between
    # (every frame: 30 s)
    ends = [f for kind in sorted({f.type for f in frames})
            for f in ([g for g in frames if g.type == kind][:1]
                      + [g for g in frames if g.type == kind][-1:])]
    frames = ends + rng.sample(frames, min(len(frames), 6))
    for frame in frames:
        for x in (None, 1e7, 1e39):
            pose = near(frame.pose, rng, x)
            got = outcome(cf, frame.name, pose, False, monkeypatch)
            assert got == outcome(cf, frame.name, pose, True, monkeypatch), frame.name
            assert (got == "ok") == (x is None), (frame.name, got)
    # and the element alone is what read them back
    calls = []
    read = verify._reread_declaration
    monkeypatch.setattr(verify, "_reread_declaration",
                        lambda result: calls.append(read(result)) or calls[-1])
    for frame in frames:
        patch_frame(cf, frame.name, near(frame.pose, rng), measured=False, force=True)
    assert calls and all(c is not None for c in calls)


def test_an_element_whose_head_is_not_found_reads_the_whole_file(monkeypatch):
    """A head the backwards search does not find (an element alone): the
    element does not read back, and the whole file is read instead."""
    from ucsio.vendors.fanuc.write import as_module
    element = "  [1,1] = \n  Group: 1   Config: N U T, 0, 0, 0\n"
    assert as_module(element, "  [1,9] = \n") == element
    head = "[*SYSTEM*]$MNUFRAME  Storage: SHADOW  Access: RW  : ARRAY[1,9] OF POSITION\n"
    assert as_module(element, "first line\n" + head + "  [1,0] =\n  X: 1\n") == head + element
