"""propagate / poincare / integrate_canonical: validation, datasets, agreement."""

import numpy as np
import pytest
import xarray as xr

from andoyer import RigidBody, from_andoyer, to_hess
from andoyer.integrate import Section
from andoyer.integrate.api import integrate_canonical, poincare, propagate
from andoyer.integrate.engines import available_engines, get_engine
from andoyer.io import write_netcdf

BODY = RigidBody.paper()
X0 = np.array([[0.3, 1.0, 0.2, 1.0, 0.0], [1.3, 2.0, -0.4, 1.1, 0.0]])
FAST = [e for e in ("heyoka", "numba") if e in available_engines()]


@pytest.mark.parametrize("engine", FAST + ["scipy"])
def test_propagate_dataset(engine):
    ds = propagate(BODY, X0, np.linspace(0, 50, 11), chart="andoyer", engine=engine)
    assert ds.sizes == {"orbit": 2, "time": 11}
    for v in ("G1", "gamma3", "l_angle", "L_action", "theta1", "J1", "H", "H_drift"):
        assert v in ds
    # DOP853 at rtol = atol = 1e-12 loses about 1e-11 of |gamma|^2 within a few steps.
    assert float(abs(ds.H_drift).max()) < 1e-10
    assert float(abs(ds.area_drift).max()) < 1e-10
    assert float(abs(ds.geometric_drift).max()) < 1e-10
    assert ds.attrs["engine"] == engine and ds.attrs["rtol"] == 1e-12
    assert ds.attrs["body_A"] == 2.5 and "andoyer_version" in ds.attrs
    assert ds.L_action.attrs["symbol"] == "L" and ds.l_angle.attrs["units"] == "rad"
    np.testing.assert_allclose(ds.isel(time=0)[["G1", "G2", "G3"]].to_array().T,
                               from_andoyer(X0)[:, :3], atol=1e-15)


def test_engines_agree():
    t = np.linspace(0, 100, 5)
    ref = propagate(BODY, X0, t, chart="andoyer", engine="scipy", rtol=1e-13, atol=1e-13)
    for engine in FAST:
        ds = propagate(BODY, X0, t, chart="andoyer", engine=engine)
        for v in ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3"):
            np.testing.assert_allclose(ds[v], ref[v], atol=1e-9)


def test_initial_state_charts_agree():
    xh = to_hess(BODY, from_andoyer(X0))
    a = propagate(BODY, X0, [0, 1.0], chart="andoyer", engine="scipy")
    b = propagate(BODY, xh, [0, 1.0], chart="hess", engine="scipy")
    np.testing.assert_allclose(a.G1, b.G1, atol=1e-13)


@pytest.mark.parametrize(("kw", "match"), [
    ({"t": [0.0]}, "at least 2"),
    ({"t": [0.0, 2.0, 1.0]}, "strictly increasing"),
    ({"t": [0.0, np.nan]}, "NaN"),
    ({"rtol": 1e-20}, "rtol"),
    ({"atol": 0.0}, "atol"),
    ({"engine": "rk4"}, "unknown engine"),
    ({"y0": [0, 0, 1, 0, 0, 1.001]}, "unit vector"),
    ({"y0": [0, 0, 1, 0, 0]}, r"shape \(\.\.\., 6\)"),
    ({"y0": [0, 0, 1, 0, 0, np.inf]}, "NaN or infinity"),
    ({"chart": "cartesian"}, "unknown chart"),
])
def test_propagate_bad_input(kw, match):
    args = {"y0": [0.0, 0.0, 1.0, 0.0, 0.6, 0.8], "t": [0.0, 1.0]}
    args.update(kw)
    y0, t = args.pop("y0"), args.pop("t")
    with pytest.raises(ValueError, match=match):
        propagate(BODY, y0, t, **args)


def test_gamma_renormalised_within_tolerance():
    y0 = np.array([0.0, 0.0, 1.0, 0.0, 0.6, 0.8 * (1 + 5e-13)])
    ds = propagate(BODY, y0, [0.0, 1.0], engine="scipy")
    assert abs(ds.geometric.isel(time=0).item() - 1) < 1e-15


@pytest.mark.parametrize("engine", FAST)
@pytest.mark.parametrize("text", ["G3=0:+", "g=0.5", "theta2=0:0", "theta2=6.2831"])
def test_poincare_points_on_section(engine, text):
    sec = Section.parse(text)
    ds = poincare(BODY, X0, sec, 20, engine=engine, chart="andoyer")
    assert ds.sizes == {"orbit": 2, "crossing": 20, "component": 6}
    assert int(ds.crossings_found.min()) == 20
    assert float(abs(ds.section_residual).max()) <= 1e-12
    assert ds.attrs["section_coord"] == sec.coord
    assert np.all(np.diff(ds.t.values, axis=1) > 0)


def test_poincare_engines_agree_with_scipy():
    sec = Section("G3", 0.0, 1)
    ref = poincare(BODY, X0, sec, 5, engine="scipy", rtol=1e-13, atol=1e-13,
                   chart="andoyer")
    for engine in FAST:
        ds = poincare(BODY, X0, sec, 5, engine=engine, chart="andoyer")
        np.testing.assert_allclose(ds.t, ref.t, rtol=1e-9)
        np.testing.assert_allclose(ds.G1, ref.G1, atol=1e-9)


def test_poincare_bad_input():
    with pytest.raises(ValueError, match="unknown section coordinate"):
        poincare(BODY, X0, "M=0", 3, chart="andoyer")
    with pytest.raises(ValueError, match="n_crossings"):
        poincare(BODY, X0, "g=0", 0, chart="andoyer")
    with pytest.raises(ValueError, match="G1-G2 principal plane"):
        poincare(RigidBody(2, 3, 4, 0.1, (0, 0, 1)), [0, 0, 1, 0, 0.6, 0.8], "theta2=0", 3)
    with pytest.raises(ValueError, match="not a number"):
        Section.parse("g==0")
    with pytest.raises(ValueError, match="cannot parse"):
        Section.parse("g")


def test_netcdf_round_trip(tmp_path):
    ds = poincare(BODY, X0, "g=0", 3, chart="andoyer", engine="scipy")
    out = write_netcdf(ds, tmp_path / "s.nc")
    back = xr.open_dataset(out)
    np.testing.assert_array_equal(back.t.values, ds.t.values)
    assert back.attrs["section_coord"] == "g"
    assert not list(tmp_path.glob(".*tmp"))
    with pytest.raises(ValueError, match="does not exist"):
        write_netcdf(ds, tmp_path / "nope" / "s.nc")


def test_integrate_canonical_matches_euler_poisson():
    xh = to_hess(BODY, from_andoyer(X0[0]))
    t = np.linspace(0, 20, 5)
    can = integrate_canonical(BODY, xh, t, chart="hess")
    ep = propagate(BODY, X0[0], t, chart="andoyer", engine="scipy")
    np.testing.assert_allclose(can.J1, ep.J1.isel(orbit=0), atol=1e-9)
    ad = integrate_canonical(BODY, X0[0], t, chart="andoyer")
    np.testing.assert_allclose(ad.L_action, ep.L_action.isel(orbit=0), atol=1e-9)


def test_integrate_canonical_stops_at_singularity():
    # Start close to J1 = 0 (L = -G), heading there: a clear error.
    x = np.array([0.0, 0.0, 1e-8, 1.0, 0.0])
    with pytest.raises(ValueError, match="singular set"):
        integrate_canonical(RigidBody.paper(0.0), x, [0.0, 200.0], chart="hess",
                            singular_margin=1e-6)


def test_get_engine_unknown():
    with pytest.raises(ValueError, match="unknown engine"):
        get_engine("euler")


@pytest.mark.parametrize("section", ["g=0.7", "theta2=0", "L=0.2", "G3=0"])
def test_poincare_derives_no_chart_until_one_is_read(section, monkeypatch):
    # section_residual comes from the crossings' own check: building the dataset maps no
    # chart, and the residual equals the definition on the mapped coordinate
    import andoyer.integrate.results as results
    from andoyer.notation import storage_name

    calls = []
    real = results.derived_values
    monkeypatch.setattr(results, "derived_values",
                        lambda *a, **k: calls.append(1) or real(*a, **k))
    ds = poincare(BODY, from_andoyer(X0), section, 6, engine="numba", t_max=400.0)
    assert calls == []
    sec = Section.parse(section)
    var = ds[storage_name(sec.coord)].values
    want = np.sin(var - sec.value) if sec.is_angle else var - sec.value
    assert int(ds.crossings_found.sum()) > 0
    np.testing.assert_array_equal(ds.section_residual.values, want)
    assert np.all(np.isfinite(ds.H.values) == np.isfinite(ds.t.values))
    assert calls == [1]   # once, at the first derived variable read
