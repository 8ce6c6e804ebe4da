"""Test helpers for figures: the texts a figure draws, overlapping labels, colour bars
without a label (tests/plot/test_layout.py, tests/report)."""

from __future__ import annotations

import itertools
import re
from typing import Any

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


def _data_points(ax: Any) -> Any:
    """Display coordinates of what ``ax`` plots in data coordinates (line vertices,
    densified; scatter points; contour and other collection paths; image corners),
    clipped to the axes: the pixels a legend or a note must leave free."""
    import numpy as np
    from matplotlib.collections import Collection
    from matplotlib.image import AxesImage
    from matplotlib.lines import Line2D

    pts = []
    for artist in ax.get_children():
        if not artist.get_visible():
            continue
        if isinstance(artist, Line2D):
            if artist.get_transform() != ax.transData:
                continue  # axhline / axvline: a reference line across the axes
            xy = artist.get_transform().transform(artist.get_xydata())
            xy = xy[np.all(np.isfinite(xy), axis=1)]
            if artist.get_linestyle() not in ("None", "", " ") and len(xy) > 1:
                # points every pixel or so along the segments
                seg = np.diff(xy, axis=0)
                n = np.clip(np.hypot(*seg.T).astype(int), 1, 200)
                xy = np.concatenate([xy[i] + np.outer(np.linspace(0, 1, k, endpoint=False),
                                                      seg[i]) for i, k in enumerate(n)]
                                    + [xy[-1:]])
            pts.append(xy)
        elif isinstance(artist, Collection):
            offsets = artist.get_offsets()
            if len(offsets) and artist.get_offset_transform() == ax.transData:
                pts.append(ax.transData.transform(offsets))
            if artist.get_transform() == ax.transData:
                for path in artist.get_paths():
                    v = path.interpolated(4).vertices if len(path.vertices) < 400 \
                        else path.vertices
                    if len(v):
                        pts.append(ax.transData.transform(v))
        elif isinstance(artist, AxesImage):
            e = artist.get_window_extent()
            gx, gy = np.meshgrid(np.linspace(e.x0, e.x1, 40), np.linspace(e.y0, e.y1, 40))
            pts.append(np.stack([gx.ravel(), gy.ravel()], -1))
    if not pts:
        return np.zeros((0, 2))
    xy = np.concatenate(pts)
    box = ax.get_window_extent()
    keep = (xy[:, 0] >= box.x0) & (xy[:, 0] <= box.x1) & (xy[:, 1] >= box.y0) & \
        (xy[:, 1] <= box.y1) & np.all(np.isfinite(xy), axis=1)
    return xy[keep]


def covering_boxes(fig: Figure, margin: float = 1.0) -> list[str]:
    """Legends and notes (texts placed in axes coordinates) of ``fig`` that lie over
    plotted data: each named with how many data pixels it covers. 3D axes are left out
    (their projection moves with the view)."""
    from matplotlib.text import Annotation

    FigureCanvasAgg(fig)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    out = []
    for ax in fig.axes:
        if ax.get_label() == "<colorbar>" or ax.name == "3d":
            continue
        xy = _data_points(ax)
        if not len(xy):
            continue
        boxes = []
        legend = ax.get_legend()
        if legend is not None and legend.get_visible():
            boxes.append((f"legend of {ax.get_title() or 'an axes'}",
                          legend.get_window_extent(renderer)))
        for legend in fig.legends:
            boxes.append(("figure legend", legend.get_window_extent(renderer)))
        for t in ax.texts:
            if isinstance(t, Annotation) or not t.get_visible() or not t.get_text().strip():
                continue  # an annotation labels the point it points at
            if t.get_transform() == ax.transData:
                continue  # a label written at a data point
            boxes.append((f"note {t.get_text()!r}", t.get_window_extent(renderer)))
        for name, b in boxes:
            inside = ((xy[:, 0] > b.x0 + margin) & (xy[:, 0] < b.x1 - margin)
                      & (xy[:, 1] > b.y0 + margin) & (xy[:, 1] < b.y1 - margin))
            if inside.sum():
                out.append(f"{name} over {int(inside.sum())} data pixels")
    return out


def axes_without_tick_labels(fig: Figure) -> list[str]:
    """2D axes of ``fig`` with an axis label but no tick label drawn on that axis."""
    drawn = {id(t) for t, _ in drawn_texts(fig)}
    out = []
    for ax in fig.axes:
        if ax.get_label() == "<colorbar>" or ax.name == "3d" or not ax.axison:
            continue
        for name, axis, label in (("x", ax.xaxis, ax.get_xlabel()),
                                  ("y", ax.yaxis, ax.get_ylabel())):
            if not label.strip():
                continue
            ticks = [t for t in axis.get_ticklabels(which="both") if id(t) in drawn]
            if not ticks:
                out.append(f"{ax.get_title() or 'axes'}: {name} axis {label!r} without ticks")
    return out


#: Code where a reader expects words and symbols: ``name=value`` without spaces,
#: ``mu``/``phi0``/``theta1`` spelt in ASCII, a call ``hess(``, ``sqrt(``, ``1e-3``.
_CODE = re.compile(r"[A-Za-z]\w*=\S|\bmu\b|\bphi0\b|\btheta\d\b|\bhess\(|sqrt\(|"
                   r"\b\d+(\.\d+)?e-?\d+\b|\w_\w")


def code_strings(fig: Figure) -> list[str]:
    """Texts of ``fig`` (titles, labels, legends, notes) that print code: checked
    outside ``$...$`` (mathtext is how a symbol is written)."""
    out = []
    for t, _ in drawn_texts(fig):
        text = t.get_text()
        plain = re.sub(r"\$[^$]*\$", "", text)
        if _CODE.search(plain):
            out.append(text)
    return out
