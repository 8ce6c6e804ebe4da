"""``python -m benchmarks.lane_width``: the lane kernels' cost per orbit-step at a lane
count, measured in a process of its own.

The lane count is fixed when the lane kernels are compiled
(:func:`andoyer.kernels.simd.lane_width`: ``ANDOYER_LANES``, else the CPU's vector
width), so each width runs in a fresh process with the variable set (:func:`run`, which
the harness calls for 4 and 8 lanes, and for 4 compiled for an AVX2 CPU,
:func:`avx2_environment`). In that process, on one thread, after one untimed
warm-up run each, interleaved for ``--repeat`` rounds (median CPU time,
``time.process_time``):

* the **bare lane flow** (:func:`andoyer.kernels.taylor.lanes.propagate`) of
  ``--orbits`` W2 starts to ``--t-end``, no output in between;
* a **G3 = 0 section** on the lanes
  (:func:`andoyer.kernels.taylor.lane_crossings.locate_crossings`, upward,
  ``--crossings`` crossings up to ``--t-end``).

The process prints one JSON line: the lane count and tuning, ns per orbit-step of each
run, the step counts, and the end states of the flow and the crossing times (so the
caller can compare widths: each lane's arithmetic does not depend on how many lanes run
beside it, the results agree to round-off). No timing is asserted anywhere.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from benchmarks import workloads as W


def measure(n: int, N: int, t_end: float, repeat: int) -> dict[str, Any]:
    """The runs of the module's docstring in this process (its lane count)."""
    import numba

    from andoyer.kernels import simd
    from andoyer.kernels.generated import equations
    from andoyer.kernels.taylor import flow, lane_crossings, lanes

    numba.set_num_threads(1)
    b = W.body()
    p = np.ascontiguousarray(b.engine_params, dtype=float)
    tol = W.FULL.tol
    order = flow.order_for(tol)
    big = 10**9
    y0 = np.ascontiguousarray(W.initial_states(n))
    t = np.array([0.0, t_end])
    g3 = (equations.SECTION_KINDS + equations.EXTRA_SECTION_KINDS).index("G3")
    runs: dict[str, Callable[[], Any]] = {
        "flow": lambda: lanes.propagate(y0, t, p, order, big, threads=1),
        "G3": lambda: lane_crossings.locate_crossings(y0, p, g3, 0.0, 1, N, t_end, tol, big,
                                                      threads=1),
    }
    out = {name: fn() for name, fn in runs.items()}  # warm-up: compile or load
    load0 = os.getloadavg()
    cpu: dict[str, list[float]] = {name: [] for name in runs}
    for _ in range(repeat):
        for name, fn in runs.items():
            c0 = time.process_time()
            out[name] = fn()
            cpu[name].append(time.process_time() - c0)
    load1 = os.getloadavg()
    steps = {"flow": int(out["flow"][1][:, 1].sum()), "G3": int(out["G3"][3][:, 1].sum())}
    return {"lanes": lanes.LANES, "width": simd.lane_width(), "tuning": simd.lane_tuning(),
            "orbits": n, "crossings": N, "t_end": t_end, "repeat": repeat,
            "load": [load0[0], load1[0]], "steps": steps,
            "cpu_s": {k: statistics.median(v) for k, v in cpu.items()},
            "ns_per_orbit_step": {k: 1e9 * statistics.median(v) / steps[k]
                                  for k, v in cpu.items()},
            "flow_end": out["flow"][0][:, -1, :6].tolist(),
            "crossing_t": np.where(np.isfinite(out["G3"][0]), out["G3"][0], -1.0).tolist()}


#: CPU features an AVX2 machine lacks (AVX-512 and its successors).
WIDER = ("avx512", "avx10", "evex512", "amx")


def avx2_environment() -> dict[str, str]:
    """The variables that make Numba compile for an AVX2 CPU on this machine: a Haswell
    (``NUMBA_CPU_NAME``) with the host's features but AVX-512's (:data:`WIDER`) turned off
    (``NUMBA_CPU_FEATURES``; the name alone keeps the host's features)."""
    import llvmlite.binding as ll

    features = ll.get_host_cpu_features()
    flags = ",".join(("+" if on and not name.startswith(WIDER) else "-") + name
                     for name, on in sorted(features.items()))
    return {"NUMBA_CPU_NAME": "haswell", "NUMBA_CPU_FEATURES": flags}


def run(width: int, n: int, N: int, t_end: float, repeat: int,
        env: dict[str, str] | None = None) -> dict[str, Any]:
    """:func:`measure` in a fresh process with ``ANDOYER_LANES=width`` and the variables
    ``env`` (``ANDOYER_LANE_TUNE``, ``NUMBA_CPU_NAME`` ...) set."""
    from andoyer.kernels import simd

    env = {**os.environ, **(env or {}), simd.LANES_ENV: str(width)}
    out = subprocess.run([sys.executable, "-m", "benchmarks.lane_width", "--orbits", str(n),
                          "--crossings", str(N), "--t-end", str(t_end), "--repeat",
                          str(repeat)], env=env, capture_output=True, text=True, check=True,
                         cwd=Path(__file__).resolve().parent.parent)
    result: dict[str, Any] = json.loads(out.stdout.strip().splitlines()[-1])
    return result


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.lane_width", description=__doc__)
    ap.add_argument("--orbits", type=int, default=64)
    ap.add_argument("--crossings", type=int, default=200)
    ap.add_argument("--t-end", type=float, default=300.0)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    print(json.dumps(measure(args.orbits, args.crossings, args.t_end, args.repeat)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
