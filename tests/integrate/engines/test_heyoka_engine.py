"""The heyoka engine against independent references and the laws of the flow.

* orbits agree with ``scipy.integrate.solve_ivp(DOP853)`` at rtol = atol = 1e-13;
* H, the area integral (G, gamma) and |gamma|^2 drift by less than 1e-10 over t = 1e3;
* crossings lie on the section (``|f| <= 1e-12``), have the requested direction, and
  are the crossings scipy's event location finds;
* angle sections (g, theta2) at a value near 0 / 2 pi give no spurious crossing at
  the wrap: the chart angle at every crossing equals the value mod 2 pi.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

hy = pytest.importorskip("heyoka")

from scipy.integrate import solve_ivp  # noqa: E402

from andoyer import (  # noqa: E402
    RigidBody,
    area_integral,
    energy,
    from_andoyer,
    geometric_integral,
    to_andoyer,
    to_hess,
)
from andoyer.integrate.engines import heyoka_engine as he  # noqa: E402
from andoyer.integrate.engines import heyoka_integrators as hi  # noqa: E402
from andoyer.integrate.engines.base import ALL_KINDS, Section, Tolerance  # noqa: E402
from andoyer.integrate.engines.heyoka_engine import HeyokaEngine  # noqa: E402
from andoyer.kernels.generated.equations import SECTION_KINDS, ep_field, section  # noqa: E402

BODIES = {
    "paper": RigidBody.paper(),  # Hess: A=2.5, B=2.0, C=2.2, mu=0.01
    "general": RigidBody(2.4, 1.9, 1.4, mu=0.5, r=(0.4, -0.3, 0.85)),  # e3 != 0
}
#: Andoyer-Deprit (l, g, L, G, M) with G = 1: rotation- and libration-type orbits.
X0 = np.array([[0.3, 1.1, 0.2, 1.0, -0.4],
               [2.0, 4.0, -0.55, 1.0, 0.3],
               [5.0, 0.4, 0.7, 1.0, 0.05]])
Y0 = from_andoyer(X0)


def params(body: RigidBody) -> tuple[float, ...]:
    phi0 = math.atan2(body.e2, body.e1)  # only enters theta sections (needs e3 = 0)
    return (*body.params, phi0)


TOL12 = Tolerance(1e-12, 1e-12)


def kind(name: str) -> int:
    return SECTION_KINDS.index(name)


def scipy_orbit(body: RigidBody, y0: np.ndarray, t: np.ndarray, **kw):
    return solve_ivp(lambda _, y: ep_field(*y, *body.params), (t[0], t[-1]), y0,
                     method="DOP853", t_eval=t, rtol=1e-13, atol=1e-13, **kw)


def section_values(body: RigidBody, k: int, value: float, y: np.ndarray):
    cv, sv = math.cos(value), math.sin(value)
    f, w = section(k, *np.moveaxis(y, -1, 0), params(body)[7], value, cv, sv)
    return np.asarray(f), np.broadcast_to(w, np.shape(f))


def section_rate(body: RigidBody, k: int, value: float, y: np.ndarray) -> np.ndarray:
    """df/dt along the flow, by a central difference of the generated section function."""
    F = np.moveaxis(np.array(ep_field(*np.moveaxis(y, -1, 0), *body.params)), 0, -1)
    h = 1e-6
    fp, _ = section_values(body, k, value, y + h * F)
    fm, _ = section_values(body, k, value, y - h * F)
    return (fp - fm) / (2 * h)


@pytest.fixture(scope="module")
def engine() -> HeyokaEngine:
    return HeyokaEngine()


# ------------------------------------------------------------------------------ orbits


@pytest.mark.parametrize("name", BODIES)
@pytest.mark.parametrize("batch_size", [1, 4])
def test_agrees_with_scipy_dop853(name: str, batch_size: int) -> None:
    body = BODIES[name]
    t = np.linspace(0.0, 20.0, 41)
    got = HeyokaEngine(batch_size=batch_size).propagate(Y0, t, params(body),
                                                        Tolerance.single(1e-13))
    assert got.shape == (len(Y0), t.size, 6)
    for i, y0 in enumerate(Y0):
        ref = scipy_orbit(body, y0, t)
        assert ref.success
        np.testing.assert_allclose(got[i], ref.y.T, rtol=0, atol=1e-9)


@pytest.mark.parametrize("name", BODIES)
def test_integrals_conserved_over_1e3(engine: HeyokaEngine, name: str) -> None:
    body = BODIES[name]
    t = np.linspace(0.0, 1e3, 201)
    y = engine.propagate(Y0, t, params(body), TOL12)
    for integral in (lambda y: energy(body, y), area_integral, geometric_integral):
        q = integral(y)
        drift = np.abs(q - q[:, :1]) / np.maximum(np.abs(q[:, :1]), 1.0)
        assert drift.max() < 1e-10


def test_scalar_and_batch_agree(engine: HeyokaEngine) -> None:
    body = BODIES["general"]
    t = np.linspace(0.0, 50.0, 11)
    y0 = np.concatenate([Y0, Y0[:2]])  # 5 orbits: one full batch of 4 and a padded one
    scalar = HeyokaEngine(batch_size=1).propagate(y0, t, params(body), TOL12)
    batch = HeyokaEngine(batch_size=4).propagate(y0, t, params(body), TOL12)
    np.testing.assert_allclose(batch, scalar, rtol=0, atol=1e-10)


@pytest.mark.parametrize("batch_size", [1, 4])
def test_first_output_is_the_initial_state(batch_size: int) -> None:
    t = np.array([0.5, 1.0, 2.0])
    eng = HeyokaEngine(batch_size=batch_size)
    y = eng.propagate(Y0, t, params(BODIES["paper"]), TOL12)
    np.testing.assert_array_equal(y[:, 0], Y0)
    np.testing.assert_array_equal(eng.propagate(Y0, t[:1], params(BODIES["paper"]),
                                                TOL12)[:, 0], Y0)


def test_compiled_integrators_are_reused(engine: HeyokaEngine) -> None:
    t = np.linspace(0.0, 1.0, 3)
    engine.propagate(Y0[:1], t, params(BODIES["paper"]), TOL12)
    key = hi.IntegratorKey(1, hi.NO_SECTION, 0, 1e-12)
    slots = list(hi._POOL[key])
    engine.propagate(Y0[:1], t, params(BODIES["general"]), TOL12)
    assert hi._POOL[key] == slots  # same compiled integrator, new body parameters


def test_tolerance_mapping() -> None:
    assert he.tolerance(1e-12, 1e-9) == 1e-12
    assert he.tolerance(1e-8, 1e-13) == 1e-13
    with pytest.raises(ValueError, match="rtol"):
        he.tolerance(0.0, 1e-12)


def test_disk_cache_is_enabled() -> None:
    assert hy.llvm_state.get_diskcache_enabled()


# ------------------------------------------------------------------------------ sections


@pytest.mark.parametrize("name", BODIES)
@pytest.mark.parametrize("direction", [1, -1, 0])
@pytest.mark.parametrize("batch_size", [1, 4])
def test_crossings_on_section_with_direction(name: str, direction: int,
                                             batch_size: int) -> None:
    body = BODIES[name]
    k = kind("G3")
    eng = HeyokaEngine(batch_size=batch_size)
    c = eng.crossings(Y0, params(body), Section.from_kind(k, 0.05, direction), 30, 1e4, TOL12)
    assert c.t.shape == (len(Y0), 30) and c.y.shape == (len(Y0), 30, 6)
    np.testing.assert_array_equal(c.count, 30)
    assert np.all(np.diff(c.t, axis=1) > 0) and np.all(c.t[:, 0] > 0)
    f, _ = section_values(body, k, 0.05, c.y)
    assert np.abs(f).max() <= 1e-12
    rate = section_rate(body, k, 0.05, c.y)
    if direction:
        assert np.all(np.sign(rate) == direction)
    else:  # both directions alternate
        assert np.all(np.sign(rate[:, 1:]) == -np.sign(rate[:, :-1]))


@pytest.mark.parametrize("section_name, value", [("G3", 0.0), ("g", 1.0), ("gamma1", 0.2)])
def test_crossings_match_scipy_events(section_name: str, value: float) -> None:
    """Same crossing times as scipy's event location on the DOP853 dense output: none
    missed, none extra."""
    body = BODIES["general"]
    k = kind(section_name)
    cv, sv = math.cos(value), math.sin(value)
    phi0 = params(body)[7]

    def f(_, y):
        return section(k, *y, phi0, value, cv, sv)[0]

    f.direction = 1  # scipy's event API
    t_max = 100.0
    for y0 in Y0:
        ref = solve_ivp(lambda _, y: ep_field(*y, *body.params), (0.0, t_max), y0,
                        method="DOP853", rtol=1e-13, atol=1e-13, events=f, dense_output=True)
        t_ref = ref.t_events[0]
        w_ref = np.array([section(k, *ref.sol(t), phi0, value, cv, sv)[1] for t in t_ref])
        t_ref = t_ref[(w_ref > 0) & (t_ref > 0)]
        c = HeyokaEngine(batch_size=1).crossings(
            y0[None], params(body), Section.from_kind(k, value, 1), t_ref.size + 5,
            t_max, TOL12)
        assert c.count[0] == t_ref.size
        np.testing.assert_allclose(c.t[0, :t_ref.size], t_ref, rtol=0, atol=1e-8)


@pytest.mark.parametrize("section_name, value", [
    ("g", 0.0), ("g", 2 * math.pi - 1e-3), ("g", 1e-3),
    ("theta2", 0.0), ("theta2", 2 * math.pi - 1e-3), ("theta2", 2 * math.pi)])
def test_angle_sections_no_spurious_wrap_crossing(section_name: str, value: float) -> None:
    body = BODIES["paper"]  # the Hess chart needs e3 = 0
    k = kind(section_name)
    c = HeyokaEngine().crossings(Y0, params(body), Section.from_kind(k, value, 0), 40,
                                 3e3, TOL12)
    assert np.all(c.count > 0)
    y = c.y[~np.isnan(c.t)]
    if section_name == "g":
        angle = to_andoyer(y)[:, 1]
    else:
        angle = to_hess(body, y)[:, 1]
    d = np.angle(np.exp(1j * (angle - value)))  # wrapped to (-pi, pi]
    assert np.abs(d).max() < 1e-9
    f, w = section_values(body, k, value, y)
    assert np.abs(f).max() <= 1e-12 * np.abs(w).max()
    assert np.all(w > 0)


def test_batch_lanes_refilled_agree_with_scalar() -> None:
    """9 orbits through 4 lanes with 2 threads: lanes are refilled as orbits finish.

    The paper's body is close to integrable: round-off differences between the
    scalar and SIMD code grow slowly (the general body at mu = 0.5 is chaotic and
    amplifies them to 1e-6 within t = 500)."""
    body = BODIES["paper"]
    x = np.column_stack([np.linspace(0.1, 6.0, 9), np.linspace(0.3, 5.0, 9),
                         np.linspace(-0.7, 0.7, 9), np.ones(9), np.linspace(-0.5, 0.4, 9)])
    y0 = from_andoyer(x)
    args = (params(body), Section("gamma3", 0.1, 1), 25, 500.0, TOL12)
    scalar = HeyokaEngine(batch_size=1, n_threads=2).crossings(y0, *args)
    batch = HeyokaEngine(batch_size=4, n_threads=2).crossings(y0, *args)
    np.testing.assert_array_equal(batch.count, scalar.count)
    np.testing.assert_allclose(batch.t, scalar.t, rtol=0, atol=1e-9)
    np.testing.assert_allclose(batch.y, scalar.y, rtol=0, atol=1e-9)


def test_stops_after_n_crossings_and_pads_with_nan(engine: HeyokaEngine) -> None:
    body = BODIES["paper"]
    k = kind("G3")
    many = engine.crossings(Y0, params(body), Section.from_kind(k, 0.0, 1), 12, 1e4, TOL12)
    np.testing.assert_array_equal(many.count, 12)
    # between two crossings of each orbit, not on one (a crossing at t_cut itself is a
    # round-off toss-up)
    t_cut = float(np.median(0.5 * (many.t[:, 4] + many.t[:, 5])))
    assert np.min(np.abs(many.t - t_cut)) > 1e-6
    few = engine.crossings(Y0, params(body), Section.from_kind(k, 0.0, 1), 12, t_cut, TOL12)
    expected = (many.t <= t_cut).sum(axis=1)
    np.testing.assert_array_equal(few.count, expected)
    for i, n in enumerate(few.count):
        np.testing.assert_allclose(few.t[i, :n], many.t[i, :n], rtol=1e-13)
        assert np.all(np.isnan(few.t[i, n:])) and np.all(np.isnan(few.y[i, n:]))


def test_initial_state_on_the_section_is_not_a_crossing(engine: HeyokaEngine) -> None:
    body = BODIES["paper"]
    y0 = from_andoyer([0.3, 1.1, 0.0, 1.0, -0.4])  # L = G3 = 0
    c = engine.crossings(y0[None], params(body), Section("G3", 0.0, 0), 3, 1e3, TOL12)
    assert c.t[0, 0] > 1e-3


def test_zero_crossings_and_bad_arguments(engine: HeyokaEngine) -> None:
    p = params(BODIES["paper"])
    c = engine.crossings(Y0, p, Section("G3", 0.0, 1), 0, 10.0, TOL12)
    assert c.t.shape == (3, 0) and c.y.shape == (3, 0, 6) and np.all(c.count == 0)
    with pytest.raises(ValueError, match="kind"):
        engine.crossings(Y0, p, Section.from_kind(len(ALL_KINDS), 0.0, 1), 5, 10.0, TOL12)
    with pytest.raises(ValueError, match="direction"):
        engine.crossings(Y0, p, Section.from_kind(0, 0.0, 2), 5, 10.0, TOL12)
    with pytest.raises(ValueError, match="t_max"):
        engine.crossings(Y0, p, Section.from_kind(0, 0.0, 1), 5, -1.0, TOL12)
    with pytest.raises(ValueError, match="params"):
        engine.propagate(Y0, np.array([0.0, 1.0]), p[:7], TOL12)


@pytest.mark.parametrize("scalar", [False, True])
def test_both_heyoka_forms_of_the_field_equal_the_generated_field(scalar):
    """The scalar integrators' rewritten field (``taylor_form``) and the batch one
    (``from_sympy``) are the field (1): compiled, at random states and bodies."""
    from andoyer.integrate.engines.heyoka_symbolic import heyoka_state_vars, heyoka_system

    cf = hy.cfunc([rhs for _, rhs in heyoka_system(scalar=scalar)], list(heyoka_state_vars()))
    rng = np.random.default_rng(7)
    Y = rng.normal(size=(6, 40))
    P = rng.uniform(0.2, 1.5, size=(cf.nparams, 40))
    got = np.asarray(cf(Y, pars=P))
    want = np.array(ep_field(*Y, *P[:7]))
    assert np.allclose(got, want, rtol=1e-13, atol=1e-14)


@pytest.mark.parametrize("body", [RigidBody(2.4, 1.9, 1.4, mu=0.5, r=(0.4, -0.3, 0.85)),
                                  RigidBody.paper(),  # e3 = 0: the e3 terms left out
                                  RigidBody(2.0, 2.0, 1.0, mu=0.3, r=(0.0, 0.0, 1.0))])
def test_the_fli_system_is_the_field_and_its_jacobian(body):
    """The 12-variable system of the FLI maps (body coefficients as runtime parameters,
    the vanishing ones left out) is ``(f(y), J(y) w)`` of the generated kernels,
    compiled, at random states and tangent vectors; ``zero`` lists what vanishes."""
    from andoyer.integrate.engines.heyoka_symbolic import (
        coefficient_tangent_system,
        coefficient_values,
        heyoka_state_vars,
    )
    from andoyer.kernels.generated.equations import ep_jacobian

    values = coefficient_values(body.engine_params)
    zero = frozenset(np.flatnonzero(values == 0.0).tolist())
    system = coefficient_tangent_system(zero)
    variables = [v for v, _ in system]
    assert [str(v) for v in variables[:6]] == [str(v) for v in heyoka_state_vars()]
    cf = hy.cfunc([rhs for _, rhs in system], variables)
    rng = np.random.default_rng(3)
    Y = rng.normal(size=(12, 30))
    P = np.repeat(values[:cf.nparams, None], 30, axis=1)
    got = np.asarray(cf(Y, pars=P))
    params = body.params
    J = np.array(ep_jacobian(*Y[:6], *params), dtype=object)
    Jw = np.array([sum(np.broadcast_to(J[6 * i + j], (30,)) * Y[6 + j] for j in range(6))
                   for i in range(6)], dtype=float)
    np.testing.assert_allclose(got[:6], np.array(ep_field(*Y[:6], *params)), rtol=1e-13,
                               atol=1e-14)
    np.testing.assert_allclose(got[6:], Jw, rtol=1e-13, atol=1e-14)
    # The Hess body has e3 = 0, the symmetric top a = b and e1 = e2 = 0: their terms
    # vanish and are left out of the compiled code.
    assert (len(zero) > 0) == (body.e3 == 0.0 or body.A == body.B)
