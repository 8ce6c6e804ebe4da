"""The explorer's logic without a browser: seeds, staged orbits, separatrices, session,
exports, the app object driven in-process, and the ``andoyer explore`` command."""

from __future__ import annotations

import math
import os
import re
import signal
import subprocess
import sys
import urllib.request
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import andoyer
from andoyer import RigidBody, energy, from_andoyer, hamiltonian, to_andoyer, to_hess
from andoyer.explore.export import netcdf_bytes, orbits_dataset, plane_figure, png_bytes
from andoyer.explore.orbits import crossing_stages, integral_drifts
from andoyer.explore.seeds import initial_charts, seed
from andoyer.explore.state import (
    PALETTE,
    PLANES,
    OutsideRegionError,
    Session,
    Settings,
    Stage,
    default_energy,
    make_settings,
    plane_coordinates,
    plane_view,
    unperturbed_separatrices,
)
from andoyer.integrate import Section, poincare

PAPER = RigidBody.paper()
H0 = default_energy(PAPER)  # the energy of `andoyer section`


@pytest.fixture(scope="module")
def settings() -> Settings:
    return make_settings(PAPER, n_crossings=120)


# ----------------------------------------------------------------------------- settings
def test_default_energy_is_that_of_andoyer_section() -> None:
    assert H0 == float(energy(PAPER, from_andoyer([0.3, 0.0, 0.3, 1.0, 0.0])))


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"h": math.nan}, "h .energy. must be finite"),
    ({"h": "x"}, "h .energy. must be a real number"),
    ({"n_crossings": 0}, "crossings per orbit must be an integer"),
    ({"n_crossings": 2.5}, "crossings per orbit must be an integer"),
    ({"engine": "rk4"}, "unknown engine 'rk4'"),
    ({"root": "middle"}, "root must be"),
    ({"section": "G3=0"}, "explorer shows the planes"),
    ({"rtol": 0.1}, "rtol must be in"),
    ({"h": None, "M": 1.5}, "give the energy h"),
])
def test_settings_reject_bad_values(kwargs: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        make_settings(PAPER, **{"h": 0.25, **kwargs})


def test_hess_plane_needs_planar_body() -> None:
    body = RigidBody(2.5, 2.0, 2.2, 0.01, (0.6, 0.6, 0.5))
    with pytest.raises(ValueError, match="e3 = 0"):
        Settings(body, 0.25)
    assert Settings(body, 0.25, section=Section("g", 0.0)).plane.x == "l_angle"


# ----------------------------------------------------------------------------- seeds
@pytest.mark.parametrize(("section", "x", "y"), [("theta2=0", 1.0, 0.5),
                                                  ("theta2=0.7", 4.0, 0.3),
                                                  ("g=0", 0.3, 0.3), ("g=1.1", 2.0, -0.4)])
def test_seed_lies_on_the_level_and_the_click(section: str, x: float, y: float) -> None:
    s = make_settings(PAPER, section=section, root="all")
    seeds = seed(s, x, y)
    assert seeds and [sd.root_index for sd in seeds] == list(range(seeds[0].n_roots))
    for sd in seeds:
        # Energy from the Euler-Poisson state, not from the chart's kernel that solved it.
        assert abs(float(energy(PAPER, sd.y0)) - H0) <= 1e-12 * H0
        chart = to_hess(PAPER, sd.y0) if s.plane.chart == "hess" else to_andoyer(sd.y0)
        value = s.section.value
        np.testing.assert_allclose(chart, [x, value, y, sd.action, 0.0], atol=1e-12)


def test_seed_known_point_and_multiplicity() -> None:
    """(l, g, L, G, M) = (0.3, 0, 0.3, 1, 0) defines H0, so G = 1 solves it there."""
    (sd,) = seed(make_settings(PAPER, section="g=0"), 0.3, 0.3)
    assert abs(sd.action - 1.0) <= 1e-12


def test_seed_outside_region_says_so(settings: Settings) -> None:
    with pytest.raises(OutsideRegionError, match="outside the accessible region"):
        seed(settings, 1.0, 1.3)          # J1 above G_max
    with pytest.raises(OutsideRegionError, match="outside the Hess chart"):
        seed(settings, 1.0, -0.1)         # J1 < 0 is not in the chart


def test_seed_angle_taken_mod_period(settings: Settings) -> None:
    a, b = seed(settings, 1.0, 0.5)[0], seed(settings, 1.0 + math.tau, 0.5)[0]
    np.testing.assert_array_equal(a.y0, b.y0)


def test_seed_direction_flag(settings: Settings) -> None:
    sd = seed(settings, 1.0, 0.5)[0]
    rate = float(andoyer.vector_field(PAPER, sd.chart_point, "hess")[1])
    assert sd.section_rate == rate
    assert sd.crosses_in(1) == (rate > 0) and sd.crosses_in(-1) == (rate < 0)
    assert sd.crosses_in(0)


def test_initial_charts_agree_with_seed(settings: Settings) -> None:
    sd = seed(settings, 2.0, 0.2)[0]
    charts = initial_charts(settings, sd.y0)
    assert list(charts) == ["Euler-Poisson", "Andoyer-Deprit", "Hess"]
    np.testing.assert_allclose(list(charts["Hess"].values()), sd.chart_point, atol=1e-12)
    np.testing.assert_allclose(from_andoyer(list(charts["Andoyer-Deprit"].values())), sd.y0,
                               atol=1e-12)


@pytest.mark.parametrize(("y0", "undefined"), [
    ([0.0, 0.0, 1.0, 0.0, 0.6, 0.8], {"l", "g", "theta1", "theta2"}),   # L = G
    # |M| = G: g is undefined, l is not, so theta1 = 2 (l + phi0) of (14) is defined
    ([0.6, 0.0, 0.8, 0.6, 0.0, 0.8], {"g", "theta2"})])
def test_initial_charts_show_undefined_angles_as_nan(settings: Settings, y0, undefined):
    charts = initial_charts(settings, np.array(y0))
    values = {**charts["Andoyer-Deprit"], **charts["Hess"]}
    assert {k for k, v in values.items() if np.isnan(v)} == undefined


# ----------------------------------------------------------------------------- orbits
@pytest.mark.parametrize(("engine", "N", "first", "growth"), [
    ("heyoka", 500, 100, 4), ("numba", 300, 50, 2), ("scipy", 12, 5, 2)])
def test_stages_are_one_poincare_call(settings: Settings, engine: str, N: int, first: int,
                                      growth: int) -> None:
    """The staged points are bit for bit those of one poincare() call (a chaotic-layer
    orbit near the separatrix, where any change of the step sequence would show)."""
    s = make_settings(PAPER, n_crossings=N, engine=engine)
    sd = seed(s, 2.8, 0.05)[0]
    stages = list(crossing_stages(s, sd.y0, first=first, growth=growth))
    bounds = [(st.start, st.stop) for st in stages]
    expected, n = [], first
    start = 0
    while True:
        expected.append((start, min(n, N)))
        if n >= N:
            break
        start, n = min(n, N), n * growth
    assert bounds == expected
    assert [st.done for st in stages] == [False] * (len(stages) - 1) + [True]
    ref = poincare(PAPER, sd.y0, s.section, N, engine=engine)
    x = np.concatenate([st.x for st in stages])
    y = np.concatenate([st.y for st in stages])
    np.testing.assert_array_equal(x, np.mod(ref.theta1.values[0], math.tau))
    np.testing.assert_array_equal(y, ref.J1.values[0])
    np.testing.assert_array_equal(stages[-1].ds.theta1.values, ref.theta1.values[0])


def test_plane_coordinates_period() -> None:
    ds = xr.Dataset({"theta1": ("crossing", [0.5, 7.0, 12.0]), "J1": ("crossing", [0.1] * 3)})
    x0, _ = plane_coordinates(make_settings(PAPER, h=0.3), ds)
    x1, _ = plane_coordinates(make_settings(PAPER, h=0.3, M=0.2), ds)
    np.testing.assert_allclose(x0, [0.5, 7.0 - math.tau, 12.0 - math.tau])
    np.testing.assert_allclose(x1, [0.5, 7.0, 12.0])


def test_integral_drifts(settings: Settings) -> None:
    sd = seed(settings, 1.0, 0.5)[0]
    ds = list(crossing_stages(settings, sd.y0))[-1].ds
    d = integral_drifts(ds, settings.h, settings.M, PAPER)
    assert 0 < d["H"] < 1e-11 and d["area"] < 1e-11 and d["geometric"] < 1e-11
    bad = ds.assign(H=ds.H + 1e-6)
    assert integral_drifts(bad, settings.h, settings.M, PAPER)["H"] > 0.9e-6 / settings.h


# ----------------------------------------------------------------------------- separatrices
def _on_separatrix(body: RigidBody, h: float, l: np.ndarray, L: np.ndarray) -> np.ndarray:
    """H0 - m G0^2 / 2 at (l, L) and G = G0, from the generated kernels with mu = 0."""
    m = sorted([body.a, body.b, body.c])[1]
    G0 = math.sqrt(2 * h / m)
    ok = np.isfinite(l) & (np.abs(L) < G0 * (1 - 1e-9))
    x = np.stack([l[ok], np.zeros(ok.sum()), L[ok], np.full(ok.sum(), G0),
                  np.zeros(ok.sum())], axis=-1)
    return hamiltonian(body.with_mu(0.0), x, "andoyer") - 0.5 * m * G0**2


@pytest.mark.parametrize("body", [
    PAPER,                                              # z middle (Hess)
    RigidBody(2.0, 2.5, 2.2, 0.1, (0.6, 0.8, 0.0)),     # z middle, other order
    RigidBody(2.2, 2.0, 2.5, 0.1, (0.6, 0.8, 0.0)),     # x middle
    RigidBody(2.0, 2.2, 2.5, 0.1, (0.6, 0.8, 0.0)),     # y middle
])
def test_separatrices_are_the_unperturbed_level(body: RigidBody) -> None:
    h = 0.23
    curves = unperturbed_separatrices(body, h, PLANES["g"], math.tau)
    assert len(curves) >= 2
    for l, L in curves:
        assert np.max(np.abs(_on_separatrix(body, h, l, L))) < 1e-13
    # The Hess plane holds the same curves through theta1 = 2 (l + phi0), J1 = (G0 + L)/2.
    G0 = math.sqrt(2 * h / sorted([body.a, body.b, body.c])[1])
    for t1, J1 in unperturbed_separatrices(body, h, PLANES["theta2"], 2 * math.tau):
        l = t1 / 2 - body.phi0
        assert np.nanmax(np.abs(_on_separatrix(body, h, l, 2 * J1 - G0))) < 1e-13


def test_separatrices_of_the_paper_body() -> None:
    phi0 = PAPER.phi0
    lines = unperturbed_separatrices(PAPER, H0, PLANES["g"], math.tau)
    got = sorted(float(x[0]) for x, _ in lines)
    np.testing.assert_allclose(got, [phi0, math.pi - phi0, math.pi + phi0, math.tau - phi0],
                               atol=1e-14)
    hess = unperturbed_separatrices(PAPER, H0, PLANES["theta2"], math.tau)
    np.testing.assert_allclose(sorted(float(x[0]) for x, _ in hess), [0, 4 * phi0, math.tau],
                               atol=1e-12)
    assert unperturbed_separatrices(PAPER, -0.001, PLANES["g"], math.tau) == []
    assert unperturbed_separatrices(RigidBody.lagrange(1.0, 2.0, 0.1), H0, PLANES["g"],
                                    math.tau) == []


def test_plane_view(settings: Settings) -> None:
    v = plane_view(settings, boundary_grid=60)
    assert v.x_range == (0.0, math.tau) and v.y_range[0] == 0.0
    assert v.accessible.shape == (60, 60) and v.accessible.any()
    assert np.isfinite(v.boundary_x).any() and len(v.separatrices) == 3
    with pytest.raises(ValueError, match="does not intersect"):
        plane_view(make_settings(PAPER, h=-1.0), boundary_grid=40)


def test_indicators_and_underlay(settings: Settings) -> None:
    pytest.importorskip("andoyer.analysis.chaos.lyapunov")
    from andoyer.explore.base import underlay_image as _underlay_image
    from andoyer.explore.orbits import chaos_underlay, orbit_indicators

    regular = orbit_indicators(settings, seed(settings, 1.6, 0.5)[0].y0, 300.0)
    assert 1.5 < regular["megno"] < 2.5 and abs(regular["H_drift"]) < 1e-10
    view = plane_view(settings, boundary_grid=40)
    ds = chaos_underlay(settings, view, n=6, t_end=20.0)
    assert ds.fli.shape == (6, 6)
    assert (ds.attrs["plane_x_min"], ds.attrs["plane_x_max"]) == view.x_range
    assert np.isnan(ds.fli.values[~ds.accessible.values]).all()
    img = _underlay_image(ds)
    assert img["image"][0].shape == (6, 6) and img["x"][0] == pytest.approx(0.0)
    assert img["dw"][0] == pytest.approx(math.tau)
    alpha = img["image"][0] >> 24
    np.testing.assert_array_equal(alpha > 0, ds.accessible.values)


# ----------------------------------------------------------------------------- session
def _stage(start: int, n: int) -> Stage:
    ds = xr.Dataset({"theta1": ("crossing", np.zeros(start + n))})
    return Stage(start, start + n, np.arange(n) + start, np.ones(n), ds, False)


def test_session_colours_and_removal(settings: Settings) -> None:
    sess = Session(settings)
    sd = seed(settings, 1.0, 0.5)[0]
    orbits = [sess.add(sd) for _ in range(len(PALETTE))]
    assert len({o.colour for o in orbits}) == len(PALETTE)   # all distinct
    sess.remove(3)
    assert sess.add(sd).colour == orbits[2].colour           # the freed colour is reused
    assert 3 in sess.removed and 3 not in sess.orbits
    sess.remove(999)                                         # unknown ids are ignored
    with pytest.raises(ValueError, match="already used"):
        sess.add(sd, orbit_id=3)


def test_session_points_follow_stages(settings: Settings) -> None:
    sess = Session(settings)
    sd = seed(settings, 1.0, 0.5)[0]
    a, b = sess.add(sd), sess.add(sd)
    assert sess.extend(a.id, _stage(0, 3)) and sess.extend(b.id, _stage(0, 2))
    assert sess.extend(a.id, _stage(3, 2))
    with pytest.raises(ValueError, match="stage starts at crossing 1"):
        sess.extend(b.id, _stage(1, 2))
    p = sess.points()
    assert list(p["orbit"]) == [a.id] * 5 + [b.id] * 2
    assert list(p["crossing"]) == [0, 1, 2, 3, 4, 0, 1]
    assert list(p["colour"]) == [a.colour] * 5 + [b.colour] * 2
    sess.remove(a.id)
    assert not sess.extend(a.id, _stage(5, 1))               # a removed orbit takes no points
    sess.clear()
    assert sess.points()["x"].size == 0 and sess.removed == {a.id, b.id}


# ----------------------------------------------------------------------------- exports
def test_export_dataset_netcdf_and_png(settings: Settings, tmp_path: Path) -> None:
    sess = Session(settings)
    for xy in [(1.0, 0.5), (2.0, 0.2)]:
        o = sess.add(seed(settings, *xy)[0])
        for st in crossing_stages(settings, o.seed.y0):
            sess.extend(o.id, st)
    ds = orbits_dataset(sess)
    assert ds.sizes["orbit"] == 2 and ds.sizes["crossing"] == settings.n_crossings
    assert list(ds.orbit_id.values) == [1, 2]
    assert list(ds.colour.values) == [o.colour for o in sess.orbits.values()]
    for k, o in enumerate(sess.orbits.values()):
        np.testing.assert_array_equal(ds.x_plane.values[k], o.x)
    for key in ("body_A", "body_mu", "h", "M", "section_coord", "andoyer_version", "rtol"):
        assert key in ds.attrs
    assert ds.attrs["h"] == settings.h and ds.attrs["n_orbits"] == 2
    back = xr.open_dataset(_write(tmp_path / "o.nc", netcdf_bytes(ds)))
    np.testing.assert_array_equal(back.theta1.values, ds.theta1.values)
    assert back.attrs["section_coord"] == "theta2"
    view = plane_view(settings, boundary_grid=40)
    fig = plane_figure(ds, view)
    assert len(fig.axes[0].collections) == 2                 # one scatter per orbit
    assert png_bytes(fig)[:8] == b"\x89PNG\r\n\x1a\n"
    empty = orbits_dataset(Session(settings))
    assert empty.attrs["n_orbits"] == 0 and not empty.data_vars
    assert len(plane_figure(empty, view).axes[0].collections) == 0


def _write(path: Path, data: bytes) -> Path:
    path.write_bytes(data)
    return path


# ----------------------------------------------------------------------------- the app
@pytest.fixture(scope="module")
def explorer():
    pytest.importorskip("panel")
    from andoyer.explore.ui import Explorer

    e = Explorer(n_crossings=150, boundary_grid=60)
    e.w_indicator_t.value = 100.0
    e.wait()
    yield e
    e.close()


def _level(e) -> str:
    return re.search(r"<b>(\w+)</b>", e.status.text).group(1)


def test_callbacks_run_in_the_order_scheduled_whatever_tick_runs_first(explorer) -> None:
    """Bokeh may run next-tick callbacks added from two threads out of order (a held
    document replays its events after new ones slip in): an orbit's first stage then ran
    before the orbit was added and was lost (CI, once). The page's own queue keeps the
    order whatever tick runs first."""

    class Doc:  # a server document whose ticks the test runs, in reverse
        session_context = object()

        def __init__(self) -> None:
            self.ticks: list = []

        def add_next_tick_callback(self, callback) -> None:
            self.ticks.append(callback)

    e, ran, doc = explorer, [], Doc()
    saved, e._doc = e._doc, doc
    try:
        for k in range(5):
            e._schedule(lambda k=k: ran.append(k))
        for tick in reversed(doc.ticks):
            tick()
    finally:
        e._doc = saved
    assert ran == [0, 1, 2, 3, 4]


def test_app_clicks_queue_and_draw(explorer) -> None:
    e = explorer
    assert e.view is not None and _level(e) == "info"
    for xy in [(1.0, 0.5), (2.0, 0.2), (0.4, 0.25)]:
        e._seed_click(*xy)              # what a Tap on the plane calls
    e.wait()
    ids = list(e.session.orbits)
    assert len(ids) == 3 and ids == sorted(ids)                  # in click order
    assert all(o.status == "done" and o.x.size == 150 for o in e.session.orbits.values())
    np.testing.assert_array_equal(e.points.data["x"], e.session.points()["x"])
    assert list(e.orbits.data["id"]) == ids and e._selected == ids[-1]
    assert e.series.data["name"] == ["theta1", "J1"]             # time plot of the selection
    assert "orbit" in e.info.object and "drift" in e.info.object
    e._seed_click(1.0, 1.5)                                      # outside: a warning
    e.wait()
    assert _level(e) == "warning" and "outside the accessible region" in e.status.text
    assert len(e.session.orbits) == 3
    if e._chaos is not None:
        e._request_indicator()                                   # FLI/MEGNO of the selection
        e.wait()
        assert "MEGNO" in e.indicator.object
    e._remove_selected()
    assert list(e.session.orbits) == ids[:2]
    assert set(e.points.data["orbit"]) == set(ids[:2])
    assert e.netcdf()[:4] == b"\x89HDF" and e.png()[:4] == b"\x89PNG"
    e._clear_orbits()
    assert not e.session.orbits and len(e.points.data["x"]) == 0


def test_app_bad_controls_give_messages(explorer) -> None:
    e = explorer
    good = e.settings
    e.w_crossings.value = 0
    assert _level(e) == "error" and "crossings per orbit" in e.status.text
    assert e.settings == good                                    # previous settings kept
    e.w_crossings.value = good.n_crossings
    e.w_h.value = -1.0                                           # below the section's minimum
    e.wait()
    assert _level(e) == "error" and "does not intersect" in e.status.text
    e.w_h.value = good.h + 0.01                                  # a new level: new plane
    e.wait()
    assert _level(e) == "info" and e.view is not None and e.view.settings.h == good.h + 0.01
    e.w_body.value = "hess"
    e.w_A.value = 10.0                                           # triangle inequality
    assert _level(e) == "error" and "triangle inequality" in e.status.text
    e.w_A.value = 2.5
    e.w_body.value = "paper"
    e.w_span.value = -5.0                                        # time span of the side plot
    assert _level(e) == "error" and "time span must be a positive number" in e.status.text
    e.w_span.value = 100.0
    e.w_h.value = good.h
    e.wait()
    assert _level(e) == "info" and e.settings == good


def test_module_is_callable_and_lazy() -> None:
    code = ("import sys, andoyer, andoyer.explore; "
            "print('panel' in sys.modules, callable(andoyer.explore))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, timeout=120)
    assert out.stdout.split() == ["False", "True"]


@pytest.mark.slow  # a fresh interpreter imports Panel and serves a page: ~10-20 s
def test_command_serves_and_stops() -> None:
    """``andoyer explore --port 0 --no-browser`` prints its address, serves the page, and
    stops cleanly on Ctrl-C."""
    proc = subprocess.Popen(
        [sys.executable, "-m", "andoyer", "explore", "--port", "0", "--no-browser"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        env={**os.environ, "PYTHONUNBUFFERED": "1"})
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        m = re.fullmatch(r"andoyer explore: serving on (http://127\.0\.0\.1:(\d+)/)\n", line)
        assert m, line
        with urllib.request.urlopen(m.group(1), timeout=60) as page:
            assert page.status == 200 and b"andoyer explore" in page.read()
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=60)
        assert proc.returncode == 0, err
        assert "stopped" in out
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()


def test_command_rejects_bad_input() -> None:
    from andoyer.cli import main

    with pytest.raises(SystemExit) as exc:
        main(["explore", "--section", "G3=0", "--no-browser"])
    assert exc.value.code == 2


def test_pages_past_the_cap_say_so_and_share_the_plane() -> None:
    """Past ``max_sessions`` open pages a page says so (it was: every load built an
    explorer and its plane, and 50 rapid loads starved the server); pages of one setting
    share one read-only plane."""
    from bokeh.client import pull_session

    from andoyer.explore.server import serve
    from andoyer.explore.state import make_settings, shared_plane_view

    handle = serve(threaded=True, max_sessions=1, n_crossings=5)
    assert handle is not None
    sessions = []
    try:
        for _ in range(2):
            sessions.append(pull_session(url=handle.url))
        first, second = (s.document for s in sessions)
        assert first.select_one({"name": "andoyer-plane"}) is not None
        assert second.select_one({"name": "andoyer-plane"}) is None
        texts = [m.text for m in second.select({}) if isinstance(getattr(m, "text", None), str)]
        assert any("1 pages are open, the most this server keeps" in t for t in texts), texts
    finally:
        for s in sessions:
            s.close()
        handle.stop()
    view = shared_plane_view(make_settings(None), 40)
    assert view is shared_plane_view(make_settings(None), 40)
    with pytest.raises(ValueError, match="read-only"):
        view.boundary_x[0] = 0.0
    with pytest.raises(ValueError, match="max_sessions"):
        serve(threaded=True, max_sessions=0)


@pytest.mark.parametrize("moment", ["sockets open", "serving"])
def test_a_signal_stops_the_server_however_far_it_got(moment):
    """A signal (``KeyboardInterrupt``, what ``andoyer explore``'s handlers raise for
    SIGINT, SIGTERM and SIGHUP) stops ``serve`` cleanly whether it comes once the sockets
    listen but before the loop runs (the race a SIGTERM under load met: the command then
    ended as "interrupted", exit 130, not "stopped") or while it serves; the port is
    free again."""
    import socket

    from andoyer.explore.server import serve

    ports = []

    def on_start(url):
        ports.append(int(url.rsplit(":", 1)[1].strip("/")))
        if moment == "sockets open":
            raise KeyboardInterrupt
        import threading  # delivered once the loop runs

        threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT)).start()

    assert serve(n_crossings=5, on_start=on_start) is None  # returned: no exception
    with socket.socket() as sock:  # the server's socket is closed
        sock.bind(("127.0.0.1", ports[0]))
