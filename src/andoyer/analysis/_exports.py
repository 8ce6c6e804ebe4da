"""The re-exports of the analysis sub-packages, imported on first use (PEP 562).

Each sub-package's ``__init__`` names its public functions and classes twice, side by
side: as explicit imports under ``TYPE_CHECKING`` (what mypy and readers see) and in
``EXPORTS``, name -> the module of the package that defines it (what runs), so that
importing one light module (``analysis.chaos.registry``, read by the CLI's argument
parser) does not import its heavy siblings (seconds of xarray, SciPy and Numba).
``tests/analysis/test_exports.py`` checks that the two lists agree and that every name
resolves. :func:`lazy_exports` is the one ``__getattr__`` / ``__dir__`` they share.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["lazy_exports"]


def lazy_exports(package: str, exports: Mapping[str, str]
                 ) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """The module ``__getattr__`` and ``__dir__`` of ``package`` re-exporting ``exports``.

    A name is imported from its module at first use and then kept in the package's
    namespace (the next look-up does not reach ``__getattr__``).

    Parameters
    ----------
    package : str
        The package's dotted name (its ``__name__``), already being imported.
    exports : mapping of str to str
        Public name -> the module of ``package`` that defines it (``"lyapunov"``).

    Returns
    -------
    (__getattr__, __dir__)
        To assign at the package's top level.

    Examples
    --------
    >>> import andoyer.analysis.space as space
    >>> get, names = lazy_exports("andoyer.analysis.space", {"lagrange_top": "lagrange"})
    >>> get("lagrange_top").__module__, "lagrange_top" in names()
    ('andoyer.analysis.space.lagrange', True)
    >>> get("nutation")
    Traceback (most recent call last):
    ...
    AttributeError: module 'andoyer.analysis.space' has no attribute 'nutation'
    """
    namespace = sys.modules[package].__dict__

    def get(name: str) -> Any:
        if name not in exports:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(f"{package}.{exports[name]}"), name)
        namespace[name] = value
        return value

    def names() -> list[str]:
        return sorted(set(namespace) | set(exports))

    return get, names
