"""The renormalised tangent flow of the Taylor method (:mod:`andoyer.kernels.taylor.tangent`)
against independent routes.

* the state, unit vectors, log norms and both MEGNO quadratures against the Numba
  DOP853's continuously renormalised system (:mod:`andoyer.kernels.dop853.tangent`, a different
  method and a different formulation of the same equations) at a tight tolerance;
* the MEGNO jets against their definitions: ``L`` is the Taylor series of
  ``ln|w_1(tau)|`` (the step's polynomial, evaluated directly), ``N`` and ``I`` solve
  ``N' = (s0 + tau) L'`` and ``I' = 2 N / (s0 + tau)`` (checked at sample points by the
  polynomial's derivative);
* the renormalisation: the log norms equal those of the linear flow's own vectors
  (:func:`andoyer.kernels.taylor.flow.propagate`, not renormalised) while those are finite,
  and a chaotic orbit carried past ``ln|w| = 709`` (where ``|w|`` overflows a double)
  stays finite with unit vectors;
* a second process loads the compiled entry point from Numba's cache.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.typing import NDArray

from _numba_cache import fresh_process_cache_stats
from andoyer import RigidBody, from_andoyer, from_hess
from andoyer.kernels import common
from andoyer.kernels.dop853 import tangent as DT
from andoyer.kernels.taylor import flow as T
from andoyer.kernels.taylor import tangent as TT

MAX_STEPS = 10**7
Y0 = [0.3, 1.1, 0.2, 1.0, -0.4]
W0 = np.array([[1.0, 0.5, -0.3, 0.2, 0.1, -0.4], [0.0, 1.0, 0.2, -0.5, 0.3, 0.1]])
#: A Hess body with a wide chaotic layer at h = mu, and a state in it (as in
#: tests/analysis/test_chaos.py; Lyapunov exponent about 0.055).
CHAOTIC_BODY = RigidBody.hess(3.0, 1.0, 2.0, mu=1.0)
CHAOTIC = [0.2617993877991494, 0.0, 1.0103629710818451, 1.712575169922734, 0.0]


def params(body: RigidBody) -> NDArray[np.float64]:
    return np.asarray(body.engine_params, dtype=float)


@pytest.fixture(scope="module")
def general() -> RigidBody:
    return RigidBody(1.3, 1.7, 2.1, mu=0.5, r=(0.3, -0.5, 0.8))


def _dop853(y0: NDArray[np.float64], W: NDArray[np.float64], t: NDArray[np.float64],
            p: NDArray[np.float64]) -> NDArray[np.float64]:
    k = W.shape[0]
    L = common.layout(k)
    z = np.zeros(common.dimension(k))
    norms = np.linalg.norm(W, axis=1)
    z[L["y"]] = y0
    z[L["u"]] = (W / norms[:, None]).ravel()
    z[L["rho"]] = np.log(norms)
    out, info = DT.propagate(z[None], t, p, 1e-14, 1e-14, MAX_STEPS)
    assert info[0, 0] == 0
    return out[0]


def _start(y0: NDArray[np.float64], W: NDArray[np.float64]
           ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``z0 = (y0, u_1 .. u_k)`` and ``rho0 = ln|w_i|`` of the kernel."""
    norms = np.linalg.norm(W, axis=1)
    return (np.concatenate([y0, (W / norms[:, None]).ravel()])[None],
            np.log(norms)[None])


def test_agrees_with_the_continuously_renormalised_dop853(general: RigidBody) -> None:
    p = params(general)
    y0 = from_andoyer([Y0])[0]
    W = W0 * np.array([[3.0], [0.5]])  # lengths other than 1: rho starts at ln|w0|
    t = np.array([0.0, 0.5, 3.0, 20.0, 60.0])
    z, info = TT.propagate(*_start(y0, W), t, p, 1e-14, MAX_STEPS)
    assert info[0, 0] == common.SUCCESS and info[0, 1] > 0
    ref = _dop853(y0, W, t, p)
    assert z.shape == (1, t.size, common.dimension(2))  # the row of tangent.layout
    L = common.layout(2)
    np.testing.assert_allclose(z[0, 0, L["rho"]], np.log(np.linalg.norm(W, axis=1)),
                               rtol=0, atol=1e-15)
    # measured: y 7e-14, u 1.1e-13, rho 1e-13, the quadratures 3e-14 relative at t = 60
    # (N ~ 98, I ~ 108) and 7.4e-13 absolute at t = 0.5 (I = -0.007: the error control
    # is absolute while |I| < 1)
    np.testing.assert_allclose(z[0, :, L["y"]], ref[:, L["y"]], rtol=0, atol=1e-12)
    np.testing.assert_allclose(z[0, :, L["u"]], ref[:, L["u"]], rtol=0, atol=1e-11)
    np.testing.assert_allclose(z[0, :, L["rho"]], ref[:, L["rho"]], rtol=0, atol=1e-11)
    for q in ("megno_num", "megno_int"):
        np.testing.assert_allclose(z[0, :, L[q]], ref[:, L[q]], rtol=1e-12, atol=5e-12)


def test_megno_jets_solve_their_equations(general: RigidBody) -> None:
    """The jets of one step at t0 = 2 (s0 = t0 + delta), compared on the polynomial:
    L(tau) = ln|w(tau)| to the truncation order, N' = (s0 + tau) L', I' = 2 N/(s0 + tau)."""
    p = params(general)
    order = 20
    y0 = from_andoyer([Y0])[0]
    w = W0[0] / np.linalg.norm(W0[0])
    X = np.ascontiguousarray(T.jet(np.concatenate([y0, w]), p, order))
    Q = np.zeros((5, order + 1, 1))
    num0, int0, s0 = 0.7, 1.3, 2.0 + common.MEGNO_DELTA
    Q[1, 0, 0], Q[2, 0, 0] = num0, int0
    TT.megno_jets(X, order, s0, Q)
    L, N, I = (np.polynomial.Polynomial(Q[c, :, 0]) for c in range(3))
    wpoly = [np.polynomial.Polynomial(X[1, :, i]) for i in range(6)]
    for tau in (0.0, 0.01, 0.03):
        direct = 0.5 * math.log(sum(float(c(tau)) ** 2 for c in wpoly))
        assert abs(L(tau) - direct) < 1e-13
        assert N.deriv()(tau) == pytest.approx((s0 + tau) * L.deriv()(tau), rel=1e-12,
                                               abs=1e-15)
        assert I.deriv()(tau) == pytest.approx(2.0 * N(tau) / (s0 + tau), rel=1e-12)
    assert (N(0.0), I(0.0)) == (num0, int0)


def test_log_norms_are_the_linear_flows_own(general: RigidBody) -> None:
    """Renormalising at every step changes nothing but the bookkeeping."""
    p = params(general)
    y0 = from_andoyer([Y0])[0]
    z0 = np.concatenate([y0, W0.ravel()])[None]
    t = np.linspace(0.0, 100.0, 11)
    z, _ = TT.propagate(*_start(y0, W0), t, p, 1e-13, MAX_STEPS)
    plain, info = T.propagate(z0, t, p, 1e-13, MAX_STEPS)
    assert info[0, 0] == common.SUCCESS
    W = plain[0, :, 6:].reshape(t.size, 2, 6)
    norms = np.linalg.norm(W, axis=-1)
    L = common.layout(2)  # measured 2.3e-13 (rho), 3.6e-13 (u) at t <= 100, ln|w| ~ 8
    np.testing.assert_allclose(z[0, :, L["rho"]], np.log(norms), rtol=0, atol=1e-11)
    np.testing.assert_allclose(z[0, :, L["u"]].reshape(t.size, 2, 6),
                               W / norms[..., None], rtol=0, atol=1e-11)


def test_a_long_chaotic_run_stays_finite() -> None:
    """Past ln|w| = 709 (t ~ 13000 here) |w| itself overflows; the renormalised vectors
    and the quadratures do not (measured ln|w(20000)| = 0.8e3 .. 1.1e3, 0.6 s an orbit).
    Three nearby chaotic orbits, the furthest checked past the overflow: one orbit in
    ten of these sticks near an island for thousands of time units (measured ln|w(20000)|
    = 180 .. 320), and which one depends on round-off (the steps)."""
    p = params(CHAOTIC_BODY)
    y0 = from_hess(CHAOTIC_BODY, [[CHAOTIC[0] + d, *CHAOTIC[1:]] for d in (0.0, 0.02, 0.04)])
    t = np.linspace(0.0, 20000.0, 5)
    L = common.layout(1)
    furthest = None
    for y in y0:
        z, info = TT.propagate(*_start(y, W0[:1]), t, p, 1e-12, MAX_STEPS)
        assert info[0, 0] == common.SUCCESS
        assert np.all(np.isfinite(z))
        rho = z[0, :, L["rho"]][:, 0]
        assert np.all(np.diff(rho) > 0.0)
        np.testing.assert_allclose(np.linalg.norm(z[0, :, L["u"]], axis=-1), 1.0, atol=1e-12)
        # mean MEGNO <Y> ~ lambda t / 2 on a chaotic orbit: large and finite
        mean = z[0, -1, L["megno_int"]] / (t[-1] + common.MEGNO_DELTA)
        assert 0.0 < mean < rho[-1]
        if furthest is None or rho[-1] > furthest[0]:
            furthest = (rho[-1], mean)
    assert furthest is not None
    assert furthest[0] > 750.0  # |w| = e^rho > 1e325: beyond the largest double
    assert furthest[1] > 100.0


def test_needs_a_tangent_vector() -> None:
    with pytest.raises(ValueError, match="at least one tangent vector"):
        TT.propagate(from_andoyer([Y0]), np.zeros((1, 0)), np.array([0.0, 1.0]),
                     params(RigidBody.paper()), 1e-12, MAX_STEPS)


def test_second_process_loads_from_the_cache() -> None:
    p = params(RigidBody.paper()).tolist()
    z0, rho0 = _start(from_andoyer([Y0])[0], W0[:1])
    TT.propagate(z0, rho0, np.array([0.0, 1.0]), np.array(p), 1e-12, MAX_STEPS)
    z, r = z0.tolist(), rho0.tolist()
    out = fresh_process_cache_stats("andoyer.kernels.taylor.tangent", {
        "propagate_block": f"m.propagate(np.array({z}), np.array({r}), np.array([0.0, 1.0]), "
                           f"np.array({p}), 1e-12, {MAX_STEPS})"})
    assert out["misses"] == [0] and out["hits"] == [1]
