r"""Alignment indices of several tangent vectors: SALI and GALI_k.

Both follow ``k >= 2`` deviation vectors of one orbit of (1) along the linearised flow
and measure how far they are from being linearly dependent:

* **SALI** (smaller alignment index, Skokos 2001 [1]_): for two unit vectors
  :math:`\hat w_1, \hat w_2`, :math:`\mathrm{SALI} = \min(\|\hat w_1 + \hat w_2\|,
  \|\hat w_1 - \hat w_2\|)`, between 0 (aligned) and :math:`\sqrt 2` (orthogonal);
* **GALI_k** (generalised alignment index, Skokos, Bountis & Antonopoulos 2007 [2]_):
  the volume of the parallelepiped of the ``k`` unit vectors, the product of the
  singular values of the ``6 x k`` matrix of :math:`\hat w_i` (as DynamicalSystems.jl's
  ``gali``), between 0 and 1. For ``k = 2``, ``GALI_2 = |sin angle|`` and
  ``SALI = 2 min(sin(angle/2), cos(angle/2))``, so both vanish together.

What they do (the theory of [2]_ for ``N`` degrees of freedom; here the reduced system
on a symplectic leaf ``|gamma| = 1, (G, gamma) = M`` has ``N = 2``, and the vectors
start in the leaf's 4-dimensional tangent space, which the linearised flow keeps):

* on a **chaotic** orbit every vector turns towards the most unstable direction, and
  :math:`\mathrm{GALI}_k \propto e^{-[(\lambda_1 - \lambda_2) + \dots + (\lambda_1 -
  \lambda_k)] t}`; with the exponents ``(lambda, 0, 0, -lambda)`` of a 2-dof Hamiltonian
  orbit, ``GALI_2 ~ exp(-lambda t)``, ``GALI_3 ~ exp(-2 lambda t)``, and SALI -> 0 at the
  rate of GALI_2;
* on a **regular** orbit on a 2-torus the vectors fall towards the torus's tangent
  plane (the shear between neighbouring tori turns every vector into it, linearly in
  t) but keep independent directions inside it: ``GALI_k`` tends to a positive
  constant for ``k <= N = 2`` and decays like :math:`t^{-2(k - N)}` for
  ``N < k <= 2N``: ``GALI_3 ~ t^-2``, ``GALI_4 ~ t^-4``. SALI, like GALI_2, stays of
  order one. (``t^-2`` is the law of GALI_2 only for ``N = 1``.)

The vectors are integrated with the state by any engine with the ``tangent``
capability (:meth:`EngineBase.tangent <andoyer.integrate.engines.base.EngineBase.tangent>`:
the variational equations, each vector renormalised continuously): heyoka's Taylor
method where installed, else the Taylor method in Numba (no heyoka needed; the Numba
DOP853 with ``engine="numba"``).

References
----------
.. [1] Ch. Skokos, "Alignment indices: a new, simple method for determining the ordered
   or chaotic nature of orbits", J. Phys. A 34, 10029 (2001).
.. [2] Ch. Skokos, T. C. Bountis, Ch. Antonopoulos, "Geometrical properties of local
   dynamics in Hamiltonian systems: the Generalized Alignment Index (GALI) method",
   Physica D 231, 30-54 (2007).
"""

from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.analysis.chaos.lyapunov import TANGENT_SPACES, Tangent, initial_tangent, output_times
from andoyer.body import RigidBody, checks_body
from andoyer.charts.euler_poisson import STATE
from andoyer.charts.integrals import INTEGRALS
from andoyer.errors import IntegrationError
from andoyer.integrate import budget
from andoyer.integrate.api import initial_states
from andoyer.integrate.engines import EngineLike, resolve_engine
from andoyer.integrate.engines.base import Capability, Tolerance
from andoyer.integrate.results import provenance
from andoyer.validation import checks_arguments, real_array

__all__ = ["sali", "gali", "initial_tangents", "alignment_indices", "MAX_K"]

#: Most vectors in each tangent space: the leaf's dimension is 4, the energy level's 3.
MAX_K = {"leaf": 4, "energy": 3}

# Fixed generic directions, projected and orthonormalised after the first vector (the
# same for every state, so results are deterministic and smooth in the initial state).
_DIRECTIONS = np.array([
    [math.sqrt(2), -1.0, math.sqrt(5), math.sqrt(3), -math.sqrt(7), 1.5],
    [-math.sqrt(3), math.sqrt(11), 1.0, -math.sqrt(2), 0.5, math.sqrt(13)],
    [math.sqrt(7), math.sqrt(5), -math.sqrt(3), 2.5, math.sqrt(2), -1.0],
    [1.0, -math.sqrt(13), math.sqrt(2), math.sqrt(5), math.sqrt(3), math.sqrt(7)],
    [-math.sqrt(5), 1.0, math.sqrt(7), -math.sqrt(11), 2.0, math.sqrt(3)],
])
_MIN_RESIDUAL = 0.1


def _unit(v: NDArray[np.float64]) -> NDArray[np.float64]:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _vectors(name: str, value: ArrayLike, min_ndim: int) -> NDArray[np.float64]:
    """``value`` as finite deviation vectors along the last axis, none of them zero (a
    zero vector has no direction: its alignment is undefined), or ``ValueError``."""
    arr = real_array(name, value)
    if arr.ndim < min_ndim or arr.shape[-1] < 2:
        need = "(..., d)" if min_ndim == 1 else "(..., k, d)"
        raise ValueError(f"{name} must have shape {need} with d >= 2 components, got shape "
                         f"{arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite, got NaN or infinity")
    # Scale each vector first: the norm of a huge vector (1e300) must not overflow.
    top = np.max(np.abs(arr), axis=-1, keepdims=True)
    if np.any(top == 0.0):
        raise ValueError(f"{name} holds a zero vector: it has no direction, so its "
                         "alignment is undefined")
    return arr / top


@checks_arguments
def sali(w1: ArrayLike, w2: ArrayLike) -> NDArray[np.float64]:
    """Smaller alignment index of two deviation vectors (any lengths), along the last axis.

    ``ValueError`` for zero, non-finite or mismatched vectors.

    Parameters
    ----------
    w1, w2 : array_like, shape (..., d)
        The two deviation vectors (normalised here), along the last axis; leading axes
        broadcast (orbits, times).

    Examples
    --------
    >>> float(sali([1, 0, 0, 0, 0, 0], [0, 3, 0, 0, 0, 0]))  # orthogonal: sqrt 2
    1.4142135623730951
    >>> float(sali([1, 1, 0, 0, 0, 0], [-2, -2, 0, 0, 0, 0]))  # anti-parallel
    0.0
    """
    u1 = _unit(_vectors("w1", w1, 1))
    u2 = _unit(_vectors("w2", w2, 1))
    if u1.shape[-1] != u2.shape[-1]:
        raise ValueError(f"w1 and w2 must have the same number of components, got "
                         f"{u1.shape[-1]} and {u2.shape[-1]}")
    try:
        np.broadcast_shapes(u1.shape, u2.shape)
    except ValueError:
        raise ValueError(f"w1 and w2 must have broadcastable shapes, got {u1.shape} and "
                         f"{u2.shape}") from None
    return np.minimum(np.linalg.norm(u1 + u2, axis=-1), np.linalg.norm(u1 - u2, axis=-1))


@checks_arguments
def gali(W: ArrayLike) -> NDArray[np.float64]:
    """GALI_k of ``k`` deviation vectors ``W[..., i, :]``: the product of the singular
    values of the matrix of the unit vectors (the volume they span).

    ``k`` must not exceed the dimension ``d`` (``k > d`` vectors span no k-volume: GALI
    is not defined); zero and non-finite vectors are refused (``ValueError``).

    Parameters
    ----------
    W : array_like, shape (..., k, d)
        ``k`` deviation vectors of dimension ``d`` (``k <= d``), along the last axis; any
        lengths (each is normalised first). Leading axes are orbits or times.

    Examples
    --------
    >>> float(gali(np.eye(6)[:3]))
    1.0
    >>> round(float(gali([[1, 0, 0, 0, 0, 0], [1, 1, 0, 0, 0, 0]])), 12)  # sin 45 deg
    0.707106781187
    """
    U = _unit(_vectors("W", W, 2))
    k, d = U.shape[-2:]
    if k > d:
        raise ValueError(f"W holds k = {k} vectors of dimension d = {d}: GALI_k needs "
                         "k <= d (more vectors than dimensions span no k-volume)")
    return np.prod(np.linalg.svd(U, compute_uv=False), axis=-1)


def _check_k(k: Any, tangent: str) -> int:
    if tangent not in TANGENT_SPACES:
        raise ValueError(f"unknown tangent space {tangent!r}; choose 'energy' or 'leaf'")
    top = MAX_K[tangent]
    if isinstance(k, bool) or not isinstance(k, numbers.Integral) or not 2 <= int(k) <= top:
        raise ValueError(f"k must be an integer from 2 to {top} (the dimension of the "
                         f"{tangent!r} tangent space), got {k!r}")
    return int(k)


@checks_body(ranges={"k": "count"})
def initial_tangents(body: RigidBody, y: ArrayLike, k: int,
                     tangent: Tangent = "leaf") -> NDArray[np.float64]:
    """``k`` orthonormal initial deviation vectors at Euler-Poisson states, (n, k, 6).

    The first is :func:`andoyer.analysis.chaos.lyapunov.initial_tangent` (the vector of the FLI
    and MEGNO); the others are fixed generic directions projected onto the same space
    (``"leaf"``: tangent to ``|gamma| = 1, (G, gamma) = M``; ``"energy"``: also to the
    energy level) and orthonormalised (Gram-Schmidt).

    Parameters
    ----------
    body : RigidBody
        The body whose energy level fixes the ``"energy"`` space.
    y : array_like, shape (6,) or (n, 6)
        Euler-Poisson states ``(G1, G2, G3, gamma1, gamma2, gamma3)`` of Eq. (1).
    k : int
        Number of deviation vectors (``1 <= k``, at most the dimension of the space: 4 on
        the leaf, 3 on the energy level).
    tangent : {"leaf", "energy"}, default "leaf"
        Space the vectors are tangent to: the symplectic leaf ``|gamma| = 1,
        (G, gamma) = M`` or, in addition, the energy level ``H = h``.

    Examples
    --------
    >>> from andoyer import from_andoyer
    >>> W = initial_tangents(RigidBody.paper(), from_andoyer([0.3, 0.0, 0.3, 1.0, 0.0]), 4)
    >>> bool(np.allclose(W[0] @ W[0].T, np.eye(4)))
    True
    """
    k = _check_k(k, tangent)
    Y = np.atleast_2d(np.asarray(y, dtype=float))
    W = np.zeros((Y.shape[0], k, len(STATE)))
    W[:, 0] = initial_tangent(body, Y, tangent)
    count = np.ones(Y.shape[0], dtype=int)
    for d in _DIRECTIONS:
        if np.all(count >= k):
            break
        try:
            v = initial_tangent(body, Y, tangent, direction=d)
        except ValueError:  # normal to the space at some state: try the next one
            continue
        for j in range(k - 1):  # Gram-Schmidt against the vectors taken so far
            taken = (j < count)[:, None]
            v = v - np.where(taken, np.einsum("ni,ni->n", v, W[:, j])[:, None] * W[:, j],
                             0.0)
        size = np.linalg.norm(v, axis=1)
        rows = np.flatnonzero((count < k) & (size > _MIN_RESIDUAL))
        W[rows, count[rows]] = v[rows] / size[rows, None]
        count[rows] += 1
    if np.any(count < k):
        raise RuntimeError("no generic direction completes the tangent basis; please "
                           "report this state")
    return W


@checks_body(ranges={"t_end": "time", "k": "count", "n_times": "count", "tol": "tolerance"})
def alignment_indices(body: RigidBody, y0: ArrayLike, t_end: float = 1000.0, *,
                      k: int = 2, n_times: int = 101, t: ArrayLike | None = None,
                      chart: str = "euler_poisson", tangent: Tangent = "leaf",
                      tol: float = 1e-12, engine: EngineLike = None) -> xr.Dataset:
    """SALI and GALI_k of orbits as functions of time, on any engine with tangent flows.

    Parameters
    ----------
    body : RigidBody
    y0 : array_like, shape (6,) or (n, 6) (or (5,)/(n, 5) in the other charts)
        Initial states in ``chart`` coordinates.
    t_end : float, default 1000
        Final time (body time units).
    k : int, default 2
        Deviation vectors: 2 to 4 in the leaf's tangent space, 2 to 3 on the energy level.
    n_times : int, default 101
        Output times ``linspace(0, t_end, n_times)`` (ignored when ``t`` is given).
    t : array_like, optional
        Increasing output times starting at 0.
    chart : {"euler_poisson", "andoyer", "hess"}
        Chart of ``y0``.
    tangent : {"leaf", "energy"}
        Space of the initial vectors (see :func:`initial_tangents`).
    tol : float, default 1e-12
        Accuracy asked for (DOP853 gets ``0.025 tol``; heyoka's Taylor tolerance).
    engine : str or Engine, optional
        Any engine with the ``tangent`` capability; default heyoka where installed,
        else taylor (no heyoka needed).

    Returns
    -------
    xarray.Dataset
        Dims ``(orbit, time)``: ``sali`` (of the first two vectors), ``gali`` (GALI_k),
        ``mle`` (``ln|w_1(t)|/t``), the Euler-Poisson state and ``H_drift``; dims
        ``(orbit, time, vector)``: ``log_norm`` (``ln|w_i|``); ``w0`` (orbit, vector,
        component). Attrs: body, engine, tolerance, k, definitions.

    Raises
    ------
    ValueError
        Invalid inputs; :class:`~andoyer.errors.IntegrationError` if an integration fails.

    Examples
    --------
    >>> ds = alignment_indices(RigidBody.paper(), [0.3, 0.0, 0.3, 1.0, 0.0], 200.0,
    ...                        chart="andoyer")
    >>> bool(float(ds.sali.isel(orbit=0, time=-1)) > 0.01)  # a torus: SALI stays > 0
    True
    """
    k = _check_k(k, tangent)
    eng = resolve_engine(engine, Capability.TANGENT)
    tolerance = Tolerance.single(tol)
    y = initial_states(body, y0, chart)
    times = output_times(t_end, n_times, t)
    T = float(times[-1])
    budget.check("alignment_indices",
                 steps=(1.0 + k) * budget.estimate_steps(body, y, T, tol),
                 memory=8.0 * (6 + 7 * k + 2) * y.shape[0] * times.size)
    W0 = initial_tangents(body, y, k, tangent)
    res = eng.tangent(y, W0, body.engine_params, tolerance, t=times, scale=T)
    if not res.ok.all():
        bad = np.flatnonzero(~res.ok).tolist()
        raise IntegrationError(f"the variational integration failed (non-finite state) "
                               f"for orbits {bad}")
    with np.errstate(divide="ignore", invalid="ignore"):
        mle = np.where(times > 0.0, res.rho[..., 0] / times, np.nan)
    H = INTEGRALS["H"](body, res.y)
    data: dict[str, Any] = {
        "sali": (("orbit", "time"), sali(res.u[..., 0, :], res.u[..., 1, :])),
        "gali": (("orbit", "time"), gali(res.u)),
        "mle": (("orbit", "time"), mle),
        "log_norm": (("orbit", "time", "vector"), res.rho),
        "H_drift": (("orbit", "time"), INTEGRALS["H"].drift(body, H, res.y[:, :1])),
        "w0": (("orbit", "vector", "component"), W0),
    }
    for i, s in enumerate(STATE):
        data[s] = (("orbit", "time"), res.y[..., i])
    meta = eng.provenance()
    built = meta.pop("tangent_method")
    ds = xr.Dataset(
        data, coords={"orbit": np.arange(y.shape[0]), "time": times,
                      "vector": np.arange(1, k + 1), "component": list(STATE)},
        attrs=provenance(
            body, **meta, tolerance=tol, t_end=T, k=k, tangent=tangent,
            initial_chart=chart,
            equations="Euler-Poisson equations (1) of Kyrychenko with k deviation vectors "
                      f"of their variational equations ({built}), each renormalised "
                      "continuously"))
    ds.sali.attrs.update(long_name="smaller alignment index of w1, w2", symbol="SALI",
                         units="1", definition="min(|u1 + u2|, |u1 - u2|), u = w/|w| "
                                               "(Skokos 2001)")
    ds.gali.attrs.update(long_name=f"generalised alignment index GALI_{k}",
                         symbol=f"GALI_{k}", units="1",
                         definition="product of the singular values of the unit "
                                    "deviation vectors (Skokos, Bountis & Antonopoulos "
                                    "2007)")
    ds.mle.attrs.update(long_name="finite-time maximal Lyapunov exponent ln|w1(t)|/t",
                        symbol="lambda", units="1 / body time unit")
    ds.log_norm.attrs.update(long_name="ln of the deviation vectors' norms",
                             symbol="ln|w_i|", units="1")
    ds.H_drift.attrs.update(long_name="(H - H(0)) / max(|H(0)|, mu)", units="1")
    ds.w0.attrs.update(long_name="initial unit deviation vectors (orthonormal)")
    ds.time.attrs.update(units="body time units", long_name="time")
    return ds
