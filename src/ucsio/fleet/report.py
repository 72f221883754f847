"""The HTML report of ``ucsio batch --report FILE.html``, for a plant manager.

One self-contained file: inline CSS, charts drawn here as inline SVG (no
matplotlib, no scripts, nothing fetched from the network). Read top down:

1. what the run was (when, which ucsio, which manifest, tolerance,
   threshold, min points) in one line;
2. **what needs action**: every entry over tolerance, rejected or failed and
   every patched copy that was not written, each with its reason in plain
   words and what to do next (or a green line saying nothing does);
3. the summary cards, the roll-up per station (an entry's ``station``, else
   its controller's folder), the five groups of dt_mean (the grouping of
   the study ucsio's method follows, ``GROUPS_SOURCE``) and the noise check,
   said once with the count of entries it concerns;
4. the charts, each with a legend and labelled axes: dt_mean per entry on
   an axis where every group is equally wide, and each entry's measurement
   error e against the outlier threshold, on a log axis so that passing bars,
   the threshold and gross outliers all read;
5. the table of entries (with how far taught points move, where asked) and
   each entry's details: the diff, its points and their residuals (a chart
   with a legend), the determinacy numbers, links to its patched copy.

Symbols keep their plain words beside them: dt_mean is the average shift of
the frame along x, y and z; e the mean distance of the used points from the
fitted frame.

Any value may be missing or null (an entry that failed after it was solved
has points and residuals but no e; a hand-edited JSON may lack anything): a
missing number is drawn as "–", never an error.

Numbers for machines: the whole ``--json`` document is embedded as
``<script type="application/json" id="ucsio-data">`` (data, never run); the
summary cells carry ``data-key``/``data-value`` and every entry row
``data-name``, ``data-status``, ``data-e``, ``data-dt-mean``, ``data-group``,
``data-pass`` (and a rejected entry's ``data-reason``).
"""
from __future__ import annotations

import datetime as _dt
import html
import json
import math
import os
from typing import Any, Sequence

from .. import defaults
from ..method.noise import P_WARN
from ..output import fmt
from ..review.diff import GROUP_BOUNDS

GROUP_COLORS = ("#2e7d32", "#7cb342", "#f9a825", "#ef6c00", "#c62828")
GROUP_WORDS = ("small", "moderate", "large", "very large", "extreme")
STATUS_CLASS = {"pass": "ok", "over tolerance": "warn", "rejected": "bad", "error": "err"}
STATUS_WORDS = {"pass": "passed", "over tolerance": "over tolerance", "rejected": "rejected",
                "error": "failed"}
BAR = "#1f6feb"
BAD = "#c62828"
E_WORDS = "mean distance of the used points from the fitted frame"
DT_WORDS = "average shift of the frame along x, y and z"

CSS = """
:root { --fg:#1d2329; --muted:#5f6b76; --line:#d9dee3; --bg:#ffffff; --panel:#f6f8fa; }
* { box-sizing: border-box; }
body { font: 14px/1.45 -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif;
       color: var(--fg); background: var(--bg); margin: 0 auto; padding: 20px 32px;
       max-width: 1200px; }
h1 { font-size: 22px; margin: 0 0 4px; }
h2 { font-size: 17px; margin: 26px 0 10px; border-bottom: 1px solid var(--line);
     padding-bottom: 4px; }
#meta { color: var(--muted); font-size: 12.5px; margin: 0 0 14px; display: flex;
        flex-wrap: wrap; gap: 2px 18px; }
#meta b { color: var(--fg); font-weight: 600; }
#meta code { word-break: break-all; }
#actions { border: 2px solid #b26a00; border-radius: 8px; padding: 10px 16px 6px;
           background: #fff8ec; }
#actions.clear { border-color: #2e7d32; background: #eef7ef; }
#actions h2 { margin: 0 0 6px; border: 0; padding: 0; }
#actions h3 { font-size: 15px; margin: 10px 0 2px; }
#actions ol { margin: 2px 0 6px; padding-left: 26px; }
#actions li { margin: 0 0 3px; }
#actions li .todo { margin-left: 6px; }
#actions .todo { color: #1d2329; }
#actions p.todo { margin: 0 0 2px; }
#actions .todo::before { content: "What to do: "; font-weight: 600; }
.cards { display: flex; flex-wrap: wrap; gap: 12px; }
.card { background: var(--panel); border: 1px solid var(--line); border-radius: 6px;
        padding: 8px 14px; min-width: 120px; }
.card .v { font-size: 22px; font-weight: 600; }
.card .k { color: var(--muted); font-size: 12px; }
.card.ok .v { color: #2e7d32; } .card.warn .v { color: #b26a00; }
.card.bad .v { color: #c62828; } .card.err .v { color: #6a1b9a; }
.card.info .v { color: #455a64; }
table { border-collapse: collapse; font-variant-numeric: tabular-nums; }
th, td { padding: 3px 10px; border-bottom: 1px solid var(--line); text-align: left;
         vertical-align: top; }
th { background: var(--panel); font-weight: 600; }
th small { display: block; font-weight: 400; color: var(--muted); font-size: 11px; }
td.n, th.n { text-align: right; }
.swatch { display: inline-block; width: 12px; height: 12px; border-radius: 2px;
          margin-right: 6px; vertical-align: -1px; }
.swatch.line { height: 0; border-top: 2px dashed #1d2329; border-radius: 0; width: 18px;
               vertical-align: 3px; }
.swatch.line.red { border-top-color: #c62828; }
.swatch.outline { background: none; border: 1.5px solid #1f6feb; }
.pill { display: inline-block; padding: 0 8px; border-radius: 9px; font-size: 12px; color: #fff; }
.pill.ok { background: #2e7d32; } .pill.warn { background: #b26a00; }
.pill.bad { background: #c62828; } .pill.err { background: #6a1b9a; }
.pill.info { background: #455a64; }
figure.chart { background: var(--panel); border: 1px solid var(--line); border-radius: 6px;
               padding: 8px; margin: 0; }
figure.chart svg { display: block; width: 100%; height: auto; }
figure.chart.small { display: inline-block; align-self: flex-start; }
figure.chart.small svg { width: auto; }
.legend { font-size: 12px; color: var(--fg); display: flex; flex-wrap: wrap; gap: 4px 16px;
          margin: 6px 4px 0; }
.note { color: var(--muted); font-size: 12px; margin: 6px 0 0; }
details { border-bottom: 1px solid var(--line); padding: 4px 0; }
details summary { cursor: pointer; }
details .body { display: flex; flex-wrap: wrap; gap: 18px 24px; padding: 8px 0 12px 18px; }
.err-msg { color: #6a1b9a; font-family: ui-monospace, Consolas, monospace; font-size: 12px; }
code, .mono { font-family: ui-monospace, Consolas, monospace; font-size: 12px; }
svg text { font-family: -apple-system, "Segoe UI", Roboto, Arial, sans-serif; }
@media print { details { break-inside: avoid; } #actions { break-inside: avoid; } }
"""


def _e(s: Any) -> str:
    return html.escape("" if s is None else str(s), quote=True)


def _f(v: Any, digits: int = 3) -> str:
    return fmt(_num(v), digits, none="\u2013")


def _num(v: Any) -> Any:
    """A finite number (ints, floats, bools kept), else None."""
    if isinstance(v, bool) or isinstance(v, int):
        return v
    if isinstance(v, float):
        return v if math.isfinite(v) else None
    return None


def _g(v: Any) -> str:
    """A number in its shortest form ("–" when missing)."""
    v = _num(v)
    return "\u2013" if v is None or isinstance(v, bool) else f"{v:g}"


def _attr(v: Any) -> str:
    """A number as a data-* value: repr precision, empty for null."""
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return ""
    if isinstance(v, bool):
        return "true" if v else "false"
    return repr(v) if isinstance(v, float) else str(v)


def _dict(v: Any) -> dict:
    return v if isinstance(v, dict) else {}


def _legend(items: Sequence[tuple[str, str]]) -> str:
    """An HTML legend: (swatch HTML, label) pairs."""
    return ('<figcaption class="legend">'
            + "".join(f'<span class="item">{sw}{_e(label)}</span>' for sw, label in items)
            + "</figcaption>")


def _swatch(color: str, cls: str = "") -> str:
    style = f"background:{color}" if "line" not in cls and "outline" not in cls else \
        (f"border-color:{color}" if color else "")
    return f'<span class="swatch {cls}" style="{style}"></span>'


# ---------------------------------------------------------------- charts

def _group_axis(dt: float, top: float) -> float:
    """dt_mean (mm) -> position 0..5 on an axis where each group is one unit wide."""
    edges = (0.0, *GROUP_BOUNDS, top)
    for k in range(len(edges) - 1):
        lo, hi = edges[k], edges[k + 1]
        if dt < hi or k == len(edges) - 2:
            return k + min(max((dt - lo) / (hi - lo), 0.0), 1.0)
    return float(len(edges) - 1)


#: Where the five groups of dt_mean come from (SPEC's "Diff"): the report
#: shows them itself, so it cites the study, not a table of it.
GROUPS_SOURCE = ("The five groups of dt_mean (below 10, 25, 50 and 100 mm, and from 100 mm on) "
                 "are the grouping of the published study ucsio's method follows (its Table 4); "
                 "this run's accepted entries are counted in them here.")


def _p(value) -> str:
    v = _num(value)
    return "–" if v is None else f"{v:.1g}"


def _noise_check(entries: list) -> str:
    """The noise check's explanation once, with how many entries it concerns
    (each entry's details keep only its own numbers)."""
    noisy = [e for e in entries if _dict(e.get("consistency")).get("message")
             and e.get("status") != "error"]
    if not noisy:
        return ""
    names = ", ".join(str(e.get("name")) for e in noisy[:8]) + \
        (f" and {len(noisy) - 8} more" if len(noisy) > 8 else "")
    return ('<p class="note warning" id="noise-check" '
            f'data-count="{len(noisy)}">Noise check: {len(noisy)} of {len(entries)} '
            f'entr{"y" if len(entries) == 1 else "ies"} ({_e(names)}) have residuals far above '
            "the stated noise √(σ_laser² + σ_robot²): residuals that large would happen with "
            f"p below {P_WARN:g} if the stated noise were right (χ²). The tracker, the robot or the "
            "stated σ (--sigma-laser, --sigma-robot) is off. Their precision uses the "
            "residuals' σ; each entry's details give its numbers.</p>")


def _correlation(c: dict) -> str:
    """The Pearson line, folded away with what it shows: near 1 whenever the
    frames lie metres apart, whatever their errors."""
    return ('<details class="note" id="correlation-details"><summary>Correlation of simulated '
            'and measured positions</summary><p class="note" id="correlation" '
            + " ".join(f'data-{k}="{_attr(c.get(k))}"' for k in "xyz")
            + ">Pearson correlation of the simulated and the measured frame positions over "
              "passing entries: " + ", ".join(f"{k} {_f(c.get(k), 5)}" for k in "xyz")
            + ". Where the frames lie metres apart across the cells, it is near 1 whatever "
              "their errors: it shows that each measured frame is the simulated one moved, "
              "not how far. How far is dt_mean, above.</p></details>")

def histogram_svg(dts: Sequence[tuple[float, int]], bins_per_group: int = 5,
                  tolerance: float | None = None) -> str:
    """dt_mean histogram. ``dts``: (dt_mean, group) of the accepted entries."""
    W, H, left, right, top_pad, bottom = 1100, 300, 56, 20, 30, 50
    top = max([100.0 * 1.5] + [d for d, _ in dts])
    top = float(math.ceil(top / 50.0) * 50.0)
    n_bins = bins_per_group * 5
    counts = [0] * n_bins
    for d, _ in dts:
        pos = _group_axis(d, top)
        counts[min(int(pos * bins_per_group), n_bins - 1)] += 1
    ymax = max(counts + [1])
    ystep = max(1, math.ceil(ymax / 5))
    ymax = ystep * math.ceil(ymax / ystep)
    pw, ph = W - left - right, H - top_pad - bottom

    def X(pos):
        return left + pw * pos / 5.0

    def Y(c):
        return top_pad + ph * (1 - c / ymax)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {W} {H}" role="img" '
           f'aria-label="number of entries by dt_mean">']
    for g in range(5):   # group bands
        out.append(f'<rect x="{X(g):.1f}" y="{top_pad}" width="{pw / 5:.1f}" height="{ph}" '
                   f'fill="{GROUP_COLORS[g]}" opacity="0.07"/>')
        out.append(f'<text x="{X(g + 0.5):.1f}" y="{top_pad - 9}" text-anchor="middle" '
                   f'font-size="13" fill="{GROUP_COLORS[g]}" font-weight="600">group {g + 1}</text>')
    for k in range(0, ymax + 1, ystep):
        y = Y(k)
        out.append(f'<line x1="{left}" x2="{W - right}" y1="{y:.1f}" y2="{y:.1f}" stroke="#d9dee3"/>')
        out.append(f'<text x="{left - 8}" y="{y + 4:.1f}" text-anchor="end" font-size="13" '
                   f'fill="#1d2329">{k}</text>')
    bw = pw / n_bins
    for b, c in enumerate(counts):
        if not c:
            continue
        g = b // bins_per_group
        out.append(f'<rect class="bin" data-bin="{b}" data-count="{c}" '
                   f'x="{X(b / bins_per_group) + 1:.1f}" y="{Y(c):.1f}" width="{bw - 2:.1f}" '
                   f'height="{Y(0) - Y(c):.1f}" fill="{GROUP_COLORS[g]}"><title>{c} '
                   f'entr{"y" if c == 1 else "ies"}</title></rect>')
        out.append(f'<text x="{X((b + 0.5) / bins_per_group):.1f}" y="{Y(c) - 3:.1f}" '
                   f'text-anchor="middle" font-size="12" fill="#1d2329">{c}</text>')
    for k, bound in enumerate(GROUP_BOUNDS, 1):   # the group boundaries
        x = X(k)
        out.append(f'<line class="boundary" data-mm="{bound:g}" x1="{x:.1f}" x2="{x:.1f}" '
                   f'y1="{top_pad}" y2="{Y(0):.1f}" stroke="#1d2329" stroke-dasharray="5 4"/>')
    if tolerance is not None and tolerance < top:
        x = X(_group_axis(tolerance, top))
        out.append(f'<line class="tolerance" data-mm="{tolerance:g}" x1="{x:.1f}" x2="{x:.1f}" '
                   f'y1="{top_pad}" y2="{Y(0):.1f}" stroke="{BAD}" stroke-width="2.5"/>')
    out.append(f'<line x1="{left}" x2="{W - right}" y1="{Y(0):.1f}" y2="{Y(0):.1f}" stroke="#1d2329"/>')
    for k, mm in enumerate((0.0, *GROUP_BOUNDS, top)):
        out.append(f'<text x="{X(k):.1f}" y="{Y(0) + 17:.1f}" text-anchor="middle" font-size="13" '
                   f'fill="#1d2329">{mm:g}</text>')
    out.append(_axis_titles(left + pw / 2, H - 8,
                            f"dt_mean, mm ({DT_WORDS}); each group one fifth of the axis",
                            top_pad + ph / 2, "number of entries"))
    return "".join(out)


def _axis_titles(x_mid: float, x_base: float, x_title: str, y_mid: float, y_title: str) -> str:
    """A chart's axis titles, the y one turned upright, and the end of its svg."""
    return (f'<text x="{x_mid:.1f}" y="{x_base}" text-anchor="middle" font-size="13" '
            f'fill="#1d2329">{x_title}</text>'
            f'<text x="16" y="{y_mid:.1f}" font-size="13" fill="#1d2329" '
            f'transform="rotate(-90 16 {y_mid:.1f})" text-anchor="middle">{y_title}</text>'
            "</svg>")


def histogram_legend(tolerance: float | None) -> str:
    items = [(_swatch(GROUP_COLORS[g]), f"group {g + 1}: {_group_range(g + 1)} "
              f"({GROUP_WORDS[g]})") for g in range(5)]
    items.append((_swatch("#1d2329", "line"), "group boundary"))
    if tolerance is not None:
        items.append((_swatch(BAD, "line red"), f"tolerance {tolerance:g} mm: a frame passes "
                      "below it"))
    return _legend(items)


def _group_range(g: int) -> str:
    lo = 0.0 if g == 1 else GROUP_BOUNDS[g - 2]
    return f"{lo:g}–{GROUP_BOUNDS[g - 1]:g} mm" if g <= len(GROUP_BOUNDS) else f"≥ {lo:g} mm"


def residual_axis(values: Sequence[float], threshold: float | None) -> tuple[float, float]:
    """(bottom, top) of the residual chart's logarithmic axis, whole decades.
    A linear axis drawn to the worst entry (a gross outlier of several mm)
    leaves every passing bar (a few hundredths of a mm) a flat line; on a
    log axis the passing bars, the threshold and the outliers all read."""
    vals = [v for v in values if v is not None and v > 0]
    lo = min(vals + ([threshold] if threshold else []) + [1.0])
    hi = max(vals + ([threshold] if threshold else []) + [0.01])
    bottom = 10.0 ** math.floor(math.log10(max(lo, 1e-4)))
    top = 10.0 ** math.ceil(math.log10(hi * 1.05))
    if top <= bottom:
        top = bottom * 10
    return bottom, top


NAME_CHARS = 24          # an entry's name under its bar, at most (the tooltip has it all)
NAME_FONT = 9.0          # the smallest font the names get (svg units, about px)


def _short(name: str) -> str:
    return name if len(name) <= NAME_CHARS else name[:NAME_CHARS].rstrip() + "…"


def residual_bars_svg(rows: Sequence[dict], threshold: float | None) -> str:
    """One bar per solved entry: e (solid) in front of the largest used
    residual (light); red for a rejected dataset; on a logarithmic axis
    (``residual_axis``). Under each bar its entry's name, turned upright
    (shortened to NAME_CHARS; where the bars are narrower than a line of
    NAME_FONT, every k-th bar is named and the axis title says so). The
    threshold's label sits in the right margin, beside the plot, never over
    the bars."""
    W, left, right, top_pad, plot_h = 1100, 64, 120, 14, 202
    n = max(len(rows), 1)
    rows = [dict(r, e=_num(r.get("e")), max=_num(r.get("max"))) for r in rows]
    pw = W - left - right
    bw = pw / n
    font = min(12.0, max(NAME_FONT, bw * 0.9))
    every = max(1, math.ceil(font / bw))          # names a line apart, never on top of each other
    names = [_short(str(r.get("name") or "")) for r in rows]
    longest = max((len(nm) for k, nm in enumerate(names) if k % every == 0), default=0)
    label_h = 8 + 0.6 * font * longest            # the upright names below the axis
    bottom_pad = label_h + 30
    H = top_pad + plot_h + bottom_pad
    vals = [r["max"] for r in rows if r["max"] is not None] + \
           [r["e"] for r in rows if r["e"] is not None]
    lo, hi = residual_axis(vals, threshold)
    ph = plot_h
    span = math.log10(hi) - math.log10(lo)

    def Y(v):
        v = min(max(v, lo), hi)
        return top_pad + ph * (1 - (math.log10(v) - math.log10(lo)) / span)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {W} {H:.0f}" role="img" '
           f'aria-label="measurement error e per entry">']
    decade = lo
    while decade <= hi * 1.0001:
        for m in (1, 2, 5):
            v = decade * m
            if v > hi * 1.0001:
                break
            y = Y(v)
            major = m == 1
            out.append(f'<line x1="{left}" x2="{W - right}" y1="{y:.1f}" y2="{y:.1f}" '
                       f'stroke="{"#c4cbd2" if major else "#e6e9ec"}"/>')
            out.append(f'<text x="{left - 8}" y="{y + 4:.1f}" text-anchor="end" '
                       f'font-size="{13 if major else 11}" fill="#1d2329">{v:g}</text>')
        decade *= 10
    base = Y(lo)
    for i, r in enumerate(rows):
        x = left + i * bw
        color = BAD if r.get("status") == "rejected" else BAR
        if r.get("max") is not None:
            out.append(f'<rect x="{x + bw * 0.1:.2f}" y="{Y(r["max"]):.1f}" width="{bw * 0.8:.2f}" '
                       f'height="{base - Y(r["max"]):.1f}" fill="{color}" opacity="0.28"/>')
        if r.get("e") is not None:
            out.append(f'<rect class="ebar" data-name="{_e(r.get("name"))}" data-e="{_attr(r["e"])}" '
                       f'x="{x + bw * 0.1:.2f}" y="{Y(r["e"]):.1f}" width="{bw * 0.8:.2f}" '
                       f'height="{base - Y(r["e"]):.1f}" fill="{color}"><title>{_e(r.get("name"))}: '
                       f'e {r["e"]:.3f} mm, max {_f(r.get("max"))} mm</title></rect>')
        if i % every == 0:       # the name, upright, its end at the axis under the bar
            cx, cy = x + bw / 2 + font * 0.35, base + 6
            out.append(f'<text class="ename" x="{cx:.1f}" y="{cy:.1f}" text-anchor="end" '
                       f'font-size="{font:g}" fill="{"#8e1c1c" if color == BAD else "#1d2329"}" '
                       f'transform="rotate(-90 {cx:.1f} {cy:.1f})">{_e(names[i])}</text>')
    if threshold is not None:
        y = Y(threshold)
        out.append(f'<line class="threshold" x1="{left}" x2="{W - right}" y1="{y:.1f}" '
                   f'y2="{y:.1f}" stroke="{BAD}" stroke-width="1.5" stroke-dasharray="6 4"/>'
                   f'<text x="{W - right + 6}" y="{y + 4:.1f}" font-size="13" fill="{BAD}">'
                   f'threshold {threshold:g} mm</text>')
    out.append(f'<line x1="{left}" x2="{W - right}" y1="{base:.1f}" y2="{base:.1f}" stroke="#1d2329"/>')
    named = "" if every == 1 else f"; every {every}{_ordinal(every)} one named"
    out.append(_axis_titles(left + pw / 2, H - 10,
                            f"entries in manifest order ({len(rows)} solved{named})",
                            top_pad + ph / 2, "mm (log scale)"))
    return "".join(out)


def _ordinal(k: int) -> str:
    return "th" if 10 <= k % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(k % 10, "th")


def residual_legend(threshold: float | None) -> str:
    items = [(_swatch(BAR), f"e: {E_WORDS}"),
             (_swatch(BAR + "48"), "largest distance of one used point"),
             (_swatch(BAD), "rejected dataset")]
    if threshold is not None:
        items.append((_swatch(BAD, "line red"), f"outlier threshold {threshold:g} mm"))
    return _legend(items)


def points_svg(points: Sequence[dict], threshold: float) -> str:
    """Small chart of one entry's points: residual (solid), leave-one-out
    residual (outline), threshold line; excluded points red."""
    points = [dict(p, residual=_num(p.get("residual")), loo_residual=_num(p.get("loo_residual")))
              for p in points if isinstance(p, dict)]
    W, H, left, bottom, top_pad = 60 + 34 * max(len(points), 1), 160, 48, 30, 14
    vals = [p["residual"] for p in points if p["residual"] is not None] + \
           [p["loo_residual"] for p in points if p["loo_residual"] is not None]
    ymax = max(vals + [threshold * 1.15])
    cap = max(threshold * 4, 0.1)
    clipped = ymax > cap
    ymax = min(ymax, cap)
    ph = H - top_pad - bottom

    def Y(v):
        return top_pad + ph * (1 - min(v, ymax) / ymax)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
           f'viewBox="0 0 {W} {H}" role="img" aria-label="distance of each point from the fit">',
           f'<line x1="{left}" x2="{W - 4}" y1="{Y(0):.1f}" y2="{Y(0):.1f}" stroke="#1d2329"/>',
           f'<text x="{left - 5}" y="{Y(0) + 4:.1f}" text-anchor="end" font-size="12">0</text>',
           f'<text x="{left - 5}" y="{Y(ymax) + 8:.1f}" text-anchor="end" font-size="12">'
           f'{ymax:.2g}</text>',
           f'<text x="12" y="{top_pad + ph / 2:.1f}" font-size="12" text-anchor="middle" '
           f'transform="rotate(-90 12 {top_pad + ph / 2:.1f})">mm</text>']
    for i, p in enumerate(points):
        x = left + 6 + i * 34
        color = BAR if p.get("used", True) else BAD
        if p["residual"] is not None:
            out.append(f'<rect x="{x}" y="{Y(p["residual"]):.1f}" width="11" '
                       f'height="{Y(0) - Y(p["residual"]):.1f}" fill="{color}"/>')
        if p["loo_residual"] is not None:
            out.append(f'<rect x="{x + 13}" y="{Y(p["loo_residual"]):.1f}" width="11" '
                       f'height="{Y(0) - Y(p["loo_residual"]):.1f}" fill="none" stroke="{color}"/>')
        if clipped and max(p["residual"] or 0, p["loo_residual"] or 0) > ymax:
            out.append(f'<text x="{x + 12}" y="{top_pad + 8}" text-anchor="middle" font-size="11" '
                       f'fill="{color}">▲</text>')
        out.append(f'<text x="{x + 12}" y="{H - 12}" text-anchor="middle" font-size="11">'
                   f'{_e(str(p.get("name") or "")[:6])}</text>')
    y = Y(threshold)
    out.append(f'<line x1="{left}" x2="{W - 4}" y1="{y:.1f}" y2="{y:.1f}" stroke="{BAD}" '
               f'stroke-dasharray="4 3"/>')
    if threshold < ymax * 0.85 and y - Y(0) < -14:    # the threshold's value, unless crowded
        out.append(f'<text x="{left - 5}" y="{y + 4:.1f}" text-anchor="end" font-size="12" '
                   f'fill="{BAD}">{threshold:g}</text>')
    out.append("</svg>")
    return "".join(out)


def points_legend(threshold: float) -> str:
    return _legend([(_swatch(BAR), "distance from the fit"),
                    (_swatch(BAR, "outline"), "from the fit without that point"),
                    (_swatch(BAD), "point left out"),
                    (_swatch(BAD, "line red"), f"threshold {threshold:g} mm")])


# ---------------------------------------------------------------- the page

def _pct(v: Any) -> str:
    v = _num(v)
    return "\u2013" if v is None else f"{100 * v:.1f} %"


def _same(entries: Sequence[dict], key: str) -> str:
    """One manifest-wide value, or the range the entries use."""
    vals = sorted({v for v in (_num(e.get(key)) for e in entries) if v is not None})
    if not vals:
        return "\u2013"
    if len(vals) == 1:
        return f"{vals[0]:g}"
    return f"{vals[0]:g}–{vals[-1]:g} (per entry)"


def _href(target: str, base: str | None) -> str:
    """A link from the report's folder to ``target`` (a relative path where
    the two share a folder tree, so the link survives moving both)."""
    if base is None:
        return target
    try:
        rel = os.path.relpath(os.path.abspath(target), base)
    except ValueError:       # another drive on Windows
        rel = os.path.abspath(target)
    return rel.replace(os.sep, "/")


def _meta(data: dict, entries: list[dict], meta: dict) -> str:
    made = meta.get("generated") or "\u2013"
    parts = [("made", _e(made)), ("by ucsio", _e(meta.get("version") or "\u2013")),
             ("manifest", (f'<a id="manifest-link" href="{_e(_href(data["manifest"], meta["base"]))}">'
                           f"<code>{_e(data['manifest'])}</code></a>")
              if isinstance(data.get("manifest"), str) and meta.get("base")
              else f"<code>{_e(data.get('manifest'))}</code>"),
             ("tolerance", f"{_e(_same(entries, 'tolerance'))} mm"),
             ("outlier threshold", f"{_e(_same(entries, 'threshold'))} mm"),
             ("min points", _e(_same(entries, "min_points")))]
    reaches = sorted({v for v in (_num(_dict(e.get("precision")).get("reach"))
                                  for e in entries) if v is not None})
    if reaches:
        parts.append(("precision checked at", f"{_e(', '.join(f'{r:g}' for r in reaches))} mm "
                      "from the points"))
    links = []
    if meta.get("csv"):
        links.append(f'<a id="csv-link" href="{_e(_href(meta["csv"], meta.get("base")))}">'
                     f'{_e(os.path.basename(meta["csv"]))}</a>')
    if links:
        parts.append(("table (CSV)", " ".join(links)))
    return '<div id="meta">' + "".join(f"<span>{k} <b>{v}</b></span>" for k, v in parts) + "</div>"


# what needs action, by kind: (status, heading, what to do for all of them)
ACTION_KINDS = (
    ("over tolerance", "Over tolerance: the fixture is not where the simulation has it",
     "check that the fixture sits where the cell layout says; if it does, have the programs "
     "corrected (re-teach, or update the frame in the simulation) before they are downloaded."),
    ("rejected", "Rejected: the points do not give a frame to trust",
     "each line says what was wrong and what to do about it."),
    ("error", "Failed: ucsio could not process these entries",
     "fix the input each line names and run the batch again."),
    ("patch error", "Not patched: the corrected controller file was not written",
     "resolve the refusal (or patch by hand with ucsio patch) and run the batch again."),
)


def _why(e: dict) -> tuple[str, str]:
    """(why, what to do beyond the kind's advice) for an entry that needs
    action, in plain words."""
    status = e.get("status")
    frame = e.get("frame_name") or "the frame"
    if status == "over tolerance":
        d = _dict(e.get("diff"))
        why = (f"{frame} is {_f(e.get('dt_mean'), 1)} mm off on average along x, y and z "
               f"(dt_mean; tolerance {_g(e.get('tolerance'))} mm)")
        if _num(d.get("angle")) is not None:
            why += f" and turned by {_f(d.get('angle'), 2)}°"
        pm = _dict(e.get("points_moved"))
        if _num(pm.get("max")) is not None:
            why += f"; its taught points move by up to {_f(pm.get('max'), 1)} mm ({pm.get('worst')})"
        return why + ".", ""
    if status == "rejected":
        reason = _reason(e)
        if e.get("diagnosis"):      # a wrong TCP: the points are fine
            return reason + ".", ("correct the TCP of this entry (its tool or tcp in the "
                                  "manifest, or tcp = \"solve\") and run the batch again; the "
                                  "points need not be measured again.")
        todo = ("measure more points, spread over the whole fixture" if "too few" in reason
                or "pin" in reason else "check the reflector, its TCP, and that the fixture "
                "did not move while measuring, then measure again")
        return reason + ".", todo + "."
    if status == "error":
        todo = {
            "manifest": "fix this entry in the manifest.",
            "controller": "check the controller file and the frame name in the manifest.",
            "tool": "check the tool named in the manifest (file and name).",
            "measurement": "fix or replace the measurement file (the message names the line).",
            "solve": "the points do not define a frame (too few, or on a line): measure "
                     "points spread over the fixture.",
            "diff": "this frame is not a fixed frame in robot world: name the right frame "
                    "in the manifest.",
        }.get(e.get("stage") or "", "")
        return f"{e.get('error') or 'unknown error'}.", todo
    return "", ""


def _action_item(i: int, e: dict, status: str, why: str, todo: str) -> str:
    return (f'<li class="action" data-name="{_e(e.get("name"))}" data-status="{_e(status)}">'
            f'<a href="#e{i}"><b>{_e(e.get("name"))}</b></a> '
            f'<span class="why">{_e(why)}</span>'
            + (f'<span class="todo">{_e(todo)}</span>' if todo else "") + "</li>")


def _actions(entries: list[dict]) -> str:
    """The action list: entries over tolerance, rejected, failed, and
    patched copies not written, each kind with what to do, each entry with
    its reason in plain words."""
    kinds = []
    total = 0
    for status, heading, todo in ACTION_KINDS:
        items = []
        for i, e in enumerate(entries):
            if status == "patch error":
                if e.get("patch_error"):
                    items.append(_action_item(i, e, status, f"{e['patch_error']}.", ""))
            elif e.get("status") == status:
                why, more = _why(e)
                items.append(_action_item(i, e, status, why, more))
        if not items:
            continue
        total += len(items)
        cls = {"over tolerance": "warn", "rejected": "bad"}.get(status, "err")
        kinds.append(f'<div class="kind" data-kind="{_e(status)}"><h3><span class="pill {cls}">'
                     f'{len(items)}</span> {_e(heading)}</h3><p class="todo">{_e(todo)}</p>'
                     f'<ol>{"".join(items)}</ol></div>')
    unset = [(i, e) for i, e in enumerate(entries)
             if e.get("simulated_set") is False and e.get("status") != "error"]
    if unset:
        total += len(unset)
        kinds.append('<div class="kind" data-kind="unset"><h3><span class="pill warn">'
                     f'{len(unset)}</span> Simulated frame unset: the difference is the whole '
                     'measured pose</h3><p class="todo">check the frame named in the manifest '
                     '(an unset entry is most often the wrong number); where it is right, the '
                     'measured frame is new, not a correction of the simulation.</p><ol>'
                     + "".join(_action_item(i, e, "unset", _unset_words(e), "")
                               for i, e in unset) + "</ol></div>")
    unplaced = [(i, e) for i, e in enumerate(entries) if e.get("points_error")]
    if unplaced:
        total += len(unplaced)
        kinds.append('<div class="kind" data-kind="points error"><h3><span class="pill err">'
                     f'{len(unplaced)}</span> Taught points not placed</h3><p class="todo">check '
                     'the frame data in the controller file.</p><ol>'
                     + "".join(_action_item(i, e, "points error", f"{e['points_error']}.", "")
                               for i, e in unplaced) + "</ol></div>")
    if not kinds:
        n = len(entries)
        return ('<section id="actions" class="clear"><h2>Nothing needs action</h2>'
                f'<p>All {n} entr{"y" if n == 1 else "ies"} passed: the measured frames are '
                'within tolerance and the programs can be used as they are.</p></section>')
    return (f'<section id="actions"><h2>Needs action: {total}</h2>' + "".join(kinds)
            + "</section>")


def _unset_words(e: dict) -> str:
    """The entry's unset-frame warning (batch puts it in ``warnings``)."""
    for w in e.get("warnings") or []:
        if isinstance(w, str) and " is unset " in w:
            return w + "."
    return f"{e.get('frame_name') or 'the frame'} is unset."


def _stations(entries: list[dict]) -> str:
    """Per station (the entry's ``station``, else its controller's folder):
    entries, how many passed, the worst dt_mean, the mean e."""
    by: dict[str, list[dict]] = {}
    for e in entries:
        by.setdefault(station_of(e), []).append(e)
    points = any(isinstance(e.get("points_moved"), dict) for e in entries)
    head = ('<table id="stations"><tr><th>station</th><th class="n">entries</th>'
            '<th class="n">passed</th><th class="n">over tolerance</th><th class="n">rejected</th>'
            '<th class="n">failed</th><th class="n">worst dt_mean<small>largest average shift, '
            'mm</small></th><th class="n">mean e<small>measurement error, mm</small></th>'
            + ('<th class="n">taught points move<small>up to, mm</small></th>' if points else "")
            + "</tr>")
    rows = []
    for st in sorted(by):
        es = by[st]
        count = {s: sum(e.get("status") == s for e in es)
                 for s in ("pass", "over tolerance", "rejected", "error")}
        dts = [v for v in (_num(e.get("dt_mean")) for e in es) if v is not None]
        errs = [v for v in (_num(e.get("e")) for e in es if e.get("accepted")) if v is not None]
        moved = [v for v in (_num(_dict(e.get("points_moved")).get("max")) for e in es)
                 if v is not None]
        ok = count["pass"] == len(es)
        rows.append(
            f'<tr class="station" data-station="{_e(st)}" data-entries="{len(es)}" '
            f'data-passed="{count["pass"]}"><td>{_e(st)}</td><td class="n">{len(es)}</td>'
            f'<td class="n">{count["pass"]}{"" if ok else " ⚠"}</td>'
            f'<td class="n">{count["over tolerance"]}</td><td class="n">{count["rejected"]}</td>'
            f'<td class="n">{count["error"]}</td><td class="n">{_f(max(dts) if dts else None)}</td>'
            f'<td class="n">{_f(sum(errs) / len(errs) if errs else None)}</td>'
            + (f'<td class="n">{_f(max(moved) if moved else None)}</td>' if points else "")
            + "</tr>")
    return head + "".join(rows) + "</table>"


def station_of(e: dict) -> str:
    """An entry's station: its ``station``, else its controller's folder."""
    st = e.get("station")
    if not isinstance(st, str) or not st:
        c = e.get("controller")
        st = os.path.basename(os.path.dirname(c)) if isinstance(c, str) else ""
    return st or "\u2013"


def _axes_xy(q: Any) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """A frame's x and y axes (unit quaternion w, x, y, z) seen from above."""
    if not isinstance(q, (list, tuple)) or len(q) != 4 or any(_num(v) is None for v in q):
        return None
    from ..geometry.rotations import quat_to_matrix
    m = quat_to_matrix(tuple(float(v) for v in q))
    return (m[0][0], m[1][0]), (m[0][1], m[1][1])


def station_svg(name: str, entries: Sequence[dict]) -> str:
    """One station from above (robot world, x right, y up): each frame's
    nominal origin (a ring, its x and y axes red and green) and its measured
    one (a dot in its group's colour, at the nominal plus the measured shift
    magnified by a stated factor, an arrow between); rejected and failed
    entries a ring alone. Scale bar in mm; numbers for machines in
    ``data-*`` attributes."""
    from ..picture.scene import nice      # the 1-2-5 steps the pictures' scale bars take
    rows = []
    for e in entries:
        sim = _dict(e.get("simulated"))
        x, y = _num(sim.get("x")), _num(sim.get("y"))
        if x is None or y is None:
            continue
        d = _dict(e.get("diff")) if e.get("accepted") else {}
        dx, dy = _num(d.get("dx")), _num(d.get("dy"))
        rows.append((e, x, y, dx, dy, _axes_xy(sim.get("q"))))
    if not rows:
        return ""
    W, H, pad = 420, 300, 34
    xs, ys = [r[1] for r in rows], [r[2] for r in rows]
    span = max(max(xs) - min(xs), max(ys) - min(ys), 500.0)
    cx, cy = (max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2
    scale = min(W - 2 * pad, H - 2 * pad - 24) / span                 # px per mm

    def P(x: float, y: float) -> tuple[float, float]:
        return W / 2 + (x - cx) * scale, (H - 24) / 2 - (y - cy) * scale

    shifts = [math.hypot(r[3], r[4]) for r in rows if r[3] is not None and r[4] is not None]
    far = max(shifts, default=0.0)
    factor = nice(0.08 * span / far) if far > 0 else 1.0       # the largest shift ~8 % of the view
    factor = max(factor, 1.0)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
           f'viewBox="0 0 {W} {H}" role="img" class="station-view" data-station="{_e(name)}" '
           f'data-factor="{factor:g}" data-scale="{scale:.6g}" data-cx="{cx:.6g}" '
           f'data-cy="{cy:.6g}" aria-label="station {_e(name)} from above: nominal and '
           f'measured frames, shifts magnified {factor:g} times">']
    for e, x, y, dx, dy, axes in rows:
        px, py = P(x, y)
        g = e.get("group") if isinstance(e.get("group"), int) else None
        color = GROUP_COLORS[(g - 1) % len(GROUP_COLORS)] if g else "#8a949e"
        out.append(f'<g class="frame" data-name="{_e(e.get("name"))}" data-x="{x:.6g}" '
                   f'data-y="{y:.6g}" data-dx="{_attr(dx)}" data-dy="{_attr(dy)}" '
                   f'data-group="{_attr(g)}">')
        if axes is not None:
            for (ax, ay), c in zip(axes, ("#c62828", "#2e7d32")):
                out.append(f'<line x1="{px:.1f}" y1="{py:.1f}" x2="{px + 16 * ax:.1f}" '
                           f'y2="{py - 16 * ay:.1f}" stroke="{c}" stroke-width="1.2"/>')
        out.append(f'<circle cx="{px:.1f}" cy="{py:.1f}" r="5" fill="none" stroke="#5b6570"/>')
        if dx is not None and dy is not None:
            mx, my = px + dx * factor * scale, py - dy * factor * scale
            out.append(f'<line class="shift" x1="{px:.1f}" y1="{py:.1f}" x2="{mx:.1f}" '
                       f'y2="{my:.1f}" stroke="{color}" stroke-width="1.5"/>'
                       f'<circle class="measured" cx="{mx:.1f}" cy="{my:.1f}" r="3.5" '
                       f'fill="{color}"/>')
        out.append(f'<text x="{px + 7:.1f}" y="{py + 14:.1f}" font-size="10">'
                   f'{_e(_short(str(e.get("frame_name") or e.get("name") or "")))}</text></g>')
    bar = nice(span / 4)
    mid = (H - 24) / 2
    out.append(f'<line x1="{pad}" x2="{pad + bar * scale:.1f}" y1="{H - 12}" y2="{H - 12}" '
               f'stroke="#1d2329" stroke-width="2"/><text x="{pad}" y="{H - 16}" '
               f'font-size="11">{bar:g} mm</text>'
               f'<text x="{W / 2:.0f}" y="{H - 4}" text-anchor="middle" font-size="11">x, mm '
               f'(robot world)</text>'
               f'<text x="12" y="{mid:.1f}" font-size="11" text-anchor="middle" '
               f'transform="rotate(-90 12 {mid:.1f})">y, mm</text>'
               f'<text x="{W - 6}" y="{H - 8}" text-anchor="end" font-size="11">shifts '
               f'\u00d7 {factor:g}</text></svg>')
    return "".join(out)


def station_legend(factor: str) -> str:
    return _legend([(_swatch("#5b6570", "outline"), "nominal origin (x axis red, y green)"),
                    (_swatch(GROUP_COLORS[0]), "measured, coloured by group (as above)"),
                    (_swatch("#1d2329", "line"), f"shift, drawn {factor} times its length")])


def _station_views(entries: list[dict]) -> str:
    """Every station's frames in one picture each, nominal beside measured,
    coloured by group (folded, so that a fleet's report stays readable)."""
    by: dict[str, list[dict]] = {}
    for e in entries:
        by.setdefault(station_of(e), []).append(e)
    figures = []
    for k, st in enumerate(sorted(by)):
        svg = station_svg(st, by[st])
        if svg:
            factor = svg.split('data-factor="', 1)[1].split('"', 1)[0]
            figures.append(f'<details class="station-view"><summary>{_e(st)}: '
                           f'{len(by[st])} frame{"s" if len(by[st]) != 1 else ""} from above'
                           f'</summary><figure class="chart small" id="station-{k}">{svg}'
                           f'{station_legend(factor)}</figure></details>')
    if not figures:
        return ""
    return ('<div id="station-views"><p class="note">Each station from above (robot world, '
            'x to the right, y up), folded: the measured shift of every frame is drawn '
            'magnified by the factor its picture states.</p>' + "".join(figures) + "</div>")


def render_report(data: dict, title: str = "ucsio batch report",
                  meta: dict | None = None) -> str:
    """The report from the ``--json`` document of ``ucsio batch``. ``meta``:
    ``generated`` (when), ``version``, ``csv`` (the CSV written beside it),
    ``base`` (the report's folder, for relative links)."""
    meta = dict(meta or {})
    sm = _dict(data.get("summary"))
    entries = [e for e in (data.get("entries") or []) if isinstance(e, dict)]
    parts = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
             '<meta name="viewport" content="width=device-width, initial-scale=1">',
             f"<title>{_e(title)}</title>",
             # no network: forbid any fetch, even if a value smuggled a URL in
             '<meta http-equiv="Content-Security-Policy" content="default-src \'none\'; '
             'style-src \'unsafe-inline\'; img-src data:">',
             f"<style>{CSS}</style></head><body>",
             f'<header id="top"><h1>{_e(title)}</h1>{_meta(data, entries, meta)}</header>',
             _actions(entries)]

    parts.append("<h2>Summary</h2>")
    cards = [("total", _f(sm.get("total")), "", "total", "entries in the manifest"),
             ("passed", _f(sm.get("passed")), "ok", "passed", "within tolerance"),
             ("over tolerance", _f(sm.get("over_tolerance")), "warn", "over_tolerance",
              "frame moved too far"),
             ("rejected", _f(sm.get("rejected")), "bad", "rejected", "points not trusted"),
             ("errors", _f(sm.get("errors")), "err", "errors", "could not be processed"),
             ("success rate", _pct(sm.get("success_rate")), "ok", "success_rate",
              "passed of total")]
    patching = bool(sm.get("patched") or sm.get("patch_errors")) or any(
        "patched" in e or "patch_error" in e for e in entries)
    if patching:
        listings = _num(sm.get("listings")) or 0
        corrected = sm.get("corrected", sm.get("patched"))     # an older JSON: its copies
        cards += [("corrected files", _f(corrected), "ok", "corrected",
                   "written for the controller to load")]
        if listings:
            cards += [("listings for review", _f(listings), "info", "listings",
                       "copies the controller does not load")]
        cards += [("patch errors", _f(sm.get("patch_errors")), "err", "patch_errors",
                   "corrected files not written")]
    parts.append('<div class="cards" id="summary">')
    for label, value, cls, key, words in cards:
        raw = sm.get(key)
        parts.append(f'<div class="card {cls}" data-key="{key}" data-value="{_attr(raw)}">'
                     f'<div class="v">{_e(value)}</div><div class="k">{_e(label)}: '
                     f'{_e(words)}</div></div>')
    parts.append("</div>")
    refused = [e for e in entries if e.get("patch_error")]
    if refused:
        parts.append('<div class="err-msg" id="patch-errors" style="margin-top:10px">'
                     f'{len(refused)} patched cop{"y" if len(refused) == 1 else "ies"} not written '
                     '(a refused patch fails the run, exit 1):<ul>'
                     + "".join(f'<li><b>{_e(e.get("name"))}</b>: {_e(e["patch_error"])}</li>'
                               for e in refused) + "</ul></div>")

    parts.append("<h2>By station</h2>")
    parts.append(_stations(entries))
    parts.append(_station_views(entries))

    parts.append("<h2>Groups by dt_mean</h2>")
    parts.append(f'<p class="note" id="groups-source">{_e(GROUPS_SOURCE)}</p>')
    parts.append('<table id="groups"><tr><th>group</th><th>dt_mean<small>average shift, mm'
                 '</small></th><th>meaning</th><th class="n">count</th>'
                 '<th class="n">% of total</th><th class="n">mean e<small>measurement error, mm'
                 '</small></th><th class="n">std e<small>its spread, mm</small></th></tr>')
    for k, g in enumerate(sm.get("groups") or [], 1):
        g = _dict(g)
        gno = g.get("group") if isinstance(g.get("group"), int) else k
        rng = g.get("range") if isinstance(g.get("range"), (list, tuple)) else [None, None]
        lo, hi = (list(rng) + [None, None])[:2]
        span = (f"{_g(lo)} – {_g(hi)}" if _num(hi) is not None else f"≥ {_g(lo)}")
        color = GROUP_COLORS[(gno - 1) % len(GROUP_COLORS)]
        parts.append(
            f'<tr class="group" data-group="{_attr(gno)}" data-count="{_attr(g.get("count"))}" '
            f'data-percent="{_attr(g.get("percent"))}" data-mean-e="{_attr(g.get("mean_e"))}" '
            f'data-std-e="{_attr(g.get("std_e"))}"><td><span class="swatch" '
            f'style="background:{color}"></span>{_e(gno)}</td>'
            f'<td>{span}</td><td>{_e(GROUP_WORDS[(gno - 1) % 5])}</td>'
            f'<td class="n">{_f(g.get("count"))}</td>'
            f'<td class="n">{_f(g.get("percent"), 1)}</td>'
            f'<td class="n">{_f(g.get("mean_e"))}</td><td class="n">{_f(g.get("std_e"))}</td></tr>')
    parts.append("</table>")
    parts.append('<p class="note">Counts by group are over accepted entries; std e is the '
                 "sample standard deviation (n − 1), blank below two entries.</p>")
    parts.append(_noise_check(entries))
    parts.append(_correlation(_dict(sm.get("correlation"))))

    tolerances = {_num(e.get("tolerance")) for e in entries} - {None}
    tol = tolerances.pop() if len(tolerances) == 1 else None
    dts = [(_num(e.get("dt_mean")), e.get("group")) for e in entries
           if _num(e.get("dt_mean")) is not None]
    parts.append("<h2>How far the frames moved (dt_mean)</h2>")
    parts.append(f'<figure class="chart" id="histogram">{histogram_svg(dts, tolerance=tol)}'
                 f'{histogram_legend(tol)}</figure>')
    parts.append('<p class="note">Accepted entries only. A frame passes below its tolerance'
                 + (f" ({tol:g} mm)." if tol is not None else " (set per entry).") + "</p>")

    solved = [e for e in entries if _num(e.get("e")) is not None]
    thresholds = {_num(e.get("threshold")) for e in solved} - {None}
    thr = thresholds.pop() if len(thresholds) == 1 else None
    parts.append("<h2>Measurement error per entry (e)</h2>")
    parts.append(f'<figure class="chart" id="residuals">{residual_bars_svg(solved, thr)}'
                 f'{residual_legend(thr)}</figure>')

    parts.append("<h2>Entries</h2>")
    points = any(isinstance(e.get("points_moved"), dict) for e in entries)
    solved = any(_dict(e.get("tcp_solved")) for e in entries)    # tcp = "solve" entries
    working = any(_dict(e.get("worst")) for e in entries)        # at = "FILE" entries
    parts.append('<table id="entries"><tr><th>entry</th><th>station</th><th>status</th>'
                 '<th class="n">points used</th>'
                 '<th class="n">e<small>measurement error, mm</small></th>'
                 '<th class="n">dt_mean<small>average shift, mm</small></th>'
                 '<th class="n">group</th><th class="n">dx<small>mm</small></th>'
                 '<th class="n">dy<small>mm</small></th><th class="n">dz<small>mm</small></th>'
                 '<th class="n">angle<small>turned, °</small></th>'
                 + ('<th class="n">taught points<small>moved up to, mm (n)</small></th>'
                    if points else "")
                 + ('<th class="n">TCP solved<small>x, y, z mm ± 95 % doubt</small></th>'
                    if solved else "")
                 + ('<th class="n">worst working point<small>known within, mm (95 %)</small></th>'
                    if working else "") + '</tr>')
    for i, e in enumerate(entries):
        d = _dict(e.get("diff"))
        status = e.get("status")
        cls = STATUS_CLASS.get(status, "err")
        pm = _dict(e.get("points_moved"))
        parts.append(
            f'<tr class="entry" data-name="{_e(e.get("name"))}" data-status="{_e(status)}" '
            f'data-e="{_attr(_num(e.get("e")))}" data-dt-mean="{_attr(_num(e.get("dt_mean")))}" '
            f'data-group="{_attr(_num(e.get("group")))}" data-pass="{_attr(e.get("pass"))}"'
            + (f' data-points-max="{_attr(_num(pm.get("max")))}"' if pm else "")
            + (f' data-patch-error="{_e(e["patch_error"])}"' if e.get("patch_error") else "")
            + (f' data-reason="{_e(_reason(e))}"' if status == "rejected" else "")
            + f'><td><a href="#e{i}">{_e(e.get("name"))}</a></td>'
            f'<td>{_e(e.get("station"))}</td>'
            f'<td><span class="pill {cls}"'
            + (f' title="{_e(_reason(e))}"' if status == "rejected" else "")
            + f'>{_e(status)}</span>{_patch_pill(e)}</td>'
            f'<td class="n">{_used(e)}</td>'
            f'<td class="n">{_f(e.get("e"))}</td><td class="n">{_f(e.get("dt_mean"))}</td>'
            f'<td class="n">{_f(e.get("group"))}</td><td class="n">{_f(d.get("dx"))}</td>'
            f'<td class="n">{_f(d.get("dy"))}</td><td class="n">{_f(d.get("dz"))}</td>'
            f'<td class="n">{_f(d.get("angle"), 4)}</td>'
            + (f'<td class="n">{_points_cell(pm)}</td>' if points else "")
            + (f'<td class="n tcp-solved">{_tcp_cell(e)}</td>' if solved else "")
            + (f'<td class="n worst-working">{_worst_cell(e)}</td>' if working else "") + '</tr>')
    parts.append("</table>")

    parts.append("<h2>Details</h2>")
    views = meta.get("views") or {}
    for i, e in enumerate(entries):
        parts.append(_detail(i, e, meta.get("base"), views.get(i)))

    payload = json.dumps(data, ensure_ascii=False, allow_nan=False).replace("</", "<\\/")
    parts.append(f'<script type="application/json" id="ucsio-data">{payload}</script>')
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"


def _worst_cell(e: dict) -> str:
    w = _dict(e.get("worst"))
    if not w or e.get("status") == "error":
        return "-"
    return f"{_e(w.get('name'))} {_f(w.get('at_95'))}"


#: the working points an entry's details list (the predicted worst)
WORKING_SHOWN = 10


def _working(e: dict) -> str:
    """An entry's working points: the predicted 95 % error of its frame where
    the robot works, worst first."""
    w = _dict(e.get("worst"))
    rows = [r for r in (e.get("working_points") or []) if isinstance(r, dict)]
    rows.sort(key=lambda r: -(_num(r.get("at_95")) or 0.0))
    gate = ("; the determinacy gate judged the worst of them (gate = \"at\")"
            if e.get("gate") == "at" else "")
    note = (f'<p class="note working" style="flex-basis:100%">Where the robot works '
            f'({_e(os.path.basename(str(e.get("at") or "")))}): the frame is known within '
            f'{_f(w.get("at_95"))} mm (95 %) at its worst working point, {_e(w.get("name"))}'
            f'{_e(gate)}.</p>')
    if not rows:
        return note
    shown = rows[:WORKING_SHOWN]
    more = (f"<caption>the {len(shown)} predicted worst of {len(rows)}</caption>"
            if len(rows) > len(shown) else "")
    body = "".join(f"<tr><td>{_e(r.get('name'))}</td><td class='n'>{_f(r.get('x'), 1)}</td>"
                   f"<td class='n'>{_f(r.get('y'), 1)}</td><td class='n'>{_f(r.get('z'), 1)}</td>"
                   f"<td class='n'>{_f(r.get('at_95'))}</td></tr>" for r in shown)
    return (note + f"<table class='working-points'>{more}<tr><th>working point</th>"
            "<th class='n'>x mm</th><th class='n'>y mm</th><th class='n'>z mm</th>"
            "<th class='n'>known within<small>mm, 95 %</small></th></tr>" + body + "</table>")


def _tcp_text(t: dict) -> str:
    return f"{_f(t.get('x'))}, {_f(t.get('y'))}, {_f(t.get('z'))}"


def _tool_name(spec: Any) -> str:
    """'Cell.mod:tReflector' of '/path/to/Cell.mod:tReflector'."""
    file, _, name = str(spec or "").rpartition(":")
    return f"{os.path.basename(file)}:{name}" if file else str(spec or "")


def _tcp_cell(e: dict) -> str:
    """An entries-table cell: the solved TCP, its 95 % doubt, where it went."""
    t = _dict(e.get("tcp_solved"))
    if not t or e.get("status") == "error":
        return "\u2013"
    where = ""
    if e.get("tool_patched"):
        where = f" → {_e(_tool_name(e.get('tool')))}"
    elif e.get("tool_not_patched"):
        where = " (no tool patched)"
    return f"{_e(_tcp_text(t))} ± {_f(t.get('at_95'))}{where}"


def _tcp_note(e: dict, base: str | None) -> str:
    """The details' paragraph on a TCP solved with the frame: the TCP, its
    doubt, the tool the manifest names (its value and how far), and whether
    the tool was patched, or that none was (no tool named)."""
    t = _dict(e.get("tcp_solved"))
    std = _dict(t.get("std"))
    txt = (f"TCP solved with the frame: {_e(_tcp_text(t))} mm in flange coordinates, within "
           f"{_f(t.get('at_95'))} mm at 95 % (std {_f(std.get('x'))}, {_f(std.get('y'))}, "
           f"{_f(std.get('z'))} mm).")
    tool = e.get("tool")
    held = _dict(e.get("tool_tcp"))
    if tool and held:
        txt += (f" Tool <code>{_e(_tool_name(tool))}</code> holds {_e(_tcp_text(held))} mm, "
                f"{_f(held.get('distance'))} mm from it")
        if e.get("tool_patched"):
            txt += (f"; the solved TCP is written into it in the patched copy "
                    f'<a class="patched" href="{_e(_href(str(e["tool_patched"]), base))}">'
                    f'{_e(e["tool_patched"])}</a> (x, y, z only).')
        elif e.get("patch_error"):
            txt += "; it was not patched (see the patch error)."
        else:
            txt += "; it was not patched."
    else:
        txt += (" The manifest names no tool for it, so no tool was patched (tool = "
                "\"FILE:NAME\" beside tcp = \"solve\" names the one to write it into).")
    return f'<p class="note tcp-solved" style="flex-basis:100%">{txt}</p>'


def _points_cell(pm: dict) -> str:
    if not pm:
        return "\u2013"
    if not pm.get("count"):
        return "none found"
    return f"{_f(pm.get('max'))} ({_f(pm.get('count'))})"


def _used(e: dict) -> str:
    n_used, n_points = _num(e.get("n_used")), _num(e.get("n_points"))
    if n_points is None:
        return "\u2013"
    return f"{_f(n_used)}/{_f(n_points)}"


def _reason(e: dict) -> str:
    """Why an entry's dataset was rejected: the solver's ``reason`` (too few
    points, residuals over the threshold with no point to single out, points
    that do not pin the orientation down); a JSON without one (older, or
    hand-edited) gets a generic line."""
    reason = e.get("reason")
    if isinstance(reason, str) and reason.strip():
        return reason.strip()
    return "the dataset was rejected"


#: What --patch-dir wrote for an entry (EntryResult.written), as a pill.
WRITTEN_PILLS = {
    "patched": ("ok", "the corrected controller file"),
    "program written": ("ok", "a program that sets the frame, for the controller to load"),
    "listing for review": ("info", "a copy the controller does not load: for review only"),
}


def _patch_pill(e: dict) -> str:
    if e.get("patch_error"):
        return ' <span class="pill err" title="patched copy not written">not patched</span>'
    written = e.get("written")
    if not isinstance(written, list):       # an older JSON: a patched copy, nothing more said
        written = ["patched"] if e.get("patched") else []
    return "".join(f' <span class="pill {WRITTEN_PILLS[w][0]}" title="{WRITTEN_PILLS[w][1]}">'
                   f'{_e(w)}</span>' for w in written if w in WRITTEN_PILLS)


def _pose_rows(label: str, p: Any, keys: str = "abc") -> str:
    """A pose's row; ``keys``: its a/b/c in the order of the vendor's angle names."""
    if not isinstance(p, dict) or not p:
        return ""
    q = p.get("q")
    qs = ("[" + ", ".join(_f(v, 6) for v in q) + "]") if isinstance(q, (list, tuple)) else "\u2013"
    return (f"<tr><th>{label}</th><td class='n'>{_f(p.get('x'))}</td>"
            f"<td class='n'>{_f(p.get('y'))}</td><td class='n'>{_f(p.get('z'))}</td>"
            + "".join(f"<td class='n'>{_f(p.get(k), 4)}</td>" for k in keys)
            + f"<td class='mono'>{qs}</td></tr>")


def _delta_cells(d: dict, sim: Any, mea: Any, keys: str) -> str:
    """The Δ row's numbers: the difference of the two rows as shown (so it
    adds up), where both are there; else the diff's own."""
    from ..output import shown_difference

    def cell(k: str, digits: int) -> str:
        s, m = (_num(sim.get(k)) if isinstance(sim, dict) else None,
                _num(mea.get(k)) if isinstance(mea, dict) else None)
        if s is None or m is None:
            return f"<td class='n'>{_f(d.get('d' + k), digits)}</td>"
        return f"<td class='n'>{_f(shown_difference(m, s, digits, wrap=k in 'abc'), digits)}</td>"
    return "".join(cell(k, 3) for k in "xyz") + "".join(cell(k, 4) for k in keys)


def _detail(i: int, e: dict, base: str | None = None, view: str | None = None) -> str:
    status = e.get("status")
    cls = STATUS_CLASS.get(status, "err")
    is_open = status in ("error", "rejected") or bool(e.get("patch_error"))
    head = (f'<details id="e{i}"{" open" if is_open else ""}>'
            f'<summary><b>{_e(e.get("name"))}</b> <span class="pill {cls}">{_e(status)}</span>'
            f'{_patch_pill(e)} <span class="mono">{_e(e.get("frame_name"))}</span> in '
            f'<span class="mono">{_e(os.path.basename(str(e.get("controller") or "")))}</span>'
            '</summary><div class="body">')
    body = []
    if e.get("error"):
        stage = f' (at the {_e(e["stage"])} stage)' if e.get("stage") else ""
        body.append(f'<div class="err-msg" style="flex-basis:100%">{_e(e["error"])}{stage}</div>')
    if e.get("patch_error"):
        body.append('<div class="err-msg patch-error" style="flex-basis:100%">patched copy NOT '
                    f'written: {_e(e["patch_error"])}</div>')
    for w in e.get("warnings") or []:       # an unset simulated frame, unpaired points
        body.append(f'<p class="note warning" style="flex-basis:100%">warning: {_e(w)}</p>')
    if view is not None:                    # the entry's 3D picture, a page beside the report
        body.append(f'<p class="note" style="flex-basis:100%"><a class="view" '
                    f'href="{_e(view)}">the picture: points, residuals, simulated and '
                    'measured frame in 3D</a> (ucsio view)</p>')
    if e.get("simulated") or e.get("frame"):
        from ..vendors import angle_columns
        cols = angle_columns(e.get("vendor"))       # the vendor's own names (FANUC w p r, ...)
        rows = _pose_rows("simulated", e.get("simulated"), cols.keys) + _pose_rows(
            "measured" if e.get("accepted") else "fit (rejected)", e.get("frame"), cols.keys)
        d = e.get("diff")
        if isinstance(d, dict) and d:
            rows += (f"<tr><th>Δ</th>{_delta_cells(d, e.get('simulated'), e.get('frame'), cols.keys)}"
                     f"<td>angle {_f(d.get('angle'), 4)}°, dist {_f(d.get('dist'))} mm, dt_mean "
                     f"{_f(d.get('dt_mean'))} mm ({DT_WORDS}), group {_f(d.get('group'))}</td></tr>")
        body.append("<table><tr><th></th><th class='n'>x mm</th><th class='n'>y mm</th>"
                    "<th class='n'>z mm</th>"
                    + "".join(f"<th class='n'>{name} °</th>" for name in cols.names)
                    + "<th>q</th></tr>" + rows + "</table>")
    pts = [p for p in (e.get("points") or []) if isinstance(p, dict)]
    if pts:
        prow = "".join(
            f"<tr><td>{_e(p.get('name'))}</td><td class='n'>{_f(p.get('residual'))}</td>"
            f"<td class='n'>{_f(p.get('loo_residual'))}</td>"
            f"<td>{'yes' if p.get('used', True) else 'no (' + _e(p.get('excluded_by')) + ')'}</td></tr>"
            for p in pts)
        body.append("<table><tr><th>point</th><th class='n'>residual<small>from the fit, mm"
                    "</small></th><th class='n'>leave-one-out<small>from the fit without it, mm"
                    "</small></th><th>used</th></tr>" + prow + "</table>")
        thr = _num(e.get("threshold")) or defaults.THRESHOLD
        body.append(f'<figure class="chart small" id="points-{i}">{points_svg(pts, thr)}'
                    f'{points_legend(thr)}</figure>')
    if pts or e.get("n_points") is not None:
        info = (f"n {_f(e.get('n_used'))} of {_f(e.get('n_points'))} used, e {_f(e.get('e'))} mm, "
                f"rms {_f(e.get('rms'))}, max {_f(e.get('max'))} mm (threshold "
                f"{_g(e.get('threshold'))}, min points {_f(e.get('min_points'))}, tolerance "
                f"{_g(e.get('tolerance'))} mm)")
        u = e.get("uncertainty")
        if isinstance(u, dict) and u:
            std = u.get("std") if isinstance(u.get("std"), dict) else {}
            axes = e.get("uncertainty_axes") or "world"
            info += (f"; uncertainty (std, {'user frame' if axes == 'uframe' else axes} axes) "
                     + ", ".join(f"{k} {_f(std.get(k), 4)}" for k in ("x", "y", "z", "angle")))
        if e.get("uncertainty_error"):
            info += f"; uncertainty not computed: {e['uncertainty_error']}"
        body.append(f'<p class="note" style="flex-basis:100%">{_e(info)}</p>')
    if _dict(e.get("tcp_solved")) and status != "error":
        body.append(_tcp_note(e, base))
    prec = _dict(e.get("precision"))
    if _num(prec.get("at_reach")) is not None:
        body.append(f'<p class="note precision" style="flex-basis:100%">How well the points pin '
                    f'the frame down: a point {_g(prec.get("reach"))} mm from them is known to '
                    f'{_f(prec.get("at_reach"), 2)} mm (95 %); orientation ± '
                    f'{_f(prec.get("angle_std"), 4)}° (1σ), noise σ {_f(prec.get("sigma"), 3)} '
                    'mm per axis.</p>')
    if _dict(e.get("worst")) and status != "error":
        body.append(_working(e))
    noise = _dict(e.get("consistency"))
    if noise.get("message") and status != "error":     # the explanation is said once, above
        body.append(f'<p class="note warning noise-check" style="flex-basis:100%">noise check: '
                    f'the residuals show {_f(noise.get("sigma_residual"), 3)} mm of noise per '
                    f'axis, {_f(noise.get("ratio"), 1)} times the stated '
                    f'{_f(noise.get("sigma_stated"), 3)} mm (p = {_p(noise.get("p"))}); see '
                    '<a href="#noise-check">the noise check</a>.</p>')
    pm = _dict(e.get("points_moved"))
    if pm:
        if pm.get("count"):
            txt = (f"Taught points in this frame: {_f(pm.get('count'))}; they move in world by "
                   f"up to {_f(pm.get('max'))} mm ({pm.get('worst')}), "
                   f"{_f(pm.get('mean'))} mm on average.")
        else:
            txt = "No taught points found in this frame."
        body.append(f'<p class="note points-moved" style="flex-basis:100%">{_e(txt)}</p>')
    if e.get("points_error"):
        body.append(f'<div class="err-msg" style="flex-basis:100%">taught points not placed: '
                    f'{_e(e["points_error"])}</div>')
    if status == "rejected":
        again = "" if e.get("diagnosis") else "; measure again"   # a wrong TCP: check it
        body.append('<div class="err-msg rejected" style="flex-basis:100%">REJECTED: '
                    f'{_e(_reason(e))}{again}</div>')
    sources = _dict(e.get("sources"))
    if sources.get("laser") or sources.get("robot"):   # laser + robot: every file it was read from
        src = "; ".join(f"{k} <code>{_e(sources[k])}</code>"
                        for k in ("laser", "robot", "config", "map") if sources.get(k))
    else:
        src = f"measurement <code>{_e(e.get('measurement'))}</code>"
    src += f"; controller <code>{_e(e.get('controller'))}</code>"
    if e.get("patched"):
        what = "listing for review" if e.get("listing") else "patched copy"
        src += (f'; {what} <a class="patched" href="{_e(_href(str(e["patched"]), base))}">'
                f'{_e(e["patched"])}</a>')
    program = _dict(e.get("program"))
    if program.get("file"):
        src += (f'; program written <a class="program" href="{_e(_href(str(program["file"]), base))}">'
                f'{_e(program["file"])}</a> (sets {_e(program.get("frame"))} through '
                f'PR[{_e(program.get("pr"))}])')
    elif e.get("program_error"):
        src += f'; no program written: {_e(e["program_error"])}'

    body.append(f'<p class="note" style="flex-basis:100%">{src}</p>')
    return head + "".join(body) + "</div></details>"


def write_report(result, path: str, csv: str | None = None) -> None:
    """Write the report of a ``BatchResult`` (atomically); ``csv``: the CSV
    written beside it, linked from the report; each solved entry's picture
    (``ucsio view``'s page) in the folder beside it (``views_folder``)."""
    from .. import __version__
    from ..files import atomic_write_text
    from ..output import _clean, versioned

    data = _clean(versioned(result.as_dict()))      # batch --json's document, embedded
    now = _dt.datetime.now(_dt.timezone.utc).replace(microsecond=0)
    meta = {"generated": now.strftime("%Y-%m-%d %H:%M UTC"), "version": __version__,
            "csv": csv, "base": os.path.dirname(os.path.abspath(path)),
            "views": write_views(result, path)}
    atomic_write_text(path, render_report(data, meta=meta))


def views_folder(path: str) -> str:
    """Where the report's pictures go: REPORT.views beside REPORT.html."""
    return os.path.splitext(path)[0] + ".views"


def write_views(result, path: str) -> dict[int, str]:
    """Each solved entry's picture, as ``ucsio view`` draws it (its points,
    residuals, the simulated and the measured frame): one page in
    ``views_folder(path)`` that draws the entry its address names
    (``view.html#12``) from one data file of every entry's fit and point
    pairs (``entries.js``), with one shared copy of three.js there. The
    report itself stays small and without script, and a fleet's pictures
    cost three files, not one per entry. Returns each entry's index -> its
    picture's address relative to the report."""
    import json

    from ..files import atomic_write, atomic_write_text
    from ..picture.page import report_page, write_library

    entries = {str(k + 1): _view_entry(r) for k, r in enumerate(result.entries)
               if r.solution is not None and r.solution.points
               and all(p.laser is not None for p in r.solution.points)}
    if not entries:
        return {}
    folder = views_folder(path)
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as exc:
        from ..errors import UcsioError
        raise UcsioError(f"--report: cannot make the folder for the pictures: "
                         f"{exc.strerror or exc}", file=folder) from None
    write_library(folder)
    data = json.dumps(entries, separators=(",", ":"), allow_nan=True)
    data = data.replace("NaN", "null").replace("-Infinity", "null").replace("Infinity", "null")
    atomic_write(os.path.join(folder, "entries.js"),
                 ("window.UCSIO_ENTRIES = " + data + ";\n").encode("ascii"))
    atomic_write_text(os.path.join(folder, "view.html"), report_page())
    base = os.path.basename(folder)
    return {int(k) - 1: f"{base}/view.html#{k}" for k in entries}


def _view_entry(r) -> dict:
    """An entry's numbers for the picture: the fit, the point pairs, the
    working points, and the simulated frame as ``diff`` compares it."""
    s = r.solution
    d = {"title": f"{r.entry.name}: {r.entry.frame}", "frame": {"t": list(s.pose.t),
                                                            "q": list(s.pose.q)},
         "accepted": s.accepted, "reason": s.reason, "rms": s.rms, "max": s.max,
         "points": [[p.name, list(p.laser), list(p.robot), p.used, p.excluded_by]
                    for p in s.points],
         "working": s.working_points or [], "worst": s.worst}
    if r.simulated is not None and r.measured is not None and r.delta is not None:
        d["simulated"] = {
            "sim": {"t": list(r.simulated.t), "q": list(r.simulated.q)},
            "mea": {"t": list(r.measured.t), "q": list(r.measured.q)}, "name": r.entry.frame,
            "delta": {k: r.delta[k] for k in ("dx", "dy", "dz", "da", "db", "dc", "angle",
                                              "dist", "dt_mean", "group", "pass")}}
    return d
