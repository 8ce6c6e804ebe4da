"""The size of a scan before it runs: points, tasks, CPU time and storage estimated from
each task's measured per-point cost (:data:`andoyer.scan.tasks.TASKS`), and the refusal
of a scan beyond the limits (``--max-core-hours``, ``--max-store-gb``)."""

from __future__ import annotations

import math
from typing import NamedTuple

from andoyer.scan.config import ScanConfig
from andoyer.scan.tasks import TASKS

__all__ = ["Cost", "estimate_cost", "check_size"]


class Cost(NamedTuple):
    """Estimated size of a scan.

    Parameters
    ----------
    points : int
        Grid points.
    tasks : int
        Dask tasks (chunks).
    core_seconds : float
        Estimated computing time, core seconds.
    store_bytes : float
        Estimated size of the store, bytes.
    """

    points: int
    tasks: int
    core_seconds: float
    store_bytes: float

    def describe(self) -> str:
        return (f"{self.points} points in {self.tasks} tasks: about "
                f"{_duration(self.core_seconds)} of CPU (one core) and "
                f"{_size(self.store_bytes)} stored (uncompressed)")


def _duration(s: float) -> str:
    if s < 120:
        return f"{s:.0f} s"
    if s < 7200:
        return f"{s / 60:.0f} min"
    return f"{s / 3600:.3g} core-hours"


def _size(b: float) -> str:
    for unit in ("B", "kB", "MB", "GB", "TB"):
        if b < 1000 or unit == "TB":
            return f"{b:.3g} {unit}"
        b /= 1000
    raise AssertionError  # pragma: no cover


def estimate_cost(cfg: ScanConfig) -> Cost:
    """Rough CPU time and storage of a scan (from measured per-crossing costs).

    Parameters
    ----------
    cfg : ScanConfig
        The validated configuration (:func:`load_config`).

    Returns
    -------
    Cost
        Points, tasks, core-seconds and bytes of the store.
    """
    seconds, values = TASKS[cfg.task].cost(dict(cfg.task_options))
    n = cfg.n_points
    return Cost(n, math.prod(cfg.block_shape), n * seconds, n * values * 8.0)


def check_size(cfg: ScanConfig, max_core_hours: float, max_store_gb: float) -> Cost:
    """Refuse a scan whose estimated cost exceeds the limits; return the estimate.

    Parameters
    ----------
    cfg : ScanConfig
        The configuration.
    max_core_hours : float
        Largest estimated computing time, core hours.
    max_store_gb : float
        Largest estimated store, GB.
    """
    cost = estimate_cost(cfg)
    over = []
    if cost.core_seconds > 3600.0 * max_core_hours:
        over.append(f"more than {max_core_hours:g} core-hours")
    if cost.store_bytes > 1e9 * max_store_gb:
        over.append(f"more than {max_store_gb:g} GB")
    if over:
        raise ValueError(
            f"the scan is unreasonably large: {' x '.join(map(str, cfg.shape))} grid, "
            f"{cost.describe()} -- {' and '.join(over)}. Sweep fewer values or reduce the "
            "task (orbits, crossings, n, t_end), or raise the limits if you mean it "
            "(--max-core-hours / --max-store-gb, or max_core_hours= / max_store_gb=)")
    return cost
