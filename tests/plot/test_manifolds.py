"""A figure's legend lists only what is drawn: andoyer manifolds --epsilon draws the
profile of the Hess branch theta1 = 0 (it splits off the Hess direction)."""

import numpy as np
import pytest
import xarray as xr

from andoyer.plot.manifolds import plot_splitting_phase, plot_splitting_vs_mu


def _splitting(mu, scale, eps=None):
    g = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    pred = -scale * np.outer(mu, np.cos(g))
    ds = xr.Dataset({"Delta_G": (("mu", "phase"), 0.97 * pred),
                     "Delta_G_melnikov": (("mu", "phase"), pred),
                     "amplitude": ("mu", 0.97 * scale * mu),
                     "amplitude_melnikov": ("mu", scale * mu),
                     "relative_error": ("mu", 3 * mu)}, coords={"mu": mu, "phase": g})
    if eps is not None:
        ds["epsilon"] = ((), eps)
    return ds


def _drawn(ax):
    """Label -> whether its artist has a finite point inside the axes' limits."""
    (x0, x1), (y0, y1) = sorted(ax.get_xlim()), sorted(ax.get_ylim())
    out = {}
    for line in ax.get_lines():
        x, y = (np.asarray(v, dtype=float) for v in line.get_data())
        inside = np.isfinite(x) & np.isfinite(y) & (x >= x0) & (x <= x1) & (y >= y0) & \
            (y <= y1)
        out[line.get_label()] = bool(inside.any())
    return out


@pytest.mark.parametrize("eps", [0.1, 0.0])
def test_every_legend_entry_is_drawn(eps):
    sp = _splitting(np.array([0.005, 0.01]), 7e-5)
    hess = _splitting(np.array([0.01]), 7e-6 if eps else 0.0, eps)
    ax = plot_splitting_phase(sp, hess=hess)
    fig = plot_splitting_vs_mu(sp, hess=hess)
    for a in (ax, *fig.axes):
        drawn = _drawn(a)
        legend = a.get_legend()
        labels = [t.get_text() for t in legend.get_texts()] if legend else []
        assert labels and all(drawn.get(lab, False) for lab in labels), (labels, drawn)
    # the turned Hess branch's profile is on the phase panel, named with its epsilon
    names = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any("theta_1 = 0" in n and "0.1" in n for n in names) == (eps != 0.0)
