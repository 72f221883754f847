"""Parse every byte with the grammar, prove the byte-exact round trip, and lint
(unnormalised quaternions, robot-held tools without mass, moving user frames,
KUKA labels and references). Exit 1 when there is any warning; an "info"
(legal code worth knowing, such as a PERS whose value another module gives)
does not fail the check."""
from __future__ import annotations

from ..output import emit_json


def add_arguments(p) -> None:
    p.add_argument("files", nargs="+", metavar="FILE")


def round_trip(cf) -> bool:
    """What a patch relies on: the bytes ucsio writes for the unedited
    document are the file's bytes; parsing them again gives the same frames;
    and every frame number's span holds exactly that number, so a patch
    replaces the number and nothing beside it."""
    from ..controller import parse
    from ..document import Document

    doc = cf.document
    out = doc.to_bytes()
    if out != doc.raw:
        return False
    again = parse(Document(out, doc.path), full=True)
    if [f.as_dict() for f in again.frames] != [f.as_dict() for f in cf.frames]:
        return False
    for f in cf.frames:
        for n in f.numbers.values():
            if doc.slice(n.span) != n.text:   # the span holds the number exactly as written
                return False
    return True


def check_file(path: str) -> dict:
    from ..controller import parse
    from ..document import Document

    doc = Document.read(path)
    cf = parse(doc, full=True)
    return {"file": path, "vendor": cf.vendor, "encoding": doc.encoding + ("-bom" if doc.bom else ""),
            "frames": len(cf.frames), "round_trip": round_trip(cf),
            "lints": [l.as_dict() for l in cf.lints]}


def run(args) -> int:
    results = [check_file(f) for f in args.files]
    bad = any(not r["round_trip"] or any(l["severity"] != "info" for l in r["lints"])
              for r in results)
    if args.json:
        emit_json({"files": results, "ok": not bad})
        return 1 if bad else 0
    for r in results:
        status = "round trip ok" if r["round_trip"] else "ROUND TRIP FAILED"
        print(f"{r['file']}: {r['vendor']}, {r['encoding']}, {r['frames']} frames, {status}")
        for l in r["lints"]:
            print(f"{r['file']}:{l['line']}:{l['col']}: {l['severity']}: {l['code']}: {l['message']}")
    return 1 if bad else 0
