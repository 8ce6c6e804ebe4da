r"""Tangent flows on heyoka: the variational equations of (1) built by heyoka.

Part of the heyoka engine (:class:`~andoyer.integrate.engines.heyoka_engine.HeyokaEngine`
calls it for the ``tangent`` and ``tangent_crossings`` capabilities). Two systems, both
transforms of the one SymPy -> heyoka field (:func:`heyoka_system`) by
:class:`heyoka.var_ode_sys`:

* **renormalised** (:func:`variational_system`), for long flights (chaos indicators):
  the state ``y``, ``k`` unit tangent vectors ``u_i = w_i/|w_i|`` and their log norms,
  and the MEGNO quadratures of the first vector,

  .. math::

     \dot u_i = J u_i - f_i u_i, \qquad \dot\rho_i = f_i, \qquad
     f_i = \frac{u_i \cdot J u_i}{u_i \cdot u_i}

  (a continuous renormalisation: ``|u_i|`` is a first integral and ``|w_i| = e^rho_i``
  never overflows). The log norms and the quadratures are integrated scaled by
  ``1/T`` resp. ``1/T^2`` (``T`` the runtime parameter ``inv_scale``) so that every
  variable stays of order one -- heyoka controls its step with the sup norm of the
  whole state, and a large quadrature would loosen the error control of ``y``:
  ``log_norm_i = rho_i / T``, ``megno_num = (1/T^2) int_0^t (s + delta) f_1 ds``,
  ``megno_int = (1/T^2) int_0^t 2 num(s) / (s + delta) ds`` with ``num = T^2
  megno_num`` and ``delta`` :data:`~andoyer.kernels.common.MEGNO_DELTA` (the shift
  removes the ``1/t`` singularity of the MEGNO mean at t = 0, which a Taylor integrator
  cannot evaluate).
  The engine returns them unscaled. Orbits run in blocks of ``batch_size`` lanes of
  one SIMD integrator and blocks on threads, each owning a copy of the integrator.
* **plain** (:func:`plain_flow`), for the FLI alone over many orbits: the state and ONE
  tangent vector ``w' = J w`` as is (12 variables, no division, fully compiled), each
  right-hand side a sum of monomials grouped by the body coefficient they share (one
  product per coefficient:
  :func:`~andoyer.integrate.engines.heyoka_symbolic.coefficient_tangent_system`,
  derived from the same SymPy field; the coefficients are
  runtime parameters and those that vanish for the body are left out), in the same
  SIMD blocks and threads; ``|w|`` is not renormalised, so the caller re-runs orbits
  whose ``ln|w|`` nears overflow.
* **the fundamental matrix** (``var_args.vars``: ``Phi = dy/dy0``, 36 variables),
  for short flights (monodromy matrices, the Jacobian of a section map): the
  columns start as the given vectors, so ``w_i(t) = Phi(t) w_i(0)``; optionally
  stopped at the crossings of a section (a terminal event), forward or backward,
  in double or 80-bit extended precision (``compact_mode``: 42 equations compile in
  about a second instead of ten).

Compiled integrators are kept per process in a pool keyed by what changes the code;
heyoka's on-disk JIT cache (heyoka.py >= 7.10, ``~/.cache/heyoka``) makes a rebuild in
a new process cheap (measured: benchmarks/NOTES.md#heyoka-engine).
"""

from __future__ import annotations

import copy
import threading
import time
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from functools import cache
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from andoyer.integrate.engines.base import PAR, Section, TangentFlow, unit_vectors
from andoyer.integrate.engines.heyoka_symbolic import (
    coefficient_tangent_system,
    coefficient_values,
    field_at,
    heyoka_state_vars,
    heyoka_system,
    par,
    section_cfunc,
    section_exprs,
)
from andoyer.integrate.engines.lazy import heyoka as hy
from andoyer.kernels.common import MEGNO_DELTA, T_START
from andoyer.kernels.generated.equations import section

__all__ = ["STATE_NAMES", "variational_names", "variational_system",
           "renormalised_flow", "plain_flow", "matrix_flow", "matrix_crossings", "warm_up",
           "clear_memory_cache"]

#: Names of the Euler-Poisson state variables (heyoka's variables are named so).
STATE_NAMES = ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")
_N = len(STATE_NAMES)


def variational_names(k: int = 1) -> tuple[str, ...]:
    """Variables of the renormalised system with ``k`` vectors, in order.

    Parameters
    ----------
    k : int, default 1
        Number of tangent vectors.

    Examples
    --------
    >>> variational_names()[9:]
    ('w_gamma1', 'w_gamma2', 'w_gamma3', 'log_norm', 'megno_num', 'megno_int')
    >>> variational_names(2)[-4:]
    ('log_norm1', 'log_norm2', 'megno_num', 'megno_int')
    """
    tag = [""] if k == 1 else [str(i + 1) for i in range(k)]
    return (*STATE_NAMES, *(f"w{t}_{s}" for t in tag for s in STATE_NAMES),
            *(f"log_norm{t}" for t in tag), "megno_num", "megno_int")


def _vars(names: tuple[str, ...]) -> list[Any]:
    """heyoka variables (``make_vars`` returns a bare expression for one name)."""
    return [hy.expression(name) for name in names]


@cache
def variational_system(k: int = 1) -> tuple[tuple[Any, Any], ...]:
    """The ``(variable, rhs)`` pairs of the renormalised system, order
    :func:`variational_names` (``6 + 7 k + 2`` variables)."""
    base = list(heyoka_system())
    vsys = hy.var_ode_sys(base, [heyoka_state_vars()[0]], order=1)
    pairs = list(vsys.sys)
    if vsys.n_orig_sv != _N or len(pairs) != 2 * _N:
        raise RuntimeError(f"unexpected variational system: {len(pairs)} equations")
    # var_ode_sys gives the column d y / d G1(0): its right-hand side is J(y) times that
    # column, linear in the column's variables -- renamed to each tangent vector u_i.
    column = [v for v, _ in pairs[_N:]]
    names = variational_names(k)
    u = [_vars(names[_N + 6 * i:_N + 6 * i + 6]) for i in range(k)]
    log_norms = _vars(names[_N + 6 * k:_N + 7 * k])
    num, integral = _vars(names[-2:])
    inv_T = par("inv_scale")
    s = hy.time + MEGNO_DELTA
    out: list[tuple[Any, Any]] = [(v, rhs) for v, rhs in pairs[:_N]]
    rates = []
    for ui in u:
        Ju = [hy.subs(rhs, dict(zip(column, ui, strict=True))) for _, rhs in pairs[_N:]]
        f = hy.sum([a * b for a, b in zip(ui, Ju, strict=True)]) / hy.sum([a * a for a in ui])
        out += [(a, Ja - f * a) for a, Ja in zip(ui, Ju, strict=True)]
        rates.append(f)
    out += [(ln, f * inv_T) for ln, f in zip(log_norms, rates, strict=True)]
    out += [(num, s * rates[0] * inv_T * inv_T), (integral, 2.0 * num / s)]
    return tuple(out)


# ----------------------------------------------------------------------------- pool
class _Key(NamedTuple):
    system: str  # "renormalised", "plain" or "matrix"
    batch_size: int
    tol: float
    k: int = 1
    kind: int = -1  # section kind of the terminal event (matrix only), -1: none
    direction: int = 0
    extended: bool = False
    zero: frozenset[int] = frozenset()  # plain only: body coefficients left out (zero)


def _compile(key: _Key) -> Any:
    fp: Any = np.longdouble if key.extended else float
    if key.system == "plain":
        # The state and ONE tangent vector, w' = J w: 12 variables, the body's
        # coefficients as runtime parameters (one product per coefficient), compiled in
        # full for fast steps.
        return hy.taylor_adaptive_batch(list(coefficient_tangent_system(key.zero)),
                                        np.zeros((2 * _N, key.batch_size)), tol=key.tol)
    if key.system == "renormalised":
        system = list(variational_system(key.k))
        n = len(system)
        # The one-vector system of the chaos maps is compiled in full (faster steps);
        # k > 1 in compact mode (it compiles in seconds instead of minutes).
        common: dict[str, Any] = {"tol": key.tol, "compact_mode": key.k > 1}
        if key.batch_size == 1:
            return hy.taylor_adaptive(system, [0.0] * n, **common)
        return hy.taylor_adaptive_batch(system, np.zeros((n, key.batch_size)), **common)
    sys_ = hy.var_ode_sys(list(heyoka_system()), hy.var_args.vars, order=1)
    kw: dict[str, Any] = {"tol": fp(key.tol), "compact_mode": True, "fp_type": fp}
    if key.kind >= 0:
        f = section_exprs(key.kind)[0]
        dirs = {1: hy.event_direction.positive, -1: hy.event_direction.negative,
                0: hy.event_direction.any}
        kw["t_events"] = [hy.t_event(f, callback=_Stop(key.kind), direction=dirs[key.direction],
                                     fp_type=fp)]
    return hy.taylor_adaptive(sys_, np.zeros(_N + _N * _N, dtype=fp), **kw)


class _Stop:
    """Terminal-event callback: ``True`` (go on) for the start point and where the
    section's margin ``w <= 0`` (the antipodal root of an angle section)."""

    def __init__(self, kind: int) -> None:
        self.kind = kind

    def __call__(self, ta: Any, d_sgn: int) -> bool:
        if abs(float(ta.time)) <= T_START:
            return True
        # The integrator holds the parameters its expressions use: those w needs.
        p = np.zeros(len(PAR))
        p[:np.shape(ta.pars)[0]] = np.asarray(ta.pars, dtype=float)
        args = [self.kind, *(float(v) for v in ta.state[:_N]),
                *(float(p[PAR[name]]) for name in ("phi0", "value", "cv", "sv"))]
        return not section(*args)[1] > 0.0


_TEMPLATES: dict[_Key, Any] = {}
_POOL: dict[_Key, list[Any]] = {}
_LOCK = threading.Lock()


def _template(key: _Key) -> Any:
    with _LOCK:
        if key not in _TEMPLATES:
            _TEMPLATES[key] = _compile(key)
            _POOL[key] = []
        return _TEMPLATES[key]


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


def warm_up(*, batch_size: int, tol: float, k: int = 1) -> tuple[str, float]:
    """Build the renormalised integrator for these settings now: ``(source, seconds)``,
    ``source`` ``"memory"`` (built before in this process) or ``"compiled"`` (now; from
    heyoka's on-disk cache if a process built it before).

    Parameters
    ----------
    batch_size : int
        SIMD lanes of the integrator.
    tol : float
        heyoka's tolerance.
    k : int, default 1
        Number of tangent vectors.
    """
    key = _Key("renormalised", batch_size, tol, k)
    t0 = time.perf_counter()
    had = key in _TEMPLATES
    _template(key)
    return ("memory" if had else "compiled"), time.perf_counter() - t0


def clear_memory_cache() -> None:
    """Forget the integrators built in this process (heyoka's disk cache is kept)."""
    with _LOCK:
        _TEMPLATES.clear()
        _POOL.clear()


# ----------------------------------------------------------------------------- renormalised
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


def _good(outcome: Any) -> bool:
    return bool(outcome == hy.taylor_outcome.time_limit)


def _block(key: _Key, x0: NDArray[np.float64], t: NDArray[np.float64],
           par: NDArray[np.float64], out: NDArray[np.float64], ok: NDArray[np.bool_],
           tasks: _Counter) -> None:
    """Integrate blocks of ``key.batch_size`` orbits taken from ``tasks`` until none is left."""
    m = key.batch_size
    n = x0.shape[0]
    with _borrow(key) as ta:
        n_pars = int(np.shape(ta.pars)[0])
        if m == 1:
            ta.pars[:] = par[:n_pars]
        else:
            ta.pars[:] = par[:n_pars, None]
            grid = np.ascontiguousarray(np.repeat(t, m).reshape(-1, m))
        while (start := tasks.next()) is not None:
            stop = min(start + m, n)
            if m == 1:
                ta.time = float(t[0])
                ta.state[:] = x0[start]
                res = ta.propagate_grid(t)
                good = [_good(res[0])]
                block = np.asarray(res[-1])[None]  # (1, times, variables)
            else:
                lanes = np.concatenate([x0[start:stop],
                                        np.repeat(x0[start:start + 1], m - (stop - start),
                                                  axis=0)])
                ta.set_time(np.full(m, float(t[0])))
                ta.state[:] = lanes.T
                res = ta.propagate_grid(grid)
                good = [_good(r[0]) for r in ta.propagate_res]
                block = np.transpose(np.asarray(res[-1]), (2, 0, 1))
            for j in range(stop - start):
                ok[start + j] = good[j] and bool(np.all(np.isfinite(block[j])))
                out[start + j] = block[j] if ok[start + j] else np.nan


def _run_blocks(key: _Key, x0: NDArray[np.float64], t: NDArray[np.float64],
                par: NDArray[np.float64], out: NDArray[np.float64], ok: NDArray[np.bool_],
                n_threads: int) -> None:
    """:func:`_block` on ``n_threads`` threads sharing one queue of blocks."""
    n = x0.shape[0]
    tasks = _Counter(n, key.batch_size)
    workers = min(n_threads, -(-n // key.batch_size))
    if workers <= 1:
        _block(key, x0, t, par, out, ok, tasks)
        return
    with ThreadPoolExecutor(max_workers=workers) as pool:
        for fut in [pool.submit(_block, key, x0, t, par, out, ok, tasks)
                    for _ in range(workers)]:
            fut.result()


def renormalised_flow(y0: NDArray[np.float64], w0: NDArray[np.float64],
                      t: NDArray[np.float64], par: NDArray[np.float64], tol: float,
                      scale: float, batch_size: int, n_threads: int) -> TangentFlow:
    """The renormalised system over output times ``t`` (see the module notes).

    Parameters
    ----------
    y0 : ndarray, shape (n, 6)
        Initial Euler-Poisson states.
    w0 : ndarray
        Initial tangent vectors.
    t : ndarray, shape (m,)
        Output times.
    par : ndarray
        Runtime parameters.
    tol : float
        heyoka's tolerance.
    scale : float
        Time scale of the MEGNO quadratures (``delta`` of the module notes).
    batch_size : int
        SIMD lanes per block.
    n_threads : int
        Threads over the blocks.
    """
    n, k = w0.shape[:2]
    u0, rho0 = unit_vectors(w0)
    x0 = np.concatenate([y0, u0.reshape(n, -1), rho0 / scale, np.zeros((n, 2))], axis=1)
    key = _Key("renormalised", batch_size, tol, k)
    out = np.empty((n, t.size, x0.shape[1]))
    ok = np.zeros(n, dtype=bool)
    _template(key)  # compile or load once, before the threads start
    _run_blocks(key, x0, t, par, out, ok, n_threads)
    u = out[..., _N:_N + 6 * k].reshape(n, t.size, k, _N)
    return TangentFlow(np.broadcast_to(t, (n, t.size)).copy(), out[..., :_N], u,
                       out[..., _N + 6 * k:_N + 7 * k] * scale, out[..., -2:] * scale**2,
                       np.full(n, t.size, dtype=np.int64), ok)


def _plain_blocks(key: _Key, x0: NDArray[np.float64], grid: NDArray[np.float64],
                  coeffs: NDArray[np.float64], out: NDArray[np.float64],
                  good: NDArray[np.bool_], tasks: _Counter) -> None:
    """Integrate blocks of lanes taken from ``tasks``: ``x0`` (12, n) padded to whole
    blocks, ``out`` (blocks, times, 12, lanes) and ``good`` (blocks, lanes) written in
    place, one ``propagate_grid`` per block and nothing else per block in Python."""
    m = key.batch_size
    t0 = float(grid[0, 0])
    with _borrow(key) as ta:
        ta.pars[:] = coeffs[:int(np.shape(ta.pars)[0]), None]
        time_limit = hy.taylor_outcome.time_limit
        while (start := tasks.next()) is not None:
            b = start // m
            ta.set_time(t0)
            ta.state[:] = x0[:, start:start + m]
            out[b] = ta.propagate_grid(grid)[-1]
            good[b] = [r[0] == time_limit for r in ta.propagate_res]


def plain_flow(y0: NDArray[np.float64], w0: NDArray[np.float64], t: NDArray[np.float64],
               par: NDArray[np.float64], tol: float, batch_size: int,
               n_threads: int) -> TangentFlow:
    """``w(t) = Phi(t) w(0)`` of ONE vector per orbit, not renormalised, over output
    times ``t``: the 12-variable system (state and ``w' = J w``,
    :func:`~andoyer.integrate.engines.heyoka_symbolic.coefficient_tangent_system`, the
    body's coefficients as runtime parameters and those that vanish left out) in SIMD
    blocks of ``batch_size > 1`` lanes on threads, one ``propagate_grid`` per block.
    ``|w|`` overflows past ``ln|w| ~ 709``: such orbits come back with ``ok`` False.

    Parameters
    ----------
    y0 : ndarray, shape (n, 6)
        Initial Euler-Poisson states.
    w0 : ndarray, shape (n, 1, 6)
        One initial tangent vector per orbit.
    t : ndarray, shape (m,)
        Output times.
    par : ndarray
        Runtime parameters (the body's ``a, b, c, mu, e1, e2, e3`` first).
    tol : float
        heyoka's tolerance.
    batch_size : int
        SIMD lanes per block.
    n_threads : int
        Threads over the blocks.
    """
    n = y0.shape[0]
    m = batch_size
    if w0.shape[1] != 1 or m < 2:
        raise ValueError("plain_flow takes one vector per orbit and a batch size > 1")
    coeffs = coefficient_values(par)
    key = _Key("plain", m, tol, zero=frozenset(np.flatnonzero(coeffs == 0.0).tolist()))
    n_blocks = -(-n // m)
    # Lanes as columns, padded to whole blocks with the last orbit (its copies are
    # dropped): no per-block concatenation.
    x0 = np.empty((2 * _N, n_blocks * m))
    x0[:_N, :n] = y0.T
    x0[_N:, :n] = w0[:, 0].T
    x0[:, n:] = x0[:, n - 1:n]
    grid = np.ascontiguousarray(np.repeat(t, m).reshape(-1, m))
    blocks = np.empty((n_blocks, t.size, 2 * _N, m))
    good = np.zeros((n_blocks, m), dtype=bool)
    _template(key)
    tasks = _Counter(n_blocks * m, m)
    workers = min(n_threads, n_blocks)
    if workers <= 1:
        _plain_blocks(key, x0, grid, coeffs, blocks, good, tasks)
    else:
        with ThreadPoolExecutor(max_workers=workers) as pool:
            for fut in [pool.submit(_plain_blocks, key, x0, grid, coeffs, blocks, good, tasks)
                        for _ in range(workers)]:
                fut.result()
    out = np.moveaxis(blocks, 3, 1).reshape(n_blocks * m, t.size, 2 * _N)[:n]
    ok = good.reshape(-1)[:n] & np.isfinite(out).all(axis=(1, 2))
    out[~ok] = np.nan
    u, rho = unit_vectors(out[..., None, _N:])
    return TangentFlow(np.broadcast_to(t, (n, t.size)).copy(), out[..., :_N], u, rho, None,
                       np.full(n, t.size, dtype=np.int64), ok)


# ----------------------------------------------------------------------------- matrix
def _matrix_start(ta: Any, y0: NDArray[np.float64], w0: NDArray[np.float64]) -> None:
    Phi0 = np.zeros((_N, _N))
    Phi0[:, :w0.shape[0]] = w0.T  # columns: the tangent vectors
    ta.state[:_N] = y0
    ta.state[ta.get_vslice(order=1)] = Phi0.ravel()  # row-major d y_i / d y0_j


def _matrix_vectors(ta: Any, k: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    Phi = np.array(ta.state[ta.get_vslice(order=1)], dtype=float).reshape(_N, _N)
    return np.array(ta.state[:_N], dtype=float), Phi[:, :k].T


def matrix_flow(y0: NDArray[np.float64], w0: NDArray[np.float64], t: NDArray[np.float64],
                par: NDArray[np.float64], tol: float) -> TangentFlow:
    """``w_i(t) = Phi(t) w_i(0)`` over output times ``t`` (either direction).

    Parameters
    ----------
    y0 : ndarray, shape (n, 6)
        Initial Euler-Poisson states.
    w0 : ndarray, shape (n, k, 6) or (k, 6)
        Initial tangent vectors.
    t : ndarray, shape (m,)
        Output times (either direction, from ``t[0]``).
    par : ndarray
        Runtime parameters.
    tol : float
        heyoka's tolerance.
    """
    n, k = w0.shape[:2]
    key = _Key("matrix", 1, tol)
    Y = np.full((n, t.size, _N), np.nan)
    W = np.full((n, t.size, k, _N), np.nan)
    ok = np.zeros(n, dtype=bool)
    with _borrow(key) as ta:
        ta.pars[:] = par[:int(np.shape(ta.pars)[0])]
        for i in range(n):
            ta.time = float(t[0])
            _matrix_start(ta, y0[i], w0[i])
            res = ta.propagate_grid(t)
            if not _good(res[0]):
                continue
            grid = np.asarray(res[-1])  # (times, 42)
            Y[i] = grid[:, :_N]
            Phi = grid[:, _N:].reshape(t.size, _N, _N)
            W[i] = np.swapaxes(Phi[:, :, :k], 1, 2)
            ok[i] = bool(np.all(np.isfinite(grid)))
    Y[~ok], W[~ok] = np.nan, np.nan
    u, rho = unit_vectors(W)
    return TangentFlow(np.broadcast_to(t, (n, t.size)).copy(), Y, u, rho, None,
                       np.full(n, t.size, dtype=np.int64), ok)


_MAX_POLISH = 1e-8  # largest Newton time step of the crossing polish


def _polish(kind: int, y: NDArray[np.float64], t: float, par: NDArray[np.float64]
            ) -> tuple[NDArray[np.float64], float]:
    """One Newton step in time onto ``f = 0``: heyoka stops on the Taylor root, and the
    event time is rounded to the state's precision."""
    cf = section_cfunc(kind)
    P = np.ascontiguousarray(par[:cf.nparams, None])
    f, _, fdot = (float(v[0]) for v in cf(np.ascontiguousarray(y[:, None]), pars=P))
    dt = -f / fdot if fdot != 0.0 else 0.0
    if abs(dt) < _MAX_POLISH:
        y = y + dt * field_at(y[None], par)[0]
        t += dt
    return y, t


def matrix_crossings(y0: NDArray[np.float64], w0: NDArray[np.float64],
                     par: NDArray[np.float64], event: Section, n_crossings: int,
                     t_max: float, tol: float, extended: bool) -> TangentFlow:
    """The first crossings of ``event`` with ``w_i = Phi w_i(0)`` there; ``t_max < 0``
    integrates backward (the event's direction is in physical time).

    Parameters
    ----------
    y0 : ndarray, shape (n, 6)
        Initial Euler-Poisson states.
    w0 : ndarray, shape (n, k, 6) or (k, 6)
        Initial tangent vectors.
    par : ndarray
        Runtime parameters (:data:`~andoyer.integrate.engines.base.PAR` order).
    event : Section
        The section and its crossing direction.
    n_crossings : int
        Crossings wanted per orbit.
    t_max : float
        Largest time (negative: backward).
    tol : float
        heyoka's tolerance.
    extended : bool
        Extended precision (long double).
    """
    n, k = w0.shape[:2]
    key = _Key("matrix", 1, tol, 1, event.kind, event.direction, extended)
    fp: Any = np.longdouble if extended else float
    T = np.full((n, n_crossings), np.nan)
    Y = np.full((n, n_crossings, _N), np.nan)
    W = np.full((n, n_crossings, k, _N), np.nan)
    count = np.zeros(n, dtype=np.int64)
    ok = np.ones(n, dtype=bool)
    section_cfunc(event.kind)
    with _borrow(key) as ta:
        ta.pars[:] = par[:int(np.shape(ta.pars)[0])]
        for i in range(n):
            ta.time = fp(0.0)
            _matrix_start(ta, y0[i], w0[i])
            ta.reset_cooldowns()
            while count[i] < n_crossings:
                outcome = ta.propagate_until(fp(t_max))[0]
                if outcome in (hy.taylor_outcome.time_limit, hy.taylor_outcome.step_limit):
                    break
                if outcome == hy.taylor_outcome.err_nf_state:
                    ok[i] = False
                    break
                y, w = _matrix_vectors(ta, k)
                c = int(count[i])
                Y[i, c], T[i, c] = _polish(event.kind, y, float(ta.time), par)
                W[i, c] = w
                count[i] += 1
    u, rho = unit_vectors(W)
    return TangentFlow(T, Y, u, rho, None, count, ok)
