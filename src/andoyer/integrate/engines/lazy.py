"""heyoka imported on first use: the one place where andoyer imports it.

Modules that build heyoka integrators write ``from andoyer.integrate.engines.lazy import
heyoka as hy``; importing them costs nothing and works where heyoka is not installed
(it has wheels for Linux only). The first attribute access imports heyoka, or raises
``ModuleNotFoundError`` saying what to do instead.

Examples
--------
>>> from andoyer.integrate.engines.lazy import LazyModule
>>> LazyModule("no_such_module_here").anything
Traceback (most recent call last):
...
ModuleNotFoundError: no_such_module_here is not installed here; install it
"""

from __future__ import annotations

import importlib
import types
from typing import Any

__all__ = ["LazyModule", "heyoka", "heyoka_available"]


class LazyModule(types.ModuleType):
    """A module imported at its first attribute access."""

    def __init__(self, name: str, hint: str = "") -> None:
        super().__init__(name)
        self._hint = hint

    def __getattr__(self, attr: str) -> Any:
        # Probes such as inspect.unwrap's __wrapped__ must not import the module.
        if attr.startswith("__") and attr != "__version__":
            raise AttributeError(attr)
        try:
            module = importlib.import_module(self.__name__)
        except ModuleNotFoundError:
            raise ModuleNotFoundError(
                f"{self.__name__} is not installed here; {self._hint or 'install it'}",
                name=self.__name__) from None
        return getattr(module, attr)


#: heyoka.py, imported at first use.
heyoka: Any = LazyModule(
    "heyoka", "it has wheels for Linux only (pip install heyoka, or conda-forge). Every "
              "analysis runs on engine='numba' without it (orbits, sections, chaos "
              "indicators, periodic orbits, manifolds, Floquet multipliers); only "
              "engine='heyoka' itself needs it")


def heyoka_available() -> bool:
    """Whether heyoka can be imported (without importing it)."""
    import importlib.util

    return importlib.util.find_spec("heyoka") is not None
