"""An item's independent measurements on threads: results in order, the caller's context."""

from __future__ import annotations

import warnings

import pytest

from andoyer.progress import Progress, silenced
from andoyer.report.base import concurrently


def test_results_in_order_with_the_callers_context(monkeypatch) -> None:
    monkeypatch.setattr("os.sched_getaffinity", lambda _pid: {0, 1}, raising=False)

    def bar_hidden() -> bool:
        return not Progress(1, "x", enabled=True).enabled

    with silenced():
        assert concurrently([bar_hidden] * 3) == [True] * 3
    assert concurrently([lambda i=i: i * i for i in range(5)]) == [0, 1, 4, 9, 16]


def test_warning_filters_restored_and_the_first_error_raised(monkeypatch) -> None:
    monkeypatch.setattr("os.sched_getaffinity", lambda _pid: {0, 1}, raising=False)
    before = list(warnings.filters)

    def quiet() -> int:
        warnings.simplefilter("ignore")  # a task changing the process' filters
        return 1

    def fails() -> int:
        raise ValueError("no island")

    assert concurrently([quiet, quiet]) == [1, 1]
    assert warnings.filters == before
    with pytest.raises(ValueError, match="no island"):
        concurrently([quiet, fails])
    assert warnings.filters == before


def test_an_error_does_not_wait_for_the_running_tasks(monkeypatch) -> None:
    # (an interrupt of the caller alike: the tasks still queued never start)
    import time

    monkeypatch.setattr("os.sched_getaffinity", lambda _pid: {0, 1}, raising=False)
    started = []

    def slow() -> None:
        started.append(1)
        time.sleep(3.0)

    def fails() -> None:
        raise RuntimeError("interrupted")

    t0 = time.perf_counter()
    with pytest.raises(RuntimeError, match="interrupted"):
        concurrently([slow, fails, slow, slow])
    assert time.perf_counter() - t0 < 2.0 and len(started) == 1
