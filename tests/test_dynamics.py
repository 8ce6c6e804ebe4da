"""Vector fields: chart fields agree through the chart maps, integrals are conserved.

The Jacobians of the chart maps are computed here by complex-step differentiation of
the NumPy forward maps (``andoyer_to_ep_expr``, ``hess_to_ep_expr``), not through the
generated kernels, and the integrals' gradients are written by hand, so every check
compares two independent routes.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from _rotations import Rx, Rz
from andoyer import RigidBody, from_andoyer, from_hess, to_andoyer, to_hess
from andoyer.charts.andoyer_deprit import andoyer_to_ep_expr
from andoyer.charts.hess import hess_to_ep_expr
from andoyer.dynamics import cyclic_rate, hamiltonian, vector_field

N = 200  # random points per check (vectorised: cheap)
H_STEP = 1e-30  # complex step; no cancellation, so it can be tiny


# --------------------------------------------------------------------------- helpers
def cs_jacobian(f, x: np.ndarray) -> np.ndarray:
    """``d f / d x`` of shape ``(n, 6, k)`` by complex step; ``f`` takes k columns."""
    cols = []
    for j in range(x.shape[-1]):
        xc = x.astype(complex)
        xc[:, j] += 1j * H_STEP
        cols.append(np.stack(np.broadcast_arrays(*f(*xc.T)), axis=-1).imag / H_STEP)
    return np.stack(cols, axis=-1)


def andoyer_map(l, g, L, G, M):
    return andoyer_to_ep_expr(l, g, L, G, M, sin=np.sin, cos=np.cos, sqrt=np.sqrt)


def hess_map(phi0):
    def f(theta1, theta2, J1, J2, J3):
        return hess_to_ep_expr(theta1, theta2, J1, J2, J3, phi0, sin=np.sin, cos=np.cos,
                               sqrt=np.sqrt)
    return f


def andoyer_points(rng: np.random.Generator, n: int = N, dmin: float = 0.2) -> np.ndarray:
    """Regular ``(l, g, L, G, M)``: ``J, I`` in ``[dmin, pi - dmin]``."""
    G = np.exp(rng.uniform(np.log(0.3), np.log(3.0), n))
    J = rng.uniform(dmin, np.pi - dmin, n)
    I = rng.uniform(dmin, np.pi - dmin, n)
    return np.stack([rng.uniform(0, 2 * np.pi, n), rng.uniform(0, 2 * np.pi, n),
                     G * np.cos(J), G, G * np.cos(I)], axis=-1)


def hess_points(rng: np.random.Generator, n: int = N, dmin: float = 0.05) -> np.ndarray:
    """Regular ``(theta1, theta2, J1, J2, J3)``."""
    J2 = np.exp(rng.uniform(np.log(0.3), np.log(3.0), n))
    return np.stack([rng.uniform(0, 4 * np.pi, n), rng.uniform(0, 2 * np.pi, n),
                     J2 * rng.uniform(dmin, 1 - dmin, n), J2,
                     J2 * np.cos(rng.uniform(0.2, np.pi - 0.2, n))], axis=-1)


def ep_points(rng: np.random.Generator, n: int = N, unit: bool = True) -> np.ndarray:
    G = rng.normal(size=(n, 3)) * np.exp(rng.uniform(-1, 1, (n, 1)))
    gamma = rng.normal(size=(n, 3))
    if unit:
        gamma /= np.linalg.norm(gamma, axis=-1, keepdims=True)
    return np.concatenate([G, gamma], axis=-1)


def rate(grad: np.ndarray, field: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(grad . field, |grad| |field|)``: a time derivative and its natural scale."""
    return (np.einsum("...i,...i->...", grad, field),
            np.linalg.norm(grad, axis=-1) * np.linalg.norm(field, axis=-1))


def hat(w: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


BODIES = {
    "general": RigidBody(1.3, 1.7, 2.1, mu=0.7, r=(0.3, -0.5, 0.8)),
    "planar": RigidBody(1.3, 1.7, 2.1, mu=0.45, r=(-0.6, 0.8, 0.0)),
    "paper": RigidBody.paper(),
    "hess_minus": RigidBody.hess(2.5, 2.0, 2.2, mu=0.3, branch=-1),
    "hess_heavy": RigidBody.hess(3.0, 1.2, 2.0, mu=1.5),
    "lagrange": RigidBody.lagrange(2.0, 1.2, mu=0.8),
    "kovalevskaya": RigidBody.kovalevskaya(C=0.8, mu=1.3),
    "goryachev_chaplygin": RigidBody.goryachev_chaplygin(C=0.6, mu=0.9),
    "euler_poinsot": RigidBody.euler_poinsot(1.0, 1.6, 2.3),
}
PLANAR = ["planar", "paper", "hess_minus", "hess_heavy", "kovalevskaya"]
HESS = ["paper", "hess_minus", "hess_heavy"]


# --------------------------------------------------------------------------- (1) itself
@pytest.mark.parametrize("name", ["general", "paper", "lagrange"])
def test_ep_field_is_equation_1(name):
    """``dG/dt = G x I^-1 G + mu gamma x r``, ``dgamma/dt = gamma x I^-1 G``, typed by hand."""
    body = BODIES[name]
    y = ep_points(np.random.default_rng(1))
    G, gamma = y[:, :3], y[:, 3:]
    omega = G * np.array([body.a, body.b, body.c])
    expected = np.concatenate([np.cross(G, omega) + body.mu * np.cross(gamma, body.r),
                               np.cross(gamma, omega)], axis=-1)
    np.testing.assert_allclose(vector_field(body, y), expected, rtol=0, atol=1e-14)


# --------------------------------------------------------------------------- (a) push-forward
@pytest.mark.parametrize("name", ["general", "planar", "paper", "lagrange", "euler_poinsot"])
def test_andoyer_field_pushes_forward_to_ep(name):
    body = BODIES[name]
    x = andoyer_points(np.random.default_rng(2))
    fx = vector_field(body, x, "andoyer")
    assert fx.shape == x.shape
    assert np.all(fx[:, 4] == 0.0)  # M is the area integral
    push = np.einsum("nij,nj->ni", cs_jacobian(andoyer_map, x), fx)
    fy = vector_field(body, from_andoyer(x))
    np.testing.assert_allclose(push, fy, rtol=0, atol=1e-12 * max(1.0, np.abs(fy).max()))


@pytest.mark.parametrize("name", PLANAR)
def test_hess_field_pushes_forward_to_ep(name):
    body = BODIES[name]
    x = hess_points(np.random.default_rng(3))
    fx = vector_field(body, x, "hess")
    assert fx.shape == x.shape
    assert np.all(fx[:, 4] == 0.0)
    push = np.einsum("nij,nj->ni", cs_jacobian(hess_map(body.phi0), x), fx)
    fy = vector_field(body, from_hess(body, x))
    np.testing.assert_allclose(push, fy, rtol=0, atol=1e-12 * max(1.0, np.abs(fy).max()))


@pytest.mark.parametrize("name", PLANAR)
def test_hamiltonians_agree_across_charts(name):
    body = BODIES[name]
    rng = np.random.default_rng(4)
    x = andoyer_points(rng)
    h = hess_points(rng)
    np.testing.assert_allclose(hamiltonian(body, x, "andoyer"),
                               hamiltonian(body, from_andoyer(x)), rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(hamiltonian(body, h, "hess"),
                               hamiltonian(body, from_hess(body, h)), rtol=1e-13, atol=1e-15)


# --------------------------------------------------------------------------- (b) integrals
def grad_H(body: RigidBody, y: np.ndarray) -> np.ndarray:
    G = y[:, :3]
    return np.concatenate([G * np.array([body.a, body.b, body.c]),
                           np.broadcast_to(body.mu * np.array(body.r), G.shape)], axis=-1)


@pytest.mark.parametrize("name", sorted(BODIES))
@pytest.mark.parametrize("unit", [True, False])
def test_ep_field_conserves_integrals(name, unit):
    """H, the area integral (G, gamma) and |gamma|^2 (Casimirs even off |gamma| = 1)."""
    body = BODIES[name]
    y = ep_points(np.random.default_rng(5), unit=unit)
    f = vector_field(body, y)
    G, gamma = y[:, :3], y[:, 3:]
    for grad in (grad_H(body, y),
                 np.concatenate([gamma, G], axis=-1),
                 np.concatenate([np.zeros_like(G), 2 * gamma], axis=-1)):
        d, scale = rate(grad, f)
        assert np.all(np.abs(d) <= 1e-13 * scale)


# --------------------------------------------------------------------------- (c) classics
def test_lagrange_G3_is_conserved():
    body = BODIES["lagrange"]
    y = ep_points(np.random.default_rng(6))
    f = vector_field(body, y)
    assert np.abs(f[:, 2]).max() <= 1e-15
    # ... and that is a property of the symmetric top, not of the test:
    asym = RigidBody(2.0, 2.3, 1.2, mu=0.8, r=(0.0, 0.0, 1.0))
    assert np.abs(vector_field(asym, y)[:, 2]).max() > 1e-2


def kovalevskaya_grad(body: RigidBody, y: np.ndarray, sign: float = -1.0) -> np.ndarray:
    """Gradient of ``K = (p^2 - q^2 - nu gamma1)^2 + (2 p q - nu gamma2)^2``, ``nu = mu/C``.

    ``(p, q) = (G1/A, G2/B)``; ``sign=+1`` gives the wrong-sign variant (not an integral).
    """
    G1, G2, gamma1, gamma2 = y[:, 0], y[:, 1], y[:, 3], y[:, 4]
    A, nu = body.A, sign * body.mu / body.C
    p, q = G1 / A, G2 / A
    u, v = p**2 - q**2 + nu * gamma1, 2 * p * q + nu * gamma2
    zero = np.zeros_like(G1)
    return np.stack([(4 * u * p + 4 * v * q) / A, (-4 * u * q + 4 * v * p) / A, zero,
                     2 * nu * u, 2 * nu * v, zero], axis=-1)


def test_kovalevskaya_integral_is_conserved():
    body = BODIES["kovalevskaya"]
    y = ep_points(np.random.default_rng(7))
    f = vector_field(body, y)
    d, scale = rate(kovalevskaya_grad(body, y), f)
    assert np.all(np.abs(d) <= 1e-13 * scale)
    d_wrong, scale_wrong = rate(kovalevskaya_grad(body, y, sign=+1.0), f)
    assert np.median(np.abs(d_wrong) / scale_wrong) > 1e-2


def goryachev_chaplygin(body: RigidBody, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``K = G3 (G1^2 + G2^2) - 4 mu C G1 gamma3`` and its gradient.

    ``dK/dt = -mu G2 M`` along (1) (derived by hand): an integral on ``M = 0`` only.
    """
    G1, G2, G3, gamma3 = y[:, 0], y[:, 1], y[:, 2], y[:, 5]
    k = 4 * body.mu * body.C
    zero = np.zeros_like(G1)
    K = G3 * (G1**2 + G2**2) - k * G1 * gamma3
    grad = np.stack([2 * G1 * G3 - k * gamma3, 2 * G2 * G3, G1**2 + G2**2,
                     zero, zero, -k * G1], axis=-1)
    return K, grad


def test_goryachev_chaplygin_integral_on_zero_area_level():
    body = BODIES["goryachev_chaplygin"]
    y = ep_points(np.random.default_rng(8))
    G, gamma = y[:, :3], y[:, 3:]
    # Project gamma onto the plane perpendicular to G: the level M = 0.
    on = y.copy()
    on[:, 3:] = gamma - G * (np.einsum("ni,ni->n", G, gamma) / np.einsum("ni,ni->n", G, G))[:, None]
    on[:, 3:] /= np.linalg.norm(on[:, 3:], axis=-1, keepdims=True)
    assert np.abs(np.einsum("ni,ni->n", on[:, :3], on[:, 3:])).max() <= 1e-13
    _, grad = goryachev_chaplygin(body, on)
    d, scale = rate(grad, vector_field(body, on))
    assert np.all(np.abs(d) <= 1e-13 * scale)
    # Off M = 0 it is not an integral: dK/dt = -mu G2 M, nonzero.
    _, grad = goryachev_chaplygin(body, y)
    d, scale = rate(grad, vector_field(body, y))
    M = np.einsum("ni,ni->n", G, gamma)
    np.testing.assert_allclose(d, -body.mu * y[:, 1] * M, rtol=0, atol=1e-13 * scale.max())
    assert np.median(np.abs(d) / scale) > 1e-3


# --------------------------------------------------------------------------- (d) Hess
def sigma(body: RigidBody) -> float:
    return math.sqrt((body.b - body.c) * (body.c - body.a))


@pytest.mark.parametrize("name", HESS)
def test_hess_invariant_relation_3(name):
    """``e1 G1 + e2 G2 = 0`` is invariant: its rate vanishes on it, not off it."""
    body = BODIES[name]
    e1, e2, _ = body.r
    rng = np.random.default_rng(9)
    y = ep_points(rng)
    t, s = rng.normal(size=(2, N))
    on = y.copy()
    on[:, :3] = np.stack([-e2 * t, e1 * t, s], axis=-1)
    e = np.array([e1, e2, 0.0, 0.0, 0.0, 0.0])
    f_on = vector_field(body, on)
    d, scale = rate(np.broadcast_to(e, on.shape), f_on)
    assert np.all(np.abs(d) <= 1e-15 * (1 + scale))
    d_off, scale_off = rate(np.broadcast_to(e, y.shape), vector_field(body, y))
    assert np.median(np.abs(d_off) / scale_off) > 1e-3


@pytest.mark.parametrize("name", HESS)
def test_hess_linear_law(name):
    """``d(G, r)/dt = -branch * sigma * G3 (G, r)``, ``sigma = sqrt((b - c)(c - a))``.

    From (1): ``d(G, r)/dt = (G x I^-1 G, r) = G3 (e1 (c - b) G2 + e2 (a - c) G1)
    = G3 e2 (a - c)/e1 (G, r)`` by (8); ``e2 (a - c)/e1 = -sigma`` on the paper's
    branch (``e2 > 0``, ``a < c``) and ``+sigma`` on the other.
    """
    body = BODIES[name]
    branch = 1.0 if body.e2 > 0 else -1.0
    y = ep_points(np.random.default_rng(10))
    f = vector_field(body, y)
    Gr = y[:, :3] @ np.array(body.r)
    dGr = f[:, :3] @ np.array(body.r)
    expected = -branch * sigma(body) * y[:, 2] * Gr
    np.testing.assert_allclose(dGr, expected, rtol=0, atol=1e-14 * (1 + np.abs(f).max()))
    assert np.abs(expected).max() > 1e-2


def test_relation_3_is_not_invariant_without_hess_conditions():
    """Same construction for a planar body that violates (2): the rate on the set is O(1)."""
    body = BODIES["planar"]
    e1, e2, _ = body.r
    rng = np.random.default_rng(11)
    y = ep_points(rng)
    t, s = rng.normal(size=(2, N))
    y[:, :3] = np.stack([-e2 * t, e1 * t, s], axis=-1)
    d, scale = rate(np.broadcast_to([e1, e2, 0.0, 0.0, 0.0, 0.0], y.shape),
                    vector_field(body, y))
    assert np.median(np.abs(d) / scale) > 1e-3


@pytest.mark.parametrize("name", HESS)
def test_hess_relation_in_hess_chart(name):
    """On ``theta1 = 0`` and ``theta1 = 2 pi`` (the Hess set) ``dtheta1/dt = 0``, any J3."""
    body = BODIES[name]
    x = hess_points(np.random.default_rng(12))
    x[: N // 2, 0] = 0.0
    x[N // 2:, 0] = 2 * np.pi
    f = vector_field(body, x, "hess")
    assert np.abs(f[:, 0]).max() <= 1e-14 * np.abs(f).max()
    nonhess = vector_field(BODIES["planar"], x, "hess")
    assert np.abs(nonhess[:, 0]).max() > 1e-2


# --------------------------------------------------------------------------- (e) cyclic angle
def _attitude_rhs(body: RigidBody, chart: str):
    def rhs(t, z):
        y, R = z[:6], z[6:15].reshape(3, 3)
        omega = np.array([body.a, body.b, body.c]) * y[:3]
        x = to_andoyer(y) if chart == "andoyer" else to_hess(body, y)
        return np.concatenate([vector_field(body, y), (R @ hat(omega)).ravel(),
                               [cyclic_rate(body, x, chart)]])
    return rhs


@pytest.mark.parametrize(("name", "chart"), [("general", "andoyer"), ("paper", "andoyer"),
                                             ("hess_minus", "hess"), ("planar", "hess"),
                                             ("hess_heavy", "hess")])
def test_cyclic_angle_quadrature(name, chart):
    """m(t) read off the attitude equals the quadrature of ``dm/dt = dH/dM``."""
    body = BODIES[name]
    rng = np.random.default_rng(13)
    l, g, m0 = rng.uniform(0, 2 * np.pi, 3)
    G, L, M = 1.2, 0.3, -0.4
    J, I = math.acos(L / G), math.acos(M / G)
    R0 = Rz(m0) @ Rx(I) @ Rz(g) @ Rx(J) @ Rz(l)
    y0 = from_andoyer([l, g, L, G, M])
    np.testing.assert_allclose(R0.T @ [0.0, 0.0, 1.0], y0[3:], atol=1e-15)
    T = 3.0
    t_eval = np.linspace(0.0, T, 31)
    sol = solve_ivp(_attitude_rhs(body, chart), (0.0, T),
                    np.concatenate([y0, R0.ravel(), [0.0]]), method="DOP853",
                    rtol=1e-12, atol=1e-14, t_eval=t_eval)
    assert sol.success
    Z = sol.y.T
    R = Z[:, 6:15].reshape(-1, 3, 3)
    # The attitude reproduces gamma = R^T e_Z (kinematics of (1)).
    np.testing.assert_allclose(R[:, 2, :], Z[:, 3:6], atol=1e-10)
    Gs = np.einsum("nij,nj->ni", R, Z[:, :3])  # G in space: G (sI sin m, -sI cos m, cI)
    np.testing.assert_allclose(Gs[:, 2], M, atol=1e-10)
    m = np.unwrap(np.arctan2(Gs[:, 0], -Gs[:, 1]))
    assert abs(m[0] - m0) <= 1e-12 or abs(abs(m[0] - m0) - 2 * np.pi) <= 1e-12
    swept = m - m[0]
    assert np.abs(swept).max() > 1e-3  # the node must actually move (1e6 x the tolerance)
    np.testing.assert_allclose(swept, Z[:, 15], rtol=0, atol=1e-9)


# --------------------------------------------------------------------------- (f) singular
SING_ANDOYER = [[0.1, 0.2, 1.0, 1.0, 0.3], [0.1, 0.2, -1.0, 1.0, 0.3],
                [0.1, 0.2, 0.3, 1.0, 1.0], [0.1, 0.2, 0.3, 1.0, -1.0]]
SING_HESS = [[0.1, 0.2, 0.0, 1.0, 0.3], [0.1, 0.2, 1.0, 1.0, 0.3],
             [0.1, 0.2, 0.4, 1.0, 1.0], [0.1, 0.2, 0.4, 1.0, -1.0]]


@pytest.mark.parametrize("x", SING_ANDOYER)
def test_andoyer_field_raises_on_singular_set(x):
    body = BODIES["general"]
    for f in (vector_field, cyclic_rate):
        with pytest.raises(ValueError, match="singular set"):
            f(body, x, "andoyer")
        with pytest.raises(ValueError, match="singular set"):  # one bad point in a batch
            f(body, [[0.1, 0.2, 0.3, 1.0, 0.3], x], "andoyer")
    assert np.all(np.isfinite(vector_field(body, from_andoyer(x))))  # EP is global


@pytest.mark.parametrize("x", SING_HESS)
def test_hess_field_raises_on_singular_set(x):
    body = BODIES["paper"]
    for f in (vector_field, cyclic_rate):
        with pytest.raises(ValueError, match="singular set"):
            f(body, x, "hess")
    assert np.all(np.isfinite(vector_field(body, from_hess(body, x))))


def test_field_argument_errors():
    body = BODIES["general"]
    with pytest.raises(ValueError, match="unknown chart"):
        vector_field(body, [0.1, 0.2, 0.3, 1.0, 0.3], "delaunay")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="cyclic angle"):
        cyclic_rate(body, [0.1, 0.2, 0.3, 0.0, 0.6, 0.8], "euler_poisson")
    with pytest.raises(ValueError, match="e3 = 0"):
        vector_field(body, [0.1, 0.2, 0.3, 1.0, 0.3], "hess")
    with pytest.raises(ValueError, match=r"\|L\| must not exceed G"):
        vector_field(body, [0.1, 0.2, 1.3, 1.0, 0.3], "andoyer")
    with pytest.raises(ValueError, match=r"shape \(\.\.\., 6\)"):
        vector_field(body, [0.1, 0.2, 0.3, 1.0, 0.3])
