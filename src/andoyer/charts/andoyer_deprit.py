"""Andoyer-Deprit chart ``x = (l, g, L, G, M)``, Eqs. (5)-(6) of [1]_ and their inverse.

``G`` is the length of the angular momentum, ``L = G3`` its projection on the body
axis 3, ``M = (G, gamma)`` its projection on the vertical (the area integral, a
parameter of the motion); ``l`` is the angle from the body axis ``Ox`` to the node of
the invariant plane (perpendicular to G) with the body plane ``Oxy``; ``g`` the angle
in the invariant plane between that node and the node with the horizontal plane.
The sixth coordinate ``m`` (the node longitude, canonically conjugate to M) is cyclic:
the body-frame state ``y`` does not determine it.

Construction
------------
The body-to-space rotation is ``R = Rz(m) Rx(I) Rz(g) Rx(J) Rz(l)`` with
``cos J = L/G`` and ``cos I = M/G``; then ``G_body = R^T (G e_G)`` and
``gamma = R^T e_Z``. :func:`andoyer_to_ep_expr` applies those rotations in turn. The
result coincides with the paper's (5)-(6) (checked by :func:`andoyer.paper_check`).

Singular set
------------
``G = 0`` (everything undefined); ``L = +-G`` (``G1 = G2 = 0``: only ``l +- g`` is
defined, we return ``l = 0``); ``|M| = G`` (``gamma`` parallel to G: ``g`` undefined,
we return ``g = 0`` and ``M = +-G |gamma|`` exactly). :func:`to_andoyer` flags these
points in a mask (see :class:`Singular`) instead of returning NaN.

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring".
"""

from __future__ import annotations

import enum
import math
import warnings
from typing import Any, Literal, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.charts.euler_poisson import as_state
from andoyer.errors import SingularChartWarning
from andoyer.validation import checks_arguments, real_array

__all__ = [
    "COORDS",
    "SINGULAR_RTOL",
    "Singular",
    "andoyer_to_ep_expr",
    "rotation_chain_expr",
    "from_andoyer",
    "to_andoyer",
    "singular_mask",
    "singular_flags",
    "singular_distances",
    "require_regular",
    "warn_singular",
    "undefined_as_nan",
]

#: Order of the Andoyer-Deprit coordinates.
COORDS = ("l", "g", "L", "G", "M")

#: A point is flagged singular when its distance to the singular set, relative to G,
#: is below this (there the angles lose about ``eps / distance`` of accuracy).
SINGULAR_RTOL = 1e-12



class Singular(enum.IntFlag):
    """Bit flags of the singular sets of the Andoyer-Deprit and Hess charts."""

    NONE = 0
    #: ``L = +G`` or ``L = -G``: ``G1 = G2 = 0``; ``l`` set to 0 (``J1 = J2`` or ``J1 = 0``).
    L_EQ_PM_G = 1
    #: ``|M| = G``: gamma parallel to G; ``g`` set to 0, ``M`` to ``+-G |gamma|`` (``|J3| = J2``).
    M_EQ_PM_G = 2
    #: ``G = 0``: all angles set to 0, ``L = M = 0``.
    G_ZERO = 4


def rotation_chain_expr(l: Any, g: Any, G: Any, cJ: Any, sJ: Any, cI: Any, sI: Any, *,
                        sin: Any, cos: Any) -> tuple[Any, ...]:
    """Body-frame ``(G1, G2, G3, gamma1, gamma2, gamma3)`` from the rotation chain.

    ``cJ, sJ`` are the cosine and sine of the angle between G and the body axis 3
    (``cos J = L/G``), ``cI, sI`` those between G and the vertical (``cos I = M/G``).
    ``gamma = R^T e_Z`` with ``R = Rz(m) Rx(I) Rz(g) Rx(J) Rz(l)``; ``m`` drops out.

    Parameters
    ----------
    l, g : number, array or sympy.Expr
        Andoyer-Deprit angles (rad).
    G : number, array or sympy.Expr
        ``|G|``.
    cJ, sJ : number, array or sympy.Expr
        Cosine and sine of the angle between ``G`` and body axis 3 (``cos J = L/G``).
    cI, sI : number, array or sympy.Expr
        Cosine and sine of the angle between ``G`` and the vertical (``cos I = M/G``).
    sin, cos : callable
        The functions to use (NumPy's or SymPy's).
    """
    # The vertical in the invariant-plane frame (z along G): Rz(-g) (0, sin I, cos I).
    v0, v1, v2 = sI * sin(g), sI * cos(g), cI
    # Rx(-J): to the frame whose x axis is the node of the invariant and body planes.
    v1, v2 = v1 * cJ + v2 * sJ, -v1 * sJ + v2 * cJ
    # Rz(-l): to the body frame.
    gamma1 = v0 * cos(l) + v1 * sin(l)
    gamma2 = -v0 * sin(l) + v1 * cos(l)
    gamma3 = v2
    return G * sJ * sin(l), G * sJ * cos(l), G * cJ, gamma1, gamma2, gamma3


def andoyer_to_ep_expr(l: Any, g: Any, L: Any, G: Any, M: Any, *, sin: Any, cos: Any,
                       sqrt: Any) -> tuple[Any, ...]:
    """Map ``(l, g, L, G, M) -> (G1, G2, G3, gamma1, gamma2, gamma3)`` written once.

    ``sin, cos, sqrt`` come from NumPy (numbers) or SymPy (derivations); the map is
    the rotation chain of the module docstring, so it equals Eqs. (5)-(6) of the paper.
    Radicands are written as products, ``(G - L)(G + L)``, so that they keep their
    relative accuracy near ``L = +-G``.

    Parameters
    ----------
    l, g, L, G, M : number, array or sympy.Expr
        Andoyer-Deprit coordinates (Eq. (7)): angles ``l, g`` (rad), actions ``L, G, M``.
    sin, cos, sqrt : callable
        The functions to use (NumPy's or SymPy's).
    """
    return rotation_chain_expr(l, g, G, L / G, sqrt((G - L) * (G + L)) / G,
                               M / G, sqrt((G - M) * (G + M)) / G, sin=sin, cos=cos)


def as_andoyer(x: ArrayLike, name: str = "x") -> NDArray[np.float64]:
    """Validate Andoyer-Deprit coordinates of shape ``(..., 5)``: ``G > 0``, ``|L|, |M| <= G``.

    Values of ``|L|`` or ``|M|`` above ``G`` by less than ``SINGULAR_RTOL * G`` are
    clipped to ``+-G`` (round-off); larger excesses raise ``ValueError``.
    """
    arr = real_array(name, x, copy=True)
    if arr.ndim == 0 or arr.shape[-1] != 5:
        raise ValueError(f"{name} must have shape (..., 5) = (l, g, L, G, M), "
                         f"got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} contains NaN or infinity")
    L, G, M = arr[..., 2], arr[..., 3], arr[..., 4]
    if np.any(G <= 0.0):
        raise ValueError(f"{name}: G (length of the angular momentum) must be > 0; "
                         "the chart is singular at G = 0, use the Euler-Poisson state there")
    for k, label in ((2, "L"), (4, "M")):
        v = arr[..., k]
        excess = np.abs(v) - G
        if np.any(excess > SINGULAR_RTOL * G):
            raise ValueError(f"{name}: |{label}| must not exceed G (a projection of the "
                             f"angular momentum), max |{label}| - G = {excess.max():.3g}")
        arr[..., k] = np.clip(v, -G, G)
    del L, M
    return arr


@checks_arguments
def from_andoyer(x: ArrayLike, *, name: str = "x") -> NDArray[np.float64]:
    """Euler-Poisson state from Andoyer-Deprit coordinates, Eqs. (5)-(6).

    Parameters
    ----------
    x : array_like, shape (..., 5)
        ``(l, g, L, G, M)`` with ``G > 0``, ``|L| <= G``, ``|M| <= G``.
    name : str, default "x"
        The argument's name in error messages (a caller passes its own).

    Returns
    -------
    y : ndarray, shape (..., 6)
        ``(G1, G2, G3, gamma1, gamma2, gamma3)`` with ``|gamma| = 1``.

    Examples
    --------
    >>> y = from_andoyer([0.3, 1.1, 0.2, 1.0, -0.4])
    >>> bool(np.allclose(to_andoyer(y), [0.3, 1.1, 0.2, 1.0, -0.4]))
    True
    """
    arr = as_andoyer(x, name)
    # The map is homogeneous in the actions (L, G, M): of degree 1 for G1, G2, G3 and 0
    # for gamma. It is evaluated at actions scaled by a power of two (exact), G/s in
    # [1, 2), so that the radicands (G - L)(G + L) neither overflow (G = 1e201) nor
    # underflow (G = 1e-200), and keep their accuracy near L = +-G.
    s = np.ldexp(1.0, np.frexp(arr[..., 3])[1] - 1)
    arr[..., 2:] /= s[..., None]
    cols = andoyer_to_ep_expr(*np.moveaxis(arr, -1, 0), sin=np.sin, cos=np.cos,
                              sqrt=np.sqrt)
    y = np.stack(np.broadcast_arrays(*cols), axis=-1)
    y[..., :3] *= s[..., None]
    return y


def singular_mask(y: ArrayLike, scale: ArrayLike | None = None) -> NDArray[np.int_]:
    """:class:`Singular` flags of Euler-Poisson states (0 at regular points).

    ``G = 0`` is flagged where ``|G| <= SINGULAR_RTOL * scale`` (``scale``, e.g.
    :func:`andoyer.charts.euler_poisson.momentum_bound`, broadcasts against the states;
    without it only ``G == 0`` exactly); ``L = +-G`` and ``|M| = G`` relative to ``|G|``.

    Parameters
    ----------
    y : array_like, shape (..., 6)
        Euler-Poisson states.
    scale : array_like, optional
        Momentum scale for ``G = 0`` (without it only ``G == 0`` exactly is flagged).
    """
    arr = as_state(y)
    return singular_flags(arr, scale)[0]


def singular_distances(y: ArrayLike, scale: ArrayLike) -> NDArray[np.float64]:
    """Relative distances of states to the singular sets, shape ``(..., 3)``.

    Columns: ``|G| / scale`` (to ``G = 0``), ``sqrt(G1^2 + G2^2) / |G|`` (to ``L = +-G``,
    the sine of the angle between G and body axis 3) and ``|G x gamma| / (|G| |gamma|)``
    (to ``|M| = G``, the sine of the angle between G and the vertical). An angle that
    depends on a set is resolved to about ``(state error) / distance``; the distances to
    ``L = +-G`` and ``|M| = G`` are 0 where ``G = 0``.

    Parameters
    ----------
    y : array_like, shape (..., 6)
        Euler-Poisson states.
    scale : array_like
        Momentum scale (e.g. :func:`andoyer.charts.euler_poisson.momentum_bound`),
        broadcast against the states.

    Examples
    --------
    >>> d = singular_distances([0.0, 0.6, 0.8, 0.0, 0.0, 1.0], 2.0)
    >>> [round(float(v), 12) for v in d]
    [0.5, 0.6, 0.6]
    """
    arr = as_state(y)
    Gv, gamma = arr[..., :3], arr[..., 3:]
    G = np.linalg.norm(Gv, axis=-1)
    rho = np.hypot(Gv[..., 0], Gv[..., 1])
    cross = np.linalg.norm(np.cross(Gv, gamma), axis=-1)
    gnorm = np.linalg.norm(gamma, axis=-1)
    s = np.asarray(scale, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        dG = np.where(s > 0, G / np.where(s > 0, s, 1.0), np.where(G > 0, np.inf, 0.0))
        dL = np.where(G > 0, rho / np.where(G > 0, G, 1.0), 0.0)
        dM = np.where(G * gnorm > 0, cross / np.where(G * gnorm > 0, G * gnorm, 1.0), 0.0)
    return np.stack(np.broadcast_arrays(dG, dL, dM), axis=-1)


def singular_flags(arr: NDArray[np.float64], scale: ArrayLike | None = None
                   ) -> tuple[NDArray[np.int_], NDArray[np.float64], NDArray[np.float64],
                              NDArray[np.float64]]:
    """``(flags, |G|, sqrt(G1^2 + G2^2), |gamma|)`` of validated states ``arr``.

    The flags as in :func:`singular_mask`; the lengths are returned because the chart
    maps need them too.

    Parameters
    ----------
    arr : ndarray, shape (..., 6)
        Validated Euler-Poisson states.
    scale : array_like, optional
        Momentum scale, as in :func:`singular_mask`.
    """
    Gv, gamma = arr[..., :3], arr[..., 3:]
    G = np.linalg.norm(Gv, axis=-1)
    rho = np.hypot(Gv[..., 0], Gv[..., 1])
    gnorm = np.linalg.norm(gamma, axis=-1)
    # |G x gamma| = G |gamma| sin I measures the distance to |M| = G.
    cross = np.linalg.norm(np.cross(Gv, gamma), axis=-1)
    flags = np.zeros(G.shape, dtype=int)
    flags |= np.where(rho <= SINGULAR_RTOL * G, int(Singular.L_EQ_PM_G), 0)
    flags |= np.where(cross <= SINGULAR_RTOL * G * gnorm, int(Singular.M_EQ_PM_G), 0)
    zero = G == 0.0
    if scale is not None:
        zero = zero | (G <= SINGULAR_RTOL * np.asarray(scale, dtype=float))
    flags = np.where(zero, int(Singular.G_ZERO), flags)
    return flags, G, rho, gnorm


@overload
def to_andoyer(y: ArrayLike, *, with_mask: Literal[False] = ...) -> NDArray[np.float64]: ...
@overload
def to_andoyer(y: ArrayLike, *, with_mask: Literal[True]
               ) -> tuple[NDArray[np.float64], NDArray[np.int_]]: ...
@checks_arguments
def to_andoyer(y: ArrayLike, *, with_mask: bool = False
               ) -> NDArray[np.float64] | tuple[NDArray[np.float64], NDArray[np.int_]]:
    """Andoyer-Deprit coordinates of Euler-Poisson states (inverse of (5)-(6)).

    ``L = G3``, ``G = |G|``, ``M = (G, gamma)``; ``l = atan2(G1, G2)`` and
    ``g = atan2(G (G2 gamma1 - G1 gamma2), G3 (G1 gamma1 + G2 gamma2) - gamma3 (G1^2 + G2^2))``
    -- quadrant-correct, where the paper writes ``l = arctg(G1/G2)``. Angles in
    ``[0, 2 pi)``.

    Parameters
    ----------
    y : array_like, shape (..., 6)
        Euler-Poisson states. ``gamma`` need not be exactly unit: ``M`` uses it as given.
    with_mask : bool, default False
        Also return the :class:`Singular` flags. On the singular set the returned
        values are the conventions of the module docstring (never NaN); without the
        mask, states there raise a :class:`~andoyer.errors.SingularChartWarning`.

    Returns
    -------
    x : ndarray, shape (..., 5)
        ``(l, g, L, G, M)``.
    mask : ndarray of int, shape (...)
        Only with ``with_mask=True``.

    Warns
    -----
    SingularChartWarning
        Without ``with_mask``, when some state lies on the singular set (relative
        distance below :data:`SINGULAR_RTOL`): its angles there are conventions.

    Examples
    --------
    >>> x, flags = to_andoyer([0.0, 0.0, 1.0, 0.0, 0.6, 0.8], with_mask=True)
    >>> x.round(12).tolist(), Singular(int(flags))
    ([0.0, 0.0, 1.0, 1.0, 0.8], <Singular.L_EQ_PM_G: 1>)
    """
    arr = np.array(as_state(y), dtype=float)
    # The angles are homogeneous of degree 0 in (G1, G2, G3), the actions of degree 1:
    # evaluated at G scaled by a power of two (exact) so that |G|^2 cannot overflow.
    s = np.ldexp(1.0, np.frexp(np.max(np.abs(arr[..., :3]), axis=-1))[1] - 1)
    arr[..., :3] /= s[..., None]
    flags, G, rho, gnorm = singular_flags(arr)
    G1, G2, G3, gamma1, gamma2, gamma3 = np.moveaxis(arr, -1, 0)
    M = G1 * gamma1 + G2 * gamma2 + G3 * gamma3
    # On |M| = G the dot product misses +-G|gamma| by round-off, which from_andoyer
    # would turn into a spurious sin I ~ sqrt(eps) (gamma off G by ~1e-8): pin M to
    # +-G|gamma|, and to +-G where |gamma| = 1 up to round-off.
    gunit = np.where(np.abs(gnorm - 1.0) <= 4.0 * np.finfo(float).eps, 1.0, gnorm)
    M = np.where(flags & int(Singular.M_EQ_PM_G), np.copysign(G * gunit, M), M)
    # The convention on L = +-G exactly is l = 0; atan2(-0., -0.) = -pi, hence the where.
    l = np.where(rho == 0.0, 0.0, np.arctan2(G1, G2))
    Gsafe = np.where(G > 0.0, G, 1.0)
    sl, cl = np.sin(l), np.cos(l)
    # gamma in the invariant-plane frame: Rx(J) Rz(l) gamma, with cos J = L/G.
    v0 = gamma1 * cl - gamma2 * sl
    u = gamma1 * sl + gamma2 * cl
    v1 = (u * G3 - gamma3 * rho) / Gsafe
    g = np.where(flags & int(Singular.M_EQ_PM_G), 0.0, np.arctan2(v0, v1))
    x = np.stack(np.broadcast_arrays(np.mod(l, math.tau), np.mod(g, math.tau), G3, G, M),
                 axis=-1)
    zero = flags == int(Singular.G_ZERO)
    x = np.where(zero[..., None], 0.0, x)
    # mod can round 2 pi - tiny up to exactly 2 pi.
    x[..., :2] = np.where(x[..., :2] >= math.tau, 0.0, x[..., :2])
    x[..., 2:] *= s[..., None]
    if with_mask:
        return x, flags
    warn_singular(flags, "to_andoyer")
    return x


def warn_singular(flags: NDArray[np.int_], what: str, stacklevel: int = 3) -> None:
    """Warn (:class:`~andoyer.errors.SingularChartWarning`) if any flag is set: the
    angles of those points are the chart's conventions, not data.

    Parameters
    ----------
    flags : ndarray of int
        :class:`Singular` flags.
    what : str
        The caller, named in the warning.
    stacklevel : int, default 3
        Passed to :func:`warnings.warn`.
    """
    flags = np.asarray(flags)
    if not np.any(flags):
        return
    counts = ", ".join(f"{name} {int(np.count_nonzero(flags & int(bit)))}"
                       for name, bit in (("G = 0:", Singular.G_ZERO),
                                         ("L = +-G:", Singular.L_EQ_PM_G),
                                         ("|M| = G:", Singular.M_EQ_PM_G)))
    warnings.warn(
        f"{what}: {int(np.count_nonzero(flags))} of {flags.size} states lie on the chart's "
        f"singular set ({counts}), where an angle is undefined: the angles returned there "
        "are conventions (l = 0 on L = +-G, g = 0 on |M| = G, all 0 at G = 0), not data. "
        "Pass with_mask=True for the flags of those points.",
        SingularChartWarning, stacklevel=stacklevel)


def undefined_as_nan(x: NDArray[np.float64], flags: NDArray[np.int_]
                     ) -> NDArray[np.float64]:
    """A copy of ``to_andoyer``'s ``x`` with NaN for the angles its ``flags`` leave
    undefined: ``l`` and ``g`` at ``G = 0`` and on ``L = +-G`` (only ``l +- g`` exists
    there), ``g`` on ``|M| = G``. Charts derived from ``x`` (Hess, (14)) inherit the NaN
    exactly where their angles depend on an undefined one.

    Parameters
    ----------
    x : ndarray, shape (..., 5)
        ``(l, g, L, G, M)`` from :func:`to_andoyer`.
    flags : ndarray of int
        Its :class:`Singular` flags.

    Examples
    --------
    >>> x, flags = to_andoyer([0.6, 0.0, 0.8, 0.6, 0.0, 0.8], with_mask=True)
    >>> undefined_as_nan(x, flags)[:2].tolist()
    [1.5707963267948966, nan]
    """
    f = np.asarray(flags)[..., None]
    both = (f & int(Singular.L_EQ_PM_G | Singular.G_ZERO)) != 0
    g_only = (f & int(Singular.M_EQ_PM_G)) != 0
    out = np.array(x, dtype=float)
    out[..., :2] = np.where(both | (g_only & (np.arange(2) == 1)), np.nan, out[..., :2])
    return out


def require_regular(flags: NDArray[np.int_], what: str) -> None:
    """Raise ``ValueError`` if any flag is set; ``what`` names the caller.

    Parameters
    ----------
    flags : ndarray of int
        :class:`Singular` flags (:func:`singular_mask`).
    what : str
        The caller, named in the error.
    """
    if np.any(flags):
        bad = Singular(int(np.bitwise_or.reduce(np.ravel(flags))))
        raise ValueError(
            f"{what} needs regular points of the Andoyer-Deprit chart, but some lie on "
            f"its singular set ({bad!r}: L = +-G, |M| = G or G = 0); use the "
            "Euler-Poisson description there")
