"""The SIMD-lane Taylor kernel (:mod:`andoyer.kernels.taylor.lanes`) against the scalar one.

* the lane jets (generated ``ep_taylor_jet_lanes``/``ep_taylor_tangent_jet_lanes``,
  compiled with the vector intrinsics of :mod:`andoyer.kernels.taylor.simd`) equal the scalar
  jets of :func:`andoyer.kernels.taylor.flow.jet` lane by lane, to round-off, on random
  states and states near the Andoyer chart's singular sets;
* orbits: every orbit of a lane run takes the scalar kernel's steps (``info`` equal,
  row by row) and reaches the same states to round-off; against the Numba DOP853 to
  the tolerance's level; threads and blocks change no bit;
* failures are per orbit, with the scalar kernel's statuses: a non-finite state
  (``STEP_TOO_SMALL``), ``max_steps`` (``MAX_STEPS``) beside orbits that succeed;
* queue edge cases: fewer orbits than lanes, none, one output time, repeated initial
  times.
"""

from __future__ import annotations

from collections.abc import Callable
from types import ModuleType

import numba
import numpy as np
import pytest
from numpy.typing import NDArray

from _chart_points import andoyer_points
from _numba_cache import fresh_process_cache_stats
from andoyer import RigidBody, from_andoyer
from andoyer.kernels import common, simd
from andoyer.kernels.dop853 import flow as dop853
from andoyer.kernels.taylor import flow as T
from andoyer.kernels.taylor import lanes as TL
from andoyer.kernels.taylor.jets import fill_constants

L = TL.LANES
ORDER = 15  # order_for(1e-12)


@pytest.fixture(scope="module")
def body() -> RigidBody:
    return RigidBody(1.3, 1.7, 2.1, mu=0.5, r=(0.3, -0.5, 0.8))


def states(n: int, seed: int) -> NDArray[np.float64]:
    """Random states, a third of them near the chart's singular sets (|L| = G, |H| = G)."""
    rng = np.random.default_rng(seed)
    P = andoyer_points(n, rng)
    return np.ascontiguousarray(from_andoyer(P))


@numba.njit
def _lane_jets(X, p, order):  # noqa: ANN001, ANN202 - a compiled test helper
    q = np.empty(12)
    fill_constants(p, q)
    m = np.empty((TL._P, TL.LANES))
    TL.lane_jets(X, order, q, m)


def test_lane_jets_equal_the_scalar_jets(body: RigidBody) -> None:
    p = np.asarray(body.engine_params, dtype=float)
    rng = np.random.default_rng(3)
    worst = 0.0
    for k in (0, 1, 2):
        y = states(L, 10 + k)
        z = np.concatenate([y, rng.normal(size=(L, 6 * k))], axis=1)
        X = np.zeros((1 + k, ORDER + 1, 6, L))
        X[:, 0] = z.reshape(L, 1 + k, 6).transpose(1, 2, 0)
        _lane_jets(X, p, ORDER)
        for lane in range(L):
            ref = T.jet(np.ascontiguousarray(z[lane]), p, ORDER)
            got = X[..., lane]
            scale = np.max(np.abs(ref), axis=2, keepdims=True)  # per block and order
            worst = max(worst, float(np.max(np.abs(got - ref) / scale)))
    assert worst < 1e-14, worst


def test_simd_fallbacks_equal_the_compiled_intrinsics() -> None:
    rng = np.random.default_rng(4)
    u = rng.normal(size=(6, 6, L))
    v = rng.normal(size=(6, 6, L))
    products = (0, 1, 2, 1, 5, 0, 2, 3, 3)

    @numba.njit
    def compiled(m, u, v, k):  # noqa: ANN001, ANN202
        simd.cauchy(m, u, v, k, (0, 1, 2, 1, 5, 0, 2, 3, 3))
        simd.combine(u, m, k, (2.0, -0.5),
                     (0, 0, 0, 0, 0, 1, 5, 1, 1, 0, 1, 1, 2, 0, 2, 0, 3, 1, 3, 0, 4, 1, 4, 1,
                      5, 1, 0, 0))

    for k in range(5):
        m0 = np.zeros((3, L))
        m1 = np.zeros((3, L))
        u1 = u.copy()
        compiled(m0, u, v, k)
        simd.cauchy(m1, u1, v, k, products)
        simd.combine(u1, m1, k, (2.0, -0.5), (0, 0, 0, 0, 0, 1, 5, 1, 1, 0, 1, 1, 2, 0, 2, 0,
                                               3, 1, 3, 0, 4, 1, 4, 1, 5, 1, 0, 0))
        np.testing.assert_allclose(m0, m1, rtol=1e-14, atol=1e-14)
        np.testing.assert_allclose(u, u1, rtol=1e-14, atol=1e-14)
        assert m0[1, 3] == pytest.approx(sum(u[j, 5, 3] * v[k - j, 0, 3] for j in range(k + 1)))


def test_section_tape_intrinsics_equal_their_fallbacks() -> None:
    """The tape's product node at every order count around the groups of four orders
    (0 .. 9, 15, 19), its linear node with one and two terms."""
    rng = np.random.default_rng(8)

    @numba.njit
    def compiled(U, S, order):  # noqa: ANN001, ANN202
        simd.series_product(U, 3, 1, 2, order)
        for k in range(order + 1):
            simd.series_linear(U, 4, S, 5, 0.5, 2, -2.0, k)
            simd.series_linear(U, 5, U, 3, 3.0, -1, 0.0, k)

    for order in (*range(10), 15, 19):
        U = rng.normal(size=(order + 1, 8, L))
        S = rng.normal(size=(order + 1, 6, L))
        V = U.copy()
        compiled(U, S, order)
        simd.series_product(V, 3, 1, 2, order)
        for k in range(order + 1):
            simd.series_linear(V, 4, S, 5, 0.5, 2, -2.0, k)
            simd.series_linear(V, 5, V, 3, 3.0, -1, 0.0, k)
        np.testing.assert_allclose(U, V, rtol=1e-13, atol=1e-13)
        k = order
        assert U[k, 3, L - 1] == pytest.approx(sum(U[j, 1, L - 1] * U[k - j, 2, L - 1]
                                                   for j in range(k + 1)))


@pytest.mark.parametrize("order", [15, 14, 5])
def test_lane_tape_jets_are_the_scalar_tapes_to_round_off(order: int) -> None:
    """``lane_sections.lane_tape_jet`` against ``sections.tape_jet`` lane by lane, for
    every section kind's function tape (the square root's of ``G``, ``J1``, ``J2`` and
    the angles' included), on state jets with ``|G|`` from 1e-6 to 2: every coefficient
    within 1e-13 of the jet's scale ``max_k |f^[k]| r^k`` (r = 1/2). A square root summed
    in another order than the scalar one, or with a term twice, is off by far more."""
    from andoyer.kernels.generated import recurrences
    from andoyer.kernels.taylor import sections as S
    from andoyer.kernels.taylor.lane_sections import lane_tape_jet

    @numba.njit
    def lanes_jet(tape, C, x, order):  # noqa: ANN001, ANN202
        U = np.zeros((order + 1, tape.shape[0], L))
        lane_tape_jet(tape, C, x, order, U)
        return U[:, tape.shape[0] - 1, :].copy()

    rng = np.random.default_rng(36)
    r = 0.5 ** np.arange(order + 1)
    worst = 0.0
    for kind in range(len(recurrences.SECTION_TAPES)):
        tape, C = S.section_tape(kind, rng.uniform(-3, 3), rng.uniform(-1, 1))
        x = rng.normal(size=(order + 1, 6, L)) * r[:, None, None]
        G = rng.normal(size=(3, L))
        x[0, :3] = G * np.logspace(-6, np.log10(2.0), L) / np.linalg.norm(G, axis=0)
        x[0, 3:] /= np.linalg.norm(x[0, 3:], axis=0)
        got = lanes_jet(tape, C, np.ascontiguousarray(x), order)
        for lane in range(L):
            ref = S.section_jet(tape, C, np.ascontiguousarray(x[:, :, lane]), order)
            scale = float(np.max(np.abs(ref) * r))
            err = float(np.max(np.abs(got[:, lane] - ref) * r))
            worst = max(worst, err / scale)
            assert err <= 1e-13 * scale, (kind, lane, err, scale)
    assert worst < 1e-13


@pytest.mark.parametrize("k", [0, 1, 2])
def test_orbits_take_the_scalar_steps(body: RigidBody, k: int) -> None:
    p = np.asarray(body.engine_params, dtype=float)
    n = 3 * L + 5  # lanes refilled, a partial last round
    y = states(n, 20 + k)
    z = np.ascontiguousarray(np.concatenate(
        [y, np.random.default_rng(5).normal(size=(n, 6 * k))], axis=1))
    t = np.linspace(0.0, 30.0, 7)
    ref, ref_info = T.propagate(z, t, p, 1e-12, 10**6)
    got, info = TL.propagate(z, t, p, ORDER, 10**6, threads=1)
    np.testing.assert_array_equal(info, ref_info)
    scale = 1.0 + np.abs(ref)
    assert np.max(np.abs(got - ref) / scale) < 1e-11
    # blocks and threads change nothing
    again, info2 = TL.propagate(z, t, p, ORDER, 10**6, block=L + 3, threads=2)
    np.testing.assert_array_equal(again, got)
    np.testing.assert_array_equal(info2, info)
    assert len(TL.block_starts(n, 2)) > 1
    guided, info3 = TL.propagate(z, t, p, ORDER, 10**6, threads=2)  # the guided blocks
    np.testing.assert_array_equal(guided, got)
    np.testing.assert_array_equal(info3, info)


def test_guided_blocks_cover_the_orbits_and_shrink() -> None:
    for n, m in [(1, 2), (2 * L, 2), (1000, 2), (4099, 3), (50, 1)]:
        starts = TL.block_starts(n, m)
        sizes = np.diff([*starts, n])
        assert starts[0] == 0 and np.all(sizes > 0) and sizes.sum() == n
        assert np.all(sizes[:-1] >= 2 * L)  # at least two orbits per lane
        assert np.all(np.diff(sizes[:-1]) <= 0)  # shorter as the orbits run out
    assert TL.block_starts(1024, 2)[1] == 256  # a thread's share of half the orbits


def test_orbits_agree_with_dop853(body: RigidBody) -> None:
    p = np.asarray(body.engine_params, dtype=float)
    y = states(2 * L + 1, 30)
    t = np.linspace(0.0, 10.0, 5)
    got, info = TL.propagate(y, t, p, ORDER, 10**6)
    assert np.all(info[:, 0] == common.SUCCESS)
    ref, ref_info = dop853.propagate(y, t, p, 1e-13, 1e-13, 10**7)
    assert np.all(ref_info[:, 0] == common.SUCCESS)
    assert np.max(np.abs(got - ref) / (1.0 + np.abs(ref))) < 1e-9


def test_failures_are_per_orbit(body: RigidBody) -> None:
    p = np.asarray(body.engine_params, dtype=float)
    n = 2 * L + 3
    z = np.ascontiguousarray(np.concatenate(
        [states(n, 40), np.random.default_rng(6).normal(size=(n, 6))], axis=1))
    z[3, 0] = np.nan
    z[L + 4, 7] = np.inf  # a tangent vector
    t = np.linspace(0.0, 20.0, 5)
    ref, ref_info = T.propagate(z, t, p, 1e-12, 10**6)
    got, info = TL.propagate(z, t, p, ORDER, 10**6, threads=1)
    np.testing.assert_array_equal(info, ref_info)
    assert info[3, 0] == info[L + 4, 0] == common.STEP_TOO_SMALL
    assert np.sum(info[:, 0] != common.SUCCESS) == 2
    np.testing.assert_array_equal(np.isnan(got), np.isnan(ref))
    # max_steps: orbits needing more steps than allowed fail, the others do not
    limit = int(np.median(ref_info[:, 1]))
    ref, ref_info = T.propagate(z, t, p, 1e-12, limit)
    got, info = TL.propagate(z, t, p, ORDER, limit, threads=1)
    np.testing.assert_array_equal(info, ref_info)
    assert np.any(info[:, 0] == common.MAX_STEPS) and np.any(info[:, 0] == common.SUCCESS)
    ok = info[:, 0] == common.SUCCESS
    assert np.max(np.abs(got[ok] - ref[ok]) / (1.0 + np.abs(ref[ok]))) < 1e-11
    np.testing.assert_array_equal(np.isnan(got), np.isnan(ref))
    # no step at all allowed
    _, info = TL.propagate(z, t, p, ORDER, 0)
    assert np.all(info[:, 0] == common.MAX_STEPS)


def test_a_second_process_loads_the_lane_kernel(body: RigidBody) -> None:
    """After this process compiled (or loaded) it, a new process pays no compile, for
    states alone and with a tangent vector alike (one specialisation)."""
    p = np.asarray(body.engine_params, dtype=float).tolist()
    TL.propagate(states(L, 70), np.array([0.0, 1.0]), np.array(p), ORDER, 10**6)
    y = states(L, 70).tolist()
    z = np.concatenate([states(L, 70), np.ones((L, 6))], axis=1).tolist()
    out = fresh_process_cache_stats("andoyer.kernels.taylor.lanes", {
        "lanes_block": f"m.propagate(np.array({y}), np.array([0.0, 1.0]), np.array({p}), "
                       f"{ORDER}, 10**6); m.propagate(np.array({z}), np.array([0.0, 1.0]), "
                       f"np.array({p}), {ORDER}, 10**6)"})
    assert out["misses"] == [0] and out["hits"] == [1]


@pytest.mark.parametrize("n", [0, 1, L - 1, L])
def test_queue_edges(body: RigidBody, n: int) -> None:
    p = np.asarray(body.engine_params, dtype=float)
    y = states(max(n, 1), 50)[:n]
    for t in (np.array([0.0]), np.array([0.0, 0.0, 0.0]), np.array([0.0, 0.0, 2.0, 2.0, 5.0])):
        ref, ref_info = T.propagate(y, t, p, 1e-12, 10**6)
        got, info = TL.propagate(y, t, p, ORDER, 10**6)
        np.testing.assert_array_equal(info, ref_info)
        assert got.shape == ref.shape
        np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-12)


def test_the_taylor_engine_runs_many_orbits_on_lanes(
        body: RigidBody, monkeypatch: pytest.MonkeyPatch,
        orbits_per_call: Callable[[ModuleType, str], list[int]]) -> None:
    """The engine's routes (``propagate``; ``tangent`` without renormalisation, the FLI
    map's) on lanes agree per orbit with the same engine on the scalar kernel and with
    the numba engine; a failed orbit is flagged alone."""
    from andoyer.integrate.engines import taylor_engine as TE
    from andoyer.integrate.engines.base import Tolerance
    from andoyer.integrate.engines.numba_engine import NumbaEngine

    real = TL.propagate
    calls = orbits_per_call(TL, "propagate")
    p = body.engine_params
    tol = Tolerance(1e-12, 1e-12)
    n = L + 5
    y = states(n, 60)
    w = np.random.default_rng(7).normal(size=(n, 1, 6))
    t = np.linspace(0.0, 10.0, 6)
    eng = TE.TaylorEngine()
    lanes_y = eng.propagate(y, t, p, tol)
    lanes_w = eng.tangent(y, w, p, tol, t=t, renormalise=False)
    assert calls == [n, n]
    monkeypatch.setattr(TE, "LANES_FROM", 10**9)
    scalar_y = eng.propagate(y, t, p, tol)
    scalar_w = eng.tangent(y, w, p, tol, t=t, renormalise=False)
    assert calls == [n, n]  # the scalar kernel this time
    np.testing.assert_allclose(lanes_y, scalar_y, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(lanes_w.rho, scalar_w.rho, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(lanes_w.u, scalar_w.u, rtol=1e-11, atol=1e-11)
    other = NumbaEngine().tangent(y, w, p, tol, t=t, renormalise=False)
    np.testing.assert_allclose(lanes_w.y, other.y, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(lanes_w.rho, other.rho, rtol=1e-8, atol=1e-8)
    # failures per orbit: a step budget that some orbits need more than
    monkeypatch.setattr(TE, "LANES_FROM", 8)
    z0 = np.ascontiguousarray(np.concatenate([y, w[:, 0]], axis=1))
    _, info = real(z0, t, eng._kernel_params(np.asarray(p, float)), 15, 10**6)
    limit = int(np.median(info[:, 1]))
    flow = TE.TaylorEngine(max_steps=limit).tangent(y, w, p, tol, t=t, renormalise=False)
    assert calls[-1] == n
    np.testing.assert_array_equal(flow.ok, info[:, 1] <= limit)
    assert flow.ok.any() and not flow.ok.all()
    assert np.all(np.isnan(flow.y[~flow.ok])) and np.all(np.isfinite(flow.y[flow.ok]))
