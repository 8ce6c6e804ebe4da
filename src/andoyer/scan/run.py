"""Running a scan on Dask: bounded submission, streaming into the store, resume.

One Dask task computes one chunk of the grid (:func:`run_chunk`) and
sends its result back; this process writes it into the chunk's region of the Zarr
store, then marks the chunk done (:mod:`andoyer.scan.store`). At most ``max_in_flight``
tasks are submitted at any time (default: twice the cluster's threads), so neither the
scheduler nor this process holds more than that many results, whatever the grid size.

A task that raises is retried (``retries``); a task whose worker dies is rescheduled
on another worker by the Dask scheduler. An interrupted scan restarted with the same
configuration and store computes only the chunks not marked done.
"""

from __future__ import annotations

import contextlib
import logging
import os
import time
import uuid
from collections.abc import Generator, Iterator, Sequence
from dataclasses import dataclass, field
from itertools import islice
from pathlib import Path
from typing import Any

import xarray as xr

from andoyer.outputs import OutputLock
from andoyer.processes import children_ignore_interrupts
from andoyer.progress import Progress
from andoyer.scan.config import ScanConfig, load_config
from andoyer.scan.cost import check_size
from andoyer.scan.store import (
    Schema,
    check_store,
    initialise,
    point_schema,
    prepare,
    store_schema,
    write_chunk,
)
from andoyer.scan.tasks import TASKS, Empty
from andoyer.validation import integer

__all__ = ["run_scan", "summary", "ScanReport", "DEFAULT_MAX_CORE_HOURS", "DEFAULT_MAX_STORE_GB",
           "ChunkResult", "run_point", "run_chunk"]

#: The only interface the servers of a local cluster listen on.
LOOPBACK = "127.0.0.1"

#: Limits of the size check (see :func:`andoyer.scan.cost.check_size`).
DEFAULT_MAX_CORE_HOURS = 100.0
DEFAULT_MAX_STORE_GB = 50.0


# ---------------------------------------------------------------------- running
@dataclass(frozen=True)
class ChunkResult:
    """What a worker sends back: one result per point of the chunk (C order).

    Attributes
    ----------
    block : tuple of int
        The chunk's index in the grid of chunks.
    points : list of xarray.Dataset or Empty
        One result per point of the chunk, in C order.
    seconds : float
        The time the worker took.
    """

    block: tuple[int, ...]
    points: list[xr.Dataset | Empty]
    seconds: float


def run_point(config: ScanConfig, index: tuple[int, ...]) -> xr.Dataset | Empty:
    """Run the task at the grid point ``index`` (one index per swept parameter).

    Parameters
    ----------
    config : ScanConfig
        The scan.
    index : tuple of int
        One index per swept parameter.
    """
    kind = TASKS[config.task]
    values = config.point(index)
    body = config.body_at(values)
    return kind.run(body, values.get("h"), values.get("M"), dict(config.task_options),
                    config.integrator)


def run_chunk(config: ScanConfig, block: tuple[int, ...]) -> ChunkResult:
    """Run every point of the chunk ``block`` (what one Dask task does).

    Parameters
    ----------
    config : ScanConfig
        The scan.
    block : tuple of int
        The chunk's index in the grid of chunks.
    """
    t0 = time.perf_counter()
    points = [run_point(config, index) for index in config.block_points(block)]
    return ChunkResult(tuple(block), points, time.perf_counter() - t0)


@dataclass(frozen=True)
class ScanReport:
    """What a scan did.

    Attributes
    ----------
    store : Path
    tasks : int
        Chunks of the grid (one task each).
    resumed : int
        Chunks already done in the store when the scan started.
    computed : int
        Chunks computed by this run.
    empty : list of (dict, str)
        Points of this run with nothing to compute: parameter values and reason.
    seconds : float
        Wall time of this run.
    dashboard : str or None
        Address of the Dask dashboard.
    """

    store: Path
    tasks: int
    resumed: int
    computed: int
    empty: list[tuple[dict[str, float], str]] = field(default_factory=list)
    seconds: float = 0.0
    dashboard: str | None = None

    def open(self) -> xr.Dataset:
        """The store as a (lazy) xarray dataset."""
        return xr.open_zarr(self.store, consolidated=True)


# ---------------------------------------------------------------------- executors
def _serial(cfg: ScanConfig, blocks: Sequence[tuple[int, ...]]
            ) -> Generator[ChunkResult, None, None]:
    for block in blocks:
        yield run_chunk(cfg, block)


def _dask(client: Any, cfg: ScanConfig, blocks: Sequence[tuple[int, ...]], retries: int,
          window: int) -> Generator[ChunkResult, None, None]:
    """Results as they complete, with at most ``window`` tasks submitted at a time."""
    from distributed import as_completed

    token = uuid.uuid4().hex[:8]
    todo = iter(blocks)

    def submit(block: tuple[int, ...]) -> Any:
        key = f"andoyer-scan-{token}-{'-'.join(map(str, block)) or '0'}"
        return client.submit(run_chunk, cfg, block, retries=retries, pure=False, key=key)

    queue = as_completed([submit(b) for b in islice(todo, window)])
    try:
        for future in queue:
            result = future.result()  # the task's error, after its retries
            future.release()
            nxt = next(todo, None)
            if nxt is not None:
                queue.add(submit(nxt))
            yield result
    finally:
        # On error or interruption: nothing more is submitted, pending tasks cancelled.
        with contextlib.suppress(Exception):
            client.cancel(list(queue.futures))


@contextlib.contextmanager
def _client(scheduler: str | None, client: Any, n_workers: int | None
            ) -> Iterator[Any]:
    """The Dask client to use: given, connected to an address, or a new local cluster."""
    if client is not None:
        yield client
        return
    from distributed import Client, LocalCluster

    if scheduler not in (None, "local"):
        with Client(scheduler, timeout="30s") as c:
            yield c
        return
    n = n_workers or os.cpu_count() or 1
    # One thread per worker process: a task runs single-threaded (andoyer.scan.tasks),
    # and fill_section is NumPy code that holds the GIL. Every server of the cluster
    # (scheduler, nannies, workers, dashboard) listens on the loopback interface only.
    # Its threads and processes never see Ctrl-C: this process ends them.
    # A signal in the start is delivered once the cluster can be closed (the stack).
    with contextlib.ExitStack() as stack:
        with children_ignore_interrupts():
            cluster = stack.enter_context(LocalCluster(
                n_workers=n, threads_per_worker=1, processes=True, host=LOOPBACK,
                dashboard_address=f"{LOOPBACK}:0", silence_logs=logging.ERROR))
        yield stack.enter_context(Client(cluster))


def _dashboard(client: Any) -> str | None:
    try:
        return str(client.dashboard_link)
    except Exception:  # no bokeh: no dashboard
        return None


# ---------------------------------------------------------------------- the scan
def run_scan(config: ScanConfig | str | os.PathLike[str] | dict[str, Any],
             store: str | os.PathLike[str], *, scheduler: str | None = None,
             client: Any = None, n_workers: int | None = None, overwrite: bool = False,
             retries: int = 2, max_in_flight: int | None = None,
             progress: bool | None = None,
             max_core_hours: float = DEFAULT_MAX_CORE_HOURS,
             max_store_gb: float = DEFAULT_MAX_STORE_GB) -> ScanReport:
    """Run a parameter scan and stream its results into a Zarr store (what
    ``andoyer scan CONFIG.toml`` runs).

    Parameters
    ----------
    config : ScanConfig, path of a TOML file, or mapping
        See :func:`andoyer.scan.config.load_config`.
    store : path
        The Zarr store (a directory). If it exists and was made by the same
        configuration, the scan resumes: only the chunks not marked done are computed.
    scheduler : {None, "local", "serial"} or str
        ``None``/``"local"``: a local cluster of ``n_workers`` processes (default: all
        cores), one thread each, started and closed here. ``"serial"``: no Dask, every
        task in this process. Otherwise the address of a running scheduler,
        ``"tcp://HOST:PORT"`` (its workers need andoyer installed; they do not need
        access to the store).
    client : distributed.Client, optional
        Use this client (and its cluster) instead; it is left open.
    n_workers : int, optional
        Workers of the local cluster.
    overwrite : bool
        Start again in an existing store of this or another configuration.
    retries : int
        Retries of a task that raises. A task whose worker dies is rescheduled by Dask.
    max_in_flight : int, optional
        Tasks submitted at a time (default: twice the cluster's threads).
    progress : bool, optional
        Progress line on stderr (default: when stderr is a terminal).
    max_core_hours, max_store_gb : float
        A scan estimated to need more is refused (:func:`~andoyer.scan.cost.check_size`).

    Returns
    -------
    ScanReport
        ``report.open()`` is the store as an xarray dataset.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> cfg = {"parameters": {"mu": [0.01, 0.1], "h": 0.3},
    ...        "task": {"kind": "section", "n_orbits": 2, "n_crossings": 3}}
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     report = run_scan(cfg, pathlib.Path(tmp) / "s.zarr", scheduler="serial")
    ...     ds = report.open()
    ...     print(report.computed, dict(ds.sizes), bool(ds.done.all()))
    2 {'mu': 2, 'orbit': 2, 'crossing': 3, 'component': 6} True
    """
    cfg = config if isinstance(config, ScanConfig) else load_config(config)
    if client is not None and scheduler is not None:
        raise ValueError("give either client= or scheduler=, not both")
    retries = integer("retries", retries, 0)
    n_workers = None if n_workers is None else integer("n_workers", n_workers, 1)
    check_size(cfg, max_core_hours, max_store_gb)
    path = Path(store)
    check_store(path, cfg, overwrite=overwrite)  # before the lock and any cluster
    # One writer per store, for the whole run: a second scan (with --overwrite too) is
    # refused, naming this one, instead of replacing the store under it.
    with OutputLock(path):
        t0 = time.perf_counter()
        done = prepare(path, cfg, overwrite=overwrite)
        blocks = cfg.blocks()
        todo = blocks if done is None else [b for b in blocks
                                            if not done[cfg.block_slices(b)].all()]
        schema = None if done is None else store_schema(path, cfg)
        report = ScanReport(path, len(blocks), len(blocks) - len(todo), 0)
        if not todo:
            return report
        serial = scheduler == "serial"
        with contextlib.ExitStack() as stack:
            dashboard = None
            if serial:
                results = _serial(cfg, todo)
            else:
                c = stack.enter_context(_client(scheduler, client, n_workers))
                dashboard = _dashboard(c)
                threads = sum(c.nthreads().values()) or 1
                window = max_in_flight or max(2, 2 * threads)
                results = _dask(c, cfg, todo, retries, window)
                stack.callback(results.close)
            bar = Progress(len(blocks), f"scan ({len(blocks) - report.resumed} of "
                           f"{len(blocks)} tasks to compute)", progress,
                           postfix=f"Dask dashboard {dashboard}" if dashboard else None,
                           initial=report.resumed)
            stack.callback(bar.close)
            computed, empty = _consume(results, path, cfg, schema, overwrite, bar)
        return ScanReport(path, len(blocks), report.resumed, computed, empty,
                          time.perf_counter() - t0, dashboard)


def _consume(results: Iterator[ChunkResult], path: Path, cfg: ScanConfig,
             schema: Schema | None, overwrite: bool, bar: Progress
             ) -> tuple[int, list[tuple[dict[str, float], str]]]:
    """Write each chunk's results as they arrive; lay out the store at the first data."""
    kind = TASKS[cfg.task]
    pending: list[ChunkResult] = []
    empty: list[tuple[dict[str, float], str]] = []
    computed = 0
    for res in results:
        for index, p in zip(cfg.block_points(res.block), res.points, strict=True):
            if isinstance(p, Empty):
                empty.append((cfg.point(index), p.reason))
        if schema is None:
            first = next((p for p in res.points if not isinstance(p, Empty)), None)
            if first is None:  # nothing to lay the store out from yet
                pending.append(res)
                bar.update()
                continue
            schema = point_schema(first, kind.fixed_coords)
            initialise(path, cfg, schema, first.attrs, overwrite=overwrite)
            for old in pending:
                write_chunk(path, cfg, schema, old.block, old.points)
                computed += 1
            pending.clear()
        write_chunk(path, cfg, schema, res.block, res.points)
        computed += 1
        bar.update()
    if schema is None:
        why = empty[0][1] if empty else "no result"
        raise ValueError(f"no point of the scan had anything to compute ({len(empty)} empty "
                         f"points), so no store was written; the first: {why}")
    return computed, empty


def summary(report: ScanReport) -> str:
    """One paragraph on what a scan did (for the command line).

    Parameters
    ----------
    report : ScanReport
        What :func:`run_scan` returned.
    """
    lines = [f"wrote {report.store}: {report.tasks} tasks ({report.computed} computed now, "
             f"{report.resumed} done before) in {report.seconds:.1f} s"]
    if report.empty:
        vals, why = report.empty[0]
        at = ", ".join(f"{k} = {v:g}" for k, v in vals.items() if k in ("mu", "epsilon", "h", "M"))
        lines.append(f"{len(report.empty)} points had nothing to compute (stored empty), "
                     f"e.g. at {at}: {why}")
    return "\n".join(lines)
