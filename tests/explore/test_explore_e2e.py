"""The explorer in a real browser: headless Chromium driven by Playwright.

The app is served on a free loopback port; the test clicks on the section plane (three
clicks in a row, so the later ones wait in the queue), waits until the orbits' points
are drawn, checks them against ``poincare()`` from the same initial states, changes the
energy in its input field, checks that the plane is recomputed and a new click lands on
the new level, and saves a screenshot. Any error on the page (the status line, or a
JavaScript exception) fails the test.

Needs Debian's ``chromium`` (``/usr/bin/chromium`` or ``$ANDOYER_CHROMIUM``): no browser is
downloaded. Without it the test is skipped, unless ``ANDOYER_REQUIRE_BROWSER=1`` (CI),
where it fails. ``ANDOYER_SCREENSHOT=path`` also writes the screenshot there (the
README's ``docs/explore.png`` is made so).
"""

from __future__ import annotations

import json
import math
import os
import shutil
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from andoyer import RigidBody, energy
from andoyer.integrate import Section, poincare

CHROMIUM = os.environ.get("ANDOYER_CHROMIUM", "/usr/bin/chromium")
REQUIRE = os.environ.get("ANDOYER_REQUIRE_BROWSER", "") not in ("", "0")
#: Without the background-networking switches Chromium's connections are refused on a
#: closed network; as root it needs --no-sandbox.
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]
CROSSINGS = 300
CLICKS = [(1.0, 0.5), (2.0, 0.2), (0.4, 0.25)]

pytestmark = pytest.mark.timeout(120)


def _need_browser() -> Any:
    """The Playwright module, or skip (fail under ANDOYER_REQUIRE_BROWSER=1)."""
    def missing(why: str) -> None:
        if REQUIRE:
            pytest.fail(f"{why}, and ANDOYER_REQUIRE_BROWSER is set")
        pytest.skip(f"{why}: install Debian's chromium (apt-get install chromium) or set "
                    "ANDOYER_CHROMIUM to run the browser test")

    if not (Path(CHROMIUM).is_file() or shutil.which(CHROMIUM)):
        missing(f"no Chromium at {CHROMIUM}")
    try:
        from playwright import sync_api
    except ImportError:
        missing("the Python package playwright is not installed")
    return sync_api


# JavaScript run in the page: the test hook of andoyer.explore.ui (named Bokeh models).
_MODEL = "name => Bokeh.documents[0].get_model_by_name(name)"
_STATE = f"(() => {{ const m = ({_MODEL})('andoyer-state'); " \
         "return m ? JSON.parse(m.text) : null; })()"
_TO_PAGE = """([x, y]) => {
  const fig = Bokeh.documents[0].get_model_by_name('andoyer-plane');
  const view = [...Bokeh.index.all_views()].find(v => v.model === fig);
  const rect = view.canvas_view.el.getBoundingClientRect();
  return [rect.left + view.frame.x_scale.compute(x), rect.top + view.frame.y_scale.compute(y)];
}"""


def _wait(page: Any, condition: str, timeout: float = 60_000) -> dict[str, Any]:
    """Wait until ``condition`` (JS over ``s``, the app's state) holds; fail as soon as
    the page has shown an error message (the app counts them in ``s.errors``)."""
    handle = page.wait_for_function(
        f"() => {{ if (!window.Bokeh || Bokeh.documents.length === 0) return false; "
        f"const s = {_STATE}; return s !== null && (s.errors > 0 || ({condition})) && s; }}",
        timeout=timeout)
    state: dict[str, Any] = handle.json_value()
    if state["errors"] > 0:
        status = page.evaluate(f"() => ({_MODEL})('andoyer-status').text")
        pytest.fail(f"the page showed an error: {status}")
    return state


def _column(page: Any, source: str, name: str) -> np.ndarray:
    return np.asarray(page.evaluate(
        f"() => Array.from(({_MODEL})('{source}').data['{name}'])"), dtype=float)


def _click(page: Any, x: float, y: float) -> None:
    px, py = page.evaluate(_TO_PAGE, [x, y])
    page.mouse.click(px, py)


def test_explore_in_chromium(tmp_path: Path) -> None:
    sync_api = _need_browser()
    from andoyer.explore.server import serve

    body = RigidBody.paper()
    server = serve(body, threaded=True, n_crossings=CROSSINGS)
    page_errors: list[str] = []
    try:
        with sync_api.sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
            try:
                page = browser.new_page(viewport={"width": 1400, "height": 960})
                page.on("pageerror", lambda exc: page_errors.append(str(exc)))
                page.goto(server.url)
                state = _wait(page, "s.view_ready && s.pending === 0")
                h0 = state["h"]

                # Three clicks in a row: the second and third are queued behind the first.
                for x, y in CLICKS:
                    _click(page, x, y)
                _wait(page, f"s.n_orbits === {len(CLICKS)} && s.pending === 0 && "
                            f"({_MODEL})('andoyer-points').data.x.length === "
                            f"{len(CLICKS) * CROSSINGS}")
                ids = _column(page, "andoyer-orbits", "id")
                assert list(ids) == [1, 2, 3]
                seeds = np.stack([_column(page, "andoyer-orbits", v) for v in
                                  ("seed_x", "seed_y")], axis=1)
                # A click lands where it was made (to a fraction of a pixel).
                np.testing.assert_allclose(seeds, CLICKS, atol=0.01)
                colours = page.evaluate(
                    f"() => Array.from(({_MODEL})('andoyer-orbits').data.colour)")
                assert len(set(colours)) == len(CLICKS)
                y0 = np.stack([_column(page, "andoyer-orbits", v) for v in
                               ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")], axis=1)
                np.testing.assert_allclose(energy(body, y0), h0, rtol=0, atol=1e-12)

                # The drawn points are those of one poincare() call, bit for bit.
                px, py = (_column(page, "andoyer-points", v) for v in ("x", "y"))
                orbit = _column(page, "andoyer-points", "orbit")
                for k, oid in enumerate(ids):
                    ref = poincare(body, y0[k], Section("theta2", 0.0, 1), CROSSINGS)
                    rx = np.mod(ref.theta1.values[0], 2 * math.pi)
                    ry = ref.J1.values[0]
                    mine = orbit == oid
                    assert mine.sum() == CROSSINGS
                    np.testing.assert_array_equal(px[mine], rx)
                    np.testing.assert_array_equal(py[mine], ry)

                # Change the energy in its field: the plane is recomputed for the new level.
                before = _column(page, "andoyer-boundary", "y")
                h1 = round(h0 + 0.01, 6)
                field = page.locator(".andoyer-h input")
                field.fill(str(h1))
                field.press("Enter")
                state = _wait(page, f"s.h === {h1} && s.view_ready && s.pending === 0")
                assert state["n_orbits"] == 0
                after = _column(page, "andoyer-boundary", "y")
                assert after.size > 0 and not np.array_equal(np.nan_to_num(before),
                                                             np.nan_to_num(after[:before.size]))
                assert np.nanmax(after) > np.nanmax(before)  # more energy, larger region
                assert _column(page, "andoyer-points", "x").size == 0
                _click(page, *CLICKS[0])
                _wait(page, f"s.n_orbits === 1 && s.pending === 0 && "
                            f"({_MODEL})('andoyer-points').data.x.length === {CROSSINGS}")
                y1 = np.stack([_column(page, "andoyer-orbits", v) for v in
                               ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")], axis=1)
                np.testing.assert_allclose(energy(body, y1), h1, rtol=0, atol=1e-12)

                shot = tmp_path / "explore.png"
                page.screenshot(path=str(shot))
                assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
                if os.environ.get("ANDOYER_SCREENSHOT"):
                    shutil.copyfile(shot, os.environ["ANDOYER_SCREENSHOT"])
                state = json.loads(page.evaluate(f"() => ({_MODEL})('andoyer-state').text"))
                assert state["errors"] == 0 and state["level"] != "error"
            finally:
                browser.close()
    finally:
        server.stop()
    assert not page_errors, f"JavaScript errors on the page: {page_errors}"


_TABLE_STATUS = """() => {
  const table = Bokeh.documents[0].get_model_by_name('andoyer-orbit-table');
  const view = [...Bokeh.index.all_views()].find(v => v.model === table);
  if (!view) return null;
  const root = view.shadow_el || view.el;
  const rows = [...root.querySelectorAll('.slick-row')];
  return rows.map(r => [...r.querySelectorAll('.slick-cell')].map(c => c.textContent.trim()));
}"""


_CLIPPED = """() => {
  const all = [];
  const walk = (root) => {
    for (const el of root.querySelectorAll('*')) {
      if (el.matches('input, select, textarea')) all.push(el);
      if (el.shadowRoot) walk(el.shadowRoot);
    }
  };
  walk(document);
  const status = [...Bokeh.index.all_views()].find(v => v.model.name === 'andoyer-status');
  const main = status.el.getBoundingClientRect().left;
  return all.map(el => [el, el.getBoundingClientRect()])
    .filter(([el, r]) => r.width > 0 && r.height > 0 && el.type !== 'checkbox'
                         && el.type !== 'file')
    .filter(([el, r]) => (r.left < main && r.right > main) || r.right > window.innerWidth)
    .map(([el, r]) => `${el.value}: ${r.left}-${r.right} (the plane starts at ${main})`);
}"""


def test_orbit_table_follows_the_work_without_a_click(tmp_path: Path) -> None:
    """Clicks queue orbits ("queued"); the rendered table shows each one "done" when its
    work ends, with no other interaction (issue 29): read from the table's DOM cells."""
    sync_api = _need_browser()
    from andoyer.explore.server import serve

    server = serve(RigidBody.paper(), threaded=True, n_crossings=CROSSINGS)
    try:
        with sync_api.sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
            try:
                page = browser.new_page(viewport={"width": 1400, "height": 960})
                page.goto(server.url)
                _wait(page, "s.view_ready && s.pending === 0")
                for x, y in CLICKS:
                    _click(page, x, y)
                _wait(page, f"s.n_orbits === {len(CLICKS)} && s.pending === 0")
                # No further click, key or mouse move: the rendered cells must follow.
                page.wait_for_function(
                    f"() => {{ const r = ({_TABLE_STATUS})(); return r !== null && "
                    f"r.length === {len(CLICKS)} && r.every(c => c[c.length - 1] === "
                    f"'done' && c[c.length - 2] === '{CROSSINGS}'); }}", timeout=30_000)
                cells = page.evaluate(_TABLE_STATUS)
                assert [c[0] for c in cells] == ["1", "2", "3"]
                # The sidebar's fields end before the plane starts (they ran under it,
                # their right edges hidden), and no field leaves the window.
                clipped = page.evaluate(_CLIPPED)
                assert clipped == [], f"clipped fields: {clipped}"
            finally:
                browser.close()
    finally:
        server.stop()


#: The two window sizes of the layout test: a desktop and a narrow laptop window (at
#: 1000 px the side panel once stood 330 px beyond the window's right edge).
WINDOWS = [(1400, 960), (1000, 800)]

#: JavaScript: what is wrong with the page's layout, as sentences. Every rendered part of
#: the three columns (``andoyer-controls``, ``andoyer-main``, ``andoyer-side``: widgets,
#: panes, figures; a figure's own parts are drawn inside its box) is measured: none may
#: leave the window or its own column, parts of different columns may not overlap, no
#: part's content may be wider than its box, and the page must not scroll sideways.
_LAYOUT = """() => {
  const groups = ['andoyer-controls', 'andoyer-main', 'andoyer-side'];
  const groupOf = v => {
    for (let p = v; p; p = p.parent) {
      const c = (p.model && p.model.css_classes) || [];
      const g = groups.find(n => c.includes(n));
      if (g) return g;
    }
    return null;
  };
  const boxes = [], overflowing = [];
  for (const v of Bokeh.index.all_views()) {
    if (!(v.el instanceof Element) || !v.el.isConnected
        || !Array.isArray(v.model.css_classes)) continue;
    let inPlot = false;  // a figure's parts (frame, glyphs, axes) are drawn in its box
    for (let p = v.parent; p; p = p.parent)
      if (p.model && (p.model.type === 'Figure' || p.model.type === 'Plot')) inPlot = true;
    if (inPlot) continue;
    const g = groupOf(v);
    if (g === null) continue;
    const r = v.el.getBoundingClientRect();
    if (r.width < 1 || r.height < 1) continue;
    const root = (v.model.css_classes || []).includes(g);
    boxes.push({g, root, what: v.model.name || v.model.type, l: r.left + scrollX,
                r: r.right + scrollX, t: r.top + scrollY, b: r.bottom + scrollY});
    const inner = v.shadow_el || v.el;  // content wider than its box runs out of it
    if (!root && inner.scrollWidth > v.el.clientWidth + 1
        && getComputedStyle(v.el).overflowX === 'visible')
      overflowing.push(`${g}/${v.model.name || v.model.type}: content ${inner.scrollWidth} px `
                       + `wide in a ${v.el.clientWidth} px box`);
  }
  const problems = [...overflowing];
  const W = window.innerWidth;
  if (document.documentElement.scrollWidth > W)
    problems.push(`the page is ${document.documentElement.scrollWidth} px wide `
                  + `in a ${W} px window`);
  for (const x of boxes)
    if (x.l < -0.5 || x.r > W + 0.5)
      problems.push(`${x.g}/${x.what} spans ${x.l}-${x.r}, outside the window 0-${W}`);
  for (const x of boxes) {
    const col = boxes.find(c => c.root && c.g === x.g);
    if (col && (x.l < col.l - 0.5 || x.r > col.r + 0.5))
      problems.push(`${x.g}/${x.what} spans ${x.l}-${x.r}, outside its column ${col.l}-${col.r}`);
  }
  for (let i = 0; i < boxes.length; i++)
    for (let j = i + 1; j < boxes.length; j++) {
      const a = boxes[i], b = boxes[j];
      if (a.g === b.g) continue;  // nested parts of one column contain each other
      const w = Math.min(a.r, b.r) - Math.max(a.l, b.l);
      const h = Math.min(a.b, b.b) - Math.max(a.t, b.t);
      if (w > 0.5 && h > 0.5)
        problems.push(`${a.g}/${a.what} overlaps ${b.g}/${b.what} `
                      + `(${w.toFixed(1)} x ${h.toFixed(1)} px)`);
    }
  const seen = groups.filter(g => boxes.some(x => x.g === g));
  return {problems, groups: seen, n: boxes.length};
}"""


def test_layout_fits_wide_and_narrow_windows(tmp_path: Path) -> None:
    """At 1400 x 960 and at 1000 x 800, with an orbit seeded and selected (its side
    panel filled: description, time plot), nothing overlaps or leaves the window
    (issue 29); a screenshot of the whole page is taken at each size."""
    sync_api = _need_browser()
    from andoyer.explore.server import serve

    server = serve(RigidBody.paper(), threaded=True, n_crossings=CROSSINGS)
    page_errors: list[str] = []
    try:
        with sync_api.sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
            try:
                for width, height in WINDOWS:
                    page = browser.new_page(viewport={"width": width, "height": height})
                    page.on("pageerror", lambda exc: page_errors.append(str(exc)))
                    page.goto(server.url)
                    _wait(page, "s.view_ready && s.pending === 0")
                    _click(page, *CLICKS[0])
                    _wait(page, "s.n_orbits === 1 && s.pending === 0 && s.selected === 1")
                    page.wait_for_function(
                        f"() => ({_MODEL})('andoyer-timeseries').data.xs.length > 0",
                        timeout=60_000)
                    layout = page.evaluate(_LAYOUT)
                    assert layout["groups"] == ["andoyer-controls", "andoyer-main",
                                                "andoyer-side"], layout
                    assert layout["problems"] == [], f"at {width} x {height}: {layout}"
                    shot = tmp_path / f"explore-{width}.png"
                    page.screenshot(path=str(shot), full_page=True)
                    assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
                    page.close()
            finally:
                browser.close()
    finally:
        server.stop()
    assert not page_errors, f"JavaScript errors on the page: {page_errors}"


#: The Plotly 3D view of the side panel (issue 27): its plot element, searched through
#: the shadow roots Panel renders into.
_GYROSCOPE = """() => {
  const found = [];
  const walk = (root) => {
    for (const el of root.querySelectorAll('*')) {
      if (el.classList && el.classList.contains('js-plotly-plot')) found.push(el);
      if (el.shadowRoot) walk(el.shadowRoot);
    }
  };
  walk(document);
  const el = found.find(e => e.layout && e.layout.meta === 'andoyer-gyroscope');
  if (!el || !el._transitionData || !el.data || el.data.length < 4
      || !el._transitionData._frames || el._transitionData._frames.length === 0) return null;
  const gl = el.querySelectorAll('canvas').length;
  return {n_traces: el.data.length, n_frames: el._transitionData._frames.length,
          names: el.data.map(d => d.name), canvases: gl,
          axle: [el.data[2].x[1], el.data[2].y[1], el.data[2].z[1]],
          trace_points: el.data[1].x.length};
}"""


def test_3d_view_of_the_selected_orbit(tmp_path: Path) -> None:
    """A click seeds an orbit; the side panel's 3D view shows that orbit's gyroscope: a
    WebGL scene with the sphere, the axis trace, the axle and the wheel, and frames that
    move the axle in the browser (Plotly.animate), starting where the orbit's vertical
    puts the symmetry axis."""
    sync_api = _need_browser()
    from andoyer.charts.rotation import quaternion_from_vertical, rotation_matrix
    from andoyer.explore.server import serve

    body = RigidBody.paper()
    server = serve(body, threaded=True, n_crossings=50)
    page_errors: list[str] = []
    try:
        with sync_api.sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
            try:
                page = browser.new_page(viewport={"width": 1400, "height": 1400})
                page.on("pageerror", lambda exc: page_errors.append(str(exc)))
                page.goto(server.url)
                _wait(page, "s.view_ready && s.pending === 0")
                _click(page, *CLICKS[0])
                _wait(page, "s.n_orbits === 1 && s.pending === 0")
                view = page.wait_for_function(_GYROSCOPE, timeout=60_000).json_value()
                assert view["names"] == ["sphere", "axis trace", "axle", "wheel"]
                assert view["n_frames"] == 80 and view["trace_points"] == 801
                assert view["canvases"] >= 1  # a WebGL scene
                y0 = np.array([_column(page, "andoyer-orbits", v)[0] for v in
                               ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")])
                tip = rotation_matrix(quaternion_from_vertical(y0[3:], 0.0))[:, 2]
                np.testing.assert_allclose(view["axle"], tip, atol=1e-6)
                # Played in the browser: a later frame moves the axle.
                page.evaluate("""() => new Promise(done => {
                  const walk = (root, out) => { for (const el of root.querySelectorAll('*')) {
                    if (el.classList && el.classList.contains('js-plotly-plot')) out.push(el);
                    if (el.shadowRoot) walk(el.shadowRoot, out); } return out; };
                  const el = walk(document, []).find(e => e.layout.meta === 'andoyer-gyroscope');
                  const name = el._transitionData._frames[40].name;
                  window.Plotly.animate(el, [name], {frame: {duration: 0}, mode: 'immediate'})
                    .then(done);
                })""")
                moved = page.evaluate(_GYROSCOPE)
                assert np.linalg.norm(np.subtract(moved["axle"], view["axle"])) > 1e-3
                page.screenshot(path=str(tmp_path / "explore-3d.png"), full_page=True)
                if os.environ.get("ANDOYER_SCREENSHOT_3D"):
                    shutil.copyfile(tmp_path / "explore-3d.png",
                                    os.environ["ANDOYER_SCREENSHOT_3D"])
            finally:
                browser.close()
    finally:
        server.stop()
    assert not page_errors, f"JavaScript errors on the page: {page_errors}"


#: JavaScript: for each source of the chain overlay, how many items its rendered glyph
#: holds in the browser (the renderer views Bokeh drew on the plane's canvas).
_DRAWN = """() => {
  const out = {};
  for (const v of Bokeh.index.all_views()) {
    const src = v.model && v.model.data_source;
    if (!src || !src.name || !src.name.startsWith('andoyer-chain-') || !v.glyph) continue;
    out[src.name] = v.glyph.data_size;
  }
  return out;
}"""


def test_chain_overlay_in_chromium(tmp_path: Path) -> None:
    """The toggle 'predicted island chains' draws, on the plane on screen, the chains of
    :func:`andoyer.explore.chains.chain_overlay` for the page's body and level: the points
    and lines in the browser are those computed here in Python, their glyphs are rendered,
    the order field and a new level redraw them, unticking removes them, and a level where
    the theory does not apply (h < 0) gives an error message and no chains."""
    sync_api = _need_browser()
    from andoyer.explore.chains import chain_overlay
    from andoyer.explore.server import serve
    from andoyer.explore.state import Settings

    body = RigidBody.paper()
    server = serve(body, threaded=True, n_crossings=50)
    page_errors: list[str] = []
    try:
        with sync_api.sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
            try:
                page = browser.new_page(viewport={"width": 1400, "height": 960})
                page.on("pageerror", lambda exc: page_errors.append(str(exc)))
                page.goto(server.url)
                state = _wait(page, "s.view_ready && s.pending === 0")
                assert state["chains"] is None
                assert _column(page, "andoyer-chain-points", "x").size == 0
                h0 = state["h"]
                page.locator(".andoyer-chains input").check()
                state = _wait(page, "s.chains !== null")
                ref = chain_overlay(Settings(body, h0), 10)
                assert state["chains"] == ref.n_chains == 12
                px, py = (_column(page, "andoyer-chain-points", v) for v in ("x", "y"))
                np.testing.assert_array_equal(px, ref.points_x)
                np.testing.assert_array_equal(py, ref.points_y)
                assert np.all((px >= 0) & (px < 2 * math.pi))   # on the plane shown
                kinds = page.evaluate(
                    f"() => Array.from(({_MODEL})('andoyer-chain-points').data.kind)")
                assert kinds == list(ref.points_kind)
                centres = page.evaluate(
                    f"() => ({_MODEL})('andoyer-chain-centres').data.ys.map(a => a.length)")
                assert centres == [c.size for c in ref.centre_y]
                status = page.evaluate(f"() => ({_MODEL})('andoyer-status').text")
                assert "predicted chains" in status and "12 centre lines" in status
                drawn = page.wait_for_function(
                    f"() => {{ const d = ({_DRAWN})(); return d['andoyer-chain-points'] === "
                    f"{ref.points_x.size} && d; }}", timeout=30_000).json_value()
                assert drawn == {"andoyer-chain-centres": ref.n_chains,
                                 "andoyer-chain-separatrices": len(ref.separatrix_x),
                                 "andoyer-chain-points": ref.points_x.size}
                page.screenshot(path=str(tmp_path / "explore-chains.png"))

                # The order field: fewer chains (6:1 and 7:1 only, both signs).
                field = page.locator(".andoyer-chain-order input")
                field.fill("8")
                field.press("Enter")
                _wait(page, "s.chains === 4")
                np.testing.assert_array_equal(_column(page, "andoyer-chain-points", "x"),
                                              chain_overlay(Settings(body, h0), 8).points_x)

                # A new level: the plane and the chains are recomputed for it.
                h1 = round(h0 + 0.01, 6)
                field = page.locator(".andoyer-h input")
                field.fill(str(h1))
                field.press("Enter")
                _wait(page, f"s.h === {h1} && s.view_ready && s.chains !== null")
                ref1 = chain_overlay(Settings(body, h1), 8)
                got = _column(page, "andoyer-chain-points", "y")
                np.testing.assert_array_equal(got, ref1.points_y)
                assert not np.array_equal(got, ref.points_y[:got.size])

                # Off: nothing of the chains stays on the plane.
                page.locator(".andoyer-chains input").uncheck()
                page.wait_for_function(
                    f"() => {{ const s = {_STATE}; return s && s.chains === null && "
                    f"({_MODEL})('andoyer-chain-centres').data.xs.length === 0; }}",
                    timeout=30_000)

                # h < 0, where the free top has no tori: on again, a message, no chains,
                # no traceback.
                field.fill("-0.001")
                field.press("Enter")
                _wait(page, "s.h === -0.001 && s.view_ready && s.pending === 0")
                page.locator(".andoyer-chains input").check()
                page.wait_for_function(
                    f"() => {{ const s = {_STATE}; return s && s.errors > 0; }}",
                    timeout=60_000)
                status = page.evaluate(f"() => ({_MODEL})('andoyer-status').text")
                assert "andoyer-level-error" in page.evaluate(
                    f"() => ({_MODEL})('andoyer-status').css_classes.join(' ')")
                assert "predicted chains: h must be &gt; 0" in status, status
                assert "Traceback" not in status
                assert _column(page, "andoyer-chain-points", "x").size == 0
                assert json.loads(page.evaluate(
                    f"() => ({_MODEL})('andoyer-state').text"))["chains"] is None
            finally:
                browser.close()
    finally:
        server.stop()
    assert not page_errors, f"JavaScript errors on the page: {page_errors}"
