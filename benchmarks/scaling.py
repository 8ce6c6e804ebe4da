"""How cost grows: time and peak memory vs orbits, crossings, map resolution and cores.

Each point runs in a fresh process (``python -m benchmarks.scaling --point JSON``) pinned
to ``cores`` CPUs (``os.sched_setaffinity``; Numba's threads set to match), after one
tiny warm-up call of the same function (compiled code loaded from the on-disk caches).
Memory is the growth of the resident set over the warm process, its peak sampled every
2 ms while the work runs, beside the size of the dataset returned.

Series (the paper's body and W2's initial states, tolerance 1e-12):

* ``orbits``: 10 ... 10^4 orbits x 100 upward crossings of theta2 = 0 (``poincare``);
* ``crossings``: 50 orbits x 10 ... 10^4 crossings of theta2 = 0;
* ``map``: FLI maps 32^2 ... 256^2 of the theta2 = 0 plane to t = 250 (``chaos_map``);

each for the heyoka and numba engines on 1 and 2 cores.
"""

from __future__ import annotations

import argparse
import gc
import json
import os
import resource
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

SERIES: dict[str, tuple[int, ...]] = {
    "orbits": (10, 100, 1000, 10000),
    "crossings": (10, 100, 1000, 10000),
    "map": (32, 64, 128, 256),
}
QUICK: dict[str, tuple[int, ...]] = {"orbits": (10, 40), "crossings": (10, 40), "map": (8, 16)}
ENGINES = ("heyoka", "numba")
MAP_T_END = 250.0
#: Fixed sizes of the other dimension of each series.
CROSSINGS_PER_ORBIT, ORBITS = 100, 50


def _call(series: str, engine: str, size: int) -> Any:
    """The workload of one point: a function returning the dataset."""
    from andoyer.analysis.chaos.lyapunov import IndicatorRun, chaos_map
    from andoyer.integrate import Section, poincare
    from benchmarks import workloads as W

    b = W.body()
    if series == "map":
        h = W.energy_level(b)
        return lambda: chaos_map(b, h, 0.0, ("theta2", 0.0), (size, size),
                                 IndicatorRun("fli", t_end=MAP_T_END), engine=engine,
                                 progress=False)
    n, N = (size, CROSSINGS_PER_ORBIT) if series == "orbits" else (ORBITS, size)
    y0 = W.initial_states(n)
    return lambda: poincare(b, y0, Section("theta2", 0.0, 1), N, engine=engine,
                            progress=False)


def _rss() -> int:
    """The resident set of this process now (bytes), from /proc."""
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize()


class _PeakSampler:
    """The largest resident set seen while the work runs, sampled every 2 ms (the
    process's ru_maxrss is a high-water mark that start-up may already have set)."""

    def __init__(self) -> None:
        self.peak = _rss()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        while not self._stop.wait(0.002):
            self.peak = max(self.peak, _rss())

    def __enter__(self) -> _PeakSampler:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()
        self.peak = max(self.peak, _rss())


def point(series: str, engine: str, size: int, cores: int) -> dict[str, Any]:
    """Run one point in this process (pinned to ``cores`` CPUs by the caller)."""
    warm = {"orbits": 2, "crossings": 2, "map": 4}[series]
    _call(series, engine, warm)()
    fn = _call(series, engine, size)
    gc.collect()
    rss0 = _rss()
    with _PeakSampler() as peak:
        c0, t0 = time.process_time(), time.perf_counter()
        ds = fn()
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    return {"series": series, "engine": engine, "size": size, "cores": cores,
            "wall_s": wall, "cpu_s": cpu, "peak_growth_mb": (peak.peak - rss0) / 2**20,
            "peak_mb": peak.peak / 2**20, "dataset_mb": ds.nbytes / 2**20}


def run(quick: bool = False, say: Any = print) -> list[dict[str, Any]]:
    """Every point of every series, each in its own pinned process."""
    sizes = QUICK if quick else SERIES
    ncpu = len(os.sched_getaffinity(0))
    out = []
    root = Path(__file__).resolve().parent.parent
    for series, values in sizes.items():
        for engine in ENGINES:
            for cores in sorted({1, min(2, ncpu)}):
                for size in values:
                    say(f"S {series} {engine} {cores} core(s) size {size} ...")
                    env = dict(os.environ, NUMBA_NUM_THREADS=str(cores))
                    arg = json.dumps({"series": series, "engine": engine, "size": size,
                                      "cores": cores})
                    res = subprocess.run([sys.executable, "-m", "benchmarks.scaling",
                                          "--point", arg], env=env, cwd=root, check=True,
                                         capture_output=True, text=True)
                    out.append(json.loads(res.stdout.strip().splitlines()[-1]))
    return out


def _label(series: str, size: int) -> str:
    return {"orbits": f"{size} orbits x {CROSSINGS_PER_ORBIT} crossings",
            "crossings": f"{ORBITS} orbits x {size} crossings",
            "map": f"FLI map {size}^2, t = {MAP_T_END:g}"}[series]


def markdown(points: list[dict[str, Any]]) -> list[str]:
    """The scaling table (wall time, CPU, peak memory growth, dataset size)."""
    lines = ["## Scaling: time and peak memory", "",
             "Each point in a fresh process pinned to the cores given (`benchmarks/scaling.py`)"
             "; memory: growth of the resident set over the warmed-up process (peak, sampled every "
             "2 ms), beside the "
             "size of the dataset returned (its chart coordinates are computed when read, so "
             "`dataset` counts the states only). Plot: `scaling.png`.", "",
             "| workload | engine | cores | wall | CPU | peak growth | dataset |",
             "|---|---|---|---|---|---|---|"]
    for p in points:
        lines.append(f"| {_label(p['series'], p['size'])} | {p['engine']} | {p['cores']} | "
                     f"{p['wall_s']:.3g} s | {p['cpu_s']:.3g} s | {p['peak_growth_mb']:.0f} MB"
                     f" | {p['dataset_mb']:.1f} MB |")
    return lines + [""]


def plot(points: list[dict[str, Any]], path: Path) -> None:
    """Time (top) and peak memory growth (bottom) vs size, per series, log-log."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(dict.fromkeys(p["series"] for p in points))
    fig, axes = plt.subplots(2, len(names), figsize=(4.2 * len(names), 6.4),
                             squeeze=False, layout="constrained")
    xlabel = {"orbits": f"orbits ({CROSSINGS_PER_ORBIT} crossings each)",
              "crossings": f"crossings per orbit ({ORBITS} orbits)",
              "map": f"map points (FLI, t = {MAP_T_END:g})"}
    for j, series in enumerate(names):
        for engine, color in zip(ENGINES, ("C0", "C1"), strict=True):
            for cores, style in ((1, "--"), (2, "-")):
                sel = [p for p in points if p["series"] == series and p["engine"] == engine
                       and p["cores"] == cores]
                if not sel:
                    continue
                x = [p["size"] ** 2 if series == "map" else p["size"] for p in sel]
                kw = dict(color=color, ls=style, marker="o", ms=3,
                          label=f"{engine}, {cores} core{'s' if cores > 1 else ''}")
                axes[0, j].loglog(x, [p["wall_s"] for p in sel], **kw)
                axes[1, j].loglog(x, [max(p["peak_growth_mb"], 0.1) for p in sel], **kw)
        ref = [p for p in points if p["series"] == series and p["engine"] == ENGINES[0]
               and p["cores"] == 1]
        if ref:
            axes[1, j].loglog([p["size"] ** 2 if series == "map" else p["size"] for p in ref],
                              [max(p["dataset_mb"], 0.1) for p in ref], color="0.5", ls=":",
                              label="size of the dataset returned")
        axes[0, j].set_title(series)
        axes[1, j].set_xlabel(xlabel[series])
    axes[0, 0].set_ylabel("wall time (s)")
    axes[1, 0].set_ylabel("peak memory growth (MB)")
    axes[0, 0].legend(fontsize=8)
    axes[1, 0].legend(fontsize=8)
    tmp = path.with_suffix(".tmp.png")
    fig.savefig(tmp, dpi=120)
    plt.close(fig)
    tmp.replace(path)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.scaling", description=__doc__)
    ap.add_argument("--point", help="run one point (JSON: series, engine, size, cores) "
                                    "and print its result as JSON")
    args = ap.parse_args(argv)
    if args.point:
        spec = json.loads(args.point)
        os.sched_setaffinity(0, set(sorted(os.sched_getaffinity(0))[:int(spec["cores"])]))
        print(json.dumps(point(spec["series"], spec["engine"], int(spec["size"]),
                               int(spec["cores"]))))
        return 0
    ap.error("use python -m benchmarks (workload S) for the whole table, or --point")
    return 2


if __name__ == "__main__":
    raise SystemExit(main())
