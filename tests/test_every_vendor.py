"""What every registered vendor gets without a test of its own (issue 26,
docs/architecture.md "Adding a vendor"): each file of its corpus folder with
one of its suffixes (or a first line it claims) reads, round-trips byte for byte, has each frame number
at its span, and gives the same frames on the fast path as through the
whole-file grammar. (Its frames are also held by tests/test_frames_snapshot.py,
its files are fuzz seeds: tests/fuzzing.py.)"""
from __future__ import annotations

import re

import pytest

from conftest import CORPUS

from ucsio import vendors
from ucsio.parsing.controller import parse
from ucsio.parsing.document import Document


def _params():
    out = []
    for e in vendors.VENDORS:
        folder = CORPUS / e.name
        if not folder.is_dir():
            out.append(pytest.param(e.name, None, marks=pytest.mark.skip(
                reason=f"{folder} is absent: the shared corpus is not beside this checkout")))
            continue
        out += [pytest.param(e.name, p, id=f"{e.name}:{p.name[-50:]}")
                for p in sorted(folder.rglob("*")) if _reads(e, p)]
    return out


def _reads(e, path) -> bool:
    """Whether ``path`` is a file of vendor ``e`` that ucsio reads: by its
    suffix, or by the first line the vendor claims (Yaskawa's RBCALIB.DAT,
    in both its versions) where no refusal stands for it yet."""
    from ucsio.parsing import foreign
    if not path.is_file() or path.suffix.lower() in (".md", ".tsv"):
        return False
    if path.suffix.lower() in e.suffixes:
        return True
    head = path.read_bytes()[:512].decode("latin-1")
    return vendors.claimed(head) == e.name and foreign.other_vendor(path.name, head) is None


def _frames(cf) -> list:
    return [(f.as_dict(), {k: (n.span, n.text) for k, n in f.numbers.items()}) for f in cf.frames]


@pytest.mark.parametrize("vendor, path", _params())
def test_corpus_file_reads_and_round_trips(vendor, path):
    raw = path.read_bytes()
    doc = Document(raw, str(path))
    assert doc.to_bytes() == raw
    assert vendors.detect(doc) == vendor
    fast = parse(doc)
    assert fast.vendor == vendor
    whole = parse(Document(raw, str(path)), full=True)
    assert _frames(fast) == _frames(whole)
    for f in fast.frames:
        for key, num in f.numbers.items():
            text = doc.slice(num.span)
            assert text == num.text, (f.name, key)
            assert float(re.sub(r"^([+-])\s+", r"\1", text)) == num.value, (f.name, key)


def test_every_vendor_has_corpus_files():
    """The parametrisation found each registered vendor's files (not an empty run)."""
    if not CORPUS.is_dir():
        pytest.skip(f"{CORPUS} is absent: the shared corpus is not beside this checkout")
    counts = {e.name: sum(1 for p in (CORPUS / e.name).rglob("*")
                          if p.is_file() and p.suffix.lower() in e.suffixes)
              for e in vendors.VENDORS}
    assert all(n > 0 for n in counts.values()), counts
