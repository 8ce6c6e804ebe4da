"""The interactive explorer in the browser: a Panel app over a Bokeh section plane.

The page shows the section plane of :mod:`andoyer.explore.state` (accessible region,
unperturbed separatrices), the seeded orbits' section points as they arrive, the list
of orbits and a side panel for the selected orbit (its initial state in the three
charts, the drift of the integrals, a time plot, its chaos indicator when
:mod:`andoyer.analysis.chaos.lyapunov` provides one), and exports of what is on screen.

Threads
-------
Nothing slow runs on the server's event loop. A click only queues a job on the
session's worker thread (one per browser session, so clicks made while orbits run
wait their turn, in order); the worker solves the seed, integrates the orbit in
stages (:func:`andoyer.explore.orbits.crossing_stages`) and hands each stage back to the
event loop with ``Document.add_next_tick_callback``, the thread-safe way to change a
Bokeh document; only there is the :class:`~andoyer.explore.state.Session` or any
model changed. A second worker computes the side panel (time plot, indicator), so it
never waits behind long orbits. A change of body, h, M or section starts a new
*generation*: queued and running jobs of the old one stop at their next stage and
their results are dropped.

In Jupyter (no server session) the same callbacks run directly on the worker and the
Bokeh panes are pushed with :func:`panel.io.push_notebook`.

Test hook
---------
Bokeh models carry names: ``andoyer-plane`` (figure), ``andoyer-points`` (section
points: ``x, y, orbit, crossing, colour``), ``andoyer-orbits`` (one row per orbit: the
seed, its Euler-Poisson state ``G1 .. gamma3``, status, crossings), ``andoyer-boundary``,
``andoyer-separatrix``, the predicted island chains ``andoyer-chain-centres`` and
``andoyer-chain-separatrices`` (``xs, ys, colour, label``: one line per row) and
``andoyer-chain-points`` (``x, y, kind, marker, colour, label``), ``andoyer-status``
(the visible message; CSS class ``andoyer-level-error`` on errors) and
``andoyer-state`` (a hidden Div holding JSON: settings, generation, pending jobs, the
level of the last message, the number of error messages shown so far and ``chains``, the
number of predicted chains drawn or null). A browser test reads them through
``Bokeh.documents[0].get_model_by_name(...)``.
"""

from __future__ import annotations

import logging
import math
import threading
from functools import partial
from typing import Any

import numpy as np
import panel as pn
from bokeh.events import DoubleTap, Event
from bokeh.models.annotations.labels import Title
from bokeh.models.tickers import FixedTicker

from andoyer.analysis.chaos.registry import INDICATORS
from andoyer.body import PRESETS, RigidBody, make_body
from andoyer.explore.base import (
    ANGLE_LABELS,
    TIME_COLOURS,
    Job,
    number,
    orbit_columns,
    orbit_info_html,
    underlay_image,
)
from andoyer.explore.chains import (
    CHAINS_MAX_ORDER,
    ChainOverlay,
    empty_columns,
    shared_chain_overlay,
)
from andoyer.explore.layout import ExplorerLayout
from andoyer.explore.orbits import (
    EXPLORER_INDICATORS,
    chaos_underlay,
    crossing_stages,
    integral_drifts,
    orbit_indicators,
)
from andoyer.explore.seeds import seed
from andoyer.explore.state import (
    PLANES,
    PlaneView,
    Seed,
    Settings,
    Stage,
    shared_plane_view,
)
from andoyer.integrate import Section

__all__ = ["Explorer"]

def _gyroscope(settings: Settings, y0: Any, span: float) -> Any:
    """The 3D view of the side panel: the orbit's attitude over ``span`` as a Plotly
    figure (:func:`andoyer.plot.space.gyroscope_plotly`)."""
    from andoyer.integrate.orientation import attitude
    from andoyer.plot.space import gyroscope_plotly

    ds = attitude(settings.body, y0, np.linspace(0.0, span, 801), engine=settings.engine,
                  rtol=settings.rtol, atol=settings.atol, progress=False)
    return gyroscope_plotly(ds, frames=80)


#: Integrators already warmed up in this process (one page does it for all).
_WARM: set[tuple[Any, ...]] = set()
_WARM_LOCK = threading.Lock()


def _warm_up(settings: Settings, view: PlaneView) -> None:
    """Compile (or load from heyoka's cache) the engine now, not at the first click: a
    few crossings of the fill's own seed; once per process and integrator."""
    from andoyer.integrate.api import poincare

    key = (settings.body, settings.section, settings.engine, settings.rtol, settings.atol)
    with _WARM_LOCK:
        if key in _WARM:
            return
        poincare(settings.body, view.fill.y0.values[:1], settings.section, 2,
                 engine=settings.engine, rtol=settings.rtol, atol=settings.atol,
                 progress=False)
        _WARM.add(key)

log = logging.getLogger("andoyer.explore")  # the logger of andoyer.explore.base

class Explorer(ExplorerLayout):
    """One explorer page: controls, the section plane, the orbits and the side panel.

    Parameters
    ----------
    body : RigidBody, optional
        Default: the paper's Hess body (``RigidBody.paper()``).
    boundary_grid : int, default 160
        Resolution of the accessible-region grid.
    **settings
        ``h, M, section, n_crossings, engine, root, rtol, atol`` of
        :func:`andoyer.explore.state.make_settings` (default h: the energy of
        ``andoyer section``; section ``"theta2=0"``; 500 crossings).

    Attributes
    ----------
    panel : panel.viewable.Viewable
        The page (display it in Jupyter, or ``.servable()``).
    session : Session
        The orbits on screen.
    """

    def __init__(self, body: RigidBody | None = None, *, boundary_grid: int = 160,
                 **settings: Any) -> None:
        super().__init__(body, boundary_grid=boundary_grid, **settings)
        self._last_tap: tuple[float, float] | None = None
        self._side_token = 0
        self._build_plane()
        self._build_controls()
        self._build_side()
        # A wrapping row: where the window is too narrow for the three columns
        # (300 + 670 + 370 px), the side panel moves below instead of running out of the
        # window (at 1000 px it stood 330 px beyond the right edge).
        self.panel = pn.Row(self.controls, self.main, self.side_panel,
                            sizing_mode="stretch_width", styles={"flex-wrap": "wrap"})
        if self._doc is not None and self._doc.session_context is not None:
            self._doc.on_session_destroyed(lambda _ctx: self.close())
        self._submit_view(self.settings, warm_up=True)
        self._status("computing the accessible region …", "busy")

    # ------------------------------------------------------------------ the plane
    def _submit_view(self, settings: Settings, warm_up: bool = False) -> None:
        gen = self._generation
        with self._lock:
            self._pending += 1

        def job() -> None:
            try:
                view = shared_plane_view(settings, self.boundary_grid)
                self._schedule(lambda: self._show_view(gen, view))
                if warm_up:
                    _warm_up(settings, view)
            finally:
                self._schedule(self._job_done)
        self._background(self._work, job)

    def _job_done(self) -> None:
        with self._lock:
            self._pending = max(0, self._pending - 1)
        self._publish_state()

    def _show_view(self, gen: int, view: PlaneView) -> None:
        if gen != self._generation:
            return
        self.view = view
        s = view.settings
        (x0, x1), (y0, y1) = view.x_range, view.y_range
        acc = view.accessible.T  # (plane_y, plane_x): rows are y
        rgba = np.where(acc, np.uint32(0), np.uint32(0xFFE6E6E6)).astype(np.uint32)
        self.region.data = {"image": [rgba], "x": [x0], "y": [y0], "dw": [x1 - x0],
                            "dh": [y1 - y0]}
        self.boundary.data = {"x": view.boundary_x, "y": view.boundary_y}
        xs: list[np.ndarray] = []
        ys: list[np.ndarray] = []
        for x, y in view.separatrices:
            xs += [x, np.array([np.nan])]
            ys += [y, np.array([np.nan])]
        self.separatrix.data = {"x": np.concatenate(xs) if xs else np.empty(0),
                                "y": np.concatenate(ys) if ys else np.empty(0)}
        pad = 0.02 * (y1 - y0)
        self.fig.x_range.update(start=x0, end=x1, reset_start=x0, reset_end=x1)
        self.fig.y_range.update(start=y0 - pad, end=y1 + pad, reset_start=y0 - pad,
                                reset_end=y1 + pad)
        self.fig.xaxis.axis_label = s.plane.text[0]
        self.fig.yaxis.axis_label = s.plane.text[1]
        k = np.arange(math.ceil(x0 / (math.pi / 2) - 1e-9),
                      math.floor(x1 / (math.pi / 2) + 1e-9) + 1)
        ticks = [float(v * math.pi / 2) for v in k]
        self.fig.xaxis.ticker = FixedTicker(ticks=ticks)
        self.fig.xaxis.major_label_overrides = {
            t: ANGLE_LABELS.get(int(v), f"{int(v)}π/2") for t, v in zip(ticks, k,
                                                                          strict=True)}
        arrow = {1: "+", -1: "−", 0: "±"}[s.section.direction]
        title = self.fig.title
        if isinstance(title, Title):
            title.text = (f"{s.body.name or 'body'}: h = {s.h:.10g}, M = {s.M:.6g}, "
                          f"{s.plane.text[3]} = {s.section.value:.6g} ({arrow})")
        self._status("ready: click inside the boundary to seed an orbit "
                     f"({s.plane.text[2]} is solved from H = h)", "info")
        if self.w_underlay.value:
            self._request_underlay()
        if self.w_chains.value:
            self._request_chains()

    # ------------------------------------------------------------------ clicks
    def _on_tap(self, event: Event) -> None:
        x, y = getattr(event, "x", None), getattr(event, "y", None)
        sx, sy = getattr(event, "sx", None), getattr(event, "sy", None)
        if x is None or y is None:
            return
        if isinstance(event, DoubleTap) and self._last_tap is not None and sx is not None \
                and sy is not None and math.dist(self._last_tap, (sx, sy)) <= 6.0:
            return  # the second click of a double click: one seed, not two
        if sx is not None and sy is not None:
            self._last_tap = (float(sx), float(sy))
        self._guard(lambda: self._seed_click(float(x), float(y)))

    def _seed_click(self, x: float, y: float) -> None:
        """Queue an orbit through the plane point ``(x, y)`` (also the API for tests)."""
        job = Job(self._generation, self._epoch, self.settings)
        with self._lock:
            self._pending += 1
            ahead = self._pending - 1
        p = job.settings.plane
        self._status(f"seeding at ({p.text[0]}, {p.text[1]}) = ({x:.6g}, {y:.6g})"
                     + (f"; {ahead} job(s) ahead in the queue" if ahead else ""), "busy")

        def work() -> None:
            try:
                self._run_click(job, x, y)
            finally:
                self._schedule(self._job_done)
        self._background(self._work, work)

    def _live(self, job: Job) -> bool:
        return job.generation == self._generation and job.epoch == self._epoch

    def _run_click(self, job: Job, x: float, y: float) -> None:
        if not self._live(job):
            return
        seeds = seed(job.settings, x, y)
        ids = [self.session.new_id() for _ in seeds]
        self._schedule(lambda: self._add_orbits(job, ids, seeds))
        for oid, sd in zip(ids, seeds, strict=True):
            for stage in crossing_stages(job.settings, sd.y0):
                if not self._live(job) or oid in self.session.removed:
                    return
                self._schedule(partial(self._add_stage, job, oid, stage))

    def _add_orbits(self, job: Job, ids: list[int], seeds: list[Seed]) -> None:
        if not self._live(job):
            return
        s = job.settings
        notes = []
        for oid, sd in zip(ids, seeds, strict=True):
            self.session.add(sd, job.settings, orbit_id=oid)
            if not sd.crosses_in(s.section.direction):
                notes.append(f"orbit {oid} crosses {s.plane.text[3]} = "
                             f"{s.section.value:.4g} at the click in the other direction: "
                             "its section points do not start at the click")
        if seeds[0].n_roots > 1 and s.root != "all":
            notes.append(f"{seeds[0].n_roots} values of {s.plane.text[2]} solve H = h "
                         f"here; seeded the {s.root} (choose 'all' to seed every one)")
        self._refresh_orbit_table()
        self._select(ids[-1])
        if notes:
            self._status("; ".join(notes), "warning")

    def _add_stage(self, job: Job, oid: int, stage: Stage) -> None:
        if not self._live(job) or not self.session.extend(oid, stage):
            return
        o = self.session.orbits[oid]
        self.points.stream({"x": stage.x, "y": stage.y, "orbit": np.full(stage.x.size, oid),
                            "crossing": np.arange(stage.start, stage.stop),
                            "colour": [o.colour] * stage.x.size})
        self._refresh_orbit_table()
        if oid == self._selected:
            self._show_info()
        if stage.done:
            drift = integral_drifts(stage.ds, o.settings.h, o.settings.M, o.settings.body)
            short = (f" (t_max = {1000.0 * o.settings.n_crossings:g} reached first)"
                     if stage.stop < o.settings.n_crossings else "")
            self._status(f"orbit {oid}: {stage.stop} crossings{short}; max drift of H "
                         f"{drift['H']:.1e}", "info")
        else:
            self._status(f"orbit {oid}: {stage.stop} of {o.settings.n_crossings} crossings …",
                         "busy")

    def _refresh_orbit_table(self) -> None:
        """Push the session's orbits to the table: a patch of the cells that changed
        (status, crossings), or new columns when orbits came or went. The page redraws
        the table at each change (``layout.REDRAW_TABLE``): Bokeh's DataTable alone kept showing
        "queued" for an orbit that was done, until the next click added a row."""
        new = orbit_columns(self.session)
        old = self.orbits.data
        if list(old.get("id", [])) == new["id"]:
            patches = {k: [(i, v) for i, (was, v) in enumerate(zip(old[k], new[k],
                                                                  strict=True)) if was != v]
                       for k in new}
            patches = {k: p for k, p in patches.items() if p}
            if patches:
                self.orbits.patch(patches)
        else:
            self.orbits.data = new
        ids = list(self.session.orbits)
        want = [ids.index(self._selected)] if self._selected in ids else []
        if list(self.orbits.selected.indices) != want:
            self.orbits.selected.indices = want
        self._publish_state()

    def _refresh_points(self) -> None:
        self.points.data = self.session.points()

    def _select(self, oid: int | None) -> None:
        self._selected = oid
        ids = list(self.session.orbits)
        want = [ids.index(oid)] if oid in ids else []
        if list(self.orbits.selected.indices) != want:
            self.orbits.selected.indices = want
        self._show_info()
        self._request_side()
        self._publish_state()

    def _on_select(self, _attr: str, _old: Any, new: list[int]) -> None:
        ids = list(self.session.orbits)
        oid = ids[new[0]] if new and new[0] < len(ids) else None
        if oid != self._selected:
            self._guard(lambda: self._select(oid))

    def _clear_orbits(self) -> None:
        self._epoch += 1
        self.session.clear()
        self._refresh_points()
        self._refresh_orbit_table()
        self._select(None)
        self._status("all orbits cleared", "info")

    def _remove_selected(self) -> None:
        if self._selected is None:
            self._status("select an orbit in the table first", "warning")
            return
        oid = self._selected
        self.session.remove(oid)
        self._refresh_points()
        self._refresh_orbit_table()
        self._select(None)
        self._status(f"orbit {oid} removed", "info")

    # ------------------------------------------------------------------ controls
    def _sync_body_widgets(self) -> None:
        mode = self.w_body.value
        flags = PRESETS[mode].flags
        for name, wid in (("A", self.w_A), ("B", self.w_B), ("C", self.w_C)):
            wid.disabled = name not in flags
        self.w_r.disabled = "r" not in flags

    def _settings_from_widgets(self) -> Settings:
        mode = self.w_body.value
        mu = number(self.w_mu)
        flags = PRESETS[mode].flags
        values: dict[str, Any] = {"mu": mu}
        if "A" in flags:
            values.update(A=number(self.w_A), B=number(self.w_B), C=number(self.w_C))
        if "r" in flags:
            from andoyer.validation import floats

            values["r"] = tuple(floats(self.w_r.value or "", 3, "r = (e1, e2, e3)"))
        body = make_body(mode, **values)
        section = Section(self.w_section.value, number(self.w_value),
                          self.w_direction.value)
        engine = None if self.w_engine.value == "default" else self.w_engine.value
        return Settings(body, number(self.w_h), number(self.w_M), section,
                        int(number(self.w_crossings)), engine, self.w_root.value)

    def _on_control(self, event: Any) -> None:
        self._guard(lambda: self._apply_controls(event))

    def _apply_controls(self, event: Any) -> None:
        if event.obj is self.w_body:
            self._sync_body_widgets()
            if event.new == "paper":
                paper = RigidBody.paper()
                self.w_A.value, self.w_B.value, self.w_C.value = paper.A, paper.B, paper.C
        try:
            new = self._settings_from_widgets()
        except ValueError as exc:
            self._status(f"{exc} (the page keeps the previous settings)", "error")
            return
        old = self.settings
        same_plane = (new.body, new.h, new.M, new.section) == (old.body, old.h, old.M,
                                                                 old.section)
        self.settings = new
        if same_plane and self.view is not None:
            self.session.settings = new
            self._status("new clicks use the changed settings; the orbits on screen keep "
                         "theirs", "info")
            return
        if event.obj is self.w_section:
            coords = [PLANES[new.section.coord].x, PLANES[new.section.coord].y]
            self.w_coords.value = coords
        self._generation += 1
        n = len(self.session.orbits)
        self.session.clear(new)
        self.view = None
        self._refresh_points()
        self._refresh_orbit_table()
        self._select(None)
        self.region.data = {"image": [], "x": [], "y": [], "dw": [], "dh": []}
        self.boundary.data = {"x": [], "y": []}
        self.separatrix.data = {"x": [], "y": []}
        self._show_chains(None)
        self._status("computing the accessible region …"
                     + (f" ({n} orbit(s) of the previous level cleared)" if n else ""), "busy")
        self._submit_view(new)

    # ------------------------------------------------------------------ side panel
    def _show_info(self) -> None:
        o = self.session.orbits.get(self._selected) if self._selected is not None else None
        self.info.object = "<i>no orbit selected</i>" if o is None else orbit_info_html(o)

    def _request_side(self) -> None:
        self._side_token += 1
        token = self._side_token
        span = number(self.w_span)
        if not (math.isfinite(span) and span > 0):
            raise ValueError(f"time span must be a positive number, got {span!r}")
        o = self.session.orbits.get(self._selected) if self._selected is not None else None
        if o is None:
            self.series.data = {"xs": [], "ys": [], "name": [], "colour": []}
            self.gyroscope.object = None
            return
        coords = list(self.w_coords.value)
        settings, y0 = o.settings, o.seed.y0

        def job() -> None:
            from andoyer.integrate.api import propagate

            if token != self._side_token:
                return
            t = np.linspace(0.0, float(span), 2001)
            ds = propagate(settings.body, y0, t, engine=settings.engine, rtol=settings.rtol,
                           atol=settings.atol, progress=False).isel(orbit=0)
            shown = [c for c in coords if c in ds]
            data = {"xs": [t for _ in shown],
                    "ys": [np.asarray(ds[c].values, dtype=float) for c in shown],
                    "name": shown, "colour": [TIME_COLOURS[k % len(TIME_COLOURS)]
                                              for k in range(len(shown))]}
            missing = sorted(set(coords) - set(shown))
            if token != self._side_token:
                return
            gyro = _gyroscope(settings, y0, float(span))

            def show() -> None:
                if token == self._side_token:
                    self.series.data = data
                    self.gyroscope.object = gyro
                    if missing:
                        self._status(f"no {', '.join(missing)} for this body (the Hess "
                                     "chart needs e3 = 0)", "warning")
            self._schedule(show)
        self._background(self._side, job)

    def _request_indicator(self) -> None:
        o = self.session.orbits.get(self._selected) if self._selected is not None else None
        if self._chaos is None:
            self._status("FLI/MEGNO need andoyer.analysis.chaos.lyapunov", "warning")
            return
        if o is None:
            self._status("select an orbit in the table first", "warning")
            return
        t_end = number(self.w_indicator_t)
        settings, y0, oid = o.settings, o.seed.y0, o.id

        def job() -> None:
            ind = orbit_indicators(settings, y0, t_end)
            text = f"<b>orbit {oid}</b>, t = {t_end:g}: " + ", ".join(
                f"{INDICATORS[k].text} = {ind[k]:.4g}"
                + (f" ({INDICATORS[k].reading})" if INDICATORS[k].reading else "")
                for k in EXPLORER_INDICATORS)

            def show() -> None:
                self.indicator.object = text
            self._schedule(show)
        self.indicator.object = "computing …"
        self._background(self._side, job)

    def _on_underlay(self, _event: Any) -> None:
        self._guard(self._request_underlay)

    def _request_underlay(self) -> None:
        if not self.w_underlay.value:
            if self.view is not None:
                self._show_view(self._generation, self.view)
            return
        if self._chaos is None:
            self._status("the chaos-map underlay needs andoyer.analysis.chaos.lyapunov",
                         "warning")
            return
        view, gen = self.view, self._generation
        if view is None:
            return  # drawn when the plane is ready (_show_view asks again)

        def job() -> None:
            img = underlay_image(chaos_underlay(view.settings, view))

            def show() -> None:
                if gen == self._generation and self.w_underlay.value:
                    self.region.data = img
                    self._status("chaos map drawn: FLI from pale (regular) to red "
                                 "(chaotic)", "info")
            self._schedule(show)
        self._status("computing the chaos map …", "busy")
        self._background(self._side, job)

    # ------------------------------------------------------------------ predicted chains
    def _on_chains(self, _event: Any) -> None:
        self._guard(self._request_chains)

    def _show_chains(self, overlay: ChainOverlay | None) -> None:
        """Draw ``overlay`` (None: remove the chains) on the plane."""
        cols = empty_columns() if overlay is None else overlay.columns()
        self.chain_centres.data = cols["centres"]
        self.chain_separatrices.data = cols["separatrices"]
        self.chain_points.data = cols["points"]
        self._chains_drawn = None if overlay is None else overlay.n_chains
        self._chains_key = None if overlay is None else overlay.key
        self._chains_overlay = overlay
        self._publish_state()

    def _request_chains(self) -> None:
        """Draw the predicted chains of the plane on screen (issue 28), computed on the
        side worker (:func:`andoyer.explore.chains.shared_chain_overlay`, cached per body,
        level, section and order); switched off, remove them."""
        from andoyer.validation import integer

        self._chain_token += 1
        token = self._chain_token
        if not self.w_chains.value:
            self._show_chains(None)
            return
        order = integer("chains up to order p + q", self.w_chain_order.value, 2,
                        CHAINS_MAX_ORDER)
        view, gen = self.view, self._generation
        if view is None:
            return  # drawn when the plane is ready (_show_view asks again)
        s = view.settings
        if self._chains_key == (s.body, s.h, s.M, s.section, order):
            return  # on screen already

        def job() -> None:
            if token != self._chain_token:
                return
            try:
                overlay = shared_chain_overlay(s, order)
            except ValueError as exc:
                raise ValueError(f"predicted chains: {exc}") from exc

            def show() -> None:
                if token == self._chain_token and gen == self._generation \
                        and self.w_chains.value:
                    self._show_chains(overlay)
                    self._status(overlay.message(), "info")
            self._schedule(show)
        self._show_chains(None)
        self._status(f"computing the predicted chains (p + q ≤ {order}) …", "busy")
        self._background(self._side, job)
