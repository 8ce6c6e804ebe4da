"""The interactive explorer of Poincare sections, in the browser or in Jupyter.

``andoyer explore`` (the command) serves it on ``http://127.0.0.1:PORT/``; in a
notebook ``andoyer.explore.app()`` returns the same page as a Panel object. The module
is callable, so ``andoyer.explore(...)`` is ``andoyer.explore.app(...)``.

Panel and Bokeh are imported only when the app is built (:mod:`andoyer.explore.ui`);
the logic (:mod:`andoyer.explore.state`) and the exports
(:mod:`andoyer.explore.export`) need neither.
"""

from __future__ import annotations

import sys
import types
from typing import Any

__all__ = ["app", "serve", "Explorer"]


def app(*args: Any, **kwargs: Any) -> Any:
    """The explorer page as a Panel object (see :func:`andoyer.explore.server.app`).

    Parameters
    ----------
    *args, **kwargs
        Those of :func:`andoyer.explore.server.app` (imported on first call: it loads
        Panel).

    Returns
    -------
    panel.viewable.Viewable
    """
    from andoyer.explore.server import app as _app

    return _app(*args, **kwargs)


def serve(*args: Any, **kwargs: Any) -> Any:
    """Serve the explorer (see :func:`andoyer.explore.server.serve`).

    Parameters
    ----------
    *args, **kwargs
        Those of :func:`andoyer.explore.server.serve` (imported on first call: it loads
        Panel).

    Returns
    -------
    object
        What :func:`andoyer.explore.server.serve` returns.
    """
    from andoyer.explore.server import serve as _serve

    return _serve(*args, **kwargs)


def __getattr__(name: str) -> Any:
    if name == "Explorer":
        from andoyer.explore.ui import Explorer

        return Explorer
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


class _CallableModule(types.ModuleType):
    """``andoyer.explore(...)`` builds the app, as ``andoyer.explore.app(...)`` does."""

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return app(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule
