"""Conventions of the attitude (issue 27): scalar-first quaternions, active rotations body
-> space, z-x-z Euler angles, the singular set theta = 0, pi reported, and the
Andoyer-Deprit node."""

from __future__ import annotations

import numpy as np
import pytest

from andoyer.charts.andoyer_deprit import from_andoyer
from andoyer.charts.rotation import (
    EULER_SINGULAR_RTOL,
    andoyer_rotation,
    euler_angles,
    quaternion_conjugate,
    quaternion_from_euler,
    quaternion_from_matrix,
    quaternion_from_vertical,
    quaternion_product,
    rotation_matrix,
)

RNG = np.random.default_rng(27)


def Rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def Rx(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def random_quaternions(n):
    q = RNG.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def test_scalar_first_active_body_to_space():
    # A quarter turn about Z takes the body axis x to the space axis Y (active).
    q = np.array([np.cos(np.pi / 4), 0.0, 0.0, np.sin(np.pi / 4)])
    R = rotation_matrix(q)
    assert np.allclose(R @ [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], atol=1e-15)
    assert np.allclose(rotation_matrix([1.0, 0.0, 0.0, 0.0]), np.eye(3))
    # R x = vector part of q (x) (0, x) (x) q*.
    Q = random_quaternions(50)
    x = RNG.normal(size=(50, 3))
    rotated = quaternion_product(quaternion_product(Q, np.c_[np.zeros(50), x]),
                                 quaternion_conjugate(Q))
    assert np.abs(rotated[:, 1:] - np.einsum("nij,nj->ni", rotation_matrix(Q), x)).max() < 1e-14
    # Composition: R(p q) = R(p) R(q).
    P = random_quaternions(50)
    assert np.abs(rotation_matrix(quaternion_product(P, Q))
                  - rotation_matrix(P) @ rotation_matrix(Q)).max() < 1e-14


def test_matrix_and_quaternion_round_trip():
    Q = random_quaternions(200)
    Q *= np.sign(Q[:, :1])
    assert np.abs(quaternion_from_matrix(rotation_matrix(Q)) - Q).max() < 1e-14


def test_euler_angles_are_zxz_with_gamma_the_last_row():
    psi, theta, phi = RNG.uniform(-3, 3, 100), RNG.uniform(0.01, 3.1, 100), RNG.uniform(-3, 3, 100)
    q = quaternion_from_euler(psi, theta, phi)
    R = rotation_matrix(q)
    expected = np.stack([Rz(a) @ Rx(b) @ Rz(c) for a, b, c in zip(psi, theta, phi, strict=True)])
    assert np.abs(R - expected).max() < 1e-14
    e = euler_angles(q)
    assert np.abs(e.psi - psi).max() < 1e-12 and np.abs(e.theta - theta).max() < 1e-12
    assert np.abs(e.phi - phi).max() < 1e-12 and not e.singular.any()
    gamma = np.stack([np.sin(theta) * np.sin(phi), np.sin(theta) * np.cos(phi),
                      np.cos(theta)], axis=-1)
    assert np.abs(R[:, 2, :] - gamma).max() < 1e-14


@pytest.mark.parametrize("theta", [0.0, np.pi, 1e-13, np.pi - 1e-13])
def test_singular_euler_angles_are_nan_and_flagged(theta):
    e = euler_angles(quaternion_from_euler(0.4, theta, 0.2))
    assert e.singular and np.isnan(e.psi) and np.isnan(e.phi)
    assert abs(float(e.theta) - theta) < 1e-12
    near = euler_angles(quaternion_from_euler(0.4, 100 * EULER_SINGULAR_RTOL, 0.2))
    assert not near.singular and np.isfinite(near.psi)


def test_vertical_and_precession_fix_the_attitude():
    gamma = RNG.normal(size=(30, 3))
    gamma /= np.linalg.norm(gamma, axis=1, keepdims=True)
    psi = RNG.uniform(-3, 3, 30)
    q = quaternion_from_vertical(gamma, psi)
    R = rotation_matrix(q)
    assert np.abs(np.einsum("nji,j->ni", R, [0.0, 0.0, 1.0]) - gamma).max() < 1e-14
    assert np.abs(euler_angles(q).psi - psi).max() < 1e-12


def test_andoyer_chain_gives_the_state_and_the_node():
    x = np.array([[0.3, 1.1, 0.2, 1.0, -0.4], [2.0, -0.5, -0.7, 1.3, 0.9]])
    m = np.array([0.7, -2.0])
    R = rotation_matrix(andoyer_rotation(x, m))
    y = from_andoyer(x)
    # gamma = R^T e_Z and G_body = R^T (G in space), G in space at longitude m and
    # inclination I: G (sin m sin I, -cos m sin I, cos I).
    G, M = x[:, 3], x[:, 4]
    sI = np.sqrt(G**2 - M**2) / G
    G_space = G[:, None] * np.stack([np.sin(m) * sI, -np.cos(m) * sI, M / G], axis=-1)
    assert np.abs(np.einsum("nji,nj->ni", R, G_space) - y[:, :3]).max() < 1e-14
    assert np.abs(R[:, 2, :] - y[:, 3:]).max() < 1e-14
    # psi = m + psi(chain at m = 0).
    psi = euler_angles(andoyer_rotation(x, m)).psi
    psi_red = euler_angles(andoyer_rotation(x, 0.0)).psi
    assert np.abs(np.angle(np.exp(1j * (psi - psi_red - m)))).max() < 1e-13


@pytest.mark.parametrize("bad", [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0], [np.nan, 0, 0, 1]])
def test_bad_quaternions_are_refused_naming_the_argument(bad):
    with pytest.raises(ValueError, match="q"):
        rotation_matrix(bad)


@pytest.mark.parametrize("R, what", [
    (np.ones((3, 3)), "not orthogonal"),
    (-np.eye(3), "reflection"),
    (np.diag([1.0, 1.0, -1.0]), "reflection"),
    (2.0 * np.eye(3), "not orthogonal"),
    (1e-10 * np.eye(3), "not orthogonal"),
    (np.zeros((3, 3)), "not orthogonal"),
    (1e10 * np.eye(3), "not orthogonal"),
])
def test_quaternion_from_matrix_refuses_what_is_not_a_rotation(R, what):
    """Before, np.ones((3, 3)) gave [1, 0, 0, 0] and -I (a reflection) [0, 1, 0, 0]."""
    with pytest.raises(ValueError, match=rf"^R must hold rotation matrices.*{what}"):
        quaternion_from_matrix(R)
    with pytest.raises(ValueError, match=r"matrix 1 of 2"):
        quaternion_from_matrix(np.stack([np.eye(3), R]))


def test_quaternion_from_matrix_takes_rotations_to_the_stated_tolerance():
    from andoyer.charts.rotation import ROTATION_RTOL

    R = rotation_matrix([0.5, 0.5, -0.5, 0.5])
    q = quaternion_from_matrix(np.round(R + 0.3 * ROTATION_RTOL, 12))
    assert np.abs(q - [0.5, 0.5, -0.5, 0.5]).max() <= 1e-8
    with pytest.raises(ValueError, match="not orthogonal"):
        quaternion_from_matrix(R * (1.0 + 10 * ROTATION_RTOL))
