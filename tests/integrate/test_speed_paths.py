"""The fast paths give the same answers as the simple ones (no timing here).

* heyoka engine, batched sections: the pilot + longest-first schedule + per-lane end
  times give the crossings of the scalar integrator, for orbits of very different
  return times on 2 threads, including orbits that never cross and orbits done in the
  pilot;
* the schedule puts the longest orbits first; end times are predicted from the
  return time;
* numba engine: a state seeded on the section is not a crossing (same rule as heyoka);
* ``propagate``'s drifts (computed in NumPy) are the documented definitions;
* ``poincare`` hands all orbits to the engine in one call unless a progress line is
  shown.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from andoyer import RigidBody, area_integral, energy, from_andoyer, geometric_integral
from andoyer.integrate import Section, poincare, propagate
from andoyer.integrate import api as api_module
from andoyer.kernels.generated.equations import SECTION_KINDS

hy = pytest.importorskip("heyoka")
from andoyer.integrate.engines import heyoka_engine as he  # noqa: E402
from andoyer.integrate.engines.base import Tolerance  # noqa: E402
from andoyer.integrate.engines.numba_engine import NumbaEngine  # noqa: E402

TOL12 = Tolerance(1e-12, 1e-12)

BODY = RigidBody.paper()
P = BODY.engine_params


def orbits(n: int) -> np.ndarray:
    """Rotations and librations of l, |G| = 1: G3 returns at very different rates."""
    x = np.column_stack([np.linspace(0.1, 6.0, n), np.linspace(0.3, 5.0, n),
                         np.linspace(-0.8, 0.8, n), np.ones(n), np.linspace(-0.5, 0.4, n)])
    return from_andoyer(x)


def test_scheduled_batches_agree_with_scalar_integrators() -> None:
    y0 = orbits(13)
    args = (P, Section("G3", 0.0, 1), 40, 3e3, TOL12)
    scalar = he.HeyokaEngine(batch_size=1, n_threads=1).crossings(y0, *args)
    batch = he.HeyokaEngine(batch_size=4, n_threads=2).crossings(y0, *args)
    assert len(set(np.round(scalar.t[:, -1] / scalar.t[:, 0], 1))) > 5  # varied orbits
    np.testing.assert_array_equal(batch.count, scalar.count)
    np.testing.assert_allclose(batch.t, scalar.t, rtol=0, atol=1e-9)
    np.testing.assert_allclose(batch.y, scalar.y, rtol=0, atol=1e-9)


def test_orbits_that_never_cross_and_orbits_done_in_the_pilot() -> None:
    y0 = orbits(6)
    eng = he.HeyokaEngine(batch_size=4, n_threads=2)
    never = eng.crossings(y0, P, Section("G3", 5.0, 1), 10, 200.0, TOL12)
    np.testing.assert_array_equal(never.count, 0)
    assert np.all(np.isnan(never.t))
    few = eng.crossings(y0, P, Section("G3", 0.0, 1), 1, 1e4, TOL12)
    ref = he.HeyokaEngine(batch_size=1).crossings(y0, P, Section("G3", 0.0, 1), 1, 1e4, TOL12)
    np.testing.assert_allclose(few.t, ref.t, rtol=0, atol=1e-9)


def test_orbit_bookkeeping_predicts_end_time_from_return_time() -> None:
    o = he._Orbit(0, np.zeros(6))
    assert math.isnan(o.return_time())
    assert o.end_time(10, 500.0) == 500.0  # unknown return time: run to t_max
    o.hi, o.steps = 25.0, 50
    t = np.zeros(3)
    t[:] = (5.0, 15.0, 25.0)
    o.add(he._Found(t, np.zeros((3, 6))))
    assert o.return_time() == 10.0
    assert o.end_time(10, 500.0) == 25.0 + 7.5 * 10.0  # 7 to go, then half a return
    assert o.end_time(10, 60.0) == 60.0
    assert o.steps_to(35.0) == 20.0  # 2 steps per time unit so far
    assert not o.done(10, 500.0) and o.done(3, 500.0) and o.done(10, 25.0)


def test_schedule_is_longest_first_and_drops_finished_orbits() -> None:
    def orbit(i: int, hi: float, steps: int, period: float, n: int) -> he._Orbit:
        o = he._Orbit(i, np.zeros(6))
        o.hi, o.steps = hi, steps
        t = hi - period * np.arange(n, dtype=np.float64)[::-1]
        o.add(he._Found(t, np.zeros((n, 6))))
        return o

    todo = [orbit(0, 30.0, 30, 10.0, 3), orbit(1, 30.0, 30, 5.0, 6),
            orbit(2, 30.0, 30, 30.0, 1), orbit(3, 30.0, 30, 1.0, 20)]
    order = [o.index for o in he._schedule(todo, 20, 1e6)]
    assert order == [2, 0, 1]  # orbit 3 is done; then by steps still to go


def test_numba_does_not_count_an_initial_state_on_the_section() -> None:
    from andoyer.integrate import fill_section

    h = float(energy(BODY, from_andoyer([0.3, 0.0, 0.3, 1.0, 0.0])))
    y0 = fill_section(BODY, h, 0.0, ("theta2", 0.0), n_orbits=6)["y0"].values  # on theta2 = 0
    k = SECTION_KINDS.index("theta2")
    nb = NumbaEngine().crossings(y0, P, Section.from_kind(k, 0.0, 0), 3, 1e3, TOL12)
    hk = he.HeyokaEngine().crossings(y0, P, Section.from_kind(k, 0.0, 0), 3, 1e3, TOL12)
    assert np.all(nb.t[:, 0] > 1e-3)
    np.testing.assert_allclose(nb.t, hk.t, rtol=0, atol=1e-8)


def test_propagate_drifts_are_the_documented_definitions() -> None:
    y0 = orbits(2)
    ds = propagate(BODY, y0, np.linspace(0.0, 50.0, 6), progress=False)
    Y = np.stack([ds[v].values for v in ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")],
                 axis=-1)
    H, area, geo = energy(BODY, Y), area_integral(Y), geometric_integral(Y)
    G0 = np.linalg.norm(Y[:, 0, :3], axis=-1)[:, None]
    np.testing.assert_allclose(ds.H_drift, (H - H[:, :1]) / np.abs(H[:, :1]), atol=1e-18)
    np.testing.assert_allclose(ds.area_drift, (area - area[:, :1]) / G0, atol=1e-18)
    np.testing.assert_allclose(ds.geometric_drift, geo - geo[:, :1], atol=1e-18)
    assert ds.H_drift.dims == ("orbit", "time") and ds.H_drift.attrs["units"] == "1"
    assert abs(ds.H_drift).max() < 1e-12 and ds.H_drift.attrs["long_name"].startswith("drift")


@pytest.mark.parametrize("progress, calls", [(False, 1), (True, 2)])
def test_poincare_calls_the_engine_once_without_progress(monkeypatch, capsys, progress,
                                                         calls) -> None:
    seen: list[int] = []
    real = he.HeyokaEngine.crossings

    def spy(self, y0, *args):
        seen.append(len(y0))
        return real(self, y0, *args)

    monkeypatch.setattr(he.HeyokaEngine, "crossings", spy)
    n = 2 * api_module._MIN_CHUNK
    y0 = np.repeat(orbits(1), n, axis=0)
    poincare(BODY, y0, Section("G3", 0.0), 1, engine="heyoka", progress=progress)
    assert seen == [n // calls] * calls
