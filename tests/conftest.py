"""Shared test helpers: where the real-file corpus and our fixtures live."""
from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import settings

# Every property test draws the same examples on every run: the suite is
# deterministic (a test's own @settings keeps this unless it says otherwise).
settings.register_profile("ucsio", derandomize=True)
settings.load_profile("ucsio")

ROOT = Path(__file__).resolve().parents[1]
FIXTURES = ROOT / "fixtures"
# ../shared/corpus beside the checkout (CI lays it there); tests read it in place.
CORPUS = ROOT.parent / "shared" / "corpus"


def corpus_files(vendor: str) -> list:
    """Corpus files as pytest params; one skipped param (saying why) if absent."""
    folder = CORPUS / vendor
    if not folder.is_dir():
        return [pytest.param(None, marks=pytest.mark.skip(reason=f"{folder} is absent: "
                                                           "the shared corpus is not beside this checkout"))]
    return [pytest.param(p, id=p.name[-60:]) for p in sorted(folder.iterdir()) if p.is_file()]


def corpus_file(vendor: str, name_part: str) -> Path:
    folder = CORPUS / vendor
    if not folder.is_dir():
        pytest.skip(f"{folder} is absent: the shared corpus is not beside this checkout")
    hits = [p for p in folder.iterdir() if name_part in p.name]
    assert len(hits) == 1, f"{name_part!r} matches {len(hits)} corpus files"
    return hits[0]
