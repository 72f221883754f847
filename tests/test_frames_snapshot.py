"""Every controller file's frames, against a stored snapshot (issue 26, point 6).

``frames --json --all`` (in-process: ``ucsio.api.frames``) of every file of
the shared corpus of every registered vendor (ucsio.vendors) and of every controller file
among the fixtures, compared with tests/expected/frames_snapshot.json: per
file, each frame's name, type, reference, parent, label, set, and x y z a b c
rounded to 1e-6 (a file that cannot be read: its error's message). It guards
moves that must change no behaviour: every frame unchanged.

After a change that is meant to change frames, regenerate the snapshot and
review its diff before committing it:

    python tests/test_frames_snapshot.py --update

The corpus part is skipped (saying why) where ../shared/corpus is absent.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))   # conftest, also as a script

from conftest import CORPUS, FIXTURES  # noqa: E402

from ucsio import vendors as registry  # noqa: E402

SNAPSHOT = Path(__file__).resolve().parent / "expected" / "frames_snapshot.json"
# Every registered vendor's corpus folder, every suffix a backup is read for: a
# vendor added to the registry has its files here (without a snapshot until --update).
VENDORS = tuple(e.name for e in registry.VENDORS)
SUFFIXES = registry.BACKUP_SUFFIXES


def _files(folder: Path) -> list[Path]:
    return sorted(p for p in folder.rglob("*") if p.is_file() and p.suffix.lower() in SUFFIXES)


def corpus_files() -> dict[str, Path]:
    return {f"corpus/{p.relative_to(CORPUS).as_posix()}": p
            for v in VENDORS if (CORPUS / v).is_dir() for p in _files(CORPUS / v)}


def fixture_files() -> dict[str, Path]:
    return {f"fixtures/{p.relative_to(FIXTURES).as_posix()}": p for p in _files(FIXTURES)}


def _round(v):
    return None if v is None else round(v, 6) + 0.0          # -0.0 and 0.0 alike


def snapshot_of(path: Path):
    """One file's frames, compactly: [name, type, reference, parent_kind:parent,
    label, set, [x, y, z, a, b, c] or None]; or {"error": message}."""
    from ucsio import api
    from ucsio.errors import UcsioError
    try:
        doc = api.frames([str(path)])
    except UcsioError as exc:
        return {"error": exc.message}
    return [[f["name"], f["type"], f["reference"], f"{f['parent_kind']}:{f['parent']}",
             f.get("label"), f["set"],
             None if f["x"] is None else [_round(f[k]) for k in ("x", "y", "z", "a", "b", "c")]]
            for f in doc["frames"]]


def stored() -> dict:
    return json.loads(SNAPSHOT.read_text(encoding="utf-8"))


def _compare(files: dict[str, Path]) -> None:
    want = stored()
    missing = sorted(set(files) - set(want))
    assert not missing, f"files without a snapshot (run this file with --update): {missing}"
    prefix = next(iter(files)).split("/", 1)[0] + "/"
    gone = sorted(n for n in want if n.startswith(prefix) and n not in files)
    assert not gone, f"files in the snapshot no longer read: {gone}"
    changed = [name for name, p in files.items() if snapshot_of(p) != want[name]]
    assert not changed, f"frames changed in {changed} (this file's docstring says how to update)"


def test_fixture_frames_are_the_snapshot():
    _compare(fixture_files())


@pytest.mark.skipif(not CORPUS.is_dir(), reason=f"{CORPUS} is absent: the shared corpus is "
                                               "not beside this checkout")
def test_corpus_frames_are_the_snapshot():
    files = corpus_files()
    assert len(files) > 60                      # the three vendors' folders were found
    _compare(files)


def _entry(name: str, got) -> str:
    """One frame a line, so that a change reads as a diff of the frames it moves."""
    def dump(v):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(got, dict) or not got:
        return f"{dump(name)}: {dump(got)}"
    return f"{dump(name)}: [\n  " + ",\n  ".join(dump(f) for f in got) + "\n]"


def update() -> None:
    if not CORPUS.is_dir():
        sys.exit(f"{CORPUS} is absent: the snapshot needs the corpus")
    files = {**corpus_files(), **fixture_files()}
    SNAPSHOT.write_text("{\n" + ",\n".join(_entry(name, snapshot_of(p))
                                            for name, p in sorted(files.items())) + "\n}\n",
                        encoding="utf-8")
    print(f"{SNAPSHOT}: {len(files)} files")


if __name__ == "__main__":
    if sys.argv[1:] != ["--update"]:
        sys.exit(__doc__)
    update()
