"""Test helpers for figures: the texts a figure draws, overlapping labels, colour bars
without a label (tests/plot/test_layout.py, tests/report)."""

from __future__ import annotations

import itertools

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.text import Text


def drawn_texts(fig: Figure) -> list[tuple[Text, object]]:
    """The texts drawn on ``fig`` (those asked to draw themselves: tick labels out of
    view are not), each with its box in pixels."""
    from unittest import mock

    FigureCanvasAgg(fig)
    renderer = fig.canvas.get_renderer()
    drawn: list[Text] = []
    draw = Text.draw

    def record(self: Text, r: object) -> None:
        if self.get_visible() and self.get_text().strip():
            drawn.append(self)
        draw(self, r)

    with mock.patch.object(Text, "draw", record):
        fig.canvas.draw()
    out, seen = [], set()
    for t in drawn:
        if id(t) not in seen:
            seen.add(id(t))
            out.append((t, t.get_window_extent(renderer)))
    return out


def overlapping_texts(fig: Figure, slack: float = 0.5) -> list[tuple[str, str]]:
    """Pairs of texts of ``fig`` whose boxes overlap by more than ``slack`` pixels."""
    texts = drawn_texts(fig)
    pairs = []
    for (a, ba), (b, bb) in itertools.combinations(texts, 2):
        if (min(ba.x1, bb.x1) - max(ba.x0, bb.x0) > slack
                and min(ba.y1, bb.y1) - max(ba.y0, bb.y0) > slack):
            pairs.append((a.get_text(), b.get_text()))
    return pairs


def unlabelled_colour_bars(fig: Figure) -> list[object]:
    """Colour-bar axes of ``fig`` without a label."""
    return [ax for ax in fig.axes if ax.get_label() == "<colorbar>"
            and not (ax.get_ylabel().strip() or ax.get_xlabel().strip())]
