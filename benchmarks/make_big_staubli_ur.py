"""A Stäubli .dtx and a Universal Robots .installation of a given size, in the
corpus's style, for the cold-start benchmark (bench_cold.py).

    python benchmarks/make_big_staubli_ur.py OUT.dtx OUT.installation [--kb 30]

The .dtx is the s7 / CS9 dialect as the corpus's ros_server.dtx writes it
(BOM, LF, attributes left out where zero): station frames hanging from
world and from each other, tools from the flange, and pointRx tables taught
in the frames, until the file is the size asked for. The .installation is
PolyScope 5.11's XML (../shared/corpus/ur) with TCPs and point features,
gzip around it as PolyScope writes it (fixed header, zlib level 6); its
size is the file's, the gzip's. Numbers are seeded random with the
precision the controllers write (Java doubles for UR), so the files
compress and parse like real ones. Standard library only.
"""
from __future__ import annotations

import argparse
import math
import random
import zlib
from pathlib import Path

DTX_HEAD = ('\ufeff<?xml version="1.0" encoding="utf-8"?>\n'
            '<Database xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" '
            'xmlns="http://www.staubli.com/robotics/VAL3/Data/2">\n  <Datas>\n')
DTX_TAIL = "  </Datas>\n</Database>\n"


def _num(rng: random.Random, span: float, decimals: int) -> str:
    return f"{rng.uniform(-span, span):.{decimals}f}".rstrip("0").rstrip(".")


def _dtx_block(rng: random.Random, k: int) -> str:
    """One station: a frame of 4 entries (the first from world, the rest from
    it), a tool, and a pointRx table of 6 entries taught in the frame."""
    lines = [f'    <Data name="fStation{k}" access="public" xsi:type="array" type="frame" '
             'size="4">']
    for e in range(4):
        father = "world[0]" if e == 0 else f"fStation{k}[0]"
        values = " ".join(f'{c}="{_num(rng, 1500 if c in "xyz" else 180, 3)}"'
                          for c in ("x", "y", "z", "rx", "ry", "rz") if rng.random() > 0.15)
        lines.append(f'      <Value key="{e}" {values} fatherId="{father}" />')
    lines.append("    </Data>")
    lines.append(f'    <Data name="tTool{k}" access="public" xsi:type="array" type="tool" '
                 'size="1">')
    lines.append(f'      <Value key="0" x="{_num(rng, 50, 2)}" z="{abs(float(_num(rng, 400, 2)))}" '
                 f'ry="{_num(rng, 45, 1)}" fatherId="flange[0]" ioLink="valve1" />')
    lines.append("    </Data>")
    lines.append(f'    <Data name="pStation{k}" access="public" xsi:type="array" '
                 'type="pointRx" size="6">')
    for e in range(6):
        values = " ".join(f'{c}="{_num(rng, 800 if c in "xyz" else 180, 5)}"'
                          for c in ("x", "y", "z", "rx", "ry", "rz"))
        lines.append(f'      <Value key="{e}" {values} shoulder="righty" elbow="epositive" '
                     f'wrist="wpositive" fatherId="fStation{k}[{e % 4}]" />')
    lines.append("    </Data>")
    return "\n".join(lines) + "\n"


def big_dtx(kb: int = 30, seed: int = 30) -> bytes:
    rng = random.Random(seed)
    body, k = [], 0
    size = len(DTX_HEAD.encode()) + len(DTX_TAIL)
    while size < kb * 1000:
        block = _dtx_block(rng, k)
        body.append(block)
        size += len(block.encode())
        k += 1
    return (DTX_HEAD + "".join(body) + DTX_TAIL).encode("utf-8")


def java_double(v: float) -> str:
    """As Java's Double.toString writes a double: "E" notation below 1e-3 and from 1e7."""
    from decimal import Decimal
    v = float(v) + 0.0
    if v == 0 or 1e-3 <= abs(v) < 1e7:
        return repr(v)
    sign, digits, exponent = Decimal(repr(v)).as_tuple()
    shown = "".join(map(str, digits)).rstrip("0") or "0"
    return (("-" if sign else "") + shown[0] + "." + (shown[1:] or "0")
            + f"E{exponent + len(digits) - 1}")


def _rotvec(rng: random.Random) -> list[float]:
    axis = [rng.gauss(0, 1) for _ in range(3)]
    norm = math.sqrt(sum(a * a for a in axis))
    angle = rng.uniform(0.1, math.pi - 0.01)
    return [a / norm * angle for a in axis]


def _values(values) -> str:
    return ", ".join(java_double(v) for v in values)


def _point(rng: random.Random, k: int) -> str:
    uid = f"d{k:07x}-0000-4000-8000-000000000000"
    return "\n".join([
        "    <GeomPoseNode>",
        f'      <GeomPoseNode showAxes="true" joggable="true" isVariable="false" id="{uid}" '
        f'name="Point_{k}">',
        f'        <jointPositionVector value="{_values(rng.uniform(-3, 3) for _ in range(6))}"/>',
        f'        <toolPosition value="{_values(rng.uniform(-0.9, 0.9) for _ in range(3))}"/>',
        f'        <toolAxisAngle value="{_values(_rotvec(rng))}"/>',
        '        <tcpOffset value="0.0, 0.0, 0.15, 0.0, 0.0, 0.0"/>',
        "      </GeomPoseNode>",
        "    </GeomPoseNode>"]) + "\n"


def installation_xml(points: int, seed: int = 30) -> str:
    rng = random.Random(seed)
    head = ('<Installation directory="/programs" fileName="big" showSpeedSliderOnRunTab="false">\n'
            '  <Version projectName="URSoftware" major="5" minor="11" bugfix="0" '
            'buildNumber="108249" buildDate="May 19 2021, 12:00:00"/>\n'
            "  <SafetySettings>\n[Safety Checksum]\nversion = 5.5\ncrc = 123456789\n\n"
            "</SafetySettings>\n  <Features>\n    <BaseView>\n"
            '      <BaseView showAxes="true" joggable="true" isVariable="false" '
            'id="1b785537-e70a-4c26-a8af-4602e931277e"/>\n    </BaseView>\n')
    features = "".join(_point(rng, k) for k in range(points))
    tcps = "".join(f'      <tcp id="c{k:07x}-ab01-4b68-bc81-2fe899b7e3fc" name="Tool_{k}" '
                   f'offset="{_values([*(rng.uniform(-0.05, 0.05) for _ in range(2)), 0.15, 0.0, 0.0, rng.uniform(-3, 3)])}"/>\n'
                   for k in range(8))
    return (head + features + "  </Features>\n"
            '  <TCPSettings activePose="Tool_0">\n    <availablePoses>\n' + tcps
            + "    </availablePoses>\n  </TCPSettings>\n</Installation>")


def gzip_as_polyscope(xml: str) -> bytes:
    body = xml.encode("utf-8")
    deflate = zlib.compressobj(6, zlib.DEFLATED, -15, 8, zlib.Z_DEFAULT_STRATEGY)
    stream = deflate.compress(body) + deflate.flush()
    return (bytes.fromhex("1f8b0800000000000000") + stream
            + zlib.crc32(body).to_bytes(4, "little") + len(body).to_bytes(4, "little"))


def big_installation(kb: int = 30) -> bytes:
    """The fewest point features whose file (the gzip) is at least ``kb`` KB."""
    points = 16
    while True:
        data = gzip_as_polyscope(installation_xml(points))
        if len(data) >= kb * 1000:
            return data
        points = max(points + 1, int(points * kb * 1000 / len(data)))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dtx")
    ap.add_argument("installation")
    ap.add_argument("--kb", type=int, default=30)
    args = ap.parse_args(argv)
    Path(args.dtx).write_bytes(big_dtx(args.kb))
    Path(args.installation).write_bytes(big_installation(args.kb))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
