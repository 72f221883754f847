"""``ucsio view``'s page in headless Chromium (tests/browser.py), as the batch
report is tested: it opens from disk with no console error and no request
beyond the page itself, the rendered scene's numbers read back equal the
solution's, the canvas is drawn and shows one marker per point, each SVG
projection one circle per point. ``UCSIO_UPDATE_DOCS=1`` also writes the
pictures of docs/view.md. A missing browser skips, or fails under
``UCSIO_REQUIRE_BROWSER`` (as .ci/run sets)."""
from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import pytest

from browser import Browser, blobs, find_chromium
from test_view import run
from view_cases import write_case

DOCS = Path(__file__).resolve().parents[1] / "docs"
MARKER = (0xE6, 0x00, 0x7E)


@pytest.fixture(scope="module")
def chromium():
    path = find_chromium()
    if path is None:
        how = "Chromium is not installed (sudo apt-get install chromium)"
        if os.environ.get("UCSIO_REQUIRE_BROWSER"):
            pytest.fail(f"{how}, and UCSIO_REQUIRE_BROWSER is set: view's browser tests must run")
        pytest.skip(f"{how}: view's browser tests did not run")
    return path


def _page(folder: Path, kind: str) -> tuple[Path, dict]:
    c = write_case(folder, kind)
    out = folder / "view.html"
    code, _, err = run("view", c["solution"], "--controller", c["config"], "--frame",
                       "BASE_DATA[3]", "--at", c["working"], "-o", out)
    assert code == 0, err
    return out, json.loads(c["solution"].read_text())


@pytest.fixture(scope="module")
def opened(chromium, tmp_path_factory):
    html, sol = _page(tmp_path_factory.mktemp("view_browser"), "blunder")
    with Browser(1280, 900, executable=chromium) as b:
        b.load(html)
        shot = html.with_suffix(".png")
        # the names are HTML over the canvas: counted out of the canvas's markers
        b.evaluate("document.getElementById('labels').style.visibility = 'hidden'")
        b.screenshot(shot)
        b.evaluate("document.getElementById('labels').style.visibility = ''")
        yield b, html, sol, shot


def test_opens_from_disk_with_no_error_and_no_request(opened):
    b, html, _, _ = opened
    assert b.errors == []
    assert b.evaluate("document.body.dataset.ready") == "1"
    assert b.requests == [html.resolve().as_uri()]      # the page itself, nothing else


def test_the_rendered_markers_are_the_solutions_points(opened):
    b, _, sol, _ = opened
    scene = json.loads(b.evaluate("document.getElementById('ucsio-scene').textContent"))
    markers = b.evaluate("ucsioView.markers('tracker')")
    robots = b.evaluate("ucsioView.markers('robot')")
    assert [m["name"] for m in markers] == [p["name"] for p in sol["points"]]
    f = sol["frame"]
    for m, r, p, s in zip(markers, robots, sol["points"], scene["points"]):
        assert m["at"] == pytest.approx(s["tracker"], abs=1e-3)       # float32 on the GPU side
        assert r["at"] == pytest.approx(p["robot"], abs=1e-3)
        assert s["residual"] == pytest.approx(p["residual"], abs=1e-9)
    assert scene["measured"]["origin"] == pytest.approx([f["x"], f["y"], f["z"]], abs=1e-9)


def test_the_canvas_shows_one_marker_per_point(opened):
    b, _, sol, shot = opened
    box = b.evaluate("(() => { const r = document.querySelector('#view3d canvas')"
                     ".getBoundingClientRect(); return {x: r.left, y: r.top, width: r.width,"
                     " height: r.height}; })()")
    assert blobs(shot, MARKER, box) == len(sol["points"])
    assert blobs(shot, (0xFF, 0x7F, 0x0E), box) >= 1                  # a residual drawn


def test_hover_tells_a_points_numbers(opened):
    b, _, sol, _ = opened
    text = b.evaluate("""(() => { const m = ucsioView.scene.children.find(o =>
          o.userData && o.userData.kind === 'tracker' && o.userData.name === 'P6');
        const v = m.position.clone().project(ucsioView.camera);
        const r = document.querySelector('#view3d canvas').getBoundingClientRect();
        window.dispatchEvent(new PointerEvent('pointermove', {clientX: r.left + (v.x + 1) / 2
          * r.width, clientY: r.top + (1 - v.y) / 2 * r.height}));
        return document.getElementById('info').textContent; })()""")
    p6 = next(p for p in sol["points"] if p["name"] == "P6")
    assert text.startswith("P6 (excluded") and f"{p6['residual']:.3f}" in text


def test_rotate_zoom_and_reset(opened):
    """A drag turns the camera, the wheel zooms (the scale bar follows), reset
    comes back to the first view."""
    b = opened[0]
    state = ("JSON.stringify([ucsioView.camera.position.toArray().map(v => v.toFixed(3)), "
             "ucsioView.camera.zoom, document.getElementById('scale-text').textContent])")
    first = b.evaluate(state)
    b.evaluate("""(() => { const c = document.querySelector('#view3d canvas');
        const r = c.getBoundingClientRect(), x = r.left + 200, y = r.top + 200;
        c.dispatchEvent(new PointerEvent('pointerdown', {clientX: x, clientY: y, bubbles: true}));
        window.dispatchEvent(new PointerEvent('pointermove', {clientX: x + 80, clientY: y + 30}));
        window.dispatchEvent(new PointerEvent('pointerup', {clientX: x + 80, clientY: y + 30}));
        c.dispatchEvent(new WheelEvent('wheel', {deltaY: -1500, bubbles: true, cancelable: true}));
    })()""")
    turned = json.loads(b.evaluate(state))
    assert turned[0] != json.loads(first)[0] and turned[1] > 4 and turned[2] != json.loads(first)[2]
    b.evaluate("document.getElementById('reset').click()")
    assert b.evaluate(state) == first


def test_each_projection_has_one_circle_per_point(opened):
    b, _, sol, _ = opened
    counts = b.evaluate("[...document.querySelectorAll('#static svg')].map(s => "
                        "s.querySelectorAll('circle').length)")
    assert counts == [len(sol["points"])] * 3


@pytest.mark.parametrize("kind", ["swapped", "blunder", "one-sided", "rotated"])
def test_the_docs_pictures(chromium, tmp_path, kind):
    """Each mistake docs/view.md shows renders cleanly; UCSIO_UPDATE_DOCS=1 keeps the picture."""
    html, sol = _page(tmp_path, kind)
    with Browser(1000, 760, executable=chromium) as b:
        b.load(html)
        assert b.errors == [] and len(b.requests) == 1
        shot = tmp_path / f"view-{kind}.png"
        b.evaluate("document.getElementById('stage').scrollIntoView()")
        b.screenshot(shot)
    assert blobs(shot, MARKER) >= len(sol["points"]) - 2      # the SVG's circles too; merged few
    if os.environ.get("UCSIO_UPDATE_DOCS"):
        shutil.copy(shot, DOCS / f"view-{kind}.png")
