r"""Tangent flows at output times on the Taylor method: renormalised, with the MEGNO
quadratures (the ``tangent`` capability of the taylor engine).

One orbit carries ``k`` tangent vectors of the linearised flow :math:`\dot w = J(y) w`
beside the state ``y`` of (1). The jets are those of :mod:`andoyer.kernels.taylor.flow`
(the state's by ``ep_taylor_jet``, each vector's by ``ep_taylor_tangent_jet``, through
:func:`andoyer.kernels.taylor.jets.tangent_jets`: one owner of the variational jets);
this module adds the renormalisation, the MEGNO quadratures and the orbit loop.

Renormalisation
---------------
The variational equations are linear in ``w``, so a vector may be rescaled by a constant
at any time without changing its direction's evolution. At the start of every step each
vector is divided by its length and ``ln|w_i|`` is added to ``rho_i``; within the step
``w_i(tau)`` is the step's Taylor polynomial, and at an output time

.. math::

   u_i = \frac{w_i(\tau)}{|w_i(\tau)|}, \qquad
   \rho_i = \rho_i(t_0) + \ln |w_i(\tau)|,

the quantities ``w_i = e^{rho_i} u_i`` of the continuous renormalisation of
:mod:`andoyer.kernels.dop853.tangent` (:math:`\dot u = J u - f u`, :math:`\dot\rho = f`,
:math:`f = u \cdot J u / u \cdot u`), without its nonlinear term in the field. As
``|w_i| = 1`` at each step's start, nothing overflows however long the flight (a step
multiplies ``|w_i|`` by a bounded factor).

MEGNO quadratures: extra jet variables
--------------------------------------
The quadratures of the first vector (Cincotta & Simo [1]_, with the shifted weights of
:mod:`andoyer.integrate.variational`, ``delta`` = :data:`~andoyer.kernels.common.MEGNO_DELTA`)

.. math::

   \dot N = (t + \delta) f, \qquad \dot I = \frac{2 N}{t + \delta}, \qquad
   f = \frac{d\rho_1}{dt}, \quad N(0) = I(0) = 0,

are integrated as extra jet variables of the same Taylor step (order ``p``, step ``h``):
their coefficients about the step's start :math:`t_0` (:math:`s_0 = t_0 + \delta`)
follow from the first vector's jets :math:`w^{[j]}` by the recurrences of these
equations,

.. math::

   P_k = \sum_{j=0}^{k} w^{[j]} \cdot w^{[k-j]}, \qquad
   \ell_k = \frac{1}{P_0}\Big(P_k - \frac1k \sum_{j=1}^{k-1} j\, \ell_j P_{k-j}\Big),
   \qquad L_k = \ell_k / 2

(:math:`L = \ln|w_1|` relative to the step's start: ``ln P`` by the Taylor recurrence
of the logarithm, :math:`P \dot\ell = \dot P`, so :math:`f = \dot L`),

.. math::

   N_k = s_0 L_k + \frac{k-1}{k} L_{k-1}, \qquad
   g_0 = \frac{N_0}{s_0},\ g_k = \frac{N_k - g_{k-1}}{s_0}, \qquad
   I_k = \frac{2 g_{k-1}}{k} \quad (k \ge 1)

(:math:`N' = (s_0 + \tau) L'`, :math:`g = N / (s_0 + \tau)` by the division
recurrence), with :math:`N_0, I_0` their values at :math:`t_0`. They are evaluated at
output times and at the step's end by Horner, as the state.

Why jets and not a quadrature rule on samples of :math:`\rho`: this is exactly what the
Taylor method does with the quadratures as state variables (heyoka's system of
:mod:`andoyer.integrate.engines.heyoka_tangent`), so their truncation error is of the
order of the state's, nothing is sampled, and their series take part in the step size:
``I``'s has the pole of :math:`1/(t + \delta)` at distance :math:`s_0`, which keeps the
first steps after t = 0 short while ``I`` is large relative to the tolerance (heyoka's
steps are limited the same way), and ``L``'s guards the complex zeros of
:math:`w \cdot w`. The quadratures are unscaled (each jet block has its own error scale,
so their size never loosens the state's control; the engine's ``scale`` is not used).

Step size: Jorba-Zou's (:mod:`andoyer.kernels.taylor.flow`), the least radius over the state,
each vector (``m = 1`` after the renormalisation: absolute error = relative error of
``w``), ``L`` (``m = 1``: an absolute error of ``rho``) and, while the pole of ``I`` is
nearer than that radius (:math:`s_0 \le r`: the first steps), ``I`` (``m = max(1,
|I_0|)``). ``N`` has ``L``'s singularities (:math:`N' = (s_0 + \tau) L'`), and once
:math:`s_0 > r` the series of ``I`` converges faster than the state's (its terms fall
as :math:`(h / s_0)^k` with :math:`h \approx r / e^2`), so neither is measured then.

Entry point (cached, ``nogil``; blocks of orbits in threads,
:func:`andoyer.kernels.threads.over_orbits`): :func:`propagate`. Its rows have the
layout of :func:`andoyer.kernels.common.layout` (``y``, ``u_1 .. u_k``, ``rho_1 ..
rho_k``, ``N``, ``I``); ``info`` columns are :data:`andoyer.kernels.common.INFO`.

References
----------
.. [1] P. M. Cincotta, C. Simo, "Simple tools to study global dynamics in
   non-axisymmetric galactic potentials - I", Astron. Astrophys. Suppl. 147, 205
   (2000), Eqs. (4)-(6) (MEGNO and its mean).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from andoyer.kernels import common
from andoyer.kernels.common import (
    INFO,
    MAX_STEPS,
    MEGNO_DELTA,
    N_STATE,
    STEP_TOO_SMALL,
    dimension,
    exact_jit,
    fast_jit,
    kernel_jit,
    source_stamp,
)
from andoyer.kernels.generated import recurrences
from andoyer.kernels.taylor import flow, jets, sections
from andoyer.kernels.taylor.flow import order_for
from andoyer.kernels.taylor.jets import (
    advance,
    fill_constants,
    horner,
    load,
    radius,
    tangent_jets,
)
from andoyer.kernels.threads import over_orbits

__all__ = ["TANGENT_STAMP", "megno_jets", "renormalised_orbit",
           "propagate_block", "propagate"]

_N = N_STATE
_N_Q = 5  # rows of the quadrature jets: L, N, I, and the work rows P, g

#: Hash of every source the compiled entry point depends on (its cache key).
TANGENT_STAMP = source_stamp(__file__, flow.__file__, recurrences.__file__, jets.__file__,
                             sections.__file__, common.__file__)


@fast_jit
def megno_jets(X, order, s0, Q):
    """Jets of the MEGNO quadratures (module notes) from the first vector's jets
    ``X[1]``: ``Q[0]`` = L, ``Q[1]`` = N, ``Q[2]`` = I (rows ``Q[1, 0], Q[2, 0]`` hold
    their values at the step's start, set by the caller), ``Q[3]``, ``Q[4]`` work rows
    (P and g). ``Q`` has shape (5, order + 1, 1); ``s0 = t0 + delta``."""
    L = Q[0, :, 0]
    N = Q[1, :, 0]
    I = Q[2, :, 0]  # noqa: E741 (the paper's symbol)
    P = Q[3, :, 0]
    g = Q[4, :, 0]
    w = X[1]
    for k in range(order + 1):  # the Cauchy product w.w, each pair of terms once
        s = 0.0
        for j in range((k + 1) // 2):
            a = w[j]
            b = w[k - j]
            s += (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
                  + a[3] * b[3] + a[4] * b[4] + a[5] * b[5])
        s *= 2.0
        if k % 2 == 0:
            a = w[k // 2]
            s += (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]
                  + a[3] * a[3] + a[4] * a[4] + a[5] * a[5])
        P[k] = s
    inv_p0 = 1.0 / P[0]
    inv_s0 = 1.0 / s0
    L[0] = 0.5 * math.log(P[0])
    g[0] = N[0] * inv_s0
    ell_prev = 0.0  # l_{k-1} = 2 L_{k-1} (ln P), carried to N_k
    for k in range(1, order + 1):
        inv_k = 1.0 / k
        acc = 0.0
        for j in range(1, k):
            acc += j * L[j] * P[k - j]  # L_j = l_j / 2, hence the 2 below
        ell = (P[k] - 2.0 * acc * inv_k) * inv_p0
        L[k] = 0.5 * ell
        N[k] = s0 * L[k] + (k - 1) * inv_k * 0.5 * ell_prev
        ell_prev = ell
        I[k] = 2.0 * g[k - 1] * inv_k
        if k < order:
            g[k] = (N[k] - g[k - 1]) * inv_s0


#: The kernel's own megno_jets: without Python and C-callback wrappers (kernel_jit);
#: ``megno_jets`` keeps its Python entry (tests).
_megno_jets = kernel_jit(megno_jets.py_func)


@kernel_jit
def _value(c, order, tau):
    """The polynomial of coefficients ``c[:order + 1, 0]`` at ``tau`` (Horner)."""
    v = c[order, 0]
    for k in range(order - 1, -1, -1):
        v = v * tau + c[k, 0]
    return v


@kernel_jit
def write_vectors(tmp, rho, row):
    """The state, unit vectors and logarithms of an output row (layout of the module
    notes) from ``tmp``, the state and the ``k`` vectors ``w_b`` at the row's time, and
    ``rho`` (shape (k,)): ``u_b = w_b / |w_b|``, ``rho_b + ln|w_b|``."""
    k = rho.shape[0]
    for i in range(_N):
        row[i] = tmp[i]
    for b in range(k):
        o = _N + _N * b
        s = 0.0
        for i in range(_N):
            s += tmp[o + i] * tmp[o + i]
        nrm = math.sqrt(s)
        for i in range(_N):
            row[o + i] = tmp[o + i] / nrm
        row[_N + _N * k + b] = rho[b] + math.log(nrm)


@kernel_jit
def _write_row(X, Q, order, tau, rho, tmp, row):
    """An output row (layout of the module notes) at ``t0 + tau``."""
    k = X.shape[0] - 1
    horner(X, order, tau, tmp)
    write_vectors(tmp, rho, row)
    row[_N + 7 * k] = _value(Q[1], order, tau)
    row[_N + 7 * k + 1] = _value(Q[2], order, tau)


@kernel_jit
def _renormalise(X, rho):
    """Rows 0 of the vectors' jets to unit length, their logarithms added to ``rho``."""
    for b in range(1, X.shape[0]):
        s = 0.0
        for i in range(_N):
            s += X[b, 0, i] * X[b, 0, i]
        nrm = math.sqrt(s)
        for i in range(_N):
            X[b, 0, i] /= nrm
        rho[b - 1] += math.log(nrm)


@kernel_jit
def renormalised_orbit(z0, rho0, t_out, q, order, max_steps, X, Q, out, info):
    """One orbit from ``z0 = (y, u_1 .. u_k)`` (unit vectors) and ``rho0`` (their log
    lengths): ``out[j]`` = the row at ``t_out[j]`` (non-decreasing; rows not reached
    stay as they are). The rows at the initial time are ``z0, rho0, 0, 0`` as given."""
    m = t_out.shape[0]
    k = X.shape[0] - 1
    nz = _N + _N * k
    rho = np.empty(k)
    for b in range(k):
        rho[b] = rho0[b]
    tmp = np.empty(nz)
    load(X, z0)
    Q[1, 0, 0] = 0.0
    Q[2, 0, 0] = 0.0
    for j in range(m):  # rows at the initial time
        if j > 0 and t_out[j] > t_out[0]:
            break
        for i in range(nz):
            out[j, i] = z0[i]
        for b in range(k):
            out[j, nz + b] = rho0[b]
        out[j, nz + k] = 0.0
        out[j, nz + k + 1] = 0.0
    if m == 1:
        return
    t = t_out[0]
    t_end = t_out[m - 1]
    j = 1
    while j < m and t_out[j] <= t:
        j += 1
    while j < m:
        if info[1] >= max_steps:
            info[0] = MAX_STEPS
            return
        tangent_jets(X, order, q)
        _megno_jets(X, order, t + MEGNO_DELTA, Q)
        info[3] += 1
        r = radius(X[0], order)
        for b in range(1, k + 1):
            r = min(r, radius(X[b], order))
        r = min(r, radius(Q[0], order))  # L (N has the same singularities)
        if not t + MEGNO_DELTA > r:  # I's pole at distance s0 = t + delta is near
            r = min(r, radius(Q[2], order))
        h = r * math.exp(-0.7 / (order - 1)) / (math.e * math.e)
        min_step = 10.0 * (np.nextafter(t, np.inf) - t)
        if not h >= min_step:  # also NaN (a non-finite state)
            info[0] = STEP_TOO_SMALL
            return
        t1 = t + h
        if t1 >= t_end:
            t1 = t_end
        h = t1 - t
        while j < m and t_out[j] <= t1:
            _write_row(X, Q, order, t_out[j] - t if t_out[j] < t1 else h, rho, tmp, out[j])
            j += 1
        advance(X, order, h)
        Q[1, 0, 0] = _value(Q[1], order, h)
        Q[2, 0, 0] = _value(Q[2], order, h)
        _renormalise(X, rho)
        info[1] += 1
        t = t1


def _build(stamp: str) -> Any:
    """The cached entry point, keyed on ``stamp`` (see :mod:`andoyer.kernels.dop853.flow`)."""

    @exact_jit
    def propagate_block(z0, rho0, t, p, order, max_steps, out, info):
        """:func:`propagate` of a block of orbits on the calling thread."""
        _ = len(stamp)  # keys the cache
        q = np.empty(recurrences.N_CONSTANTS)
        fill_constants(p, q)
        X = np.empty((z0.shape[1] // _N, order + 1, _N))
        Q = np.zeros((_N_Q, order + 1, 1))
        for i in range(z0.shape[0]):
            renormalised_orbit(z0[i], rho0[i], t, q, order, max_steps, X, Q, out[i],
                               info[i])

    return propagate_block


propagate_block = _build(TANGENT_STAMP)


def propagate(z0: np.ndarray, rho0: np.ndarray, t: np.ndarray, p: np.ndarray, tol: float,
              max_steps: int, *, block: int = 1, threads: int | None = None
              ) -> tuple[np.ndarray, np.ndarray]:
    """Renormalised tangent flows of many orbits at the output times ``t``.

    Parameters
    ----------
    z0 : ndarray, shape (n, 6 + 6 k)
        Initial states and unit vectors ``(y, u_1 .. u_k)`` at ``t[0]``
        (:func:`andoyer.integrate.engines.values.unit_vectors` splits given vectors).
    rho0 : ndarray, shape (n, k)
        ``ln|w_i(t[0])|``: where ``rho`` starts.
    t : ndarray, shape (m,)
        Output times, non-decreasing; the MEGNO weights are ``t + delta``.
    p : ndarray, shape (8,)
        Kernel parameters :data:`andoyer.kernels.dop853.flow.PARAMS`.
    tol : float
        Tolerance of the local error (:func:`andoyer.kernels.taylor.flow.order_for`).
    max_steps : int
        Maximum steps per orbit.
    block, threads : int
        Orbits per block and threads (:func:`andoyer.kernels.threads.over_orbits`).

    Returns
    -------
    z : ndarray, shape (n, m, 6 + 7 k + 2)
        Rows ``(y, u_1 .. u_k, rho_1 .. rho_k, N, I)``; NaN after a failure.
    info : ndarray of int64, shape (n, 4)
        Columns :data:`andoyer.kernels.common.INFO`.

    Examples
    --------
    >>> from andoyer import RigidBody, from_andoyer
    >>> y0 = from_andoyer([[0.3, 1.1, 0.2, 1.0, -0.4]])
    >>> z0 = np.concatenate([y0, [[0.0, 0.0, 0.0, 0.0, 0.0, 1.0]]], axis=1)
    >>> z, info = propagate(z0, np.log([[2.0]]), np.array([0.0, 1.0]),
    ...                     np.asarray(RigidBody.paper().engine_params), 1e-12, 10**6)
    >>> z.shape, float(z[0, 0, 12]) == float(np.log(2.0)), int(info[0, 0]) == common.SUCCESS
    ((1, 2, 15), True, True)
    """
    n = z0.shape[0]
    k = flow.n_vectors(z0.shape[1])
    if k < 1:
        raise ValueError("z0 must carry at least one tangent vector (6 + 6 k floats, k >= 1)")
    out = np.full((n, t.shape[0], dimension(k)), np.nan)
    info = np.zeros((n, len(INFO)), dtype=np.int64)
    rho = np.ascontiguousarray(np.broadcast_to(rho0, (n, k)), dtype=np.float64)
    over_orbits(propagate_block, n, (np.ascontiguousarray(z0, dtype=np.float64), rho),
                (out, info), (t, p, order_for(float(tol)), int(max_steps)), block=block,
                threads=threads)
    return out, info
