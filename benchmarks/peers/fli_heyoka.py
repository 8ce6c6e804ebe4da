"""W3 without andoyer: the FLI map as an expert heyoka.py user writes it.

Following heyoka.py's batch-mode and ensemble tutorials:

* the Euler-Poisson equations of :mod:`benchmarks.peers.model` (the body's numbers
  folded in as constants: no runtime parameters) and ONE tangent vector,
  ``w' = J(y) w`` with the Jacobian ``J`` built by ``heyoka.diff`` -- 12 variables,
  not the 42 of the full state transition matrix; the FLI needs ``|w|`` only;
* no renormalisation: at the FLI values of these maps (``ln |w| < 100`` at t = 1000)
  ``|w|`` is far from overflowing (``ln`` of the largest double is 709; the script
  checks that the norm stayed finite);
* a batch (SIMD) integrator of ``heyoka.recommended_simd_size()`` lanes, fully
  compiled (not ``compact_mode``), ONE ``propagate_grid`` call per block of lanes;
* blocks on a thread pool over every core (heyoka releases the GIL), each thread
  owning one copy of the integrator;
* ``FLI = max over the output times of ln |w(t)|``, as andoyer's ``chaos_map``.

The harness hands it the initial states and tangent vectors of andoyer's map (so
both compute the same thing); :func:`reference_map` is the same script at
``tol = 1e-15``, cached under ``benchmarks/reference/``.
"""

from __future__ import annotations

import copy
import os
import threading
from concurrent.futures import ThreadPoolExecutor
from functools import cache
from typing import Any

import heyoka as hy
import numpy as np
from benchmarks.peers.model import heyoka_system

Params = tuple[tuple[str, float], ...]


@cache
def _template(p: Params, tol: float, batch: int) -> Any:
    eqs = heyoka_system(dict(p), hy)
    y = [v for v, _ in eqs]
    w = hy.make_vars(*(f"w{i}" for i in range(6)))
    tangent = [(wi, hy.sum([hy.diff(rhs, yj) * wj for yj, wj in zip(y, w, strict=True)]))
               for wi, (_, rhs) in zip(w, eqs, strict=True)]
    return hy.taylor_adaptive_batch(eqs + tangent, np.zeros((12, batch)), tol=tol)


def fli_map(p: dict[str, float], y0: np.ndarray, w0: np.ndarray, t: np.ndarray, tol: float,
            batch: int | None = None, threads: int | None = None) -> np.ndarray:
    """FLI at ``t[-1]`` of the orbits from ``y0`` (n, 6) with tangents ``w0`` (n, 6),
    the maximum of ``ln |w|`` over the output times ``t`` (``t[0]`` the start)."""
    batch = batch or hy.recommended_simd_size()
    threads = threads or os.cpu_count() or 1
    template = _template(tuple(p.items()), tol, batch)
    n = len(y0)
    x0 = np.concatenate([y0, w0], axis=1)
    out = np.empty(n)
    grid = np.ascontiguousarray(np.repeat(t, batch).reshape(-1, batch))
    local = threading.local()

    def run(start: int) -> None:
        ta = getattr(local, "ta", None)
        if ta is None:
            ta = local.ta = copy.deepcopy(template)
        stop = min(n, start + batch)
        lanes = np.arange(start, start + batch).clip(max=stop - 1)  # pad: repeat the last
        ta.set_time(float(t[0]))
        ta.state[:] = x0[lanes].T
        res = ta.propagate_grid(grid)[-1]  # (times, 12, batch)
        norm = np.sqrt(np.sum(res[:, 6:, :] ** 2, axis=1))  # (times, batch)
        fli = np.log(norm).max(axis=0)
        done = [r[0] == hy.taylor_outcome.time_limit for r in ta.propagate_res]
        fli[~(np.all(np.isfinite(norm), axis=0) & np.array(done))] = np.nan
        out[start:stop] = fli[:stop - start]

    with ThreadPoolExecutor(threads) as pool:
        list(pool.map(run, range(0, n, batch)))
    return out


def inputs(ds: Any, body: Any, t_end: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Initial states, tangents and output times of andoyer's map ``ds`` (setup)."""
    from andoyer.analysis.chaos.lyapunov import initial_tangent
    from andoyer.charts.hess import from_hess

    a = ds.attrs
    xname, yname, action = a["plane_x"], a["plane_y"], a["action"]
    acc = ds.accessible.values
    Y, X = np.meshgrid(ds[yname].values, ds[xname].values, indexing="ij")
    P = np.stack([X[acc], np.full(acc.sum(), float(a["section_value"])), Y[acc],
                  ds[action].values[acc], np.full(acc.sum(), float(a["M"]))], axis=-1)
    y0 = from_hess(body, P)
    w0 = initial_tangent(body, y0, "energy" if a.get("tangent") == "energy" else "leaf")
    t = np.linspace(0.0, t_end, int(a.get("n_samples", 64)) + 1)
    return y0, w0, t


def reference_map(ds: Any, body: Any, t_end: float) -> np.ndarray:
    """FLI of every grid point of ``ds`` (NaN outside the accessible region) at tol 1e-15."""
    from benchmarks import reference as R
    from benchmarks import workloads as W

    y0, w0, t = inputs(ds, body, t_end)
    p = W.params(body)
    key = R._key(p=sorted(p.items()), y0=y0, w0=w0, t=t)

    def compute() -> dict[str, Any]:
        return {"fli": fli_map(p, y0, w0, t, 1e-15).tolist(), "tol": 1e-15}
    fli = np.array(R._cached("fli", key, compute)["fli"])
    full = np.full(ds.accessible.shape, np.nan)
    full[ds.accessible.values] = fli
    return full
