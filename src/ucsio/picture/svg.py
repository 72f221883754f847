"""Three orthographic projections of a scene (XY, XZ, YZ) as plain SVG: they
print and read without script. Each measured point is one ``circle.point``
(nothing else in them is a circle); residuals are magnified as in 3D."""
from __future__ import annotations

from html import escape

VIEWS = (("XY", 0, 1), ("XZ", 0, 2), ("YZ", 1, 2))
SIZE, PAD = 300, 30
AXIS_COLOURS = ("#d62728", "#2ca02c", "#1f77b4")     # X red, Y green, Z blue


def projections(s: dict) -> str:
    return "".join(_view(s, name, i, j) for name, i, j in VIEWS)


def _view(s: dict, name: str, i: int, j: int) -> str:
    cx, cy = s["center"][i], s["center"][j]
    k = (SIZE - 2 * PAD) / (s["size"] * 1.3)

    def xy(p):
        return (SIZE / 2 + (p[i] - cx) * k, SIZE / 2 - (p[j] - cy) * k)

    out = [f'<figure class="proj"><svg id="svg-{name}" viewBox="0 0 {SIZE} {SIZE}" '
           f'width="{SIZE}" height="{SIZE}" role="img" aria-label="{name} view">',
           f'<rect class="bg" width="{SIZE}" height="{SIZE}"/>']
    for f, dash in ((s.get("simulated"), ' stroke-dasharray="4 3"'), (s["measured"], "")):
        if f:
            o = xy(f["origin"])
            for axis, colour in zip(f["axes"], AXIS_COLOURS):
                e = xy([f["origin"][m] + axis[m] * s["axis_length"] for m in range(3)])
                out.append(f'<line x1="{o[0]:.1f}" y1="{o[1]:.1f}" x2="{e[0]:.1f}" '
                           f'y2="{e[1]:.1f}" stroke="{colour}" stroke-width="2"{dash}/>')
    for w in s["working"]:
        x, y = xy(w["at"])
        out.append(f'<rect class="working" x="{x - 3:.1f}" y="{y - 3:.1f}" width="6" height="6">'
                   f'<title>{escape(w["name"])}</title></rect>')
    if s.get("plan"):
        for p in s["plan"]["points"]:
            x, y = xy(p["at"])
            out.append(f'<path class="planned" d="M{x:.1f} {y - 5:.1f}l5 5-5 5-5-5z">'
                       f'<title>{escape(p["name"])}</title></path>')
    for p in s["points"]:
        x, y = xy(p["tracker"])
        e = xy([p["tracker"][m] + p["drawn"][m] for m in range(3)])
        cls = "point" if p["used"] else "point excluded"
        out.append(f'<line class="residual" x1="{x:.1f}" y1="{y:.1f}" x2="{e[0]:.1f}" '
                   f'y2="{e[1]:.1f}"/>')
        out.append(f'<circle class="{cls}" cx="{x:.1f}" cy="{y:.1f}" r="4" '
                   f'data-name="{escape(p["name"])}"><title>{escape(p["name"])}: '
                   f'{p["residual"]:.3f} mm</title></circle>')
        if not p["used"]:
            out.append(f'<text x="{x + 6:.1f}" y="{y - 6:.1f}">{escape(p["name"])} '
                       f'{p["residual"]:.2f} mm</text>')
    bar = s["scale_bar"] * k
    out.append(f'<line class="scale" x1="10" y1="{SIZE - 10}" x2="{10 + bar:.1f}" '
               f'y2="{SIZE - 10}"/><text x="10" y="{SIZE - 14}">{s["scale_bar"]:g} mm</text>')
    out.append(f'<text x="{SIZE - 10}" y="16" text-anchor="end">{name}</text></svg>'
               f'<figcaption>{name}: {name[0]} to the right, {name[1]} up</figcaption></figure>')
    return "".join(out)
