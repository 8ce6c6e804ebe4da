"""The renormalised tangent flow on SIMD lanes (:mod:`andoyer.kernels.taylor.lane_tangent`)
against the scalar kernel (:mod:`andoyer.kernels.taylor.tangent`).

* the lane MEGNO jets equal the scalar ``megno_jets`` lane by lane, to round-off, and
  the intrinsics of their ``w . w`` and their orders (:func:`andoyer.kernels.simd.series_dot`,
  :func:`~andoyer.kernels.simd.megno_orders`) their plain Python fallbacks;
* orbits (k = 1, 2, 3 vectors, states near the chart's singular sets, a chaotic orbit
  whose ``rho`` grows): every orbit takes the scalar kernel's steps (``info`` equal, row
  by row) and its rows (state, unit vectors, ``rho``, ``N``, ``I``) agree to round-off;
  threads and blocks change no bit;
* failures per orbit with the scalar kernel's statuses: a non-finite state
  (``STEP_TOO_SMALL``), a non-finite vector (no failure there either), ``max_steps``;
* queue edges: fewer orbits than lanes, one output time, repeated initial times;
* the taylor engine's renormalised ``tangent`` runs many orbits on the lanes.
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
from andoyer import RigidBody, from_andoyer, from_hess
from andoyer.integrate.engines.values import unit_vectors
from andoyer.kernels import common, simd
from andoyer.kernels.taylor import lane_tangent as LT
from andoyer.kernels.taylor import lanes as TL
from andoyer.kernels.taylor import tangent as TT
from andoyer.kernels.taylor.jets import fill_constants

L = TL.LANES
ORDER = 15  # order_for(1e-12)
#: The chaotic layer of tests/kernels/taylor/test_tangent.py (Lyapunov exponent ~0.055).
CHAOTIC_BODY = RigidBody.hess(3.0, 1.0, 2.0, mu=1.0)
CHAOTIC = [0.2617993877991494, 0.0, 1.0103629710818451, 1.712575169922734, 0.0]


@pytest.fixture(scope="module")
def body() -> RigidBody:
    return RigidBody(1.3, 1.7, 2.1, mu=0.5, r=(0.3, -0.5, 0.8))


def starts(n: int, k: int, seed: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(z0, rho0)``: random states (a third near the chart's singular sets) with ``k``
    random unit vectors, and their log lengths."""
    rng = np.random.default_rng(seed)
    P = andoyer_points(n, rng)
    u, rho = unit_vectors(rng.normal(size=(n, k, 6)) * rng.uniform(0.1, 10.0, (n, k, 1)))
    z = np.concatenate([from_andoyer(P), u.reshape(n, 6 * k)], axis=1)
    return np.ascontiguousarray(z), rho


def close(got: NDArray[np.float64], ref: NDArray[np.float64]) -> float:
    """The largest difference relative to ``1 + |ref|`` (non-finite values equal)."""
    ok = np.isfinite(ref)
    np.testing.assert_array_equal(np.isfinite(got), ok)
    np.testing.assert_array_equal(got[~ok], ref[~ok])
    return float(np.max(np.abs(got[ok] - ref[ok]) / (1.0 + np.abs(ref[ok])), initial=0.0))


@numba.njit
def _jets(X, p, order, s0):  # noqa: ANN001, ANN202 - a compiled test helper
    q = np.empty(12)
    fill_constants(p, q)
    m = np.empty((TL._P, L))
    TL.lane_jets(X, order, q, m)
    W = np.zeros((order + 1, 6, L))
    for lane in range(L):
        W[0, 1, lane] = 0.3 + lane  # N and I at the step's start
        W[0, 2, lane] = -0.2 * lane
    LT.lane_megno_jets(X, order, s0, W, np.empty((2, L)))
    return W


def test_lane_megno_jets_equal_the_scalar_ones(body: RigidBody) -> None:
    p = np.asarray(body.engine_params, dtype=float)
    z, _ = starts(L, 2, 1)
    s0 = np.linspace(1e-3, 40.0, L)
    X = np.zeros((3, ORDER + 1, 6, L))
    X[:, 0] = z.reshape(L, 3, 6).transpose(1, 2, 0)
    X[1:, 0] *= 1.7  # a vector not of unit length: P0 != 1
    W = _jets(X, p, ORDER, s0)
    for lane in range(L):
        Xs = np.ascontiguousarray(X[..., lane])  # the lane jets (tested in test_lanes.py)
        Q = np.zeros((5, ORDER + 1, 1))
        Q[1, 0, 0] = 0.3 + lane
        Q[2, 0, 0] = -0.2 * lane
        TT.megno_jets(Xs, ORDER, s0[lane], Q)
        for row in range(3):  # L, N, I
            ref = Q[row, :, 0]
            got = W[:, row, lane]
            assert np.max(np.abs(got - ref) / (1e-300 + np.max(np.abs(ref)))) < 1e-13, row


def test_series_dot_equals_its_fallback() -> None:
    """The intrinsic (each pair of terms once, doubled; the middle term of even orders)
    against the plain sum, at every order count 0 .. 9 and 15."""
    rng = np.random.default_rng(5)

    @numba.njit
    def compiled(P, w, order):  # noqa: ANN001, ANN202
        simd.series_dot(P, 2, w, order)

    for order in (*range(10), 15):
        w = rng.normal(size=(order + 1, 6, L))
        P = rng.normal(size=(order + 1, 4, L))
        V = P.copy()
        compiled(P, w, order)
        simd.series_dot(V, 2, w, order)
        np.testing.assert_allclose(P, V, rtol=1e-13, atol=1e-13)
        k = order
        assert P[k, 2, 3] == pytest.approx(sum(w[j, :, 3] @ w[k - j, :, 3]
                                               for j in range(k + 1)))


def test_megno_orders_equal_their_fallback() -> None:
    rng = np.random.default_rng(6)

    @numba.njit
    def compiled(W, order, s0, inv):  # noqa: ANN001, ANN202
        simd.megno_orders(W, order, s0, inv)

    for order in (1, 2, 5, 15):
        W = rng.normal(size=(order + 1, 6, L))
        s0 = rng.uniform(1e-6, 30.0, L)
        inv = np.stack([1.0 / rng.uniform(0.5, 2.0, L), 1.0 / s0])
        V = W.copy()
        compiled(W, order, s0, inv)
        simd.megno_orders(V, order, s0, inv)
        np.testing.assert_allclose(W, V, rtol=1e-12, atol=1e-12 * np.max(np.abs(V)))


@pytest.mark.parametrize("k", [1, 2, 3])
def test_orbits_take_the_scalar_steps(body: RigidBody, k: int) -> None:
    p = np.asarray(body.engine_params, dtype=float)
    n = 3 * L + 5  # lanes refilled, a partial last round
    z, rho = starts(n, k, 20 + k)
    t = np.concatenate([[0.0, 0.0], np.linspace(0.5, 30.0, 7)])  # a repeated start
    ref, ref_info = TT.propagate(z, rho, t, p, 1e-12, 10**6)
    got, info = LT.propagate(z, rho, t, p, 1e-12, 10**6, threads=1)
    np.testing.assert_array_equal(info, ref_info)
    assert np.all(info[:, 0] == common.SUCCESS)
    assert close(got, ref) < 1e-11
    # blocks and threads change nothing
    again, info2 = LT.propagate(z, rho, t, p, 1e-12, 10**6, block=L + 3, threads=2)
    np.testing.assert_array_equal(again, got)
    np.testing.assert_array_equal(info2, info)
    guided, info3 = LT.propagate(z, rho, t, p, 1e-12, 10**6, threads=2)  # guided blocks
    np.testing.assert_array_equal(guided, got)
    np.testing.assert_array_equal(info3, info)


def test_a_chaotic_orbit_and_its_megno(body: RigidBody) -> None:
    """Orbits in a chaotic layer to t = 2000 (rho grows to about 100, MEGNO away from 2):
    rows as the scalar kernel's to t = 250 (round-off grows as exp(0.055 t)), the same
    chaos after."""
    p = np.asarray(CHAOTIC_BODY.engine_params, dtype=float)
    y = from_hess(CHAOTIC_BODY, np.asarray(CHAOTIC)[None])
    rng = np.random.default_rng(9)
    n = L + 1
    y = np.repeat(y, n, axis=0) + 1e-9 * rng.normal(size=(n, 6))
    u, rho = unit_vectors(rng.normal(size=(n, 1, 6)))
    z = np.ascontiguousarray(np.concatenate([y, u[:, 0]], axis=1))
    t = np.linspace(0.0, 2000.0, 9)
    ref, ref_info = TT.propagate(z, rho, t, p, 1e-12, 10**7)
    got, info = LT.propagate(z, rho, t, p, 1e-12, 10**7)
    np.testing.assert_array_equal(info[:, 0], ref_info[:, 0])
    for z in (got, ref):
        assert np.all(z[:, -1, 12] > 50.0)  # rho: chaotic
        assert np.all(2.0 * z[:, -1, 14] / t[-1] > 4.0)  # mean MEGNO 2 I / t (delta small)
    np.testing.assert_allclose(got[:, :2], ref[:, :2], rtol=1e-8, atol=1e-8)


def test_failures_are_per_orbit(body: RigidBody) -> None:
    p = np.asarray(body.engine_params, dtype=float)
    n = 2 * L + 3
    z, rho = starts(n, 1, 40)
    z[3, 0] = np.nan  # a non-finite state: STEP_TOO_SMALL
    z[L + 4, 7] = np.inf  # a non-finite vector: the scalar kernel steps on (NaN rows)
    t = np.linspace(0.0, 20.0, 5)
    ref, ref_info = TT.propagate(z, rho, t, p, 1e-12, 10**6)
    got, info = LT.propagate(z, rho, t, p, 1e-12, 10**6, threads=1)
    np.testing.assert_array_equal(info, ref_info)
    assert info[3, 0] == common.STEP_TOO_SMALL
    assert np.sum(info[:, 0] != common.SUCCESS) == 1
    assert close(got, ref) < 1e-11
    # max_steps: orbits needing more steps than allowed fail, the others do not
    limit = int(np.median(ref_info[:, 1]))
    ref, ref_info = TT.propagate(z, rho, t, p, 1e-12, limit)
    got, info = LT.propagate(z, rho, t, p, 1e-12, limit, threads=1)
    np.testing.assert_array_equal(info, ref_info)
    assert np.any(info[:, 0] == common.MAX_STEPS) and np.any(info[:, 0] == common.SUCCESS)
    assert close(got, ref) < 1e-11
    # no step at all allowed: the initial rows only
    got, info = LT.propagate(z, rho, t, p, 1e-12, 0)
    ref, ref_info = TT.propagate(z, rho, t, p, 1e-12, 0)
    np.testing.assert_array_equal(info, ref_info)
    assert np.all(info[:, 0] == common.MAX_STEPS)
    np.testing.assert_array_equal(got, ref)


@pytest.mark.parametrize("n", [0, 1, L - 1, L])
def test_queue_edges(body: RigidBody, n: int) -> None:
    p = np.asarray(body.engine_params, dtype=float)
    z, rho = starts(max(n, 1), 1, 50)
    z, rho = z[:n], rho[:n]
    for t in (np.array([0.0]), np.array([0.0, 0.0, 0.0]), np.array([0.0, 0.0, 2.0, 2.0, 5.0])):
        ref, ref_info = TT.propagate(z, rho, t, p, 1e-12, 10**6)
        got, info = LT.propagate(z, rho, t, p, 1e-12, 10**6)
        np.testing.assert_array_equal(info, ref_info)
        assert got.shape == ref.shape
        assert close(got, ref) < 1e-12
    with pytest.raises(ValueError, match="at least one tangent vector"):
        LT.propagate(z[:, :6], rho, np.array([0.0, 1.0]), p, 1e-12, 10)


def test_the_taylor_engine_runs_renormalised_flows_on_lanes(
        body: RigidBody, monkeypatch: pytest.MonkeyPatch,
        orbits_per_call: Callable[[ModuleType, str], list[int]]) -> None:
    """``tangent`` (renormalised: MEGNO maps, SALI/GALI) from LANES_FROM orbits on runs on
    the lanes, with the scalar route's flow to round-off; fewer orbits stay scalar."""
    from andoyer.integrate.engines import taylor_engine as TE
    from andoyer.integrate.engines.base import Tolerance

    calls = orbits_per_call(LT, "propagate")
    p = body.engine_params
    tol = Tolerance(1e-12, 1e-12)
    n = TE.LANES_FROM + 3
    z, _ = starts(n, 2, 60)
    y = z[:, :6]
    w = np.random.default_rng(7).normal(size=(n, 2, 6))
    t = np.linspace(0.0, 10.0, 6)
    eng = TE.TaylorEngine()
    lanes_w = eng.tangent(y, w, p, tol, t=t)
    eng.tangent(y[:TE.LANES_FROM - 1], w[:TE.LANES_FROM - 1], p, tol, t=t)
    assert calls == [n]
    monkeypatch.setattr(TE, "LANES_FROM", 10**9)
    scalar_w = eng.tangent(y, w, p, tol, t=t)
    assert calls == [n]
    np.testing.assert_array_equal(lanes_w.ok, scalar_w.ok)
    for name in ("y", "u", "rho", "megno"):
        np.testing.assert_allclose(getattr(lanes_w, name), getattr(scalar_w, name),
                                   rtol=1e-11, atol=1e-11, err_msg=name)


def test_a_second_process_loads_the_lane_tangent_kernel(body: RigidBody) -> None:
    """After this process compiled (or loaded) it, a new process pays no compile."""
    p = np.asarray(body.engine_params, dtype=float).tolist()
    z, rho = starts(L, 1, 70)
    LT.propagate(z, rho, np.array([0.0, 1.0]), np.array(p), 1e-12, 10**6)
    out = fresh_process_cache_stats("andoyer.kernels.taylor.lane_tangent", {
        "lane_tangent_block": f"m.propagate(np.array({z.tolist()}), np.array({rho.tolist()}), "
                              f"np.array([0.0, 1.0]), np.array({p}), 1e-12, 10**6)"})
    assert out["misses"] == [0] and out["hits"] == [1]
