r"""The attitude of the body: unit quaternions, rotation matrices and Euler angles.

Conventions (the SymPy derivation of the attitude flow,
:mod:`andoyer.symbolic.attitude`, uses the same):

* a quaternion is ``q = (q0, q1, q2, q3)``, **scalar first**, of unit length;
* ``R(q)`` is the **active rotation body -> space**: the body-frame components ``x``
  of a vector have space-frame components ``R x``; ``R[i, j]`` is the space component
  ``i`` of the body axis ``j``. The space frame ``(X, Y, Z)`` is inertial with ``Z``
  the upward vertical; the body frame ``(x, y, z)`` the principal axes;
* the vertical is fixed in space: ``gamma = R^T e_Z`` (the last row of ``R``);
* **Euler angles** ``z-x-z``: ``R = Rz(psi) Rx(theta) Rz(phi)`` with the precession
  ``psi`` (about the vertical), the nutation ``theta`` (``cos theta = gamma3``, the
  tilt of the body axis ``z`` from the vertical) and the proper rotation ``phi``
  (about the body axis ``z``), so that

  .. math:: \gamma = (\sin\theta \sin\varphi,\ \sin\theta \cos\varphi,\ \cos\theta);

  ``phi = atan2(gamma1, gamma2)`` is the section angle ``psi`` of
  :class:`andoyer.integrate.engines.values.Section`, *not* the precession.

Precession and the Andoyer-Deprit node. From the kinematics of ``z-x-z`` angles,
``omega_1 = psi' sin theta sin phi + theta' cos phi`` and ``omega_2 = psi' sin theta
cos phi - theta' sin phi``, hence

.. math:: \dot\psi = \frac{\omega_1\gamma_1 + \omega_2\gamma_2}{\gamma_1^2 + \gamma_2^2},
   \qquad \boldsymbol\omega = \mathbf I^{-1} \mathbf G,

singular at ``theta = 0, pi`` (``gamma1 = gamma2 = 0``). The Andoyer-Deprit chart
writes the same rotation as ``R = Rz(m) Rx(I) Rz(g) Rx(J) Rz(l)``
(:mod:`andoyer.charts.andoyer_deprit`; ``cos I = M/G``, ``cos J = L/G``): the first
factor is the only one the reduced state ``(G, gamma)`` does not fix, so

.. math:: \psi = m + \psi\bigl(R_x(I) R_z(g) R_x(J) R_z(l)\bigr),

the node longitude ``m`` (conjugate to ``M``, ``dm/dt = dH/dM``) plus an angle of the
reduced state: :func:`andoyer_rotation` builds ``R`` from ``(l, g, L, G, M, m)``.
The quaternion is the regular description (no singular set); the Euler angles are
undefined where ``sin theta = 0``: :func:`euler_angles` returns NaN for ``psi`` and
``phi`` there and flags the points (``sin theta <=`` :data:`EULER_SINGULAR_RTOL`,
relative to ``|gamma| = 1``), never a conventional value that would pass for data.

Examples
--------
>>> q = quaternion_from_euler(0.3, 1.1, -0.4)
>>> [round(float(v), 12) for v in euler_angles(q)[:3]]
[0.3, 1.1, -0.4]
>>> R = rotation_matrix(q)
>>> bool(np.allclose(R @ R.T, np.eye(3)))
True
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.charts.andoyer_deprit import SINGULAR_RTOL, as_andoyer
from andoyer.validation import finite_array

__all__ = ["QUATERNION", "SPACE_AXES", "BODY_AXES", "EULER_SINGULAR_RTOL", "ROTATION_RTOL",
           "EulerAngles",
           "quaternion_product", "quaternion_conjugate", "rotation_matrix",
           "quaternion_from_matrix", "euler_angles", "quaternion_from_euler",
           "quaternion_from_vertical", "andoyer_rotation"]

#: Names of the quaternion components, scalar first.
QUATERNION = ("q0", "q1", "q2", "q3")
#: The inertial frame (``Z`` up) and the body's principal axes.
SPACE_AXES = ("X", "Y", "Z")
BODY_AXES = ("x", "y", "z")
#: ``psi`` and ``phi`` are undefined (NaN, flagged) where ``sin theta`` is below this.
EULER_SINGULAR_RTOL = SINGULAR_RTOL
#: A matrix is taken for a rotation where ``max |R^T R - 1| <= ROTATION_RTOL max(1, |R|^2)``
#: (``|R|`` its largest singular value: the tolerance is relative to the matrix's scale)
#: and ``det R > 0``; a matrix read from eight significant digits passes.
ROTATION_RTOL = 1e-8


def _quaternions(name: str, q: ArrayLike) -> NDArray[np.float64]:
    arr = finite_array(name, q)
    if arr.ndim == 0 or arr.shape[-1] != 4:
        raise ValueError(f"{name} must have shape (..., 4) = (q0, q1, q2, q3), scalar first, "
                         f"got shape {arr.shape}")
    norm = np.linalg.norm(arr, axis=-1)
    if np.any(norm == 0.0):
        raise ValueError(f"{name} holds a zero quaternion (no rotation)")
    return arr


def quaternion_product(left: ArrayLike, right: ArrayLike) -> NDArray[np.float64]:
    """Hamilton's product ``left (x) right`` of scalar-first quaternions (broadcast).

    Parameters
    ----------
    left, right : array_like, shape (..., 4)
        The factors (scalar first), broadcast.

    Examples
    --------
    >>> quaternion_product([0, 1, 0, 0], [0, 0, 1, 0]).tolist()  # i j = k
    [0.0, 0.0, 0.0, 1.0]
    """
    P, Q = _quaternions("left", left), _quaternions("right", right)
    p0, p1, p2, p3 = np.moveaxis(P, -1, 0)
    q0, q1, q2, q3 = np.moveaxis(Q, -1, 0)
    return np.stack(np.broadcast_arrays(p0 * q0 - p1 * q1 - p2 * q2 - p3 * q3,
                                        p0 * q1 + p1 * q0 + p2 * q3 - p3 * q2,
                                        p0 * q2 - p1 * q3 + p2 * q0 + p3 * q1,
                                        p0 * q3 + p1 * q2 - p2 * q1 + p3 * q0), axis=-1)


def quaternion_conjugate(q: ArrayLike) -> NDArray[np.float64]:
    """``q* = (q0, -q1, -q2, -q3)``: the inverse rotation of a unit quaternion.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Quaternions (scalar first).

    Examples
    --------
    >>> quaternion_conjugate([1.0, 2.0, 3.0, 4.0]).tolist()
    [1.0, -2.0, -3.0, -4.0]
    """
    return _quaternions("q", q) * np.array([1.0, -1.0, -1.0, -1.0])


def rotation_matrix(q: ArrayLike) -> NDArray[np.float64]:
    """``R(q)`` (body -> space), shape ``(..., 3, 3)``; ``q`` is normalised first.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Quaternions (scalar first).

    Examples
    --------
    >>> rotation_matrix([np.cos(0.5), 0.0, 0.0, np.sin(0.5)]).round(12)[:2, :2].tolist()
    [[0.540302305868, -0.841470984808], [0.841470984808, 0.540302305868]]
    """
    Q = _quaternions("q", q)
    Q = Q / np.linalg.norm(Q, axis=-1, keepdims=True)
    w, x, y, z = np.moveaxis(Q, -1, 0)
    rows = ((1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)),
            (2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)),
            (2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)))
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def _check_rotations(m: NDArray[np.float64]) -> None:
    """``ValueError`` naming ``R`` unless every matrix of ``m`` (n, 3, 3) is a rotation:
    orthogonal to :data:`ROTATION_RTOL` relative to its scale, with ``det > 0``."""
    if m.shape[0] == 0:
        return
    scale = np.maximum(np.linalg.norm(m, ord=2, axis=(1, 2)) ** 2, 1.0)
    defect = np.abs(np.einsum("nki,nkj->nij", m, m) - np.eye(3)).max(axis=(1, 2)) / scale
    det = np.linalg.det(m)
    bad = np.flatnonzero((defect > ROTATION_RTOL) | (det <= 0.0))
    if bad.size:
        i = int(bad[0])
        what = (f"not orthogonal (max |R^T R - 1| = {defect[i] * scale[i]:.3g}, relative "
                f"{defect[i]:.3g} > ROTATION_RTOL = {ROTATION_RTOL:g})"
                if defect[i] > ROTATION_RTOL else
                f"a reflection, not a rotation (det R = {det[i]:.6g})")
        where = f" (matrix {i} of {m.shape[0]})" if m.shape[0] > 1 else ""
        raise ValueError(f"R must hold rotation matrices (orthogonal, det R = +1); R is "
                         f"{what}{where}")


def quaternion_from_matrix(R: ArrayLike) -> NDArray[np.float64]:
    """The unit quaternion with ``q0 >= 0`` of a rotation matrix, by Shepperd's method.

    The largest of the squares ``q_i^2`` is taken from the diagonal, the others from it.

    Parameters
    ----------
    R : array_like, shape (..., 3, 3)
        Rotation matrices: orthogonal to :data:`ROTATION_RTOL` relative to their scale
        (``max |R^T R - 1| <= ROTATION_RTOL max(1, |R|^2)``) with ``det R > 0``; anything
        else (a reflection, a scaled or a singular matrix) is refused naming ``R``.

    Returns
    -------
    ndarray, shape (..., 4)
        Unit quaternions, scalar first, ``q0 >= 0``.

    Examples
    --------
    >>> q = quaternion_from_matrix(rotation_matrix([0.5, 0.5, -0.5, 0.5]))
    >>> q.round(12).tolist()
    [0.5, 0.5, -0.5, 0.5]
    >>> quaternion_from_matrix(-np.eye(3))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: R must hold rotation matrices ...; R is a reflection, ... (det R = -1)
    """
    M = finite_array("R", R)
    if M.ndim < 2 or M.shape[-2:] != (3, 3):
        raise ValueError(f"R must have shape (..., 3, 3), got {M.shape}")
    m = M.reshape(-1, 3, 3)
    _check_rotations(m)
    tr = np.trace(m, axis1=1, axis2=2)
    diag = np.stack([tr, m[:, 0, 0], m[:, 1, 1], m[:, 2, 2]], axis=1)
    k = np.argmax(diag, axis=1)
    out = np.empty((m.shape[0], 4))
    for i in range(m.shape[0]):
        r = m[i]
        if k[i] == 0:
            s = 2.0 * np.sqrt(max(1.0 + tr[i], 0.0))
            out[i] = (0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s,
                      (r[1, 0] - r[0, 1]) / s)
        elif k[i] == 1:
            s = 2.0 * np.sqrt(max(1.0 + r[0, 0] - r[1, 1] - r[2, 2], 0.0))
            out[i] = ((r[2, 1] - r[1, 2]) / s, 0.25 * s, (r[0, 1] + r[1, 0]) / s,
                      (r[0, 2] + r[2, 0]) / s)
        elif k[i] == 2:
            s = 2.0 * np.sqrt(max(1.0 - r[0, 0] + r[1, 1] - r[2, 2], 0.0))
            out[i] = ((r[0, 2] - r[2, 0]) / s, (r[0, 1] + r[1, 0]) / s, 0.25 * s,
                      (r[1, 2] + r[2, 1]) / s)
        else:
            s = 2.0 * np.sqrt(max(1.0 - r[0, 0] - r[1, 1] + r[2, 2], 0.0))
            out[i] = ((r[1, 0] - r[0, 1]) / s, (r[0, 2] + r[2, 0]) / s,
                      (r[1, 2] + r[2, 1]) / s, 0.25 * s)
    out *= np.where(out[:, :1] < 0.0, -1.0, 1.0)
    out /= np.linalg.norm(out, axis=1, keepdims=True)
    return out.reshape(*M.shape[:-2], 4)


class EulerAngles(NamedTuple):
    """``z-x-z`` Euler angles of rotations (see the module notes), in rad.

    Parameters
    ----------
    psi : ndarray
        Precession (rad).
    theta : ndarray
        Nutation (rad), in ``[0, pi]``.
    phi : ndarray
        Proper rotation (rad).
    singular : ndarray of bool
        Where ``sin theta`` is below the threshold: only ``psi +- phi`` is defined.
    """

    psi: NDArray[np.float64]       #: precession about the vertical, in (-pi, pi]; NaN if singular
    theta: NDArray[np.float64]     #: nutation, in [0, pi]: cos theta = gamma3
    phi: NDArray[np.float64]       #: proper rotation about body z, in (-pi, pi]; NaN if singular
    singular: NDArray[np.bool_]    #: sin theta <= EULER_SINGULAR_RTOL: psi, phi undefined


def euler_angles(q: ArrayLike) -> EulerAngles:
    """``(psi, theta, phi)`` of ``R(q) = Rz(psi) Rx(theta) Rz(phi)``, with the singular mask.

    ``theta = atan2(sin theta, gamma3)`` with ``sin theta = hypot(R31, R32)`` (accurate
    near 0 and pi, unlike ``acos``); ``psi = atan2(R13, -R23)``, ``phi = atan2(R31, R32)``.
    Where ``sin theta <= EULER_SINGULAR_RTOL`` only ``psi +- phi`` is defined: ``psi`` and
    ``phi`` are NaN there and ``singular`` is True.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Quaternions (scalar first; normalised first).

    Examples
    --------
    >>> e = euler_angles([1.0, 0.0, 0.0, 0.0])  # the identity: theta = 0
    >>> float(e.theta), bool(np.isnan(e.psi)), bool(e.singular)
    (0.0, True, True)
    """
    R = rotation_matrix(q)
    s = np.hypot(R[..., 2, 0], R[..., 2, 1])
    theta = np.arctan2(s, R[..., 2, 2])
    singular = s <= EULER_SINGULAR_RTOL
    psi = np.where(singular, np.nan, np.arctan2(R[..., 0, 2], -R[..., 1, 2]))
    phi = np.where(singular, np.nan, np.arctan2(R[..., 2, 0], R[..., 2, 1]))
    return EulerAngles(psi, theta, phi, np.asarray(singular))


def _axis_quaternion(angle: NDArray[np.float64], axis: int) -> NDArray[np.float64]:
    q = np.zeros((*np.shape(angle), 4))
    q[..., 0] = np.cos(0.5 * angle)
    q[..., 1 + axis] = np.sin(0.5 * angle)
    return q


def _rotations(*factors: tuple[NDArray[np.float64], int]) -> NDArray[np.float64]:
    out = _axis_quaternion(*factors[0])
    for f in factors[1:]:
        out = quaternion_product(out, _axis_quaternion(*f))
    return out


def quaternion_from_euler(psi: ArrayLike, theta: ArrayLike, phi: ArrayLike
                          ) -> NDArray[np.float64]:
    """The quaternion of ``Rz(psi) Rx(theta) Rz(phi)`` (any angles; broadcast).

    Parameters
    ----------
    psi, theta, phi : array_like
        ``z-x-z`` Euler angles (rad), broadcast.

    Examples
    --------
    >>> quaternion_from_euler(0.0, 0.0, 0.0).tolist()
    [1.0, 0.0, 0.0, 0.0]
    """
    a, b, c = (finite_array(n, v) for n, v in (("psi", psi), ("theta", theta),
                                               ("phi", phi)))
    a, b, c = np.broadcast_arrays(a, b, c)
    return _rotations((a, 2), (b, 0), (c, 2))


def quaternion_from_vertical(gamma: ArrayLike, psi: ArrayLike = 0.0) -> NDArray[np.float64]:
    """The attitude with vertical ``gamma`` (body components) and precession ``psi``.

    ``theta = atan2(hypot(gamma1, gamma2), gamma3)``, ``phi = atan2(gamma1, gamma2)``:
    the reduced state fixes everything but the rotation about the vertical, which
    ``psi`` gives. At ``theta = 0`` (``gamma = e_z``) ``phi = 0`` by convention and
    ``psi`` is the angle of ``R e_x`` from ``X`` (only ``psi + phi`` is defined there).

    Parameters
    ----------
    gamma : array_like, shape (..., 3)
        Body components of the upward vertical (normalised here).
    psi : array_like
        Precession angles (rad), broadcast against ``gamma[..., 0]``.

    Examples
    --------
    >>> q = quaternion_from_vertical([0.0, 0.6, 0.8], 0.25)
    >>> rotation_matrix(q)[2].round(12).tolist()  # gamma = R^T e_Z, the last row
    [0.0, 0.6, 0.8]
    """
    g = finite_array("gamma", gamma)
    if g.ndim == 0 or g.shape[-1] != 3:
        raise ValueError(f"gamma must have shape (..., 3), got {g.shape}")
    norm = np.linalg.norm(g, axis=-1)
    if np.any(norm == 0.0):
        raise ValueError("gamma holds a zero vector")
    g = g / norm[..., None]
    theta = np.arctan2(np.hypot(g[..., 0], g[..., 1]), g[..., 2])
    phi = np.arctan2(g[..., 0], g[..., 1])
    p = finite_array("psi", psi)
    p, theta, phi = np.broadcast_arrays(p, theta, phi)
    return _rotations((p, 2), (theta, 0), (phi, 2))


def andoyer_rotation(x: ArrayLike, m: ArrayLike) -> NDArray[np.float64]:
    """The quaternion of ``R = Rz(m) Rx(I) Rz(g) Rx(J) Rz(l)`` (the Andoyer-Deprit chain).

    Parameters
    ----------
    x : array_like, shape (..., 5)
        Andoyer-Deprit coordinates ``(l, g, L, G, M)`` (``cos J = L/G``, ``cos I = M/G``).
    m : array_like
        The node longitude (the cyclic angle conjugate to ``M``), broadcast against
        ``x[..., 0]``.

    Examples
    --------
    >>> from andoyer.charts.andoyer_deprit import from_andoyer
    >>> x = np.array([0.3, 1.1, 0.2, 1.0, -0.4])
    >>> R = rotation_matrix(andoyer_rotation(x, 0.7))
    >>> bool(np.allclose(R.T @ [0, 0, 1], from_andoyer(x)[3:]))
    True
    """
    X = as_andoyer(x)
    l, g, L, G, M = np.moveaxis(X, -1, 0)
    J = np.arctan2(np.sqrt((G - L) * (G + L)), L)
    incl = np.arctan2(np.sqrt((G - M) * (G + M)), M)
    mm = finite_array("m", m)
    mm, incl, g, J, l = np.broadcast_arrays(mm, incl, g, J, l)
    return _rotations((mm, 2), (incl, 0), (g, 2), (J, 0), (l, 2))
