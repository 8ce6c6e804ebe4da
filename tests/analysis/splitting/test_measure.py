"""Splitting of the Hess separatrix when the centre of mass is turned off the Hess
direction (issue 16, item 2).

Routes: the manifolds grown and measured by the flow of the turned body
(:func:`separatrix_splitting`) against the first-order Melnikov function of the turned
centre of mass, closed form (:func:`melnikov_off_hess`), itself checked against the
trapezoidal rule of ``{E, H1}`` along the orbits; the error of first order shrinks like
``mu``; the amplitude vanishes at ``epsilon = 0`` and is linear in ``sin epsilon``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.splitting.measure import separatrix_splitting, splitting_vs_epsilon
from andoyer.analysis.splitting.melnikov import melnikov_function

RHO1 = RigidBody.hess(2.5, 1.0, 1.6, name="rho~1")


def test_turned_body_melnikov_closed_form_matches_quadrature() -> None:
    for eps in (0.05, -0.2):
        turned = RigidBody.near_hess(2.5, 1.0, 1.6, epsilon=eps)
        for branch in ("theta1=0", "theta1=4phi0"):
            ds = melnikov_function(turned, n=12, branch=branch)
            assert np.max(np.abs(ds.M - ds.M_quadrature)) < 1e-12 * float(ds.amplitude)
            theta1 = 0.0 if branch == "theta1=0" else 4 * RHO1.phi0
            expect = 2 * float(ds.pi_rho_over_sinh) * abs(math.sin(theta1 / 2 + eps))
            assert float(ds.amplitude) == pytest.approx(expect, rel=1e-14)
            peak = float(np.max(np.abs(ds.M_quadrature)))   # 12 phases: within cos(pi/12)
            assert expect * math.cos(math.pi / 12) - 1e-15 <= peak <= expect * (1 + 1e-12)
    # epsilon = 0 is the Hess body's Melnikov function exactly
    a = melnikov_function(RHO1, n=8, quadrature=False, branch="theta1=4phi0")
    b = melnikov_function(RigidBody.near_hess(2.5, 1.0, 1.6, epsilon=0.0), n=8,
                          quadrature=False, branch="theta1=4phi0")
    assert np.array_equal(a.M.values, b.M.values)


def test_hess_branch_splits_like_melnikov_to_first_order_in_mu() -> None:
    turned = RigidBody.near_hess(2.5, 1.0, 1.6, epsilon=0.1)
    out = separatrix_splitting(turned, [0.005, 0.01], branch="theta1=0", n_phase=16)
    sp = out["splitting"]
    err = sp.relative_error.values
    assert err[1] < 0.01                       # measured 2.6e-3 at mu = 0.01
    assert 1.7 < err[1] / err[0] < 2.3         # the first-order error is O(mu)
    assert float(sp.epsilon) == pytest.approx(0.1, abs=1e-14)
    # the amplitude mu 2 (pi rho / sinh pi rho) sin(epsilon) / (c G), measured to 0.3 %
    assert sp.amplitude.values[1] == pytest.approx(7.362e-4, rel=3e-3)
    it = out["intersections"]                   # the reversor still fixes g = pi/2
    assert np.max(np.abs(it.g.values[:, 0] - math.pi / 2)) < 1e-10


def test_amplitude_vanishes_at_the_hess_direction_and_grows_like_sin_epsilon() -> None:
    ds = splitting_vs_epsilon(RHO1, [0.0, 0.05, 0.1, -0.1], [0.01], n_phase=8)
    amp = ds.amplitude.values[:, 0]
    assert amp[0] < 1e-12                               # Hess: the manifolds coincide
    assert amp[2] / amp[1] == pytest.approx(math.sin(0.1) / math.sin(0.05), rel=5e-3)
    assert amp[3] == pytest.approx(amp[2], rel=5e-3)    # |sin epsilon|
    assert np.all(ds.relative_error.values[1:] < 0.01)
    assert np.isnan(ds.relative_error.values[0, 0])     # no prediction to divide by
    assert ds.amplitude.attrs["long_name"] and float(ds.rho) == pytest.approx(
        RHO1.c / (2 * RHO1.sigma), rel=1e-12)
    with pytest.raises(ValueError, match="epsilon"):
        splitting_vs_epsilon(RHO1, [2.0], [0.01])


@pytest.mark.slow
def test_paper_body_turned_hess_branch_converges_to_melnikov() -> None:
    """rho = 4.56: exponentially small, 7.5e-6 mu; first-order error ~2.2 mu."""
    turned = RigidBody.near_hess(2.5, 2.0, 2.2, epsilon=0.1)
    sp = separatrix_splitting(turned, [0.00125, 0.0025, 0.005], branch="theta1=0",
                              n_phase=16)["splitting"]
    err = sp.relative_error.values
    assert err[0] < 0.005                       # measured 2.7e-3, 5.6e-3, 1.2e-2
    assert 1.8 < err[1] / err[0] < 2.3 and 1.8 < err[2] / err[1] < 2.3
    assert sp.amplitude.values[0] == pytest.approx(9.325e-9, rel=1e-3)


def test_cli_turns_the_centre_of_mass(tmp_path, capsys) -> None:
    import xarray as xr

    from andoyer.cli import main

    out = tmp_path / "mf"
    assert main(["manifolds", "--body", "hess", "--A", "2.5", "--B", "1", "--C", "1.6",
                 "--mu-list", "0.01", "--n-phase", "8", "--delta", "1e-4",
                 "--epsilon", "0.1", "--out", str(out)]) == 0
    with xr.open_dataset(out / "hess_branch.nc") as hb:
        assert float(hb.epsilon) == pytest.approx(0.1, abs=1e-14)
        assert float(hb.relative_error[0]) < 0.01 and float(hb.amplitude[0]) > 1e-4
    assert "former Hess separatrix" in capsys.readouterr().out
