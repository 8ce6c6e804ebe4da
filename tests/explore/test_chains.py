"""The predicted island chains of the explorer (issue 28): the overlay's data
(:mod:`andoyer.explore.chains`) and the page's toggle without a browser (the browser test
is ``tests/explore/test_explore_e2e.py::test_chain_overlay_in_chromium``)."""

from __future__ import annotations

import math
import re
from dataclasses import replace

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.explore.chains import (
    CHAINS_MAX_ORDER,
    chain_overlay,
    shared_chain_overlay,
)
from andoyer.explore.seeds import seed
from andoyer.explore.state import Settings, default_energy
from andoyer.kernels.generated.equations import andoyer_hamiltonian

ORDER = 8


@pytest.fixture(scope="module")
def paper_g() -> Settings:
    body = RigidBody.paper()
    return Settings(body, default_energy(body), section="g=0")


def _points(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    ok = np.isfinite(x) & np.isfinite(y)
    return x[ok], y[ok]


def test_centre_lines_are_the_resonant_tori_of_the_free_top(paper_g: Settings) -> None:
    """Independent route: every point (l, L) of a drawn centre line, with the chain's G*,
    has the free-top energy H0(l, L, G*) = h (Eq. (9), mu = 0, from the generated
    Andoyer Hamiltonian, not from the resonance package)."""
    s = paper_g
    ov = chain_overlay(s, ORDER)
    assert ov.n_chains >= 2
    b = s.body
    G_star = ov.ds.G_action.values
    for k in range(ov.n_chains):
        x, y = _points(ov.centre_x[k], ov.centre_y[k])
        assert x.size > 100
        assert np.all((x >= 0.0) & (x < 2 * math.pi))       # l as the orbits' points show it
        h0 = np.array([andoyer_hamiltonian(lv, 0.0, Lv, G_star[k], s.M, b.a, b.b, b.c, 0.0,
                                           *b.r) for lv, Lv in zip(x, y, strict=True)])
        np.testing.assert_allclose(h0, s.h, rtol=0, atol=1e-9)


def test_points_and_separatrices_of_a_small_mu_body() -> None:
    """Hess(3, 1, 2) at mu = 1e-3, h = 1 on g = 0 (the 3:1 and 2:1 chains of the closing
    note): a q:1 chain has q stable and q unstable points, its two separatrices enclose
    the centre line, and a click at a stable point seeds a state whose |G| is G* to
    within the chain's half-width plus O(mu) (the explorer's own seed solver)."""
    body = RigidBody.hess(3.0, 1.0, 2.0, 1e-3)
    s = Settings(body, 1.0, section="g=0")
    ov = chain_overlay(s, 5)
    first = ov.mu_order == 1
    assert first.sum() >= 2 and len(ov.separatrix_x) == 2 * first.sum()
    cols = ov.columns()
    assert len(cols["separatrices"]["label"]) == len(ov.separatrix_x)
    assert len(cols["points"]["marker"]) == ov.points_x.size == len(ov.points_kind)
    ds = ov.ds
    for k in np.flatnonzero(first):
        label = ov.labels[k]
        q = int(ds.q.values[k])
        mine = np.array([lb == label for lb in ov.points_label])
        kinds = np.array(ov.points_kind)[mine]
        assert (kinds == "stable").sum() == (kinds == "unstable").sum() == q
    # a stable point of the widest chain, seeded as a click there
    k = int(np.nanargmax(np.where(first, ov.half_width, np.nan)))
    mine = np.array([lb == ov.labels[k] and kd == "stable"
                     for lb, kd in zip(ov.points_label, ov.points_kind, strict=True)])
    G_star, dG = float(ds.G_action.values[k]), float(ov.half_width[k])
    seeded = replace(s, root="all")
    for x, y in zip(ov.points_x[mine], ov.points_y[mine], strict=True):
        G = [float(np.linalg.norm(sd.y0[:3])) for sd in seed(seeded, float(x), float(y))]
        assert min(abs(g - G_star) for g in G) < dG + 10 * body.mu


def test_theta2_plane_wraps_like_the_orbits() -> None:
    """On theta2 = 0 with M = 0 the plane's theta1 runs over [0, 2 pi) (the explorer's
    x_period); the centre lines of resonance_widths live on [0, 4 pi): reduced, and broken
    by NaN where they wrap, never drawn across the plane."""
    body = RigidBody.paper()
    s = Settings(body, default_energy(body))
    assert s.x_period == 2 * math.pi
    ov = chain_overlay(s, ORDER)
    assert ov.n_chains > 0
    for x in (*ov.centre_x, *ov.separatrix_x):
        fin = x[np.isfinite(x)]
        assert np.all((fin >= 0) & (fin < s.x_period))
        steps = np.abs(np.diff(x))
        assert np.all(steps[np.isfinite(steps)] < s.x_period / 2)
    assert np.all((ov.points_x >= 0) & (ov.points_x < s.x_period))
    raw = ov.ds.stable_x.values
    np.testing.assert_allclose(np.sort(ov.points_x[np.array(ov.points_kind) == "stable"]),
                               np.sort(np.mod(raw[np.isfinite(raw)], s.x_period)))


def test_shared_overlay_is_computed_once_per_plane(paper_g: Settings) -> None:
    a = shared_chain_overlay(paper_g, 8)
    assert shared_chain_overlay(replace(paper_g, n_crossings=50, engine="numba"), 8) is a
    assert shared_chain_overlay(replace(paper_g, h=paper_g.h + 0.01), 8) is not a
    assert shared_chain_overlay(paper_g, 9) is not a
    with pytest.raises(ValueError, match="read-only"):
        a.points_x[:] = 0.0
    with pytest.raises(ValueError, match="read-only"):
        a.centre_y[0][:] = 0.0


@pytest.mark.parametrize("order", [1, CHAINS_MAX_ORDER + 1, True, 2.5, "8", math.nan, None])
def test_bad_order_is_refused_by_name(paper_g: Settings, order: object) -> None:
    with pytest.raises(ValueError, match="max_order"):
        chain_overlay(paper_g, order)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="max_order"):
        shared_chain_overlay(paper_g, order)  # type: ignore[arg-type]


def test_bad_settings_are_refused(paper_g: Settings) -> None:
    with pytest.raises(TypeError, match="settings"):
        chain_overlay("g=0")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="h must be > 0"):
        chain_overlay(replace(paper_g, h=-0.001), 6)


def test_png_of_the_plane_draws_the_chains(paper_g: Settings) -> None:
    """The page's PNG export (plane_figure) draws the chains on screen: one line per centre
    line and separatrix, the stable and unstable points at their plane coordinates."""
    from andoyer.explore.export import plane_figure, png_bytes
    from andoyer.explore.state import plane_view

    view = plane_view(paper_g, boundary_grid=40)
    ov = shared_chain_overlay(paper_g, ORDER)
    bare = plane_figure(None, view).axes[0]
    ax = plane_figure(None, view, chains=ov).axes[0]
    assert len(ax.lines) - len(bare.lines) == ov.n_chains + len(ov.separatrix_x)
    offsets = np.concatenate([c.get_offsets() for c in ax.collections[len(bare.collections):]])
    np.testing.assert_array_equal(np.sort(offsets[:, 0]), np.sort(ov.points_x))
    assert png_bytes(ax.figure)[:4] == b"\x89PNG"


# ----------------------------------------------------------------------------- the page
def _level(e) -> str:
    return re.search(r"<b>(\w+)</b>", e.status.text).group(1)


def test_page_toggle_draws_caches_and_reports_errors() -> None:
    """The toggle draws the chains of the plane on screen (from the side worker), a new
    level redraws them, a level without them gives a message (no traceback), off removes
    them."""
    pytest.importorskip("panel")
    import json

    from andoyer.explore.ui import Explorer

    e = Explorer(section="g=0", n_crossings=50, boundary_grid=40)
    try:
        e.wait()
        assert e._chains_drawn is None and not e.chain_points.data["x"]
        e.w_chain_order.value = 8
        e.w_chains.value = True
        e.wait()
        ref = shared_chain_overlay(e.settings, 8)
        assert _level(e) == "info" and "predicted chains" in e.status.text
        assert json.loads(e.state_div.text)["chains"] == ref.n_chains > 0
        np.testing.assert_array_equal(e.chain_points.data["x"], ref.points_x)
        assert len(e.chain_centres.data["xs"]) == ref.n_chains
        # the chains' colours have a legend: one entry per chain label, in its colour
        legend = e.fig.legend[0]
        entry = next(i for i in legend.items
                     if any(r.data_source is e.chain_centres for r in i.renderers))
        assert entry.label.field == "label" and list(e.chain_centres.data["label"]) \
            == list(ref.labels)
        assert e.png()[:4] == b"\x89PNG"                       # the export draws them too
        e.w_h.value = e.settings.h + 0.01                     # a new level: new chains
        e.wait()
        new = shared_chain_overlay(e.settings, 8)
        assert new is not ref and e._chains_key == new.key
        assert not np.array_equal(e.chain_centres.data["ys"][0], ref.centre_y[0])
        e.w_h.value = -0.001                                  # the free top needs h > 0
        e.wait()
        assert _level(e) == "error" and "predicted chains: h must be &gt; 0" in e.status.text
        assert "Traceback" not in e.status.text and e._chains_drawn is None
        e.w_chains.value = False
        assert not e.chain_centres.data["xs"] and e._chains_drawn is None
    finally:
        e.close()
