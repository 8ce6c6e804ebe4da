"""What a heyoka.py user writes without andoyer: three levels of effort.

* ``plain_orbit`` / ``plain_section``: one ``taylor_adaptive`` reused in a serial loop;
  the section is a terminal event whose callback records the crossing and returns
  False at the N-th one (the integrator stops exactly there).
* ``ensemble_section``: the same integrator handed to ``ensemble_propagate_until`` on
  a few threads (one deep copy per orbit).
* ``tuned_section``: the expert script: batch (SIMD) integrators of 4 lanes, 2
  threads, a short pilot run to measure each orbit's return time, orbits sorted by
  it and grouped in batches of similar length, per-lane end times predicted from the
  return time, lanes still short of N crossings continued.

Integrators are built once per session (``functools.cache``): heyoka compiles them
with LLVM on first use, and a session reuses them.
"""

from __future__ import annotations

import copy
from concurrent.futures import ThreadPoolExecutor
from functools import cache
from typing import Any

import heyoka as hy
import numpy as np
from benchmarks.peers.model import T_START, heyoka_section, heyoka_system, numpy_section

Params = tuple[tuple[str, float], ...]  # dict items, hashable for the caches


# ----------------------------------------------------------------------------- W1


@cache
def _plain_integrator(p: Params, tol: float) -> Any:
    return hy.taylor_adaptive(heyoka_system(dict(p), hy), [0.0] * 6, tol=tol)


def plain_orbit(p: dict[str, float], y0: np.ndarray, t: np.ndarray, tol: float) -> np.ndarray:
    """States on the grid ``t`` (t[0] is the initial time): shape (len(t), 6)."""
    ta = _plain_integrator(tuple(p.items()), tol)
    ta.time = float(t[0])
    ta.state[:] = y0
    return np.array(ta.propagate_grid(np.asarray(t, dtype=float))[-1])


# ----------------------------------------------------------------------------- W2, plain


class _Stopper:
    """Terminal-event callback: record the crossing, stop at the N-th one."""

    def __init__(self) -> None:
        self.reset(0, None)

    def reset(self, n: int, margin: Any) -> None:
        self.n, self.margin = n, margin
        self.t: list[float] = []
        self.y: list[np.ndarray] = []

    def __call__(self, ta: Any, d_sgn: Any) -> bool:
        # The integrator stands exactly at the event: its state is the crossing.
        if ta.time > T_START and self.margin(ta.state) > 0.0:
            self.t.append(ta.time)
            self.y.append(ta.state.copy())
        return len(self.t) < self.n


@cache
def _terminal_integrator(p: Params, name: str, value: float, tol: float) -> Any:
    f = heyoka_section(dict(p), name, value, hy)
    ev = hy.t_event(f, callback=_Stopper(), direction=hy.event_direction.positive)
    return hy.taylor_adaptive(heyoka_system(dict(p), hy), [0.0] * 6, tol=tol, t_events=[ev])


def _margin(p: dict[str, float], name: str, value: float) -> Any:
    fw = numpy_section(p, name, value)
    return lambda y: float(fw(y)[1])


def plain_section(p: dict[str, float], y0: np.ndarray, name: str, value: float, n: int,
                  tol: float) -> tuple[np.ndarray, np.ndarray]:
    """First ``n`` upward crossings of ``name = value``: times (k, n), states (k, n, 6)."""
    ta = _terminal_integrator(tuple(p.items()), name, value, tol)
    margin = _margin(p, name, value)
    T = np.full((len(y0), n), np.nan)
    Y = np.full((len(y0), n, 6), np.nan)
    for i, y in enumerate(y0):
        cb = ta.t_events[0].callback  # the integrator's own copy of the callback
        cb.reset(n, margin)
        ta.time = 0.0
        ta.state[:] = y
        ta.propagate_until(1e9)
        T[i, :len(cb.t)] = cb.t
        Y[i, :len(cb.t)] = cb.y
    return T, Y


def ensemble_section(p: dict[str, float], y0: np.ndarray, name: str, value: float, n: int,
                     tol: float, threads: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """The plain integrator run by ``ensemble_propagate_until`` on ``threads`` threads."""
    ta = _terminal_integrator(tuple(p.items()), name, value, tol)
    margin = _margin(p, name, value)
    ta.t_events[0].callback.reset(n, margin)  # each orbit's copy starts from this
    ta.time = 0.0

    def gen(ta_i: Any, i: int) -> Any:
        ta_i.state[:] = y0[i]
        return ta_i

    res = hy.ensemble_propagate_until(ta, 1e9, len(y0), gen, max_workers=threads)
    T = np.full((len(y0), n), np.nan)
    Y = np.full((len(y0), n, 6), np.nan)
    for i, r in enumerate(res):
        cb = r[0].t_events[0].callback
        T[i, :len(cb.t)] = cb.t
        Y[i, :len(cb.t)] = cb.y
    return T, Y


# ----------------------------------------------------------------------------- W2, tuned


class _Recorder:
    """Non-terminal batch-event callback: (time, dense-output state) per lane."""

    def __init__(self, batch: int) -> None:
        self.t: list[list[float]] = [[] for _ in range(batch)]
        self.y: list[list[np.ndarray]] = [[] for _ in range(batch)]
        self.tv = np.zeros(batch)

    def __call__(self, ta: Any, t: float, d_sgn: Any, lane: int) -> None:
        self.tv[lane] = t
        self.t[lane].append(t)
        self.y[lane].append(ta.update_d_output(self.tv)[:, lane].copy())


@cache
def _batch_template(p: Params, name: str, value: float, tol: float, batch: int) -> Any:
    f = heyoka_section(dict(p), name, value, hy)
    ev = hy.nt_event_batch(f, _Recorder(batch), direction=hy.event_direction.positive)
    return hy.taylor_adaptive_batch(heyoka_system(dict(p), hy), np.zeros((6, batch)),
                                    tol=tol, nt_events=[ev])


def tuned_section(p: dict[str, float], y0: np.ndarray, name: str, value: float, n: int,
                  tol: float, batch: int = 4, threads: int = 2, t_pilot: float = 2000.0,
                  margin: float = 1.02) -> tuple[np.ndarray, np.ndarray]:
    """The hand-tuned script: batches of similar orbits, per-lane end times, threads."""
    template = _batch_template(tuple(p.items()), name, value, tol, batch)
    keep = _margin(p, name, value)
    k = len(y0)
    times: list[list[float]] = [[] for _ in range(k)]
    states: list[list[np.ndarray]] = [[] for _ in range(k)]
    t_now = np.zeros(k)
    y_now = np.array(y0, dtype=float)

    def run(orbits: list[int], t_end: np.ndarray) -> None:
        ta = copy.deepcopy(template)
        rec = ta.nt_events[0].callback
        pad = orbits + [orbits[-1]] * (batch - len(orbits))
        ta.set_time(t_now[pad])
        ta.state[:] = y_now[pad].T
        ta.propagate_until(np.concatenate([t_end, t_end[-1:].repeat(batch - len(orbits))]))
        for lane, i in enumerate(orbits):
            for t, y in zip(rec.t[lane], rec.y[lane], strict=True):
                if t > T_START and keep(y) > 0.0:
                    times[i].append(t)
                    states[i].append(y)
            t_now[i] = ta.time[lane]
            y_now[i] = ta.state[:, lane]

    def in_batches(order: list[int], end: Any) -> None:
        groups = [order[s:s + batch] for s in range(0, len(order), batch)]
        with ThreadPoolExecutor(threads) as pool:
            list(pool.map(lambda g: run(g, np.array([end(i) for i in g])), groups))

    # 1. pilot: every orbit to t_pilot, for its return time
    in_batches(list(range(k)), lambda i: t_pilot)
    period = np.array([(ts[-1] - ts[0]) / (len(ts) - 1) if len(ts) > 1 else t_pilot
                       for ts in times])
    # 2. similar orbits together, per-lane end time at the predicted N-th crossing
    order = [int(i) for i in np.argsort(period)[::-1]]
    in_batches(order, lambda i: t_now[i] + margin * (n - len(times[i]) + 0.5) * period[i])
    # 3. the few lanes still short of N crossings
    while short := [i for i in order if len(times[i]) < n]:
        in_batches(short, lambda i: t_now[i] + (n - len(times[i]) + 2) * period[i])
    T = np.array([ts[:n] for ts in times])
    Y = np.array([ys[:n] for ys in states])
    return T, Y
