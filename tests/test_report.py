"""ucsio batch --report: one self-contained HTML file whose numbers are the
JSON's (the browser side: test_report_browser.py)."""
from __future__ import annotations

import html
import importlib.util
import json
import re
from html.parser import HTMLParser
from pathlib import Path

import pytest

from ucsio.cli import main

ROOT = Path(__file__).resolve().parents[1]


def _make_fleet():
    spec = importlib.util.spec_from_file_location("make_fleet", ROOT / "fixtures/fleet/make_fleet.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.make_fleet


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    dest = tmp_path_factory.mktemp("fleet")
    _make_fleet()(dest)
    html_path = dest / "report.html"
    json_path = dest / "out.json"
    import contextlib
    import io
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        code = main(["batch", str(dest / "manifest.toml"), "--json", "--report", str(html_path)])
    assert code == 1
    json_path.write_text(buf.getvalue())
    return html_path, json.loads(buf.getvalue())


class _Collect(HTMLParser):
    def __init__(self):
        super().__init__()
        self.tags: list[tuple[str, dict]] = []
        self.script: dict[str, str] = {}
        self._in = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.tags.append((tag, a))
        if tag == "script":
            self._in = a.get("id")
            self.script[self._in] = ""

    def handle_endtag(self, tag):
        if tag == "script":
            self._in = None

    def handle_data(self, data):
        if self._in is not None:
            self.script[self._in] += data


def _parse(path: Path) -> _Collect:
    p = _Collect()
    p.feed(path.read_text(encoding="utf-8"))
    return p


def _num(s: str):
    return None if s == "" else float(s)


def test_embedded_json_is_the_json_output(report):
    path, data = report
    p = _parse(path)
    embedded = json.loads(p.script["ucsio-data"])
    assert embedded == data


def test_summary_numbers_in_html(report):
    path, data = report
    p = _parse(path)
    s = data["summary"]
    cards = {a["data-key"]: a["data-value"] for t, a in p.tags if "data-key" in a}
    for key in ("total", "passed", "rejected", "errors", "over_tolerance"):
        assert int(cards[key]) == s[key]
    assert float(cards["success_rate"]) == s["success_rate"]
    groups = [a for t, a in p.tags if t == "tr" and a.get("class") == "group"]
    assert len(groups) == 5
    for a, g in zip(groups, s["groups"]):
        assert int(a["data-group"]) == g["group"]
        assert int(a["data-count"]) == g["count"]
        assert float(a["data-percent"]) == g["percent"]
        assert _num(a["data-mean-e"]) == g["mean_e"]
        assert _num(a["data-std-e"]) == g["std_e"]
    corr = next(a for t, a in p.tags if a.get("id") == "correlation")
    for k in "xyz":
        assert _num(corr[f"data-{k}"]) == s["correlation"][k]


def test_entry_rows_in_html(report):
    path, data = report
    p = _parse(path)
    rows = [a for t, a in p.tags if t == "tr" and a.get("class") == "entry"]
    assert len(rows) == len(data["entries"])
    for a, e in zip(rows, data["entries"]):
        assert a["data-name"] == e["name"] and a["data-status"] == e["status"]
        assert _num(a["data-dt-mean"]) == e["dt_mean"]
        assert _num(a["data-e"]) == e["e"]
        assert a["data-group"] == ("" if e["group"] is None else str(e["group"]))
        assert a["data-pass"] == ("true" if e["pass"] else "false")
    bars = [a for t, a in p.tags if a.get("class") == "ebar"]
    assert [b["data-name"] for b in bars] == [e["name"] for e in data["entries"] if e["e"] is not None]


def test_histogram(report):
    path, data = report
    p = _parse(path)
    bins = [a for t, a in p.tags if t == "rect" and a.get("class") == "bin"]
    accepted = [e for e in data["entries"] if e["dt_mean"] is not None]
    assert sum(int(b["data-count"]) for b in bins) == len(accepted)
    bounds = [float(a["data-mm"]) for t, a in p.tags if a.get("class") == "boundary"]
    assert bounds == [10.0, 25.0, 50.0, 100.0]


def test_self_contained(report):
    path, _ = report
    text = path.read_text(encoding="utf-8")
    p = _parse(path)
    assert not [a for t, a in p.tags if t in ("link", "img", "iframe", "object", "embed")]
    assert not [a for t, a in p.tags if t == "script" and "src" in a]
    assert [a.get("type") for t, a in p.tags if t == "script"] == ["application/json"]
    urls = set(re.findall(r"https?://[^\s\"'<>)]+", text))
    assert urls <= {"http://www.w3.org/2000/svg"}          # the SVG namespace is not a fetch
    assert "Content-Security-Policy" in text
    assert text.count("<svg") >= 2


def test_names_are_escaped(tmp_path):
    from ucsio.fleet.report import render_report
    data = {"manifest": "m.toml", "summary": {
        "total": 1, "passed": 0, "rejected": 0, "errors": 1, "over_tolerance": 0,
        "success_rate": 0.0, "correlation": {"x": None, "y": None, "z": None},
        "groups": [{"group": g, "range": [0, None], "count": 0, "percent": 0.0, "mean_e": None,
                    "std_e": None} for g in range(1, 6)]},
        "entries": [{"name": "<b>x</b></script>", "status": "error", "accepted": False, "e": None,
                     "dt_mean": None, "group": None, "pass": False, "frame": None,
                     "error": "bad & <worse>", "frame_name": "f", "controller": "c.mod"}]}
    html = render_report(data)
    assert "<b>x</b>" not in html and "&lt;b&gt;x&lt;/b&gt;" in html
    assert "</script>\"" not in html                         # the JSON cannot end the script early
    p = _Collect()
    p.feed(html)
    assert json.loads(p.script["ucsio-data"]) == data


def _one(entry: dict, **summary) -> dict:
    sm = {"total": 1, "passed": 0, "rejected": 0, "errors": 1, "over_tolerance": 0,
          "success_rate": 0.0, "correlation": {"x": None, "y": None, "z": None},
          "groups": [{"group": g, "range": [0, None], "count": 0, "percent": 0.0, "mean_e": None,
                      "std_e": None} for g in range(1, 6)]}
    sm.update(summary)
    return {"manifest": "m.toml", "summary": sm, "entries": [entry]}


def test_entry_failed_after_it_was_solved():
    """Refused at the diff (e.g. a KUKA BASE_TYPE #TCP base): e is null, but
    the points, n_used and rms are there; the report shows both."""
    from ucsio.fleet.report import render_report
    entry = {"name": "R01", "status": "error", "accepted": False, "e": None, "dt_mean": None,
             "group": None, "pass": False, "frame": None, "stage": "diff",
             "error": "frame BASE_DATA[2]: BASE_TYPE #TCP: not a plain base",
             "frame_name": "fixed_spindle", "controller": "$config.dat", "threshold": 1.5,
             "min_points": 6, "tolerance": 100.0, "n_points": 8, "n_used": 7, "rms": 0.0612,
             "mean": 0.05, "max": 0.1, "simulated": {"x": 1.0, "y": 2.0, "z": 3.0, "a": 0.0,
                                                     "b": 0.0, "c": 0.0, "q": [1, 0, 0, 0]},
             "points": [{"name": f"P{i}", "residual": 0.05, "loo_residual": None, "used": i != 0,
                         "excluded_by": "auto" if i == 0 else None} for i in range(8)]}
    html = render_report(_one(entry))
    assert "BASE_TYPE #TCP" in html and "at the diff stage" in html
    assert "n 7 of 8 used, e \u2013 mm, rms 0.061" in html
    assert '<td class="n">7/8</td>' in html


def test_uncertainty_axes_and_patch_error_in_report():
    from ucsio.fleet.report import render_report
    entry = {"name": "o", "status": "pass", "accepted": True, "e": 0.05, "dt_mean": 1.0,
             "group": 1, "pass": True, "n_points": 6, "n_used": 6, "rms": 0.05, "max": 0.08,
             "threshold": 1.5, "tolerance": 100.0, "points": [],
             "uncertainty": {"std": {"x": 0.01, "y": 0.02, "z": 0.03, "angle": 0.001}},
             "uncertainty_axes": "uframe", "patch_error": "wobj1: also declared in other.mod"}
    html = render_report(_one(entry, passed=1, errors=0, success_rate=1.0, patched=0,
                              patch_errors=1))
    assert "uncertainty (std, user frame axes) x 0.0100" in html
    assert 'id="patch-errors"' in html and "patched copy NOT written: wobj1: also declared" in html
    assert 'data-key="patch_errors" data-value="1"' in html and "not patched</span>" in html


def test_rejected_entry_shows_its_reason():
    """REJECTED says why, as the solver did: n_used >= min_points can be
    rejected too (residuals over the threshold, no point to single out). A
    JSON without a reason (older, hand-edited) gets a generic line, shown
    even when the entry has no points."""
    from ucsio.fleet.report import render_report
    why = ("residuals over the threshold and no point can be singled out: max 7.100 mm > 1.5 mm "
           "with 3 points used (the leave-one-out residual needs at least 4 points)")
    entry = {"name": "three", "status": "rejected", "accepted": False, "e": 2.5, "pass": False,
             "reason": why, "n_points": 3, "n_used": 3, "min_points": 3, "threshold": 1.5,
             "points": [{"name": f"P{i}", "residual": 3.0, "loo_residual": None, "used": True,
                         "excluded_by": None} for i in range(3)]}
    html = render_report(_one(entry, rejected=1, errors=0))
    assert "only 3 points left" not in html and "at least 3 needed" not in html
    shown = why.replace(">", "&gt;")
    assert f"REJECTED: {shown}; measure again" in html
    assert f'data-reason="{shown}"' in html and f'title="{shown}"' in html
    bare = {"name": "old", "status": "rejected", "accepted": False}
    html = render_report(_one(bare, rejected=1, errors=0))
    assert "REJECTED: the dataset was rejected; measure again" in html
    entry["reason"] = "<b>x</b>"
    assert "REJECTED: &lt;b&gt;x&lt;/b&gt;; measure again" in render_report(_one(entry))


def test_action_list_comes_first_with_reasons_and_what_to_do(report):
    path, data = report
    text = path.read_text(encoding="utf-8")
    assert text.index('id="actions"') < text.index('id="summary"') < text.index('id="histogram"')
    p = _parse(path)
    items = [a for t, a in p.tags if t == "li" and a.get("class") == "action"]
    need = [e for e in data["entries"] if e["status"] != "pass"]
    assert sorted(a["data-name"] for a in items) == sorted(e["name"] for e in need)
    kinds = [a["data-kind"] for t, a in p.tags if a.get("class") == "kind"]
    assert kinds == ["over tolerance", "rejected", "error"]
    for e in need:                       # each entry's own reason, in the action list
        why = e["error"] if e["status"] == "error" else e["reason"] if e["status"] == "rejected" \
            else f"{e['dt_mean']:.1f} mm off on average along x, y and z"
        section = text[text.index('id="actions"'):text.index('id="summary"')]
        assert html.escape(why, quote=True) in section, why
    assert text.count('class="todo"') >= len(kinds)


def test_run_facts_are_stated(report):
    from ucsio import __version__
    path, data = report
    text = path.read_text(encoding="utf-8")
    meta = text[text.index('id="meta"'):text.index('id="actions"')]
    assert re.search(r"made <b>\d{4}-\d\d-\d\d \d\d:\d\d UTC</b>", meta)
    assert f"by ucsio <b>{__version__}</b>" in meta
    assert html.escape(data["manifest"]) in meta
    for words in ("tolerance <b>", "outlier threshold <b>1.5 mm", "min points <b>"):
        assert words in meta


def test_station_rollup(report):
    path, data = report
    p = _parse(path)
    rows = {a["data-station"]: a for t, a in p.tags if a.get("class") == "station"}
    by = {}
    for e in data["entries"]:
        by.setdefault(e["station"], []).append(e)
    assert set(rows) == set(by)
    for st, es in by.items():
        assert int(rows[st]["data-entries"]) == len(es)
        assert int(rows[st]["data-passed"]) == sum(e["status"] == "pass" for e in es)


def test_nothing_needs_action_and_points_moved():
    from ucsio.fleet.report import render_report
    entry = {"name": "ok", "status": "pass", "accepted": True, "e": 0.05, "dt_mean": 3.0,
             "group": 1, "pass": True, "station": "cell 7", "tolerance": 100.0,
             "points_moved": {"count": 12, "max": 17.25, "mean": 6.0, "worst": "XP7"}}
    html_text = render_report(_one(entry, passed=1, errors=0, success_rate=1.0))
    assert "Nothing needs action" in html_text and "All 1 entry passed" in html_text
    assert 'data-points-max="17.25"' in html_text and "17.250 (12)" in html_text
    assert "they move in world by up to 17.250 mm (XP7)" in html_text
    over = dict(entry, status="over tolerance", dt_mean=150.0, group=5, **{"pass": False})
    html_text = render_report(_one(over, errors=0))
    assert "its taught points move by up to 17.2 mm (XP7)" in html_text


# ---------------------------------------------------------------- issue 18, point 9

def test_measurement_error_bars_carry_their_entry_names(report):
    path, data = report
    labels: list[str] = []

    class Labels(HTMLParser):
        def __init__(self):
            super().__init__()
            self.on = False

        def handle_starttag(self, tag, attrs):
            self.on = tag == "text" and dict(attrs).get("class") == "ename"

        def handle_endtag(self, tag):
            self.on = False

        def handle_data(self, d):
            if self.on:
                labels.append(d)

    text = path.read_text(encoding="utf-8")
    chart = text.split('id="residuals"', 1)[1].split("</figure>", 1)[0]
    Labels().feed(chart)
    solved = [e["name"] for e in data["entries"] if e["e"] is not None]
    assert labels == solved                     # one per bar, in the bars' order


def test_long_names_are_shortened_and_crowds_thinned():
    from ucsio.fleet.report import residual_bars_svg
    rows = [{"name": "Station 12 / robot 3 / the big welding fixture", "e": 0.05, "max": 0.1}]
    svg = residual_bars_svg(rows, 1.5)
    assert ">Station 12 / robot 3 / t…</text>" in svg
    assert "Station 12 / robot 3 / the big welding fixture: e 0.050" in svg   # the tooltip keeps all
    many = [{"name": f"E{i}", "e": 0.05, "max": 0.1} for i in range(400)]
    svg = residual_bars_svg(many, 1.5)
    shown = re.findall(r'class="ename"[^>]*>([^<]*)<', svg)
    assert 0 < len(shown) < 400 and shown[0] == "E0"          # every k-th, never on top of each other
    assert "every" in svg                                      # and the axis says so


def test_laser_and_robot_files_are_both_listed():
    from ucsio.fleet.report import render_report
    entry = {"name": "R03 jig", "status": "pass", "accepted": True, "e": 0.05, "dt_mean": 1.0,
             "group": 1, "pass": True, "n_points": 6, "n_used": 6, "rms": 0.05, "max": 0.08,
             "threshold": 1.5, "tolerance": 100.0, "points": [],
             "measurement": "R03/jig_points.txt", "controller": "R03/$config.dat",
             "sources": {"laser": "R03/jig_points.txt", "robot": "R03/MEASURE.dat",
                         "config": "R03/$config.dat", "map": "R03/names.csv"}}
    html = render_report(_one(entry, passed=1, errors=0, success_rate=1.0))
    shown = html.split('<script type="application/json"', 1)[0]
    assert "laser <code>R03/jig_points.txt</code>" in shown
    assert "robot <code>R03/MEASURE.dat</code>" in shown
    assert "map <code>R03/names.csv</code>" in shown
    assert "measurement <code>R03/jig_points.txt</code>" not in shown


def test_groups_cite_the_study_and_the_noise_check_is_said_once():
    """Issue 25, point 10: no "Table 4" the report does not show; the
    correlation folded away with what it shows; the noise check's
    explanation once, with a count, each entry keeping its own numbers."""
    from ucsio.fleet.report import GROUPS_SOURCE, render_report
    noise = {"ratio": 8.6, "p": 1e-12, "dof": 18, "sigma_residual": 0.431,
             "sigma_stated": 0.0522, "message": "the residuals show 0.431 mm ..."}
    entries = [{"name": f"R0{k}", "status": "pass", "accepted": True, "e": 0.4,
                "dt_mean": 3.0, "group": 1, "pass": True, "frame": None, "frame_name": "f",
                "controller": f"R0{k}/c.mod", "consistency": dict(noise) if k < 4 else
                {"ratio": 1.0, "p": 0.5}} for k in range(1, 6)]
    data = _one(entries[0], total=5, passed=5, errors=0,
                correlation={"x": 0.99999, "y": 1.0, "z": 0.99998})
    data["entries"] = entries
    page = render_report(data).split('<script type="application/json"', 1)[0]
    assert "Table 4)</h2>" not in page and "<h2>Groups by dt_mean</h2>" in page
    assert html.escape(GROUPS_SOURCE) in page
    p = _Collect()
    p.feed(page)
    once = [a for t, a in p.tags if a.get("id") == "noise-check"]
    assert len(once) == 1 and once[0]["data-count"] == "3"
    assert page.count("would happen with p below") == 1
    assert "3 of 5 entries (R01, R02, R03)" in page
    assert page.count('class="note warning noise-check"') == 3
    assert "0.431 mm of noise per axis, 8.6 times the stated 0.052 mm" in page
    folded = page.split('<details class="note" id="correlation-details">', 1)[1]
    assert 'id="correlation"' in folded.split("</details>", 1)[0]
    assert "not how far" in folded


def test_station_views_draw_every_frame_where_it_moved(report):
    """issue 29 point 2: one picture per station, from above: every entry
    with a simulated frame at its nominal origin, its measured origin at the
    nominal plus the diff's shift times the stated factor (the SVG's own
    coordinates checked against the JSON), coloured by its group."""
    from ucsio.fleet.report import GROUP_COLORS, station_of
    path, doc = report
    tags = _parse(path).tags
    views = {a["data-station"]: a for t, a in tags if t == "svg" and "data-factor" in a}
    entries = [e for e in doc["entries"] if e.get("simulated")]
    assert set(views) == {station_of(e) for e in entries}
    frames, measured = [], []
    svg = None
    for t, a in tags:
        if t == "svg":
            svg = a if "data-factor" in a else None
        elif svg is not None and t == "g" and a.get("class") == "frame":
            frames.append((svg, a))
        elif svg is not None and t == "circle" and a.get("class") == "measured":
            measured.append(a)
    assert len(frames) == len(entries)
    by_name = {e["name"]: e for e in entries}
    moved = [(s, a) for s, a in frames if a["data-dx"] != ""]
    assert len(moved) == len(measured) == sum(bool(e.get("accepted")) for e in entries)
    for (s, a), dot in zip(moved, measured):
        e = by_name[a["data-name"]]
        assert station_of(e) == s["data-station"]
        scale, factor = float(s["data-scale"]), float(s["data-factor"])
        cx, cy = float(s["data-cx"]), float(s["data-cy"])
        px = 210 + (e["simulated"]["x"] - cx) * scale
        py = 138 - (e["simulated"]["y"] - cy) * scale
        assert float(dot["cx"]) == pytest.approx(px + e["diff"]["dx"] * factor * scale, abs=0.06)
        assert float(dot["cy"]) == pytest.approx(py - e["diff"]["dy"] * factor * scale, abs=0.06)
        assert dot["fill"] == GROUP_COLORS[e["group"] - 1]
    # a rejected entry shows where it should be, not a shift it does not have
    assert all(not by_name[a["data-name"]].get("accepted") for s, a in frames
               if a["data-dx"] == "")


def test_each_solved_entry_links_its_picture(report):
    """issue 29 point 2: every solved entry's details link its 3D picture:
    REPORT.views/view.html#k beside the report, one page that draws entry k
    from one data file of every entry's fit and point pairs (entries.js),
    with one shared three.js there (the report itself stays without
    script); the data holds each entry's points and fit as the JSON has them."""
    from ucsio.picture.page import three_version
    path, doc = report
    folder = path.with_suffix(".views")
    links = [a["href"] for t, a in _parse(path).tags if t == "a" and a.get("class") == "view"]
    solved = [k for k, e in enumerate(doc["entries"]) if e.get("points")]
    assert links == [f"{folder.name}/view.html#{k + 1}" for k in solved]
    assert sorted(p.name for p in folder.iterdir()) == ["entries.js", "three.js", "view.html"]
    assert three_version() in (folder / "three.js").read_text(encoding="utf-8")[:200]
    assert path.read_bytes().count(b"<script") == 1          # the JSON data block alone
    text = (folder / "entries.js").read_text(encoding="ascii")
    assert text.startswith("window.UCSIO_ENTRIES = ") and text.endswith(";\n")
    data = json.loads(text[len("window.UCSIO_ENTRIES = "):-2])
    assert sorted(map(int, data)) == [k + 1 for k in solved]
    for k in solved:
        e, v = doc["entries"][k], data[str(k + 1)]
        assert [p[0] for p in v["points"]] == [p["name"] for p in e["points"]]
        assert [p[3] for p in v["points"]] == [p["used"] for p in e["points"]]
        assert v["frame"]["t"] == pytest.approx([e["frame"][c] for c in "xyz"], abs=1e-9)
