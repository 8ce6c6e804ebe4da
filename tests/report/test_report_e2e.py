"""The report in a real browser: headless Chromium (Playwright) at two window widths.

``index.html`` of a quick report is opened at 800 and 1400 CSS pixels: every figure is
loaded, fits the window (no horizontal scrolling), is shown smaller in the narrow
window than in the wide one (it scales with the window) and no larger than the PNG
itself, and a click on a figure opens the PNG at full size; every table fits the page
(its cells wrap); every formula is typeset by the MathJax copied beside the page (no
TeX delimiter left as text, no request leaving the folder). That labels inside the
figures do not overlap is checked on the figures themselves (tests/plot/test_layout.py).

Needs Debian's ``chromium`` (``/usr/bin/chromium`` or ``$ANDOYER_CHROMIUM``): no browser
is downloaded. Without it the test is skipped, unless ``ANDOYER_REQUIRE_BROWSER=1``
(CI), where it fails. ``ANDOYER_SCREENSHOT_DIR=folder`` keeps the screenshots there.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path
from typing import Any

import pytest

from andoyer.report.paper import build_paper

CHROMIUM = os.environ.get("ANDOYER_CHROMIUM", "/usr/bin/chromium")
REQUIRE = os.environ.get("ANDOYER_REQUIRE_BROWSER", "") not in ("", "0")
ARGS = ["--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
        "--disable-component-update", "--disable-sync"]
WIDTHS = (800, 1400)

pytestmark = pytest.mark.timeout(300)

# Per figure: where it is on the page, its shown and natural sizes, its link.
_FIGURES = """() => [...document.querySelectorAll('figure img')].map(img => {
  const r = img.getBoundingClientRect();
  return {src: img.getAttribute('src'), left: r.left, right: r.right, width: r.width,
          height: r.height, natural: img.naturalWidth, naturalHeight: img.naturalHeight,
          complete: img.complete, link: img.closest('a') && img.closest('a').getAttribute('href')};
})"""


def _sync_api() -> Any:
    def missing(why: str) -> None:
        if REQUIRE:
            pytest.fail(f"{why}, and ANDOYER_REQUIRE_BROWSER is set")
        pytest.skip(f"{why}: install Debian's chromium or set ANDOYER_CHROMIUM")

    if not (Path(CHROMIUM).is_file() or shutil.which(CHROMIUM)):
        missing(f"no Chromium at {CHROMIUM}")
    try:
        from playwright import sync_api
    except ImportError:
        missing("the Python package playwright is not installed")
    return sync_api


def inner_width(page: Any) -> float:
    return float(page.evaluate("() => document.documentElement.clientWidth"))


def test_report_figures_scale_with_the_window(tmp_path: Path) -> None:
    sync_api = _sync_api()
    index, _ = build_paper(tmp_path / "paper", quick=True,
                           only=["fig1", "fig2", "heteroclinic", "paper-check"],
                           engine="numba", progress=False, jobs=1)
    shots = Path(os.environ.get("ANDOYER_SCREENSHOT_DIR", tmp_path))
    shown: dict[int, dict[str, float]] = {}
    with sync_api.sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        try:
            for width in WIDTHS:
                page = browser.new_page(viewport={"width": width, "height": 1000})
                errors: list[str] = []
                requests: list[str] = []
                page.on("pageerror", lambda exc, errors=errors: errors.append(str(exc)))
                page.on("request", lambda r, requests=requests: requests.append(r.url))
                page.goto(index.as_uri())
                page.wait_for_load_state("load")
                page.wait_for_function("() => window.MathJax && MathJax.startup && "
                                       "MathJax.startup.promise", timeout=30000)
                page.evaluate("() => MathJax.startup.promise")
                typeset = page.evaluate("() => document.querySelectorAll('mjx-container').length")
                raw = page.evaluate("() => [...document.querySelectorAll('p, li')]"
                                    ".map(e => e.innerText)"
                                    ".filter(s => s.includes('\\\\(')).length")
                tables = page.evaluate("""() => [...document.querySelectorAll('table')].map(
                    t => t.getBoundingClientRect().right)""")
                assert typeset > 20 and raw == 0, (typeset, raw)
                assert all(u.startswith("file://" + str(index.parent)) for u in requests), \
                    [u for u in requests if not u.startswith("file://" + str(index.parent))]
                assert tables and max(tables) <= inner_width(page), (width, tables)
                pres = page.evaluate("""() => [...document.querySelectorAll('pre')].map(
                    e => e.scrollWidth - e.clientWidth)""")
                assert pres and max(pres) <= 1, (width, pres)  # text tables unscrolled
                page.screenshot(path=str(shots / f"report-{width}-full.png"), full_page=True)
                figures = page.evaluate(_FIGURES)
                inner = page.evaluate("() => window.innerWidth")
                scroll = page.evaluate("() => document.documentElement.scrollWidth")
                page.screenshot(path=str(shots / f"report-{width}.png"), full_page=False)
                assert errors == []
                assert {f["src"] for f in figures} == {"fig1.png", "fig2.png"}
                assert scroll <= inner, f"the page scrolls sideways at {width} px"
                for f in figures:
                    assert f["complete"] and f["natural"] > 0, f
                    assert f["left"] >= 0 and f["right"] <= inner, (width, f)
                    assert f["width"] <= f["natural"], f  # never blown up
                    assert f["height"] / f["width"] == pytest.approx(
                        f["naturalHeight"] / f["natural"], rel=0.02)  # not distorted
                    assert f["link"] == f["src"]  # a click opens the PNG
                shown[width] = {f["src"]: f["width"] for f in figures}
                if width == WIDTHS[0]:
                    page.click("figure img[src='fig2.png']")
                    page.wait_for_load_state("load")
                    assert page.url.endswith("/fig2.png")
                page.close()
        finally:
            browser.close()
    # The figures scale with the window: those wider than the narrow window's page are
    # narrower there (fig2), none is wider.
    assert all(shown[WIDTHS[0]][s] <= shown[WIDTHS[1]][s] for s in shown[WIDTHS[0]])
    assert shown[WIDTHS[0]]["fig2.png"] < shown[WIDTHS[1]]["fig2.png"], shown
