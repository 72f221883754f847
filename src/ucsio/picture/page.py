"""A scene as one self-contained HTML page: the numbers in a JSON block
(``#ucsio-scene``, what tests and scripts read back), the 3D view drawn by
three.js (inlined, or linked where a report shares one copy), three static SVG
projections that need no script."""
from __future__ import annotations

import os
from html import escape

from .svg import projections

HERE = os.path.dirname(os.path.abspath(__file__))
THREE_DIR = os.path.join(HERE, "three")


def three_version() -> str:
    with open(os.path.join(THREE_DIR, "VERSION"), encoding="utf-8") as f:
        return f.read().strip()


def library_script() -> str:
    """three.js as a classic script defining ``THREE``.

    The vendored file is three's ES module build, unchanged; its one
    ``export{a as B,...}`` becomes the object the function returns, so the
    page runs it from an inline script: a module would have to be imported
    from a URL (a request) or a blob."""
    with open(os.path.join(THREE_DIR, "three.module.min.js"), encoding="utf-8") as f:
        text = f.read()
    at = text.rfind("export{")
    end = text.find("}", at)
    if at < 0 or end < 0 or "</script" in text.lower():
        raise RuntimeError("the vendored three.js is not the single-file module build "
                           "tools/update_three.sh fetches")
    pairs = []
    for item in text[at + len("export{"):end].split(","):
        local, _, public = item.strip().partition(" as ")
        pairs.append(f"{public or local}:{local}")
    return (f"/* three.js {three_version()}, MIT licence: Copyright 2010-2024 three.js "
            "authors (ucsio/picture/three/LICENSE) */\n"
            'var THREE=(function(){"use strict";' + text[:at]
            + "return{" + ",".join(pairs) + "};})();\n")


def write_library(folder: str, name: str = "three.js") -> str:
    """One shared copy of ``library_script`` in ``folder`` (for pages that
    link it: ``page(scene, library=name)``); returns its path."""
    from ..files import atomic_write_text
    path = os.path.join(folder, name)
    atomic_write_text(path, library_script())
    return path


def _json_block(data) -> str:
    import json

    from ..output import _clean
    text = json.dumps(_clean(data), ensure_ascii=False, allow_nan=False, separators=(",", ":"))
    return text.replace("<", "\\u003c")            # no </script> or <!-- inside the block


def _asset(name: str) -> str:
    """A script shipped beside this module (viewer.js, report_view.js)."""
    with open(os.path.join(HERE, name), encoding="utf-8") as f:
        return f.read()


def page(scene: dict, *, library: str | None = None) -> str:
    """The HTML page of ``scene``. ``library``: None inlines three.js (a page
    that opens from disk alone); a relative URL links a shared copy instead."""
    lib = (f'<script src="{escape(library)}"></script>' if library is not None
           else f"<script>{library_script()}</script>")
    title = escape(f"ucsio view: {scene['title']}")
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{title}</title>
<style>{CSS}</style></head>
<body>
<h1>{title}</h1>
<p class="facts">{_facts(scene)}</p>
<div id="stage"><div id="view3d" aria-label="3D view: drag to rotate, right-drag or shift-drag
 to pan, wheel to zoom"></div><div id="labels"></div>
<div id="tools"><button id="reset" type="button">reset view</button>
<span id="scale"><span id="scale-bar"></span> <span id="scale-text"></span></span></div>
<div id="info" aria-live="polite">hover or click a point for its numbers</div>
<noscript><p>The 3D view needs script; the projections below do not.</p></noscript></div>
{_legend(scene)}
<section id="static"><h2>Projections (mm, {escape(scene['coordinates'])})</h2>
{projections(scene)}</section>
<script type="application/json" id="ucsio-scene">{_json_block(scene)}</script>
{lib}
<script>{_asset("viewer.js")}</script>
</body></html>
"""


def _facts(s: dict) -> str:
    n = len(s["points"])
    used = sum(p["used"] for p in s["points"])
    parts = [f"{n} points, {used} used", f"residuals drawn ×{s['magnify']:g}",
             f"units mm, {escape(s['coordinates'])}"]
    if s.get("rms") is not None:
        parts.insert(1, f"rms {s['rms']:.3f} mm")
    d = s.get("delta")
    if d and d.get("dist") is not None:
        parts.append(f"Δ simulated → measured {d['dist']:.3f} mm, {d['angle']:.4f}°")
    if s.get("accepted") is False:
        parts.append("REJECTED: " + escape(str(s.get("reason") or "")))
    return " · ".join(parts)


def _legend(s: dict) -> str:
    items = [("swatch sw-tracker", "tracker point, mapped through the fit"),
             ("swatch sw-robot", "robot point (flange · TCP)"),
             ("swatch sw-residual", f"residual robot − fit, drawn ×{s['magnify']:g}"),
             ("swatch sw-excluded", "excluded point (named)"),
             ("swatch sw-measured", "measured frame: X red, Y green, Z blue")]
    if s.get("simulated"):
        items.append(("swatch sw-simulated", "simulated frame (dashed), Δ its offset"))
    if s["working"]:
        items.append(("swatch sw-working", "working point: predicted 95 % error, green low to "
                                        "red high; the worst named"))
    if s.get("plan"):
        items += [("swatch sw-planned", "planned point"), ("swatch sw-add", "suggested point"),
                  ("swatch sw-drop", "point plan would drop")]
    lis = "".join(f'<li class="item"><span class="{c}"></span>{escape(t)}</li>' for c, t in items)
    return f'<ul id="legend" class="legend">{lis}</ul>'


def report_page(*, library: str = "three.js", data: str = "entries.js") -> str:
    """The one page of a batch report's pictures: the same layout as
    ``page``, filled in the browser by report_view.js from ``data`` (every
    entry's fit and point pairs) for the entry the address's #k names, so a
    fleet's pictures cost one page and one data file, not a page each."""
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>ucsio view</title>
<style>{CSS}</style></head>
<body>
<h1>ucsio view</h1>
<p class="facts"></p>
<div id="stage"><div id="view3d" aria-label="3D view: drag to rotate, right-drag or shift-drag
 to pan, wheel to zoom"></div><div id="labels"></div>
<div id="tools"><button id="reset" type="button">reset view</button>
<span id="scale"><span id="scale-bar"></span> <span id="scale-text"></span></span></div>
<div id="info" aria-live="polite">hover or click a point for its numbers</div>
<noscript><p>This page draws from the report's data with script; ucsio view SOLUTION.json
writes a page whose projections need none.</p></noscript></div>
<ul id="legend" class="legend"></ul>
<section id="static"><h2>Projections (mm, robot world (the measured frame's parent))</h2>
<div id="projections"></div></section>
<script src="{escape(data)}"></script>
<script>{_asset("report_view.js")}</script>
<script src="{escape(library)}"></script>
<script>{_asset("viewer.js")}</script>
</body></html>
"""


CSS = """
body{font:14px/1.4 system-ui,sans-serif;margin:16px;color:#222;background:#fff}
h1{font-size:18px;margin:0 0 4px}h2{font-size:15px}
.facts{margin:0 0 8px;color:#444}
#stage{position:relative;width:100%;height:560px;border:1px solid #ccc}
#view3d{position:absolute;inset:0}#labels{position:absolute;inset:0;pointer-events:none;overflow:hidden}
.label{position:absolute;font-size:12px;white-space:nowrap;transform:translate(6px,-50%);color:#222}
.label.excluded{color:#b00}.label.delta{color:#555;font-weight:600}.label.worst{color:#a00}
#tools{position:absolute;left:8px;bottom:8px;display:flex;gap:12px;align-items:center}
#scale-bar{display:inline-block;height:4px;background:#222;vertical-align:middle}
#info{position:absolute;right:8px;top:8px;max-width:320px;background:#fffe;border:1px solid #ccc;
padding:6px 8px;font-size:12px;white-space:pre-line}
.legend{list-style:none;padding:0;display:flex;flex-wrap:wrap;gap:6px 18px;margin:8px 0}
.swatch{display:inline-block;width:12px;height:12px;margin-right:6px;vertical-align:middle}
.sw-tracker{background:#e6007e;border-radius:50%}.sw-robot{background:#555;border-radius:50%;
width:8px;height:8px}.sw-residual{background:#ff7f0e;height:3px}
.sw-excluded{border:2px solid #000;border-radius:50%;background:#e6007e}
.sw-measured{background:linear-gradient(90deg,#d62728 33%,#2ca02c 33% 66%,#1f77b4 66%);height:3px}
.sw-simulated{background:repeating-linear-gradient(90deg,#888 0 4px,#fff 4px 7px);height:3px}
.sw-working{background:linear-gradient(90deg,#2ca02c,#d62728)}.sw-planned{background:#17becf;
transform:rotate(45deg)}.sw-add{background:#2ca02c;transform:rotate(45deg)}
.sw-drop{border:2px dashed #d62728}
.proj{display:inline-block;margin:0 12px 12px 0}.proj svg{border:1px solid #ccc}
svg .bg{fill:#fff}svg circle.point{fill:#e6007e}svg circle.excluded{stroke:#000;stroke-width:2}
svg .residual{stroke:#ff7f0e;stroke-width:1.5}svg .working{fill:#888}svg .planned{fill:#17becf}
svg .scale{stroke:#222;stroke-width:3}svg text{font-size:11px}
@media print{#stage,#tools{display:none}}
"""
