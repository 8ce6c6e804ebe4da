"""The Hess solution theta1 = 0 (issue 4, part 3): reduction, periods, closed form.

Independent routes: the reduced Hamiltonian against the SymPy derivation and the
generated Hess-chart kernels; closed-form periods against quadrature and against the
crossing times of integrated orbits; the closed-form state against the Euler-Poisson
integration (across G = 0), the reduced manifold integration, and -- for the cyclic
angle theta3 = m -- against an integration of the body's orientation matrix.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from andoyer import RigidBody
from andoyer.analysis.hess.solution import (
    MOTIONS,
    classify_motion,
    cubic_roots,
    derive_reduced_hamiltonian,
    drift_rate,
    energy_minimum,
    hess_solution,
    hess_state,
    period,
    reduced_field,
    reduced_hamiltonian,
    signed_to_hess,
)
from andoyer.charts.hess import from_hess, to_hess
from andoyer.dynamics import cyclic_rate, hamiltonian, vector_field
from andoyer.integrate import Section, poincare, propagate, propagate_hess_manifold
from andoyer.kernels.dop853.fields import ep_field

STATE = ["G1", "G2", "G3", "gamma1", "gamma2", "gamma3"]
BODY = RigidBody.paper()  # mu = 0.01: pendulum frequency sqrt(c mu) = 0.067

#: Orbits of the paper's body, (theta1, theta2, J1, J2, J3) at t = 0.
LIBRATION = [0.0, 1.5 * math.pi, 0.03, 0.1, 0.0]       # M = 0, through G = 0
ROTATION = [2 * math.pi, 2.0, 0.2, 0.6, 0.0]           # M = 0, heteroclinic drift of J1
LIBRATION_M = [0.0, 4.0, 0.04, 0.1, 0.05]              # M != 0, crosses J1 = 0 (sheet flip)
ROTATION_M = [2 * math.pi, 1.0, 0.3, 0.5, -0.2]        # M != 0
CASES = {"libration": LIBRATION, "rotation": ROTATION, "libration_M": LIBRATION_M,
         "rotation_M": ROTATION_M}


def ep(ds) -> np.ndarray:
    return np.stack([np.asarray(ds[v].values).reshape(-1) for v in STATE], axis=-1)


def wrap(a):
    return np.angle(np.exp(1j * np.asarray(a)))


# ---------------------------------------------------------------------- reduction
def test_reduced_hamiltonian_is_the_derivation():
    """SymPy: H_hess at theta1 = 0 with the Hess condition is c J2^2/2 + mu sqrt(..) sin/J2."""
    import sympy as sp

    from andoyer.symbolic.hamiltonian import S

    c_hess = S.a * sp.sin(S.phi0) ** 2 + S.b * sp.cos(S.phi0) ** 2
    written = (c_hess * S.J2**2 / 2
               + S.mu * sp.sqrt(S.J2**2 - S.J3**2) * sp.sin(S.theta2) / S.J2)
    derived = derive_reduced_hamiltonian()
    assert S.J1 not in derived.free_symbols
    assert sp.simplify(derived - written) == 0


@pytest.mark.parametrize("theta1", [0.0, 2 * math.pi])
@pytest.mark.parametrize("M", [0.0, 0.37])
def test_reduced_hamiltonian_and_field_match_the_generated_kernels(theta1, M):
    """On theta1 = 0 and 2 pi: H and d(theta2, J1, J2)/dt, dtheta3/dt of the Hess chart."""
    rng = np.random.default_rng(7)
    n = 200
    J2 = rng.uniform(0.5, 2.0, n)
    x = np.stack([np.full(n, theta1), rng.uniform(0, 2 * np.pi, n),
                  J2 * rng.uniform(0.01, 0.99, n), J2, np.full(n, M)], axis=-1)
    H = hamiltonian(BODY, x, "hess")
    np.testing.assert_allclose(reduced_hamiltonian(BODY, x[:, 1], J2, M), H, rtol=1e-14,
                               atol=1e-15)
    f = vector_field(BODY, x, "hess")
    assert np.max(np.abs(f[:, 0])) < 1e-15  # dtheta1/dt = 0: the manifold is invariant
    mine = reduced_field(BODY, x[:, 1], x[:, 2], J2, M, theta1=theta1)
    np.testing.assert_allclose(mine[:, :3], f[:, [1, 2, 3]], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(mine[:, 3], cyclic_rate(BODY, x, "hess"), atol=1e-15)


def test_reduction_fails_off_the_hess_condition():
    """A body with e3 = 0 but not Hess: H on theta1 = 0 depends on J1 (not a reduction)."""
    other = RigidBody(2.5, 2.0, 2.2, 0.01, (0.6, 0.8, 0.0))
    x = np.array([[0.0, 1.0, 0.2, 1.0, 0.0], [0.0, 1.0, 0.7, 1.0, 0.0]])
    H = hamiltonian(other, x, "hess")
    assert abs(H[0] - H[1]) > 1e-3
    with pytest.raises(ValueError, match="Hess body"):
        reduced_field(other, 1.0, 0.2, 1.0)


# ---------------------------------------------------------------------- energies
def test_classification_and_minimum():
    mu, c = BODY.mu, BODY.c
    assert classify_motion(BODY, -mu) == "equilibrium"
    assert classify_motion(BODY, 0.3 * mu) == "libration"
    assert classify_motion(BODY, mu) == "separatrix"
    assert classify_motion(BODY, 1.5 * mu) == "rotation"
    with pytest.raises(ValueError, match="below"):
        classify_motion(BODY, -1.01 * mu)
    M = 0.05
    J, hmin = energy_minimum(BODY, M)
    # The centre: dH/dJ2 = 0 and dH/dtheta2 = 0 at (3 pi/2, J).
    f = reduced_field(BODY, 1.5 * math.pi, 0.5 * J, J, M)
    assert abs(f[0]) < 1e-15 and abs(f[2]) < 1e-15
    assert classify_motion(BODY, hmin, M) == "equilibrium"
    assert classify_motion(BODY, 0.5 * (hmin + c * M * M / 2), M) == "libration"
    assert classify_motion(BODY, c * M * M / 2, M) == "pole_passage"
    assert classify_motion(BODY, c * M * M, M) == "rotation"
    with pytest.raises(ValueError, match="below the minimum"):
        classify_motion(BODY, hmin - 1e-6, M)
    assert set(MOTIONS) >= {"libration", "rotation", "separatrix", "pole_passage"}


def test_relative_equilibrium_at_M_nonzero():
    """Started at the centre (3 pi/2, J2*): J2 and theta2 stay, psi and theta3 move."""
    M = 0.05
    J, hmin = energy_minimum(BODY, M)
    x0 = [0.0, 1.5 * math.pi, 0.4 * J, J, M]
    t = np.linspace(0.0, 100.0, 101)
    sol = hess_solution(BODY, x0, t)
    assert sol.attrs["motion"] == "equilibrium"
    assert np.ptp(sol.J2.values) == 0.0 and np.ptp(sol.theta2_signed.values) == 0.0
    assert np.ptp(sol.psi.values) > 0.1
    ref = propagate(BODY, from_hess(BODY, x0), t)
    assert np.max(np.abs(ep(sol) - ep(ref.isel(orbit=0)))) < 1e-10


def test_cubic_roots_are_roots():
    for h, M in ((0.5 * BODY.mu, 0.0), (0.02, 0.1), (-0.003, 0.05)):
        ua, ub, uc = cubic_roots(BODY, h, M)
        for u in (ua, ub, uc):
            P = BODY.mu**2 * (u - M * M) - u * (h - BODY.c * u / 2) ** 2
            assert abs(P) < 1e-17
        assert ua <= ub < uc and ub >= M * M


H_GRID = [(-0.99, 0.0), (-0.3, 0.0), (0.7, 0.0), (0.999, 0.0), (1.001, 0.0), (3.0, 0.0),
          (40.0, 0.0), (None, 0.05), (0.0, 0.05), (2.0, 0.1), (30.0, 0.3)]


@pytest.mark.parametrize("h_over_mu, M", H_GRID)
def test_period_elliptic_vs_quadrature(h_over_mu, M):
    """Closed form (ellipk) vs scipy quad of du/sqrt(P(u)) with the end singularities removed."""
    if h_over_mu is None:  # halfway between the centre and the pole passage
        h = 0.5 * (energy_minimum(BODY, M)[1] + BODY.c * M * M / 2)
    else:
        h = h_over_mu * BODY.mu
    T = period(BODY, h, M)
    assert math.isfinite(T)
    assert period(BODY, h, M, method="quad") == pytest.approx(T, rel=1e-10)


def test_period_limits():
    mu, c = BODY.mu, BODY.c
    w0 = math.sqrt(c * mu)
    assert period(BODY, -mu) == pytest.approx(2 * math.pi / w0, rel=1e-14)
    assert period(BODY, -mu * (1 - 1e-10)) == pytest.approx(2 * math.pi / w0, rel=1e-9)
    assert period(BODY, mu) == math.inf
    # Near the separatrix: logarithmic growth, from both sides.
    assert period(BODY, mu * (1 - 1e-8)) > 4 * period(BODY, 0.0)
    # Fast rotation: theta2 advances uniformly, dtheta2/dt = c J2, T -> 2 pi / (c J2).
    J2 = 20.0
    assert period(BODY, c * J2**2 / 2) == pytest.approx(2 * math.pi / (c * J2), rel=1e-6)
    # M != 0: smooth through the pole passage h = c M^2/2 (no separatrix)...
    M = 0.05
    hp = c * M * M / 2
    T0 = period(BODY, hp, M)
    Tm, Tp = period(BODY, hp - 1e-7, M), period(BODY, hp + 1e-7, M)
    assert abs(Tm - T0) < 1e-4 * T0 and abs(Tp - T0) < 1e-4 * T0
    # ... and the centre frequency is the small-oscillation limit.
    J, hmin = energy_minimum(BODY, M)
    assert period(BODY, hmin + 1e-12, M) == pytest.approx(period(BODY, hmin, M), rel=1e-5)


@pytest.mark.parametrize("case", list(CASES))
def test_period_vs_integrated_crossings(case):
    """Periods to 1e-9 relative: crossing times of G = const (+) of the integrated orbit."""
    x0 = np.array(CASES[case])
    M = x0[4]
    h = float(reduced_hamiltonian(BODY, x0[1], x0[3], M))
    T = period(BODY, h, M)
    _, ub, uc = cubic_roots(BODY, h, M)
    level = math.sqrt(0.5 * (ub + uc))  # a value of G = J2 in the middle of its range
    ds = poincare(BODY, from_hess(BODY, x0), Section("G", level, 1), 4, t_max=6 * T)
    t = ds.t.values[0]
    assert np.all(np.isfinite(t))
    # On an M = 0 libration |G| = |J2| repeats every half period.
    expected = T / 2 if case == "libration" else T
    np.testing.assert_allclose(np.diff(t), expected, rtol=1e-9)


def test_libration_full_period_returns_the_state():
    """The physical libration (M = 0) has period T, not T/2: the chart's (theta2, J2)
    repeats at T/2 but the sheet theta1 and J1 do not."""
    x0 = np.array(LIBRATION)
    h = float(reduced_hamiltonian(BODY, x0[1], x0[3]))
    T = period(BODY, h)
    y0 = from_hess(BODY, x0)
    ds = propagate(BODY, y0, [0.0, T / 2, T])
    Y = ep(ds)
    assert np.max(np.abs(Y[2] - y0)) < 1e-12
    assert np.max(np.abs(Y[1] - y0)) > 1e-2
    # A time error dT moves the state by |dy/dt| dT: the return bounds dT/T below 1e-9.
    speed = np.linalg.norm(vector_field(BODY, y0))
    assert np.max(np.abs(Y[2] - y0)) / speed / T < 1e-9
    xh = to_hess(BODY, Y)
    assert abs(wrap(xh[1, 1] - x0[1])) < 1e-9 and abs(xh[1, 3] - x0[3]) < 1e-11
    assert abs(xh[1, 0] - x0[0]) > 1.0  # the other sheet at T/2


# ---------------------------------------------------------------------- closed form
@pytest.fixture(scope="module")
def solutions():
    """Closed form and Euler-Poisson integration of the four orbits, t in [0, 300]."""
    t = np.linspace(0.0, 300.0, 1201)
    out = {}
    for name, x0 in CASES.items():
        out[name] = (hess_solution(BODY, x0, t), propagate(BODY, from_hess(BODY, x0), t))
    return out


@pytest.mark.parametrize("case", list(CASES))
def test_closed_form_matches_euler_poisson_integration(solutions, case):
    """The closed-form state (through G = 0 and across the sheet flips) vs the 6-D flow."""
    sol, ref = solutions[case]
    err = np.max(np.abs(ep(sol) - ep(ref.isel(orbit=0))))
    assert err < 5e-11, err


@pytest.mark.parametrize("case", list(CASES))
def test_conservation(solutions, case):
    sol, _ = solutions[case]
    h, M = sol.attrs["h"], sol.attrs["M"]
    # Closed form: H is exact up to the round-off of ellipj at large arguments (~1e-13).
    assert np.max(np.abs(sol.H.values - h)) < 1e-16 + 2e-13 * abs(h)
    assert np.max(np.abs(sol.area.values - M)) < 1e-15
    assert np.max(np.abs(sol.geometric.values - 1.0)) < 1e-15
    hess_rel = BODY.e1 * sol.G1.values + BODY.e2 * sol.G2.values
    assert np.max(np.abs(hess_rel)) < 1e-16


@pytest.mark.parametrize("case", list(CASES))
def test_chart_values_match_integration_away_from_singular_set(solutions, case):
    """theta1, theta2, J1, J2 (to_hess of the integrated orbit) vs the closed form."""
    sol, ref = solutions[case]
    ref = ref.isel(orbit=0)
    x = sol.J1.values / np.where(sol.J2.values > 0, sol.J2.values, 1.0)
    ok = (sol.J2.values > 1e-3) & (x > 1e-6) & (x < 1 - 1e-6)
    assert ok.sum() > 600
    assert np.max(np.abs(wrap(sol.theta1.values[ok] - ref.theta1.values[ok]))) < 1e-9
    assert np.max(np.abs(wrap(sol.theta2.values[ok] - ref.theta2.values[ok]))) < 1e-9
    np.testing.assert_allclose(sol.J2.values[ok], ref.J2.values[ok], rtol=1e-10)
    np.testing.assert_allclose(sol.J1.values[ok], ref.J1.values[ok], rtol=1e-8)


def test_J1_logistic_law_and_heteroclinic_drift(solutions):
    """M = 0: log(J1/(J2 - J1)) - s theta2/c is constant (s = kappa sin 2 phi0); on a
    rotation J1 -> 0 on branch +1 (s < 0): towards L = -G, the physical pendulum."""
    sol, ref = solutions["rotation"]
    ref = ref.isel(orbit=0)
    s, c = drift_rate(BODY), BODY.c
    assert s < 0
    logit = np.log(ref.J1.values / (ref.J2.values - ref.J1.values))
    inv = logit - s * sol.theta2_signed.values / c
    assert np.ptp(inv) < 1e-8
    assert ref.J1.values[-1] / ref.J2.values[-1] < 1e-3 * ref.J1.values[0] / ref.J2.values[0]


def test_drift_reverses_on_the_other_branch():
    body = RigidBody.hess(2.5, 2.0, 2.2, mu=0.3, branch=-1)
    assert drift_rate(body) > 0
    x0 = [0.0, 1.0, 0.3, 1.2, 0.0]
    t = np.linspace(0.0, 60.0, 121)
    sol = hess_solution(body, x0, t)
    assert sol.attrs["motion"] == "rotation"
    assert sol.J1.values[-1] / sol.J2.values[-1] > 0.999  # towards L = +G
    ref = propagate(body, from_hess(body, x0), t)
    assert np.max(np.abs(ep(sol) - ep(ref.isel(orbit=0)))) < 1e-11


# ---------------------------------------------------------------------- G = 0
def test_libration_passes_through_G_zero_with_the_chart_rule(solutions):
    """Across each zero of the signed J2 the integrated chart values obey
    (theta1, theta2, J1/J2) -> (theta1 + 2 pi, pi - theta2, 1 - J1/J2): theta2 jumps from
    one turning point 3 pi/2 + alpha to the other 3 pi/2 - alpha, not by pi."""
    sol, ref = solutions["libration"]
    ref = ref.isel(orbit=0)
    J2s = sol.J2_signed.values
    passes = np.flatnonzero(np.sign(J2s[:-1]) != np.sign(J2s[1:]))
    assert passes.size >= 5  # T/2 = 48: six passages in t <= 300
    amplitudes = []
    for i in passes:
        before, after = i - 2, i + 3  # 0.5 time units either side (|G| ~ 3e-4)
        for k in (before, after):  # the closed form carries the rule: same chart values
            assert abs(wrap(float(sol.theta1[k] - ref.theta1[k]))) < 1e-9
            assert abs(wrap(float(sol.theta2[k] - ref.theta2[k]))) < 1e-7
            assert float(sol.J1[k] / sol.J2[k]) == pytest.approx(
                float(ref.J1[k] / ref.J2[k]), abs=1e-7)
        xb, xa = ref.isel(time=before), ref.isel(time=after)
        flip = abs(math.remainder(float(xa.theta1 - xb.theta1), 4 * math.pi))
        assert flip == pytest.approx(2 * math.pi, abs=1e-9)  # the other sheet
        assert float(xa.J1 / xa.J2) == pytest.approx(1 - float(xb.J1 / xb.J2), abs=1e-4)
        amp = wrap(float(xb.theta2) - 1.5 * math.pi)
        jump = wrap(float(xa.theta2 - xb.theta2))
        assert jump == pytest.approx(-2 * amp, abs=1e-3)
        assert abs(abs(jump) - math.pi) > 0.5
        amplitudes.append(amp)
    # The chart always sees the same arc, ending at the upper turning point.
    assert np.ptp(amplitudes) < 1e-3 and amplitudes[0] > 0
    x = signed_to_hess([1.0, 1.0], [0.1, -0.1], [0.7, 0.7])
    assert x[1, 0] == 2 * math.pi and x[1, 1] == pytest.approx(math.pi - 1.0)
    assert x[1, 2] / x[1, 3] == pytest.approx(1 - x[0, 2] / x[0, 3])


def test_hess_state_is_regular_at_G_zero():
    """The signed chain map: continuous across J2 = 0, and equal to from_hess of the rule."""
    J2 = np.array([-1e-3, -1e-9, 0.0, 1e-9, 1e-3])
    y = hess_state(BODY, 1.5 * math.pi + 0.4, J2, 0.8)
    assert np.max(np.abs(np.diff(y[1:4], axis=0))) < 1e-8
    for j2 in (-0.3, 0.3):
        chart = signed_to_hess(2.0, j2, 0.8)
        np.testing.assert_allclose(hess_state(BODY, 2.0, j2, 0.8), from_hess(BODY, chart),
                                   atol=1e-15)


# ---------------------------------------------------------------------- theta3 = m
def _orientation_m(body, y0, t, m0=0.0):
    """Node longitude m(t) from an integration of the attitude R (body -> space)."""
    a, b, c, mu, e1, e2, e3 = body.params
    G0, gam0 = y0[:3], y0[3:]
    M = float(G0 @ gam0)
    Gh = G0 - M * gam0
    u = np.stack([gam0, Gh / np.linalg.norm(Gh), np.cross(gam0, Gh / np.linalg.norm(Gh))])
    # In space: gamma -> e_Z and G -> G (sin I sin m0, -sin I cos m0, cos I).
    v2 = np.array([math.sin(m0), -math.cos(m0), 0.0])
    v = np.stack([np.array([0.0, 0.0, 1.0]), v2, np.cross([0.0, 0.0, 1.0], v2)])
    R0 = v.T @ u

    def rhs(_t, z):
        f = np.array(ep_field(*z[:6], a, b, c, mu, e1, e2, e3))
        w = np.array([a * z[0], b * z[1], c * z[2]])
        W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        return np.concatenate([f, (z[6:].reshape(3, 3) @ W).ravel()])

    sol = solve_ivp(rhs, (t[0], t[-1]), np.concatenate([y0, R0.ravel()]), t_eval=t,
                    method="DOP853", rtol=1e-12, atol=1e-13)
    Gs = np.einsum("kij,jk->ki", sol.y[6:].T.reshape(-1, 3, 3), sol.y[:3])
    return np.arctan2(Gs[:, 0], -Gs[:, 1]), sol.y[:6].T


@pytest.mark.parametrize("case", ["libration", "libration_M", "rotation_M"])
def test_theta3_is_the_node_longitude(case):
    """theta3 (quadrature; 0/pi jumps at G = 0) vs m from the integrated orientation."""
    t = np.linspace(0.0, 120.0, 241)
    sol = hess_solution(BODY, CASES[case], t)
    m, _ = _orientation_m(BODY, from_hess(BODY, CASES[case]), t)
    G = np.hypot(sol.J2.values, 0)
    ok = G > 1e-3
    assert np.max(np.abs(wrap(sol.theta3.values[ok] - m[ok]))) < 1e-9
    if case == "libration":
        assert set(np.round(sol.theta3.values, 12)) == {0.0, round(math.pi, 12)}
    else:
        assert np.ptp(sol.theta3.values) > 0.05  # M != 0: m moves


# ---------------------------------------------------------------------- long times
def test_long_rotation_against_the_manifold_integrator():
    """t = 1200 (13 revolutions): propagate_hess_manifold (reduced equations, relation (3)
    exact) vs the closed form; J1 relative, as it decays by ~1e-6."""
    x0 = [2 * math.pi, 1.0, 0.03, 0.1, 0.0]
    t = np.linspace(0.0, 1200.0, 241)
    sol = hess_solution(BODY, x0, t)
    num = propagate_hess_manifold(BODY, x0, t, rtol=1e-13, atol=1e-13)
    assert sol.J1.values[-1] / sol.J1.values[0] < 1e-4
    np.testing.assert_allclose(sol.J1.values, num.J1.values, rtol=1e-8, atol=1e-16)
    np.testing.assert_allclose(sol.J2.values, num.J2.values, rtol=2e-9)
    assert np.max(np.abs(wrap(sol.theta2.values - num.theta2.values))) < 1e-9


def test_M_nonzero_rotation_against_the_manifold_integrator():
    x0 = [0.0, 1.0, 0.25, 0.5, 0.1]
    t = np.linspace(0.0, 60.0, 121)
    sol = hess_solution(BODY, x0, t)
    num = propagate_hess_manifold(BODY, x0, t, rtol=1e-13, atol=1e-13)
    for v in ("J1", "J2", "theta3"):
        np.testing.assert_allclose(sol[v].values, num[v].values, rtol=1e-9, atol=1e-12)


# ---------------------------------------------------------------------- validation
def test_validation_messages():
    t = [0.0, 1.0]
    with pytest.raises(ValueError, match="Hess body"):
        hess_solution(RigidBody(2.5, 2.0, 2.2, 0.01, (0.6, 0.8, 0.0)), LIBRATION, t)
    with pytest.raises(ValueError, match="not on the Hess manifold"):
        hess_solution(BODY, [0.3, 1.0, 0.1, 0.5, 0.0], t)
    with pytest.raises(ValueError, match="J2 = G must be > 0"):
        hess_solution(BODY, [0.0, 1.0, 0.0, 0.0, 0.0], t)
    with pytest.raises(ValueError, match="J1"):
        hess_solution(BODY, [0.0, 1.0, 0.7, 0.5, 0.0], t)
    with pytest.raises(ValueError, match="M"):
        hess_solution(BODY, [0.0, 1.0, 0.2, 0.5, 0.5], t)
    with pytest.raises(ValueError, match="strictly increasing"):
        hess_solution(BODY, LIBRATION, [1.0, 0.0])
    with pytest.raises(ValueError, match="mu > 0"):
        period(BODY.with_mu(0.0), 0.1)
    with pytest.raises(ValueError, match="method"):
        period(BODY, 0.0, method="simpson")


def test_dataset_is_self_describing(solutions):
    sol, _ = solutions["libration"]
    for key in ("h", "M", "motion", "period", "drift_rate", "andoyer_version", "body_A"):
        assert key in sol.attrs
    for v in ("theta3", "theta2_signed", "J2_signed", "psi", "J1"):
        assert sol[v].attrs.get("long_name")


@pytest.mark.parametrize("M", [0.03, -0.05])
@pytest.mark.parametrize("offset", [0.0, 1e-9, -1e-7, 1e-3])
@pytest.mark.parametrize("theta2_0", [0.5 * math.pi, 1.5 * math.pi])
def test_full_precision_at_and_near_the_turning_points(theta2_0, offset, M):
    """``cos theta2 = 0`` is a turning point of ``u = J2^2`` (``u_b`` or ``u_c``): the
    initial phase must not come from ``sqrt(u_c - u0)`` alone (was 1.2e-8 against
    integration and ``|H - h|`` 1e-10 exactly there, 1e-12 a little away)."""
    body = RigidBody.paper()
    x0 = [0.0, theta2_0 + offset, 0.05, 0.1, M]
    t = np.linspace(0.0, 30.0, 7)
    ds = hess_solution(body, x0, t)
    ref = propagate_hess_manifold(body, x0, t)
    assert float(abs(ds.H - ds.attrs["h"]).max()) <= 1e-13 * abs(ds.attrs["h"])
    err = max(float(abs(ds[v] - ref[v]).max()) for v in ("G1", "G2", "G3", "gamma1",
                                                          "gamma2", "gamma3"))
    assert err < 2e-11, err
