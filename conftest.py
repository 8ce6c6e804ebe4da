"""Collection rules for the whole suite (tests/ and the doctests of src/).

heyoka.py has wheels for Linux only, and andoyer must work without it (every analysis
runs on the numba engine). Where heyoka is not installed, the tests that need heyoka
itself are skipped with one reason, and their number is printed at the end of the run
(CI keeps it small):

* tests marked ``@pytest.mark.heyoka``;
* tests parametrized with the engine ``"heyoka"`` (any parameter equal to it, or a
  tuple of engines holding it);
* the doctests of the modules that are heyoka's own (:data:`HEYOKA_DOCTEST_MODULES`).
"""

from __future__ import annotations

import importlib.util

import pytest
from _pytest.doctest import DoctestItem

HEYOKA = importlib.util.find_spec("heyoka") is not None
HEYOKA_REASON = "needs heyoka itself, which is not installed here"
#: Modules (or single functions) whose doctests build heyoka integrators or expressions.
HEYOKA_DOCTEST_MODULES = ("andoyer.integrate.variational",
                          "andoyer.integrate.engines.heyoka_engine",
                          "andoyer.integrate.engines.heyoka_symbolic.taylor_form")


def _needs_heyoka(item: pytest.Item) -> bool:
    if item.get_closest_marker("heyoka") is not None:
        return True
    callspec = getattr(item, "callspec", None)
    if callspec is not None:
        for value in callspec.params.values():
            # isinstance first: a parameter may be an array, whose == is elementwise
            if (isinstance(value, str) and value == "heyoka") or (
                    isinstance(value, tuple | list)
                    and any(isinstance(v, str) and v == "heyoka" for v in value)):
                return True
    return isinstance(item, DoctestItem) and item.name.startswith(HEYOKA_DOCTEST_MODULES)


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if HEYOKA:
        return
    skip = pytest.mark.skip(reason=HEYOKA_REASON)
    for item in items:
        if _needs_heyoka(item):
            item.add_marker(skip)


def pytest_terminal_summary(terminalreporter: pytest.TerminalReporter) -> None:
    if HEYOKA:
        return
    skipped = terminalreporter.stats.get("skipped", [])
    n = sum(1 for report in skipped if "heyoka" in str(report.longrepr))
    terminalreporter.write_line(f"without heyoka: {n} tests skipped because they need heyoka "
                                "itself")
