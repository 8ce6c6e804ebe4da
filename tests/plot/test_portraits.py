"""Figures 1 and 2 (andoyer.plot.portraits): non-empty images whose data match the analysis."""

from __future__ import annotations

import matplotlib.image as mpimg
import numpy as np
import pytest
import xarray as xr
from matplotlib.collections import PathCollection
from matplotlib.figure import Figure

from andoyer import RigidBody
from andoyer.analysis.unperturbed.fixed_points import andoyer_fixed_points, hess_fixed_points
from andoyer.analysis.unperturbed.portraits import portrait_andoyer, portrait_hess
from andoyer.dynamics import hamiltonian
from andoyer.plot.portraits import plot_fig1, plot_fig2


@pytest.fixture(scope="module")
def portraits() -> tuple[xr.Dataset, xr.Dataset]:
    body = RigidBody.paper()
    return (portrait_andoyer(body, 1.0, n=(97, 49), n_curve=101),
            portrait_hess(body, 1.0, n=(97, 25), n_curve=101))


def _render(fig: Figure, path) -> np.ndarray:
    fig.savefig(path, dpi=80)
    assert path.stat().st_size > 5000
    img = mpimg.imread(path)
    assert img.shape[0] > 100 and img.shape[1] > 100
    assert np.ptp(img[..., :3]) > 0.5          # not a blank image
    return img


def _lines(ax, *gids: str) -> list[np.ndarray]:
    return [np.column_stack(ln.get_data()) for ln in ax.get_lines() if ln.get_gid() in gids]


def _points(ax, gid: str) -> np.ndarray:
    offs = [c.get_offsets() for c in ax.collections
            if isinstance(c, PathCollection) and c.get_gid() == gid]
    return np.concatenate(offs) if offs else np.empty((0, 2))


def _check_panel(ax, ds: xr.Dataset, chart: str) -> None:
    body = RigidBody.paper().with_mu(0.0)
    x, y = ds.attrs["plane_x"], ds.attrs["plane_y"]
    fps = (andoyer_fixed_points if chart == "andoyer" else hess_fixed_points)(body, 1.0)
    # The drawn fixed points are the analysis' points (plus copies at the right edge).
    drawn = np.concatenate([_points(ax, "fixed-point-saddle"), _points(ax, "fixed-point-centre")])
    period = ds.attrs["angle_period"]
    for fp in fps.points:
        assert np.min(np.hypot(drawn[:, 0] - fp.q, drawn[:, 1] - fp.p)) < 1e-12
        if fp.q == 0.0:  # the right edge is the same line
            assert np.min(np.hypot(drawn[:, 0] - period, drawn[:, 1] - fp.p)) < 1e-12
    # Every saddle lies on a drawn separatrix curve, and H0 there is the saddle's energy.
    curves = _lines(ax, "separatrix", "separatrix-hess")
    assert curves
    pts = np.concatenate(curves)
    for fp in fps.by_type("saddle"):
        assert np.min(np.hypot(pts[:, 0] - fp.q, pts[:, 1] - fp.p)) < 1e-12
    zeros = np.zeros(len(pts))
    xs = np.column_stack([pts[:, 0], zeros, pts[:, 1], np.ones(len(pts)), zeros])
    H = hamiltonian(body, xs, chart)
    assert np.max(np.abs(H - fps.by_type("saddle")[0].H0)) < 1e-14
    # Contour levels: those drawn are the dataset's; the dataset's include the saddles' H0.
    cs = [c for c in ax.collections if c.get_gid() == "contour"]
    assert len(cs) == 1
    assert np.all(np.isin(cs[0].levels, ds.levels.values))
    for fp in fps.by_type("saddle"):
        assert np.min(np.abs(ds.levels.values - fp.H0)) < 1e-14
    assert ax.get_xlabel() == ds.attrs["x_label"] and ax.get_ylabel() == ds.attrs["y_label"]
    singular = [ln for ln in ax.get_lines() if ln.get_gid() == "singular"]
    assert sorted(ln.get_ydata()[0] for ln in singular) == sorted(ds[f"singular_{y}"].values)
    assert x in ds.coords


def test_fig1(portraits, tmp_path) -> None:
    ds, _ = portraits
    fig = plot_fig1(ds)
    _render(fig, tmp_path / "fig1.png")
    _check_panel(fig.axes[0], ds, "andoyer")


def test_fig2(portraits, tmp_path) -> None:
    ds_a, ds_h = portraits
    fig = plot_fig2(ds_a, ds_h)
    _render(fig, tmp_path / "fig2.png")
    ax_a, ax_b = fig.axes
    _check_panel(ax_a, ds_a, "andoyer")
    _check_panel(ax_b, ds_h, "hess")
    phi0 = RigidBody.paper().phi0
    # Bold dotted: the Hess separatrix theta1 = 0 (l = -phi0 mod pi) and only it.
    for ax, to_theta in ((ax_a, lambda q: 2 * (q + phi0)), (ax_b, lambda q: q)):
        hess = _lines(ax, "separatrix-hess")
        assert len(hess) == 2
        for c in hess:
            assert np.allclose(np.sin(to_theta(c[:, 0]) / 2), 0.0, atol=1e-14)
    labels = sorted(t.get_text() for t in ax_b.texts if t.get_gid() == "label")
    assert labels == ["1", "2", "3", "4"]
    assert sorted(t.get_text() for t in ax_a.texts if t.get_gid() == "label") == [
        "1", "2", "3", "3", "4", "4"]


def test_plot_rejects_other_datasets(portraits) -> None:
    ds, _ = portraits
    with pytest.raises(ValueError, match="portrait"):
        plot_fig1(ds.drop_vars("levels"))
    with pytest.raises(ValueError, match="plane_x"):
        plot_fig2(xr.Dataset(), ds)
