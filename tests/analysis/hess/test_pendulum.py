"""The physical pendulum G^2 = L^2, M = 0 (issue 4, part 3): solution, potential, stability.

Independent routes: the closed-form pendulum against a direct integration and the
Euler-Poisson flow; the potential against ``from_andoyer`` (and the paper's printed form
shown wrong); the monodromy by heyoka's variational equations against central finite
differences of the compiled DOP853 flow; the multipliers against exact results (Hess
bodies), the mu -> 0 limit and the small-amplitude limit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from andoyer import RigidBody, Singular, from_andoyer, to_andoyer
from andoyer.analysis.hess.floquet import (
    floquet_multipliers,
    floquet_scan,
    hess_rotation_multiplier,
    monodromy,
    physical_pendulum_monodromy,
)
from andoyer.analysis.hess.pendulum import (
    IN_PLANE,
    STABILITY,
    TRANSVERSE,
    paper_pendulum_potential,
    pendulum_energy,
    pendulum_period,
    pendulum_potential,
    pendulum_solution,
    pendulum_state,
    physical_pendulum,
)
from andoyer.charts.euler_poisson import STATE
from andoyer.integrate import Section, poincare, propagate
from andoyer.integrate.engines.lazy import heyoka_available

PAPER = RigidBody.paper()                                   # Hess: Oz the middle axis
PLAIN = RigidBody(2.5, 2.0, 2.2, 0.01, (1.0, 0.0, 0.0))     # e3 = 0, not Hess
TILTED = RigidBody(2.5, 2.0, 2.2, 0.01, (0.6, 0.8, 0.0))    # e3 = 0, not Hess
T_IDX = [STATE.index(s) for s in TRANSVERSE]
P_IDX = [STATE.index(s) for s in IN_PLANE]


def sigma(body):
    return math.sqrt((body.b - body.c) * (body.c - body.a))


def ep(ds):
    return np.stack([np.asarray(ds[v].values).reshape(-1) for v in STATE], axis=-1)


# ---------------------------------------------------------------------- the pendulum
@pytest.mark.parametrize("q0, p0", [(4.0, 0.1), (4.0, -0.1), (1.0, -0.05), (1.0, -0.15),
                                    (-1.7, 0.3), (2.0, -0.5), (0.3, 0.0),
                                    (-math.pi / 2 + 1e-4, 1e-5), (40.0, 0.2)])
def test_pendulum_solution_vs_direct_integration(q0, p0):
    c, mu = 0.45, 0.01
    t = np.linspace(0.0, 300.0, 301)
    q, p = pendulum_solution(c, mu, q0, p0, t)
    ref = solve_ivp(lambda _t, z: [c * z[1], -mu * math.cos(z[0])], (0, 300), [q0, p0],
                    t_eval=t, rtol=1e-13, atol=1e-14, method="DOP853")
    assert q[0] == pytest.approx(q0, abs=1e-15) and p[0] == pytest.approx(p0, abs=1e-15)
    assert np.max(np.abs(q - ref.y[0])) < 1e-10
    assert np.max(np.abs(p - ref.y[1])) < 1e-11


def test_pendulum_separatrix_and_equilibrium():
    c, mu = 0.45, 0.01
    p0 = 2 * math.sqrt(mu / c)  # from the bottom with the energy of the top: h = mu
    assert pendulum_energy(c, mu, -math.pi / 2, p0) == pytest.approx(mu, rel=1e-15)
    t = np.linspace(0.0, 200.0, 201)
    q, p = pendulum_solution(c, mu, -math.pi / 2, p0, t)
    assert q[-1] == pytest.approx(math.pi / 2, abs=1e-5)  # creeping up to the top
    assert np.all(np.diff(q) > 0)
    assert pendulum_period(c, mu, mu) == math.inf
    q, p = pendulum_solution(c, mu, -math.pi / 2, 0.0, t)
    assert np.all(q == -math.pi / 2) and np.all(p == 0.0)


# ---------------------------------------------------------------------- physical pendulum
@pytest.mark.parametrize("body", [PAPER, TILTED], ids=["hess", "tilted"])
@pytest.mark.parametrize("vartheta0, L0", [(4.0, 0.1), (4.0, -0.1), (1.0, -0.15), (2.0, 0.5)])
def test_physical_pendulum_vs_euler_poisson(body, vartheta0, L0):
    """The closed form (through L = 0, i.e. G = 0, on librations) vs the 6-D flow; the set
    G1 = G2 = gamma3 = 0 is invariant for any body with e3 = 0."""
    t = np.linspace(0.0, 300.0, 601)
    sol = physical_pendulum(body, vartheta0, L0, t)
    ref = propagate(body, pendulum_state(body, vartheta0, L0), t)
    R = ep(ref.isel(orbit=0))
    assert np.max(np.abs(ep(sol) - R)) < 1e-10
    assert np.max(np.abs(R[:, T_IDX])) == 0.0  # exactly invariant (no round-off source)
    # Closed form: exact up to the round-off of ellipj at large arguments.
    assert np.max(np.abs(sol.H.values - sol.attrs["h"])) < 2e-13 * abs(sol.attrs["h"])


@pytest.mark.parametrize("h_over_mu", [-0.9, 0.5, 0.999, 1.001, 5.0])
def test_period_vs_integrated_crossings(h_over_mu):
    """Closed-form periods to 1e-9 relative: librations cross L = G3 = 0 upwards once per
    period, rotations cross gamma1 = 0 upwards once per turn."""
    body = PAPER
    h = h_over_mu * body.mu
    T = pendulum_period(body.c, body.mu, h)
    y0 = pendulum_state(body, 1.5 * math.pi, math.sqrt(2 * (h + body.mu) / body.c))
    section = Section("G3", 0.0, 1) if h_over_mu < 1 else Section("gamma1", 0.0, 1)
    ds = poincare(body, y0, section, 3, t_max=5 * T)
    np.testing.assert_allclose(np.diff(ds.t.values[0]), T, rtol=1e-9)


# ---------------------------------------------------------------------- potential
def test_potential_on_the_pendulum_and_the_paper_misprint():
    """Pi = mu (r, gamma) at from_andoyer((l, g, +-G, G, 0)) is mu sin(g + l + phi0) on
    L = G and mu sin(g - l - phi0) on L = -G; the printed mu^-1 sin(g + l - phi0) is not."""
    rng = np.random.default_rng(11)
    for body in (PAPER, TILTED, RigidBody.hess(2.5, 2.0, 2.2, mu=0.3, branch=-1)):
        l, g = rng.uniform(0, 2 * np.pi, (2, 300))
        G = rng.uniform(0.1, 3.0, 300)
        for sign in (1, -1):
            y = from_andoyer(np.stack([l, g, sign * G, G, 0 * G], axis=-1))
            Pi = body.mu * (body.e1 * y[:, 3] + body.e2 * y[:, 4])
            np.testing.assert_allclose(pendulum_potential(body, l, g, sign), Pi, atol=1e-15)
            # Only g + l (L = G) or g - l (L = -G) is defined there: the formula holds
            # for the chart inverse's own convention (l = 0, or pi for signed zeros).
            x, flags = to_andoyer(y, with_mask=True)
            assert np.all(flags & int(Singular.L_EQ_PM_G))
            assert np.all((x[:, 0] == 0.0) | (x[:, 0] == math.pi))
            np.testing.assert_allclose(pendulum_potential(body, x[:, 0], x[:, 1], sign), Pi,
                                       atol=1e-15)
        y = from_andoyer(np.stack([l, g, G, G, 0 * G], axis=-1))
        Pi = body.mu * (body.e1 * y[:, 3] + body.e2 * y[:, 4])
        assert np.max(np.abs(paper_pendulum_potential(body, l, g) - Pi)) > 1.0
        # Even with mu for mu^-1 the printed -phi0 is wrong.
        assert np.max(np.abs(body.mu * body.mu * paper_pendulum_potential(body, l, g) - Pi)) \
            > 0.1 * body.mu
    # vartheta = g + l + phi0 on L = G: the pendulum angle is the chart's angle sum.
    l, g = 0.4, 1.3
    np.testing.assert_allclose(pendulum_state(PAPER, g + l + PAPER.phi0, 0.7),
                               from_andoyer([l, g, 0.7, 0.7, 0.0]), atol=1e-15)


# ---------------------------------------------------------------------- monodromy
@pytest.mark.parametrize("body, h_over_mu", [(PAPER, -0.5), (PAPER, 3.0), (TILTED, 0.5),
                                             (PLAIN, 1.5)])
def test_monodromy_structure(body, h_over_mu):
    """det = 1; the in-plane and transverse blocks decouple; in-plane multipliers 1, 1, 1;
    transverse: 1 (area integral, left eigenvector dM) and a pair lambda, 1/lambda."""
    m = physical_pendulum_monodromy(body, h_over_mu * body.mu)
    Phi = m.matrix
    assert np.max(np.abs(m.y_end - m.y0)) < 1e-12  # the closed-form period closes the orbit
    assert np.linalg.det(Phi) == pytest.approx(1.0, abs=1e-9)
    assert np.max(np.abs(Phi[np.ix_(T_IDX, P_IDX)])) == 0.0
    assert np.max(np.abs(Phi[np.ix_(P_IDX, T_IDX)])) == 0.0
    ev_in = np.linalg.eigvals(Phi[np.ix_(P_IDX, P_IDX)])
    assert np.max(np.abs(ev_in - 1.0)) < 1e-4  # a Jordan block: sqrt(eps)-sensitive
    P = Phi[np.ix_(T_IDX, T_IDX)]
    dM = np.array([m.y0[3], m.y0[4], m.y0[2]])  # gamma1 dG1 + gamma2 dG2 + G3 dgamma3
    np.testing.assert_allclose(dM @ P, dM, atol=1e-9 * np.abs(P).max())
    f = floquet_multipliers(body, h_over_mu * body.mu)
    assert abs(f.multipliers[0] * f.multipliers[1] - 1.0) < 1e-12
    assert np.linalg.det(f.leaf_matrix) == pytest.approx(1.0, abs=1e-9)
    ev = np.sort_complex(np.linalg.eigvals(P))
    expected = np.sort_complex(np.array([1.0, *f.multipliers]))
    if f.stability != "parabolic":
        np.testing.assert_allclose(ev, expected, atol=1e-8 * abs(f.multipliers[0]))
    if f.stability == "elliptic":
        np.testing.assert_allclose(np.abs(f.multipliers), 1.0, atol=1e-12)


@pytest.mark.parametrize("body, h_over_mu", [(PLAIN, -0.5), (TILTED, 0.5), (PAPER, 3.0)])
def test_monodromy_two_routes(body, h_over_mu):
    """heyoka variational equations vs central differences of the DOP853 flow map."""
    h = h_over_mu * body.mu
    v = physical_pendulum_monodromy(body, h)
    f = physical_pendulum_monodromy(body, h, method="finite_difference", tol=1e-13, step=1e-6)
    scale = np.abs(v.matrix).max()
    assert np.max(np.abs(v.matrix - f.matrix)) < 1e-7 * scale


# ---------------------------------------------------------------------- multipliers
@pytest.mark.parametrize("body", [PAPER, RigidBody.hess(2.5, 2.0, 2.2, 0.3, branch=-1)],
                         ids=["branch+1", "branch-1"])
def test_hess_rotations_have_the_exact_multiplier(body):
    """Hess body: every rotation has lambda = exp(2 pi sigma / c) (unstable), whatever h."""
    lam = hess_rotation_multiplier(body)
    assert lam == pytest.approx(math.exp(2 * math.pi * sigma(body) / body.c))
    # heyoka (Taylor, tol 1e-15): trace to 1e-11. The Numba DOP853 (tolerance floored at
    # 1e-13) near the separatrix, h = 1.01 mu, measured 5.7e-11: round-off of the long
    # period, the default where heyoka is missing.
    rel_trace = 1e-11 if heyoka_available() else 1e-10
    for h_over_mu in (1.01, 2.0, 30.0):
        f = floquet_multipliers(body, h_over_mu * body.mu)
        assert f.stability == "hyperbolic"
        assert f.multipliers[0].real == pytest.approx(lam, rel=1e-10)
        assert f.trace == pytest.approx(lam + 1 / lam, rel=rel_trace)


def test_hess_librations_are_parabolic_with_a_jordan_block():
    """Hess body: librations have lambda = 1 twice and a shear (linear divergence)."""
    for h_over_mu in (-0.99, -0.5, 0.0, 0.9):
        f = floquet_multipliers(PAPER, h_over_mu * PAPER.mu)
        assert f.stability == "parabolic"
        assert abs(f.trace - 2.0) < 1e-9
        assert f.shear > 1e-4


def test_hess_libration_neighbours_drift_linearly():
    """The Jordan block at work: a 1e-8 push off the Hess manifold (G along r) of a
    physical-pendulum libration grows linearly with the number of periods (not
    exponentially); a push along the Hess family (G along k x r) stays put."""
    body = PAPER
    h = -0.5 * body.mu
    T = pendulum_period(body.c, body.mu, h)
    y0 = pendulum_state(body, 1.5 * math.pi, math.sqrt(2 * (h + body.mu) / body.c))
    t = T * np.arange(0, 101)
    off = np.array([body.e1, body.e2, 0, 0, 0, 0]) * 1e-8
    along = np.array([-body.e2, body.e1, 0, 0, 0, 0]) * 1e-8
    ds = propagate(body, np.stack([y0 + off, y0 + along]), t)
    d = np.sqrt(ds.G1**2 + ds.G2**2 + ds.gamma3**2).values
    assert d[0, 100] > 100 * d[0, 0]
    assert d[0, 100] / d[0, 50] == pytest.approx(2.0, rel=0.05)
    assert np.max(np.abs(d[1] - d[1, 0])) < 1e-3 * d[1, 0]


def test_mu_to_zero_limit_of_rotations():
    """Rotation about the middle axis z of a non-Hess body: as mu -> 0 at fixed L, the
    pendulum turns uniformly (T = 2 pi/(c L)) and the Euler exponent sigma L gives
    lambda -> exp(sigma L T) = exp(2 pi sigma / c); the error falls like mu^2."""
    L = 1.0
    limit = 2 * math.cosh(2 * math.pi * sigma(PLAIN) / PLAIN.c)
    errors = []
    for mu in (1e-2, 1e-3):
        body = PLAIN.with_mu(mu)
        h = 0.5 * body.c * L * L - mu  # from the bottom with L
        f = floquet_multipliers(body, h)
        assert f.stability == "hyperbolic"
        errors.append(abs(f.trace - limit))
    assert errors[0] < 1e-2
    assert errors[1] < errors[0] / 50  # quadratic convergence (x100 ideally)


@pytest.mark.parametrize("body", [PLAIN, TILTED], ids=["plain", "tilted"])
def test_small_libration_limit(body):
    """About the hanging equilibrium the transverse mode has omega^2 = mu (a e2^2 + b e1^2)
    (rotation about the in-plane axis normal to r), the pendulum omega0^2 = mu c:
    lambda -> exp(+-2 pi i omega / omega0). On a Hess body the two are equal (1:1)."""
    ratio = math.sqrt((body.a * body.e2**2 + body.b * body.e1**2) / body.c)
    f = floquet_multipliers(body, -0.99999 * body.mu)
    assert f.trace == pytest.approx(2 * math.cos(2 * math.pi * ratio), abs=1e-4)
    hess = PAPER
    assert (hess.a * hess.e2**2 + hess.b * hess.e1**2) == pytest.approx(hess.c, rel=1e-12)


def test_tilted_body_resonance_tongue():
    """A non-Hess body can be elliptic, hyperbolic, then elliptic again along the energy."""
    kinds = [floquet_multipliers(TILTED, h * TILTED.mu).stability for h in (-0.9999, 0.0, 1.5)]
    assert kinds == ["elliptic", "hyperbolic", "elliptic"]


# ---------------------------------------------------------------------- dataset
def test_floquet_scan_dataset(tmp_path):
    from andoyer.io import write_netcdf

    body = PAPER
    h = body.mu * np.array([-0.5, 0.5, 2.0])
    ds = floquet_scan(body, h)
    assert ds.sizes == {"H": 3, "pair": 2, "row": 6, "col": 6}
    assert ds.stability.values.tolist() == [STABILITY["parabolic"]] * 2 + [
        STABILITY["hyperbolic"]]
    assert ds.motion.attrs["flag_meanings"].split()[ds.motion.values[-1]] == "rotation"
    assert ds.attrs["hess_rotation_multiplier"] == pytest.approx(hess_rotation_multiplier(body))
    assert float(ds.abs_multiplier[-1]) == pytest.approx(ds.attrs["hess_rotation_multiplier"])
    assert np.all(ds.return_error.values < 1e-12)
    for v in ds.data_vars:
        assert ds[v].attrs.get("long_name"), v
    path = tmp_path / "floquet.nc"
    write_netcdf(ds, path)
    import xarray as xr

    with xr.open_dataset(path) as back:
        np.testing.assert_allclose(back.floquet_trace.values, ds.floquet_trace.values)


def test_validation():
    with pytest.raises(ValueError, match="e3 = 0"):
        physical_pendulum(RigidBody(2.5, 2.0, 2.2, 0.01, (0.6, 0.0, 0.8)), 1.0, 0.1, [0.0])
    with pytest.raises(ValueError, match="mu > 0"):
        floquet_scan(PAPER.with_mu(0.0), [0.1])
    with pytest.raises(ValueError, match="below"):
        floquet_multipliers(PAPER, -2 * PAPER.mu)
    with pytest.raises(ValueError, match="separatrix"):
        floquet_multipliers(PAPER, PAPER.mu)
    with pytest.raises(ValueError, match="method"):
        monodromy(PAPER, pendulum_state(PAPER, 1.0, 0.5), 1.0, method="magic")
    with pytest.raises(ValueError, match="L_sign"):
        pendulum_potential(PAPER, 0.0, 0.0, 2)
    with pytest.raises(ValueError, match="middle axis"):
        hess_rotation_multiplier(RigidBody(2.0, 2.2, 2.5, 0.01, (1.0, 0.0, 0.0)))
