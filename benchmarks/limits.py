"""The machine limit of each workload: its integration steps times the cost of a step.

What the method cannot beat on this machine: the steps the engine must take (counted by
the engine's own step counter on the same orbits, over the same spans of time, at the
same tolerance) times the cost of one step with every SIMD lane busy, on every core. No
events, no output, no Python: the bare integrator. An andoyer time divided by this limit
says how much of the run is spent on anything else (event location, dense output,
polishing, datasets, threads waiting for the slowest orbit).

* heyoka: steps from ``propagate_until`` of a scalar integrator of andoyer's own
  expressions (:func:`andoyer.integrate.engines.heyoka_symbolic.heyoka_system`, resp.
  :func:`andoyer.integrate.variational.variational_system` for W3); the cost of a
  lane-step from a batch integrator of :func:`heyoka.recommended_simd_size` lanes
  stepping without events on one thread. One orbit (W1) cannot fill lanes or cores:
  its limit is its steps at the scalar cost on one core.
* numba: accepted + rejected steps from the DOP853 kernel's ``info`` counters
  (:func:`andoyer.kernels.dop853.flow.propagate`, tolerances scaled as the engine scales
  them), the cost of a step from the same runs (the kernel is scalar: one orbit per
  core, no lanes).
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

#: Steps of the batch integrator timed for the cost of a lane-step.
_BATCH_STEPS = 4000


@dataclass
class Limit:
    """The limit of one engine on one workload."""

    engine: str
    steps: int  # integration steps of the workload (all orbits)
    step_s: float  # cost of one step of one orbit, every lane and core busy
    limit_s: float  # steps x step_s
    note: str = ""


def _cores() -> int:
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (
        os.cpu_count() or 1)


def heyoka_limit(body: Any, y0: np.ndarray, t_end: np.ndarray, tol: float, *,
                 variational: bool = False, w0: np.ndarray | None = None,
                 single_orbit: bool = False) -> Limit:
    """Steps of the orbits ``y0`` to their times ``t_end`` and the heyoka limit."""
    import heyoka as hy

    lanes = 1
    if variational:
        from andoyer.integrate.engines.heyoka_engine import PLAIN_SIMD_MULTIPLE
        from andoyer.integrate.engines.heyoka_symbolic import (
            coefficient_tangent_system,
            coefficient_values,
        )

        # The system chaos_map(indicator="fli") integrates (engines.heyoka_tangent's
        # "plain" flow): the state and ONE tangent vector, 12 variables, the body's
        # coefficients as runtime parameters (those that vanish left out), not
        # renormalised (the renormalised 17-variable system is only re-run for the few
        # orbits whose ln|w| nears overflow), in PLAIN_SIMD_MULTIPLE x SIMD lanes.
        pars = coefficient_values(body.engine_params)
        zero = frozenset(np.flatnonzero(pars == 0.0).tolist())
        system = batch_system = list(coefficient_tangent_system(zero))
        lanes = PLAIN_SIMD_MULTIPLE
        assert w0 is not None
        x0 = np.concatenate([y0, w0], axis=1)
        compact = False  # as andoyer compiles it
    else:
        from andoyer.integrate.engines.heyoka_symbolic import heyoka_system

        # each integrator on the form andoyer gives it (the scalar one is rewritten)
        system, batch_system = list(heyoka_system(scalar=True)), list(heyoka_system())
        pars = np.array([*body.engine_params, 0.0, 1.0, 0.0])
        x0 = y0
        compact = False
    dim = x0.shape[1]
    ta = hy.taylor_adaptive(system, [0.0] * dim, tol=tol, compact_mode=compact)
    ta.pars[:] = pars[:len(ta.pars)]
    scalar = np.inf
    for _ in range(3 if single_orbit else 1):  # one orbit: best of 3 (a few ms each)
        steps = 0
        t0 = time.perf_counter()
        for x, T in zip(x0, np.broadcast_to(t_end, (x0.shape[0],)), strict=True):
            ta.time = 0.0
            ta.state[:] = x
            res = ta.propagate_until(float(T))
            steps += int(res[3])
        scalar = min(scalar, (time.perf_counter() - t0) / max(steps, 1))
    if single_orbit:
        return Limit("heyoka", steps, scalar, steps * scalar,
                     "one orbit: one lane of one core (scalar integrator)")
    m = lanes * int(hy.recommended_simd_size())
    tb = hy.taylor_adaptive_batch(batch_system, np.zeros((dim, m)), tol=tol, compact_mode=compact)
    tb.pars[:] = pars[:len(ta.pars), None]
    rows = np.resize(np.arange(x0.shape[0]), m)
    best = np.inf
    for _ in range(3):
        tb.set_time(np.zeros(m))
        tb.state[:] = x0[rows].T
        t1 = time.perf_counter()
        tb.propagate_until(np.full(m, 1e12), max_steps=_BATCH_STEPS)
        best = min(best, time.perf_counter() - t1)
    lane_step = best / (_BATCH_STEPS * m)
    cores = _cores()
    return Limit("heyoka", steps, lane_step / cores, steps * lane_step / cores,
                 f"{m} SIMD lanes x {cores} cores; scalar step {scalar * 1e9:.0f} ns, "
                 f"lane-step {lane_step * 1e9:.0f} ns")


def numba_limit(body: Any, y0: np.ndarray, t_end: np.ndarray, tol: float, *,
                single_orbit: bool = False) -> Limit:
    """Steps of the orbits ``y0`` to ``t_end`` with the numba engine's DOP853 kernel."""
    from andoyer.integrate.engines.base import TOLERANCE_FACTOR
    from andoyer.kernels.common import INFO
    from andoyer.kernels.dop853 import flow

    p = np.ascontiguousarray(body.engine_params, dtype=float)
    f = TOLERANCE_FACTOR
    col = [INFO.index("accepted"), INFO.index("rejected")]
    wall = np.inf
    for _ in range(3 if single_orbit else 1):
        steps, spent = 0, 0.0
        for x, T in zip(y0, np.broadcast_to(t_end, (y0.shape[0],)), strict=True):
            t1 = time.perf_counter()
            _, info = flow.propagate(x[None].copy(), np.array([0.0, float(T)]), p,
                                       f * tol, f * tol, 10**8, threads=1)
            spent += time.perf_counter() - t1
            steps += int(info[0, col].sum())
        wall = min(wall, spent)
    step = wall / max(steps, 1)
    cores = 1 if single_orbit else _cores()
    return Limit("numba", steps, step / cores, steps * step / cores,
                 "one orbit: one core" if single_orbit else
                 f"{cores} cores (scalar kernel); step {step * 1e9:.0f} ns")
