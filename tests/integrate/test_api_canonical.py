"""integrate_canonical at its boundary: the point in its chart's domain, finite, off the
singular set; the margin and the cost checked before scipy sees anything."""

from __future__ import annotations

import math

import pytest

from andoyer import RigidBody
from andoyer.errors import CostLimitError
from andoyer.integrate import integrate_canonical

B = RigidBody.paper()
X0 = [0.0, 4.7, 0.03, 0.1, 0.0]


@pytest.mark.parametrize("i", range(5))
def test_nan_in_the_state_is_refused_naming_x0(i):
    """Before: scipy's 'All components of the initial state `y0` must be finite.'"""
    x = list(X0)
    x[i] = math.nan
    with pytest.raises(ValueError, match=r"^x0 must be finite"):
        integrate_canonical(B, x, [0.0, 1.0])


def test_a_point_on_the_singular_set_is_refused_naming_x0():
    with pytest.raises(ValueError, match=r"^x0 lies within singular_margin"):
        integrate_canonical(B, [0.0, 4.7, 0.0, 0.1, 0.0], [0.0, 1.0])
    with pytest.raises(ValueError, match=r"^x0"):
        integrate_canonical(B, [0.0, 4.7, 0.2, 0.1, 0.0], [0.0, 1.0])  # J1 > J2


@pytest.mark.parametrize("margin", [0.0, -1.0, 1.0, math.nan, True, "x"])
def test_the_singular_margin_is_checked(margin):
    with pytest.raises(ValueError, match="singular_margin"):
        integrate_canonical(B, X0, [0.0, 1.0], singular_margin=margin)


def test_the_cost_is_guarded():
    with pytest.raises(CostLimitError):
        integrate_canonical(B, X0, [0.0, 1e12])


def test_a_regular_point_integrates():
    ds = integrate_canonical(B, X0, [0.0, 1.0, 2.0])
    assert ds.sizes["time"] == 3
