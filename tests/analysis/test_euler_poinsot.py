"""Euler-Poinsot closed forms against integration of (1) with mu = 0."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from andoyer import RigidBody, energy, from_andoyer
from andoyer.analysis.euler_poinsot import elliptic_pi, euler_poinsot_frequencies
from andoyer.integrate import poincare, propagate

BODIES = [(2.5, 2.0, 2.2), (1.0, 2.0, 3.0), (3.0, 1.0, 2.0), (2.0, 3.0, 1.2)]
STATES = [[0.3, 0.0, 0.3, 1.0, 0.2], [1.0, 0.5, 0.9, 1.0, 0.1], [0.2, 0.1, -0.1, 1.0, -0.3]]


def _free(A, B, C):
    return RigidBody(A, B, C, 0.0, (1.0, 0.0, 0.0))


@pytest.mark.parametrize("moments", BODIES)
@pytest.mark.parametrize("x0", STATES)
def test_period_and_advance_of_g_against_integration(moments, x0):
    body = _free(*moments)
    y0 = from_andoyer(x0)
    f = euler_poinsot_frequencies(body, float(energy(body, y0)), 1.0)
    # The middle-axis component u = U sn(lambda t, k) crosses 0 upwards once a period.
    q = int(np.argsort([body.a, body.b, body.c])[1])
    ds = poincare(body, y0, f"G{q + 1}=0:+", 4, engine="numba", rtol=1e-13, atol=1e-13)
    T = np.diff(ds.t.values[0])
    np.testing.assert_allclose(T, f.period, rtol=1e-12)
    dg = np.diff(ds.g_angle.values[0])
    err = np.angle(np.exp(1j * (dg - f.g_rate * f.period)))
    assert np.max(np.abs(err)) < 1e-10


@pytest.mark.parametrize("moments", BODIES[:2])
def test_whole_turns_of_g(moments):
    """The advance of g over a period in whole turns too (unwrapped on a fine grid)."""
    body = _free(*moments)
    y0 = from_andoyer(STATES[0])
    f = euler_poinsot_frequencies(body, float(energy(body, y0)), 1.0)
    t = np.linspace(0.0, f.period, 20001)
    ds = propagate(body, y0, t, engine="numba", rtol=1e-13, atol=1e-13).isel(orbit=0)
    advance = np.unwrap(ds.g_angle.values)[-1] - ds.g_angle.values[0]
    assert abs(advance / (2 * math.pi) - f.frequency_ratio) < 1e-9


def test_elliptic_pi_against_quadrature():
    def integrand(p, n, m):
        return 1 / ((1 - n * math.sin(p) ** 2) * math.sqrt(1 - m * math.sin(p) ** 2))

    for n, m in [(0.3, 0.5), (-2.0, 0.9), (0.9, 0.1), (-0.5, 0.0)]:
        ref = quad(integrand, 0, math.pi / 2, args=(n, m), epsabs=1e-13, epsrel=1e-13)[0]
        assert abs(elliptic_pi(n, m) - ref) < 1e-13
    with pytest.raises(ValueError, match="n < 1"):
        elliptic_pi(1.5, 0.2)


def test_bad_levels_and_the_separatrix_are_refused():
    body = _free(2.5, 2.0, 2.2)   # inverse moments p = 0.5 (B), q = 0.4545 (C), r = 0.4
    with pytest.raises(ValueError, match="separatrix"):
        euler_poinsot_frequencies(body, 0.5 * body.c, 1.0)
    with pytest.raises(ValueError, match="accessible range"):
        euler_poinsot_frequencies(body, 0.1, 1.0)
    with pytest.raises(ValueError, match="G must be"):
        euler_poinsot_frequencies(body, 0.21, -1.0)
    with pytest.raises(ValueError, match="distinct"):
        euler_poinsot_frequencies(RigidBody(2.0, 2.0, 1.0, 0.0, (1, 0, 0)), 0.3, 1.0)


@pytest.mark.parametrize("moments", BODIES)
def test_momentum_at_any_time_by_jacobi_functions(moments):
    from andoyer.analysis.euler_poinsot import euler_poinsot_momentum

    body = _free(*moments)
    rng = np.random.default_rng(7)
    t = np.linspace(0.0, 200.0, 401)
    for _ in range(4):   # random states: both regimes, every sign
        g0 = rng.normal(size=3)
        closed = euler_poinsot_momentum(body, g0, t)
        ds = propagate(body, np.r_[g0, 0.0, 0.0, 1.0], t, engine="numba", rtol=1e-13,
                       atol=1e-13).isel(orbit=0)
        numeric = np.stack([ds.G1.values, ds.G2.values, ds.G3.values], axis=-1)
        assert np.max(np.abs(closed - numeric)) < 1e-10
