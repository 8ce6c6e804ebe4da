"""What the report's items share: the context they build in, what they return, an item.

An item's builder (in :mod:`andoyer.report.items`) computes with the analysis layer,
draws with the plot layer, writes its files through :class:`Context` and returns a
:class:`Result`: the files, the numbers of ``summary.json``, the values its prose needs
and an optional table. The prose itself lives next to the templates
(``templates/items/<key>.html.j2``), rendered by :mod:`andoyer.report.html`.

Examples
--------
>>> t = Table(["mu", "max |Delta G|"], [[0.01, "1.2e-06"]])
>>> t.head, len(t.rows)
(['mu', 'max |Delta G|'], 1)
"""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

from andoyer.atomic import atomic_path
from andoyer.body import RigidBody

if TYPE_CHECKING:
    import xarray as xr

    from andoyer.integrate.engines.base import Capability

__all__ = ["Context", "Result", "Item", "Table", "concurrently"]

_T = TypeVar("_T")


def concurrently(tasks: Sequence[Callable[[], _T]]) -> list[_T]:
    """Run independent ``tasks`` on threads, one per core at most, and return their
    results in order. The first error is raised at once, as is an interrupt of the
    caller (Ctrl-C, SIGTERM): the tasks not started are dropped, those running are not
    waited for (daemon threads, ended with the process).

    For an item's independent integrations: the engines integrate without the GIL
    (heyoka, the Numba kernels), so the measurements of one item share the cores
    instead of running one after another, and each gives what it gives alone. Every
    task runs in a copy of the caller's context (a :func:`~andoyer.progress.silenced`
    caller's tasks show no bar either), and the warning filters are the caller's again
    when all are done (a task's own ``warnings.catch_warnings`` is not thread-safe and
    could leave them changed).

    Parameters
    ----------
    tasks : sequence of callables
        Each called with no argument.

    Examples
    --------
    >>> concurrently([lambda: 1, lambda: 2])
    [1, 2]
    """
    import contextvars
    import os
    import threading
    import warnings

    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (
        os.cpu_count() or 1)
    workers = max(1, min(len(tasks), cores))
    if workers == 1:
        return [task() for task in tasks]
    results: list[Any] = [None] * len(tasks)
    errors: list[BaseException] = []
    queue = list(enumerate(tasks))
    lock, done = threading.Lock(), threading.Event()
    left = [len(tasks)]

    def work(context: contextvars.Context) -> None:
        while True:
            with lock:
                if not queue or errors:
                    return
                i, task = queue.pop(0)
            try:
                results[i] = context.run(task)
            except BaseException as exc:  # noqa: BLE001 -- handed to the caller
                with lock:
                    errors.append(exc)
                done.set()
                return
            with lock:
                left[0] -= 1
                if left[0] == 0:
                    done.set()

    with warnings.catch_warnings():
        # Daemon threads: on an error or an interrupt of the caller (Ctrl-C, SIGTERM) the
        # tasks still queued never start and the process does not wait for those running.
        for _ in range(workers):
            threading.Thread(target=work, args=(contextvars.copy_context(),),
                             name="andoyer-item", daemon=True).start()
        try:
            done.wait()
        finally:
            with lock:
                queue.clear()
    if errors:
        raise errors[0]
    return results


@dataclass
class Context:
    """What every item builder gets: the output folder, the paper's body, the engine.

    Attributes
    ----------
    out : pathlib.Path
        The report's folder.
    body : RigidBody
        The paper's body.
    engine : str, optional
        The integration engine asked for (None: each item's default).
    quick : bool
        Smaller grids and shorter times (a check, not the paper's figures).
    """

    out: Path
    body: RigidBody
    engine: str | None = None
    quick: bool = False

    def engine_name(self, *capabilities: Capability, workload: str | None = None) -> str:
        """The engine that actually runs: :attr:`engine`, or the default
        (:func:`~andoyer.integrate.engines.default_engine_name` of the ``capabilities`` and
        the ``workload``: the measured default where there is one, heyoka where installed,
        else the first fallback with the capabilities); for an analysis that needs
        ``capabilities`` the engine lacks, the default.

        >>> from andoyer.integrate.engines.base import Capability
        >>> ctx = Context(Path("."), RigidBody.paper(), "taylor")
        >>> ctx.engine_name(), ctx.engine_name(Capability.EXTENDED_PRECISION) != "taylor"
        ('taylor', True)
        """
        from andoyer.integrate.engines import default_engine_name, engine_class

        if self.engine is not None and set(capabilities) <= engine_class(self.engine).capabilities:
            return self.engine
        return default_engine_name(*capabilities, workload=workload)

    def figure(self, fig: Any, name: str) -> list[Path]:
        """Write a figure as ``name.png`` and ``name.pdf``."""
        from andoyer.plot.section import save_figure

        return save_figure(fig, self.out / name, pdf=True, dpi=200)

    def data(self, ds: xr.Dataset, name: str) -> Path:
        """Write a dataset as ``name.nc`` (atomically)."""
        from andoyer.io import write_netcdf

        return write_netcdf(ds, self.out / f"{name}.nc")

    def text(self, name: str, text: str) -> Path:
        """Write ``text`` as the file ``name`` (atomically)."""
        path = self.out / name
        with atomic_path(path) as tmp:
            tmp.write_text(text, encoding="utf-8")
        return path

    def json(self, name: str, value: Any) -> Path:
        """Write ``value`` as the JSON file ``name`` (atomically)."""
        return self.text(name, json.dumps(value, indent=1))


@dataclass
class Table:
    """A table of the report: column heads and rows of cells (any values, shown as text).

    Attributes
    ----------
    head : list of str
        Column heads.
    rows : list of list
        Rows of cells (shown as text).
    """

    head: list[str]
    rows: list[list[Any]]


@dataclass
class Result:
    """What an item wrote, its numbers for ``summary.json`` and the values of its prose.

    ``values`` are the names its template (``templates/items/<key>.html.j2``) reads,
    besides ``body`` and ``engine``; ``table`` and ``pre`` (preformatted text) follow the
    prose.

    Attributes
    ----------
    files : list of pathlib.Path
        The files it wrote.
    numbers : dict of str to float
        Its numbers for ``summary.json``.
    values : dict
        The names its template reads.
    table : Table or None
        A table shown under the prose.
    pre : str
        Preformatted text shown under the prose.
    """

    files: list[Path]
    numbers: dict[str, float] = field(default_factory=dict)
    values: dict[str, Any] = field(default_factory=dict)
    table: Table | None = None
    pre: str = ""


@dataclass(frozen=True)
class Item:
    """One section of the report: a key, a title and the function that builds it.

    Attributes
    ----------
    key : str
        Its name (files, template ``templates/items/<key>.html.j2``).
    title : str
        Its title in the report.
    build : callable
        ``build(ctx) -> Result``.
    cost : float
        Its relative cost (longest items start first).
    """

    key: str
    title: str
    build: Callable[[Context], Result]
    #: Seconds it takes (measured, warm caches, 2 cores): items start longest first.
    cost: float = 1.0
