"""Serving the explorer: the Panel page (:func:`app`) and a Bokeh server on 127.0.0.1
(:func:`serve`) started in a thread of its own, with a handle to stop it.
"""

from __future__ import annotations

import queue
import socket
import threading
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import panel as pn

from andoyer.body import RigidBody
from andoyer.explore.state import (
    make_settings,
)
from andoyer.explore.ui import Explorer

__all__ = ["ServerHandle", "app", "serve"]


# ---------------------------------------------------------------------- entry points
def app(body: RigidBody | None = None, **kwargs: Any) -> Any:
    """The explorer as a Panel object: display it in Jupyter, or ``.servable()``.

    Parameters are those of :class:`Explorer`. In a notebook run
    ``pn.extension()`` first, then ``andoyer.explore.app()`` (or ``andoyer.explore()``)
    as the last expression of a cell.
    """
    return Explorer(body, **kwargs).panel


@dataclass
class ServerHandle:
    """A running explorer server on a background thread (see :func:`serve`)."""

    url: str
    port: int
    _stop: Callable[[], None]

    def stop(self) -> None:
        """Stop the server and its thread."""
        self._stop()


def _free_port(address: str) -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind((address, 0))
        return int(sock.getsockname()[1])


def _make_server(factory: Callable[[], Any], port: int, address: str, loop: Any) -> Any:
    return pn.serve({"/": factory}, port=port, address=address, show=False, start=False,
                    loop=loop, verbose=False, title="andoyer explore", location=False,
                    websocket_origin=[f"{address}:{port}", f"localhost:{port}"])


def serve(body: RigidBody | None = None, *, port: int = 0, address: str = "127.0.0.1",
          show: bool = False, threaded: bool = False,
          on_start: Callable[[str], None] | None = None, **kwargs: Any) -> ServerHandle | None:
    """Serve the explorer on ``http://address:port/`` (one :class:`Explorer` per page).

    Parameters
    ----------
    body : RigidBody, optional
        Passed with ``**kwargs`` to :class:`Explorer`.
    port : int, default 0
        0 picks a free port.
    address : str, default "127.0.0.1"
        Loopback only by default.
    show : bool
        Open the page in the default web browser.
    threaded : bool
        Run the server on a background thread and return a :class:`ServerHandle`;
        otherwise block until interrupted (Ctrl-C) and return None.
    on_start : callable, optional
        Called with the page's address once the server listens.
    """
    if isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535:
        raise ValueError(f"port must be an integer in [0, 65535], got {port!r}")
    settings = {k: v for k, v in kwargs.items() if k != "boundary_grid"}
    make_settings(body, **settings)  # bad input fails here, not in every page

    def factory() -> Any:
        return Explorer(body, **kwargs).panel

    from tornado.ioloop import IOLoop

    if not threaded:
        p = port or _free_port(address)
        server = _make_server(factory, p, address, IOLoop(make_current=False))
        url = f"http://{address}:{server.port}/"
        server.start()
        if on_start is not None:
            on_start(url)
        if show:
            server.io_loop.add_callback(server.show, "/")
        try:
            server.io_loop.start()
        except KeyboardInterrupt:
            pass
        finally:
            server.stop()
        return None

    ready: queue.Queue[Any] = queue.Queue()

    def run() -> None:
        try:
            loop = IOLoop(make_current=False)
            p = port or _free_port(address)
            server = _make_server(factory, p, address, loop)
            server.start()
        except BaseException as exc:  # noqa: BLE001 - handed to the caller's thread
            ready.put(exc)
            return
        ready.put((server, loop))
        loop.start()
        server.stop()
        loop.close()

    thread = threading.Thread(target=run, name="andoyer-explore-server", daemon=True)
    thread.start()
    got = ready.get(timeout=60)
    if isinstance(got, BaseException):
        raise got
    server, loop = got
    url = f"http://{address}:{server.port}/"

    def stop() -> None:
        loop.add_callback(loop.stop)
        thread.join(timeout=10)

    if on_start is not None:
        on_start(url)
    if show:
        loop.add_callback(server.show, "/")
    return ServerHandle(url, int(server.port), stop)
