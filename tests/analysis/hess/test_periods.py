"""Periods of the Hess solution: the closed form (complete elliptic integrals) against the
period measured on integrated Euler-Poisson orbits, on a libration and a rotation level."""

from __future__ import annotations

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.hess.periods import hess_periods

PAPER = RigidBody.paper()


@pytest.fixture(scope="module")
def periods():
    return hess_periods(PAPER, (0.0, 0.2), 25, 2, engine="numba")


def test_the_closed_form_is_the_integrated_period(periods):
    ratio = periods.T_integrated / periods.T_elliptic_check
    assert ratio.shape == (2, 2) and bool(np.isfinite(ratio).all())
    np.testing.assert_allclose(ratio.values, 1.0, rtol=1e-9)
    # one libration (h < mu) and one rotation (h > mu) level per M
    assert bool((periods.h_check.min("check") < PAPER.mu).all())
    assert bool((periods.h_check.max("check") > PAPER.mu).all())


def test_the_period_grows_toward_the_separatrix(periods):
    T = periods.T_elliptic.sel(M=0.0).values
    h = periods.h.values
    ok = np.isfinite(T)
    assert ok.sum() == h.size  # every level of M = 0 above its bottom h = -mu
    below = h < PAPER.mu
    # approaching h = mu from either side, the period grows (the separatrix's log)
    lib, rot = T[below], T[~below]
    assert lib[-1] > lib[0] and rot[0] > rot[-1]


def test_a_body_off_the_hess_case_is_refused():
    with pytest.raises(ValueError, match="hess_periods"):
        hess_periods(RigidBody(2.5, 2.0, 2.2, 0.01, (1.0, 0.0, 0.0)), (0.0,), 5, 1)
