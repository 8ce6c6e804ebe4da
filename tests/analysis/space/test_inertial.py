"""The body in space (issue 27, item 3): axis traces, precession and nutation of orbits,
the herpolhode, the Hess heteroclinic cycle. Measured (numba, rtol = atol = 1e-12):
the colatitude of z equals theta to round-off; the Lagrange top's sampled rate over 20
nutation periods agrees with the closed form to 5e-14; the free top's plane distance
2T/|L| is constant to 2e-15 and the symmetric top's herpolhode is a circle to 7e-15;
the cycle's branches end at |L/G| = 0.99998771 (t_half = 12/lambda), (R G)_Z = M = 0 to
3e-13 (mu = 0.1), the Hess relation sin(theta1/2) = 0 to 2e-11."""

from __future__ import annotations

import math

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.space.inertial import (
    axis_trace,
    herpolhode,
    heteroclinic_cycle,
    precession_nutation,
)
from andoyer.analysis.space.lagrange import lagrange_top
from andoyer.integrate import attitude

ENGINE = "numba"
LAGRANGE = RigidBody.lagrange(1.0, 0.6, 1.0)
Y_LAGRANGE = [0.2, 0.1, 1.5, 0.0, math.sin(0.8), math.cos(0.8)]


@pytest.fixture(scope="module")
def lagrange_run():
    top = lagrange_top(LAGRANGE, Y_LAGRANGE)
    T = float(top.nutation_period)
    t = np.linspace(0.0, 20 * T, 8001)
    return top, attitude(LAGRANGE, Y_LAGRANGE, t, engine=ENGINE)


def test_axis_traces_are_the_rotated_body_axes(lagrange_run):
    _, ds = lagrange_run
    z = axis_trace(ds, "z")
    assert np.abs(z.colatitude - ds.nutation).max() <= 1e-12
    wrapped = np.angle(np.exp(1j * (z.azimuth - ds.precession + math.pi / 2)))
    assert np.abs(wrapped).max() <= 1e-12
    R = ds.rotation.values
    assert np.abs(z.trace.values - R[..., :, 2]).max() == 0.0
    com = axis_trace(ds, "centre_of_mass")  # r = e_z for the Lagrange top
    assert np.abs(com.trace.values - z.trace.values).max() <= 1e-15
    assert np.allclose(np.linalg.norm(axis_trace(ds, "angular_velocity").trace, axis=-1), 1.0)
    with pytest.raises(ValueError, match="axis"):
        axis_trace(ds, "w")


def test_precession_and_nutation_of_an_orbit_match_the_lagrange_closed_form(lagrange_run):
    top, ds = lagrange_run
    pn = precession_nutation(ds)
    assert abs(float(pn.precession_rate[0]) / float(top.precession_rate) - 1.0) <= 1e-11
    assert abs(float(pn.nutation_min[0]) - float(top.nutation_min)) <= 1e-4
    assert abs(float(pn.nutation_max[0]) - float(top.nutation_max)) <= 1e-4
    assert not pn.passes_pole[0] and not pn.undersampled[0]
    # Too sparse to unwrap psi: flagged, no rate.
    sparse = precession_nutation(ds.isel(time=slice(None, None, 400)))
    assert bool(sparse.undersampled[0]) and np.isnan(sparse.precession_rate[0])


def test_an_orbit_through_the_pole_has_no_precession_rate():
    # The symmetry axis vertical at t = 0: theta = 0, psi undefined there.
    ds = attitude(LAGRANGE, [0.3, 0.0, 1.5, 0.0, 0.0, 1.0], np.linspace(0, 5, 51),
                  engine=ENGINE)
    assert bool(ds.euler_singular[0, 0]) and np.isnan(ds.precession[0, 0])
    pn = precession_nutation(ds)
    assert bool(pn.passes_pole[0]) and np.isnan(pn.precession_rate[0])


def test_herpolhode_lies_on_the_invariable_plane():
    free = RigidBody.euler_poinsot(2.5, 2.0, 2.2)
    ds = attitude(free, [0.3, 0.8, 0.5, 0.0, 0.6, 0.8], np.linspace(0, 50, 501),
                  engine=ENGINE)
    hp = herpolhode(ds)
    G = np.array([0.3, 0.8, 0.5])
    two_T = free.a * G[0] ** 2 + free.b * G[1] ** 2 + free.c * G[2] ** 2
    assert np.abs(hp.plane_distance.values - two_T / np.linalg.norm(G)).max() <= 1e-12
    # The symmetric free top: the herpolhode is a circle.
    sym = RigidBody.euler_poinsot(2.0, 2.0, 1.2)
    hs = herpolhode(attitude(sym, [0.3, 0.8, 0.5, 0.0, 0.6, 0.8], np.linspace(0, 50, 501),
                             engine=ENGINE))
    assert np.ptp(np.linalg.norm(hs.herpolhode.values, axis=-1)) <= 1e-12
    with pytest.raises(ValueError, match="mu = 0"):
        herpolhode(attitude(LAGRANGE, Y_LAGRANGE, [0.0, 1.0], engine=ENGINE))


@pytest.mark.parametrize("mu", [0.0, 0.1])
def test_heteroclinic_cycle_joins_the_two_pendulum_like_rotations(mu):
    cyc = heteroclinic_cycle(RigidBody.paper(mu=mu), engine=ENGINE, n_times=801)
    LG = cyc.L_over_G.sel(branch="theta1=0").values
    # The Hess branch theta1 = 0 is heteroclinic for every mu: P+ -> P-.
    assert LG[0] > 1 - 1e-4 and LG[-1] < -1 + 1e-4
    assert np.nanmax(np.abs(np.sin(cyc.theta1.sel(branch="theta1=0").values / 2))) <= 1e-9
    if mu == 0.0:  # ... and the other one takes P- back to P+ (it splits for mu > 0)
        back = cyc.L_over_G.sel(branch="theta1=4phi0").values
        assert back[0] < -1 + 1e-4 and back[-1] > 1 - 1e-4
    # M = 0: the angular momentum stays horizontal in space.
    assert np.abs(cyc.space_momentum.values[..., 2]).max() <= 1e-11


def test_off_the_hess_direction_the_cycle_starts_on_the_nearest_hess_separatrices():
    """A body turned by epsilon = 0.05 off the Hess direction: its orbits start on the free
    top's separatrices (those of the nearest Hess body) and come close to both pendulum-like
    rotations (measured: |L/G| = 0.999988 at the ends of theta1 = 0, 0.979 on the other)."""
    body = RigidBody.near_hess(2.5, 2.0, 2.2, mu=0.01, epsilon=0.05)
    cyc = heteroclinic_cycle(body, engine=ENGINE, n_times=801)
    assert abs(cyc.attrs["hess_epsilon"] - 0.05) <= 1e-12
    LG = cyc.L_over_G.values
    assert LG[0, 0] > 1 - 1e-3 and LG[0, -1] < -1 + 1e-3
    assert LG[1].min() < -0.9 and LG[1].max() > 0.9
    assert np.abs(cyc.space_momentum.values[..., 2]).max() <= 1e-11
    with pytest.raises(ValueError, match="e3"):
        heteroclinic_cycle(LAGRANGE)


# ------------------------------------------------------- closed forms know their domain
def test_a_fast_sleeping_top_is_flagged_not_nan_data():
    """gamma = e3, G along the axis, a L^2 > 4 mu: the stable sleeping top. Before, the
    closed form returned precession_rate = nan with no flag."""
    top = lagrange_top(LAGRANGE, [0.0, 0.0, 3.0, 0.0, 0.0, 1.0])
    assert str(top.regime.values) == "sleeping"
    assert float(top.nutation_min) == float(top.nutation_max) == 0.0
    assert np.isnan(top.precession_rate) and np.isnan(top.nutation_period)
    assert "NaN: " in top.precession_rate.attrs["long_name"]


def test_a_slow_upright_top_is_an_equilibrium_not_the_separatrix_motion():
    """a L^2 < 4 mu upright: the state stays at theta = 0 (integrated), while the cubic's
    roots describe the separatrix (before: 'nutates from 0 to 120 deg, period 25')."""
    y0 = [0.0, 0.0, 0.5, 0.0, 0.0, 1.0]
    top = lagrange_top(LAGRANGE, y0)
    assert str(top.regime.values) == "upright_unstable"
    assert float(top.nutation_max) == 0.0 and np.isnan(top.nutation_period)
    ds = attitude(LAGRANGE, y0, np.linspace(0.0, 30.0, 31), engine=ENGINE)
    assert float(ds.nutation.max()) <= 1e-12
    hanging = lagrange_top(LAGRANGE, [0.0, 0.0, 0.5, 0.0, 0.0, -1.0])
    assert str(hanging.regime.values) == "hanging"
    assert float(hanging.nutation_min) == math.pi


def test_the_separatrix_of_the_upright_top_has_no_finite_period():
    # M = L = 1, 2E - c L^2 = 2 mu, u0 = 0.5: on the separatrix (a L^2 = 1 < 4 mu).
    u0, L = 0.5, 1.0
    g2 = math.sqrt(1.0 - u0 * u0)
    G2 = L * (1.0 - u0) / g2
    G1 = math.sqrt(2.0 * LAGRANGE.mu * (1.0 - u0) / LAGRANGE.a - G2 * G2)
    top = lagrange_top(LAGRANGE, [G1, G2, L, 0.0, g2, u0])
    assert str(top.regime.values) == "separatrix"
    assert np.isnan(top.nutation_period) and np.isnan(top.precession_rate)
    assert float(top.nutation_min) == 0.0


def test_a_top_through_the_pole_has_a_period_and_no_mean_rate():
    y0 = [0.3, 0.0, 1.5, 0.0, 0.0, 1.0]
    top = lagrange_top(LAGRANGE, y0)
    assert str(top.regime.values) == "through_the_pole"
    assert np.isnan(top.precession_rate)
    T = float(top.nutation_period)
    ds = attitude(LAGRANGE, y0, np.linspace(0.0, T, 2001), engine=ENGINE)
    theta = ds.nutation.values[0]
    assert abs(theta.max() - float(top.nutation_max)) <= 1e-5
    assert theta[-1] <= 1e-5  # back at the vertical after one period


@pytest.mark.parametrize("e3", [1.0, -1.0])
def test_u_roots_are_ascending_for_either_side_of_the_centre_of_mass(e3):
    """r = (0, 0, -1): before, u_roots came out descending (the negated roots)."""
    body = RigidBody(1.0, 1.0, 0.6, 1.0, (0.0, 0.0, e3))
    top = lagrange_top(body, Y_LAGRANGE)
    roots = top.u_roots.values
    assert np.all(np.diff(roots) >= 0.0), roots
    # cos(theta) of the body axis z moves between two of them.
    lo, hi = (roots[0], roots[1]) if e3 > 0 else (roots[1], roots[2])
    assert math.isclose(math.cos(float(top.nutation_max)), lo, abs_tol=1e-12)
    assert math.isclose(math.cos(float(top.nutation_min)), hi, abs_tol=1e-12)
    T = float(top.nutation_period)
    ds = attitude(body, Y_LAGRANGE, np.linspace(0.0, 3 * T, 3001), engine=ENGINE)
    u = np.cos(ds.nutation.values[0])
    assert lo - 1e-10 <= u.min() <= lo + 1e-4 and hi - 1e-4 <= u.max() <= hi + 1e-10
    assert float(top.precession_rate_error) <= 1e-12


def test_a_precession_sampled_every_1_01_periods_is_flagged_aliased(lagrange_run):
    """Sampled every 1.01 precession periods the wrapped steps of psi are small and the
    rate came out 93 times too small, unflagged: the rates at the samples say otherwise."""
    top, _ = lagrange_run
    Tp = 2.0 * math.pi / float(top.precession_rate)
    ds = attitude(LAGRANGE, Y_LAGRANGE, np.arange(0.0, 60.0 * Tp, 1.01 * Tp), engine=ENGINE)
    pn = precession_nutation(ds)
    assert bool(pn.undersampled[0]) and np.isnan(pn.precession_rate[0])
    assert bool(pn.nutation_undersampled[0])
    # Sampled once a nutation period: the nutation looks frozen; flagged.
    T = float(top.nutation_period)
    frozen = precession_nutation(attitude(LAGRANGE, Y_LAGRANGE, np.arange(0.0, 40 * T, T),
                                          engine=ENGINE))
    assert bool(frozen.nutation_undersampled[0])
    # Twenty samples a nutation period: neither flag, the rate right.
    fine = precession_nutation(attitude(LAGRANGE, Y_LAGRANGE,
                                        np.linspace(0.0, 40 * T, 801), engine=ENGINE))
    assert not fine.undersampled[0] and not fine.nutation_undersampled[0]
    assert abs(float(fine.precession_rate[0]) / float(top.precession_rate) - 1.0) <= 1e-3


def test_the_momentum_axis_at_g_zero_is_flagged_not_nan_data():
    ds = attitude(RigidBody.paper(), [0.0, 0.0, 0.0, 0.0, 0.6, 0.8], [0.0, 1.0, 2.0],
                  engine=ENGINE)
    tr = axis_trace(ds, "momentum")
    assert bool(tr.undefined[0, 0]) and not tr.undefined[0, 1:].any()
    assert np.isnan(tr.trace[0, 0]).all() and np.isfinite(tr.trace[0, 1:]).all()
    assert "NaN: " in tr.trace.attrs["long_name"]
    # A vertical axis has no azimuth (as psi at theta = 0).
    up = axis_trace(attitude(LAGRANGE, [0.0, 0.0, 1.0, 0.0, 0.0, 1.0], [0.0, 1.0],
                             engine=ENGINE), "z")
    assert bool(up.at_pole.all()) and np.isnan(up.azimuth).all()
    assert not axis_trace(ds, "z").undefined.any()


def test_the_herpolhode_of_a_top_at_rest_is_refused_naming_ds():
    free = RigidBody.euler_poinsot(2.5, 2.0, 2.2)
    ds = attitude(free, [0.0, 0.0, 0.0, 0.0, 0.6, 0.8], [0.0, 1.0], engine=ENGINE)
    with pytest.raises(ValueError, match=r"ds: G = 0"):
        herpolhode(ds)
