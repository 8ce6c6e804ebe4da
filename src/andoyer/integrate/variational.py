"""Variational equations of the Euler-Poisson flow (1), for chaos indicators.

The tangent flow and the indicator integrals are one heyoka system of 15 variables,
compiled once and cached in memory and on disk:

* ``y = (G1, G2, G3, gamma1, gamma2, gamma3)``: the Euler-Poisson equations (1), the
  heyoka system of :mod:`andoyer.integrate.engines.heyoka_engine` (derived from
  ``H = (G, IG)/2 + mu (r, gamma)`` by SymPy, nothing typed by hand);
* ``w_G1 .. w_gamma3``: a tangent vector ``w`` carried by the linearised flow
  ``dw/dt = J(y) w``; ``J(y) w`` is built by :class:`heyoka.var_ode_sys` (first-order
  variational equations of (1)) and the vector is kept at unit length: the system
  integrates ``u = w / |w|`` and ``rho = ln |w|``,

  .. math::

     \\dot u = J u - f u, \\qquad \\dot\\rho = f, \\qquad f = \\frac{u \\cdot J u}{u \\cdot u}

  (a continuous renormalisation: ``|u|`` is a first integral of this system, and
  ``|w| = e^rho`` never overflows however fast it grows);
* three quadratures for the indicators (scaled by ``1/T`` resp. ``1/T^2``, with the
  scale ``T`` a runtime parameter, so that every variable stays of order one --
  heyoka controls its step with the sup norm of the whole state, and a large
  quadrature would loosen the error control of ``y``):

  - ``log_norm = rho / T``,
  - ``megno_num = (1/T^2) int_0^t (s + delta) f(s) ds``,
  - ``megno_int = (1/T^2) int_0^t 2 num(s) / (s + delta) ds``, ``num = T^2 megno_num``.

From them (see :mod:`andoyer.analysis.chaos`) ``ln |w(t)| = T log_norm``, the MEGNO
``Y(t) = 2/t int_0^t s f(s) ds = ((t + delta) Y_delta - 2 delta rho) / t`` exactly,
with ``Y_delta = 2 num / (t + delta)``, and its mean ``<Y>_delta = int_0^t Y_delta
ds / (t + delta)`` (Cincotta & Simo 2000). The shift ``delta`` (:data:`MEGNO_DELTA`)
removes the ``1/t`` singularity of the mean at t = 0 (a Taylor integrator cannot
evaluate ``0/0``); it changes ``<Y>`` by a relative ``O(delta / t)`` only.

The numba engine (``engine="numba"``, no heyoka) integrates the same variables with
the Numba DOP853 (:func:`andoyer.integrate.tangent.propagate_tangent`: ``J`` generated
by SymPy from the same H, the same continuous renormalisation and MEGNO quadratures,
unscaled while integrating since DOP853 controls each component on its own scale) and
returns them in this order and scaling, so the indicators are computed by the same
formulas whichever engine ran.

Runtime parameters: ``par[0..7] = (a, b, c, mu, e1, e2, e3, phi0)`` (the engines'
``params``; ``phi0`` is not used by (1)) and ``par[8] = 1/T``. One compiled
integrator serves every body, tolerance aside.

Parallelism
-----------
Orbits run in blocks of ``batch_size`` lanes of one SIMD (batch-mode) integrator
(:func:`heyoka.recommended_simd_size`, 4 doubles with AVX2), and blocks on a pool of
threads, each owning one copy of the integrator (heyoka releases the GIL while it
integrates). Results do not depend on the threads or the order of the blocks.
(``heyoka.ensemble_propagate_*`` would deep-copy the integrator for every task;
heyoka's ``parallel_mode`` parallelises one step and pays off only for systems of
hundreds of variables, not 15.)

Caches
------
An integrator (scalar or batch, per tolerance) is compiled once per process and kept
in a module-level pool; threads and worker processes reuse it. Across processes,
heyoka's own on-disk JIT cache (heyoka.py >= 7.10, on by default, in ``~/.cache/heyoka``;
:meth:`heyoka.llvm_state.get_diskcache_path`) skips LLVM's optimisation and code
generation. Measured on this 2-core machine for the variational integrator at
tol = 1e-12: 1.01 s to compile with no cache, 0.063 s in a fresh process from heyoka's
disk cache, 0.035 s from the pickled copy andoyer used to keep in ``~/.cache/andoyer``
-- within 2x, so that hand-written cache (pickles, fingerprints, checksums) was removed.
"""

from __future__ import annotations

import copy
import math
import os
import threading
import time
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from functools import cache
from typing import Any, Literal, NamedTuple, cast

import numpy as np
from numpy.typing import NDArray

from andoyer.charts.euler_poisson import STATE
from andoyer.errors import IntegrationError
from andoyer.integrate.engines import default_engine_name
from andoyer.integrate.engines.base import TOLERANCE_FACTOR, Params
from andoyer.integrate.engines.heyoka_engine import tolerance
from andoyer.integrate.engines.heyoka_symbolic import heyoka_state_vars, heyoka_system
from andoyer.integrate.engines.lazy import heyoka as hy
from andoyer.validation import integer

__all__ = [
    "VARIATIONAL_STATE", "TANGENT", "N_VARIATIONAL", "MEGNO_DELTA", "SCALE_PAR",
    "FORMULATION", "ENGINES", "variational_system", "warm_up",
    "clear_memory_cache",
    "propagate_variational", "VariationalResult",
]

#: The tangent vector's components (``u = w/|w|``), in the order of ``STATE``.
TANGENT: tuple[str, ...] = tuple(f"w_{name}" for name in STATE)

#: Order of the 15 variables of the variational system.
VARIATIONAL_STATE: tuple[str, ...] = (*STATE, *TANGENT, "log_norm", "megno_num",
                                      "megno_int")
N_VARIATIONAL = len(VARIATIONAL_STATE)

#: Time shift of the MEGNO weights (see the module docstring).
MEGNO_DELTA = 1e-6

#: Index of the runtime parameter ``1/T`` (the quadratures' scale).
SCALE_PAR = 8

#: Name of this formulation; change it when the meaning of the variables changes.
FORMULATION = "unit-tangent+megno-shifted/1"

#: Engines that integrate the variational system.
ENGINES = ("heyoka", "scipy", "numba")

EngineName = Literal["heyoka", "scipy", "numba"]


# ----------------------------------------------------------------------------- symbolic


@cache
def variational_system() -> tuple[tuple[Any, Any], ...]:
    """The 15 ``(variable, rhs)`` pairs of the system, order :data:`VARIATIONAL_STATE`."""
    base = list(heyoka_system())
    vsys = hy.var_ode_sys(base, [heyoka_state_vars()[0]], order=1)
    pairs = list(vsys.sys)
    if vsys.n_orig_sv != len(STATE) or len(pairs) != 2 * len(STATE):
        raise RuntimeError(f"unexpected variational system: {len(pairs)} equations")
    # var_ode_sys gives the column d y / d G1(0): its right-hand side is J(y) times
    # that column, linear in the column's variables -- renamed to the tangent vector u.
    u = list(hy.make_vars(*TANGENT))
    rename = dict(zip([v for v, _ in pairs[len(STATE):]], u, strict=True))
    Ju = [hy.subs(rhs, rename) for _, rhs in pairs[len(STATE):]]
    f = hy.sum([ui * Jui for ui, Jui in zip(u, Ju, strict=True)]) / hy.sum([ui * ui for ui in u])
    log_norm, num, integral = hy.make_vars(*VARIATIONAL_STATE[-3:])
    inv_T = hy.par[SCALE_PAR]
    s = hy.time + MEGNO_DELTA
    return (*((v, rhs) for v, rhs in pairs[:len(STATE)]),
            *((ui, Jui - f * ui) for ui, Jui in zip(u, Ju, strict=True)),
            (log_norm, f * inv_T),
            (num, s * f * inv_T * inv_T),
            (integral, 2.0 * num / s))


class _Key(NamedTuple):
    batch_size: int
    tol: float


def _compile(key: _Key) -> Any:
    system = list(variational_system())
    common: dict[str, Any] = {"tol": key.tol, "compact_mode": False}
    if key.batch_size == 1:
        return hy.taylor_adaptive(system, [0.0] * N_VARIATIONAL, **common)
    return hy.taylor_adaptive_batch(system, np.zeros((N_VARIATIONAL, key.batch_size)),
                                    **common)


# ----------------------------------------------------------------------------- pool

_TEMPLATES: dict[_Key, Any] = {}
_SOURCES: dict[_Key, str] = {}
_POOL: dict[_Key, list[Any]] = {}
_LOCK = threading.Lock()


def _template(key: _Key) -> Any:
    """The compiled integrator for ``key``: from this process's pool, or built now (from
    heyoka's on-disk JIT cache when a process built it before)."""
    with _LOCK:
        if key in _TEMPLATES:
            return _TEMPLATES[key]
        ta = _compile(key)
        _TEMPLATES[key] = ta
        _SOURCES[key] = "compiled"
        _POOL[key] = []
        return ta


@contextmanager
def _borrow(key: _Key) -> Iterator[Any]:
    """A private copy of the compiled integrator for one thread (returned to the pool)."""
    template = _template(key)
    with _LOCK:
        free = _POOL[key]
        ta = free.pop() if free else None
    if ta is None:
        ta = copy.deepcopy(template)  # about a millisecond: the code is not recompiled
    try:
        yield ta
    finally:
        with _LOCK:
            _POOL[key].append(ta)


def warm_up(*, batch_size: int | None = None, tol: float = 1e-12) -> tuple[str, float]:
    """Make the integrator for these settings ready; say where it came from and how long.

    ``batch_size=None`` is :func:`heyoka.recommended_simd_size`, the batch size of maps.

    Returns
    -------
    (source, seconds)
        ``source`` is ``"memory"`` (already built in this process) or ``"compiled"``
        (built now; from heyoka's on-disk JIT cache if a process built it before).

    Examples
    --------
    >>> source, seconds = warm_up()
    >>> source in ("memory", "compiled")
    True
    """
    m = int(hy.recommended_simd_size()) if batch_size is None else _check_batch(batch_size)
    key = _Key(m, tolerance(tol, tol))
    t0 = time.perf_counter()
    had = key in _TEMPLATES
    _template(key)
    return ("memory" if had else _SOURCES[key]), time.perf_counter() - t0


def clear_memory_cache() -> None:
    """Forget the integrators loaded in this process (the disk cache is kept)."""
    with _LOCK:
        _TEMPLATES.clear()
        _SOURCES.clear()
        _POOL.clear()


def _check_batch(batch_size: int) -> int:
    return integer("batch_size", batch_size, 1)


# ----------------------------------------------------------------------------- propagation


class VariationalResult(NamedTuple):
    """What :func:`propagate_variational` returns."""

    x: NDArray[np.float64]  # (n, k, 15): the variables of VARIATIONAL_STATE at times t
    ok: NDArray[np.bool_]  # (n,): False where the integration failed (x is NaN there)


def _pars(params: Params, scale: float) -> NDArray[np.float64]:
    if len(params) != 8:
        raise ValueError("params must be (a, b, c, mu, e1, e2, e3, phi0), "
                         f"got {len(params)} values")
    return np.array([*map(float, params), 1.0 / scale])


def _initial(y0: NDArray[np.float64], w0: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.concatenate([y0, w0, np.zeros((y0.shape[0], 3))], axis=1)


def _good(outcome: Any) -> bool:
    return bool(outcome == hy.taylor_outcome.time_limit)


def _heyoka_block(key: _Key, x0: NDArray[np.float64], t: NDArray[np.float64],
                  pars: NDArray[np.float64], out: NDArray[np.float64],
                  ok: NDArray[np.bool_], tasks: _Counter) -> None:
    """Integrate blocks of ``key.batch_size`` orbits taken from ``tasks`` until none is left."""
    m = key.batch_size
    n = x0.shape[0]
    with _borrow(key) as ta:
        if m == 1:
            ta.pars[:] = pars
        else:
            ta.pars[:] = pars[:, None]
            grid = np.ascontiguousarray(np.repeat(t, m).reshape(-1, m))
        while (start := tasks.next()) is not None:
            stop = min(start + m, n)
            if m == 1:
                ta.time = float(t[0])
                ta.state[:] = x0[start]
                res = ta.propagate_grid(t)
                good = [_good(res[0])]
                block = np.asarray(res[-1])[None]  # (1, k, 15)
            else:
                lanes = np.concatenate([x0[start:stop],
                                        np.repeat(x0[start:start + 1], m - (stop - start),
                                                  axis=0)])
                ta.set_time(np.full(m, float(t[0])))
                ta.state[:] = lanes.T
                res = ta.propagate_grid(grid)
                good = [_good(r[0]) for r in ta.propagate_res]
                block = np.transpose(np.asarray(res[-1]), (2, 0, 1))  # (m, k, 15)
            for j in range(stop - start):
                ok[start + j] = good[j] and bool(np.all(np.isfinite(block[j])))
                out[start + j] = block[j] if ok[start + j] else np.nan


class _Counter:
    """A thread-safe source of block start indices 0, step, 2 step, ... < n."""

    def __init__(self, n: int, step: int) -> None:
        self._next, self._n, self._step = 0, n, step
        self._lock = threading.Lock()

    def next(self) -> int | None:
        with self._lock:
            if self._next >= self._n:
                return None
            self._next += self._step
            return self._next - self._step


@cache
def _cfunc() -> Any:
    """The system's right-hand side compiled as a function of ``(x, par, time)``."""
    system = variational_system()
    return hy.cfunc([rhs for _, rhs in system], [v for v, _ in system])


_CFUNC_LOCK = threading.Lock()


def _scipy_orbit(x0: NDArray[np.float64], t: NDArray[np.float64], pars: NDArray[np.float64],
                 tol: float) -> tuple[NDArray[np.float64], bool]:
    from andoyer.integrate.engines.scipy_engine import solve_dop853

    with _CFUNC_LOCK:
        cf = _cfunc()
    buf = np.empty(N_VARIATIONAL)

    def rhs(s: float, x: NDArray[np.float64]) -> NDArray[np.float64]:
        cf(x, pars=pars, time=s, outputs=buf)
        return buf.copy()

    rtol = max(tol * TOLERANCE_FACTOR, 100 * np.finfo(float).eps)
    try:
        sol = solve_dop853(rhs, t, x0, rtol, tol * TOLERANCE_FACTOR)
    except IntegrationError:
        return np.full((t.size, N_VARIATIONAL), np.nan), False
    if sol.y.shape[1] != t.size:
        return np.full((t.size, N_VARIATIONAL), np.nan), False
    return np.ascontiguousarray(sol.y.T), True


def _numba(y0: NDArray[np.float64], w0: NDArray[np.float64], t: NDArray[np.float64],
           params: Params, tol: float, T: float) -> VariationalResult:
    """The variables of :data:`VARIATIONAL_STATE` from the Numba DOP853."""
    from andoyer.integrate.tangent import propagate_tangent

    res = propagate_tangent(y0, w0[:, None, :], t, params, tol=tol)
    x = np.concatenate([res.y, res.u[:, :, 0], res.rho / T,
                        res.megno_num[..., None] / T**2, res.megno_int[..., None] / T**2],
                       axis=-1)
    return VariationalResult(x, res.ok)


def propagate_variational(y0: NDArray[np.float64], w0: NDArray[np.float64],
                          t: NDArray[np.float64], params: Params, *, tol: float = 1e-12,
                          scale: float | None = None, engine: EngineName | None = None,
                          batch_size: int | None = None,
                          n_threads: int | None = None) -> VariationalResult:
    """Integrate orbits with their tangent vectors and indicator quadratures.

    Plain arrays in and out (the friendly layer is :mod:`andoyer.analysis.chaos`).

    Parameters
    ----------
    y0 : ndarray, shape (n, 6)
        Euler-Poisson initial states.
    w0 : ndarray, shape (n, 6)
        Initial tangent vectors, unit length (``log_norm`` counts from ``ln |w0| = 0``).
    t : ndarray, shape (k,)
        Output times, increasing, ``t[0] = 0`` (the indicators count from t = 0).
    params : tuple
        ``(a, b, c, mu, e1, e2, e3, phi0)``.
    tol : float
        heyoka's tolerance; the scipy engine (DOP853) gets ``tol * TOLERANCE_FACTOR``.
    scale : float, optional
        The scale ``T`` of the quadratures (default ``t[-1]``).
    engine : {"heyoka", "scipy", "numba"}, optional
        Default heyoka where installed, else numba. ``"heyoka"``: Taylor method,
        batch (SIMD) mode and threads. ``"scipy"``:
        ``solve_ivp(DOP853)`` on the same right-hand side (compiled by heyoka), one
        orbit at a time: an independent integrator for checks. ``"numba"``: the Numba
        DOP853 on the variational equations generated by SymPy, orbits in parallel;
        needs no heyoka (``tol`` is the accuracy asked for, DOP853 gets
        ``TOLERANCE_FACTOR * tol``).
    batch_size : int, optional
        Orbits per SIMD integrator (heyoka); default :func:`heyoka.recommended_simd_size`
        when there are that many orbits, else 1.
    n_threads : int, optional
        Threads running blocks of orbits; default ``os.cpu_count()``.

    Returns
    -------
    VariationalResult
        ``x`` of shape ``(n, k, 15)`` (order :data:`VARIATIONAL_STATE`), NaN for the
        orbits whose integration failed (``ok`` False: a non-finite state).
    """
    y0 = np.ascontiguousarray(y0, dtype=float).reshape(-1, len(STATE))
    w0 = np.ascontiguousarray(w0, dtype=float).reshape(-1, len(STATE))
    t = np.ascontiguousarray(t, dtype=float).reshape(-1)
    if y0.shape != w0.shape:
        raise ValueError(f"y0 and w0 must have the same shape, got {y0.shape} and {w0.shape}")
    if t.size < 2 or t[0] != 0.0 or np.any(np.diff(t) <= 0.0) or not np.all(np.isfinite(t)):
        raise ValueError("t must be increasing finite output times starting at t[0] = 0")
    T = float(t[-1]) if scale is None else float(scale)
    if not (math.isfinite(T) and T > 0.0):
        raise ValueError(f"scale must be finite and > 0, got {scale!r}")
    if engine is None:
        engine = cast(EngineName, default_engine_name())
    if engine not in ENGINES:
        raise ValueError(f"unknown engine {engine!r} for the variational equations; choose "
                         f"{' or '.join(repr(e) for e in ENGINES)}")
    tol = tolerance(tol, tol)
    pars = _pars(params, T)
    n = y0.shape[0]
    x0 = _initial(y0, w0)
    out = np.empty((n, t.size, N_VARIATIONAL))
    ok = np.zeros(n, dtype=bool)
    if n == 0:
        return VariationalResult(out, ok)
    if engine == "numba":
        return _numba(y0, w0, t, params, tol, T)
    if engine == "scipy":
        for i in range(n):
            out[i], ok[i] = _scipy_orbit(x0[i], t, pars, tol)
        return VariationalResult(out, ok)
    simd = int(hy.recommended_simd_size())
    m = _check_batch(batch_size) if batch_size is not None else (simd if n >= simd else 1)
    threads = integer("n_threads", n_threads, 1) if n_threads is not None else (os.cpu_count() or 1)
    key = _Key(m, tol)
    _template(key)  # compile or load once, before the threads start
    tasks = _Counter(n, m)
    workers = min(threads, -(-n // m))
    if workers <= 1:
        _heyoka_block(key, x0, t, pars, out, ok, tasks)
    else:
        with ThreadPoolExecutor(max_workers=workers) as pool:
            futures = [pool.submit(_heyoka_block, key, x0, t, pars, out, ok, tasks)
                       for _ in range(workers)]
            for fut in futures:
                fut.result()
    return VariationalResult(out, ok)
