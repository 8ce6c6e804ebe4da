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
from collections.abc import Callable
from functools import cache
from typing import Any

__all__ = ["LazyModule", "heyoka", "heyoka_available"]


class LazyModule(types.ModuleType):
    """A module imported at its first attribute access.

    Parameters
    ----------
    name : str
        Dotted name of the module to import on first use.
    hint : str, default ""
        What to install, added to the ``ImportError`` when it is missing.
    on_import : callable, optional
        Called with the module once it is imported (e.g. to configure it).
    """

    def __init__(self, name: str, hint: str = "",
                 on_import: Callable[[types.ModuleType], None] | None = None) -> None:
        super().__init__(name)
        self._hint = hint
        self._on_import = on_import

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
        if self._on_import is not None:
            hook, self._on_import = self._on_import, None
            hook(module)
        return getattr(module, attr)


def _heyoka_disk_cache(hy: Any) -> None:
    """heyoka keeps compiled integrators in the user's cache folder; where that is not
    writable (a read-only home) it would warn at every compilation: its disk cache is
    turned off instead, with andoyer's one warning (:mod:`andoyer.kernels.cache`)."""
    from andoyer.kernels.cache import warn_no_cache, writable

    state = hy.llvm_state
    if state.get_diskcache_enabled() and not writable(state.get_diskcache_path()):
        state.set_diskcache_enabled(False)
        warn_no_cache(f"heyoka's {state.get_diskcache_path()}")


#: heyoka.py, imported at first use.
heyoka: Any = LazyModule(
    "heyoka", "it has wheels for Linux only (pip install heyoka, or conda-forge). Every "
              "analysis runs on engine='numba' without it (orbits, sections, chaos "
              "indicators, periodic orbits, manifolds, Floquet multipliers); only "
              "engine='heyoka' itself needs it", on_import=_heyoka_disk_cache)


@cache
def heyoka_available() -> bool:
    """Whether heyoka can be imported (without importing it); looked up once per process
    (``find_spec`` walks ``sys.path``: 76 us, paid by every ``engine=None`` call before).

    >>> heyoka_available() in (True, False)
    True
    """
    import importlib.util

    return importlib.util.find_spec("heyoka") is not None
