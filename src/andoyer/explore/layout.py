"""The explorer page's layout: the Bokeh section plane and time plot, the controls'
column and the side panel (:class:`ExplorerLayout`), built once per page. What the
widgets do -- clicks, controls, the side panel's jobs -- is
:class:`andoyer.explore.ui.Explorer`'s; the threads and messages are
:class:`andoyer.explore.base.ExplorerBase`'s.
"""

from __future__ import annotations

import math
from typing import Any

import panel as pn
from bokeh.events import DoubleTap, Event, Tap
from bokeh.layouts import column
from bokeh.models.callbacks import CustomJS
from bokeh.models.ranges import Range1d
from bokeh.models.sources import ColumnDataSource
from bokeh.models.widgets.markups import Div
from bokeh.models.widgets.tables import (
    DataTable,
    HTMLTemplateFormatter,
    NumberFormatter,
    TableColumn,
)
from bokeh.plotting import figure

from andoyer.explore.base import (
    BODIES,
    DIRECTIONS,
    SECTIONS,
    TIME_COORDS,
    ExplorerBase,
    orbit_columns,
    widget,
)
from andoyer.explore.chains import CHAINS_MAX_ORDER, CHAINS_ORDER, empty_columns
from andoyer.explore.orbits import (
    UNDERLAY_N,
    UNDERLAY_T_END,
)
from andoyer.integrate.engines import ENGINES

__all__ = ["ExplorerLayout", "PlotlyWithFrames", "CONTROLS_WIDTH", "REDRAW_TABLE"]

#: Width of the controls' column (px).
CONTROLS_WIDTH = 300

#: JavaScript: redraw the orbit table's cells (``table``: the DataTable model).
REDRAW_TABLE = """
for (const view of Bokeh.index.all_views()) {
  if (view.model === table && typeof view.updateGrid === "function") view.updateGrid()
}
"""





class PlotlyWithFrames(pn.pane.Plotly):
    """Panel's Plotly pane with the figure's animation frames: Panel 1.9's
    ``_plotly_json_wrapper`` sends data and layout only, so a figure's frames never reach
    the browser (its model has a ``frames`` property that nothing fills).

    Parameters
    ----------
    object : plotly.graph_objects.Figure, optional
        The figure, with its frames.
    **params
        Panel's pane parameters (``sizing_mode``, ``width``, ...).
    """

    @classmethod
    def _plotly_json_wrapper(cls, fig: Any) -> dict[str, Any]:
        json: dict[str, Any] = super()._plotly_json_wrapper(fig)
        json["frames"] = [frame.to_plotly_json() for frame in getattr(fig, "frames", ())]
        return json


class ExplorerLayout(ExplorerBase):
    """The models of one explorer page (no behaviour): :meth:`_build_plane`,
    :meth:`_build_controls` and :meth:`_build_side` create them and connect them to the
    page's callbacks, which :class:`~andoyer.explore.ui.Explorer` implements.

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

    # -- the page's callbacks (implemented by Explorer) -----------------------------
    def _on_tap(self, event: Event) -> None:
        raise NotImplementedError

    def _on_select(self, _attr: str, _old: Any, new: list[int]) -> None:
        raise NotImplementedError

    def _on_control(self, event: Any) -> None:
        raise NotImplementedError

    def _on_underlay(self, _event: Any) -> None:
        raise NotImplementedError

    def _on_chains(self, _event: Any) -> None:
        raise NotImplementedError

    def _clear_orbits(self) -> None:
        raise NotImplementedError

    def _remove_selected(self) -> None:
        raise NotImplementedError

    def _sync_body_widgets(self) -> None:
        raise NotImplementedError

    def _request_side(self) -> None:
        raise NotImplementedError

    def _request_indicator(self) -> None:
        raise NotImplementedError

    # -- the models ----------------------------------------------------------------

    def _build_plane(self) -> None:
        s = self.settings
        self.points = ColumnDataSource(
            {"x": [], "y": [], "orbit": [], "crossing": [], "colour": []},
            name="andoyer-points")
        self.orbits = ColumnDataSource(orbit_columns(self.session), name="andoyer-orbits")
        self.boundary = ColumnDataSource({"x": [], "y": []}, name="andoyer-boundary")
        self.separatrix = ColumnDataSource({"x": [], "y": []}, name="andoyer-separatrix")
        self.region = ColumnDataSource({"image": [], "x": [], "y": [], "dw": [], "dh": []},
                                       name="andoyer-region")
        fig = figure(name="andoyer-plane", width=660, height=520,
                     x_range=Range1d(start=0.0, end=2.0 * math.pi),
                     y_range=Range1d(start=0.0, end=1.0),
                     tools="pan,wheel_zoom,box_zoom,reset", toolbar_location="above",
                     x_axis_label=s.plane.text[0], y_axis_label=s.plane.text[1],
                     output_backend="canvas")
        fig.image_rgba(image="image", x="x", y="y", dw="dw", dh="dh", source=self.region)
        fig.line("x", "y", source=self.boundary, color="black", line_width=1.2,
                 legend_label="accessible-region boundary")
        fig.line("x", "y", source=self.separatrix, color="#c0392b", line_width=1.2,
                 line_dash="dashed", legend_label="unperturbed separatrices (μ = 0)")
        fig.scatter("x", "y", source=self.points, color="colour", size=2.6, line_width=0)
        # The predicted island chains (issue 28; drawn by Explorer._request_chains): centre
        # lines dashed, separatrices solid, stable points o and unstable points x.
        chains = empty_columns()
        self.chain_centres = ColumnDataSource(chains["centres"],
                                              name="andoyer-chain-centres")
        self.chain_separatrices = ColumnDataSource(chains["separatrices"],
                                                   name="andoyer-chain-separatrices")
        self.chain_points = ColumnDataSource(chains["points"], name="andoyer-chain-points")
        # legend_field: one legend entry per chain (its label, e.g. 7:1, in its colour).
        fig.multi_line("xs", "ys", source=self.chain_centres, color="colour",
                       line_dash="dashed", line_width=1.0, legend_field="label")
        fig.multi_line("xs", "ys", source=self.chain_separatrices, color="colour",
                       line_width=0.8)
        fig.scatter("x", "y", source=self.chain_points, marker="marker", size=8,
                    line_color="colour", fill_color=None, line_width=1.4)
        seeds = fig.scatter("seed_x", "seed_y", source=self.orbits, color="colour", size=11,
                            marker="star", line_color="black", line_width=0.6)
        seeds.selection_glyph = seeds.glyph.clone(size=16, line_width=1.2)
        seeds.nonselection_glyph = seeds.glyph.clone()
        legend = fig.legend[0]
        legend.orientation = "horizontal"
        legend.ncols = 3                        # rows of three: the chains' entries wrap
        legend.label_text_font_size = "9pt"
        legend.border_line_alpha = 0.0
        fig.add_layout(legend, "below")
        # Two quick clicks at different places arrive as Tap + DoubleTap: both seed.
        fig.on_event(Tap, self._on_tap)
        fig.on_event(DoubleTap, self._on_tap)
        self.fig = fig
        self.status = Div(text="", name="andoyer-status", width=660,
                          css_classes=["andoyer-status"])
        self.state_div = Div(text="{}", name="andoyer-state", visible=False)
        colour = HTMLTemplateFormatter(
            template='<span style="color:<%= value %>;font-size:150%">●</span>')
        num = NumberFormatter(format="0.000000")
        self.table = DataTable(
            source=self.orbits, name="andoyer-orbit-table", width=660, height=170,
            index_position=None, selectable=True,
            columns=[TableColumn(field="id", title="orbit", width=45),
                     TableColumn(field="colour", title="", formatter=colour, width=30),
                     TableColumn(field="seed_x", title="x", formatter=num),
                     TableColumn(field="seed_y", title="y", formatter=num),
                     TableColumn(field="action", title="solved action", formatter=num),
                     TableColumn(field="crossings", title="crossings", width=90),
                     TableColumn(field="status", title="status", width=160)])
        self.orbits.selected.on_change("indices", self._on_select)
        # Bokeh's DataTable redraws its cells when its view's indices change, not when the
        # values of rows already shown do: redraw on every change of the source here.
        redraw = CustomJS(args={"table": self.table}, code=REDRAW_TABLE)
        for what in ("data", "patching", "streaming"):
            self.orbits.js_on_change(what, redraw)
        self.plane_pane = pn.pane.Bokeh(column(self.status, fig, self.table, self.state_div))
        self.main = pn.Column(self.plane_pane, css_classes=["andoyer-main"])

    def _build_controls(self) -> None:
        s = self.settings
        b = s.body
        mode = "paper" if b.name == "paper" else ("hess" if b.is_hess else "general")
        w = pn.widgets
        self.w_body = widget(w.Select, "body", options=BODIES,
                               value=mode, css_classes=["andoyer-body"])
        self.w_A = widget(w.FloatInput, "A", value=b.A, step=0.1, start=1e-9, width=80)
        self.w_B = widget(w.FloatInput, "B", value=b.B, step=0.1, start=1e-9, width=80)
        self.w_C = widget(w.FloatInput, "C", value=b.C, step=0.1, start=1e-9, width=80)
        self.w_mu = widget(w.FloatInput, "μ (weight × distance)", value=b.mu, step=0.005,
                                 start=0.0, css_classes=["andoyer-mu"])
        self.w_r = widget(w.TextInput, "r = (e1, e2, e3) (general body)",
                               value=", ".join(f"{v:.12g}" for v in b.r))
        self.w_h = widget(w.FloatInput, "h (energy)", value=s.h, step=0.005,
                                css_classes=["andoyer-h"])
        self.w_M = widget(w.FloatInput, "M (area constant)", value=s.M, step=0.05,
                                css_classes=["andoyer-M"])
        self.w_section = widget(w.Select, "section", options=SECTIONS,
                                  value=s.section.coord)
        self.w_value = widget(w.FloatInput, "section value (rad)", value=s.section.value,
                                    step=0.1)
        self.w_direction = widget(w.Select, "crossing direction", options=DIRECTIONS,
                                    value=s.section.direction)
        self.w_crossings = widget(w.IntInput, "crossings per orbit", value=s.n_crossings,
                                      step=100, start=1, css_classes=["andoyer-crossings"])
        self.w_engine = widget(w.Select, "engine", options=["default", *ENGINES],
                                 value=s.engine or "default")
        self.w_root = widget(w.Select, "solutions of H = h above a click",
                               options=["smallest", "largest", "all"], value=s.root)
        self.w_underlay = widget(w.Checkbox, f"chaos-map underlay (FLI, {UNDERLAY_N}² "
                                  f"orbits to t = {UNDERLAY_T_END:g})", value=False,
                                  disabled=self._chaos is None)
        self.w_chains = widget(w.Checkbox, "predicted island chains (first order in μ)",
                               value=False, css_classes=["andoyer-chains"])
        self.w_chain_order = widget(w.IntInput, "chains up to order p + q",
                                    value=CHAINS_ORDER, start=2, end=CHAINS_MAX_ORDER,
                                    step=1, css_classes=["andoyer-chain-order"])
        self.w_clear = widget(w.Button, "clear all orbits", button="warning")
        self.w_remove = widget(w.Button, "remove selected orbit", button="default")
        self.w_nc = widget(w.FileDownload, "NetCDF of the orbits", button="primary",
                            callback=self._download_netcdf, filename="andoyer-explore.nc")
        self.w_png = widget(w.FileDownload, "PNG of the plane", button="primary",
                             callback=self._download_png, filename="andoyer-explore.png")
        for wid in (self.w_body, self.w_A, self.w_B, self.w_C, self.w_mu, self.w_r,
                    self.w_h, self.w_M, self.w_section, self.w_value, self.w_direction,
                    self.w_crossings, self.w_engine, self.w_root):
            wid.param.watch(self._on_control, "value")
        self.w_underlay.param.watch(self._on_underlay, "value")
        self.w_chains.param.watch(self._on_chains, "value")
        self.w_chain_order.param.watch(self._on_chains, "value")
        self.w_clear.on_click(lambda _e: self._guard(self._clear_orbits))
        self.w_remove.on_click(lambda _e: self._guard(self._remove_selected))
        self._sync_body_widgets()
        # Fields fit the column (its width less their margins): at Panel's default width
        # they ran under the plane and their right edges were hidden.
        for wid in (self.w_body, self.w_mu, self.w_r, self.w_h, self.w_M, self.w_section,
                    self.w_value, self.w_direction, self.w_crossings, self.w_engine,
                    self.w_root, self.w_chain_order):
            wid.width = CONTROLS_WIDTH - 20
        self.controls = pn.Column(
            pn.pane.Markdown("### andoyer explore\nClick inside the boundary to seed an orbit "
                             "on the energy level."),
            self.w_body, pn.Row(self.w_A, self.w_B, self.w_C), self.w_mu, self.w_r,
            self.w_h, self.w_M, self.w_section, self.w_value, self.w_direction,
            self.w_crossings, self.w_engine, self.w_root, self.w_underlay, self.w_chains,
            self.w_chain_order,
            pn.Row(self.w_clear, self.w_remove), self.w_nc, self.w_png, width=CONTROLS_WIDTH,
            css_classes=["andoyer-controls"])

    def _build_side(self) -> None:
        self.info = pn.pane.HTML("<i>no orbit selected</i>", width=340,
                                 css_classes=["andoyer-info"])
        self.w_coords = widget(
            pn.widgets.MultiChoice, "time plot of", options=list(TIME_COORDS),
            value=[self.settings.plane.x, self.settings.plane.y])
        self.w_span = widget(pn.widgets.FloatInput, "time span", value=100.0, step=50.0,
                                            start=1e-3)
        self.w_coords.param.watch(lambda _e: self._guard(self._request_side), "value")
        self.w_span.param.watch(lambda _e: self._guard(self._request_side), "value")
        self.series = ColumnDataSource({"xs": [], "ys": [], "name": [], "colour": []},
                                       name="andoyer-timeseries")
        tfig = figure(name="andoyer-timeplot", width=340, height=260, x_axis_label="t",
                      tools="pan,wheel_zoom,box_zoom,reset", toolbar_location="above")
        tfig.multi_line("xs", "ys", source=self.series, color="colour", legend_field="name")
        tfig.legend.label_text_font_size = "8pt"
        self.tfig = tfig
        self.w_indicator = widget(
            pn.widgets.Button, "FLI / MEGNO of the selected orbit",
            disabled=self._chaos is None)
        self.w_indicator_t = widget(pn.widgets.FloatInput, "indicator time", value=1000.0,
                                     step=500.0, start=1e-3)
        self.w_indicator.on_click(lambda _e: self._guard(self._request_indicator))
        self.indicator = pn.pane.HTML("" if self._chaos is not None else
                                      "<small>FLI/MEGNO: not available in this version "
                                      "(no andoyer.analysis.chaos.lyapunov)</small>", width=340)
        self.time_pane = pn.pane.Bokeh(tfig)
        # The body in space (issue 27): the selected orbit's gyroscope in a Plotly 3D
        # scene, played in the browser (andoyer.plot.space.gyroscope_plotly).
        self.gyroscope = PlotlyWithFrames(None, width=340, height=340,
                                          css_classes=["andoyer-gyroscope"])
        self.side_panel = pn.Column(pn.pane.Markdown("#### selected orbit"), self.info,
                                    self.w_coords, self.w_span, self.time_pane,
                                    pn.pane.Markdown("#### the body in space "
                                                     "(over the time span)"),
                                    self.gyroscope,
                                    self.w_indicator_t, self.w_indicator, self.indicator,
                                    width=360, css_classes=["andoyer-side"])

