"""The states dataset: derived variables built lazily, equal to the chart maps."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.charts.andoyer_deprit import to_andoyer
from andoyer.charts.euler_poisson import energy
from andoyer.charts.hess import to_hess
from andoyer.integrate import propagate
from andoyer.integrate.results import states_dataset


@pytest.fixture(scope="module")
def orbit():
    body = RigidBody.paper()
    ds = propagate(body, [0.3, 1.0, 0.2, 1.0, 0.0], np.linspace(0, 50, 201), chart="andoyer",
                   engine="numba")
    y = np.stack([ds[v].values for v in ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")], -1)
    return body, ds, y


def test_lazy_variables_equal_the_chart_maps(orbit) -> None:
    body, ds, y = orbit
    x = to_andoyer(y)
    for i, name in enumerate(("l_angle", "g_angle", "L_action", "G_action", "M_action")):
        np.testing.assert_array_equal(ds[name].values, x[..., i])
    np.testing.assert_array_equal(ds.theta1.values, to_hess(body, y)[..., 0])
    np.testing.assert_array_equal(ds.H.values, energy(body, y))
    H = energy(body, y)
    np.testing.assert_allclose(ds.H_drift.values, (H - H[:, :1]) / abs(H[:, :1]))
    assert ds.singular.dtype == np.int64 and ds.H_drift.attrs["units"] == "1"


def test_hess_chart_from_given_andoyer_coordinates(orbit) -> None:
    body, _, y = orbit
    np.testing.assert_array_equal(to_hess(body, y, andoyer=to_andoyer(y, with_mask=True)),
                                  to_hess(body, y))


def test_lazy_dataset_pickles_slices_and_writes(orbit, tmp_path) -> None:
    body, _, y = orbit
    ds = states_dataset(body, y, ("orbit", "time"), {"time": np.arange(y.shape[1])}, {},
                        drifts=True)
    back = pickle.loads(pickle.dumps(ds))  # Dask scans ship datasets between processes
    np.testing.assert_array_equal(back.g_angle.values, to_andoyer(y)[..., 1])
    np.testing.assert_array_equal(ds.isel(time=slice(3, 9)).theta2.values,
                                  to_hess(body, y)[:, 3:9, 1])
    ds.to_netcdf(tmp_path / "o.nc")
    import xarray as xr
    with xr.open_dataset(tmp_path / "o.nc") as f:
        np.testing.assert_array_equal(f.M_action.values, to_andoyer(y)[..., 4])


def test_padding_gives_nan_and_flag_minus_one() -> None:
    body = RigidBody.paper()
    y = np.array([[0.0, 0.6, 0.8, 0.0, 0.6, 0.8], [np.nan] * 6])
    ds = states_dataset(body, y, ("crossing",), {}, {})
    assert np.isfinite(ds.H.values[0]) and np.isnan(ds.H.values[1])
    assert ds.singular.values.tolist()[1] == -1


def test_copies_are_independent_and_derive_once(orbit, monkeypatch) -> None:
    import andoyer.integrate.results as results

    body, _, y = orbit
    calls = []
    real = results.derived_values
    monkeypatch.setattr(results, "derived_values",
                        lambda *a, **k: calls.append(1) or real(*a, **k))
    ds = states_dataset(body, y, ("orbit", "time"), {}, {}, drifts=True)
    assert not calls  # nothing derived until read
    deep = ds.copy(deep=True).load()
    assert len(calls) == 1  # once for every variable, not once per variable
    deep.H.values[0, 0] = 99.0
    assert ds.H.values[0, 0] == energy(body, y[0, 0])  # the copy is independent


def test_writes_into_values_stay(orbit) -> None:
    """Once read, a derived variable is one array (as in an eager dataset)."""
    body, _, y = orbit
    ds = states_dataset(body, y, ("orbit", "time"), {}, {})
    ds["J2"].values[...] = 7.0  # the first access is a write
    assert np.all(ds.J2.values == 7.0)
    copy = ds.copy(deep=True)
    copy["J2"].values[...] = 8.0
    assert np.all(ds.J2.values == 7.0)


def test_built_directly_as_the_public_constructor_builds(orbit) -> None:
    # states_dataset skips xarray's merge where nothing is left to merge: the same dataset
    import xarray as xr

    body, _, y = orbit
    coords = {"orbit": np.arange(y.shape[0]), "time": np.linspace(0.0, 50.0, y.shape[1])}
    extra = {"count": (("orbit",), np.ones(y.shape[0], dtype=np.int64))}
    ds = states_dataset(body, y, ("orbit", "time"), coords, {"a": 1}, extra, drifts=True)
    ref = xr.Dataset({k: ds.variables[k] for k in ds.data_vars}, coords=coords,
                     attrs={"a": 1})
    xr.testing.assert_identical(ds.load(), ref.load())
    assert list(ds.variables) == list(ref.variables)
    assert set(ds.xindexes) == {"orbit", "time"} and set(ds.coords) == {"orbit", "time"}
    assert ds.sel(time=50.0).G_action.shape == (y.shape[0],)


@pytest.mark.parametrize("coords, extra", [
    ({"time": np.arange(3)}, None),  # a coordinate of the wrong size
    ({}, {"count": (("orbit",), np.ones(5))}),  # a variable of the wrong size
])
def test_sizes_that_disagree_are_refused(orbit, coords, extra) -> None:
    body, _, y = orbit
    with pytest.raises(ValueError, match="conflicting sizes|length"):
        states_dataset(body, y, ("orbit", "time"), coords, {}, extra)


def test_other_coordinates_as_before(orbit) -> None:
    # a coordinate of strings, or one that is not a dimension's, takes the public path
    body, _, y = orbit
    ds = states_dataset(body, y[0], ("time",), {"time": np.arange(y.shape[1]),
                                                "component": ["w", "x"]}, {})
    assert ds.component.values.tolist() == ["w", "x"] and ds.sizes["component"] == 2
