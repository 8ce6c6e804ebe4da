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
from andoyer.validation import integer

__all__ = ["ServerHandle", "app", "serve", "MAX_SESSIONS"]

#: Pages a server keeps open at once (each has its orbits and two worker threads); a page
#: opened past it says so and asks to close one. A page loaded but never connected
#: (no browser behind it) is dropped after :data:`_UNUSED_MS`.
MAX_SESSIONS = 8
_UNUSED_MS = 10_000


# ---------------------------------------------------------------------- entry points
def app(body: RigidBody | None = None, **kwargs: Any) -> Any:
    """The explorer as a Panel object: display it in Jupyter, or ``.servable()``.

    Parameters are those of :class:`Explorer`. In a notebook run
    ``pn.extension()`` first, then ``andoyer.explore.app()`` (or ``andoyer.explore()``)
    as the last expression of a cell.

    Parameters
    ----------
    body : RigidBody, optional
        As in :class:`Explorer` (default: the paper's body).
    **kwargs
        The other parameters of :class:`Explorer`.
    """
    return Explorer(body, **kwargs).panel


@dataclass
class ServerHandle:
    """A running explorer server on a background thread (see :func:`serve`).

    Attributes
    ----------
    url : str
        The page's address (``http://127.0.0.1:<port>/``).
    port : int
        The port it listens on.
    _stop : callable
        Stops the server and its thread (call :meth:`stop`).
    """

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
                    websocket_origin=[f"{address}:{port}", f"localhost:{port}"],
                    unused_session_lifetime_milliseconds=_UNUSED_MS,
                    check_unused_sessions_milliseconds=1_000)


def _capped(factory: Callable[[], Any], max_sessions: int) -> Callable[[], Any]:
    """``factory`` for at most ``max_sessions`` open pages; past it, a page saying so.

    A page's place is freed when Bokeh destroys its session (tab closed, or never
    connected), and with it the page's explorer (:meth:`Explorer.close`).
    """
    live: set[str] = set()
    lock = threading.Lock()

    def page() -> Any:
        doc = pn.state.curdoc
        ctx = doc.session_context if doc is not None else None
        with lock:
            if len(live) >= max_sessions:
                return pn.pane.HTML(
                    f"<h3>andoyer explore: {max_sessions} pages are open, the most this "
                    "server keeps</h3><p>Close another page of the explorer, then reload "
                    "this one (or restart it with a larger <code>--max-sessions</code>)."
                    "</p>", name="andoyer-busy")
            if ctx is not None:
                live.add(ctx.id)
        if doc is not None and ctx is not None:
            doc.on_session_destroyed(lambda c: _forget(live, lock, c.id))
        return factory()
    return page


def _forget(live: set[str], lock: threading.Lock, sid: str) -> None:
    with lock:
        live.discard(sid)


def serve(body: RigidBody | None = None, *, port: int = 0, address: str = "127.0.0.1",
          show: bool = False, threaded: bool = False,
          on_start: Callable[[str], None] | None = None, max_sessions: int = MAX_SESSIONS,
          **kwargs: Any) -> ServerHandle | None:
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
    max_sessions : int, default :data:`MAX_SESSIONS`
        Pages open at once; a page past it says so (what the server does is bounded:
        the plane of a setting is computed once and shared by the pages, a closed page
        frees its explorer).
    **kwargs
        The parameters of :class:`~andoyer.explore.ui.Explorer` (``h``, ``M``,
        ``section``, ``n_crossings``, ``engine``, ``rtol``, ``atol``, ...).
    """
    if isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535:
        raise ValueError(f"port must be an integer in [0, 65535], got {port!r}")
    settings = {k: v for k, v in kwargs.items() if k != "boundary_grid"}
    make_settings(body, **settings)  # bad input fails here, not in every page

    max_sessions = integer("max_sessions", max_sessions, 1)

    def explorer() -> Any:
        return Explorer(body, **kwargs).panel

    factory = _capped(explorer, max_sessions)

    from tornado.ioloop import IOLoop

    if not threaded:
        # A signal (Ctrl-C, SIGTERM, SIGHUP: KeyboardInterrupt) stops the server however
        # far it got: while its sockets open, before its loop runs, or while it serves
        # (a SIGTERM between the two ended the command as "interrupted", exit 130).
        server = None
        try:
            p = port or _free_port(address)
            server = _make_server(factory, p, address, IOLoop(make_current=False))
            url = f"http://{address}:{server.port}/"
            server.start()
            if on_start is not None:
                on_start(url)
            if show:
                server.io_loop.add_callback(server.show, "/")
            server.io_loop.start()
        except KeyboardInterrupt:
            pass
        finally:
            if server is not None:
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
