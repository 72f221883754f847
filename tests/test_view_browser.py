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
from pathlib import Path

import pytest

from browser import Browser, find_chromium
from test_view import run
from view_cases import write_case

DOCS = Path(__file__).resolve().parents[1] / "docs"
MARKER = (0xE6, 0x00, 0x7E)

# The canvas's own pixels (the page keeps its drawing buffer), copied to a 2D
# canvas: patches of exactly one colour, 4-connected, and the colours drawn.
PIXELS = """((rgb) => {
  const gl = document.querySelector('#view3d canvas'), w = gl.width, h = gl.height;
  const c = document.createElement('canvas'); c.width = w; c.height = h;
  const ctx = c.getContext('2d'); ctx.drawImage(gl, 0, 0);
  const px = ctx.getImageData(0, 0, w, h).data, seen = new Uint8Array(w * h);
  const is = i => px[4 * i] === rgb[0] && px[4 * i + 1] === rgb[1] && px[4 * i + 2] === rgb[2];
  let patches = 0, other = 0;
  for (let i = 0; i < w * h; i++) {
    if (px[4 * i] !== 255 || px[4 * i + 1] !== 255 || px[4 * i + 2] !== 255) other++;
    if (seen[i] || !is(i)) continue;
    patches++; const stack = [i]; seen[i] = 1;
    while (stack.length) { const j = stack.pop(), x = j % w;
      for (const k of [x > 0 ? j - 1 : -1, x < w - 1 ? j + 1 : -1, j - w, j + w])
        if (k >= 0 && k < w * h && !seen[k] && is(k)) { seen[k] = 1; stack.push(k); } }
  }
  return {patches: patches, drawn: other, total: w * h};
})(RGB)"""


def canvas(b, rgb=MARKER) -> dict:
    return b.evaluate(PIXELS.replace("RGB", json.dumps(list(rgb))))


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
        yield b, html, sol


def test_opens_from_disk_with_no_error_and_no_request(opened):
    b, html, _ = opened
    assert b.errors == []
    assert b.evaluate("document.body.dataset.ready") == "1"
    assert b.requests == [html.resolve().as_uri()]      # the page itself, nothing else


def test_the_rendered_markers_are_the_solutions_points(opened):
    b, _, sol = opened
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
    b, _, sol = opened
    got = canvas(b)
    assert got["patches"] == len(sol["points"])
    assert 50 * len(sol["points"]) < got["drawn"] < 0.5 * got["total"]  # drawn, not blank
    assert canvas(b, (0xFF, 0x7F, 0x0E))["patches"] >= 1               # a residual drawn


def test_hover_tells_a_points_numbers(opened):
    b, _, sol = opened
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
    b, _, sol = opened
    counts = b.evaluate("[...document.querySelectorAll('#static svg')].map(s => "
                        "s.querySelectorAll('circle').length)")
    assert counts == [len(sol["points"])] * 3


def test_the_docs_pictures(chromium, tmp_path):
    """Each mistake docs/view.md shows renders cleanly, every point a marker
    apart; UCSIO_UPDATE_DOCS=1 keeps the pictures."""
    with Browser(1000, 760, executable=chromium) as b:
        for kind in ("swapped", "blunder", "one-sided", "rotated"):
            html, sol = _page(tmp_path / kind, kind)
            before = len(b.requests)
            b.load(html)
            assert b.errors == [] and b.requests[before:] == [html.resolve().as_uri()], kind
            patches = canvas(b)["patches"]
            if kind == "one-sided":     # bunched points: some overlap in the view, as they should
                assert 0 < patches <= len(sol["points"])
            else:
                assert patches == len(sol["points"]), kind
            if os.environ.get("UCSIO_UPDATE_DOCS"):
                b.evaluate("document.getElementById('stage').scrollIntoView()")
                b.screenshot(DOCS / f"view-{kind}.png")
