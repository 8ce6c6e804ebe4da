"""The predicted chains drawn in their section plane."""

import numpy as np
import pytest
import xarray as xr

from andoyer import RigidBody
from andoyer.analysis.resonance import resonance_widths
from andoyer.plot.resonance import plot_resonances


def test_plot_resonances_draws_every_chain():
    ds = resonance_widths(RigidBody.hess(3.0, 1.0, 2.0, mu=1e-3), 1.0, 0.0, max_order=4)
    ax = plot_resonances(ds)
    n = ds.sizes["resonance"]
    # centre, two separatrices, stable and unstable points per first-order chain
    assert len(ax.lines) == 5 * n
    x = np.concatenate([ln.get_xdata() for ln in ax.lines])
    x = x[np.isfinite(x)]
    assert x.min() >= 0.0 and x.max() < 2 * np.pi    # the fill plane's l in [0, 2 pi)
    assert ax.get_xlabel() == "$l$"


def test_plot_resonances_refuses_other_datasets():
    with pytest.raises(ValueError, match="resonance_widths"):
        plot_resonances(xr.Dataset({"x": ("a", [1.0])}))


def test_plot_residues_draws_the_resolved_residues():
    """One line per dataset, only the residues above the integration's resolution, and the
    threshold 1/4."""
    from andoyer.analysis.resonance import last_torus
    from andoyer.plot.resonance import plot_residues

    body = RigidBody.hess(3.0, 1.0, 2.0, mu=2e-3)
    ds = last_torus(body, 1.0, head=(2,), axis=2, n_convergents=2, progress=False)
    low = ds.copy()
    low["residue_resolution_elliptic"] = ds.residue_elliptic * 2    # nothing resolved
    ax = plot_residues([ds, low])
    assert len(ax.lines) == 3
    np.testing.assert_allclose(ax.lines[0].get_ydata(), ds.residue_elliptic.values)
    assert len(ax.lines[1].get_xdata()) == 0
    assert ax.lines[2].get_ydata()[0] == 0.25 and ax.get_yscale() == "log"
