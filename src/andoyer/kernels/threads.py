"""Orbits in parallel: blocks of orbits handed to threads running nogil kernels.

The compiled entry points of :mod:`andoyer.kernels.dop853.flow` and
:mod:`andoyer.kernels.dop853.tangent` integrate a block of orbits on the calling thread
(``nogil=True``) and write into output arrays they are given. :func:`over_orbits`
splits the orbits into blocks; the calling thread and ``threads - 1`` threads of a
pool started once per process take blocks until none is left, each writing into its
rows of the outputs, allocated once.

Why threads and not Numba's ``prange``: the same machine code runs either way (the
kernels release the GIL), but a ``parallel=True`` entry point costs Numba's parfor
passes at compile time, which the first call of a fresh install pays (measured:
benchmarks/NOTES.md#threads). Blocks are handed out as threads
free up, so orbits of unequal cost (near a separatrix the steps shrink) balance as with
``prange`` at chunk size 1.

The number of threads is Numba's (:func:`numba.get_num_threads`, which
``numba.set_num_threads`` and ``NUMBA_NUM_THREADS`` set, per calling thread), so a scan
worker that asks for one thread gets one.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numba
import numpy as np

__all__ = ["over_orbits", "block_starts"]


def block_starts(n: int, threads: int, block: int = 1) -> list[int]:
    """First orbit of each block: blocks of ``block`` orbits (``0``: ``n`` split evenly
    over ``threads``).

    Parameters
    ----------
    n : int
        Orbits.
    threads : int
        Threads.
    block : int, default 1
        Orbits per block (0: ``n`` split evenly over ``threads``).

    Examples
    --------
    >>> block_starts(5, 2, 2)
    [0, 2, 4]
    >>> block_starts(5, 2, 0)
    [0, 3]
    """
    size = max(1, -(-n // threads)) if block == 0 else int(block)
    return list(range(0, n, size))


def over_orbits(kernel: Callable[..., None], n: int, inputs: Sequence[np.ndarray],
                outputs: Sequence[np.ndarray], args: Sequence[Any], *, block: int = 1,
                threads: int | None = None, starts: Sequence[int] | None = None) -> None:
    """Run ``kernel(*inputs[rows], *args, *outputs[rows])`` over blocks of rows.

    Parameters
    ----------
    kernel : callable
        A compiled nogil function of a block of orbits: it reads the rows of
        ``inputs`` and writes the same rows of ``outputs``.
    n : int
        Number of orbits (the first dimension of every input and output).
    inputs, outputs : sequence of ndarray
        Per-orbit arrays (C-contiguous; a block is a contiguous slice of rows).
    args : sequence
        Arguments shared by all orbits, passed between the inputs and the outputs.
    block : int
        Orbits per block (``0``: one block per thread).
    threads : int, optional
        Default :func:`numba.get_num_threads`.
    starts : sequence of int, optional
        First row of each block, increasing from 0 (blocks of any sizes; instead of
        ``block``).
    """
    m = numba.get_num_threads() if threads is None else int(threads)
    starts = block_starts(n, max(1, m), block) if starts is None else list(starts)
    if m <= 1 or len(starts) <= 1:
        kernel(*inputs, *args, *outputs)
        return
    stops = starts[1:] + [n]
    blocks = iter(range(len(starts)))
    lock = threading.Lock()

    def work() -> None:
        # Take the next block until none is left: blocks go to whichever thread is free.
        while True:
            with lock:
                i = next(blocks, None)
            if i is None:
                return
            rows = slice(starts[i], stops[i])
            kernel(*(a[rows] for a in inputs), *args, *(a[rows] for a in outputs))

    helpers = [_pool().submit(work) for _ in range(min(m, len(starts)) - 1)]
    try:
        work()  # the calling thread works too
    finally:
        for f in helpers:
            f.result()


_POOL: ThreadPoolExecutor | None = None
_POOL_LOCK = threading.Lock()


def _pool() -> ThreadPoolExecutor:
    """The process's worker threads, started once (a pool per call costs milliseconds
    a call; with this one the engine is as fast as with ``prange``; measured:
    benchmarks/NOTES.md#threads)."""
    global _POOL
    with _POOL_LOCK:
        if _POOL is None:
            config: Any = numba.config
            size = max(int(config.NUMBA_NUM_THREADS), os.cpu_count() or 1)
            _POOL = ThreadPoolExecutor(size, thread_name_prefix="andoyer-orbits")
        return _POOL
