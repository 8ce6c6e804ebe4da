"""The tight reference every runner's error is measured against.

heyoka's Taylor integrator in extended precision (``numpy.longdouble``: the x87
80-bit format on x86-64, 64-bit significand, eps = 1.1e-19) at ``tol = eps``, on the
hand-written equations of :mod:`benchmarks.peers.model` (checked against andoyer's
derived field by ``tests/test_benchmarks_harness.py``). Its own error is some 1e-17
where the double-precision runners' errors are 1e-13 and above.

Crossings are located by terminal events: the integrator stops on the crossing, so
the reference state there needs no dense output. Results are cached as small JSON
files under ``benchmarks/reference/``, keyed by a hash of everything they depend on
(parameters, initial states, section, number of crossings, t_end).
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path
from typing import Any

import heyoka as hy
import numpy as np

from benchmarks.peers.model import T_START, heyoka_section, heyoka_system, numpy_section

CACHE = Path(__file__).with_name("reference")
LD = np.longdouble
TOL = np.finfo(LD).eps


def _key(**what: Any) -> str:
    h = hashlib.sha256()
    for k in sorted(what):
        v = what[k]
        h.update(k.encode())
        h.update(np.ascontiguousarray(v).tobytes() if isinstance(v, np.ndarray)
                 else repr(v).encode())
    return h.hexdigest()[:16]


def _cached(kind: str, key: str, compute: Any) -> dict[str, Any]:
    path = CACHE / f"{kind}-{key}.json"
    if path.exists():
        out: dict[str, Any] = json.loads(path.read_text())
        return out
    out = compute()
    CACHE.mkdir(exist_ok=True)
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(out, indent=1))
    tmp.replace(path)
    return out


def orbit_end(p: dict[str, float], y0: np.ndarray, t_end: float) -> np.ndarray:
    """Reference state at ``t_end`` of the orbit from ``y0`` at t = 0."""
    def compute() -> dict[str, Any]:
        ta = hy.taylor_adaptive(heyoka_system(p, hy), np.asarray(y0, dtype=LD), tol=TOL,
                                fp_type=LD)
        outcome = ta.propagate_until(LD(t_end))[0]
        if outcome != hy.taylor_outcome.time_limit:
            raise RuntimeError(f"reference orbit stopped: {outcome}")
        return {"y": [str(v) for v in ta.state], "t_end": t_end, "tol": str(TOL)}
    key = _key(p=sorted(p.items()), y0=np.asarray(y0, dtype=float), t_end=t_end)
    return np.array(_cached("orbit", key, compute)["y"], dtype=LD).astype(float)


class _Last:
    """Terminal-event callback: count crossings, stop at the n-th, keep it."""

    def __init__(self) -> None:
        self.reset(0, None)

    def reset(self, n: int, margin: Any) -> None:
        self.n, self.margin, self.count = n, margin, 0
        self.t: str = "nan"
        self.y: list[str] = []

    def __call__(self, ta: Any, d_sgn: Any) -> bool:
        if ta.time > T_START and self.margin(ta.state.astype(float)) > 0.0:
            self.count += 1
            if self.count == self.n:
                self.t, self.y = str(ta.time), [str(v) for v in ta.state]
        return self.count < self.n


def crossing(p: dict[str, float], y0: np.ndarray, name: str, value: float, n: int,
             threads: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """Reference time (k,) and state (k, 6) of the ``n``-th upward crossing of each orbit."""
    y0 = np.asarray(y0, dtype=float)

    def compute() -> dict[str, Any]:
        fw = numpy_section(p, name, value)
        f = heyoka_section(p, name, value, hy)
        ev = hy.t_event(f, callback=_Last(), direction=hy.event_direction.positive,
                        fp_type=LD)
        ta = hy.taylor_adaptive(heyoka_system(p, hy), np.zeros(6, dtype=LD), tol=TOL,
                                fp_type=LD, t_events=[ev])
        ta.t_events[0].callback.reset(n, lambda y: float(fw(y)[1]))

        def gen(ta_i: Any, i: int) -> Any:
            ta_i.state[:] = y0[i].astype(LD)
            return ta_i

        res = hy.ensemble_propagate_until(ta, LD(1e9), len(y0), gen, max_workers=threads)
        cbs = [r[0].t_events[0].callback for r in res]
        return {"t": [cb.t for cb in cbs], "y": [cb.y for cb in cbs], "n": n, "tol": str(TOL)}
    key = _key(p=sorted(p.items()), y0=y0, name=name, value=value, n=n)
    out = _cached(f"crossing-{name}", key, compute)
    return (np.array(out["t"], dtype=LD).astype(float),
            np.array(out["y"], dtype=LD).astype(float))
