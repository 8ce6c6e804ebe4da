"""The Taylor kernel (:mod:`andoyer.kernels.taylor.flow`) against independent routes.

* jets: the order-1 coefficient is the generated field; higher orders equal the Lie
  series of the SymPy field (repeated Lie derivatives, exact rationals); tangent jets
  equal central differences of state jets (the field is quadratic: exact up to
  round-off); section jets equal the Taylor coefficients (mpmath, 40 digits) of the
  SymPy section function along the state's polynomial;
* the order of one step: the error of a single step of order p scales as h^(p+1);
* tolerance proportionality: the error after t = 20 scales as the tolerance;
* orbits and crossings against the Numba DOP853 at a tight tolerance; two crossings
  inside one Taylor step are both found; the tangent flow against the DOP853
  fundamental matrix; the tangent vectors at crossings;
* a second process loads the compiled entry points from Numba's cache.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import sympy as sp
from numpy.typing import NDArray

from _numba_cache import fresh_process_cache_stats, fresh_process_compiles
from andoyer import RigidBody, from_andoyer
from andoyer.kernels import common
from andoyer.kernels.dop853 import flow as dop853
from andoyer.kernels.dop853 import tangent as DT
from andoyer.kernels.generated import equations
from andoyer.kernels.taylor import flow as T
from andoyer.kernels.taylor import sections
from andoyer.symbolic import hamiltonian as sym
from andoyer.symbolic import sections as sec

MAX_STEPS = 10**7
KIND = {name: i for i, name in enumerate(equations.SECTION_KINDS + equations.EXTRA_SECTION_KINDS)}


def params(body: RigidBody) -> NDArray[np.float64]:
    return np.asarray(body.engine_params, dtype=float)


@pytest.fixture(scope="module")
def general() -> RigidBody:
    return RigidBody(1.3, 1.7, 2.1, mu=0.5, r=(0.3, -0.5, 0.8))


def state(x: list[float]) -> NDArray[np.float64]:
    return np.ascontiguousarray(from_andoyer([x]).reshape(6))


Y0 = [0.3, 1.1, 0.2, 1.0, -0.4]


def test_order_one_coefficient_is_the_field(general: RigidBody) -> None:
    p = params(general)
    rng = np.random.default_rng(1)
    for _ in range(5):
        y = rng.normal(size=6)
        X = T.jet(y, p, 6)
        f = np.array(equations.ep_field(*y, *p[:7]))
        np.testing.assert_allclose(X[0, 1], f, rtol=1e-15, atol=1e-15)
        np.testing.assert_array_equal(X[0, 0], y)


def test_jets_are_the_lie_series_of_the_sympy_field(general: RigidBody) -> None:
    """x^[k] = (L_f^k x) / k! with L_f g = grad g . f, in exact rationals."""
    order = 6
    body = dict(zip(sym.S.body, (sp.Rational(str(v)) for v in params(general)[:7]),
                    strict=True))
    f = [e.subs(body) for e in sym.euler_poisson_field()]
    y = np.array([0.3, -0.7, 1.1, 0.6, 0.0, -0.8])
    point = dict(zip(sym.S.y, (sp.Rational(str(v)) for v in y), strict=True))
    X = T.jet(y, params(general), order)[0]
    for i, xi in enumerate(sym.S.y):
        g = xi
        for k in range(1, order + 1):
            g = sp.expand(sum(sp.diff(g, v) * fv for v, fv in zip(sym.S.y, f, strict=True)))
            exact = float(g.subs(point) / math.factorial(k))
            assert X[k, i] == pytest.approx(exact, rel=1e-13, abs=1e-14), (k, i)


def test_tangent_jets_are_derivatives_of_state_jets(general: RigidBody) -> None:
    p = params(general)
    rng = np.random.default_rng(2)
    y, w = rng.normal(size=6), rng.normal(size=6)
    X = T.jet(np.concatenate([y, w]), p, 12)
    eps = 1e-5
    fd = (T.jet(y + eps * w, p, 12)[0] - T.jet(y - eps * w, p, 12)[0]) / (2 * eps)
    scale = np.abs(X[1]).max(axis=1, keepdims=True) + 1.0
    assert np.max(np.abs(X[1] - fd) / scale) < 1e-8
    np.testing.assert_allclose(X[0], T.jet(y, p, 12)[0], rtol=0, atol=0)


@pytest.mark.parametrize("name", ["G3", "G", "J1", "l", "g", "theta1", "theta2", "psi"])
def test_section_jets_are_the_taylor_coefficients_of_f(name: str, general: RigidBody) -> None:
    """The tape's jet of f = the Taylor coefficients of f(x(t)) along the state's
    polynomial (mpmath.taylor, 40 digits, on the SymPy expression)."""
    order = 10
    p = params(general)
    value = 0.4 if name not in ("G", "J1") else 1.2
    y = np.array([0.3, -0.7, 1.1, 0.6, 0.2, -0.8])
    x = T.jet(y, p, order)[0]
    tape, C = sections.section_tape(KIND[name], p[7], value)
    s = sections.section_jet(tape, C, np.ascontiguousarray(x), order)
    f_expr = sec.section_function(name)[0]
    args = [*sec.SECTION_ARGS]
    fn = sp.lambdify(args, f_expr, "mpmath")
    with mpmath.workdps(40):
        poly = [[mpmath.mpf(float(x[k, i])) for k in range(order + 1)] for i in range(6)]

        def along(t: mpmath.mpf) -> mpmath.mpf:
            yt = [mpmath.polyval(c[::-1], t) for c in poly]
            return fn(*yt, mpmath.mpf(float(p[7])), mpmath.mpf(value),
                      mpmath.cos(value), mpmath.sin(value))

        ref = mpmath.taylor(along, 0, order)
    ref = np.array([float(r) for r in ref])
    np.testing.assert_allclose(s, ref, rtol=1e-11, atol=1e-12 * np.abs(ref).max())
    margin, wC = sections.section_tape(KIND[name], p[7], value, margin=True)
    w = sections.section_jet(margin, wC, np.ascontiguousarray(x), 0)[0]
    assert w == pytest.approx(equations.section(KIND[name], *y, p[7], value, math.cos(value),
                                                math.sin(value))[1], rel=1e-14, abs=1e-15)


def test_single_step_error_scales_as_h_to_the_order_plus_one(general: RigidBody) -> None:
    """One step of the order-p polynomial: error ~ C h^(p+1) (slope of log error)."""
    p = params(general)
    y = state(Y0)
    order = 4
    X = T.jet(y, p, order)[0]
    hs = np.array([0.02, 0.04, 0.08, 0.16])
    ref, _ = dop853.propagate(y[None], np.concatenate([[0.0], hs]), p, 1e-14, 1e-14,
                              MAX_STEPS)
    err = []
    for m, h in enumerate(hs):
        approx = sum(X[k] * h**k for k in range(order + 1))
        err.append(np.max(np.abs(approx - ref[0, m + 1])))
    slope = np.polyfit(np.log(hs), np.log(err), 1)[0]
    assert slope == pytest.approx(order + 1, abs=0.3)


def test_error_is_proportional_to_the_tolerance(general: RigidBody) -> None:
    p = params(general)
    y = state(Y0)[None]
    t = np.array([0.0, 20.0])
    ref, _ = dop853.propagate(y, t, p, 1e-14, 1e-14, MAX_STEPS)
    tols = np.array([1e-6, 1e-7, 1e-8, 1e-9, 1e-10])
    err = []
    for tol in tols:
        out, info = T.propagate(y, t, p, tol, MAX_STEPS)
        assert info[0, 0] == common.SUCCESS
        err.append(np.max(np.abs(out[0, -1] - ref[0, -1])))
    slope = np.polyfit(np.log(tols), np.log(err), 1)[0]
    assert 0.7 < slope < 1.3
    assert max(e / tol for e, tol in zip(err, tols, strict=True)) < 100.0


@pytest.mark.parametrize("mu", [0.01, 0.5])
def test_orbits_agree_with_dop853(mu: float) -> None:
    body = RigidBody(2.5, 2.0, 2.2, mu=mu, r=(0.3, 0.5, 0.2))
    p = params(body)
    y0 = np.ascontiguousarray(from_andoyer([Y0, [1.0, 2.0, -0.5, 1.0, 0.3]]))
    t = np.linspace(0.0, 200.0, 41)
    out, info = T.propagate(y0, t, p, 1e-12, MAX_STEPS)
    ref, _ = dop853.propagate(y0, t, p, 1e-14, 1e-14, MAX_STEPS)
    assert (info[:, 0] == common.SUCCESS).all()
    assert np.max(np.abs(out - ref)) < 1e-10


def test_output_times_hit_exactly_and_repeat() -> None:
    p = params(RigidBody.paper())
    y0 = state(Y0)[None]
    t = np.array([0.0, 0.0, 0.5, 0.5, 3.0])
    out, _ = T.propagate(y0, t, p, 1e-12, MAX_STEPS)
    np.testing.assert_array_equal(out[0, 1], y0[0])
    np.testing.assert_array_equal(out[0, 2], out[0, 3])


@pytest.mark.parametrize("name,value", [("G3", 0.0), ("theta2", 0.3), ("g", 1.0), ("G", 1.0),
                                        ("psi", 0.5)])
@pytest.mark.parametrize("direction", [1, -1, 0])
def test_crossings_agree_with_dop853(name: str, value: float, direction: int) -> None:
    """On the paper's body (regular orbits: no chaos amplifying the round-off)."""
    p = params(RigidBody.paper())
    y0 = np.ascontiguousarray(from_andoyer([Y0, [1.0, 2.0, -0.5, 1.0, 0.3]]))
    tc, yc, count, info = T.locate_crossings(y0, p, KIND[name], value, direction, 12, 1e4,
                                             1e-12, MAX_STEPS)
    rt, ry, rcount, _ = dop853.locate_crossings(y0, p, KIND[name], value, direction, 12, 1e4,
                                                1e-14, 1e-14, MAX_STEPS)
    assert (info[:, 0] == common.SUCCESS).all()
    np.testing.assert_array_equal(count, rcount)
    if not count.any():  # the angles theta2 and g only increase here
        assert name in ("theta2", "g") and direction == -1
        return
    assert np.nanmax(np.abs(tc - rt)) < 1e-9
    assert np.nanmax(np.abs(yc - ry)) < 1e-9
    for i in range(2):
        for j in range(count[i]):
            f, w = equations.section(KIND[name], *yc[i, j], p[7], value, math.cos(value),
                                     math.sin(value))
            assert abs(f) < 1e-13 and w > 0


def test_two_crossings_inside_one_step() -> None:
    """A section just below the top of G3: the orbit dips through it and back within a
    small part of one Taylor step; both crossings are found, in time order."""
    body = RigidBody.paper()
    p = params(body)
    y0 = state(Y0)[None]
    t = np.linspace(0.0, 40.0, 40001)
    ref, _ = dop853.propagate(y0, t, p, 1e-13, 1e-13, MAX_STEPS)
    top = int(np.argmax(ref[0, :, 2]))
    value = ref[0, top, 2] - 1e-9  # the two roots are ~1e-4 apart in time
    tc, yc, count, info = T.locate_crossings(y0, p, KIND["G3"], value, 0, 50, t[-1], 1e-12,
                                             MAX_STEPS)
    steps = info[0, 1] / t[-1]
    near = np.flatnonzero(np.abs(tc[0, :count[0]] - t[top]) < 0.01)
    assert near.size == 2 and 1 / steps > 100 * np.ptp(tc[0, near])
    assert yc[0, near[0], 2] == pytest.approx(value, abs=1e-12)
    rt, _, rcount, _ = dop853.locate_crossings(y0, p, KIND["G3"], value, 0, 50, t[-1], 1e-14,
                                               1e-14, MAX_STEPS)
    np.testing.assert_allclose(tc[0, :count[0]], rt[0, :rcount[0]], atol=1e-7)
    assert np.all(np.diff(tc[0, :count[0]]) > 0)


def test_tangent_flow_is_the_fundamental_matrix(general: RigidBody) -> None:
    """Six tangent vectors from the identity = DOP853's fundamental matrix."""
    p = params(general)
    y0 = state(Y0)
    z0 = np.concatenate([y0, np.eye(6).ravel()])[None]
    t = np.array([0.0, 5.0, 20.0])
    z, info = T.propagate(z0, t, p, 1e-13, MAX_STEPS)
    assert info[0, 0] == common.SUCCESS
    u0 = np.zeros(common.dimension(6))
    L = common.layout(6)
    u0[L["y"]] = y0
    u0[L["u"]] = np.eye(6).ravel()
    ref, _ = DT.propagate(u0[None], t, p, 1e-13, 1e-13, MAX_STEPS)
    W = np.exp(ref[0, :, L["rho"]])[..., None] * ref[0, :, L["u"]].reshape(3, 6, 6)
    np.testing.assert_allclose(z[0, :, :6], ref[0, :, :6], atol=1e-10)
    scale = np.abs(W).max(axis=(1, 2), keepdims=True)
    assert np.max(np.abs(z[0, :, 6:].reshape(3, 6, 6) - W) / scale) < 1e-9


def test_tangent_vectors_at_crossings(general: RigidBody) -> None:
    """The tangent state at a crossing is the propagated one at the crossing time."""
    p = params(general)
    y0 = state(Y0)
    z0 = np.concatenate([y0, np.eye(6)[:2].ravel()])[None]
    tc, zc, count, info = T.locate_crossings(z0, p, KIND["theta2"], 0.0, 0, 3, 500.0, 1e-13,
                                             MAX_STEPS)
    assert count[0] == 3
    z, _ = T.propagate(z0, np.concatenate([[0.0], tc[0]]), p, 1e-13, MAX_STEPS)
    scale = np.abs(z[0, 1:]).max(axis=1, keepdims=True)
    assert np.max(np.abs(z[0, 1:] - zc[0]) / scale) < 1e-9


def test_non_finite_state_fails() -> None:
    p = params(RigidBody.paper())
    y0 = state(Y0)[None].copy()
    y0[0, 0] = np.nan
    out, info = T.propagate(y0, np.array([0.0, 1.0]), p, 1e-12, MAX_STEPS)
    assert info[0, 0] == common.STEP_TOO_SMALL and np.isnan(out[0, 1]).all()
    _, _, count, info = T.locate_crossings(y0, p, 2, 0.0, 1, 3, 10.0, 1e-12, MAX_STEPS)
    assert info[0, 0] == common.STEP_TOO_SMALL and count[0] == 0


def test_max_steps() -> None:
    p = params(RigidBody.paper())
    out, info = T.propagate(state(Y0)[None], np.array([0.0, 100.0]), p, 1e-12, 3)
    assert info[0, 0] == common.MAX_STEPS and info[0, 1] == 3


def test_order_for() -> None:
    assert T.order_for(1e-12) == 15
    assert T.order_for(1e-300) == T.MAX_ORDER
    assert T.order_for(0.5) == T.MIN_ORDER
    with pytest.raises(ValueError, match="6 \\+ 6 k"):
        T.n_vectors(13)


def test_second_process_loads_from_the_cache() -> None:
    p = params(RigidBody.paper()).tolist()
    y0 = state(Y0)[None]
    T.propagate(y0, np.array([0.0, 1.0]), np.array(p), 1e-12, MAX_STEPS)
    T.locate_crossings(y0, np.array(p), 2, 0.0, 1, 1, 50.0, 1e-12, MAX_STEPS)
    y = y0.tolist()
    g3_block = f"CROSSINGS_BLOCKS[(False, {sections.COMPONENT})]"  # G3 (kind 2)'s family
    out = fresh_process_cache_stats("andoyer.kernels.taylor.flow", {
        "propagate_block": f"m.propagate(np.array({y}), np.array([0.0, 1.0]), np.array({p}), "
                           f"1e-12, {MAX_STEPS})",
        g3_block: f"m.locate_crossings(np.array({y}), np.array({p}), 2, 0.0, 1, 1, 50.0, "
                  f"1e-12, {MAX_STEPS})"})
    assert out["misses"] == [0, 0] and out["hits"] == [1, 1]


W4_CALLS = """
from andoyer import RigidBody, from_andoyer
from andoyer.integrate import Section, poincare, propagate
body = RigidBody.paper()
y0 = from_andoyer([[0.3, 1.1, 0.2, 1.0, -0.4], [1.0, 2.0, 0.5, 0.8, 0.3]])
propagate(body, y0[0], np.linspace(0.0, 50.0, 11), engine="taylor", progress=False)
poincare(body, y0, Section("G3", 0.0, 1), 3, engine="taylor", progress=False)
"""


def test_a_second_process_compiles_nothing() -> None:
    # W4's second process (the start-up target: <= 0.5 s): with the on-disk cache warm,
    # a process's first propagate and poincare on taylor load machine code and compile
    # nothing at all -- no entry point (the test above), and nothing else on the way: a
    # Numba function called from Python without a cache, an entry point whose cache key
    # changes with each process, a helper compiled on its own.
    exec(W4_CALLS, {"np": np})  # this process warms the cache (or already has)
    assert fresh_process_compiles(W4_CALLS) == []


def test_a_cold_component_section_compiles_its_family_only(tmp_path) -> None:
    # Each family of section tapes has its own loop and entry point: a G3 section on an
    # empty cache compiles the component loop and none of the angle sections' jets.
    import os

    env = {**os.environ, "ANDOYER_CACHE_DIR": str(tmp_path)}
    env.pop("NUMBA_CACHE_DIR", None)
    p = params(RigidBody.paper()).tolist()
    names = fresh_process_compiles(
        "from andoyer.kernels.taylor import flow as m\n"
        f"m.locate_crossings(np.array([{state(Y0).tolist()}]), np.array({p}), "
        f"{KIND['G3']}, 0.0, 1, 2, 50.0, 1e-12, {MAX_STEPS})\n", env=env)
    assert any(n.endswith("section_loops.<locals>.crossings_from__state_jets_component")
               for n in names), names
    assert "linear_component" in names
    for other in ("pair_jet", "product_pair", "tape_jet", "section_step_size"):
        assert other not in names, other


def test_kernel_helpers_compile_once_and_refuse_python_calls() -> None:
    # A helper of the kernels has no Python entry (kernel_jit): a call from Python is a
    # TypeError, not a jump into a missing wrapper. tape_value evaluates the tape as a jet
    # of order len(Y) - 1: a literal 0 there compiled tape_jet a second time, for
    # Literal[int](0) (0.3 s of every cold first section).
    import numba

    S = sections

    with pytest.raises(TypeError, match="compiled kernels only"):
        S.poly(np.ones(3), 2, 0.5)
    tape, C = sections.section_tape(2, 0.0, 0.1)

    @numba.njit
    def g3(tape: NDArray[np.int64], C: NDArray[np.float64], y: NDArray[np.float64]) -> float:
        Y = np.empty((1, 6))
        Y[0] = y
        return float(S.tape_value(tape, C, Y, np.empty((tape.shape[0], 1))))

    @numba.njit
    def g3_jet(tape: NDArray[np.int64], C: NDArray[np.float64], Y: NDArray[np.float64]
               ) -> float:
        u = np.empty((tape.shape[0], Y.shape[0]))
        S.tape_jet(tape, C, Y, Y.shape[0] - 1, u)  # the kernels' call: the order a variable
        return float(u[tape.shape[0] - 1, 0])

    y = state(Y0)
    assert g3(tape, C, y) == y[2] - 0.1
    # tape_value no longer goes through tape_jet (its own loop at order 0): compile
    # tape_jet here, as the kernels call it, since a process that loads the kernels from
    # the cache compiles no helper at all (the no-heyoka CI job found the set empty)
    X = np.zeros((4, 6))
    X[0] = y
    assert g3_jet(tape, C, X) == y[2] - 0.1
    orders = {str(sig[3]) for sig in S.tape_jet.signatures}
    assert orders == {"int64"}, orders
