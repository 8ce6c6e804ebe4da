"""Fixtures of the Taylor kernels' tests."""

from __future__ import annotations

from collections.abc import Callable
from types import ModuleType
from typing import Any

import pytest


@pytest.fixture
def orbits_per_call(monkeypatch: pytest.MonkeyPatch) -> Callable[[ModuleType, str], list[int]]:
    """``orbits_per_call(module, name)``: ``module.name`` (a kernel entry point taking the
    orbits' start states first) spied on for the test; the list it returns gets the number
    of orbits of each call (which route an engine took)."""
    def spy_on(module: ModuleType, name: str) -> list[int]:
        calls: list[int] = []
        real = getattr(module, name)

        def spy(z0: Any, *args: Any, **kwargs: Any) -> Any:
            calls.append(z0.shape[0])
            return real(z0, *args, **kwargs)

        monkeypatch.setattr(module, name, spy)
        return calls
    return spy_on
