"""Section crossings on SIMD lanes (:mod:`andoyer.kernels.taylor.lane_crossings`) against
the scalar Taylor kernel and the DOP853 kernel.

* random states of two bodies, state-component sections (G3, gamma_i, L) in both
  directions: the scalar kernel's counts, step counts and crossings (to round-off: the
  lanes' vector jets may contract sums differently) and DOP853's to 1e-9;
* the sections with a tape (the angles theta2, g, l, theta1, psi; G, J1, J2), every
  direction, on a planar body whose orbits cross them both ways: the scalar kernel's
  counts, steps and crossings to round-off (the section jets on the lanes);
* a Hess libration through G = 0 among ordinary orbits, through ``poincare`` on the
  lanes: the same crossings and singular passages as on the scalar kernel;
* the queue: orbit counts that are not a multiple of the lanes, orbits of very
  different lengths, no crossing asked, ``t_max`` reached;
* the pilot's schedule (one block per thread, longest orbit first) and the scalar tail
  of a block: the scalar kernel's results, for orbits that end in the pilot or after it;
* statuses per orbit: ``max_steps`` and a non-finite state end that orbit only, with
  the scalar kernel's ``info``;
* the engine runs many crossings of many orbits on the lanes (spied), and only those;
* tangent states are refused.
"""

from __future__ import annotations

from collections.abc import Callable
from types import ModuleType

import numpy as np
import pytest
from numpy.typing import NDArray

from andoyer import RigidBody
from andoyer.integrate.engines import taylor_engine
from andoyer.integrate.engines.base import Section, Tolerance
from andoyer.integrate.engines.taylor_engine import TaylorEngine
from andoyer.kernels import common
from andoyer.kernels.dop853 import flow as dop853
from andoyer.kernels.generated import equations
from andoyer.kernels.taylor import flow as T
from andoyer.kernels.taylor import lane_crossings as LC
from andoyer.kernels.taylor.lanes import LANES

MAX_STEPS = 10**7
#: The widest lane count (AVX-512): orbit counts from it fill, refill and part-fill the
#: vectors at every width, and keep the tests' states the same on every CPU.
WIDEST = 8
KIND = {name: i for i, name in enumerate(equations.SECTION_KINDS + equations.EXTRA_SECTION_KINDS)}
GENERAL = RigidBody(1.3, 1.7, 2.1, mu=0.5, r=(0.3, -0.5, 0.8))
#: A planar body (the Hess-chart angles are defined) whose random orbits cross every
#: angle section in both directions within t = 60.
PLANAR = RigidBody(2.1, 1.5, 1.9, mu=0.7, r=(0.4, 0.3, 0.0))


def params(body: RigidBody) -> NDArray[np.float64]:
    return np.asarray(body.engine_params, dtype=float)


def random_states(n: int, rng: np.random.Generator) -> NDArray[np.float64]:
    gamma = rng.normal(size=(n, 3))
    gamma /= np.linalg.norm(gamma, axis=1, keepdims=True)
    return np.ascontiguousarray(np.hstack([rng.normal(size=(n, 3)), gamma]))


@pytest.mark.parametrize("body,t_max", [(RigidBody.paper(), 400.0), (GENERAL, 40.0)],
                         ids=["paper", "general"])
def test_lanes_give_the_scalar_kernels_crossings(body: RigidBody, t_max: float) -> None:
    """(The general body's orbits are chaotic: over a short time only, where round-off
    differences of the steps have not grown.)"""
    p = params(body)
    y0 = random_states(2 * WIDEST + 3, np.random.default_rng(7))
    for name, value in (("G3", 0.0), ("gamma3", -0.2), ("gamma1", 0.1), ("L", 0.3)):
        for direction in (1, -1, 0):
            what = f"{name} = {value}, direction {direction}"
            a = LC.locate_crossings(y0, p, KIND[name], value, direction, 12, t_max, 1e-12,
                                    MAX_STEPS, threads=1)
            b = T.locate_crossings(y0, p, KIND[name], value, direction, 12, t_max, 1e-12,
                                   MAX_STEPS)
            np.testing.assert_array_equal(a[2], b[2], err_msg=what)
            np.testing.assert_array_equal(a[3], b[3], err_msg=what)  # statuses and steps
            assert a[2].sum() > 20, what
            assert np.nanmax(np.abs(a[0] - b[0]), initial=0.0) < 1e-11, what
            assert np.nanmax(np.abs(a[1] - b[1]), initial=0.0) < 1e-11, what
            np.testing.assert_array_equal(np.isnan(a[0]), np.isnan(b[0]))
            r = dop853.locate_crossings(y0, p, KIND[name], value, direction, 12, t_max, 1e-14,
                                        1e-14, MAX_STEPS)
            np.testing.assert_array_equal(a[2], r[2], err_msg=what)
            assert np.nanmax(np.abs(a[0] - r[0]), initial=0.0) < 1e-9, what


@pytest.mark.parametrize("name,value", [("theta2", 0.5), ("g", -1.0), ("l", 0.3),
                                        ("theta1", 2.0), ("psi", 1.0), ("G", 1.5),
                                        ("J1", 0.2), ("J2", 1.5)])
def test_tape_sections_on_lanes_give_the_scalar_kernels_crossings(name: str,
                                                                  value: float) -> None:
    """Half the orbits time-reversed (G -> -G), so that the angles run both ways."""
    p = params(PLANAR)
    y0 = random_states(2 * WIDEST + 3, np.random.default_rng(7))
    y0[::2, :3] *= -1.0
    for direction in (1, -1, 0):
        what = f"{name} = {value}, direction {direction}"
        a = LC.locate_crossings(y0, p, KIND[name], value, direction, 12, 60.0, 1e-12,
                                MAX_STEPS, threads=1)
        b = T.locate_crossings(y0, p, KIND[name], value, direction, 12, 60.0, 1e-12,
                               MAX_STEPS)
        np.testing.assert_array_equal(a[2], b[2], err_msg=what)
        np.testing.assert_array_equal(a[3], b[3], err_msg=what)  # statuses and steps
        assert a[2].sum() >= 9, what
        assert np.nanmax(np.abs(a[0] - b[0]), initial=0.0) < 1e-11, what
        assert np.nanmax(np.abs(a[1] - b[1]), initial=0.0) < 1e-11, what
        np.testing.assert_array_equal(np.isnan(a[0]), np.isnan(b[0]))


def test_theta2_on_lanes_on_the_paper_body() -> None:
    """The paper's section on many orbits of the paper's body (several blocks and
    threads), against the scalar kernel and DOP853."""
    p = params(RigidBody.paper())
    y0 = random_states(3 * WIDEST + 5, np.random.default_rng(2))
    a = LC.locate_crossings(y0, p, KIND["theta2"], 0.0, 1, 20, 500.0, 1e-12, MAX_STEPS,
                            block=LANES + 3, threads=2)
    b = T.locate_crossings(y0, p, KIND["theta2"], 0.0, 1, 20, 500.0, 1e-12, MAX_STEPS)
    r = dop853.locate_crossings(y0, p, KIND["theta2"], 0.0, 1, 20, 500.0, 1e-14, 1e-14,
                                MAX_STEPS)
    np.testing.assert_array_equal(a[2], b[2])
    np.testing.assert_array_equal(a[3], b[3])
    assert a[2].sum() > 100
    assert np.nanmax(np.abs(a[0] - b[0])) < 1e-11
    np.testing.assert_array_equal(a[2], r[2])
    assert np.nanmax(np.abs(a[0] - r[0])) < 1e-9


def test_singular_passages_on_lanes_are_the_scalar_kernels(
        monkeypatch: pytest.MonkeyPatch,
        orbits_per_call: Callable[[ModuleType, str], list[int]]) -> None:
    """A Hess libration at M = 0 passes G = 0, where theta2 is undefined: on the lanes,
    as on the scalar kernel, those passages are reported apart, never as crossings."""
    import warnings

    from andoyer import from_andoyer, from_hess
    from andoyer.integrate import poincare

    body = RigidBody.paper()
    libration = from_hess(body, [0.0, 4.0, 0.03, 0.1, 0.0])
    y0 = np.vstack([np.repeat(np.atleast_2d(libration), 3, axis=0),
                    from_andoyer([[0.3, 0.2 * i, 0.3, 1.0 + 0.01 * i, 0.0]
                                  for i in range(WIDEST)])])
    calls = orbits_per_call(LC, "locate_crossings")
    runs, spied = [], []
    for start in (1, 10**9):  # the lanes, then the scalar kernel
        monkeypatch.setattr(taylor_engine, "LANE_CROSSINGS_FROM", start)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            runs.append(poincare(body, y0, "theta2=1", 6, engine="taylor", t_max=600.0,
                                 progress=False))
        spied.append(len(calls))
    assert calls[0] == y0.shape[0] and spied[0] == spied[1] > 0  # only the first on lanes
    lanes, scalar = runs
    np.testing.assert_array_equal(lanes.crossings_found, scalar.crossings_found)
    for run in runs:
        assert (run.singular_passages.values[:3] >= 6).all()
        assert (run.singular_passages.values[3:] == 0).all()
    assert (lanes.crossings_found.values[:3] == 0).all()
    assert (lanes.crossings_found.values[3:] == 6).all()
    np.testing.assert_allclose(lanes.t, scalar.t, atol=1e-11)
    # Whether a passage through G = 0 is a root of the section function at all depends
    # on round-off (the function's scale vanishes there, and the square root's jet
    # divides by it), and its time is ill-conditioned (1e-5 apart between the kernels):
    # their counts may differ (8 and 12 on these librations to t = 600, passing G = 0
    # every 49.8), but most passages are found by both, at the same places.
    for i in range(3):
        a = lanes.singular_passage_t.values[i]
        b = scalar.singular_passage_t.values[i]
        a, b = a[np.isfinite(a)], b[np.isfinite(b)]
        same = np.abs(a[:, None] - b[None, :]).min(axis=1) < 1e-3
        assert same.sum() >= 6, (a, b)


def test_the_queue_refills_lanes_with_orbits_of_any_length() -> None:
    """Orbits that end after 1, 2 or 40 crossings (t_max per orbit is one number, so
    lengths differ by the section's period), 3 blocks of lanes and a remainder, several
    threads: each orbit's crossings are the scalar kernel's."""
    p = params(RigidBody.paper())
    base = random_states(4, np.random.default_rng(11))
    y0 = np.ascontiguousarray(np.repeat(base, 7, axis=0)[:3 * WIDEST + 5])
    y0[::3, 2] *= 0.01  # some orbits hug the section
    for n_crossings, t_max in ((40, 300.0), (1, 300.0), (40, 7.5), (0, 10.0), (5, -1.0)):
        a = LC.locate_crossings(y0, p, KIND["G3"], 0.0, 0, n_crossings, t_max, 1e-12,
                                MAX_STEPS, block=LANES + 3, threads=2)
        b = T.locate_crossings(y0, p, KIND["G3"], 0.0, 0, n_crossings, t_max, 1e-12,
                               MAX_STEPS)
        np.testing.assert_array_equal(a[2], b[2])
        np.testing.assert_array_equal(a[3], b[3])
        assert np.nanmax(np.abs(a[0] - b[0]), initial=0.0) < 1e-11
    assert len(set(b[2].tolist())) >= 1


@pytest.mark.parametrize("n", [3, 2 * LANES + 1])
@pytest.mark.parametrize("n_crossings,t_max,max_steps,pilot_from,ends_in_pilot",
                         [(12, 400.0, MAX_STEPS, 4, True), (12, 400.0, 300, 4, True),
                          (100, 4000.0, MAX_STEPS, LC.PILOT_FROM, False)],
                         ids=["t_max", "max_steps", "default"])
def test_the_pilots_schedule_changes_no_crossing(
        n: int, n_crossings: int, t_max: float, max_steps: int, pilot_from: int,
        ends_in_pilot: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    """The default blocks (a pilot, then one block per thread, longest orbit first, the
    last busy lanes' orbits finished on the scalar kernel) give every orbit the scalar
    kernel's crossings, counts, statuses and steps (orbit counts below the lanes and not
    a multiple of them); orbits ended in the pilot (``t_max``, ``max_steps``) keep its
    results."""
    p = params(RigidBody.paper())
    y0 = np.ascontiguousarray(random_states(2 * WIDEST + 1, np.random.default_rng(3))[:n])
    blocks: list[list[int]] = []
    real = LC._schedule

    def spy(*args: object) -> list[NDArray[np.int64]]:
        parts = real(*args)  # type: ignore[arg-type]
        blocks.extend(b.tolist() for b in parts)
        return parts

    monkeypatch.setattr(LC, "_schedule", spy)
    monkeypatch.setattr(LC, "PILOT_FROM", pilot_from)
    a = LC.locate_crossings(y0, p, KIND["G3"], 0.0, 1, n_crossings, t_max, 1e-12, max_steps,
                            threads=2)
    b = T.locate_crossings(y0, p, KIND["G3"], 0.0, 1, n_crossings, t_max, 1e-12, max_steps)
    np.testing.assert_array_equal(a[2], b[2])
    np.testing.assert_array_equal(a[3], b[3])  # statuses and steps
    np.testing.assert_allclose(a[0], b[0], rtol=1e-14, atol=1e-11)  # round-off, to t = 4000
    np.testing.assert_allclose(a[1], b[1], rtol=0.0, atol=1e-10)
    ended = b[2] < LC.PILOT_CROSSINGS
    assert len(blocks) == 2 and sorted(sum(blocks, [])) == np.flatnonzero(~ended).tolist()
    assert ended.any() == ends_in_pilot, b[2]


def test_failures_end_their_orbit_only() -> None:
    p = params(RigidBody.paper())
    y0 = random_states(WIDEST + 2, np.random.default_rng(3))
    y0[2, 4] = np.nan
    y0[WIDEST + 1, 0] = np.inf
    for max_steps in (300, MAX_STEPS):
        a = LC.locate_crossings(y0, p, KIND["gamma2"], 0.0, 0, 50, 1e3, 1e-12, max_steps)
        b = T.locate_crossings(y0, p, KIND["gamma2"], 0.0, 0, 50, 1e3, 1e-12, max_steps)
        np.testing.assert_array_equal(a[3], b[3])
        np.testing.assert_array_equal(a[2], b[2])
        assert np.nanmax(np.abs(a[0] - b[0])) < 1e-11
        assert a[3][2, 0] == a[3][WIDEST + 1, 0] == common.STEP_TOO_SMALL
        ok = np.ones(WIDEST + 2, dtype=bool)
        ok[[2, WIDEST + 1]] = False
        short = a[2][ok] < 50
        if max_steps == 300:  # orbits short of 50 crossings stop at 300 steps
            assert short.any() and (a[3][ok, 0] == np.where(short, common.MAX_STEPS, 0)).all()
            assert (a[3][ok, 1][short] == 300).all()
        else:
            assert (a[3][ok, 0] == common.SUCCESS).all()


def test_the_engine_runs_many_orbits_on_lanes(
        monkeypatch: pytest.MonkeyPatch,
        orbits_per_call: Callable[[ModuleType, str], list[int]]) -> None:
    calls = orbits_per_call(LC, "locate_crossings")
    p = tuple(RigidBody.paper().engine_params)
    tol = Tolerance(1e-12, 1e-12)
    y0 = random_states(WIDEST + 1, np.random.default_rng(5))
    engine = TaylorEngine()
    engine.crossings(y0, p, Section("G3", 0.0, 1), 5, 100.0, tol)
    assert calls == []  # 45 crossings asked: the scalar kernel (no lane kernel to compile)
    monkeypatch.setattr(taylor_engine, "LANE_CROSSINGS_FROM", 5 * (WIDEST + 1))
    c = engine.crossings(y0, p, Section("G3", 0.0, 1), 5, 100.0, tol)
    assert calls == [WIDEST + 1]
    one = engine.crossings(y0[:1], p, Section("G3", 0.0, 1), 5, 100.0, tol)
    assert calls == [WIDEST + 1]  # one orbit: the scalar kernel
    assert c.count[0] == one.count[0] >= 1
    assert np.nanmax(np.abs(c.t[0] - one.t[0])) < 1e-11
    a = engine.crossings(y0, p, Section("theta2", 0.0, 1), 5, 100.0, tol)
    assert calls == [WIDEST + 1] * 2  # an angle section: on the lanes too
    b = engine.crossings(y0[:1], p, Section("theta2", 0.0, 1), 5, 100.0, tol)
    assert a.count[0] == b.count[0] >= 1
    assert np.nanmax(np.abs(a.t[0] - b.t[0])) < 1e-11


def test_tangent_states_are_refused() -> None:
    p = params(RigidBody.paper())
    y0 = random_states(LANES, np.random.default_rng(0))
    with pytest.raises(ValueError, match="states alone"):
        LC.locate_crossings(np.hstack([y0, y0]), p, KIND["G3"], 0.0, 0, 3, 10.0, 1e-12,
                            MAX_STEPS)
    assert LC.component(KIND["gamma2"], 0.0, 0.3) == 4
    assert LC.component(KIND["G"], 0.0, 1.0) == -1


def test_grazing_roots_inside_one_lane_step_are_both_found() -> None:
    """G3 = (its maximum on a fine grid) - 1e-9: the orbits dip through the section and
    back within a small part of one step; every lane finds both roots, as the scalar
    kernel does."""
    from andoyer import from_andoyer

    p = params(RigidBody.paper())
    z = np.ascontiguousarray(from_andoyer([[0.3, 1.1, 0.2, 1.0, -0.4]]))
    t = np.linspace(0.0, 40.0, 40001)
    ref, _ = dop853.propagate(z, t, p, 1e-13, 1e-13, MAX_STEPS)
    top = int(np.argmax(ref[0, :, 2]))
    value = ref[0, top, 2] - 1e-9
    y0 = np.ascontiguousarray(np.repeat(z, LANES + 1, axis=0))
    a = LC.locate_crossings(y0, p, KIND["G3"], value, 0, 50, t[-1], 1e-12, MAX_STEPS)
    b = T.locate_crossings(y0[:1], p, KIND["G3"], value, 0, 50, t[-1], 1e-12, MAX_STEPS)
    assert (a[2] == b[2][0]).all()
    near = np.abs(a[0] - t[top]) < 0.01
    assert (near.sum(axis=1) == 2).all()
    assert np.nanmax(np.abs(a[0] - b[0])) < 1e-11
