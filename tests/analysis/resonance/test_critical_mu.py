"""The critical mu over the energy levels, mu_c(h) (G5), (G7): one computation scaled on
M = 0, one per level otherwise; the scaling law checked by an independent computation on a
second level."""

import math

import numpy as np
import pytest
import xarray as xr

from andoyer import RigidBody
from andoyer.analysis.resonance import residues
from andoyer.analysis.resonance.residues import MAX_LEVELS, critical_mu_curve, last_torus

HESS = RigidBody.hess(3.0, 1.0, 2.0, mu=2e-3)
CHEAP = {"head": (2,), "axis": 2, "n_convergents": 3}


class _Recorder:
    """A stand-in for last_torus: records its calls, returns mu_c = 0.05 h (+ M)."""

    def __init__(self):
        self.calls = []

    def __call__(self, body, h, M=0.0, **kwargs):
        self.calls.append((body.mu, h, M, kwargs))
        return xr.Dataset({"mu_critical": 0.05 * h + M, "mu_critical_error": 0.001 * h},
                          attrs={"rotation_number": 0.38, "head": "2",
                                 "main_chains": "2:1, 3:1", "tolerance": 1e-13,
                                 "engine": "taylor"})


def test_on_M_zero_one_level_is_computed_and_scaled(monkeypatch):
    fake = _Recorder()
    monkeypatch.setattr(residues, "last_torus", fake)
    ds = critical_mu_curve(HESS, [0.5, 1.0, 3.0], mu_range=(0.01, 1.0), progress=False,
                           **CHEAP)
    assert len(fake.calls) == 1
    mu, h, M, kwargs = fake.calls[0]
    assert (mu, h, M) == (HESS.mu, 0.5, 0.0) and kwargs["mu_range"] == (0.01, 1.0)
    assert kwargs["axis"] == 2 and kwargs["n_convergents"] == 3
    np.testing.assert_allclose(ds.mu_critical, 0.025 * np.array([0.5, 1.0, 3.0]) / 0.5)
    np.testing.assert_allclose(ds.mu_critical_error, 0.0005 * np.array([1.0, 2.0, 6.0]))
    assert ds.mu_critical.dims == ("h_level",)
    assert ds.attrs["method"] == "scaled" and ds.attrs["reference_level"] == 0.5
    assert ds.attrs["kind"] == "critical_mu_curve" and ds.attrs["M"] == 0.0
    assert ds.mu_critical.attrs["equation"] == "(G5), (G7)"
    assert ds.mu_critical.attrs["symbol"] == "\\mu_c"


def test_off_M_zero_every_level_is_computed(monkeypatch):
    fake = _Recorder()
    monkeypatch.setattr(residues, "last_torus", fake)
    ds = critical_mu_curve(HESS, [1.0, 2.0], 0.2, mu_range=(0.01, 1.0), progress=False,
                           **CHEAP)
    assert [c[1] for c in fake.calls] == [1.0, 2.0]
    assert [c[2] for c in fake.calls] == [0.2, 0.2]
    # mu_range and the body's mu follow h / h0
    assert fake.calls[1][3]["mu_range"] == (0.02, 2.0)
    assert fake.calls[1][0] == pytest.approx(2 * HESS.mu)
    np.testing.assert_allclose(ds.mu_critical, [0.25, 0.3])
    assert ds.attrs["method"] == "per_level"


@pytest.mark.parametrize("h_values, message", [
    ([], "h_values"), ([1.0, -1.0], "h_values"), ([2.0, 1.0], "h_values"),
    ("x", "h_values"), ([1.0, math.nan], "h_values"), ([[1.0, 2.0]], "h_values"),
])
def test_bad_levels_are_refused_by_name(h_values, message):
    with pytest.raises(ValueError, match=message):
        critical_mu_curve(HESS, h_values, mu_range=(0.01, 1.0), progress=False)


def test_bad_options_are_refused_by_name():
    with pytest.raises(ValueError, match="mu_range"):
        critical_mu_curve(HESS, [1.0], mu_range=(0.01,), progress=False)
    with pytest.raises(ValueError, match="mu_range"):
        critical_mu_curve(HESS, [1.0], mu_range=(1.0, 0.01), progress=False)
    with pytest.raises(ValueError, match="mu_range"):
        critical_mu_curve(HESS, [1.0], mu_range=("a", "b"), progress=False)
    with pytest.raises(ValueError, match="h_values.*energy level"):
        critical_mu_curve(HESS, [1.0, 1e300], mu_range=(0.01, 1.0), progress=False)
    with pytest.raises(TypeError, match="mu_range"):
        critical_mu_curve(HESS, [1.0], progress=False)          # required
    with pytest.raises(TypeError, match="'h'"):
        critical_mu_curve(HESS, [1.0], mu_range=(0.01, 1.0), h=1.0)
    with pytest.raises(ValueError, match="n_convergents"):
        critical_mu_curve(HESS, [1.0], mu_range=(0.01, 1.0), n_convergents=0)


def test_too_many_levels_or_too_much_work_are_refused_before_any_orbit(monkeypatch):
    from andoyer.errors import CostLimitError
    from andoyer.integrate import budget

    fake = _Recorder()
    monkeypatch.setattr(residues, "last_torus", fake)
    many = np.linspace(1.0, 2.0, MAX_LEVELS + 1)
    with pytest.raises(ValueError, match="h_values.*MAX_LEVELS"):
        critical_mu_curve(HESS, many, 0.1, mu_range=(0.01, 1.0), progress=False)
    critical_mu_curve(HESS, many, 0.0, mu_range=(0.01, 1.0), progress=False, **CHEAP)
    with budget.limits(steps=1e4), pytest.raises(CostLimitError, match="critical_mu_curve"):
        critical_mu_curve(HESS, [1.0, 1.5], 0.1, mu_range=(0.01, 1.0), progress=False,
                          **CHEAP)
    assert len(fake.calls) == 1          # only the scaled one ran


@pytest.mark.slow
def test_the_scaled_curve_is_the_independent_computation_on_a_second_level():
    """(G7) on the golden torus of Hess(3, 1, 2) about axis 2 between the 2:1 and 3:1
    chains: the curve computed on h = 1 and scaled to h = 2 equals last_torus run on h = 2
    (mu_c = 0.0551 and 0.1103, 3 convergents; about 8 s each)."""
    curve = critical_mu_curve(HESS, [1.0, 2.0], mu_range=(1e-2, 1.0), progress=False, **CHEAP)
    two = last_torus(HESS.with_mu(4e-3), 2.0, mu_range=(2e-2, 2.0), progress=False, **CHEAP)
    assert 0.04 < float(curve.mu_critical[0]) < 0.07
    np.testing.assert_allclose(float(curve.mu_critical[1]), float(two.mu_critical),
                               rtol=1e-4)
    np.testing.assert_allclose(float(curve.mu_critical_error[1]),
                               float(two.mu_critical_error), rtol=1e-2)


@pytest.mark.slow
def test_off_M_zero_the_area_scales_like_the_square_root_of_h():
    """(G7) with M != 0: (h, M, mu) -> (lambda^2 h, lambda M, lambda^2 mu), lambda = 2; and
    a fixed M on 4 h is another problem (mu_c is not 4 mu_c(h))."""
    one = last_torus(HESS, 1.0, 0.3, mu_range=(1e-2, 1.0), progress=False, **CHEAP)
    four = last_torus(HESS.with_mu(8e-3), 4.0, 0.6, mu_range=(4e-2, 4.0), progress=False,
                      **CHEAP)
    fixed = last_torus(HESS.with_mu(8e-3), 4.0, 0.3, mu_range=(4e-2, 4.0), progress=False,
                       **CHEAP)
    assert math.isfinite(float(one.mu_critical))
    np.testing.assert_allclose(float(four.mu_critical), 4 * float(one.mu_critical), rtol=1e-4)
    assert abs(float(fixed.mu_critical) / (4 * float(one.mu_critical)) - 1) > 1e-3
