"""Every figure of the report reads like a paper's: no legend or note over the data (the
boxes of legends and of texts placed in axes coordinates against the pixels the data
occupy), tick labels on every labelled axis, labels and legends in words and symbols
(never a code string such as ``theta1=4phi0`` or ``mu = 1e-3``); and its tables print
no ``-0``."""

from __future__ import annotations

import re

import pytest
from matplotlib.figure import Figure

from _figures import axes_without_tick_labels, code_strings, covering_boxes
from andoyer.report import base
from andoyer.report.paper import build_paper

pytestmark = [pytest.mark.slow, pytest.mark.timeout(1200)]


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """The quick report built in this process, each figure kept as it is written."""
    figures: dict[str, Figure] = {}
    original = base.Context.figure

    def keep(self, fig, name):
        figures[name] = fig
        return original(self, fig, name)

    mp = pytest.MonkeyPatch()
    mp.setattr(base.Context, "figure", keep)
    try:
        out = tmp_path_factory.mktemp("paper") / "p"
        index, done = build_paper(out, quick=True, progress=False, jobs=1)
    finally:
        mp.undo()
    return figures, done, index


def test_every_item_has_its_figures(report):
    figures, done, _ = report
    assert len(figures) >= 9, sorted(figures)


def test_no_legend_or_note_over_the_data(report):
    figures, _, _ = report
    bad = {name: found for name, fig in figures.items() if (found := covering_boxes(fig))}
    assert not bad, bad


def test_tick_labels_on_every_labelled_axis(report):
    figures, _, _ = report
    bad = {name: found for name, fig in figures.items()
           if (found := axes_without_tick_labels(fig))}
    assert not bad, bad


def test_labels_in_words_and_symbols(report):
    figures, _, _ = report
    bad = {name: found for name, fig in figures.items() if (found := code_strings(fig))}
    assert not bad, bad


def test_tables_print_no_negative_zero(report):
    _, _, index = report
    cells = re.findall(r"<td>([^<]*)</td>", index.read_text())
    assert cells
    bad = [c for c in cells if re.fullmatch(r"[-−]0(\.0*)?([eE][-+]?0+)?", c.strip())]
    assert not bad, bad
    pre = " ".join(re.findall(r"<pre>(.*?)</pre>", index.read_text(), re.S))
    assert pre and not re.findall(r"(?<![\w.])[-−]0(\.0+)?([eE][-+]?0+)?(?![\w.])", pre)


def test_formulas_are_tex_rendered_by_a_local_mathjax(report):
    """The prose writes formulas in TeX for the MathJax copied beside the page (no
    network); no ASCII formula (``sqrt(``, ``^2``, ``theta1``) is left in it."""
    _, _, index = report
    page = index.read_text()
    assert '<script defer src="mathjax-tex-svg.js"></script>' in page
    assert (index.parent / "mathjax-tex-svg.js").stat().st_size > 1_000_000
    assert "http://" not in page and "https://cdn" not in page
    prose = re.sub(r"<pre>.*?</pre>|<table>.*?</table>|\\\(.*?\\\)", "", page, flags=re.S)
    ascii_math = re.findall(r"sqrt\(|\w\^\d|\btheta\d\b|\bphi0\b|\bmu = ", prose)
    assert not ascii_math, ascii_math
