"""The last torus's mu_c(h) drawn on the border of chaos (plot.atlas): the line's points
are the curve's, at the cells' coordinates; either orientation; clear errors elsewhere."""

import numpy as np
import pytest
import xarray as xr

from _figures import overlapping_texts
from andoyer.plot.atlas import _cell_coordinate, border_panel, check_critical_mu, plot_border


def _border(dims=("mu", "h_level")) -> xr.Dataset:
    mu = np.geomspace(0.01, 0.16, 5)
    h = np.array([0.5, 1.0, 1.5, 2.0])
    coords = {"mu": mu, "h_level": h}
    shape = tuple(coords[d].size for d in dims)
    f = np.random.default_rng(3).uniform(0.0, 0.4, shape)
    return xr.Dataset({"chaotic_fraction": (dims, f), "chaotic_fraction_low": (dims, 0.8 * f),
                       "chaotic_fraction_high": (dims, 1.2 * f),
                       "layer_width": (dims, 0.5 * f)},
                      coords=coords, attrs={"margin": 1.0, "body_A": 3.0, "M_level": 0.0})


def _curve(h=(0.5, 1.0, 1.5, 2.0), M=0.0) -> xr.Dataset:
    h = np.asarray(h)
    return xr.Dataset({"mu_critical": ("h_level", 0.04 * h),
                       "mu_critical_error": ("h_level", 0.004 * h)},
                      coords={"h_level": h},
                      attrs={"kind": "critical_mu_curve", "M": M, "body_A": 3.0})


def _line(ax):
    (line,) = [ln for ln in ax.get_lines() if "mu_c" in ln.get_label()]
    return line


def test_cell_coordinates_are_the_grid_indices_on_the_grid():
    grid = np.geomspace(0.01, 0.16, 5)
    np.testing.assert_allclose(_cell_coordinate(grid, grid), np.arange(5.0), atol=1e-12)
    # a geometric grid: log-linear between cells, and beyond the ends
    np.testing.assert_allclose(_cell_coordinate(np.array([0.02 * np.sqrt(2), 0.005, 0.32]),
                                                grid), [1.5, -1.0, 5.0], atol=1e-12)
    lin = np.array([0.0, 1.0, 3.0])       # not all > 0: linear
    np.testing.assert_allclose(_cell_coordinate(np.array([2.0, -1.0]), lin), [1.5, -1.0])


@pytest.mark.parametrize("dims", [("mu", "h_level"), ("h_level", "mu")])
def test_the_line_is_the_curve_either_way_round(dims):
    ds, curve = _border(dims), _curve()
    y, x = dims
    fig = plot_border(ds, x=x, y=y, critical_mu=curve)
    panels = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
    assert len(panels) == 2
    for ax in panels:
        line = _line(ax)
        hc, mc = (line.get_xdata(), line.get_ydata()) if x == "h_level" else (
            line.get_ydata(), line.get_xdata())
        # the curve's h are the grid's: the cells' indices; mu_c mapped back is the curve
        np.testing.assert_allclose(hc, np.arange(4.0), atol=1e-12)
        mu_back = np.exp(np.interp(mc, np.arange(5.0), np.log(ds.mu.values)))
        np.testing.assert_allclose(mu_back, curve.mu_critical.values, rtol=1e-12)
        assert len(ax.collections) == 2          # the mesh and the error band
    assert panels[0].get_legend() is not None
    assert "mu_c(h)" in panels[0].get_legend().get_texts()[0].get_text()
    assert overlapping_texts(fig) == []      # the legend sits above the cells' numbers


def test_nan_levels_break_the_line():
    curve = _curve()
    curve["mu_critical"][1] = np.nan
    fig = plot_border(_border(), x="h_level", y="mu", critical_mu=curve)
    assert np.isnan(_line(fig.axes[0]).get_ydata()[1])


def test_the_overlay_needs_h_and_mu_axes():
    ds = _border().rename({"h_level": "epsilon"})
    with pytest.raises(ValueError, match="h_level and mu"):
        plot_border(ds, x="epsilon", y="mu", critical_mu=_curve())
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    with pytest.raises(ValueError, match="h_level and mu"):
        border_panel(ax, ds, x="epsilon", y="mu", critical_mu=_curve())
    plt.close(fig)


def test_another_problem_or_not_a_curve_is_refused():
    with pytest.raises(ValueError, match="M = 0.2"):
        plot_border(_border(), x="h_level", y="mu", critical_mu=_curve(M=0.2))
    other = _curve().assign_attrs(body_A=2.5)
    with pytest.raises(ValueError, match="A = 2.5"):
        plot_border(_border(), x="h_level", y="mu", critical_mu=other)
    with pytest.raises(ValueError, match="mu_critical"):
        check_critical_mu(_curve().drop_vars("mu_critical"))
    with pytest.raises(ValueError, match="increasing"):
        check_critical_mu(_curve(h=(1.0, 0.5, 1.5, 2.0)))
    nan = _curve()
    nan["mu_critical"][:] = np.nan
    with pytest.raises(ValueError, match="NaN on every level"):
        check_critical_mu(nan)
    with pytest.raises(ValueError, match="dataset"):
        check_critical_mu(np.zeros(3))
