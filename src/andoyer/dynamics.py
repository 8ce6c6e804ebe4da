"""Hamiltonians and vector fields of a body in any chart (friendly layer over kernels).

Charts are named ``"euler_poisson"`` (state ``(G1, G2, G3, gamma1, gamma2, gamma3)``),
``"andoyer"`` (``(l, g, L, G, M)``) and ``"hess"`` (``(theta1, theta2, J1, J2, J3)``).
All expressions come from the generated kernels, themselves derived from the one
Hamiltonian of Eq. (1).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.body import RigidBody, checks_body
from andoyer.charts.andoyer_deprit import as_andoyer, require_regular
from andoyer.charts.euler_poisson import as_state
from andoyer.charts.hess import as_hess
from andoyer.kernels.generated import equations as K

__all__ = ["CHARTS", "Chart", "hamiltonian", "vector_field", "cyclic_rate", "canonical_field"]

Chart = Literal["euler_poisson", "andoyer", "hess"]
#: Chart name -> coordinate names.
CHARTS: dict[str, tuple[str, ...]] = {
    "euler_poisson": ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3"),
    "andoyer": ("l", "g", "L", "G", "M"),
    "hess": ("theta1", "theta2", "J1", "J2", "J3"),
}

_HAMILTONIANS: dict[str, Callable[..., Any]] = {
    "euler_poisson": K.ep_hamiltonian, "andoyer": K.andoyer_hamiltonian,
    "hess": K.hess_hamiltonian}
_FIELDS: dict[str, Callable[..., Any]] = {
    "euler_poisson": K.ep_field, "andoyer": K.andoyer_field, "hess": K.hess_field}


def _chart_args(body: RigidBody, x: ArrayLike, chart: str
                ) -> tuple[NDArray[np.float64], tuple[float, ...]]:
    if not isinstance(chart, str) or chart not in CHARTS:
        raise ValueError(f"unknown chart {chart!r}; choose one of {sorted(CHARTS)}")
    if chart == "euler_poisson":
        return as_state(x, name="x"), body.params
    if chart == "andoyer":
        arr = as_andoyer(x)
        return arr, body.params
    if chart == "hess":
        arr = as_hess(x)
        return arr, (body.a, body.b, body.c, body.mu, body.phi0)
    raise ValueError(f"unknown chart {chart!r}; choose one of {sorted(CHARTS)}")


def _regular_check(arr: NDArray[np.float64], chart: str, what: str) -> None:
    if chart == "andoyer":
        L, G, M = arr[..., 2], arr[..., 3], arr[..., 4]
        flags = (np.abs(L) >= G) | (np.abs(M) >= G)
    elif chart == "hess":
        J1, J2, J3 = arr[..., 2], arr[..., 3], arr[..., 4]
        flags = (J1 <= 0.0) | (J1 >= J2) | (np.abs(J3) >= J2)
    else:
        return
    require_regular(flags.astype(int), what)


@checks_body
def hamiltonian(body: RigidBody, x: ArrayLike, chart: Chart = "euler_poisson"
                ) -> NDArray[np.float64]:
    """H of Eq. (1) expressed in ``chart`` (Eq. (7) in Andoyer-Deprit variables).

    Parameters
    ----------
    body : RigidBody
    x : array_like, shape (..., d)
        States in ``chart`` coordinates: ``(G1, G2, G3, gamma1, gamma2, gamma3)``,
        ``(l, g, L, G, M)`` or ``(theta1, theta2, J1, J2, J3)``.
    chart : {"euler_poisson", "andoyer", "hess"}
        Chart of ``x``.

    Returns
    -------
    ndarray, shape (...)

    Examples
    --------
    >>> from andoyer import RigidBody, to_andoyer, from_andoyer
    >>> body = RigidBody.paper()
    >>> x = [0.3, 1.0, 0.2, 1.0, 0.0]
    >>> bool(np.isclose(hamiltonian(body, x, "andoyer"),
    ...                 hamiltonian(body, from_andoyer(x))))
    True
    """
    arr, p = _chart_args(body, x, chart)
    fn = _HAMILTONIANS[chart]
    return np.asarray(fn(*np.moveaxis(arr, -1, 0), *p), dtype=np.float64)


def canonical_field(body: RigidBody, x: ArrayLike, chart: str) -> NDArray[np.float64]:
    """The chart's generated field with the cyclic angle's rate appended (last column):
    ``d(l, g, L, G, M, m)/dt`` or ``d(theta1, ..., J3, theta3)/dt``; regular points only.

    Parameters
    ----------
    body : RigidBody
        The body.
    x : array_like, shape (..., 5)
        Regular points of the chart: ``(l, g, L, G, M)`` or ``(theta1, theta2, J1, J2, J3)``.
    chart : {"andoyer", "hess"}
        The chart (Eq. (7) or Eqs. (13)-(14)).
    """
    arr, p = _chart_args(body, x, chart)
    _regular_check(arr, chart, f"the {chart} vector field")
    fn = _FIELDS[chart]
    cols = fn(*np.moveaxis(arr, -1, 0), *p)
    return np.stack(np.broadcast_arrays(*cols, arr[..., 0]), axis=-1)[..., :-1]


@checks_body
def vector_field(body: RigidBody, x: ArrayLike, chart: Chart = "euler_poisson"
                 ) -> NDArray[np.float64]:
    """Time derivative of the chart coordinates, same shape as ``x``.

    Euler-Poisson: the Lie-Poisson equations (1). Andoyer-Deprit: the canonical
    equations (4) (``dM/dt = 0``). Hess chart: the canonical equations whose ``M = 0``
    form is (16) (``dJ3/dt = 0``). The canonical charts need regular points
    (``|L| < G``, ``|M| < G``; ``0 < J1 < J2``, ``|J3| < J2``) and raise otherwise.

    Parameters
    ----------
    body : RigidBody
    x : array_like, shape (..., d)
        States in ``chart`` coordinates: ``(G1, G2, G3, gamma1, gamma2, gamma3)``,
        ``(l, g, L, G, M)`` or ``(theta1, theta2, J1, J2, J3)``.
    chart : {"euler_poisson", "andoyer", "hess"}
        Chart of ``x``.

    Returns
    -------
    ndarray, shape (..., d)
    """
    return canonical_field(body, x, chart)[..., : len(CHARTS[chart])]


@checks_body
def cyclic_rate(body: RigidBody, x: ArrayLike, chart: Chart = "andoyer"
                ) -> NDArray[np.float64]:
    """``dm/dt = dH/dM`` (``= dtheta3/dt = dH/dJ3``): the quadrature for the cyclic angle.

    Parameters
    ----------
    body : RigidBody
    x : array_like, shape (..., d)
        States in ``chart`` coordinates: ``(l, g, L, G, M)`` or ``(theta1, theta2, J1, J2, J3)``.
    chart : {"andoyer", "hess"}
        Chart of ``x``.

    Returns
    -------
    ndarray, shape (...)
    """
    if chart == "euler_poisson":
        raise ValueError("the cyclic angle m is a coordinate of the 'andoyer' and 'hess' "
                         "charts; convert the state with to_andoyer or to_hess first")
    return canonical_field(body, x, chart)[..., -1]
