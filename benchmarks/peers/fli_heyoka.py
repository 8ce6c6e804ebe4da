"""W3 without andoyer: an FLI map with heyoka's variational equations (``var_ode_sys``).

The expert script: the Euler-Poisson equations of :mod:`benchmarks.peers.model` with
their first-order variational equations (``var_ode_sys``: the 6 x 6 state transition
matrix Phi, 42 equations), batch (SIMD) integrators of 4 lanes on 2 threads, each
orbit's ``w(t) = Phi(t) w0`` read on a grid of output times, and

    FLI = max over the output times of ln |w(t)|.

The harness hands it the initial states and tangent vectors of andoyer's map (so
both compute the same thing); :func:`reference_map` is the same script at
``tol = 1e-15``, cached under ``benchmarks/reference/``.
"""

from __future__ import annotations

import copy
from concurrent.futures import ThreadPoolExecutor
from functools import cache
from typing import Any

import heyoka as hy
import numpy as np
from benchmarks.peers.model import heyoka_system

Params = tuple[tuple[str, float], ...]


@cache
def _template(p: Params, tol: float, batch: int) -> Any:
    vsys = hy.var_ode_sys(heyoka_system(dict(p), hy), hy.var_args.vars, order=1)
    return hy.taylor_adaptive_batch(vsys, np.zeros((42, batch)), tol=tol, compact_mode=True)


def fli_map(p: dict[str, float], y0: np.ndarray, w0: np.ndarray, t: np.ndarray, tol: float,
            batch: int = 4, threads: int = 2) -> np.ndarray:
    """FLI at ``t[-1]`` of the orbits from ``y0`` (n, 6) with tangents ``w0`` (n, 6)."""
    template = _template(tuple(p.items()), tol, batch)
    n = len(y0)
    out = np.empty(n)
    eye = np.eye(6).ravel()

    def run(start: int) -> None:
        idx = np.arange(start, min(n, start + batch))
        lanes = np.concatenate([idx, np.repeat(idx[-1:], batch - idx.size)])
        ta = copy.deepcopy(template)
        ta.set_time(np.full(batch, t[0]))
        ta.state[:6] = y0[lanes].T
        ta.state[6:] = eye[:, None]
        res = ta.propagate_grid(np.repeat(t, batch).reshape(-1, batch))[-1]  # (k, 42, b)
        phi = res[:, 6:, :].reshape(len(t), 6, 6, batch)
        w = np.einsum("kijb,bj->kbi", phi, w0[lanes])
        fli = np.log(np.linalg.norm(w, axis=-1)).max(axis=0)
        out[idx] = fli[:idx.size]

    with ThreadPoolExecutor(threads) as pool:
        list(pool.map(run, range(0, n, batch)))
    return out


def inputs(ds: Any, body: Any, t_end: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Initial states, tangents and output times of andoyer's map ``ds`` (setup)."""
    from andoyer.analysis.chaos import initial_tangent
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
