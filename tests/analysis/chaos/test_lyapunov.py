"""Chaos indicators (FLI, MEGNO, maximal Lyapunov exponent) on cases whose answer is known.

* closed form: at the steady rotation about the middle axis 3 of a free body (mu = 0,
  a hyperbolic relative equilibrium) ``ln |w|`` grows at the rate ``sigma G0``,
  ``sigma = sqrt((b - c)(c - a))``, the eigenvalue of Euler's equations linearised there;
* MEGNO limits: ``<Y> -> 2`` on a torus of the paper's body, ``-> 0`` on the stable
  steady rotations about axes 1 and 2 (iso-energetic tangent vectors);
* Euler-Poinsot (mu = 0) is integrable: over a whole grid, FLI grows by ``ln 2`` when t
  doubles (linear growth of ``|w|``) and ``<Y>`` stays near 2;
* a chaotic orbit (Hess body A, B, C = 3, 1, 2, mu = 1, in the chaotic layer at h = mu):
  positive Lyapunov exponent at two tolerances, ``<Y>`` growing like ``lambda t / 2``,
  while a regular orbit of the same body and level reads as regular;
* independent routes: FLI against the finite-difference growth of two nearby orbits
  integrated by the numba and heyoka engines; heyoka against scipy's DOP853 on the
  same variational equations;
* the initial tangent vector stays tangent to the Casimirs' (and H's) level sets, and
  the MEGNO limit does not depend on its direction;
* the compiled integrator is built once per process; across processes heyoka's own
  on-disk JIT cache is on.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from andoyer import RigidBody, from_andoyer
from andoyer.analysis.chaos.lyapunov import (
    IndicatorRun,
    MapGrid,
    chaos_map,
    indicators,
    initial_tangent,
)
from andoyer.charts.euler_poisson import (
    STATE,
    area_integral,
    energy,
    geometric_integral,
)
from andoyer.integrate import propagate
from andoyer.integrate import variational as V
from andoyer.integrate.engines import resolve_engine
from andoyer.integrate.engines.base import Capability
from andoyer.integrate.fill import section_roots

PAPER = RigidBody.paper()
#: A torus of the paper's body (Andoyer-Deprit l, g, L, G, M).
TORUS = [0.3, 0.0, 0.3, 1.0, 0.0]
FREE = RigidBody.euler_poinsot(2.5, 2.0, 2.2)  # the paper's moments, mu = 0
#: A Hess body with a wide chaotic layer at h = mu (the energy of the upright top).
CHAOTIC_BODY = RigidBody.hess(3.0, 1.0, 2.0, mu=1.0)
#: Hess-chart states (theta1, theta2, J1, J2, J3) on H = 1, M = 0 of CHAOTIC_BODY: one in
#: the chaotic layer, one on an invariant torus (cells of a 12 x 12 FLI map at t = 1000).
CHAOTIC = [0.2617993877991494, 0.0, 1.0103629710818451, 1.712575169922734, 0.0]
REGULAR = [2.8797932657906435, 0.0, 0.7216878364870322, 1.3852961954031033, 0.0]


def _state(ds: xr.Dataset, time: int = 0) -> np.ndarray:
    return np.array([float(ds[s].isel(orbit=0, time=time)) for s in STATE])


# ----------------------------------------------------------------------------- known cases


def test_lyapunov_rate_at_the_middle_axis_rotation_is_the_eigenvalue() -> None:
    """ln|w| grows at sigma G0 at the unstable steady rotation about the middle axis 3."""
    sigma = math.sqrt((FREE.b - FREE.c) * (FREE.c - FREE.a))
    G0, T = 1.0, 400.0
    y0 = [0.0, 0.0, G0, math.sin(1.0), 0.0, math.cos(1.0)]
    ds = indicators(FREE, y0, T, n_times=401)
    t, ln = ds.time.values, ds.log_norm.isel(orbit=0).values
    late = t >= T / 4  # the slope over many turns of gamma averages its oscillation out
    slope = np.polyfit(t[late], ln[late], 1)[0]
    assert slope == pytest.approx(sigma * G0, rel=3e-3)
    # The orbit stayed at the equilibrium (round-off grows like e^(sigma t) * 1e-16).
    assert abs(float(ds.G3.isel(orbit=0, time=-1)) - G0) < 1e-6
    # MEGNO slope: <Y> ~ lambda t / 2.
    Y = ds.megno.isel(orbit=0).values
    assert 2 * (Y[-1] - Y[200]) / (t[-1] - t[200]) == pytest.approx(sigma * G0, rel=0.05)


def test_megno_tends_to_two_on_a_torus() -> None:
    ds = indicators(PAPER, TORUS, 2000.0, chart="andoyer")
    end = ds.isel(orbit=0, time=-1)
    assert abs(float(end.megno) - 2.0) < 0.1
    assert abs(float(end.megno_y) - 2.0) < 0.1
    # Linear growth: FLI gains ln 2 when t doubles (from t = 1000 to 2000).
    gain = float(end.fli) - float(ds.fli.isel(orbit=0).sel(time=1000.0))
    assert gain == pytest.approx(math.log(2.0), abs=0.1)
    assert float(end.mle) < 0.005
    assert float(abs(ds.H_drift).max()) < 1e-12
    # FLI is the supremum of ln|w| over the output times: non-decreasing, >= ln|w|, and
    # above its final value here (ln|w| oscillates on a torus).
    fli, ln = ds.fli.isel(orbit=0).values, ds.log_norm.isel(orbit=0).values
    assert np.all(np.diff(fli) >= 0.0) and np.all(fli >= ln)
    assert fli[-1] == ln.max() and np.any(fli > ln)


def test_megno_quadratures_agree_with_their_definitions() -> None:
    """The integrated Y and <Y> against quadratures of the sampled ln|w| and Y:
    ``Y = 2 (ln|w| - (1/t) int ln|w|)`` (integration by parts) and ``<Y> = (1/t) int Y``;
    trapezoid rule on 4001 samples over [0, 200] (its error, measured: 3e-7)."""
    from scipy.integrate import cumulative_trapezoid

    ds = indicators(PAPER, TORUS, 200.0, chart="andoyer", n_times=4001)
    t = ds.time.values
    ln, Y, mean = (ds[v].isel(orbit=0).values for v in ("log_norm", "megno_y", "megno"))
    late = t > 10.0
    by_parts = 2.0 * (ln - cumulative_trapezoid(ln, t, initial=0.0) / np.maximum(t, 1e-300))
    average = cumulative_trapezoid(Y, t, initial=0.0) / np.maximum(t, 1e-300)
    assert np.max(np.abs(by_parts - Y)[late]) < 5e-6
    assert np.max(np.abs(average - mean)[late]) < 5e-6
    assert Y[0] == 0.0 and mean[0] == 0.0 and ln[0] == 0.0


@pytest.mark.parametrize("axis", [0, 1])
def test_megno_tends_to_zero_on_a_stable_periodic_orbit(axis: int) -> None:
    """Stable steady rotations about the axes of largest (1) and smallest (2) moment."""
    y0 = np.zeros(6)
    y0[axis] = 1.0
    y0[3:] = [math.sin(1.0), 0.0, math.cos(1.0)] if axis == 0 else \
        [0.0, math.sin(1.0), math.cos(1.0)]
    ds = indicators(FREE, y0, 2000.0, tangent="energy")
    assert abs(float(ds.megno.isel(orbit=0, time=-1))) < 0.05
    assert float(ds.fli.isel(orbit=0, time=-1)) < 1.0  # |w| stays bounded
    # With a component across the energy levels, the shear between them gives 2.
    leaf = indicators(FREE, y0, 2000.0, tangent="leaf")
    assert abs(float(leaf.megno.isel(orbit=0, time=-1)) - 2.0) < 0.15


def test_euler_poinsot_is_regular_over_a_grid() -> None:
    h = float(energy(FREE, from_andoyer([0.3, 0.0, 0.3, 1.0, 0.2])))
    a = chaos_map(FREE, h, 0.2, "g=0", 6, IndicatorRun("both", t_end=300.0))
    b = chaos_map(FREE, h, 0.2, "g=0", 6, IndicatorRun("both", t_end=600.0))
    assert int(a.accessible.sum()) == 36
    gain = (b.fli - a.fli).values
    assert np.all(np.abs(gain - math.log(2.0)) < 0.15)  # measured: 0.67 .. 0.73
    assert float(b.megno.min()) > 1.7 and float(b.megno.max()) < 2.1


def test_chaotic_layer_orbit_is_chaotic_at_two_tolerances() -> None:
    for tol in (1e-12, 1e-10):
        ds = indicators(CHAOTIC_BODY, CHAOTIC, 1000.0, chart="hess", tol=tol)
        end = ds.isel(orbit=0, time=-1)
        assert float(end.mle) > 0.03  # measured 0.058 (1e-12), 0.047 (1e-10)
        assert float(end.fli) > 30.0
        # <Y> ~ lambda t / 2: it keeps growing, about linearly.
        assert float(end.megno) > 15.0
        assert float(end.megno) > 1.8 * float(ds.megno.isel(orbit=0).sel(time=500.0))
    regular = indicators(CHAOTIC_BODY, REGULAR, 1000.0, chart="hess")
    end = regular.isel(orbit=0, time=-1)
    assert float(end.mle) < 0.01
    assert abs(float(end.megno) - 2.0) < 0.3
    # Both orbits are on the same level.
    assert float(energy(CHAOTIC_BODY, _state(ds))) == pytest.approx(1.0, abs=1e-12)
    assert float(energy(CHAOTIC_BODY, _state(regular))) == pytest.approx(1.0, abs=1e-12)


# ----------------------------------------------------------------------------- independent routes


@pytest.mark.parametrize("case", ["torus", "chaotic"])
@pytest.mark.parametrize("engine", ["numba", "heyoka"])
def test_fli_matches_finite_difference_growth(case: str, engine: str) -> None:
    """ln|w(t)| = ln(|y(t; y0 + eps w0) - y(t; y0)| / eps) + O(eps |w|) + O(tol / eps)."""
    body, x0, chart, bound = {
        "torus": (PAPER, TORUS, "andoyer", 1e-6),  # measured 2e-8
        "chaotic": (CHAOTIC_BODY, CHAOTIC, "hess", 1e-4),  # measured 1.2e-5 (|w| ~ 230)
    }[case]
    ds = indicators(body, x0, 50.0, chart=chart, n_times=11)
    y0, w0 = _state(ds), ds.w0.isel(orbit=0).values
    eps = 1e-7
    orbits = propagate(body, np.stack([y0, y0 + eps * w0]), ds.time.values, engine=engine,
                       rtol=1e-13, atol=1e-13)
    Y = orbits[list(STATE)].to_array("c").transpose("orbit", "time", "c").values
    fd = np.log(np.linalg.norm(Y[1] - Y[0], axis=-1) / eps)
    ln = ds.log_norm.isel(orbit=0).values
    assert np.max(np.abs(fd[1:] - ln[1:])) < bound
    # The state part of the variational integration is the orbit itself.
    np.testing.assert_allclose(_state(ds, -1), Y[0, -1], rtol=0, atol=1e-10)


@pytest.mark.heyoka
def test_scipy_and_heyoka_agree_on_the_variational_equations() -> None:
    kw = {"chart": "andoyer", "n_times": 5}
    a = indicators(PAPER, TORUS, 100.0, engine="heyoka", **kw)
    b = indicators(PAPER, TORUS, 100.0, engine="scipy", **kw)
    for v in ("log_norm", "megno", "megno_y"):
        np.testing.assert_allclose(a[v].values, b[v].values, rtol=1e-8, atol=1e-9)


@pytest.mark.slow
def test_scipy_confirms_the_chaotic_orbit() -> None:
    a = indicators(CHAOTIC_BODY, CHAOTIC, 300.0, chart="hess", n_times=4)
    b = indicators(CHAOTIC_BODY, CHAOTIC, 300.0, chart="hess", n_times=4, engine="scipy")
    assert float(b.mle.isel(orbit=0, time=-1)) > 0.03
    np.testing.assert_allclose(a.mle.values[:, 1:], b.mle.values[:, 1:], rtol=1e-6)


# ----------------------------------------------------------------------------- tangent vectors


def test_initial_tangent_is_tangent_to_the_level_sets() -> None:
    rng = np.random.default_rng(3)
    x = np.column_stack([rng.uniform(0, 2 * np.pi, 20), rng.uniform(0, 2 * np.pi, 20),
                         rng.uniform(-0.9, 0.9, 20), np.ones(20), rng.uniform(-0.9, 0.9, 20)])
    y = from_andoyer(x)
    step = 1e-7
    for tangent in ("leaf", "energy"):
        w = initial_tangent(PAPER, y, tangent)
        np.testing.assert_allclose(np.linalg.norm(w, axis=1), 1.0, atol=1e-14)
        # Directional derivatives of the Casimirs vanish (to the central difference's
        # O(step^2)); that of H vanishes for "energy" only.
        for f, zero in ((area_integral, True), (geometric_integral, True),
                        (lambda s: energy(PAPER, s), tangent == "energy")):
            d = (f(y + step * w) - f(y - step * w)) / (2 * step)
            assert np.all(np.abs(d) < 1e-8) if zero else np.all(np.abs(d) > 1e-3)


@pytest.mark.parametrize("body", [PAPER, RigidBody(2.4, 1.9, 1.4, mu=0.5, r=(0.4, -0.3, 0.85))])
def test_initial_tangent_equals_the_least_squares_projection(body: RigidBody) -> None:
    """The vectorised Gram-Schmidt projection of initial_tangent gives the vectors of
    an independent route -- the projection by per-state least squares
    (``numpy.linalg.lstsq`` on the gradients, the pinv of the former code) -- to 1e-12,
    on random states and the states of a map grid."""
    from andoyer.analysis.chaos import tangent_space as I

    rng = np.random.default_rng(5)
    gamma = rng.normal(size=(300, 3))
    y = np.concatenate([rng.normal(size=(300, 3)),
                        gamma / np.linalg.norm(gamma, axis=1)[:, None]], axis=1)
    grid = np.column_stack([rng.uniform(0, 2 * np.pi, 100), np.zeros(100),
                            rng.uniform(-0.9, 0.9, 100), np.ones(100), np.zeros(100)])
    y = np.concatenate([y, from_andoyer(grid)])
    N = I._gradients(body, y)

    def lstsq_projection(rows: np.ndarray, v: np.ndarray) -> np.ndarray:
        return np.stack([n.T @ np.linalg.lstsq(n.T, vi, rcond=1e-15)[0]
                         for n, vi in zip(rows, v, strict=True)])

    v = np.broadcast_to(I._GENERIC[0] / np.linalg.norm(I._GENERIC[0]), y.shape)
    for k in (2, 3):
        np.testing.assert_allclose(I._project(N[:, :k], v), lstsq_projection(N[:, :k], v),
                                   rtol=0, atol=1e-12)
    # The whole vector, for both spaces: the same construction on the reference route.
    for tangent in ("leaf", "energy"):
        w = initial_tangent(body, y, tangent)
        iso = v - lstsq_projection(N, v)
        iso /= np.linalg.norm(iso, axis=1)[:, None]
        if tangent == "leaf":
            gH = N[:, 2]
            normal = gH - lstsq_projection(N[:, :2], gH)
            iso = (iso + normal / np.linalg.norm(normal, axis=1)[:, None]) / math.sqrt(2.0)
        np.testing.assert_allclose(w, iso, rtol=0, atol=1e-12)


def test_tangent_stays_on_the_leaf_along_the_flow() -> None:
    y0 = from_andoyer(TORUS)
    w0 = initial_tangent(PAPER, y0)
    res = V.propagate_variational(y0[None], w0, np.linspace(0.0, 500.0, 6),
                                  (*PAPER.params, PAPER.phi0))
    x = res.x[0]
    G, gamma = x[:, 0:3], x[:, 3:6]
    u = x[:, 6:12]
    dG, dgamma = u[:, :3], u[:, 3:]
    # d(G, gamma) = gamma.dG + G.dgamma and d|gamma|^2 = 2 gamma.dgamma stay 0.
    assert np.max(np.abs(np.sum(gamma * dG + G * dgamma, axis=1))) < 1e-11
    assert np.max(np.abs(np.sum(gamma * dgamma, axis=1))) < 1e-11
    assert np.max(np.abs(np.linalg.norm(u, axis=1) - 1.0)) < 1e-12  # |u| is conserved


def test_megno_limit_does_not_depend_on_the_tangent_direction() -> None:
    """Six random directions on the leaf: <Y>(2000) within 0.1 of 2 (measured 1.91-2.02);
    FLI within ln 4 of each other (measured spread 1.3: |w| ~ c t with c depending on the
    direction through its share of the shear)."""
    rng = np.random.default_rng(1)
    y = np.tile(from_andoyer(TORUS), (6, 1))
    ds = indicators(PAPER, y, 2000.0, w0=rng.normal(size=(6, 6)), n_times=21)
    end = ds.isel(time=-1)
    assert np.all(np.abs(end.megno.values - 2.0) < 0.1)
    assert float(end.fli.max() - end.fli.min()) < math.log(4.0)


# ----------------------------------------------------------------------------- maps


def test_chaos_map_dataset_is_self_describing_and_deterministic() -> None:
    body, h = RigidBody.paper(0.5), 0.3733  # the level has two sheets over some points
    grid, run = MapGrid((5, 9)), IndicatorRun("both", t_end=20.0)
    a = chaos_map(body, h, 0.0, "theta2=0", grid, run)
    b = chaos_map(body, h, 0.0, ("theta2", 0.0), grid, run, chunk=3,
                  engine=resolve_engine(None, Capability.TANGENT, workload="megno_map",
                                        n_threads=1))
    assert a.fli.dims == ("J1", "theta1")
    assert (a.sizes["J1"], a.sizes["theta1"]) == (9, 5)
    for v in ("fli", "megno", "mle", "J2", "H_error"):
        np.testing.assert_array_equal(a[v].values, b[v].values)
        assert np.all(np.isnan(a[v].values[~a.accessible.values]))
        assert np.all(np.isfinite(a[v].values[a.accessible.values]))
    # The accessible mask and the action are those of section_roots (largest root).
    J1, theta1 = np.meshgrid(a.J1.values, a.theta1.values, indexing="ij")
    roots = section_roots(body, h, 0.0, ("theta2", 0.0), theta1, J1)
    assert max(r.size for r in roots) == 2
    np.testing.assert_array_equal(a.accessible.values.ravel(), [r.size > 0 for r in roots])
    np.testing.assert_array_equal(a.J2.values.ravel(),
                                  [r.max() if r.size else np.nan for r in roots])
    assert 0 < int(a.accessible.sum()) < 45
    # The J1 axis is cropped to where the level meets the plane (J1 <= J2 <= G_max).
    G_max = math.sqrt(2 * (h + body.mu) / min(body.a, body.b, body.c))
    assert a.attrs["plane_y_max"] < 0.97 * G_max and a.accessible.values[-1].any()
    assert float(a.H_error.max()) < 1e-12
    for key in ("body_mu", "h", "M", "section_coord", "t_end", "tolerance", "engine",
                f"{a.attrs['engine']}_version", "andoyer_version", "plane_x", "plane_y",
                "indicator"):
        assert key in a.attrs, key
    assert a.fli.attrs["long_name"].startswith("fast Lyapunov indicator")
    assert a.theta1.attrs["units"] == "rad"
    # One grid point through the single-orbit API gives the same numbers.
    j, i = map(int, np.argwhere(a.accessible.values)[-1])
    x = [float(a.theta1[i]), 0.0, float(a.J1[j]), float(a.J2[j, i]), 0.0]
    one = indicators(body, x, 20.0, chart="hess", n_times=65)
    for v in ("fli", "megno", "mle"):
        assert float(one[v].isel(orbit=0, time=-1)) == pytest.approx(float(a[v][j, i]),
                                                                     abs=1e-9)


def test_chaos_map_validates_its_inputs() -> None:
    with pytest.raises(ValueError, match="indicator"):
        chaos_map(PAPER, 0.2466, 0.0, "theta2=0", 4,
                  IndicatorRun("lyapunov", t_end=10.0))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="n must be"):
        chaos_map(PAPER, 0.2466, 0.0, "theta2=0", (4,), IndicatorRun(t_end=10.0))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="engine 'euler'"):
        chaos_map(PAPER, 0.2466, 0.0, "theta2=0", 4, IndicatorRun(t_end=10.0), engine="euler")
    with pytest.raises(ValueError, match="t_end"):
        chaos_map(PAPER, 0.2466, 0.0, "theta2=0", 4, IndicatorRun(t_end=-1.0))
    with pytest.raises(ValueError, match="does not intersect"):
        chaos_map(PAPER, -1.0, 0.0, "theta2=0", 4, IndicatorRun(t_end=10.0))
    with pytest.raises(ValueError, match="increasing"):
        indicators(PAPER, TORUS, chart="andoyer", t=[1.0, 2.0])
    with pytest.raises(ValueError, match="tangent space"):
        initial_tangent(PAPER, from_andoyer(TORUS), "sphere")  # type: ignore[arg-type]


def test_plot_and_command_line(tmp_path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    from andoyer.cli import main
    from andoyer.plot.chaos import COLOUR_BAR_LABELS, plot_chaos_map

    out = tmp_path / "map.nc"
    assert main(["chaos-map", "--n", "5", "--t-end", "10", "--indicator", "both",
                 "--section", "g=0", "--out", str(out)]) == 0
    ds = xr.open_dataset(out)
    assert ds.fli.dims == ("L_action", "l_angle")
    assert (tmp_path / "map-fli.png").stat().st_size > 0
    assert (tmp_path / "map-megno.png").stat().st_size > 0
    ax = plot_chaos_map(ds, indicator="megno")
    fig = ax.get_figure(root=True)
    labels = [a.get_ylabel() for a in fig.axes]
    assert COLOUR_BAR_LABELS["megno"] in labels  # the colour bar
    assert ax.get_xlabel() == "$l$" and ax.get_ylabel() == "$L$"
    assert any(line.get_label().startswith("boundary") for line in ax.get_lines())
    assert ax.get_xticklabels()[-1].get_text() == r"$2\pi$"
    ds.close()
    with pytest.raises(SystemExit):
        main(["chaos-map", "--n", "3x", "--out", str(out)])


# ----------------------------------------------------------------------------- the cache


@pytest.mark.heyoka
def test_integrator_is_built_once_per_process_and_heyokas_disk_cache_is_on() -> None:
    # Across processes heyoka's own on-disk JIT cache replaces the pickled copies andoyer
    # used to keep (measured: 0.063 s from it vs 0.035 s from the pickle, 1.0 s with none).
    import heyoka as hy

    tol = 3.1e-11
    V.clear_memory_cache()
    assert V.warm_up(batch_size=1, tol=tol)[0] == "compiled"
    assert V.warm_up(batch_size=1, tol=tol)[0] == "memory"
    assert hy.llvm_state.get_diskcache_enabled()
    V.clear_memory_cache()
