"""Chaos indicators on the numba engine (no heyoka needed), and against heyoka's.

* known cases, as in ``test_chaos.py`` but with ``engine="numba"``: the Lyapunov rate
  ``sigma G0`` at the middle-axis rotation, ``<Y> -> 2`` on a torus, a positive exponent
  and a growing ``<Y>`` in the chaotic layer of a Hess body;
* agreement with the heyoka engine on FLI, MEGNO and mLE, on a torus (t = 1000) and on
  the chaotic orbit within its predictability horizon (t = 200; beyond, round-off grown
  by ``exp(lambda t)`` makes the two orbits different members of the chaotic layer);
* the engine is numba by default where heyoka is missing; chaos maps run on it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.chaos.lyapunov import IndicatorRun, chaos_map, indicators
from andoyer.integrate import engines

PAPER = RigidBody.paper()
TORUS = [0.3, 0.0, 0.3, 1.0, 0.0]
FREE = RigidBody.euler_poinsot(2.5, 2.0, 2.2)
CHAOTIC_BODY = RigidBody.hess(3.0, 1.0, 2.0, mu=1.0)
CHAOTIC = [0.2617993877991494, 0.0, 1.0103629710818451, 1.712575169922734, 0.0]
REGULAR = [2.8797932657906435, 0.0, 0.7216878364870322, 1.3852961954031033, 0.0]


def test_lyapunov_rate_at_the_middle_axis_rotation_is_the_eigenvalue() -> None:
    G0, T = 1.0, 400.0
    y0 = [0.0, 0.0, G0, math.sin(1.0), 0.0, math.cos(1.0)]
    ds = indicators(FREE, y0, T, n_times=401, engine="numba")
    t, ln = ds.time.values, ds.log_norm.isel(orbit=0).values
    late = t >= T / 4
    slope = np.polyfit(t[late], ln[late], 1)[0]
    assert slope == pytest.approx(FREE.sigma * G0, rel=3e-3)  # measured 1.0e-3
    Y = ds.megno.isel(orbit=0).values
    assert 2 * (Y[-1] - Y[200]) / (t[-1] - t[200]) == pytest.approx(FREE.sigma * G0,
                                                                    rel=0.05)
    assert ds.attrs["engine"] == "numba" and "numba_version" in ds.attrs


def test_megno_tends_to_two_on_a_torus_and_grows_on_a_chaotic_orbit() -> None:
    torus = indicators(PAPER, TORUS, 2000.0, chart="andoyer", engine="numba")
    end = torus.isel(orbit=0, time=-1)
    assert abs(float(end.megno) - 2.0) < 0.1 and float(end.mle) < 0.005
    assert float(abs(torus.H_drift).max()) < 1e-12
    ds = indicators(CHAOTIC_BODY, CHAOTIC, 1000.0, chart="hess", engine="numba")
    end = ds.isel(orbit=0, time=-1)
    assert float(end.mle) > 0.03 and float(end.fli) > 30.0  # measured 0.060, 60.0
    assert float(end.megno) > 1.8 * float(ds.megno.isel(orbit=0).sel(time=500.0))
    regular = indicators(CHAOTIC_BODY, REGULAR, 1000.0, chart="hess", engine="numba")
    assert abs(float(regular.megno.isel(orbit=0, time=-1)) - 2.0) < 0.3


@pytest.mark.parametrize("case", ["torus", "hess_regular", "chaotic"])
def test_indicators_agree_with_the_heyoka_engine(case: str) -> None:
    pytest.importorskip("heyoka", reason="the comparison needs heyoka")
    body, y0, chart, T, bound = {
        # measured max over the 101 times |numba - heyoka|: FLI 1.2e-13, <Y> 2.9e-8
        # (at t = 10; 2.9e-10 at the end), mLE 2.3e-15
        "torus": (PAPER, TORUS, "andoyer", 1000.0, {"fli": 1e-10, "megno": 1e-6,
                                                    "mle": 1e-12}),
        # FLI 1.9e-11, <Y> 3.6e-8, mLE 3.3e-14
        "hess_regular": (CHAOTIC_BODY, REGULAR, "hess", 1000.0,
                         {"fli": 1e-9, "megno": 1e-6, "mle": 1e-12}),
        # FLI 8.7e-11, <Y> 4.0e-9, mLE 2.4e-12 (t <= 100: exp(lambda t) ~ 1e3)
        "chaotic": (CHAOTIC_BODY, CHAOTIC, "hess", 100.0,
                    {"fli": 1e-8, "megno": 1e-6, "mle": 1e-10}),
    }[case]
    a = indicators(body, y0, T, chart=chart, engine="heyoka")
    b = indicators(body, y0, T, chart=chart, engine="numba")
    for name, tol in bound.items():
        diff = np.abs(a[name].values[:, 1:] - b[name].values[:, 1:])
        assert diff.max() < tol, (name, diff.max())


def test_numba_is_the_default_without_heyoka(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(engines, "default_engine_name", lambda *capabilities, **_: "numba")
    ds = indicators(PAPER, TORUS, 10.0, chart="andoyer", n_times=3)
    assert ds.attrs["engine"] == "numba" and "heyoka_version" not in ds.attrs
    with pytest.raises(ValueError, match="cannot integrate the variational equations"):
        indicators(PAPER, TORUS, 10.0, chart="andoyer", engine="euler")


def test_chaos_map_runs_on_numba() -> None:
    ds = chaos_map(PAPER, 0.2466, 0.0, "theta2=0", 4, IndicatorRun("both", t_end=50.0),
                   engine="numba")
    assert ds.attrs["engine"] == "numba" and int(ds.accessible.sum()) > 0
    acc = ds.accessible.values
    assert np.all(np.isfinite(ds.fli.values[acc])) and ds.attrs["n_failed"] == 0
    assert float(ds.H_error.max()) < 1e-11
    try:
        import heyoka  # noqa: F401
    except ImportError:
        return
    ref = chaos_map(PAPER, 0.2466, 0.0, "theta2=0", 4, IndicatorRun("both", t_end=50.0),
                    engine="heyoka")
    np.testing.assert_allclose(ds.fli.values[acc], ref.fli.values[acc], atol=1e-8)
    np.testing.assert_allclose(ds.megno.values[acc], ref.megno.values[acc], atol=1e-6)
