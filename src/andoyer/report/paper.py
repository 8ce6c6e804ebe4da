"""``andoyer paper``: rebuild the paper's figures and checks from nothing, into one folder.

Each *item* of the report (:data:`ITEMS`, built by :mod:`andoyer.report.items`) computes
with the library's analysis layer, draws with its plot layer, writes its figures (PNG
and PDF) and data (NetCDF) and gives the values of its prose, which lives next to the
templates (``templates/items/<key>.html.j2``). :func:`build_paper` runs the items
(:mod:`andoyer.report.schedule`: longest first, in this process and worker processes,
one progress bar), writes ``summary.json`` and ``index.html`` last (atomically,
:mod:`andoyer.report.html`), so a folder with an index is a complete one.

Examples
--------
>>> [item.key for item in ITEMS][:3]
['fig1', 'fig2', 'heteroclinic']
"""

from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

from andoyer.body import RigidBody
from andoyer.report import DEFAULT_OUT
from andoyer.report.base import Context, Item, Result
from andoyer.report.items import ITEMS
from andoyer.validation import integer

__all__ = ["Item", "Result", "Context", "ITEMS", "build_paper", "default_jobs", "DEFAULT_OUT"]

#: A worker process starts in about 2 s (its imports): worth it above this much work.
_WORKER_WORTH_S = 5.0


def default_jobs(items: list[Item]) -> int:
    """Processes for ``items``: 2 when two cores are free and the items take more than
    :data:`_WORKER_WORTH_S` (the heavy items use every core themselves; two processes
    keep the cores busy between them), else 1.

    Parameters
    ----------
    items : list of Item
        The items to build.

    Examples
    --------
    >>> default_jobs(ITEMS[2:3])  # one item of 0.1 s
    1
    """
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (
        os.cpu_count() or 1)
    if len(items) < 2 or sum(i.cost for i in items) < _WORKER_WORTH_S:
        return 1
    return max(1, min(2, cores))


def build_paper(out: str | Path = DEFAULT_OUT, *, body: RigidBody | None = None,
                engine: str | None = None, quick: bool = False,
                only: list[str] | None = None, progress: bool = True,
                jobs: int | None = None
                ) -> tuple[Path, list[tuple[Item, Result, float]]]:
    """Build the report: every item's figures and data, then ``index.html``.

    Parameters
    ----------
    out : path-like
        Output folder (created).
    body : RigidBody, optional
        Default: the paper's body, :meth:`RigidBody.paper`.
    engine : str, optional
        Integration engine (default: heyoka where installed, else each item's default,
        :func:`~andoyer.integrate.engines.default_engine_name`). The report names the
        engine that ran each integration.
    quick : bool
        Smaller grids and shorter runs (for tests).
    only : list of str, optional
        Keys of the items to build (default: all, see :data:`ITEMS`).
    progress : bool
        A progress bar on stderr (when it is a terminal) and one line per item, in
        report order.
    jobs : int, optional
        Processes building items at once (default :func:`default_jobs`: 2 on two or
        more cores). The results do not depend on it.

    Returns
    -------
    (index, done)
        The path of ``index.html`` and, per item, the item, its result and seconds.
    """
    from andoyer._version import __version__
    from andoyer.atomic import atomic_path
    from andoyer.report.html import write_index
    from andoyer.report.schedule import run_items

    keys = [i.key for i in ITEMS]
    if only:
        unknown = sorted(set(only) - set(keys))
        if unknown:
            raise ValueError(f"unknown item(s) {unknown}; choose from {keys}")
    items = [i for i in ITEMS if not only or i.key in only]
    n_jobs = default_jobs(items) if jobs is None else integer("jobs", jobs, 1)
    ctx = Context(Path(out), RigidBody.paper() if body is None else body, engine, quick)
    ctx.out.mkdir(parents=True, exist_ok=True)
    t_all = time.perf_counter()
    times = run_items(items, ctx, min(n_jobs, len(items)), progress)
    done = [(item, *times[item.key]) for item in items]
    # The engines that ran (never "default"): the report's, and per item those it names.
    summary = {"andoyer_version": __version__, "body": ctx.body.attrs(),
               "engine": ctx.engine_name(), "quick": quick,
               "items": {i.key: {"title": i.title, "seconds": round(dt, 3),
                                 "numbers": r.numbers, "files": [f.name for f in r.files],
                                 **({"engine": r.values["engine"]} if "engine" in r.values
                                    else {})}
                         for i, r, dt in done}}
    with atomic_path(ctx.out / "summary.json") as tmp:
        tmp.write_text(json.dumps(summary, indent=1), encoding="utf-8")
    index = write_index(ctx.out, ctx.body, ctx.engine_name(), done)
    if progress:
        print(f"wrote {index} ({time.perf_counter() - t_all:.1f} s in all)", file=sys.stderr)
    return index, done
