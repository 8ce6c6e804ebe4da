"""The explorer's machinery under the page: threads, messages and the test hook.

:class:`ExplorerBase` holds what :class:`andoyer.explore.ui.Explorer` does besides
drawing: the two worker threads, the hand-over of results to the Bokeh event loop
(see *Threads* in :mod:`andoyer.explore.ui`), the status line and the hidden JSON
test hook ``andoyer-state``. The widget helpers and the colour tables of the page are
here too, so that the page module holds only its layout and callbacks.
"""

from __future__ import annotations

import collections
import html
import importlib
import io
import json
import logging
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import Any

import numpy as np
import panel as pn

from andoyer.body import PAPER, RigidBody
from andoyer.charts.integrals import INTEGRALS
from andoyer.explore.orbits import integral_drifts
from andoyer.explore.seeds import initial_charts
from andoyer.explore.state import (
    Orbit,
    OutsideRegionError,
    PlaneView,
    Session,
    Settings,
    make_settings,
)

__all__ = ["ExplorerBase", "Job", "BODIES", "SECTIONS", "DIRECTIONS", "LEVEL_COLOURS",
           "TIME_COORDS", "TIME_COLOURS", "ANGLE_LABELS", "chaos_module", "widget", "number",
           "underlay_image", "orbit_info_html", "orbit_columns"]

log = logging.getLogger("andoyer.explore")

#: The explorer's body menu: label -> preset (:data:`andoyer.body.PRESETS`).
BODIES = {f"paper (Hess, A={PAPER['A']:g}, B={PAPER['B']:g}, C={PAPER['C']:g})": "paper",
          "Hess (A > C > B)": "hess", "general (A, B, C, r)": "general"}
SECTIONS = {"θ2 = const: plane (θ1, J1)": "theta2", "g = const: plane (l, L)": "g"}
DIRECTIONS = {"increasing (+)": 1, "decreasing (−)": -1, "both": 0}
LEVEL_COLOURS = {"info": "#1b5e20", "busy": "#0d47a1", "warning": "#8a5a00",
                  "error": "#b71c1c"}
TIME_COORDS = ("theta1", "theta2", "J1", "J2", "l_angle", "g_angle", "L_action",
                "G_action", "G1", "G2", "G3", "gamma1", "gamma2", "gamma3", "H")
TIME_COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#17becf")
ANGLE_LABELS = {0: "0", 1: "π/2", 2: "π", 3: "3π/2", 4: "2π", 5: "5π/2", 6: "3π",
                 7: "7π/2", 8: "4π"}


def chaos_module() -> Any | None:
    """:mod:`andoyer.analysis.chaos.lyapunov` (on heyoka where installed, else on taylor), or None
    if it cannot be imported: the indicator controls are then disabled."""
    try:  # the module by its full name
        return importlib.import_module("andoyer.analysis.chaos.lyapunov")
    except ImportError:  # pragma: no cover - chaos needs no optional package
        return None


@dataclass(frozen=True)
class Job:
    """One piece of work queued on a page's worker thread, and what it belongs to.

    Attributes
    ----------
    generation : int
        The plane's settings it belongs to (a change of body, h, M or section starts a
        new one; older jobs are dropped).
    epoch : int
        "Clear all" presses before it (a job of an older epoch is dropped).
    settings : Settings
        The settings it runs with.
    """

    generation: int   # the plane's settings it belongs to
    epoch: int        # "clear all" presses before it
    settings: Settings


class ExplorerBase:
    """Threads, messages and the test hook of an explorer page (no layout).

    Subclasses build the Bokeh models ``status``, ``state_div``, ``plane_pane`` and
    ``time_pane`` before the first message.

    Parameters
    ----------
    body : RigidBody, optional
        Default: the paper's Hess body (``RigidBody.paper()``).
    boundary_grid : int, default 160
        Resolution of the accessible-region grid.
    **settings
        ``h, M, section, n_crossings, engine, root, rtol, atol`` of
        :func:`andoyer.explore.state.make_settings`.
    """

    status: Any
    state_div: Any
    plane_pane: Any
    time_pane: Any

    def __init__(self, body: RigidBody | None = None, *, boundary_grid: int = 160,
                 **settings: Any) -> None:
        self.settings = make_settings(body, **settings)
        self.session = Session(self.settings)
        self.view: PlaneView | None = None
        self.boundary_grid = int(boundary_grid)
        self._generation = 0
        self._epoch = 0
        self._level = "info"
        self._errors = 0  # error messages shown so far (the test hook reports it)
        self._pending = 0
        self._selected: int | None = None
        self._lock = threading.RLock()
        self._queue: collections.deque[Callable[[], None]] = collections.deque()
        self._queue_lock = threading.Lock()
        self._closed = False
        self._doc = pn.state.curdoc
        self._work = ThreadPoolExecutor(1, thread_name_prefix="andoyer-explore")
        self._side = ThreadPoolExecutor(1, thread_name_prefix="andoyer-explore-side")
        self._chaos = chaos_module()
        # The predicted chains on the plane (issue 28): their number once drawn, None while
        # switched off or not drawn yet; the overlay's key (body, h, M, section, order).
        self._chains_drawn: int | None = None
        self._chains_key: tuple[Any, ...] | None = None
        self._chains_overlay: Any = None   # the ChainOverlay on screen (for the PNG)
        self._chain_token = 0

    # ------------------------------------------------------------------ threads
    def _schedule(self, fn: Callable[[], None]) -> None:
        """Run ``fn`` on the event loop (server), or now under the lock (Jupyter)."""
        if self._closed:
            return
        doc = self._doc
        if doc is not None and doc.session_context is not None:
            # Our own FIFO: Bokeh's next-tick callbacks added from two threads may run out
            # of order (Document.unhold clears the hold before it replays the held
            # "callback added" events, so a callback added meanwhile from a worker thread
            # overtakes them): an orbit's first stage then ran before the callback that
            # adds the orbit, was dropped, and the next stage was refused ("stage starts
            # at crossing 100, but 0 points are shown": seen once in CI). Each tick drains
            # the queue in the order the callbacks were scheduled, whatever tick runs first.
            with self._queue_lock:
                self._queue.append(fn)
            try:
                doc.add_next_tick_callback(self._drain)
            except Exception:  # noqa: BLE001 - the session is gone: nothing to update
                self.close()
            return
        with self._lock:
            self._guard(fn)
        try:  # a notebook: send the changed Bokeh models through Panel's comms
            pn.io.push_notebook(self.plane_pane, self.time_pane)
        except Exception:  # noqa: BLE001 - no notebook comm (plain Python): nothing to push
            pass

    def _drain(self) -> None:
        """Run the scheduled callbacks, oldest first (on the event loop)."""
        while True:
            with self._queue_lock:
                if not self._queue:
                    return
                fn = self._queue.popleft()
            self._guard(fn)

    def _guard(self, fn: Callable[[], None]) -> None:
        """Run a UI callback; any error becomes a visible message, never a dead page."""
        try:
            fn()
        except ValueError as exc:
            self._status(str(exc), "error")
        except Exception as exc:  # noqa: BLE001 - shown to the user, logged in full
            log.exception("andoyer explore: callback failed")
            self._status(f"{type(exc).__name__}: {exc}", "error")

    def _background(self, pool: ThreadPoolExecutor, fn: Callable[[], None]) -> None:
        """Run ``fn`` on a worker; its exceptions become messages on the page."""
        def run() -> None:
            try:
                fn()
            except OutsideRegionError as exc:
                msg = str(exc)
                self._schedule(lambda: self._status(msg, "warning"))
            except ValueError as exc:
                msg = str(exc)
                self._schedule(lambda: self._status(msg, "error"))
            except Exception as exc:  # noqa: BLE001 - shown to the user, logged in full
                log.exception("andoyer explore: background job failed")
                msg = f"{type(exc).__name__}: {exc}"
                self._schedule(lambda: self._status(msg, "error"))
        if not self._closed:
            pool.submit(run)

    def wait(self, timeout: float | None = 60.0) -> None:
        """Block until the work queued so far is done (for scripts, notebooks, tests)."""
        for pool in (self._work, self._side, self._work):
            if not self._closed:
                pool.submit(lambda: None).result(timeout)

    def close(self) -> None:
        """Stop the workers (queued jobs are dropped, a running stage finishes)."""
        self._closed = True
        self._generation += 1
        self._work.shutdown(wait=False, cancel_futures=True)
        self._side.shutdown(wait=False, cancel_futures=True)

    # ------------------------------------------------------------------ status
    def _status(self, text: str, level: str = "info") -> None:
        self.status.text = (f'<div style="color:{LEVEL_COLOURS[level]};font-size:110%;'
                            f'padding:2px 4px"><b>{level}</b>: {html.escape(text)}</div>')
        self.status.css_classes = ["andoyer-status", f"andoyer-level-{level}"]
        self._level = level
        self._errors += level == "error"
        self._publish_state()

    def _publish_state(self) -> None:
        s = self.settings
        state = {"generation": self._generation, "pending": self._pending,
                 "h": s.h, "M": s.M, "section": f"{s.section.coord}={s.section.value!r}",
                 "direction": s.section.direction, "n_crossings": s.n_crossings,
                 "engine": s.engine, "body": s.body.attrs(), "view_ready":
                 self.view is not None and self.view.settings == s,
                 "n_orbits": len(self.session.orbits), "selected": self._selected,
                 "level": self._level, "errors": self._errors,
                 "chains": self._chains_drawn}
        self.state_div.text = json.dumps(state)

    # ------------------------------------------------------------------ exports
    def netcdf(self) -> bytes:
        """NetCDF bytes of the orbits on screen (:func:`~andoyer.explore.export.orbits_dataset`)."""
        from andoyer.explore.export import netcdf_bytes, orbits_dataset

        return netcdf_bytes(orbits_dataset(self.session))

    def png(self) -> bytes:
        """PNG bytes of the plane as on screen (:func:`~andoyer.explore.export.plane_figure`)."""
        from andoyer.explore.export import orbits_dataset, plane_figure, png_bytes

        if self.view is None:
            raise ValueError("the plane is not ready yet: wait for the accessible region")
        return png_bytes(plane_figure(orbits_dataset(self.session), self.view,
                                      chains=self._chains_overlay))

    def _download(self, make: Callable[[], bytes]) -> io.BytesIO:
        try:
            data = make()
        except Exception as exc:  # noqa: BLE001 - a message on the page, not a dead button
            log.exception("andoyer explore: export failed")
            self._status(f"export failed: {exc}", "error")
            data = b""
        return io.BytesIO(data)

    def _download_netcdf(self) -> io.BytesIO:
        return self._download(self.netcdf)

    def _download_png(self) -> io.BytesIO:
        return self._download(self.png)


def widget(cls: Any, label: str, *, button: str | None = None, **kwargs: Any) -> Any:
    """A Panel widget of class ``cls`` with a label (``label=`` since Panel 1.9, ``name=``
    before).

    Parameters
    ----------
    label : str
        Its label.
    button : str, optional
        The button type (``"primary"``, ``"warning"``, ...) of a button widget.
    **kwargs
        Passed to the widget.
    """
    kwargs["label" if "label" in cls.param else "name"] = label
    if button is not None:
        kwargs["color" if "color" in cls.param else "button_type"] = button
    return cls(**kwargs)


def number(widget: Any) -> float:
    """A numeric widget's value, or a ValueError naming the empty field.

    Parameters
    ----------
    widget : panel.widgets.Widget
        A numeric input widget.
    """
    v = widget.value
    if v is None:
        label = getattr(widget, "label", "") or widget.name
        raise ValueError(f"{label} is empty: type a number")
    return float(v)


def underlay_image(ds: Any) -> dict[str, list[Any]]:
    """The FLI of a :func:`chaos_underlay` map as an RGBA image in the FLI's colours
    (:data:`andoyer.plot.style.SCALES`, as in the report: pale regular, dark chaotic).

    Parameters
    ----------
    ds : xarray.Dataset
        A :func:`~andoyer.explore.orbits.chaos_underlay` map.
    """
    import matplotlib as mpl

    from andoyer.plot.style import colour_scale

    z = np.asarray(ds.fli.values, dtype=float)  # dims (plane y, plane x): rows are y
    ok = np.isfinite(z)
    lo, hi = np.nanpercentile(z, [5, 95]) if ok.any() else (0.0, 1.0)
    u = np.clip((np.where(ok, z, lo) - lo) / max(hi - lo, 1e-300), 0.0, 1.0)
    rgba = (mpl.colormaps[colour_scale("fli").cmap](u) * 255).astype(np.uint32)
    r, g, b = rgba[..., 0], rgba[..., 1], rgba[..., 2]
    alpha = np.where(ok, 150, 0).astype(np.uint32)  # the orbits' points stay visible
    img = (alpha << 24) | (b << 16) | (g << 8) | r
    xs = np.asarray(ds[ds.fli.dims[1]].values, dtype=float)
    ys = np.asarray(ds[ds.fli.dims[0]].values, dtype=float)
    dx, dy = xs[1] - xs[0], ys[1] - ys[0]  # cell centres
    return {"image": [img], "x": [xs[0] - dx / 2], "y": [ys[0] - dy / 2],
            "dw": [xs[-1] - xs[0] + dx], "dh": [ys[-1] - ys[0] + dy]}


def orbit_info_html(o: Orbit) -> str:
    """The side panel's description of an orbit: its seed, its initial state in the
    three charts and the drift of the integrals at its section points (HTML).

    Parameters
    ----------
    o : Orbit
        The orbit described.
    """
    rows = []
    for chart, values in initial_charts(o.settings, o.seed.y0).items():
        cells = "".join(f"<tr><td>{html.escape(k)}</td><td style='text-align:right'>"
                        f"{v:.12g}</td></tr>" for k, v in values.items())
        rows.append(f"<b>{chart}</b><table style='font-size:85%'>{cells}</table>")
    drift = ""
    if o.ds is not None:
        d = integral_drifts(o.ds, o.settings.h, o.settings.M, o.settings.body)
        drift = "<b>drift at the section points</b>" + "".join(
            f"<br>{html.escape(INTEGRALS[k].symbol)}: |Δ|/{html.escape(INTEGRALS[k].scale_name)}"
            f" ≤ {v:.1e}" for k, v in d.items())
    return (f"<div><b style='color:{o.colour}'>● orbit {o.id}</b> "
            f"({o.status}, {o.x.size} crossings; {o.settings.plane.text[2]}"
            f" = {o.seed.action:.12g}, solution {o.seed.root_index + 1} of "
            f"{o.seed.n_roots})<br>{''.join(rows)}{drift}</div>")


def orbit_columns(session: Session) -> dict[str, list[Any]]:
    """The columns of the orbit table (model ``andoyer-orbits``): one row per orbit.

    Parameters
    ----------
    session : Session
        The orbits on screen.
    """
    state = ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")
    cols: dict[str, list[Any]] = {k: [] for k in (
        "id", "colour", "seed_x", "seed_y", "action", "crossings", "status", *state)}
    for o in session.orbits.values():
        cols["id"].append(o.id)
        cols["colour"].append(o.colour)
        cols["seed_x"].append(o.seed.x)
        cols["seed_y"].append(o.seed.y)
        cols["action"].append(o.seed.action)
        cols["crossings"].append(int(o.x.size))
        cols["status"].append(o.status)
        for k, name in enumerate(state):
            cols[name].append(float(o.seed.y0[k]))
    return cols
