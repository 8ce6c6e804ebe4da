"""Readable figures: every colour bar labelled, no two labels overlapping, cell
annotations inside their cells, one colour scale per quantity (issue 29, item 4)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from matplotlib.figure import Figure

from _figures import drawn_texts, overlapping_texts, unlabelled_colour_bars
from andoyer.plot.atlas import plot_border
from andoyer.plot.border import plot_border_of_chaos
from andoyer.plot.style import SCALES


def _border(nmu: int, neps: int) -> xr.Dataset:
    rng = np.random.default_rng(1)
    f = rng.uniform(0.0, 0.4, (nmu, neps))
    mu = np.geomspace(0.01, 0.1, nmu)
    eps = np.linspace(0.0, 0.4, neps)
    return xr.Dataset({"chaotic_fraction": (("mu", "epsilon"), f),
                       "chaotic_fraction_low": (("mu", "epsilon"), f * 0.8),
                       "chaotic_fraction_high": (("mu", "epsilon"), f * 1.2),
                       "layer_width": (("mu", "epsilon"), f * 0.5)},
                      coords={"mu": mu, "epsilon": eps}, attrs={"margin": 1.0})


def _splitting() -> xr.Dataset:
    eps = np.array([0.0, 0.1, 0.2, 0.4])
    amp = 7e-3 * eps[:, None]
    return xr.Dataset({"amplitude": (("epsilon", "mu"), amp),
                       "amplitude_melnikov": (("epsilon", "mu"), amp * 1.01)},
                      coords={"epsilon": eps, "mu": [0.01], "rho": 1.08})


def _frequency_map() -> xr.Dataset:
    th, J = np.meshgrid(np.linspace(0.3, 6.0, 8), np.linspace(0.1, 0.9, 5))
    drift = -6.0 + 6.0 * np.abs(np.sin(th))
    return xr.Dataset({"theta1": ("seed", th.ravel()), "J1": ("seed", J.ravel()),
                       "log10_drift": ("seed", drift.ravel())},
                      attrs={"plane_x": "theta1", "plane_y": "J1", "body_mu": 0.04})


def test_border_of_chaos_figure_is_readable():
    """The report's border figure: (b)'s colour bar is labelled, no label overlaps
    another (the three panels at 34 % of a page, with (c)'s axis label beside (b)'s bar,
    were the example)."""
    fig = plot_border_of_chaos(_splitting(), _border(3, 3), _frequency_map())
    assert unlabelled_colour_bars(fig) == []
    labels = {ax.get_ylabel() for ax in fig.axes if ax.get_label() == "<colorbar>"}
    assert labels == {SCALES["chaotic_fraction"].label, SCALES["log10_drift"].label}
    assert overlapping_texts(fig) == []


@pytest.mark.parametrize(("nmu", "neps"), [(3, 3), (3, 5), (10, 5), (4, 10), (12, 12)])
def test_border_cells_annotations_do_not_overlap(nmu, neps):
    """``plot_border`` (andoyer atlas): the values and bracketed ranges in the cells fit
    (the font follows the cell; no annotation where even the value would not fit)."""
    fig = plot_border(_border(nmu, neps))
    assert unlabelled_colour_bars(fig) == []
    assert overlapping_texts(fig) == []
    # Each annotation lies inside its own cell.
    texts = drawn_texts(fig)
    ax = fig.axes[0]
    cells = [(t, box) for t, box in texts if t in ax.texts]
    assert cells or nmu * neps > 100  # small grids are annotated
    for t, box in cells:
        x, y = t.get_position()
        lo = ax.transData.transform((x - 0.5, y - 0.5))
        hi = ax.transData.transform((x + 0.5, y + 0.5))
        assert lo[0] <= box.x0 and box.x1 <= hi[0] and lo[1] <= box.y0 and box.y1 <= hi[1]


def test_overlap_check_catches_overlap():
    """The check itself: two labels drawn on the same spot are found."""
    fig = Figure()
    ax = fig.add_subplot()
    ax.text(0.5, 0.5, "one label")
    ax.text(0.5, 0.5, "another")
    assert ("one label", "another") in overlapping_texts(fig)
    bar = fig.colorbar(ax.pcolormesh([[0.0, 1.0]]), ax=ax)
    assert unlabelled_colour_bars(fig) == [bar.ax]


def test_one_colour_convention_per_quantity():
    """No figure, tutorial or explorer code picks a colour map of its own: colour maps
    come from plot.style.SCALES (the frequency drift ran opposite ways in the tutorial
    and the report)."""
    root = Path(__file__).resolve().parents[2]
    sources = [*(root / "src" / "andoyer").rglob("*.py"), *(root / "docs").rglob("*.md")]
    offenders = []
    for path in sources:
        if path.name == "style.py" or "_build" in path.parts:
            continue
        text = path.read_text(encoding="utf-8")
        for name in ("magma", "viridis", "turbo", "inferno", "plasma", "cividis"):
            if f'"{name}' in text or f"'{name}" in text:
                offenders.append((path.name, name))
    assert offenders == []
