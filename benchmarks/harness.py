"""Side-by-side timings of andoyer and the scripts a user would write without it.

Every runner gets the same initial states (:mod:`benchmarks.workloads`); its error is
measured against the extended-precision reference (:mod:`benchmarks.reference`), not
assumed from its tolerance. Wall times are medians of ``repeat`` runs after one
untimed warm-up run (compilation is W4's subject); CPU times (all threads) are
recorded beside them, since the machine may be shared.
"""

from __future__ import annotations

import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np

from benchmarks import limits as L
from benchmarks import reference as R
from benchmarks import scaling as S
from benchmarks import workloads as W

#: The runner of andoyer on its heyoka engine (the default of every workload not in
#: MEASURED_DEFAULTS: :func:`default_runner`).
HEYOKA = "andoyer heyoka"
STATE = ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")


@dataclass
class Row:
    """One runner on one workload."""

    workload: str
    case: str
    runner: str
    wall_s: float  # median over the timed runs (extrapolated where noted)
    cpu_s: float
    runs: list[float]
    error_median: float = math.nan
    error_max: float = math.nan
    error_what: str = ""
    note: str = ""
    extra: dict[str, Any] = field(default_factory=dict)


def timed(fn: Callable[[], Any], repeat: int, warm_up: bool = True
          ) -> tuple[float, float, list[float], Any]:
    """(median wall, median CPU, all walls, last result) of ``repeat`` calls."""
    return timed_interleaved({"": fn}, repeat, warm_up)[""]


def timed_interleaved(fns: dict[str, Callable[[], Any]], repeat: int, warm_up: bool = True
                      ) -> dict[str, tuple[float, float, list[float], Any]]:
    """:func:`timed` of every ``fns`` in ``repeat`` rounds: each round calls each once,
    in turn, so a phase of the host (its load, its clock) falls on all of them alike and
    their ratios hold; one warm-up call each first (``warm_up``)."""
    for fn in fns.values() if warm_up else ():
        fn()
    walls: dict[str, list[float]] = {k: [] for k in fns}
    cpus: dict[str, list[float]] = {k: [] for k in fns}
    outs: dict[str, Any] = dict.fromkeys(fns)
    for _ in range(repeat):
        for name, fn in fns.items():
            c0, t0 = time.process_time(), time.perf_counter()
            outs[name] = fn()
            walls[name].append(time.perf_counter() - t0)
            cpus[name].append(time.process_time() - c0)
    return {k: (statistics.median(walls[k]), statistics.median(cpus[k]), walls[k], outs[k])
            for k in fns}


def _say(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


# ----------------------------------------------------------------------------- W1


def _method_limit(runner: str, limits: dict[str, dict[str, Any]], label: str,
                  *args: Any, **kwargs: Any) -> dict[str, Any]:
    """The machine limit of an andoyer runner's method, measured once per method into
    ``limits``: taylor's is heyoka's (the same Taylor method and steps, and the machine's
    cheapest bare lane-step of it: benchmarks/limits.py), numba's its DOP853's."""
    kind = "numba" if runner.endswith("numba") else "heyoka"
    if kind not in limits:
        _say(f"{label} {runner}: machine limit ...")
        limits[kind] = asdict((L.heyoka_limit if kind == "heyoka" else L.numba_limit)(
            *args, **kwargs))
    return limits[kind]


def w1(sizes: W.Sizes, runners: set[str]) -> list[Row]:
    from andoyer.integrate import propagate
    from benchmarks.peers import heyoka_scripts as hs
    from benchmarks.peers import scipy_scripts as ss

    b = W.body()
    p = W.params(b)
    y0 = W.initial_states(1)[0]
    t = W.w1_times(sizes)
    tol = sizes.tol
    ref = R.orbit_end(p, y0, float(t[-1]))

    def andoyer(engine: str) -> Callable[[], np.ndarray]:
        def run() -> np.ndarray:
            ds = propagate(b, y0, t, engine=engine, rtol=tol, atol=tol, progress=False)
            return np.array([ds[v].values[0, -1] for v in STATE])
        return run

    # Milliseconds each: the fast runners are timed in rounds (timed_interleaved), the
    # scipy ones, a thousand times slower, alone.
    fast: dict[str, Callable[[], np.ndarray]] = {
        "andoyer heyoka": andoyer("heyoka"),
        "andoyer numba": andoyer("numba"),
        "andoyer taylor": andoyer("taylor"),
        "heyoka plain": lambda: hs.plain_orbit(p, y0, t, tol)[-1],
    }
    slow: dict[str, tuple[Callable[[], np.ndarray], int]] = {
        "andoyer scipy": (andoyer("scipy"), 1),
        "scipy DOP853": (lambda: ss.orbit(p, y0, t, tol, tol)[-1], max(1, sizes.repeat // 2)),
    }
    chosen = [name for name in fast if name in runners]
    if chosen:
        _say(f"W1 {', '.join(chosen)}: {sizes.w1_rounds} rounds ...")
    timings = timed_interleaved({k: fast[k] for k in chosen}, sizes.w1_rounds)
    rows = []
    limits: dict[str, dict[str, Any]] = {}
    for name in ("andoyer heyoka", "andoyer numba", "andoyer taylor", "andoyer scipy",
                 "heyoka plain", "scipy DOP853"):
        if name not in runners:
            continue
        if name in slow:
            _say(f"W1 {name} ...")
            fn, repeat = slow[name]
            wall, cpu, walls, y = timed(fn, repeat, warm_up=False)
            note = f"{repeat} run(s), no warm-up"
        else:
            wall, cpu, walls, y = timings[name]
            note = ""
        err = float(np.max(np.abs(np.asarray(y) - ref)))
        rows.append(Row("W1", f"1 orbit to t = {t[-1]:g}, {t.size} outputs", name, wall, cpu,
                        walls, err, err, "max |y(t_end) - y_ref|", note=note))
        if name in ("andoyer heyoka", "andoyer numba", "andoyer taylor"):
            rows[-1].extra["limit"] = _method_limit(name, limits, "W1", b, y0[None],
                                                    np.array([t[-1]]), tol, single_orbit=True)
            if name == "andoyer heyoka":  # the dataset's cost, measured apart
                ds = propagate(b, y0, t, engine="heyoka", rtol=tol, atol=tol, progress=False)
                rows[-1].extra["dataset_load_s"] = timed(lambda ds=ds: ds.copy(deep=True)
                                                         .load(), sizes.repeat)[0]
    return rows


# ----------------------------------------------------------------------------- W2


def _errors(T: np.ndarray, Y: np.ndarray, t_ref: np.ndarray, y_ref: np.ndarray
            ) -> tuple[float, float, dict[str, float]]:
    e_y = np.max(np.abs(Y[:, -1] - y_ref), axis=-1)
    e_t = np.abs(T[:, -1] - t_ref)
    missing = int(np.isnan(T[:, -1]).sum())
    return (float(np.nanmedian(e_y)), float(np.nanmax(e_y)),
            {"t_error_median": float(np.nanmedian(e_t)), "t_error_max": float(np.nanmax(e_t)),
             "orbits_short_of_n": missing})


def w2(sizes: W.Sizes, runners: set[str], full_scipy: bool,
       sections: tuple[tuple[str, float], ...] = W.SECTIONS, quick: bool = False
       ) -> list[Row]:
    from andoyer.integrate import Section, poincare
    from benchmarks.peers import heyoka_scripts as hs
    from benchmarks.peers import scipy_scripts as ss

    b = W.body()
    p = W.params(b)
    n, N, tol = sizes.w2_orbits, sizes.w2_crossings, sizes.tol
    y0 = W.initial_states(n)
    rows: list[Row] = []
    for name, value in sections:
        case = f"{n} orbits x {N} crossings of {name} = {value:g} (upward)"
        _say(f"W2 reference {name} ({n} x {N}, extended precision; cached) ...")
        t_ref, y_ref = R.crossing(p, y0, name, value, N)
        section = Section(name, value, 1)

        def andoyer(engine: str, y: np.ndarray = y0, section: Section = section
                    ) -> Callable[[], tuple[np.ndarray, np.ndarray]]:
            def run() -> tuple[np.ndarray, np.ndarray]:
                ds = poincare(b, y, section, N, engine=engine, rtol=tol, atol=tol,
                              progress=False)
                return ds.t.values, np.stack([ds[v].values for v in STATE], axis=-1)
            return run

        def peer(fn: Callable[..., Any], *args: Any, y: np.ndarray = y0, name: str = name,
                 value: float = value) -> Callable[[], tuple[np.ndarray, np.ndarray]]:
            return lambda: fn(p, y, name, value, N, *args)

        fast: dict[str, Callable[[], tuple[np.ndarray, np.ndarray]]] = {
            "andoyer heyoka": andoyer("heyoka"),
            "andoyer numba": andoyer("numba"),
            "andoyer taylor": andoyer("taylor"),
            "heyoka plain": peer(hs.plain_section, tol),
            "heyoka ensemble": peer(hs.ensemble_section, tol, 2),
            "heyoka hand-tuned": peer(hs.tuned_section, tol),
        }
        limits: dict[str, dict[str, Any]] = {}
        for runner, fn in fast.items():
            if runner not in runners:
                continue
            _say(f"W2 {name} {runner} ...")
            wall, cpu, walls, (T, Y) = timed(fn, sizes.repeat)
            em, ex, extra = _errors(T, Y, t_ref, y_ref)
            if runner in ("andoyer heyoka", "andoyer numba", "andoyer taylor"):
                extra["limit"] = _method_limit(runner, limits, f"W2 {name}", b, y0,
                                               np.asarray(t_ref, dtype=float), tol)
            rows.append(Row("W2", case, runner, wall, cpu, walls, em, ex,
                            f"max-norm error of the state at crossing {N}", extra=extra))
        # scipy: a subset of the orbits, extrapolated by integrated time
        k = n if full_scipy else min(n, sizes.scipy_orbits)
        span = np.asarray(t_ref, dtype=float)
        # (function of the orbit indices, orbits per process)
        slow: dict[str, tuple[Callable[[np.ndarray], Any], int]] = {
            "andoyer scipy": (lambda idx: andoyer("scipy", y0[idx])(), 1),
            "scipy DOP853 serial": (lambda idx: peer(ss.section, tol, tol, y=y0[idx])(), 1),
            "scipy DOP853 pool(2)": (
                lambda idx: peer(ss.section_pool, tol, tol, 2, y=y0[idx])(), 2),
        }
        for runner, (sub, per_process) in slow.items():
            if runner not in runners or (quick and runner == "andoyer scipy"):
                continue
            idx = W.subset(n, min(n, k * per_process))
            _say(f"W2 {name} {runner} on {idx.size} orbit(s) ...")

            def call(sub: Callable[[np.ndarray], Any] = sub, idx: np.ndarray = idx) -> Any:
                return sub(idx)

            wall, cpu, walls, (T, Y) = timed(call, 1, warm_up=False)
            scale = float(span.sum() / span[idx].sum())
            em, ex, extra = _errors(T, Y, t_ref[idx], y_ref[idx])
            extra.update(orbits_run=int(idx.size), measured_wall_s=wall, scale=scale)
            rows.append(Row("W2", case, runner, wall * scale, cpu * scale, walls, em, ex,
                            f"max-norm error of the state at crossing {N}",
                            note=("" if idx.size == n else
                                  f"extrapolated: {idx.size} of {n} orbits run once, "
                                  f"time x {scale:.1f} (ratio of integrated time)"),
                            extra=extra))
    return rows


# ----------------------------------------------------------------------------- W3


def w3(sizes: W.Sizes, runners: set[str]) -> list[Row]:
    case = f"FLI map {sizes.w3_grid} x {sizes.w3_grid}, t = {sizes.w3_t_end:g}"
    try:
        from andoyer.analysis.chaos.lyapunov import IndicatorRun, chaos_map
    except ImportError as exc:
        return [Row("W3", case, HEYOKA, math.nan, math.nan, [],
                    note=f"not available: andoyer.analysis.chaos.lyapunov.chaos_map ({exc})")]
    from benchmarks.peers import fli_heyoka

    b = W.body()
    h = W.energy_level(b)
    grid = (sizes.w3_grid, sizes.w3_grid)

    def andoyer(tol: float = sizes.tol) -> Any:
        return chaos_map(b, h, 0.0, ("theta2", 0.0), grid,
                         IndicatorRun("fli", t_end=sizes.w3_t_end, tol=tol), engine="heyoka",
                         progress=False)

    _say("W3 andoyer heyoka ...")
    wall, cpu, walls, ds = timed(andoyer, max(1, sizes.repeat // 2 + 1))
    _say("W3 reference (heyoka at tol 1e-15) ...")
    fli_ref = np.asarray(fli_heyoka.reference_map(ds, b, sizes.w3_t_end))
    fli = np.asarray(ds.fli.values)
    ok = np.isfinite(fli_ref)
    err = np.abs(fli - fli_ref)[ok]
    _say("W3 machine limit (steps of a sample of the points) ...")
    y0, w0, _ = fli_heyoka.inputs(ds, b, sizes.w3_t_end)
    pick = W.subset(y0.shape[0], min(y0.shape[0], 256))
    limit = L.heyoka_limit(b, y0[pick], np.array([sizes.w3_t_end]), sizes.tol,
                           variational=True, w0=w0[pick])
    scale = y0.shape[0] / pick.size
    limit.steps, limit.limit_s = round(limit.steps * scale), limit.limit_s * scale
    limit.note += f"; steps of {pick.size} of {y0.shape[0]} points, scaled"
    rows = [Row("W3", case, HEYOKA, wall, cpu, walls, float(np.median(err)),
                float(np.max(err)), "|FLI - FLI_ref| over the accessible points",
                extra={"points": int(ok.sum()), "limit": asdict(limit)})]
    if "andoyer taylor" in runners:
        # The Taylor engine in Numba (SIMD lanes, kernels.taylor.lanes), same map.
        _say("W3 andoyer taylor ...")
        wall, cpu, walls, dt = timed(lambda: chaos_map(
            b, h, 0.0, ("theta2", 0.0), grid,
            IndicatorRun("fli", t_end=sizes.w3_t_end, tol=sizes.tol), engine="taylor",
            progress=False), max(1, sizes.repeat // 2 + 1))
        e = np.abs(np.asarray(dt.fli.values) - fli_ref)[ok]
        rows.append(Row("W3", case, "andoyer taylor", wall, cpu, walls, float(np.median(e)),
                        float(np.max(e)), "|FLI - FLI_ref| over the accessible points"))
    if "heyoka hand-tuned" in runners:
        _say("W3 heyoka hand-tuned (state + 1 tangent vector, SIMD batch, threads) ...")
        y0, w0, t_out = fli_heyoka.inputs(ds, b, sizes.w3_t_end)
        p = W.params(b)
        wall, cpu, walls, f = timed(lambda: fli_heyoka.fli_map(p, y0, w0, t_out, sizes.tol),
                                    max(1, sizes.repeat // 2 + 1))
        e = np.abs(f - fli_ref[ok])
        rows.append(Row("W3", case, "heyoka hand-tuned", wall, cpu, walls,
                        float(np.median(e)), float(np.max(e)),
                        "|FLI - FLI_ref| over the accessible points"))
    if sizes.w3_big:
        rows += w3_big(sizes, runners)
    return rows


def w3_big(sizes: W.Sizes, runners: set[str]) -> list[Row]:
    """The large map, timed once each (compiled integrators are warm from W3's runs):
    andoyer against the hand-written heyoka ensemble of the variational system, their
    FLI compared point by point (no extended-precision reference at this size)."""
    from andoyer.analysis.chaos.lyapunov import IndicatorRun, chaos_map
    from benchmarks.peers import fli_heyoka

    b = W.body()
    n = sizes.w3_big
    case = f"FLI map {n} x {n}, t = {sizes.w3_t_end:g}"
    _say(f"W3 {n} x {n} andoyer heyoka (once) ...")
    wall, cpu, walls, ds = timed(
        lambda: chaos_map(b, W.energy_level(b), 0.0, ("theta2", 0.0), (n, n),
                          IndicatorRun("fli", t_end=sizes.w3_t_end, tol=sizes.tol),
                          engine="heyoka", progress=False), 1, warm_up=False)
    rows = [Row("W3", case, HEYOKA, wall, cpu, walls,
                note="timed once", extra={"points": int(ds.accessible.values.sum())})]
    if "andoyer taylor" in runners:
        _say(f"W3 {n} x {n} andoyer taylor (once) ...")
        wall, cpu, walls, dt = timed(
            lambda: chaos_map(b, W.energy_level(b), 0.0, ("theta2", 0.0), (n, n),
                              IndicatorRun("fli", t_end=sizes.w3_t_end, tol=sizes.tol),
                              engine="taylor", progress=False), 1, warm_up=False)
        d = np.abs(np.asarray(dt.fli.values) - np.asarray(ds.fli.values))
        d = d[np.isfinite(d)]
        rows.append(Row("W3", case, "andoyer taylor", wall, cpu, walls, float(np.median(d)),
                        float(np.max(d)), "|FLI_taylor - FLI_heyoka| (no reference at this "
                        "size)", note="timed once"))
    if "heyoka hand-tuned" in runners:
        _say(f"W3 {n} x {n} heyoka hand-tuned (once) ...")
        y0, w0, t_out = fli_heyoka.inputs(ds, b, sizes.w3_t_end)
        wall, cpu, walls, f = timed(lambda: fli_heyoka.fli_map(W.params(b), y0, w0, t_out,
                                                               sizes.tol), 1, warm_up=False)
        d = np.abs(np.asarray(ds.fli.values)[ds.accessible.values] - f)
        d = d[np.isfinite(d)]
        rows.append(Row("W3", case, "heyoka hand-tuned", wall, cpu, walls,
                        float(np.median(d)), float(np.max(d)),
                        "|FLI_andoyer - FLI_hand-tuned| (no reference at this size)",
                        note="timed once"))
    return rows


def w2_small(sizes: W.Sizes, runners: set[str]) -> list[Row]:
    """W2's G3 = 0 section at a smaller size (``sizes.w2_small``), taylor beside heyoka
    (issue 36: the lanes' advantage measured at 20 x 400 as at 50 x 1000). No reference
    at this size: taylor's row gives its difference from heyoka's crossings."""
    from andoyer.integrate import Section, poincare

    if not {"andoyer taylor", HEYOKA} <= runners:
        return []
    b = W.body()
    (n, N), tol = sizes.w2_small, sizes.tol
    y0 = W.initial_states(n)
    case = f"{n} orbits x {N} crossings of G3 = 0 (upward)"

    def run(engine: str) -> Callable[[], tuple[np.ndarray, np.ndarray]]:
        def go() -> tuple[np.ndarray, np.ndarray]:
            ds = poincare(b, y0, Section("G3", 0.0, 1), N, engine=engine, rtol=tol, atol=tol,
                          progress=False)
            return ds.t.values, np.stack([ds[v].values for v in STATE], axis=-1)
        return go

    rows, out = [], {}
    for runner, engine in ((HEYOKA, "heyoka"), ("andoyer taylor", "taylor")):
        _say(f"W2 {case} {runner} ...")
        wall, cpu, walls, out[engine] = timed(run(engine), sizes.repeat)
        rows.append(Row("W2", case, runner, wall, cpu, walls))
    Yh, Yt = out["heyoka"][1], out["taylor"][1]
    d = np.max(np.abs(Yt[:, -1] - Yh[:, -1]), axis=-1)
    rows[-1].error_median, rows[-1].error_max = float(np.nanmedian(d)), float(np.nanmax(d))
    rows[-1].error_what = f"max-norm difference from heyoka's state at crossing {N}"
    rows[-1].note = "error: difference from heyoka (no reference at this size)"
    return rows


def w3_megno(sizes: W.Sizes, runners: set[str]) -> list[Row]:
    """The MEGNO map of W3's plane (``chaos_map(..., "megno")``, W3's grid and ``t_end``)
    on taylor (its default, :data:`andoyer.integrate.engines.MEASURED_DEFAULTS`
    ``megno_map``: renormalised tangent flows on SIMD lanes) and on heyoka, as
    ``benchmarks/megno_map.py`` measures it; taylor's row gives its difference from
    heyoka's MEGNO values (no reference)."""
    from andoyer.analysis.chaos.lyapunov import IndicatorRun, chaos_map

    b = W.body()
    h = W.energy_level(b)
    g = sizes.w3_grid
    case = f"MEGNO map {g} x {g}, t = {sizes.w3_t_end:g}"
    job = IndicatorRun("megno", t_end=sizes.w3_t_end, tol=sizes.tol)
    def megno_map(engine: str) -> Callable[[], Any]:
        return lambda: chaos_map(b, h, 0.0, ("theta2", 0.0), (g, g), job, engine=engine,
                                 progress=False)

    rows, maps = [], {}
    for runner in (HEYOKA, "andoyer taylor"):
        if runner not in runners:
            continue
        engine = runner.split()[-1]
        _say(f"W3 {case} {runner} ...")
        wall, cpu, walls, maps[engine] = timed(megno_map(engine),
                                               max(1, sizes.repeat // 2 + 1))
        rows.append(Row("W3", case, runner, wall, cpu, walls,
                        extra={"failed": int(maps[engine].attrs["n_failed"])}))
    if len(maps) == 2:
        d = np.abs(np.asarray(maps["taylor"].megno.values)
                   - np.asarray(maps["heyoka"].megno.values))
        d = d[np.isfinite(d)]
        rows[-1].error_median, rows[-1].error_max = float(np.median(d)), float(np.max(d))
        rows[-1].error_what = "|MEGNO_taylor - MEGNO_heyoka| over the accessible points"
        rows[-1].note = "error: difference from heyoka (no reference)"
    return rows


# ----------------------------------------------------------------------------- W4


def w4(cold: bool, runners: set[str], rounds: int = 3) -> list[Row]:
    """Fresh processes (:mod:`benchmarks.startup`), ``rounds`` per runner and state, the
    runners in turn in each round (a phase of the host falls on all alike); each row the
    medians of its rounds."""
    names = [r for r in ("andoyer-heyoka", "andoyer-numba", "andoyer-taylor", "heyoka-plain")
             if r.replace("-", " ") in runners]
    root = Path(__file__).resolve().parent.parent
    rows = []
    for state in (("cold", "warm") if cold else ("warm",)):
        for runner in names if state == "warm" else ():
            # Warm means a process ran this work before: the earlier workloads need not
            # have compiled every kernel of it (seen: taylor's 8-orbit section paid 6 s
            # in a "second process" the first time it ran).
            _say(f"W4 {runner} warm-up process ...")
            subprocess.run([sys.executable, "-m", "benchmarks.startup", runner],
                           env=dict(os.environ), capture_output=True, check=True, cwd=root)
        runs: dict[str, list[dict[str, float]]] = {runner: [] for runner in names}
        for k in range(rounds):
            for runner in names:
                env = dict(os.environ)
                with tempfile.TemporaryDirectory() as tmp:
                    if state == "cold":
                        # Cold: empty Numba cache and an empty heyoka on-disk JIT cache
                        # (heyoka keeps it under $XDG_CACHE_HOME/heyoka).
                        env.update(BENCH_COLD_CACHE=tmp,
                                   NUMBA_CACHE_DIR=os.path.join(tmp, "numba"),
                                   XDG_CACHE_HOME=os.path.join(tmp, "xdg"))
                    _say(f"W4 {runner} {state} process {k + 1}/{rounds} ...")
                    out = subprocess.run([sys.executable, "-m", "benchmarks.startup", runner],
                                         env=env, capture_output=True, text=True, check=True,
                                         cwd=root)
                runs[runner].append(json.loads(out.stdout.strip().splitlines()[-1]))
        for runner in names:
            r = {key: statistics.median(x[key] for x in runs[runner])
                 for key in ("import_s", "first_s", "second_s")}
            paid = statistics.median(x["first_s"] - x["second_s"] for x in runs[runner])
            rows.append(Row(
                "W4", f"fresh process, {state} on-disk caches: propagate 1 orbit to 1e4 "
                      "+ section 8 x 20", runner.replace("-", " "), r["first_s"], math.nan,
                [x["first_s"] for x in runs[runner]],
                note=f"medians of {rounds} processes: first call {r['first_s']:.2f} s, "
                     f"second {r['second_s']:.3f} s: compilation/cache load paid "
                     f"{paid:.2f} s",
                extra={**r, "compile_paid_s": paid, "caches": state, "rounds": runs[runner]}))
    return rows


# ----------------------------------------------------------------------------- W5


def w5(repeat: int) -> list[Row]:
    """The main job, ``andoyer paper``, in fresh processes: one to warm the on-disk
    caches, then ``repeat`` timed (each into a new folder)."""
    walls = []
    for k in range(repeat + 1):
        _say(f"W5 andoyer paper ({'warm-up' if k == 0 else f'run {k}'}) ...")
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            subprocess.run([sys.executable, "-m", "andoyer", "paper", "--out",
                            os.path.join(tmp, "paper")], check=True, capture_output=True)
            if k:
                walls.append(time.perf_counter() - t0)
    return [Row("W5", "andoyer paper in a fresh process, warm on-disk caches", HEYOKA,
                statistics.median(walls), math.nan, walls, note=f"{repeat} run(s)")]


# ----------------------------------------------------------------------------- W6


def w6(sizes: W.Sizes) -> list[Row]:
    """What a section costs over the bare flow (``benchmarks/section_cost.py``): the lane
    kernels on one thread, CPU time, the bare flow of W2's orbits over the span of the
    section runs and the G3 = 0, theta2 = 0 and g = 0 sections (upward) over it."""
    from benchmarks import section_cost

    n, N = sizes.cost
    _say(f"W6 section / bare flow ({n} orbits, {N} theta2 crossings' span) ...")
    r = section_cost.measure(n, N, sizes.repeat, scalar=False)
    case = (f"{n} orbits over the span of {N} theta2 = 0 crossings (T = {r['T']:.0f}), "
            f"lane kernels ({r['lanes']} lanes), one thread, CPU time")
    bare_label = "bare flow (lanes)"
    bare, bare_steps = r["cpu"][bare_label], r["steps"][bare_label]
    rows = []
    for label, cpu in r["cpu"].items():
        steps = r["steps"][label]
        per = cpu / steps
        rows.append(Row("W6", case, label, cpu, cpu, [cpu], note="wall = CPU, one thread",
                        extra={"steps": steps, "ns_per_step": per * 1e9,
                               "over_bare": cpu / bare,
                               # the machine limit: the section's steps at the bare step cost
                               "over_limit": cpu / (steps * bare / bare_steps),
                               "load": r["load"]}))
    return rows


# ----------------------------------------------------------------------------- W7

#: The lane kernels W7 compares, each in a fresh process: (runner, lane count, AVX2
#: target: compiled for a Haswell without AVX-512, ``lane_width.avx2_environment``); the
#: last is the reference of the differences.
WIDTHS: tuple[tuple[str, int, bool], ...] = (
    ("4 lanes", 4, False), ("4 lanes, AVX2 target (haswell)", 4, True), ("8 lanes", 8, False))


def w7(sizes: W.Sizes) -> list[Row]:
    """The lane kernels at 4 and at 8 lanes, and at 4 compiled for an AVX2 CPU
    (:data:`WIDTHS`; ``benchmarks/lane_width.py``, a fresh process each with
    ``ANDOYER_LANES`` set, one thread): ns per orbit-step of the bare lane flow and of a
    G3 = 0 section, and the largest difference of their results from 8 lanes' (end states
    of the flow, crossing times; relative to 1 + |x|)."""
    from benchmarks import lane_width

    n, N, t_end = sizes.lanes
    res = {}
    for runner, width, avx2 in WIDTHS:
        _say(f"W7 {runner} (fresh process) ...")
        res[runner] = lane_width.run(width, n, N, t_end, sizes.repeat,
                                     env=lane_width.avx2_environment() if avx2 else None)
    case = (f"lane kernels, {n} orbits to t = {t_end:g} (flow; G3 = 0 up to {N} crossings), "
            "one thread, CPU time")
    ref = res[WIDTHS[-1][0]]
    rows = []
    for runner, r in res.items():
        diff = {}
        for key in ("flow_end", "crossing_t"):
            a, b = np.asarray(r[key]), np.asarray(ref[key])
            diff[key] = float(np.max(np.abs(a - b) / (1.0 + np.abs(b))))
        cpu = r["cpu_s"]["flow"] + r["cpu_s"]["G3"]
        rows.append(Row("W7", case, runner, cpu, cpu, [cpu],
                        note=f"tuning: {r['tuning'] or 'the target CPU'}",
                        extra={"lanes": r["lanes"], "ns_per_orbit_step": r["ns_per_orbit_step"],
                               "steps": r["steps"], "steps_equal": r["steps"] == ref["steps"],
                               "diff_from_8": diff, "load": r["load"]}))
    return rows


# ----------------------------------------------------------------------------- output


def meta(mode: str, args: dict[str, Any]) -> dict[str, Any]:
    import heyoka
    import numba
    import scipy

    import andoyer

    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, cwd=Path(__file__).parent).stdout.strip()
    except OSError:
        commit = ""
    return {"date": datetime.now(UTC).isoformat(timespec="seconds"), "mode": mode,
            "args": args, "python": platform.python_version(), "machine": platform.machine(),
            "cpus": os.cpu_count(), "numpy": np.__version__, "scipy": scipy.__version__,
            "heyoka": heyoka.__version__, "numba": numba.__version__,
            "andoyer": andoyer.__version__, "commit": commit,
            "simd_size": int(heyoka.recommended_simd_size())}


#: W2 theta2 = 0 on the default engine (heyoka) when issue 26 was filed (full run of
#: 2026-11-25, commit 0791664): its target is half of it.
THETA2_BEFORE_S = 0.4324

#: W2 theta2 = 0 on the fastest engine before issue 36: andoyer numba, 481.5 ms, in the
#: full run of 2026-11-27 (commit 41dea64; benchmarks/RESULTS.md of commit 69a1e7c): its
#: target is a third of it.
THETA2_BEFORE_36_S = 0.4815


def targets(rows: list[Row]) -> list[dict[str, Any]]:
    """The issue's targets, each with the measured ratio and whether it is met."""
    def get(wl: str, case_start: str, runner: str) -> Row | None:
        for r in rows:
            if r.workload == wl and r.case.find(case_start) >= 0 and r.runner == runner:
                return r
        return None

    out: list[dict[str, Any]] = []

    def default(wl: str, case_start: str) -> Row | None:
        for r in rows:
            if r.workload == wl and r.case.find(case_start) >= 0 and \
                    r.runner == default_runner(wl, r.case):
                return r
        return None

    def ratio(what: str, a: Row | None, b: Row | None, limit: float, faster: bool) -> None:
        if a is None or b is None or not (a.wall_s > 0 and b.wall_s > 0):
            return
        value = a.wall_s / b.wall_s if not faster else b.wall_s / a.wall_s
        ok = value <= limit if not faster else value >= limit
        out.append({"target": what, "value": value, "limit": limit, "met": bool(ok)})

    for sec, _ in W.SECTIONS:
        d = default("W2", f"of {sec} ")
        ratio(f"W2 {sec}: andoyer default / hand-tuned heyoka <= 1.0", d,
              get("W2", f"of {sec} ", "heyoka hand-tuned"), 1.0, False)
        ratio(f"W2 {sec}: plain heyoka loop / andoyer default >= 3", d,
              get("W2", f"of {sec} ", "heyoka plain"), 3.0, True)
        ratio(f"W2 {sec}: scipy DOP853 serial / andoyer default >= 100", d,
              get("W2", f"of {sec} ", "scipy DOP853 serial"), 100.0, True)
        ratio(f"W2 {sec}: andoyer numba / hand-tuned heyoka <= 3", get("W2", f"of {sec} ",
              "andoyer numba"), get("W2", f"of {sec} ", "heyoka hand-tuned"), 3.0, False)
        h = get("W2", f"of {sec} ", "heyoka hand-tuned")
        if d is not None and h is not None:
            # 1.5x: the errors of a 1000-crossing run at tol 1e-12 vary that much between
            # correct integrators (theta2, max: plain 2.0e-11, hand-tuned 1.5e-11, numba
            # 4.3e-11; their step sequences differ).
            out.append({"target": f"W2 {sec}: error at the last crossing within 1.5x of "
                                  "hand-tuned heyoka (median, max)",
                        "value": [d.error_median, d.error_max],
                        "limit": [h.error_median, h.error_max],
                        "met": bool(d.error_median <= h.error_median * 1.5
                                    and d.error_max <= max(h.error_max * 1.5, 1e-6))})
        # the engines on the default's case (W2 G3 has a smaller case beside it)
        fastest = min((r for r in rows if r.workload == "W2" and f"of {sec} " in r.case
                       and (d is None or r.case == d.case)
                       and r.runner.startswith("andoyer")), key=lambda r: r.wall_s,
                      default=None)
        ratio(f"W2 {sec}: andoyer default / fastest andoyer engine <= 1.1", d, fastest, 1.1,
              False)
    ratio("W1: andoyer default / plain heyoka <= 1.2", default("W1", ""),
          get("W1", "", "heyoka plain"), 1.2, False)
    # Issue 26: the Taylor engine in Numba against heyoka's.
    ratio("W1: andoyer taylor / andoyer heyoka <= 1.2", get("W1", "", "andoyer taylor"),
          get("W1", "", HEYOKA), 1.2, False)
    for sec, _ in W.SECTIONS:
        ratio(f"W2 {sec}: andoyer taylor / andoyer heyoka <= 1.2",
              get("W2", f"of {sec} ", "andoyer taylor"), get("W2", f"of {sec} ", HEYOKA),
              1.2, False)
    # Issue 26, the rest of its targets table.
    ratio("W3 FLI map: andoyer taylor / andoyer heyoka <= 1.2",
          get("W3", "FLI map", "andoyer taylor"), get("W3", "FLI map", HEYOKA), 1.2, False)
    theta2 = default("W2", "of theta2 ")
    if theta2 is not None:
        fastest = min((r for r in rows if r.workload == "W2" and r.case == theta2.case
                       and r.runner.startswith("andoyer")), key=lambda r: r.wall_s)
        out.append({"target": "W2 theta2: fastest andoyer engine <= 0.5 x the default's "
                              f"{THETA2_BEFORE_S * 1e3:.0f} ms before issue 26 "
                              f"({fastest.runner})",
                    "value": fastest.wall_s / THETA2_BEFORE_S, "limit": 0.5,
                    "met": bool(fastest.wall_s <= 0.5 * THETA2_BEFORE_S)})
    for r in rows:
        if r.workload == "W2" and r.runner.startswith("andoyer") and "limit" in r.extra:
            x = r.wall_s / r.extra["limit"]["limit_s"]
            out.append({"target": f"W2 {r.case.split('of ')[-1].split(' ')[0]}: {r.runner} "
                                  "within 2x its machine limit", "value": x, "limit": 2.0,
                        "met": bool(x <= 2.0)})
    for wl, case in dict.fromkeys((r.workload, r.case) for r in rows
                                  if r.workload in ("W1", "W2", "W3")):
        t, d = get(wl, case, "andoyer taylor"), get(wl, case, HEYOKA)
        if t is None or d is None or not (t.error_max >= 0 and d.error_max >= 0):
            continue
        # 1.5x, as for the hand-tuned peer: correct integrators' errors over long runs
        # at tol 1e-12 vary that much with their step sequences.
        out.append({"target": f"{wl} {case}: taylor's error within 1.5x of heyoka's "
                              "(median, max)", "value": [t.error_median, t.error_max],
                    "limit": [d.error_median, d.error_max],
                    "met": bool(t.error_median <= 1.5 * d.error_median
                                and t.error_max <= 1.5 * d.error_max)})
    big = {r.runner: r for r in rows if r.workload == "W3" and r.note == "timed once"}
    peer = big.get("heyoka hand-tuned")
    for runner, r in big.items():
        if runner.startswith("andoyer"):
            ratio(f"W3 {r.case}: {runner} / hand-written heyoka ensemble <= 1", r, peer, 1.0,
                  False)
    paper = get("W5", "", HEYOKA)
    if paper is not None:
        out.append({"target": "W5: andoyer paper, warm caches, <= 20 s", "value": paper.wall_s,
                    "limit": 20.0, "met": bool(paper.wall_s <= 20.0)})
    for r in rows:
        if r.workload == "W4" and r.extra.get("caches") == "cold" and \
                r.runner.startswith("andoyer"):
            first = r.extra["first_s"]
            out.append({"target": f"W4: {r.runner}, cold first call <= 5 s", "value": first,
                        "limit": 5.0, "met": bool(first <= 5.0)})
        if r.workload == "W4" and r.extra.get("caches") == "warm" and \
                r.runner.startswith("andoyer"):
            paid = r.extra["compile_paid_s"]
            out.append({"target": f"W4: {r.runner}, second process pays <= 0.5 s of "
                                  "compilation", "value": paid, "limit": 0.5,
                        "met": bool(paid <= 0.5)})
            first = r.extra["first_s"]
            out.append({"target": f"W4: {r.runner}, a second process's first call <= 0.3 s "
                                  "(issue 36)", "value": first, "limit": 0.3,
                        "met": bool(first <= 0.3)})
    out += targets_36(rows)
    return out


def targets_36(rows: list[Row]) -> list[dict[str, Any]]:
    """Issue 36's targets that the rows above do not already check (W1 <= 1.2 x plain
    heyoka and every W2 section within 2x its machine limit are in :func:`targets`)."""
    out: list[dict[str, Any]] = []

    def add(what: str, value: float, limit: float, met: bool) -> None:
        out.append({"target": what, "value": value, "limit": limit, "met": bool(met)})

    def by(wl: str, case: str, runner: str) -> Row | None:
        return next((r for r in rows if (r.workload, r.case, r.runner) == (wl, case, runner)
                     and r.wall_s > 0), None)

    # section / bare flow <= 1.5 (W6), the g = 0 section within 2x its machine limit
    for r in rows:
        if r.workload == "W6" and r.runner.endswith(" lanes"):
            sec = r.runner.removesuffix(" lanes")
            add(f"W6 {sec}: section on lanes / bare lane flow <= 1.5", r.extra["over_bare"],
                1.5, r.extra["over_bare"] <= 1.5)
            if sec.startswith("g "):
                add(f"W6 {sec}: section on lanes within 2x its machine limit",
                    r.extra["over_limit"], 2.0, r.extra["over_limit"] <= 2.0)
    # theta2 at least 3x faster than the fastest engine before issue 36
    first = next((r for r in rows if r.workload == "W2" and "of theta2 " in r.case), None)
    theta2 = [r for r in rows if first is not None and r.workload == "W2"
              and r.case == first.case and r.runner.startswith("andoyer") and r.wall_s > 0]
    if theta2:
        fastest = min(theta2, key=lambda r: r.wall_s)
        add(f"W2 theta2: fastest andoyer engine ({fastest.runner}) <= 1/3 x the "
            f"{THETA2_BEFORE_36_S * 1e3:.1f} ms of numba before issue 36",
            fastest.wall_s / THETA2_BEFORE_36_S, round(1 / 3, 3),
            3 * fastest.wall_s <= THETA2_BEFORE_36_S)
    # W2 G3 on taylor <= 1.0 x heyoka, at every size measured
    for case in dict.fromkeys(r.case for r in rows if r.workload == "W2" and "of G3 " in r.case):
        t, h = by("W2", case, "andoyer taylor"), by("W2", case, HEYOKA)
        if t is not None and h is not None:
            x = t.wall_s / h.wall_s
            add(f"W2 G3 {case.split(' crossings')[0]}: andoyer taylor / andoyer heyoka "
                "<= 1.0", x, 1.0, x <= 1.0)
    # the MEGNO map and the 256^2 FLI map on their default engines
    for case in dict.fromkeys(r.case for r in rows if r.workload == "W3"):
        key = workload_key("W3", case)
        engine = default_engines(key)[0] if key is not None else "heyoka"
        d = by("W3", case, f"andoyer {engine}")
        if case.startswith("MEGNO map"):
            h = by("W3", case, HEYOKA)
            if d is not None and h is not None:
                x = d.wall_s / h.wall_s
                add(f"W3 {case}: default (andoyer {engine}) / andoyer heyoka <= 1.0", x, 1.0,
                    x <= 1.0)
        elif d is not None and d.note == "timed once":
            h = by("W3", case, "heyoka hand-tuned")
            if h is not None:
                x = d.wall_s / h.wall_s
                add(f"W3 {case}: default (andoyer {engine}) / hand-written heyoka ensemble "
                    "<= 0.7", x, 0.7, x <= 0.7)
    # lane widths: per-lane cost within 10 %, results equal to round-off
    w7 = [r for r in rows if r.workload == "W7"]
    eight = next((r for r in w7 if r.extra["lanes"] == 8), None)
    if eight is not None and len(w7) > 1:
        for r in w7:
            if r is eight:
                continue
            for kernel in ("flow", "G3"):
                x = (r.extra["ns_per_orbit_step"][kernel]
                     / eight.extra["ns_per_orbit_step"][kernel])
                add(f"W7 {kernel}: ns per orbit-step, {r.runner} / {eight.runner} within 10 % "
                    "(max(x, 1/x))", max(x, 1 / x), 1.1, max(x, 1 / x) <= 1.1)
        diff = [max(r.extra["diff_from_8"].values()) for r in w7]
        add("W7: results equal to round-off across the lane kernels (steps equal, largest "
            "relative difference of end states and crossing times from 8 lanes')", max(diff),
            1e-11, all(r.extra["steps_equal"] for r in w7) and max(diff) < 1e-11)
    paper = next((r for r in rows if r.workload == "W5" and r.runner == HEYOKA), None)
    if paper is not None:
        add("W5: andoyer paper, warm caches, <= 15 s (issue 36)", paper.wall_s, 15.0,
            paper.wall_s <= 15.0)
    return out


def _fmt(x: float, unit: str = "") -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "–"
    if unit == "s":
        return f"{x * 1e3:.1f} ms" if x < 1 else f"{x:.2f} s"
    return f"{x:.1e}"


def markdown(result: dict[str, Any]) -> str:
    m = result["meta"]
    rows = [Row(**r) for r in result["rows"]]
    lines = [
        "# Benchmarks: andoyer side by side with plain heyoka, hand-tuned heyoka and scipy",
        "",
        f"{m['date']}, mode **{m['mode']}**, {m['cpus']} CPUs ({m['machine']}), "
        f"load average before/after {result['load_before']} / {result['load_after']}; "
        f"Python {m['python']}, numpy {m['numpy']}, scipy {m['scipy']}, heyoka {m['heyoka']}, "
        f"numba {m['numba']}, andoyer {m['andoyer']} ({m['commit']}).",
        "",
        "Paper's Hess body (A, B, C) = (2.5, 2.0, 2.2), mu = 0.01; initial states with M = 0,"
        " |G| ~ 1 on the level of (l, g, L, G, M) = (0.3, 0, 0.3, 1, 0). Tolerance 1e-12 "
        "everywhere (rtol = atol). Wall time: median of the timed runs after one warm-up "
        "run (W1's runners but scipy's in rounds, each once in turn); CPU: all threads. "
        "Errors against an extended-precision heyoka reference "
        "(long double, tol 1e-19). **x heyoka** = this runner's time / andoyer on the "
        "heyoka engine (the default of each workload, heyoka where installed but for those "
        "of `andoyer.integrate.engines.MEASURED_DEFAULTS`, is the table \"Which engine for "
        "what\" in `SUMMARY.md`).",
        ""]
    for wl in ("W1", "W2", "W3", "W4", "W5"):
        sub = [r for r in rows if r.workload == wl]
        for case in dict.fromkeys(r.case for r in sub):
            cs = [r for r in sub if r.case == case]
            base = next((r.wall_s for r in cs if r.runner == HEYOKA), math.nan)
            lines += [f"## {wl}: {case}", ""]
            if wl == "W4":
                lines += ["| runner | imports | first call | second call | compilation paid |",
                          "|---|---|---|---|---|"]
                for r in cs:
                    lines.append(f"| {r.runner} | {_fmt(r.extra.get('import_s', math.nan), 's')}"
                                 f" | {_fmt(r.extra.get('first_s', math.nan), 's')}"
                                 f" | {_fmt(r.extra.get('second_s', math.nan), 's')} | "
                                 f"{_fmt(r.extra.get('compile_paid_s', math.nan), 's')} |")
                lines.append("")
                continue
            lines += ["| runner | wall | CPU | x heyoka | error median | error max | note |",
                      "|---|---|---|---|---|---|---|"]
            for r in cs:
                ratio = r.wall_s / base if base > 0 and math.isfinite(r.wall_s) else math.nan
                lines.append(f"| {r.runner} | {_fmt(r.wall_s, 's')} | {_fmt(r.cpu_s, 's')} | "
                             f"{'–' if not math.isfinite(ratio) else f'{ratio:.2f}'} | "
                             f"{_fmt(r.error_median)} | {_fmt(r.error_max)} | {r.note} |")
            what = next((r.error_what for r in cs if r.error_what), "")
            lines += ["", f"Error: {what}." if what else "", ""]
    lines += cost_tables(rows)
    lim = [r for r in rows if "limit" in r.extra]
    if lim:
        lines += ["## Machine limits", "",
                  "The limit of the method on this machine (`benchmarks/limits.py`): the "
                  "integration steps of the workload, counted by the engine's own step "
                  "counter, times the cost of one step with every SIMD lane and core busy "
                  "(the bare integrator: no events, no output, no Python). **x limit** = "
                  "andoyer's time / the limit.", "",
                  "| workload | runner | andoyer | steps | cost per step | limit | x limit "
                  "| how the step was costed |", "|---|---|---|---|---|---|---|---|"]
        for r in lim:
            d = r.extra["limit"]
            lines.append(f"| {r.workload}: {r.case} | {r.runner} | {_fmt(r.wall_s, 's')} | "
                         f"{d['steps']:,} | {d['step_s'] * 1e9:.0f} ns | "
                         f"{_fmt(d['limit_s'], 's')} | {r.wall_s / d['limit_s']:.2f} | "
                         f"{d['note']} |")
        load = [r for r in rows if "dataset_load_s" in r.extra]
        if load:
            lines += ["", f"W1 dataset: reading every derived variable of the propagate "
                      f"dataset (charts, integrals, drifts; computed lazily at first read) "
                      f"costs {_fmt(load[0].extra['dataset_load_s'], 's')} more."]
        lines.append("")
    if result.get("scaling"):
        lines += S.markdown(result["scaling"])
    lines += ["## Targets", ""]
    if m["mode"] == "quick":
        lines += ["Quick mode: the problems are smaller than the ones the targets are set "
                  "for (fixed costs weigh more); run the full benchmark to check them.", ""]
    lines += targets_table(result["targets"])
    lines += ["", "Reproduce: `python -m benchmarks` (full, about 35 minutes on 2 cores) or "
              "`python -m benchmarks --quick` (about 3 minutes); see `benchmarks/README.md`.", ""]
    return "\n".join(lines)


def cost_tables(rows: list[Row]) -> list[str]:
    """The tables of W6 (section / bare flow) and W7 (lane widths)."""
    lines: list[str] = []
    w6 = [r for r in rows if r.workload == "W6"]
    if w6:
        lines += [f"## W6: section / bare flow: {w6[0].case}", "",
                  "The section kernels on SIMD lanes against the bare lane flow of the same "
                  "orbits over the same span (`benchmarks/section_cost.py`), runs "
                  "interleaved, median CPU time; **x limit** = the section's time / its "
                  "steps at the bare flow's cost per step. Load "
                  f"{w6[0].extra['load'][0][0]:.2f} -> {w6[0].extra['load'][1][0]:.2f}.", "",
                  "| run | CPU | steps | ns per orbit-step | / bare flow | x limit |",
                  "|---|---|---|---|---|---|"]
        for r in w6:
            e = r.extra
            lines.append(f"| {r.runner} | {_fmt(r.cpu_s, 's')} | {e['steps']:,} | "
                         f"{e['ns_per_step']:.0f} | {e['over_bare']:.2f} | "
                         f"{e['over_limit']:.2f} |")
        lines.append("")
    w7 = [r for r in rows if r.workload == "W7"]
    if w7:
        lines += [f"## W7: lane widths: {w7[0].case}", "",
                  "Each lane count in a fresh process (`ANDOYER_LANES`, "
                  "`benchmarks/lane_width.py`; the AVX2 row compiled for a Haswell CPU "
                  "without AVX-512, `NUMBA_CPU_NAME` and `NUMBA_CPU_FEATURES`), median CPU "
                  "time; differences relative to "
                  "1 + |x|, from 8 lanes' results.", "",
                  "| lane kernels | flow ns per orbit-step | G3 section ns per orbit-step | "
                  "steps equal | flow end states differ by | crossing times differ by | "
                  "load | note |", "|---|---|---|---|---|---|---|---|"]
        for r in w7:
            e = r.extra
            lines.append(f"| {r.runner} | {e['ns_per_orbit_step']['flow']:.0f} | "
                         f"{e['ns_per_orbit_step']['G3']:.0f} | {e['steps_equal']} | "
                         f"{_fmt(e['diff_from_8']['flow_end'])} | "
                         f"{_fmt(e['diff_from_8']['crossing_t'])} | "
                         f"{e['load'][0]:.2f} -> {e['load'][1]:.2f} | {r.note} |")
        lines.append("")
    return lines


def targets_table(rows: list[dict[str, Any]]) -> list[str]:
    """The targets as a markdown table: target, measured, limit, met."""
    lines = ["| target | measured | limit | met |", "|---|---|---|---|"]
    for t in rows:
        v, lim = t["value"], t["limit"]
        vs = ", ".join(f"{x:.2g}" for x in v) if isinstance(v, list) else f"{v:.2f}"
        ls = ", ".join(f"{x:.2g}" for x in lim) if isinstance(lim, list) else f"{lim:g}"
        lines.append(f"| {t['target']} | {vs} | {ls} | {'yes' if t['met'] else '**no**'} |")
    return lines


#: Markers of the block of README.md that :func:`summary` rewrites after a full run.
README_START, README_END = "<!-- benchmarks:start -->", "<!-- benchmarks:end -->"


def summary(result: dict[str, Any]) -> str:
    """The short table (README, user guide): one row per workload, medians, x limit."""
    m = result["meta"]
    rows = [Row(**r) for r in result["rows"]]
    cols = [("andoyer heyoka", (HEYOKA,)), ("andoyer numba", ("andoyer numba",)),
            ("andoyer taylor", ("andoyer taylor",)),
            ("heyoka plain", ("heyoka plain",)), ("heyoka hand-tuned", ("heyoka hand-tuned",)),
            ("scipy DOP853", ("scipy DOP853", "scipy DOP853 pool(2)"))]
    lines = [f"Measured {m['date'][:10]} by `python -m benchmarks` ({m['mode']} run, "
             f"{m['cpus']} cores, commit {m['commit']}); every number, with CPU times, "
             "errors and start-up, in `benchmarks/RESULTS.md`.", "",
             "| workload | " + " | ".join(c for c, _ in cols) + " | default / machine limit |",
             "|---|" + "---|" * (len(cols) + 1)]
    cases = dict.fromkeys((r.workload, r.case) for r in rows if r.workload in ("W1", "W2", "W3"))
    for wl, case in cases:
        cs = {r.runner: r for r in rows if (r.workload, r.case) == (wl, case)}
        cells = []
        for _, names in cols:
            r = next((cs[n] for n in names if n in cs), None)
            cells.append("–" if r is None else _fmt(r.wall_s, "s") + (
                " (extrapolated)" if "extrapolated" in r.note else ""))
        d = cs.get(default_runner(wl, case))
        lim = "–" if d is None or "limit" not in d.extra else \
            f"{d.wall_s / d.extra['limit']['limit_s']:.1f}x"
        lines.append(f"| {wl}: {case} | " + " | ".join(cells) + f" | {lim} |")
    paper = next((r for r in rows if r.workload == "W5"), None)
    if paper is not None:
        lines += ["", f"`andoyer paper` (the main job), fresh process, warm caches: "
                      f"{_fmt(paper.wall_s, 's')}."]
    lines += engine_advice(rows)
    if result.get("targets"):
        met = sum(bool(t["met"]) for t in result["targets"])
        lines += ["", f"**Targets**: {met} of {len(result['targets'])} met (the misses are "
                      "profiled in the user guide, \"Where the targets are missed\"):", ""]
        lines += targets_table(result["targets"])
    return "\n".join(lines) + "\n"


#: The benchmark workloads as :data:`andoyer.integrate.engines.WORKLOADS` names them.
def workload_key(workload: str, case: str) -> str | None:
    """The :data:`~andoyer.integrate.engines.WORKLOADS` name of a benchmark row (W1 the
    orbit, W2 a section of a state component or of an angle, W3 the FLI or the MEGNO
    map)."""
    if workload == "W1":
        return "orbit"
    if workload == "W2":
        return "angle_section" if "theta" in case or " g = " in case else "component_section"
    if workload == "W3":
        return "megno_map" if case.startswith("MEGNO map") else "fli_map"
    return None


def default_engines(key: str) -> tuple[str, str]:
    """The engine ``engine=None`` runs for workload ``key``: where heyoka is installed
    (:data:`~andoyer.integrate.engines.MEASURED_DEFAULTS`, else heyoka) and without it
    (the first of :data:`~andoyer.integrate.engines.FALLBACK_DEFAULTS` with the capability
    the workload needs), read from the library, not from the measurements."""
    from andoyer.integrate.engines import (
        FALLBACK_DEFAULTS,
        MEASURED_DEFAULTS,
        Capability,
        engine_class,
    )

    need = {"orbit": Capability.PROPAGATE, "fli_map": Capability.TANGENT,
            "megno_map": Capability.TANGENT}.get(key, Capability.CROSSINGS)
    without = next((n for n in FALLBACK_DEFAULTS if need in engine_class(n).capabilities),
                   FALLBACK_DEFAULTS[-1])
    return MEASURED_DEFAULTS.get(key, "heyoka"), without


def default_runner(workload: str, case: str) -> str:
    """The runner of the engine ``engine=None`` runs, where heyoka is installed, for a
    benchmark row (:func:`default_engines`; ``"andoyer heyoka"`` outside W1-W3)."""
    key = workload_key(workload, case)
    return f"andoyer {default_engines(key)[0]}" if key is not None else HEYOKA


#: The header of the generated table (a test of the docs finds the table by it).
ADVICE_HEADER = ("| workload | default with heyoka | fastest with heyoka | "
                 "default without heyoka | fastest without heyoka |")


def engine_advice(rows: list[Row]) -> list[str]:
    """**Which engine for what**: per workload, the engine ``engine=None`` runs (from
    :data:`andoyer.integrate.engines.MEASURED_DEFAULTS`) beside the fastest of andoyer's
    engines in the measurements (wall time), with heyoka installed and without it."""
    engines = {"andoyer heyoka": "heyoka", "andoyer taylor": "taylor",
               "andoyer numba": "numba", "andoyer scipy": "scipy"}
    out = ["", "**Which engine for what**: the default is what `engine=None` runs "
           "(`andoyer.integrate.engines.MEASURED_DEFAULTS`, set from these measurements: "
           "where heyoka is installed a workload's default moves off heyoka only when "
           "another engine is faster by more than 10 %); the fastest is the fastest of "
           "andoyer's engines by wall time in the rows above, with the next one's time "
           "over it:", "", ADVICE_HEADER, "|---|---|---|---|---|"]
    cases = dict.fromkeys((r.workload, r.case) for r in rows if r.workload in ("W1", "W2", "W3")
                          and r.note != "timed once")

    def pick(cands: list[Row]) -> str:
        cands = sorted((r for r in cands if math.isfinite(r.wall_s)
                        and "extrapolated" not in r.note), key=lambda r: r.wall_s)
        if not cands:
            return "–"
        best = engines[cands[0].runner]
        if len(cands) == 1:
            return f"{best} (only one measured)"
        return (f"{best} ({engines[cands[1].runner]} takes "
                f"{cands[1].wall_s / cands[0].wall_s:.2f}x)")

    for wl, case in cases:
        mine = [r for r in rows if (r.workload, r.case) == (wl, case) and r.runner in engines]
        key = workload_key(wl, case)
        if not mine or key is None:
            continue
        with_heyoka, without = default_engines(key)
        out.append(f"| {wl}: {case} | {with_heyoka} | {pick(mine)} | {without} | "
                   f"{pick([r for r in mine if r.runner != 'andoyer heyoka'])} |")
    return out if len(out) > 5 else []


def update_readme(text: str, path: Path) -> bool:
    """Put ``text`` between the benchmark markers of ``path`` (atomically); False when
    the file has no markers."""
    if not path.exists():
        return False
    old = path.read_text()
    i, j = old.find(README_START), old.find(README_END)
    if i < 0 or j < i:
        return False
    tmp = path.with_suffix(path.suffix + ".tmp")
    tmp.write_text(old[:i + len(README_START)] + "\n" + text + old[j:])
    tmp.replace(path)
    return True


def regenerate(out_dir: Path | None = None) -> dict[str, Any]:
    """Rewrite ``RESULTS.md``, ``SUMMARY.md`` (and the README's block, for the full run in
    ``benchmarks/``) from ``results.json`` without running anything: for a change of the
    tables' text or of the defaults they state."""
    out_dir = Path(__file__).parent if out_dir is None else Path(out_dir)
    result = json.loads((out_dir / "results.json").read_text())
    # the targets again from the rows: the defaults they compare may have moved
    result["targets"] = targets([Row(**r) for r in result["rows"]])
    tmp = out_dir / "results.json.tmp"
    tmp.write_text(json.dumps(result, indent=1, default=float))
    tmp.replace(out_dir / "results.json")
    write_tables(result, out_dir)
    return result


def write_tables(result: dict[str, Any], out_dir: Path) -> None:
    """``RESULTS.md`` and ``SUMMARY.md`` of ``result`` into ``out_dir``; the README's block
    too after a full run of W1-W3 into ``benchmarks/``."""
    for name, text in (("RESULTS.md", markdown(result)), ("SUMMARY.md", summary(result))):
        tmp = out_dir / (name + ".tmp")
        tmp.write_text(text)
        tmp.replace(out_dir / name)
    workloads = set(result["meta"].get("args", {}).get("workloads", ()))
    if result["meta"]["mode"] == "full" and out_dir == Path(__file__).parent and \
            workloads >= {"W1", "W2", "W3"}:
        update_readme(summary(result), out_dir.parent / "README.md")


def run(quick: bool = False,
        workloads: tuple[str, ...] = ("W1", "W2", "W3", "W4", "W5", "W6", "W7", "S"),
        runners: set[str] | None = None, full_scipy: bool = False, cold: bool | None = None,
        out_dir: Path | None = None, sizes: W.Sizes | None = None,
        sections: tuple[tuple[str, float], ...] = W.SECTIONS) -> dict[str, Any]:
    """Run the workloads; write ``results.json`` and ``RESULTS.md`` into ``out_dir``.

    ``sizes`` and ``sections`` override the full/quick problem sizes and W2's sections
    (the harness's own tests run it on a tiny problem).
    """
    sizes = sizes if sizes is not None else (W.QUICK if quick else W.FULL)
    everyone = {"andoyer heyoka", "andoyer numba", "andoyer taylor", "andoyer scipy",
                "heyoka plain",
                "heyoka ensemble", "heyoka hand-tuned", "scipy DOP853",
                "scipy DOP853 serial", "scipy DOP853 pool(2)"}
    runners = everyone if runners is None else runners
    cold = (not quick) if cold is None else cold
    load_before = [round(x, 2) for x in os.getloadavg()]
    rows: list[Row] = []
    if "W1" in workloads:
        rows += w1(sizes, runners)
    if "W2" in workloads:
        rows += w2(sizes, runners, full_scipy, sections, quick)
        rows += w2_small(sizes, runners)
    if "W3" in workloads:
        rows += w3(sizes, runners)
        rows += w3_megno(sizes, runners)
    if "W4" in workloads:
        rows += w4(cold, {r.replace("-", " ") for r in runners}, rounds=1 if quick else 3)
    if "W5" in workloads and HEYOKA in runners:
        rows += w5(1 if quick else 3)
    if "W6" in workloads:
        rows += w6(sizes)
    if "W7" in workloads:
        rows += w7(sizes)
    scaling = S.run(quick, say=_say) if "S" in workloads else []
    result = {"meta": meta("quick" if quick else "full",
                           {"workloads": list(workloads), "full_scipy": full_scipy,
                            "cold": cold, "sizes": asdict(sizes)}),
              "load_before": load_before,
              "load_after": [round(x, 2) for x in os.getloadavg()],
              "rows": [asdict(r) for r in rows], "targets": targets(rows),
              "scaling": scaling}
    out_dir = Path(__file__).parent if out_dir is None else Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    if scaling:
        S.plot(scaling, out_dir / "scaling.png")
    tmp = out_dir / "results.json.tmp"
    tmp.write_text(json.dumps(result, indent=1, default=float))
    tmp.replace(out_dir / "results.json")
    write_tables(result, out_dir)
    return result
