"""The FLI-only chaos map (state and one tangent vector, not renormalised) against the
renormalised system with the MEGNO quadratures (an independent integration of other
equations).

* ``indicator="fli"`` integrates ``w' = J w`` as is; ``indicator="both"`` integrates
  ``u = w/|w|`` and ``ln|w|``: their FLI and ``ln|w(t_end)|/t_end`` agree to 1e-8 on
  the map's tori, and to 1e-5 relative in its chaotic layer (where any two
  integrations part as ``e^(lambda t)``);
* orbits whose ``ln|w|`` nears overflow are integrated again renormalised (forced here by
  lowering the threshold): the same numbers;
* the heyoka engine's 12-variable SIMD flow gives ``w`` of the fundamental matrix
  (``var_ode_sys``, orbit by orbit) to 1e-9.
"""

from __future__ import annotations

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.chaos import lyapunov as chaos
from andoyer.analysis.chaos.lyapunov import IndicatorRun, MapGrid, chaos_map, initial_tangent
from andoyer.charts.hess import from_hess
from andoyer.integrate.engines import resolve_engine
from andoyer.integrate.engines.base import Capability, Tolerance

#: The Hess body of test_chaos.py with a wide chaotic layer at h = mu.
CHAOTIC_BODY = RigidBody.hess(3.0, 1.0, 2.0, mu=1.0)
MAP = MapGrid((6, 6))


def _map(indicator: str, **kw: object) -> object:
    return chaos_map(CHAOTIC_BODY, 1.0, 0.0, "theta2=0", MAP,
                     IndicatorRun(indicator, t_end=300.0), **kw)  # type: ignore[arg-type]


def test_fli_only_map_agrees_with_the_renormalised_system() -> None:
    fast, full = _map("fli"), _map("both")
    acc = full.accessible.values
    assert acc.sum() >= 20
    for v in ("fli", "mle", "H_error"):
        assert np.all(np.isnan(fast[v].values[~acc]))
    # On the tori to 1e-8; in the chaotic layer two integrations of different equations
    # part as e^(lambda t) times the local error (measured 3e-5 at FLI 25, t = 300).
    reg = acc & (full.fli.values < 12.0)
    assert 10 <= reg.sum() < acc.sum()
    np.testing.assert_allclose(fast.fli.values[reg], full.fli.values[reg], rtol=0, atol=1e-8)
    np.testing.assert_allclose(fast.mle.values[reg], full.mle.values[reg], rtol=0, atol=1e-10)
    np.testing.assert_allclose(fast.fli.values[acc], full.fli.values[acc], rtol=1e-5)
    assert float(np.nanmax(fast.H_error)) < 1e-11
    # The map holds both kinds of orbit: FLI ~ ln t on tori, ~ lambda t in the layer.
    assert np.nanmin(fast.fli) < 10.0 < 20.0 < np.nanmax(fast.fli)
    assert "FLI only" in fast.attrs["equations"]
    assert "continuous renormalisation" in full.attrs["equations"]


def test_orbits_near_overflow_are_integrated_again_renormalised(
        monkeypatch: pytest.MonkeyPatch) -> None:
    fast = _map("fli")
    monkeypatch.setattr(chaos, "_OVERFLOW_LOG", 5.0)  # most points of the map exceed it
    redone = _map("fli")
    assert np.nanmax(fast.fli) > 5.0
    reg = fast.fli.values < 12.0  # as above: chaotic points to 1e-5 relative
    np.testing.assert_allclose(redone.fli.values[reg], fast.fli.values[reg], rtol=0,
                               atol=1e-8)
    np.testing.assert_allclose(redone.mle.values[reg], fast.mle.values[reg], rtol=0,
                               atol=1e-10)
    np.testing.assert_allclose(redone.fli.values, fast.fli.values, rtol=1e-5)


@pytest.mark.heyoka
def test_plain_simd_flow_is_the_fundamental_matrix_times_w0() -> None:
    y0 = from_hess(CHAOTIC_BODY, [[0.2617993877991494, 0.0, 1.0103629710818451,
                                   1.712575169922734, 0.0],
                                  [2.8797932657906435, 0.0, 0.7216878364870322,
                                   1.3852961954031033, 0.0]] * 5)
    w0 = initial_tangent(CHAOTIC_BODY, y0)[:, None, :]
    t = np.linspace(0.0, 50.0, 11)
    tol = Tolerance.single(1e-13)
    simd = resolve_engine("heyoka", Capability.TANGENT, batch_size=4, n_threads=2)
    one = resolve_engine("heyoka", Capability.TANGENT, batch_size=1)
    a = simd.tangent(y0, w0, CHAOTIC_BODY.engine_params, tol, t=t, renormalise=False)
    b = one.tangent(y0, w0, CHAOTIC_BODY.engine_params, tol, t=t, renormalise=False)
    assert a.ok.all() and b.ok.all() and a.megno is None
    np.testing.assert_allclose(a.rho, b.rho, rtol=0, atol=1e-9)
    np.testing.assert_allclose(a.y, b.y, rtol=0, atol=1e-10)


@pytest.mark.heyoka
def test_fli_only_map_is_the_same_in_chunks_and_on_one_thread() -> None:
    """The FLI-only map on heyoka does not depend on how its orbits are chunked or
    threaded: every chunk runs in the SIMD code chosen for the whole map (twice the SIMD
    width for this 12-variable flow), bit for bit."""
    a = _map("fli", engine="heyoka")
    engine = resolve_engine("heyoka", Capability.TANGENT, n_threads=1)
    b = _map("fli", chunk=5, engine=engine)
    assert int(a.accessible.sum()) > 5
    for v in ("fli", "mle", "H_error"):
        np.testing.assert_array_equal(a[v].values, b[v].values)


def test_fli_only_map_on_taylor_in_threads_chunks_and_lanes() -> None:
    """On taylor, threads and chunks change no bit: the map's engine is set up for the
    whole map (``for_ensemble``), so a chunk of fewer than LANES_FROM orbits runs on the
    SIMD lanes too (on the scalar kernel its FLI would differ in the round-off)."""
    a = _map("fli", engine="taylor")
    one = resolve_engine("taylor", Capability.TANGENT, n_threads=1)
    b = _map("fli", engine=one)
    for v in ("fli", "mle", "H_error"):
        np.testing.assert_array_equal(a[v].values, b[v].values)
    c = _map("fli", chunk=5, engine="taylor")
    for v in ("fli", "mle", "H_error"):
        np.testing.assert_array_equal(c[v].values, a[v].values)
