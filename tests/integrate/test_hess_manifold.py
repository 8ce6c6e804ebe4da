"""The Hess manifold theta1 = 0: its growth law in the full flow and the reduced integration.

Issue 3, item 6: in the full Euler-Poisson flow ``(G, r) = e1 G1 + e2 G2`` obeys exactly
``d(G, r)/dt = -branch sigma G3 (G, r)``, ``sigma = sqrt((b - c)(c - a))``, so the 6-D
orbit leaves the manifold; :func:`propagate_hess_manifold` keeps the relation exactly.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from andoyer import RigidBody
from andoyer.integrate.api import propagate
from andoyer.integrate.hess_manifold import METHOD, propagate_hess_manifold
from andoyer.kernels.dop853.fields import ep_field as ep_field_jit
from andoyer.kernels.generated.equations import ep_field

STATE = ["G1", "G2", "G3", "gamma1", "gamma2", "gamma3"]
#: A Hess-solution orbit that stays well inside the Hess chart (min(J1, J2 - J1,
#: J2 - |J3|) / J2 ~ 0.1) and has mean G3 ~ -0.27 < 0: on branch +1 the manifold
#: repels it at the mean rate sigma * 0.27 ~ 0.012.
X0 = np.array([math.pi / 3, 0.21, 0.3, -0.12])


def sigma(body: RigidBody) -> float:
    return math.sqrt((body.b - body.c) * (body.c - body.a))


def branch(body: RigidBody) -> int:
    return 1 if body.e2 > 0 else -1


def ep_state(ds, i=0):
    return np.array([float(ds[v].isel(time=i)) for v in STATE])


# ---------------------------------------------------------------------- (b) growth law
@pytest.mark.parametrize("br", [1, -1])
def test_growth_law_exact_from_ep_field(br):
    """d(G, r)/dt from the generated ep_field equals -branch sigma G3 (G, r) exactly."""
    body = RigidBody.hess(2.5, 2.0, 2.2, mu=0.3, branch=br)
    a, b, c, mu, e1, e2, e3 = body.params
    rng = np.random.default_rng(3 + br)
    G = rng.uniform(-2, 2, size=(3, 2000))
    gam = rng.normal(size=(3, 2000))
    gam /= np.linalg.norm(gam, axis=0)
    f = ep_field(*G, *gam, a, b, c, mu, e1, e2, e3)
    lhs = e1 * f[0] + e2 * f[1]
    rhs = -br * sigma(body) * G[2] * (e1 * G[0] + e2 * G[1])
    assert np.max(np.abs(lhs - rhs)) <= 1e-14
    # Not an identity: a non-Hess body breaks it.
    other = RigidBody(2.5, 2.0, 2.2, 0.3, (0.6, 0.8, 0.0))
    f = ep_field(*G, *gam, *other.params)
    lhs = other.e1 * f[0] + other.e2 * f[1]
    rhs = -sigma(other) * G[2] * (other.e1 * G[0] + other.e2 * G[1])
    assert np.max(np.abs(lhs - rhs)) > 1e-3


@pytest.mark.parametrize("br", [1, -1])
def test_growth_law_along_full_orbit(br):
    """Start 1e-8 off the manifold; (G, r)(t)/(G, r)(0) = exp(-branch sigma int G3)."""
    body = RigidBody.hess(2.5, 2.0, 2.2, mu=0.01, branch=br)
    y0 = ep_state(propagate_hess_manifold(body, X0, [0.0, 1.0]))
    e = np.array([body.e1, body.e2, 0.0])
    y0[:3] += 1e-8 * e  # gamma untouched: |gamma| = 1 still
    gr0 = body.e1 * y0[0] + body.e2 * y0[1]
    assert gr0 == pytest.approx(1e-8, rel=1e-6)
    p = body.params

    def rhs(_t, z):
        f = ep_field_jit(z[0], z[1], z[2], z[3], z[4], z[5], *p)
        return [*f, z[2]]  # last component: int_0^t G3 dt

    times = np.array([0.0, 50.0, 200.0, 400.0, 700.0, 1000.0])
    sol = solve_ivp(rhs, (0.0, times[-1]), [*y0, 0.0], method="DOP853", t_eval=times,
                    rtol=1e-13, atol=1e-16)
    assert sol.success
    gr = body.e1 * sol.y[0] + body.e2 * sol.y[1]
    predicted = np.exp(-br * sigma(body) * sol.y[6])
    ratio = gr / gr0
    np.testing.assert_allclose(ratio, predicted, rtol=1e-5)
    # Not a vacuous check: on this orbit (G, r) changes by orders of magnitude (mean G3
    # has the sign that makes the manifold repel on either branch: the branch -1 body is
    # the mirror image of the branch +1 one, and so is the orbit from the same chart point).
    assert ratio[-1] > 1e3


# ---------------------------------------------------------------------- (a) reduced orbit
@pytest.mark.filterwarnings("ignore:At least one element of `rtol` is too small")
def test_reduced_agrees_with_full_short_time(paper_body):
    t = np.linspace(0.0, 50.0, 101)
    red = propagate_hess_manifold(paper_body, X0, t)
    full = propagate(paper_body, ep_state(red), t, engine="scipy", rtol=1e-13,
                     atol=1e-13).isel(orbit=0)
    for v in STATE:
        np.testing.assert_allclose(red[v].values, full[v].values, rtol=0, atol=1e-9)
    assert float(abs(full.G1 * paper_body.e1 + full.G2 * paper_body.e2).max()) < 1e-12


def test_reduced_keeps_relation_full_flow_leaves(paper_body):
    t = np.linspace(0.0, 1e4, 1001)
    red = propagate_hess_manifold(paper_body, X0, t)
    assert red.sizes == {"time": 1001}
    assert float(abs(red.hess_relation).max()) <= 1e-14
    assert np.all(red.theta1.values == 0.0)
    assert float(abs(red.H_drift).max()) < 1e-8
    assert float(abs(red.area - red.area[0]).max()) < 1e-14
    assert float(abs(red.geometric - 1.0).max()) < 1e-14
    assert red.attrs["method"] == METHOD
    assert red.attrs["rtol"] == 1e-12 and red.attrs["engine"] == "scipy-DOP853"
    assert "theta3" in red and np.isfinite(red.theta3).all()
    full = propagate(paper_body, ep_state(red), t).isel(orbit=0)
    off = abs(full.G1 * paper_body.e1 + full.G2 * paper_body.e2)
    # Exponential departure: round-off grows by > 1e10 within a few thousand time units.
    assert float(off.sel(time=slice(0, 100)).max()) < 1e-12
    assert float(off.max()) > 1e-4


def test_theta1_two_pi_sheet_and_full_point(paper_body):
    t = [0.0, 5.0, 10.0]
    a = propagate_hess_manifold(paper_body, X0, t)
    b = propagate_hess_manifold(paper_body, [4 * math.pi, *X0], t)
    np.testing.assert_array_equal(a.G1.values, b.G1.values)
    c = propagate_hess_manifold(paper_body, [2 * math.pi + 1e-13, *X0], t)
    assert c.attrs["theta1"] == 2 * math.pi
    assert float(abs(c.hess_relation).max()) <= 1e-14


# ---------------------------------------------------------------------- (c) bad input
def test_bad_input(paper_body):
    t = [0.0, 1.0]
    with pytest.raises(ValueError, match="Hess conditions"):
        propagate_hess_manifold(RigidBody(2.5, 2.0, 2.2, 0.01, (0.6, 0.8, 0.0)), X0, t)
    with pytest.raises(ValueError, match="not on the Hess manifold"):
        propagate_hess_manifold(paper_body, [1e-9, *X0], t)
    with pytest.raises(ValueError, match="not on the Hess manifold"):
        propagate_hess_manifold(paper_body, [math.pi, *X0], t)
    for bad in ([0.1, 0.2, 0.3], np.zeros((2, 4)), [0.0, *X0, 1.0]):
        with pytest.raises(ValueError, match="shape"):
            propagate_hess_manifold(paper_body, bad, t)
    with pytest.raises(ValueError, match="singular set"):
        propagate_hess_manifold(paper_body, [0.0, 0.0, 0.3, 0.1], t)
    with pytest.raises(ValueError, match="t must"):
        propagate_hess_manifold(paper_body, X0, [1.0, 0.0])
    with pytest.raises(ValueError, match="rtol"):
        propagate_hess_manifold(paper_body, X0, t, rtol=1.0)


def test_orbit_through_the_hess_charts_singular_set_integrates(paper_body):
    # The docstring example (M = 0.2): the reduced Hess-chart integration stopped at
    # t = 74 (L = +-G, J1 -> J2); on the manifold in Euler-Poisson variables it goes on.
    t = np.linspace(0.0, 200.0, 401)
    red = propagate_hess_manifold(paper_body, [1.0, 0.4, 1.0, 0.2], t)
    assert int(red.sheet_switches) >= 1 and int(red.g_zero_passages) == 0
    assert set(np.unique(red.theta1.values)) == {0.0, 2 * math.pi}
    assert float(abs(red.hess_relation).max()) <= 1e-14
    assert float(abs(red.area - 0.2).max()) <= 1e-14
    full = propagate(paper_body, ep_state(red), t, engine="numba",
                     rtol=1e-13, atol=1e-13).isel(orbit=0)
    for v in STATE:
        np.testing.assert_allclose(red[v].values, full[v].values, rtol=0, atol=1e-9)
    # theta3 against the chart quadrature where the chart is regular.
    from andoyer.dynamics import cyclic_rate
    fine = np.linspace(0.0, 5.0, 2001)
    red = propagate_hess_manifold(paper_body, [1.0, 0.4, 1.0, 0.2], fine)
    x = np.stack([red[v].values for v in ("theta1", "theta2", "J1", "J2", "J3")], axis=-1)
    rate = cyclic_rate(paper_body, x, "hess")
    dm = np.gradient(red.theta3.values, fine)
    np.testing.assert_allclose(dm[1:-1], rate[1:-1], rtol=1e-5, atol=1e-9)


def test_hess_libration_through_G0_integrates_with_the_jump_of_m(paper_body):
    # M = 0 libration of the Hess solution: passes G = 0, where m jumps by pi.
    t = np.linspace(0.0, 120.0, 241)
    red = propagate_hess_manifold(paper_body, [4.0, 0.03, 0.1, 0.0], t)
    assert int(red.g_zero_passages) >= 1
    assert float(abs(red.hess_relation).max()) <= 1e-15
    full = propagate(paper_body, ep_state(red), t, engine="numba",
                     rtol=1e-13, atol=1e-13).isel(orbit=0)
    for v in STATE:
        np.testing.assert_allclose(red[v].values, full[v].values, rtol=0, atol=1e-9)
    jumps = np.diff(red.theta3.values)
    assert np.allclose(np.sort(np.abs(jumps))[-int(red.g_zero_passages):], math.pi)


def test_angular_momentum_reaching_the_vertical_is_refused(paper_body):
    with pytest.raises(ValueError, match="singular set"):
        propagate_hess_manifold(paper_body, [0.0, 0.0, 0.3, 0.1], [0.0, 1.0])
