r"""The attitude of the body: the unit quaternion carried along (1), derived by SymPy.

Conventions (the one place they are written; :mod:`andoyer.charts.rotation` evaluates
them numerically):

* ``q = (q0, q1, q2, q3)``, **scalar first**, a unit quaternion;
* ``R(q)`` is the **active rotation body -> space**: a vector with body-frame
  components ``x`` has space-frame components ``R x``. The space frame ``(X, Y, Z)``
  is inertial with ``Z`` the upward vertical; the body frame ``(x, y, z)`` the
  principal axes of the paper (``G``, ``gamma``, ``r`` have body components);
* the vertical is fixed in space, so ``gamma = R^T e_Z``.

Kinematics. With ``omega = dH/dG = I^-1 G`` the body angular velocity (``I`` the inertia tensor,
``I^-1 = diag(a, b, c)``, Eq. (1)), ``dR/dt = R [omega]_x``, which for the quaternion is

.. math:: \dot q = \tfrac12\, q \otimes (0, \boldsymbol\omega),

bilinear in ``(q, G)``: with (1) the system for ``(G, gamma, q)`` is a polynomial of
degree 2 (the Taylor engines' form). Then ``d(R^T e_Z)/dt = -[omega]_x R^T e_Z =
gamma x omega``, which is the second line of (1): the quaternion is consistent with
the reduced flow, and ``|q|`` is an integral (``q . dq/dt = 0``).

>>> f = attitude_field()
>>> len(f), sp.expand(sum(Q[i] * f[6 + i] for i in range(4)))
(10, 0)
"""

from __future__ import annotations

from functools import cache

import sympy as sp

from andoyer.symbolic.hamiltonian import H_euler_poisson, S, euler_poisson_field

__all__ = ["Q", "quaternion_product", "rotation_matrix_expr", "angular_velocity",
           "attitude_field"]

#: The quaternion's components, scalar first.
Q: tuple[sp.Symbol, ...] = sp.symbols("q0:4", real=True)


def quaternion_product(p: tuple[sp.Expr, ...], q: tuple[sp.Expr, ...]) -> tuple[sp.Expr, ...]:
    """Hamilton's product ``p (x) q`` of scalar-first quaternions.

    Parameters
    ----------
    p, q : tuple of sympy.Expr
        Scalar-first quaternions.

    Examples
    --------
    >>> i, j = (0, 1, 0, 0), (0, 0, 1, 0)
    >>> quaternion_product(i, j)
    (0, 0, 0, 1)
    """
    p0, p1, p2, p3 = p
    q0, q1, q2, q3 = q
    return (p0 * q0 - p1 * q1 - p2 * q2 - p3 * q3,
            p0 * q1 + p1 * q0 + p2 * q3 - p3 * q2,
            p0 * q2 - p1 * q3 + p2 * q0 + p3 * q1,
            p0 * q3 + p1 * q2 - p2 * q1 + p3 * q0)


def rotation_matrix_expr(q: tuple[sp.Expr, ...] = Q) -> sp.Matrix:
    """``R(q)``: ``R x = q (x) (0, x) (x) q*`` (vector part), body -> space.

    Parameters
    ----------
    q : tuple of sympy.Expr, default Q
        A scalar-first quaternion (default the symbols ``q0 .. q3``).

    Examples
    --------
    >>> R = rotation_matrix_expr()
    >>> sp.simplify((R.T * R - sp.eye(3)).subs(Q[0], sp.sqrt(1 - Q[1]**2 - Q[2]**2 - Q[3]**2)))
    Matrix([
    [0, 0, 0],
    [0, 0, 0],
    [0, 0, 0]])
    """
    conj = (q[0], -q[1], -q[2], -q[3])
    cols = []
    for k in range(3):
        e = [0, 0, 0]
        e[k] = 1
        v = quaternion_product(quaternion_product(q, (0, *e)), conj)[1:]
        cols.append([sp.expand(x) for x in v])
    return sp.Matrix(cols).T


@cache
def angular_velocity() -> tuple[sp.Expr, ...]:
    """``omega = dH/dG`` (body frame) from the Hamiltonian written once."""
    H = H_euler_poisson()
    return tuple(sp.diff(H, s) for s in S.y[:3])


@cache
def attitude_field() -> tuple[sp.Expr, ...]:
    """``d(G, gamma, q)/dt``: the field (1) and ``dq/dt = q (x) (0, omega) / 2``."""
    qdot = quaternion_product(Q, (0, *angular_velocity()))
    return (*euler_poisson_field(), *(sp.expand(e / 2) for e in qdot))

