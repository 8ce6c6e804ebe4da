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
from andoyer.analysis.space.lagrange_top import lagrange_top
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
