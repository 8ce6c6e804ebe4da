"""Euler-Poinsot closed forms against integration of (1) with mu = 0."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from andoyer import RigidBody, energy, from_andoyer
from andoyer.analysis.unperturbed.euler_poinsot import elliptic_pi, euler_poinsot_frequencies
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
    from andoyer.analysis.unperturbed.euler_poinsot import euler_poinsot_momentum

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


def test_permanent_rotations_about_the_stable_axes_are_the_limits():
    """``2h = r G^2`` and ``2h = p G^2`` are the stable rotations (major and minor axes):
    the period of the small oscillations, ``k^2 = 0``, and the rate of g there
    (was inf/NaN); the limit from inside the range agrees."""
    body = _free(2.5, 2.0, 2.2)   # p = b (axis 2), q = c (axis 3), r = a (axis 1)
    p, q, r = body.b, body.c, body.a
    for G in (1.0, 3.0):
        for x, lam, rate in ((r, math.sqrt((q - r) * (p - r)), r),
                             (p, math.sqrt((p - q) * (p - r)), p)):
            f = euler_poinsot_frequencies(body, 0.5 * x * G * G, G)
            assert f.modulus < 1e-14
            assert abs(f.period - 2.0 * math.pi / (lam * G)) < 1e-13 * f.period
            assert abs(f.g_rate - rate * G) < 1e-14 * G
            near = euler_poinsot_frequencies(body, 0.5 * x * (1.0 + (1e-9 if x == r else -1e-9))
                                             * G * G, G)
            assert abs(near.period / f.period - 1.0) < 1e-8
            assert abs(near.g_rate / f.g_rate - 1.0) < 1e-8


# (1e149: the level of G = 1e150 reaches |G| = 1.02e150, beyond the MAX_ACTION that every
# closed form takes, as an action or reached by a level: validation.momentum_limit.)
@pytest.mark.parametrize("s", [1e-150, 1e-30, 1e30, 1e149])
def test_huge_and_tiny_scales_stay_finite_and_homogeneous(s):
    from andoyer.analysis.unperturbed.euler_poinsot import euler_poinsot_momentum

    body = _free(2.5, 2.0, 2.2)
    f1 = euler_poinsot_frequencies(body, 0.21, 1.0)
    f = euler_poinsot_frequencies(body, 0.21 * s * s, s)
    assert all(math.isfinite(v) for v in f[:4])
    assert abs(f.period * s / f1.period - 1.0) < 1e-12
    assert abs(f.g_rate / (s * f1.g_rate) - 1.0) < 1e-12
    g0, t = np.array([0.3, 0.8, 0.5]), np.array([0.0, 3.0, 10.0])
    G = euler_poinsot_momentum(body, s * g0, t / s)
    assert np.all(np.isfinite(G))
    assert np.allclose(G / s, euler_poinsot_momentum(body, g0, t), rtol=0, atol=1e-12)


def test_momentum_on_the_permanent_rotations_and_bad_times():
    from andoyer.analysis.unperturbed.euler_poinsot import euler_poinsot_momentum

    body = _free(2.5, 2.0, 2.2)
    t = np.linspace(0.0, 50.0, 6)
    for g0 in ([2.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.5], [0.0, 0.0, 0.0]):
        assert np.array_equal(euler_poinsot_momentum(body, g0, t), np.tile(g0, (6, 1)))
    G = euler_poinsot_momentum(body, [1.0, 1e-20, 0.0], t)   # next to the major axis
    assert np.all(np.isfinite(G)) and np.allclose(G[:, 0], 1.0, rtol=0, atol=1e-15)
    assert np.max(np.abs(G[:, 1:])) < 2e-20
    for bad, what in (([0.0, np.nan], "t must be"), ([[0.0, 1.0]], "t must be"),
                      ([0.0, 1e300], "periods")):
        with pytest.raises(ValueError, match=what):
            euler_poinsot_momentum(body, [0.3, 0.8, 0.5], bad)


def test_momentum_starts_where_scipy_ellipkinc_is_wrong():
    """SciPy 1.17.1's ellipkinc(1.0895147838119381, 0.08843945589556104) is 20 % off; the
    motion from this state (amplitude 1.0895..., k^2 = 0.0884...) started 0.05 away from
    it before theta0 came from Carlson's form (elliptic_f)."""
    from andoyer.analysis.unperturbed.euler_poinsot import euler_poinsot_momentum

    body = _free(2.5, 2.0, 2.2)
    g0 = np.array([0.12128099822752322, 0.9309356785325529, 0.34445563125614825])
    G = euler_poinsot_momentum(body, g0, [0.0, 1.0])
    np.testing.assert_allclose(G[0], g0, rtol=0, atol=1e-12)
