"""The HTML report of ``ucsio batch --report FILE.html``.

One self-contained file: inline CSS, charts drawn here as inline SVG (no
matplotlib, no scripts, nothing fetched from the network). It holds:

- the summary (counts, success rate) and the table of the five groups;
- a histogram of dt_mean over the accepted entries with the group
  boundaries (10, 25, 50, 100 mm) drawn; each group gets the same width on
  the axis so group 1 (0-10 mm) is as readable as group 5;
- per-entry residual bars (mean residual e, and the largest residual of the
  used points, against the outlier threshold);
- per entry: the diff, the measured frame, the points with their residuals
  and leave-one-out residuals, the error, and with --patch-dir the patched
  copy or why it was refused.

Any value may be missing or null (an entry that failed after it was solved
has points and residuals but no e; a hand-edited JSON may lack anything): a
missing number is drawn as "–", never an error.

Numbers for machines: the whole ``--json`` document is embedded as
``<script type="application/json" id="ucsio-data">``; the summary cells carry
``data-key``/``data-value`` and every entry row ``data-name``, ``data-status``,
``data-e``, ``data-dt-mean``, ``data-group``, ``data-pass`` (and a rejected
entry's ``data-reason``: why its dataset was rejected).
"""
from __future__ import annotations

import html
import json
import math
import os
from typing import Any, Sequence

from . import defaults
from .diff import GROUP_BOUNDS
from .output import fmt

GROUP_COLORS = ("#2e7d32", "#7cb342", "#f9a825", "#ef6c00", "#c62828")
STATUS_CLASS = {"pass": "ok", "over tolerance": "warn", "rejected": "bad", "error": "err"}

CSS = """
:root { --fg:#1d2329; --muted:#5f6b76; --line:#d9dee3; --bg:#ffffff; --panel:#f6f8fa; }
* { box-sizing: border-box; }
body { font: 14px/1.45 -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif;
       color: var(--fg); background: var(--bg); margin: 0; padding: 24px 32px; max-width: 1200px; }
h1 { font-size: 22px; margin: 0 0 4px; }
h2 { font-size: 17px; margin: 28px 0 10px; border-bottom: 1px solid var(--line); padding-bottom: 4px; }
.sub { color: var(--muted); margin-bottom: 18px; word-break: break-all; }
.cards { display: flex; flex-wrap: wrap; gap: 12px; }
.card { background: var(--panel); border: 1px solid var(--line); border-radius: 6px;
        padding: 10px 16px; min-width: 120px; }
.card .v { font-size: 24px; font-weight: 600; }
.card .k { color: var(--muted); font-size: 12px; text-transform: uppercase; letter-spacing: .04em; }
.card.ok .v { color: #2e7d32; } .card.warn .v { color: #b26a00; }
.card.bad .v { color: #c62828; } .card.err .v { color: #6a1b9a; }
table { border-collapse: collapse; font-variant-numeric: tabular-nums; }
th, td { padding: 3px 10px; border-bottom: 1px solid var(--line); text-align: left; }
th { background: var(--panel); font-weight: 600; }
td.n, th.n { text-align: right; }
.swatch { display: inline-block; width: 10px; height: 10px; border-radius: 2px; margin-right: 6px; }
.pill { display: inline-block; padding: 0 8px; border-radius: 9px; font-size: 12px; color: #fff; }
.pill.ok { background: #2e7d32; } .pill.warn { background: #b26a00; }
.pill.bad { background: #c62828; } .pill.err { background: #6a1b9a; }
.chart { background: var(--panel); border: 1px solid var(--line); border-radius: 6px; padding: 8px; }
.chart svg { display: block; width: 100%; height: auto; }
.note { color: var(--muted); font-size: 12px; margin: 6px 0 0; }
details { border-bottom: 1px solid var(--line); padding: 4px 0; }
details summary { cursor: pointer; }
details .body { display: flex; flex-wrap: wrap; gap: 24px; padding: 8px 0 12px 18px; }
.err-msg { color: #6a1b9a; font-family: ui-monospace, Consolas, monospace; font-size: 12px; }
code, .mono { font-family: ui-monospace, Consolas, monospace; font-size: 12px; }
svg text { font-family: -apple-system, "Segoe UI", Roboto, Arial, sans-serif; }
@media print { details { break-inside: avoid; } }
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


# ---------------------------------------------------------------- charts

def _group_axis(dt: float, top: float) -> float:
    """dt_mean (mm) -> position 0..5 on an axis where each group is one unit wide."""
    edges = (0.0, *GROUP_BOUNDS, top)
    for k in range(len(edges) - 1):
        lo, hi = edges[k], edges[k + 1]
        if dt < hi or k == len(edges) - 2:
            return k + min(max((dt - lo) / (hi - lo), 0.0), 1.0)
    return float(len(edges) - 1)


def histogram_svg(dts: Sequence[tuple[float, int]], bins_per_group: int = 5,
                  tolerance: float | None = None) -> str:
    """dt_mean histogram. ``dts``: (dt_mean, group) of the accepted entries."""
    W, H, left, right, top_pad, bottom = 1100, 310, 50, 20, 30, 52
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
           f'aria-label="histogram of dt_mean">']
    for g in range(5):   # group bands
        out.append(f'<rect x="{X(g):.1f}" y="{top_pad}" width="{pw / 5:.1f}" height="{ph}" '
                   f'fill="{GROUP_COLORS[g]}" opacity="0.07"/>')
        out.append(f'<text x="{X(g + 0.5):.1f}" y="{top_pad - 9}" text-anchor="middle" '
                   f'font-size="12" fill="{GROUP_COLORS[g]}" font-weight="600">group {g + 1}</text>')
    for k in range(0, ymax + 1, ystep):
        y = Y(k)
        out.append(f'<line x1="{left}" x2="{W - right}" y1="{y:.1f}" y2="{y:.1f}" stroke="#d9dee3"/>')
        out.append(f'<text x="{left - 6}" y="{y + 4:.1f}" text-anchor="end" font-size="11" '
                   f'fill="#5f6b76">{k}</text>')
    bw = pw / n_bins
    for b, c in enumerate(counts):
        if not c:
            continue
        g = b // bins_per_group
        out.append(f'<rect class="bin" data-bin="{b}" data-count="{c}" x="{X(b / bins_per_group) + 1:.1f}" '
                   f'y="{Y(c):.1f}" width="{bw - 2:.1f}" height="{Y(0) - Y(c):.1f}" '
                   f'fill="{GROUP_COLORS[g]}"/>')
        out.append(f'<text x="{X((b + 0.5) / bins_per_group):.1f}" y="{Y(c) - 3:.1f}" '
                   f'text-anchor="middle" font-size="10" fill="#1d2329">{c}</text>')
    for k, bound in enumerate(GROUP_BOUNDS, 1):   # the group boundaries
        x = X(k)
        out.append(f'<line class="boundary" data-mm="{bound:g}" x1="{x:.1f}" x2="{x:.1f}" '
                   f'y1="{top_pad}" y2="{Y(0):.1f}" stroke="#1d2329" stroke-dasharray="5 4"/>')
    if tolerance is not None and tolerance not in GROUP_BOUNDS and tolerance < top:
        x = X(_group_axis(tolerance, top))
        out.append(f'<line x1="{x:.1f}" x2="{x:.1f}" y1="{top_pad}" y2="{Y(0):.1f}" '
                   f'stroke="#c62828" stroke-width="2"/>')
        out.append(f'<text x="{x + 4:.1f}" y="{top_pad + 28}" font-size="11" fill="#c62828">'
                   f'tolerance {tolerance:g}</text>')
    out.append(f'<line x1="{left}" x2="{W - right}" y1="{Y(0):.1f}" y2="{Y(0):.1f}" stroke="#1d2329"/>')
    for k, mm in enumerate((0.0, *GROUP_BOUNDS, top)):
        out.append(f'<text x="{X(k):.1f}" y="{Y(0) + 16:.1f}" text-anchor="middle" font-size="11" '
                   f'fill="#1d2329">{mm:g}</text>')
    out.append(f'<text x="{left + pw / 2:.1f}" y="{H - 8}" text-anchor="middle" font-size="12" '
               f'fill="#5f6b76">dt_mean (mm) — each group one fifth of the axis, linear inside it'
               f'</text>')
    out.append(f'<text x="14" y="{top_pad + ph / 2:.1f}" font-size="12" fill="#5f6b76" '
               f'transform="rotate(-90 14 {top_pad + ph / 2:.1f})" text-anchor="middle">entries</text>')
    out.append("</svg>")
    return "".join(out)


def residual_bars_svg(rows: Sequence[dict], threshold: float | None) -> str:
    """One bar per solved entry: e (mean residual of the used points, solid)
    in front of the largest used residual (light)."""
    W, H, left, right, top_pad, bottom = 1100, 240, 50, 20, 16, 40
    n = max(len(rows), 1)
    rows = [dict(r, e=_num(r.get("e")), max=_num(r.get("max"))) for r in rows]
    vals = [r["max"] for r in rows if r["max"] is not None] + \
           [r["e"] for r in rows if r["e"] is not None]
    ymax = max(vals + [0.1])
    if threshold is not None and threshold < 1.5 * ymax:
        ymax = max(ymax, threshold * 1.05)
    step = _nice_step(ymax / 5)
    ymax = step * math.ceil(ymax / step)
    pw, ph = W - left - right, H - top_pad - bottom

    def Y(v):
        return top_pad + ph * (1 - min(v, ymax) / ymax)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {W} {H}" role="img" '
           f'aria-label="residuals per entry">']
    k = 0.0
    while k <= ymax + 1e-12:
        y = Y(k)
        out.append(f'<line x1="{left}" x2="{W - right}" y1="{y:.1f}" y2="{y:.1f}" stroke="#d9dee3"/>')
        out.append(f'<text x="{left - 6}" y="{y + 4:.1f}" text-anchor="end" font-size="11" '
                   f'fill="#5f6b76">{k:g}</text>')
        k = round(k + step, 10)
    bw = pw / n
    for i, r in enumerate(rows):
        x = left + i * bw
        color = "#c62828" if r.get("status") == "rejected" else "#1f6feb"
        if r.get("max") is not None:
            out.append(f'<rect x="{x + bw * 0.1:.2f}" y="{Y(r["max"]):.1f}" width="{bw * 0.8:.2f}" '
                       f'height="{Y(0) - Y(r["max"]):.1f}" fill="{color}" opacity="0.25"/>')
        if r.get("e") is not None:
            out.append(f'<rect class="ebar" data-name="{_e(r.get("name"))}" data-e="{_attr(r["e"])}" '
                       f'x="{x + bw * 0.1:.2f}" y="{Y(r["e"]):.1f}" width="{bw * 0.8:.2f}" '
                       f'height="{Y(0) - Y(r["e"]):.1f}" fill="{color}"><title>{_e(r.get("name"))}: '
                       f'e {r["e"]:.3f} mm, max {_f(r.get("max"))} mm</title></rect>')
    if threshold is not None and threshold <= ymax:
        y = Y(threshold)
        out.append(f'<line x1="{left}" x2="{W - right}" y1="{y:.1f}" y2="{y:.1f}" stroke="#c62828" '
                   f'stroke-dasharray="6 4"/><text x="{W - right - 4}" y="{y - 4:.1f}" '
                   f'text-anchor="end" font-size="11" fill="#c62828">threshold {threshold:g} mm</text>')
    out.append(f'<line x1="{left}" x2="{W - right}" y1="{Y(0):.1f}" y2="{Y(0):.1f}" stroke="#1d2329"/>')
    out.append(f'<text x="{left + pw / 2:.1f}" y="{H - 12}" text-anchor="middle" font-size="12" '
               f'fill="#5f6b76">entries in manifest order ({len(rows)} solved) — solid: e (mean '
               f'residual of used points), light: largest used residual, red: rejected</text>')
    out.append("</svg>")
    return "".join(out)


def _nice_step(raw: float) -> float:
    if raw <= 0:
        return 1.0
    mag = 10 ** math.floor(math.log10(raw))
    for m in (1, 2, 2.5, 5, 10):
        if raw <= m * mag:
            return m * mag
    return 10 * mag


def points_svg(points: Sequence[dict], threshold: float) -> str:
    """Small chart of one entry's points: residual (solid), leave-one-out
    residual (outline), threshold line; excluded points red."""
    points = [dict(p, residual=_num(p.get("residual")), loo_residual=_num(p.get("loo_residual")))
              for p in points if isinstance(p, dict)]
    W, H, left, bottom, top_pad = 40 + 34 * max(len(points), 1), 150, 36, 28, 10
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
           f'viewBox="0 0 {W} {H}" role="img" aria-label="point residuals">',
           f'<line x1="{left}" x2="{W - 4}" y1="{Y(0):.1f}" y2="{Y(0):.1f}" stroke="#1d2329"/>',
           f'<text x="{left - 4}" y="{Y(0) + 4:.1f}" text-anchor="end" font-size="10">0</text>',
           f'<text x="{left - 4}" y="{Y(ymax) + 8:.1f}" text-anchor="end" font-size="10">'
           f'{ymax:.2g}</text>']
    for i, p in enumerate(points):
        x = left + 6 + i * 34
        color = "#1f6feb" if p.get("used", True) else "#c62828"
        if p["residual"] is not None:
            out.append(f'<rect x="{x}" y="{Y(p["residual"]):.1f}" width="11" '
                       f'height="{Y(0) - Y(p["residual"]):.1f}" fill="{color}"/>')
        if p["loo_residual"] is not None:
            out.append(f'<rect x="{x + 13}" y="{Y(p["loo_residual"]):.1f}" width="11" '
                       f'height="{Y(0) - Y(p["loo_residual"]):.1f}" fill="none" stroke="{color}"/>')
        if clipped and max(p["residual"] or 0, p["loo_residual"] or 0) > ymax:
            out.append(f'<text x="{x + 12}" y="{top_pad + 8}" text-anchor="middle" font-size="10" '
                       f'fill="{color}">▲</text>')
        out.append(f'<text x="{x + 12}" y="{H - 12}" text-anchor="middle" font-size="10">'
                   f'{_e(str(p.get("name") or "")[:6])}</text>')
    y = Y(threshold)
    out.append(f'<line x1="{left}" x2="{W - 4}" y1="{y:.1f}" y2="{y:.1f}" stroke="#c62828" '
               f'stroke-dasharray="4 3"/>')
    out.append("</svg>")
    return "".join(out)


# ---------------------------------------------------------------- the page

def _pct(v: Any) -> str:
    v = _num(v)
    return "\u2013" if v is None else f"{100 * v:.1f} %"


def render_report(data: dict, title: str = "ucsio batch report") -> str:
    """The report from the ``--json`` document of ``ucsio batch``."""
    sm = data.get("summary") or {}
    entries = [e for e in (data.get("entries") or []) if isinstance(e, dict)]
    parts = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
             '<meta name="viewport" content="width=device-width, initial-scale=1">',
             f"<title>{_e(title)}</title>",
             # no network: forbid any fetch, even if a value smuggled a URL in
             '<meta http-equiv="Content-Security-Policy" content="default-src \'none\'; '
             'style-src \'unsafe-inline\'; img-src data:">',
             f"<style>{CSS}</style></head><body>",
             f"<h1>{_e(title)}</h1>",
             f'<div class="sub">manifest <code>{_e(data.get("manifest"))}</code></div>']

    cards = [("total", _f(sm.get("total")), "", "total"),
             ("passed", _f(sm.get("passed")), "ok", "passed"),
             ("over tolerance", _f(sm.get("over_tolerance")), "warn", "over_tolerance"),
             ("rejected", _f(sm.get("rejected")), "bad", "rejected"),
             ("errors", _f(sm.get("errors")), "err", "errors"),
             ("success rate", _pct(sm.get("success_rate")), "ok", "success_rate")]
    patching = bool(sm.get("patched") or sm.get("patch_errors")) or any(
        "patched" in e or "patch_error" in e for e in entries)
    if patching:
        cards += [("patched copies", _f(sm.get("patched")), "ok", "patched"),
                  ("patch errors", _f(sm.get("patch_errors")), "err", "patch_errors")]
    parts.append('<div class="cards" id="summary">')
    for label, value, cls, key in cards:
        raw = sm.get(key)
        parts.append(f'<div class="card {cls}" data-key="{key}" data-value="{_attr(raw)}">'
                     f'<div class="v">{_e(value)}</div><div class="k">{_e(label)}</div></div>')
    parts.append("</div>")
    refused = [e for e in entries if e.get("patch_error")]
    if refused:
        parts.append('<div class="err-msg" id="patch-errors" style="margin-top:10px">'
                     f'{len(refused)} patched cop{"y" if len(refused) == 1 else "ies"} not written '
                     '(a refused patch fails the run, exit 1):<ul>'
                     + "".join(f'<li><b>{_e(e.get("name"))}</b>: {_e(e["patch_error"])}</li>'
                               for e in refused) + "</ul></div>")

    parts.append("<h2>Groups</h2>")
    parts.append('<table id="groups"><tr><th>group</th><th>dt_mean (mm)</th><th class="n">count</th>'
                 '<th class="n">% of total</th><th class="n">mean e (mm)</th>'
                 '<th class="n">std e (mm)</th></tr>')
    for k, g in enumerate(sm.get("groups") or [], 1):
        gno = g.get("group") if isinstance(g.get("group"), int) else k
        rng = g.get("range") or [None, None]
        lo, hi = (list(rng) + [None, None])[:2]
        span = (f"{_g(lo)} – {_g(hi)}" if _num(hi) is not None else f"≥ {_g(lo)}")
        color = GROUP_COLORS[(gno - 1) % len(GROUP_COLORS)]
        parts.append(
            f'<tr class="group" data-group="{_attr(gno)}" data-count="{_attr(g.get("count"))}" '
            f'data-percent="{_attr(g.get("percent"))}" data-mean-e="{_attr(g.get("mean_e"))}" '
            f'data-std-e="{_attr(g.get("std_e"))}"><td><span class="swatch" '
            f'style="background:{color}"></span>{_e(gno)}</td>'
            f'<td>{span}</td><td class="n">{_f(g.get("count"))}</td>'
            f'<td class="n">{_f(g.get("percent"), 1)}</td>'
            f'<td class="n">{_f(g.get("mean_e"))}</td><td class="n">{_f(g.get("std_e"))}</td></tr>')
    parts.append("</table>")
    c = sm.get("correlation") or {}
    parts.append('<p class="note" id="correlation" '
                 + " ".join(f'data-{k}="{_attr(c.get(k))}"' for k in "xyz")
                 + ">Pearson correlation of simulated vs measured position over passing entries: "
                 + ", ".join(f"{k} {_f(c.get(k), 5)}" for k in "xyz")
                 + ". Counts by group are over accepted entries; std e is the sample standard "
                   "deviation (n − 1), blank below two entries.</p>")

    tolerances = {_num(e.get("tolerance")) for e in entries} - {None}
    tol = tolerances.pop() if len(tolerances) == 1 else None
    dts = [(_num(e.get("dt_mean")), e.get("group")) for e in entries
           if _num(e.get("dt_mean")) is not None]
    parts.append("<h2>dt_mean of the accepted entries</h2>")
    parts.append(f'<div class="chart" id="histogram">{histogram_svg(dts, tolerance=tol)}</div>')
    parts.append('<p class="note">Dashed lines: group boundaries at '
                 + ", ".join(f"{b:g}" for b in GROUP_BOUNDS) + " mm. A frame passes below its "
                 "tolerance" + (f" ({tol:g} mm)." if tol is not None else " (per entry).") + "</p>")

    solved = [e for e in entries if _num(e.get("e")) is not None]
    thresholds = {_num(e.get("threshold")) for e in solved}
    thr = thresholds.pop() if len(thresholds) == 1 else None
    parts.append("<h2>Residuals per entry</h2>")
    parts.append(f'<div class="chart" id="residuals">{residual_bars_svg(solved, thr)}</div>')

    parts.append("<h2>Entries</h2>")
    parts.append('<table id="entries"><tr><th>entry</th><th>status</th><th class="n">used</th>'
                 '<th class="n">e</th><th class="n">dt_mean</th><th class="n">group</th>'
                 '<th class="n">dx</th><th class="n">dy</th><th class="n">dz</th>'
                 '<th class="n">angle°</th></tr>')
    for i, e in enumerate(entries):
        d = e.get("diff") or {}
        status = e.get("status")
        cls = STATUS_CLASS.get(status, "err")
        parts.append(
            f'<tr class="entry" data-name="{_e(e.get("name"))}" data-status="{_e(status)}" '
            f'data-e="{_attr(_num(e.get("e")))}" data-dt-mean="{_attr(_num(e.get("dt_mean")))}" '
            f'data-group="{_attr(_num(e.get("group")))}" data-pass="{_attr(e.get("pass"))}"'
            + (f' data-patch-error="{_e(e["patch_error"])}"' if e.get("patch_error") else "")
            + (f' data-reason="{_e(_reason(e))}"' if status == "rejected" else "")
            + f'><td><a href="#e{i}">{_e(e.get("name"))}</a></td>'
            f'<td><span class="pill {cls}"'
            + (f' title="{_e(_reason(e))}"' if status == "rejected" else "")
            + f'>{_e(status)}</span>{_patch_pill(e)}</td>'
            f'<td class="n">{_used(e)}</td>'
            f'<td class="n">{_f(e.get("e"))}</td><td class="n">{_f(e.get("dt_mean"))}</td>'
            f'<td class="n">{_f(e.get("group"))}</td><td class="n">{_f(d.get("dx"))}</td>'
            f'<td class="n">{_f(d.get("dy"))}</td><td class="n">{_f(d.get("dz"))}</td>'
            f'<td class="n">{_f(d.get("angle"), 4)}</td></tr>')
    parts.append("</table>")

    parts.append("<h2>Details</h2>")
    for i, e in enumerate(entries):
        parts.append(_detail(i, e))

    payload = json.dumps(data, ensure_ascii=False, allow_nan=False).replace("</", "<\\/")
    parts.append(f'<script type="application/json" id="ucsio-data">{payload}</script>')
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"


def _used(e: dict) -> str:
    n_used, n_points = _num(e.get("n_used")), _num(e.get("n_points"))
    if n_points is None:
        return "\u2013"
    return f"{_f(n_used)}/{_f(n_points)}"


def _reason(e: dict) -> str:
    """Why an entry's dataset was rejected: the solver's ``reason`` (too few
    points, or residuals over the threshold with no point to single out);
    a JSON without one (older, or hand-edited) gets a generic line."""
    reason = e.get("reason")
    if isinstance(reason, str) and reason.strip():
        return reason.strip()
    return "the dataset was rejected"


def _patch_pill(e: dict) -> str:
    if e.get("patch_error"):
        return ' <span class="pill err" title="patched copy not written">not patched</span>'
    if e.get("patched"):
        return ' <span class="pill ok">patched</span>'
    return ""


def _pose_rows(label: str, p: Any) -> str:
    if not isinstance(p, dict) or not p:
        return ""
    q = p.get("q")
    qs = ("[" + ", ".join(_f(v, 6) for v in q) + "]") if isinstance(q, (list, tuple)) else "\u2013"
    return (f"<tr><th>{label}</th><td class='n'>{_f(p.get('x'))}</td>"
            f"<td class='n'>{_f(p.get('y'))}</td><td class='n'>{_f(p.get('z'))}</td>"
            f"<td class='n'>{_f(p.get('a'), 4)}</td><td class='n'>{_f(p.get('b'), 4)}</td>"
            f"<td class='n'>{_f(p.get('c'), 4)}</td><td class='mono'>{qs}</td></tr>")


def _detail(i: int, e: dict) -> str:
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
    if e.get("simulated") or e.get("frame"):
        rows = _pose_rows("simulated", e.get("simulated")) + _pose_rows(
            "measured" if e.get("accepted") else "fit (rejected)", e.get("frame"))
        d = e.get("diff")
        if isinstance(d, dict) and d:
            rows += (f"<tr><th>Δ</th><td class='n'>{_f(d.get('dx'))}</td>"
                     f"<td class='n'>{_f(d.get('dy'))}</td><td class='n'>{_f(d.get('dz'))}</td>"
                     f"<td class='n'>{_f(d.get('da'), 4)}</td><td class='n'>{_f(d.get('db'), 4)}</td>"
                     f"<td class='n'>{_f(d.get('dc'), 4)}</td>"
                     f"<td>angle {_f(d.get('angle'), 4)}°, dist {_f(d.get('dist'))} mm, dt_mean "
                     f"{_f(d.get('dt_mean'))} mm, group {_f(d.get('group'))}</td></tr>")
        body.append("<table><tr><th></th><th class='n'>x</th><th class='n'>y</th><th class='n'>z</th>"
                    "<th class='n'>a</th><th class='n'>b</th><th class='n'>c</th><th>q</th></tr>"
                    + rows + "</table>")
    pts = [p for p in (e.get("points") or []) if isinstance(p, dict)]
    if pts:
        prow = "".join(
            f"<tr><td>{_e(p.get('name'))}</td><td class='n'>{_f(p.get('residual'))}</td>"
            f"<td class='n'>{_f(p.get('loo_residual'))}</td>"
            f"<td>{'yes' if p.get('used', True) else 'no (' + _e(p.get('excluded_by')) + ')'}</td></tr>"
            for p in pts)
        body.append("<table><tr><th>point</th><th class='n'>residual</th>"
                    "<th class='n'>leave-one-out</th><th>used</th></tr>" + prow + "</table>")
        body.append(points_svg(pts, _num(e.get("threshold")) or defaults.THRESHOLD))
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
    if status == "rejected":
        body.append('<div class="err-msg rejected" style="flex-basis:100%">REJECTED: '
                    f'{_e(_reason(e))}; measure again</div>')
    src = f"measurement {e.get('measurement')}; controller {e.get('controller')}"
    if e.get("patched"):
        src += f"; patched copy {e['patched']}"
    body.append(f'<p class="note" style="flex-basis:100%">{_e(src)}</p>')
    return head + "".join(body) + "</div></details>"


def write_report(result, path: str) -> None:
    """Write the report of a ``BatchResult`` (atomically)."""
    from .files import atomic_write_text
    from .output import _clean

    data = _clean(result.as_dict())
    atomic_write_text(path, render_report(data))
