"""The attitude (issue 27, item 2): checks by independent routes, on every engine with
the capability.

Measured at rtol = atol = 1e-12 (numba / heyoka / scipy; taylor agrees with heyoka to
the digits shown, e.g. route A 5.3e-11, Lagrange rate 2.7e-14; closing note
``/work/notes/27-space.md``); each bound below is ~100x the worst measured value:

* ``R`` orthogonal over t = 200 (heavy top, mu = 0.5): 1.8e-15 / 1.6e-15 / 1.8e-15;
  ``|q| - 1``: 1.2e-14 / 4.7e-15 / 1.3e-14;
* ``R^T e_Z = gamma`` (the quaternion and (1) integrated together): 2.5e-13 / 2.6e-14 /
  2.5e-13;
* the quaternion against route A, ``psi`` by quadrature of ``(omega1 gamma1 + omega2
  gamma2)/(gamma1^2 + gamma2^2)`` along (1) (SciPy, no quaternion) and ``R`` rebuilt from
  ``(gamma, psi)``: 5.1e-11 / 5.3e-11 / 5.1e-11; against route B, the Andoyer-Deprit
  canonical equations (4) with the node ``m`` (``integrate_canonical``) and
  ``R = Rz(m) Rx(I) Rz(g) Rx(J) Rz(l)``: 3.8e-11 / 4.2e-11 / 3.7e-11;
* Euler-Poinsot: ``R G = |G| e_Z`` 1.0e-13 / 5.6e-15 / 1.2e-13, the mean precession rate
  over 20 periods against ``euler_poinsot_frequencies``: 1.2e-14 / 2.4e-15 / 9.9e-15
  (relative);
* Lagrange top: nutation inside the roots of the cubic, the mean precession rate over
  20 nutation periods against :func:`andoyer.analysis.space.lagrange.lagrange_top`: 5.1e-14 /
  2.6e-14 / 4.7e-14 (relative);
* Kovalevskaya and Goryachev-Chaplygin integrals over t = 100: 9.5e-13 / 3.5e-13 / 9.6e-13
  and 1.2e-12 / 5.2e-13 / 1.2e-12 (of max(|K0|, 1)); ``(R G)_Z = M``: 4.1e-13 at most.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.space.lagrange import lagrange_top
from andoyer.analysis.unperturbed.euler_poinsot import euler_poinsot_frequencies
from andoyer.charts.rotation import (
    andoyer_rotation,
    euler_angles,
    quaternion_from_vertical,
    rotation_matrix,
)
from andoyer.integrate import attitude, integrate_canonical
from andoyer.integrate.engines import engines_with, get_engine
from andoyer.integrate.engines.base import Capability, Tolerance
from andoyer.integrate.engines.ivp import solve_dop853
from andoyer.kernels.generated.equations import ep_field

ENGINES = engines_with(Capability.ATTITUDE)
STATE = ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")
X0 = np.array([0.3, 1.1, 0.2, 1.0, -0.4])  # Andoyer-Deprit (l, g, L, G, M), regular


def states(ds, orbit=0):
    return np.stack([ds[v].values[orbit] for v in STATE], axis=-1)


def test_every_engine_has_the_attitude():
    assert {"numba", "scipy", "heyoka", "taylor"} <= set(ENGINES)


@pytest.fixture(scope="module")
def heavy():
    return RigidBody.paper(mu=0.5), np.linspace(0.0, 200.0, 2001)


@pytest.mark.parametrize("engine", ENGINES)
def test_rotation_stays_orthogonal_and_consistent_with_gamma(engine, heavy):
    body, t = heavy
    ds = attitude(body, X0, t, chart="andoyer", engine=engine, precession0=0.3)
    R = ds.rotation.values[0]
    assert np.abs(np.einsum("tki,tkj->tij", R, R) - np.eye(3)).max() <= 1e-13
    assert np.abs(ds.quaternion_drift.values).max() <= 1e-12
    # gamma = R^T e_Z: the vertical's body components are the last row of R.
    assert np.abs(R[:, 2, :] - states(ds)[:, 3:]).max() <= 1e-11
    # The angular momentum in space: its vertical component is M = (G, gamma), constant
    # (gravity's torque is horizontal), while the horizontal part moves.
    L = ds.space_momentum.values[0]
    Y = states(ds)
    assert np.abs(L[:, 2] - np.einsum("ti,ti->t", Y[:, :3], Y[:, 3:])).max() <= 1e-11
    assert np.abs(L[:, 2] - L[0, 2]).max() <= 1e-11
    assert np.ptp(L[:, 0]) > 0.1


@pytest.mark.parametrize("engine", ENGINES)
def test_quaternion_agrees_with_the_precession_quadrature(engine, heavy):
    """Route A: ``psi`` by quadrature along (1) (no quaternion anywhere), ``R`` rebuilt
    from ``(gamma, psi)`` by the z-x-z convention."""
    body, t = heavy
    ds = attitude(body, X0, t, chart="andoyer", engine=engine, precession0=0.3)
    a, b = body.a, body.b
    p = body.params

    def rhs(_t, z):
        f = ep_field(*z[:6], *p)
        g1, g2 = z[3], z[4]
        return np.array([*f, (a * z[0] * g1 + b * z[1] * g2) / (g1 * g1 + g2 * g2)])

    sol = solve_dop853(rhs, t, np.append(states(ds)[0], 0.3), 1e-13, 1e-13)
    rebuilt = rotation_matrix(quaternion_from_vertical(sol.y[3:6].T, sol.y[6]))
    assert np.abs(rebuilt - ds.rotation.values[0]).max() <= 5e-9


@pytest.mark.parametrize("engine", ENGINES)
def test_quaternion_agrees_with_the_andoyer_deprit_node(engine, heavy):
    """Route B: the canonical equations (4) with the cyclic node ``m`` (SciPy) and the
    rotation chain ``R = Rz(m) Rx(I) Rz(g) Rx(J) Rz(l)``; ``psi = m + psi(chain at m=0)``."""
    body, t = heavy
    m0 = 0.3 - float(euler_angles(andoyer_rotation(X0, 0.0)).psi)
    ds = attitude(body, X0, t, chart="andoyer", engine=engine, precession0=0.3)
    can = integrate_canonical(body, X0, t, chart="andoyer", rtol=1e-13, atol=1e-13)
    X = np.stack([can[v].values for v in ("l_angle", "g_angle", "L_action", "G_action",
                                          "M_action")], axis=-1)
    chain = rotation_matrix(andoyer_rotation(X, can["m_angle"].values + m0))
    assert np.abs(chain - ds.rotation.values[0]).max() <= 5e-9


@pytest.mark.parametrize("engine", ENGINES)
def test_engine_attitude_runs_backward_by_time_reversal(engine, heavy):
    body, _ = heavy
    eng = get_engine(engine)
    from andoyer.charts.andoyer_deprit import from_andoyer

    y0 = from_andoyer(X0)[None]
    q0 = quaternion_from_vertical(y0[:, 3:], 0.3)
    t = np.linspace(0.0, 20.0, 5)
    tol = Tolerance(1e-12, 1e-12)
    y, q = eng.attitude(y0, q0, t, body.engine_params, tol)
    yb, qb = eng.attitude(y[:, -1], q[:, -1], t[::-1], body.engine_params, tol)
    assert np.abs(qb[:, -1] - q0).max() <= 1e-11
    assert np.abs(yb[:, -1] - y0).max() <= 1e-11
    assert np.abs(qb[0, ::-1] - q[0]).max() <= 1e-11


@pytest.mark.parametrize("engine", ENGINES)
def test_euler_poinsot_momentum_fixed_and_precession_at_the_closed_form(engine):
    free = RigidBody.euler_poinsot(2.5, 2.0, 2.2)
    G0 = np.array([0.3, 0.8, 0.5])
    G = float(np.linalg.norm(G0))
    h = 0.5 * (free.a * G0[0] ** 2 + free.b * G0[1] ** 2 + free.c * G0[2] ** 2)
    f = euler_poinsot_frequencies(free, h, G)
    n = 20
    t = np.linspace(0.0, n * f.period, 400 * n + 1)
    # The vertical along G: psi is the precession of the body axis z about G.
    ds = attitude(free, np.concatenate([G0, G0 / G]), t, engine=engine)
    assert np.abs(ds.space_momentum.values[0] - [0.0, 0.0, G]).max() <= 1e-11
    psi = np.unwrap(ds.precession.values[0])
    rate = (psi[-1] - psi[0]) / t[-1]
    assert abs(rate / f.g_rate - 1.0) <= 1e-12
    # Any vertical: R G is a constant vector.
    ds = attitude(free, np.concatenate([G0, [0.0, 0.6, 0.8]]), t[:2001], engine=engine)
    L = ds.space_momentum.values[0]
    assert np.abs(L - L[0]).max() <= 1e-12


@pytest.mark.parametrize("engine", ENGINES)
def test_lagrange_top_nutates_between_the_roots_and_precesses_at_the_closed_form(engine):
    body = RigidBody.lagrange(1.0, 0.6, 1.0)
    y0 = np.array([0.2, 0.1, 1.5, 0.0, math.sin(0.8), math.cos(0.8)])
    top = lagrange_top(body, y0)
    n = 20
    T = float(top.nutation_period)
    t = np.linspace(0.0, n * T, 400 * n + 1)
    ds = attitude(body, y0, t, engine=engine)
    theta = ds.nutation.values[0]
    lo, hi = float(top.nutation_min), float(top.nutation_max)
    assert lo - 1e-10 <= theta.min() and theta.max() <= hi + 1e-10
    # ... and reaches them (to the sampling: 400 points per period).
    assert theta.min() - lo <= 1e-4 and hi - theta.max() <= 1e-4
    psi = np.unwrap(ds.precession.values[0])
    rate = (psi[-1] - psi[0]) / t[-1]
    assert abs(rate / float(top.precession_rate) - 1.0) <= 5e-12


def kovalevskaya(body, Y):
    p, q = Y[:, 0] / body.A, Y[:, 1] / body.A
    nu = body.mu / body.C
    return (p**2 - q**2 - nu * Y[:, 3]) ** 2 + (2 * p * q - nu * Y[:, 4]) ** 2


def goryachev_chaplygin(body, Y):
    return Y[:, 2] * (Y[:, 0] ** 2 + Y[:, 1] ** 2) - 4 * body.mu * body.C * Y[:, 0] * Y[:, 5]


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("case", ["kovalevskaya", "goryachev_chaplygin"])
def test_integrable_tops_keep_their_integrals_in_space(engine, case):
    G = np.array([0.4, -0.3, 0.9])
    g = np.array([0.2, 0.5, 0.7]) / np.linalg.norm([0.2, 0.5, 0.7])
    if case == "kovalevskaya":
        body, integral = RigidBody.kovalevskaya(C=0.8, mu=1.3), kovalevskaya
    else:  # the Goryachev-Chaplygin integral holds on M = 0
        body, integral = RigidBody.goryachev_chaplygin(C=0.6, mu=0.9), goryachev_chaplygin
        g = g - G * (G @ g) / (G @ G)
        g /= np.linalg.norm(g)
    t = np.linspace(0.0, 100.0, 2001)
    ds = attitude(body, np.concatenate([G, g]), t, engine=engine)
    Y = states(ds)
    K = integral(body, Y)
    assert np.abs(K - K[0]).max() <= 1e-10 * max(abs(K[0]), 1.0)
    L = ds.space_momentum.values[0]
    M = np.einsum("ti,ti->t", Y[:, :3], Y[:, 3:])
    assert np.abs(L[:, 2] - M).max() <= 1e-11 and np.abs(M - M[0]).max() <= 1e-11
    R = ds.rotation.values[0]
    assert np.abs(np.einsum("tki,tkj->tij", R, R) - np.eye(3)).max() <= 1e-13


def test_an_engine_without_the_capability_is_refused_naming_those_with_it():
    from andoyer.integrate.engines import resolve_engine
    from andoyer.integrate.engines.base import EngineBase

    class Plain(EngineBase):
        name = "plain"
        capabilities = frozenset({Capability.PROPAGATE, Capability.CROSSINGS})

    with pytest.raises(NotImplementedError, match="attitude.*numba"):
        Plain().attitude([0, 0, 1.0, 0, 0, 1.0], [1.0, 0, 0, 0], [0.0, 1.0],
                         RigidBody.paper().engine_params, Tolerance())
    with pytest.raises(ValueError, match="attitude"):
        resolve_engine(Plain(), Capability.ATTITUDE)
    with pytest.raises(ValueError, match="engine"):
        attitude(RigidBody.paper(), X0, [0.0, 1.0], chart="andoyer", engine=Plain())
