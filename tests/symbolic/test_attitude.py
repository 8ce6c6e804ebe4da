"""The attitude flow derived by SymPy (``andoyer.symbolic.attitude``), checked at random
numeric points against what it must be: R(q) a rotation for a unit q, the vertical of the
body gamma = R^T e_Z carried by the quaternion field exactly as the second line of (1)
carries it, |q| an integral."""

from __future__ import annotations

import numpy as np
import sympy as sp

from andoyer.symbolic.attitude import Q, attitude_field, rotation_matrix_expr
from andoyer.symbolic.hamiltonian import S

RNG = np.random.default_rng(7)


def _point() -> dict[sp.Symbol, float]:
    q = RNG.normal(size=4)
    q /= np.linalg.norm(q)
    values = dict(zip(Q, q, strict=True))
    values |= dict(zip(S.y, RNG.normal(size=6), strict=True))
    values |= dict(zip(S.body, RNG.uniform(0.3, 2.0, size=len(S.body)), strict=True))
    return values


def test_the_rotation_of_a_unit_quaternion_is_a_rotation():
    R = rotation_matrix_expr()
    for _ in range(3):
        Rn = np.array(R.subs(_point()).evalf(), dtype=float)
        np.testing.assert_allclose(Rn.T @ Rn, np.eye(3), atol=1e-14)
        assert abs(np.linalg.det(Rn) - 1.0) < 1e-14


def test_the_quaternion_carries_the_vertical_as_the_poisson_equation_does():
    """d(R(q)^T e_Z)/dt along the quaternion field equals d(gamma)/dt of (1) evaluated at
    gamma = R(q)^T e_Z: the two halves of the field agree."""
    f = attitude_field()
    R = rotation_matrix_expr()
    up = R.T * sp.Matrix([0, 0, 1])
    rate = [sum(sp.diff(up[i], Q[k]) * f[6 + k] for k in range(4)) for i in range(3)]
    for _ in range(3):
        point = _point()
        gamma = [float(up[i].subs(point)) for i in range(3)]
        at = point | dict(zip(S.y[3:], gamma, strict=True))
        want = [float(f[3 + i].subs(at)) for i in range(3)]
        got = [float(rate[i].subs(at)) for i in range(3)]
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12)


def test_the_norm_of_the_quaternion_is_an_integral():
    f = attitude_field()
    assert sp.expand(sum(Q[i] * f[6 + i] for i in range(4))) == 0
