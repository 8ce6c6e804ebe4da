"""The chaos indicators (:func:`andoyer.analysis.chaos.lyapunov.indicators`) on the taylor
engine against the numba engine (the Numba DOP853 on the continuously renormalised
system: an independent method) and heyoka (skipped where it is not installed).

Bounds are stated per case with the measured differences (tol = 1e-12, 101 output
times). On regular orbits and on the chaotic one within its predictability horizon
(t = 100) the three engines agree to round-off amplified by the flow; beyond it (t =
1000) round-off grown by e^(lambda t) makes them different members of the chaotic
layer, so only the statistics agree. heyoka's MEGNO differs from the other two by a few
1e-8 on the tori (its quadratures are integrated scaled by 1/T^2 under one error norm),
while taylor and numba agree to 1e-11.
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from andoyer import RigidBody
from andoyer.analysis.chaos.lyapunov import indicators
from andoyer.integrate.engines import default_engine_name
from andoyer.integrate.engines.base import Capability
from andoyer.integrate.engines.lazy import heyoka_available

PAPER = RigidBody.paper()
TORUS = [0.3, 0.0, 0.3, 1.0, 0.0]  # Andoyer chart
#: As tests/analysis/chaos/test_lyapunov.py: a Hess body with a wide chaotic layer at h = mu, one
#: state in the layer and one on an invariant torus (Hess chart).
CHAOTIC_BODY = RigidBody.hess(3.0, 1.0, 2.0, mu=1.0)
CHAOTIC = [0.2617993877991494, 0.0, 1.0103629710818451, 1.712575169922734, 0.0]
REGULAR = [2.8797932657906435, 0.0, 0.7216878364870322, 1.3852961954031033, 0.0]

#: case -> (body, state, chart, t_end, {indicator: bound on max |taylor - other|}).
#: Measured taylor - numba / taylor - heyoka: paper torus FLI 1.2e-13 / 6.4e-14, <Y>
#: 6.6e-14 / 2.9e-8, mLE 2.6e-15 / 3.1e-16; Hess torus 1.8e-11 / 4.6e-12, 6.8e-12 /
#: 3.6e-8, 3.4e-14 / 9.9e-15; chaotic, t = 100: 8.2e-11 / 1.1e-11, 4.2e-11 / 4.0e-9,
#: 2.4e-12 / 1.8e-13.
CASES = {
    "paper-torus": (PAPER, TORUS, "andoyer", 1000.0,
                    {"fli": 1e-11, "megno": 1e-7, "mle": 1e-13, "megno_y": 1e-10}),
    "hess-torus": (CHAOTIC_BODY, REGULAR, "hess", 1000.0,
                   {"fli": 1e-9, "megno": 2e-7, "mle": 1e-12, "megno_y": 1e-9}),
    "chaotic-horizon": (CHAOTIC_BODY, CHAOTIC, "hess", 100.0,
                        {"fli": 1e-9, "megno": 4e-8, "mle": 1e-10, "megno_y": 1e-8}),
}
#: taylor and numba solve the same equations with error control on each quadrature:
#: their MEGNO agrees much closer than heyoka's on the tori (measured 6.6e-14, 6.8e-12).
NUMBA_MEGNO = 1e-10


def _run(engine: str, body: RigidBody, x: list[float], chart: str, t_end: float
         ) -> xr.Dataset:
    if engine == "heyoka" and not heyoka_available():
        pytest.skip("heyoka is not installed")
    ds = indicators(body, x, t_end, chart=chart, engine=engine)
    assert ds.attrs["engine"] == engine
    return ds


@pytest.fixture(scope="module")
def taylor_runs() -> dict[str, xr.Dataset]:
    return {case: _run("taylor", b, x, chart, t) for case, (b, x, chart, t, _) in CASES.items()}


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("other", ["numba", "heyoka"])
def test_indicators_agree_with_the_other_engines(case: str, other: str,
                                                 taylor_runs: dict[str, xr.Dataset]) -> None:
    body, x, chart, t_end, bounds = CASES[case]
    ref = _run(other, body, x, chart, t_end)
    ds = taylor_runs[case]
    for name, bound in bounds.items():
        if other == "numba" and name == "megno":
            bound = NUMBA_MEGNO
        diff = float(np.abs(ds[name] - ref[name]).max())
        assert diff < bound, (name, diff)
    np.testing.assert_allclose(ds.G1.values, ref.G1.values, rtol=0, atol=1e-10)


def test_regular_and_chaotic_are_told_apart_on_each_engine() -> None:
    """Beyond the horizon (t = 1000) each engine's run is its own chaotic orbit: the
    statistics agree (measured mLE 0.0547 taylor, 0.0610 numba, 0.0540 heyoka; <Y> 29.1,
    30.2, 29.0; FLI 56.1, 61.5, 54.6) and every engine tells the chaotic orbit from the
    torus (mLE 0.0066, <Y> 1.929 on each)."""
    engines = ["taylor", "numba"] + (["heyoka"] if heyoka_available() else [])
    mle = {}
    for engine in engines:
        end = _run(engine, CHAOTIC_BODY, CHAOTIC, "hess", 1000.0).isel(orbit=0, time=-1)
        mle[engine] = float(end.mle)
        assert 0.04 < float(end.mle) < 0.08
        assert float(end.megno) > 15.0 and float(end.fli) > 40.0
    assert max(mle.values()) - min(mle.values()) < 0.02
    regular = _run("taylor", CHAOTIC_BODY, REGULAR, "hess", 1000.0).isel(orbit=0, time=-1)
    assert float(regular.mle) < 0.01 and abs(float(regular.megno) - 2.0) < 0.1


def test_taylor_is_the_default_for_tangent_flows_without_heyoka() -> None:
    expected = "heyoka" if heyoka_available() else "taylor"
    assert default_engine_name(Capability.TANGENT) == expected
