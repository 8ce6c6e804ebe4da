"""Responsiveness of ``andoyer explore``: time from a click to its first 100 points drawn.

``python -m benchmarks.explore_latency [--clicks 7] [--crossings 500] [--engine heyoka]
[--screenshot docs/explore.png]``

Serves the explorer (paper's body, default energy, section theta2 = 0) on a free
loopback port, drives headless Chromium (Debian's ``/usr/bin/chromium`` or
``$ANDOYER_CHROMIUM``, through Playwright) and clicks on the section plane. One warm-up
click first (the engine's compiled integrator is loaded, the page's code paths run);
then every click is timed from the mouse click to the first animation frame in which
the page's point source holds 100 points of the new orbit, and the next click waits
until the orbit is finished (an idle app each time). Prints one line with the median;
the target is under 1 s on the development machine.

``--screenshot PATH`` seeds a spread of orbits afterwards and saves the page (the
README's ``docs/explore.png`` is made this way).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

CHROMIUM = os.environ.get("ANDOYER_CHROMIUM", "/usr/bin/chromium")
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]

#: Timed clicks (theta1, J1): inside the accessible region of the default level.
CLICKS = [(1.6, 0.45), (1.2, 0.3), (2.0, 0.15), (4.7, 0.5), (4.2, 0.3), (5.2, 0.2),
          (1.6, 0.75), (4.7, 0.85), (0.9, 0.5), (5.5, 0.6)]
#: Orbits of the screenshot: librations about both centres, the layer near the
#: separatrices theta1 = 0 and 4 phi0, and rotations near the top of the region.
PICTURE = [(1.57, 0.5), (1.57, 0.35), (1.57, 0.2), (1.57, 0.08), (2.9, 0.03), (0.1, 0.5),
           (4.71, 0.5), (4.71, 0.35), (4.71, 0.2), (4.71, 0.08), (3.1, 0.6), (1.57, 0.95),
           (4.71, 0.97)]

_MODEL = "name => Bokeh.documents[0].get_model_by_name(name)"
_STATE = f"JSON.parse(({_MODEL})('andoyer-state').text)"
_TO_PAGE = """([x, y]) => {
  const fig = Bokeh.documents[0].get_model_by_name('andoyer-plane');
  const view = [...Bokeh.index.all_views()].find(v => v.model === fig);
  const rect = view.canvas_view.el.getBoundingClientRect();
  return [rect.left + view.frame.x_scale.compute(x), rect.top + view.frame.y_scale.compute(y)];
}"""


def _points_of(oid: int) -> str:
    return (f"(() => {{ const o = ({_MODEL})('andoyer-points').data.orbit; let k = 0; "
            f"for (const v of o) if (v === {oid}) k++; return k; }})()")


def _click_and_time(page, x: float, y: float, oid: int, n_points: int = 100) -> float:
    px, py = page.evaluate(_TO_PAGE, [x, y])
    t0 = time.perf_counter()
    page.mouse.click(px, py)
    page.wait_for_function(f"() => {_points_of(oid)} >= {n_points}", polling="raf",
                           timeout=120_000)
    dt = time.perf_counter() - t0
    page.wait_for_function(f"() => {{ const s = {_STATE}; return s.pending === 0 && "
                           f"s.level !== 'busy'; }}", timeout=600_000)
    level = page.evaluate(f"() => {_STATE}.level")
    if level == "error":
        raise RuntimeError(page.evaluate(f"() => ({_MODEL})('andoyer-status').text"))
    return dt


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.explore_latency",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("--clicks", type=int, default=7, help="timed clicks (default 7, max 10)")
    ap.add_argument("--crossings", type=int, default=500, help="crossings per orbit")
    ap.add_argument("--engine", default=None, help="engine (default: heyoka)")
    ap.add_argument("--screenshot", default=None, help="also save a screenshot here")
    args = ap.parse_args(argv)
    if not Path(CHROMIUM).exists():
        print(f"no Chromium at {CHROMIUM}: install Debian's chromium or set ANDOYER_CHROMIUM",
              file=sys.stderr)
        return 2
    from playwright.sync_api import sync_playwright

    from andoyer.body import RigidBody
    from andoyer.explore.server import serve

    server = serve(RigidBody.paper(), threaded=True, n_crossings=args.crossings,
                   engine=args.engine)
    try:
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
            page = browser.new_page(viewport={"width": 1400, "height": 960})
            page.goto(server.url)
            page.wait_for_function(
                f"() => window.Bokeh && Bokeh.documents.length > 0 && "
                f"({_MODEL})('andoyer-state') !== null && {_STATE}.view_ready && "
                f"{_STATE}.pending === 0", timeout=120_000)
            warm = _click_and_time(page, 1.57, 0.6, 1)
            times = [_click_and_time(page, x, y, k + 2)
                     for k, (x, y) in enumerate(CLICKS[:max(1, min(args.clicks, 10))])]
            med = statistics.median(times)
            print(f"explore latency, click -> first 100 points drawn (paper body, "
                  f"{args.engine or 'heyoka'}, {args.crossings} crossings per orbit): "
                  f"median {med:.3f} s over {len(times)} clicks after warm-up (min "
                  f"{min(times):.3f}, max {max(times):.3f}; warm-up click {warm:.3f} s); "
                  f"target < 1 s: {'met' if med < 1.0 else 'NOT met'}")
            if args.screenshot:
                _clear(page)
                first = 2 + len(times)
                for k, (x, y) in enumerate(PICTURE):
                    _click_and_time(page, x, y, first + k)
                page.screenshot(path=args.screenshot, full_page=True)
                print(f"wrote {args.screenshot}")
            browser.close()
    finally:
        server.stop()
    return 0


def _clear(page) -> None:
    """Press 'clear all orbits' and wait until the plane is empty."""
    page.get_by_role("button", name="clear all orbits").click()
    page.wait_for_function(f"() => {_STATE}.n_orbits === 0", timeout=30_000)


if __name__ == "__main__":
    sys.exit(main())
