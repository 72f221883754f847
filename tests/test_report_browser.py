"""The batch report in a real browser: headless Chromium from the
distribution's packages (``.ci/run`` installs it where it is missing),
driven through the DevTools protocol (tests/browser.py).

- the page loads with no console error (a CSP violation, a script error, a
  failed load all count);
- the action list is visible above the fold of a 1280 x 800 window;
- every chart has its legend, visible, and axis labels a person can read;
- the layout (positions and sizes of the page's sections) matches the
  stored expectation, tests/expected/report_layout.json, by structure and
  within tolerances, not by pixels. ``UCSIO_UPDATE_LAYOUT=1`` rewrites it
  after an intended change of the page.

Without Chromium the tests are skipped, and pytest's summary says why and
how to install it; ``.ci/run`` sets ``UCSIO_REQUIRE_BROWSER=1``, under which
a missing browser is a failure, never a skip.
"""
from __future__ import annotations

import contextlib
import importlib.util
import io
import json
import os
import struct
from pathlib import Path

import pytest

from browser import Browser, find_chromium
from ucsio.cli import main

ROOT = Path(__file__).resolve().parents[1]
EXPECTED = Path(__file__).resolve().parent / "expected" / "report_layout.json"
WIDTH, HEIGHT = 1280, 800
SECTIONS = ["#top", "#meta", "#actions", "#summary", "#stations", "#groups", "#histogram",
            "#residuals", "#entries", "details#e0"]


@pytest.fixture(scope="module")
def chromium():
    path = find_chromium()
    if path is None:
        how = ("Chromium is not installed (sudo apt-get install chromium; .ci/run installs it "
               "where it may)")
        if os.environ.get("UCSIO_REQUIRE_BROWSER"):
            pytest.fail(f"{how}, and UCSIO_REQUIRE_BROWSER is set: the report's browser "
                        "tests must run")
        pytest.skip(f"{how}: the report's browser tests did not run")
    return path


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    dest = tmp_path_factory.mktemp("fleet_browser")
    spec = importlib.util.spec_from_file_location("make_fleet", ROOT / "fixtures/fleet/make_fleet.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    mod.make_fleet(dest)
    html_path = dest / "out" / "report.html"
    html_path.parent.mkdir()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        code = main(["batch", str(dest / "manifest.toml"), "--report", str(html_path),
                     "--csv", str(dest / "out" / "fleet.csv"), "--patch-dir",
                     str(dest / "patched")])
    assert code == 1
    return html_path


@pytest.fixture(scope="module")
def page(chromium, report):
    with Browser(WIDTH, HEIGHT, executable=chromium) as b:
        b.load(report)
        yield b


MEASURE = """
(() => {
  const r = el => { const b = el.getBoundingClientRect();
    return {x: b.left + scrollX, y: b.top + scrollY, width: b.width, height: b.height}; };
  return %s.map(sel => { const el = document.querySelector(sel);
    return el ? Object.assign({selector: sel}, r(el)) : {selector: sel, missing: true}; });
})()
"""


def test_loads_without_console_errors(page):
    assert page.errors == []
    assert page.evaluate("document.readyState") == "complete"
    assert page.evaluate("document.title") == "ucsio batch report"


def test_action_list_is_above_the_fold(page):
    box = page.evaluate("""(() => { const a = document.getElementById('actions');
        const first = a.querySelector('li.action') || a.querySelector('p');
        const b = a.getBoundingClientRect(), f = first.getBoundingClientRect();
        return {top: b.top, width: b.width, firstBottom: f.bottom, firstTop: f.top,
                visible: getComputedStyle(a).visibility, display: getComputedStyle(a).display}})()""")
    assert box["display"] != "none" and box["visible"] == "visible"
    assert 0 <= box["top"] < HEIGHT / 3          # the first thing after the title and run facts
    assert box["firstBottom"] < HEIGHT           # its first item is readable without scrolling
    assert box["width"] > WIDTH / 2
    # and it comes before the summary in the page
    order = page.evaluate("[...document.querySelectorAll('#actions, #summary, #histogram')]"
                          ".map(e => e.id)")
    assert order == ["actions", "summary", "histogram"]


def test_every_chart_has_a_visible_legend_and_readable_axes(page):
    page.evaluate("document.querySelectorAll('details').forEach(d => d.open = true)")
    charts = page.evaluate("""[...document.querySelectorAll('figure.chart')].map(f => {
        const lg = f.querySelector(':scope > figcaption.legend');
        const svg = f.querySelector('svg');
        const texts = [...svg.querySelectorAll('text')].map(t => t.getBoundingClientRect().height)
                                                        .filter(h => h > 0);
        const rot = [...svg.querySelectorAll('text[transform]:not(.ename)')]   // not the names
                    .map(t => t.textContent);
        return {id: f.id, legend: lg ? lg.getBoundingClientRect().height : 0,
                items: lg ? lg.querySelectorAll('.item').length : 0,
                legendInside: lg ? (lg.getBoundingClientRect().bottom
                                    <= f.getBoundingClientRect().bottom + 0.5) : false,
                minText: Math.min(...texts), yLabel: rot}; })""")
    ids = [c["id"] for c in charts]
    assert "histogram" in ids and "residuals" in ids
    assert sum(i.startswith("points-") for i in ids) >= 90       # one per solved entry
    for c in charts:
        assert c["legend"] > 0 and c["items"] >= 3 and c["legendInside"], c
        assert c["minText"] >= 9, c             # tick labels a person can read
        assert c["yLabel"], c                   # the value axis says what it is
    big = {c["id"]: c for c in charts}
    assert big["histogram"]["yLabel"] == ["number of entries"]
    assert big["residuals"]["yLabel"] == ["mm (log scale)"]


def test_residual_chart_keeps_passing_bars_readable(page):
    """The old chart scaled to the worst entry: every passing bar was a flat
    line under the rejected ones. Now a passing entry's bar is tall enough
    to read, and the threshold label overlaps no bar."""
    got = page.evaluate("""(() => {
        const bars = [...document.querySelectorAll('#residuals rect.ebar')];
        const h = bars.map(b => b.getBoundingClientRect().height).sort((a, b) => a - b);
        const label = [...document.querySelectorAll('#residuals text')]
            .find(t => t.textContent.startsWith('threshold')).getBoundingClientRect();
        const over = bars.filter(b => { const r = b.getBoundingClientRect();
            return r.right > label.left && r.left < label.right && r.bottom > label.top
                   && r.top < label.bottom; }).length;
        return {median: h[Math.floor(h.length / 2)], over}; })()""")
    assert got["median"] >= 40 and got["over"] == 0


def test_links_to_csv_and_patched_copies_resolve(page, report):
    hrefs = page.evaluate("[...document.querySelectorAll('#manifest-link, #csv-link, a.patched')]"
                          ".map(a => a.getAttribute('href'))")
    assert hrefs[:2] == ["../manifest.toml", "fleet.csv"] and len(hrefs) > 50
    for h in hrefs:
        assert not h.startswith(("http:", "https:", "/")), h
        assert (report.parent / h).is_file(), h


def test_screenshot_and_layout_match_the_stored_structure(page, tmp_path):
    page.evaluate("document.querySelectorAll('details').forEach(d => d.open = false);"
                  "document.getElementById('e0').open = true; window.scrollTo(0, 0)")
    png = tmp_path / "report.png"
    page.screenshot(png)
    head = png.read_bytes()[:24]
    assert head[:8] == b"\x89PNG\r\n\x1a\n"
    assert struct.unpack(">II", head[16:24]) == (WIDTH, HEIGHT)
    if os.environ.get("UCSIO_KEEP_SCREENSHOT"):
        page.screenshot(os.environ["UCSIO_KEEP_SCREENSHOT"], full_page=True)
    got = page.evaluate(MEASURE % json.dumps(SECTIONS))
    assert not [g for g in got if g.get("missing")]
    layout = {"viewport": [WIDTH, HEIGHT],
              "sections": [{k: (round(v, 1) if isinstance(v, float) else v) for k, v in g.items()}
                           for g in got]}
    if os.environ.get("UCSIO_UPDATE_LAYOUT"):
        EXPECTED.parent.mkdir(exist_ok=True)
        EXPECTED.write_text(json.dumps(layout, indent=1) + "\n")
    want = json.loads(EXPECTED.read_text())
    assert [s["selector"] for s in want["sections"]] == SECTIONS
    # the sections come in the same order down the page, without overlapping
    tops = [g["y"] for g in got]
    assert tops == sorted(tops)
    page_height = max(g["y"] + g["height"] for g in got)
    for w, g in zip(want["sections"], got):
        sel = g["selector"]
        assert abs(g["x"] - w["x"]) <= 8, sel                      # same column
        # same width: a block spans the column; a table's width follows its text
        assert abs(g["width"] - w["width"]) <= max(0.03 * WIDTH, 0.12 * w["width"]), sel
        # heights and positions vary with the fonts a machine has: by share
        assert abs(g["height"] - w["height"]) <= 0.25 * w["height"] + 24, sel
        assert abs(g["y"] - w["y"]) <= 0.15 * page_height + 24, sel


def test_measurement_error_bars_carry_readable_names(page):
    """Issue 18, point 9: each bar of the measurement-error chart has its
    entry's name under it, as large as the chart's other small text, within
    the chart, and the names stand apart (a name's ink does not run into
    the next one's)."""
    got = page.evaluate("""(() => {
        const fig = document.getElementById('residuals'), svg = fig.querySelector('svg');
        const scale = svg.getBoundingClientRect().width / svg.viewBox.baseVal.width;
        const names = [...fig.querySelectorAll('text.ename')];
        const boxes = names.map(t => t.getBoundingClientRect());
        const centres = boxes.map(b => (b.left + b.right) / 2);
        const gaps = centres.slice(1).map((c, i) => c - centres[i]);
        const plot = svg.getBoundingClientRect();
        return {names: names.map(t => t.textContent),
                bars: [...fig.querySelectorAll('rect.ebar')].map(b => b.dataset.name),
                font: Math.min(...names.map(t => parseFloat(t.getAttribute('font-size')))) * scale,
                minGap: Math.min(...gaps),
                inside: boxes.every(b => b.bottom <= plot.bottom + 0.5 && b.top >= plot.top),
                upright: boxes.every(b => b.height > b.width)}; })()""")
    assert got["names"] == got["bars"] and len(got["names"]) >= 90
    assert got["font"] >= 9 and got["inside"] and got["upright"]
    assert got["minGap"] >= 0.95 * got["font"]          # a line apart: readable side by side


def test_an_entrys_linked_picture_opens_with_the_shared_library(chromium, report):
    """issue 29 point 2: an entry's link opens its picture from disk: the
    page asks for nothing but itself, the report's data file and the one
    three.js beside it, draws without error, and the scene it builds in the
    browser is the one ucsio's own picture.scene makes of that entry (every
    number), with one SVG circle per point in each projection."""
    import re

    from ucsio.picture.scene import scene
    html = report.read_text(encoding="utf-8")
    links = re.findall(r'<a class="view" href="([^"]+)"', html)
    folder = report.parent / links[0].split("/")[0]
    text = (folder / "entries.js").read_text(encoding="ascii")
    data = json.loads(text[len("window.UCSIO_ENTRIES = "):-2])
    checked = 0
    for href in links[:3] + links[-3:]:
        page, _, key = href.partition("#")
        target = (report.parent / page).resolve()
        v = data[key]
        with Browser(1280, 900, executable=chromium) as b:
            b.load(target, fragment=key)
            assert b.errors == []
            assert b.evaluate("document.body.dataset.ready") == "1"
            assert [u.split("#")[0] for u in b.requests] == [
                target.as_uri(), (folder / "entries.js").resolve().as_uri(),
                (folder / "three.js").resolve().as_uri()]
            got = json.loads(b.evaluate("document.getElementById('ucsio-scene').textContent"))
            circles = b.evaluate("[...document.querySelectorAll('#projections svg')]"
                                 ".map(s => s.querySelectorAll('circle.point').length)")
            names = [m["name"] for m in b.evaluate("ucsioView.markers('tracker')")]
        solution = {"frame": {"x": v["frame"]["t"][0], "y": v["frame"]["t"][1],
                              "z": v["frame"]["t"][2], "q": v["frame"]["q"]},
                    "accepted": v["accepted"], "rms": v["rms"], "max": v["max"],
                    "points": [{"name": n, "laser": la, "robot": ro, "used": u, "excluded_by": x}
                               for n, la, ro, u, x in v["points"]],
                    "working_points": v["working"], "worst": v["worst"]}
        simulated = None
        if v.get("simulated"):
            sv = v["simulated"]
            pose = lambda p: dict(zip("xyz", p["t"]), q=p["q"])      # noqa: E731
            simulated = {"simulated": pose(sv["sim"]), "measured": pose(sv["mea"]),
                         "name": sv["name"], **sv["delta"]}
        want = scene(solution, simulated=simulated, source=v["title"])
        assert names == [p["name"] for p in want["points"]]
        assert circles == [len(want["points"])] * 3
        for g_, w in zip(got["points"], want["points"]):
            for key_ in ("laser", "tracker", "robot", "d", "drawn"):
                assert g_[key_] == pytest.approx(w[key_], rel=1e-9, abs=1e-9), key_
            assert g_["residual"] == pytest.approx(w["residual"], rel=1e-9, abs=1e-12)
            assert (g_["used"], g_["clipped"]) == (w["used"], w["clipped"])
        for key_ in ("center", "size", "magnify", "axis_length", "scale_bar", "marker"):
            assert got[key_] == pytest.approx(want[key_], rel=1e-9, abs=1e-9), key_
        for f in ("measured", "simulated"):
            if want[f] is None:
                assert got[f] is None
                continue
            assert got[f]["origin"] == pytest.approx(want[f]["origin"], abs=1e-6)
            for a, b in zip(got[f]["axes"], want[f]["axes"]):
                assert a == pytest.approx(b, abs=1e-9)
        checked += 1
    assert checked == 6
