"""The variational equations on the Numba DOP853 (:mod:`andoyer.kernels.dop853.tangent`).

Checked against independent routes:

* the generated Jacobian against central differences of the generated field (exact for
  a quadratic field up to round-off);
* the tangent flow (a full fundamental matrix, ``w_i = exp(rho_i) u_i``) against
  central differences of nearby orbits integrated by the plain DOP853 kernels;
* the invariants of the renormalised system: ``|u_i| = 1``, ``grad C(y(t)) . w(t)``
  constant for the Casimirs and H, the base orbit unchanged by carrying vectors;
* the MEGNO quadratures against their definitions, by quadrature of the output;
* a second process loads the compiled entry points from Numba's cache.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.typing import NDArray

from _numba_cache import fresh_process_cache_stats
from andoyer import RigidBody, from_andoyer
from andoyer.kernels import common
from andoyer.kernels.dop853 import flow as dop853
from andoyer.kernels.dop853 import tangent as T
from andoyer.kernels.dop853.fields import ep_field, ep_jacobian
from andoyer.kernels.generated import equations

TOL = 1e-13
MAX_STEPS = 10**7


def params(body: RigidBody) -> NDArray[np.float64]:
    return np.asarray(body.engine_params, dtype=float)


def start(y0: NDArray[np.float64], W: NDArray[np.float64]) -> NDArray[np.float64]:
    """A tangent state (layout of common.layout) with vectors ``W`` (k, 6), ``rho = ln|w|``."""
    k = W.shape[0]
    L = common.layout(k)
    z = np.zeros(common.dimension(k))
    norms = np.linalg.norm(W, axis=1)
    z[L["y"]] = y0
    z[L["u"]] = (W / norms[:, None]).ravel()
    z[L["rho"]] = np.log(norms)
    return z


def vectors(z: NDArray[np.float64], k: int) -> NDArray[np.float64]:
    """The tangent vectors ``w_i = exp(rho_i) u_i``, shape (..., k, 6)."""
    L = common.layout(k)
    U = z[..., L["u"]].reshape(*z.shape[:-1], k, 6)
    return np.exp(z[..., L["rho"]])[..., None] * U


@pytest.fixture(scope="module")
def y_general() -> NDArray[np.float64]:
    return from_andoyer(np.array([[0.3, 1.1, 0.2, 1.0, -0.4], [2.5, 0.7, 0.6, 1.0, 0.05]]))


def test_layout_and_dimension() -> None:
    for k in range(1, common.MAX_VECTORS + 1):
        L = common.layout(k)
        assert common.n_vectors(common.dimension(k)) == k
        assert L["megno_int"] == common.dimension(k) - 1
        assert L["rho"].stop == L["megno_num"]
    with pytest.raises(ValueError, match="not a tangent state"):
        common.n_vectors(16)


def test_jacobian_is_the_derivative_of_the_field(general_body: RigidBody) -> None:
    rng = np.random.default_rng(3)
    p = tuple(general_body.params)
    for _ in range(20):
        y = rng.normal(size=6)
        J = np.array(ep_jacobian(*y, *p)).reshape(6, 6)
        fd = np.empty((6, 6))
        eps = 1e-3
        for j in range(6):
            e = np.zeros(6)
            e[j] = eps
            fd[:, j] = (np.array(ep_field(*(y + e), *p))
                        - np.array(ep_field(*(y - e), *p))) / (2 * eps)
        # The field is quadratic: central differences are exact up to round-off.
        np.testing.assert_allclose(J, fd, rtol=0, atol=1e-11)
        # NumPy (generated) and Numba kernels agree.
        np.testing.assert_allclose(J.ravel(), np.array(equations.ep_jacobian(*y, *p)),
                                   rtol=1e-15, atol=1e-15)


@pytest.mark.parametrize("body_name", ["general", "paper"])
def test_fundamental_matrix_matches_finite_differences_of_orbits(
        body_name: str, general_body: RigidBody, paper_body: RigidBody,
        y_general: NDArray[np.float64]) -> None:
    body = general_body if body_name == "general" else paper_body
    p = params(body)
    t = np.array([0.0, 3.0, 20.0])
    z0 = np.array([start(y, np.eye(6)) for y in y_general])
    z, info = T.propagate(z0, t, p, TOL, TOL, MAX_STEPS)
    assert np.all(info[:, 0] == common.SUCCESS)
    Phi = np.swapaxes(vectors(z, 6), -1, -2)  # columns: d y(t) / d y_j(0)
    eps = 1e-5
    for n, y in enumerate(y_general):
        plus = y + eps * np.eye(6)
        minus = y - eps * np.eye(6)
        out, _ = dop853.propagate(np.concatenate([plus, minus]), t, p, TOL, TOL, MAX_STEPS)
        fd = (out[:6] - out[6:]) / (2 * eps)  # (j, time, i)
        for m in range(1, t.size):
            ref = fd[:, m].T
            # central differences: error O(eps^2 |y'''|) plus round-off/eps; measured
            # 4e-11 .. 1.6e-9 (relative to max(1, |Phi|))
            assert np.abs(Phi[n, m] - ref).max() <= 1e-8 * max(1.0, np.abs(ref).max())
        # The orbit itself is the plain one (same method, other step sequence): measured
        # 1.2e-13 .. 1.9e-13.
        plain, _ = dop853.propagate(y[None], t, p, TOL, TOL, MAX_STEPS)
        np.testing.assert_allclose(z[n, :, :6], plain[0], rtol=0, atol=2e-12)


def _gradients(body: RigidBody, y: NDArray[np.float64]) -> NDArray[np.float64]:
    """Gradients of (G, gamma), |gamma|^2 and H (Euler-Poisson), shape (..., 3, 6)."""
    G, gamma = y[..., :3], y[..., 3:]
    inertia = np.array([body.a, body.b, body.c])
    mu_e = np.broadcast_to(body.mu * np.array([body.e1, body.e2, body.e3]), G.shape)
    return np.stack([np.concatenate([gamma, G], axis=-1),
                     np.concatenate([np.zeros_like(gamma), 2 * gamma], axis=-1),
                     np.concatenate([inertia * G, mu_e], axis=-1)], axis=-2)


def test_renormalised_vectors_keep_their_invariants(general_body: RigidBody,
                                                   y_general: NDArray[np.float64]) -> None:
    k = 3
    rng = np.random.default_rng(5)
    W = rng.normal(size=(y_general.shape[0], k, 6))
    z0 = np.array([start(y, w) for y, w in zip(y_general, W, strict=True)])
    t = np.linspace(0.0, 200.0, 41)
    z, info = T.propagate(z0, t, params(general_body), TOL, TOL, MAX_STEPS)
    assert np.all(info[:, 0] == common.SUCCESS)
    L = common.layout(k)
    U = z[..., L["u"]].reshape(*z.shape[:2], k, 6)
    assert np.abs(np.linalg.norm(U, axis=-1) - 1.0).max() < 1e-10
    # grad I(y(t)) . w(t) is constant along the linearised flow, for I = (G, gamma),
    # |gamma|^2, H: relative to |grad I| |w|.
    w = vectors(z, k)
    grads = _gradients(general_body, z[..., :6])  # (n, m, 3, 6)
    dots = np.einsum("nmcj,nmkj->nmck", grads, w)
    scale = (np.linalg.norm(grads, axis=-1)[..., None]
             * np.linalg.norm(w, axis=-1)[..., None, :])
    drift = np.abs(dots - dots[:, :1]) / scale
    assert drift.max() < 1e-9


def test_megno_quadratures_follow_their_definitions(paper_body: RigidBody) -> None:
    """num = int (s + delta) f ds with f = d rho/dt, int = int 2 num/(s + delta) ds."""
    y0 = from_andoyer([0.3, 0.0, 0.3, 1.0, 0.0])
    z0 = start(y0.reshape(6), np.array([[1.0, 0.5, -0.2, 0.1, 0.3, -0.4]]))[None]
    t = np.linspace(0.0, 50.0, 5001)
    z, _ = T.propagate(z0, t, params(paper_body), TOL, TOL, MAX_STEPS)
    L = common.layout(1)
    rho = z[0, :, L["rho"]][:, 0] - z[0, 0, L["rho"]][0]
    num, integral = z[0, :, L["megno_num"]], z[0, :, L["megno_int"]]
    s = t + common.MEGNO_DELTA
    # int_0^t s f ds = t rho(t) + delta rho(t) - int_0^t rho ds (by parts), trapezoids.
    from scipy.integrate import cumulative_trapezoid

    by_parts = s * rho - cumulative_trapezoid(rho, t, initial=0.0)
    assert np.abs(num - by_parts).max() < 1e-5 * np.abs(num).max()
    quad = cumulative_trapezoid(2 * num / s, t, initial=0.0)
    assert np.abs(integral - quad).max() < 1e-5 * np.abs(integral).max()


def test_a_second_process_loads_the_compiled_kernels(paper_body: RigidBody) -> None:
    p = params(paper_body)
    y0 = from_andoyer([0.3, 0.0, 0.3, 1.0, 0.0]).reshape(6)
    z0 = start(y0, np.eye(6)[:2])[None]
    T.propagate(z0, np.array([0.0, 1.0]), p, 1e-12, 1e-12, MAX_STEPS)
    T.locate_crossings(z0, p, 2, 0.0, 1, 1, 50.0, 1e-12, 1e-12, MAX_STEPS)
    z, pp = z0.tolist(), p.tolist()
    out = fresh_process_cache_stats("andoyer.kernels.dop853.tangent", {
        "propagate_block": f"m.propagate(np.array({z}), np.array([0.0, 1.0]), np.array({pp}), "
                     f"1e-12, 1e-12, {MAX_STEPS})",
        "locate_crossings_block": f"m.locate_crossings(np.array({z}), np.array({pp}), 2, 0.0, 1, "
                            f"1, 50.0, 1e-12, 1e-12, {MAX_STEPS})"})
    assert out["misses"] == [0, 0] and out["hits"] == [1, 1]
    assert out["seconds"] < 5.0


def test_crossings_carry_the_tangent_vectors(paper_body: RigidBody) -> None:
    """The tangent state at a crossing is the propagated one at the crossing time."""
    p = params(paper_body)
    y0 = from_andoyer([0.3, 0.0, 0.3, 1.0, 0.0]).reshape(6)
    z0 = start(y0, np.eye(6)[:2])[None]
    kind = equations.SECTION_KINDS.index("G3")
    tc, zc, count, info = T.locate_crossings(z0, p, kind, 0.0, 0, 3, 500.0, TOL, TOL,
                                             MAX_STEPS)
    assert count[0] == 3 and info[0, 0] == common.SUCCESS
    assert np.abs(zc[0, :, 2]).max() < 1e-12
    plain_t, _, _, _ = dop853.locate_crossings(y0[None], p, kind, 0.0, 0, 3, 500.0, TOL,
                                               TOL, MAX_STEPS)
    np.testing.assert_allclose(tc[0], plain_t[0], rtol=0, atol=1e-9)
    z, _ = T.propagate(z0, np.concatenate([[0.0], tc[0]]), p, TOL, TOL, MAX_STEPS)
    np.testing.assert_allclose(vectors(zc[0], 2), vectors(z[0, 1:], 2), rtol=0, atol=1e-8)
