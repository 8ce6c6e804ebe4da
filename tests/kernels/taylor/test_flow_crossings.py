"""Section crossings of the Taylor kernel (:mod:`andoyer.kernels.taylor.flow`) at their edges,
against independent routes.

The section search takes one pass of the section function per step: its jet (a column
of the state's jet for ``G3 = c``, ``gamma_i = c``, ...; the tape otherwise), the end
value ``P(h)`` carried over to the next step, and the next polynomial blended to start
at that value (``sections.scale_polynomial``). These tests check that no crossing
is lost or counted twice:

* many random states, two bodies, state-component sections (the column path) and tape
  sections: counts, times and states equal those of the numba engine (DOP853 at 1e-13)
  and of heyoka where installed, to ~1e-8; the column path gives the tape path's
  crossings (the same section function written as a tape);
* roots exactly at step ends (section values taken from the states at the kernel's own
  step ends, replayed in a Numba loop): each is counted once, in both directions, as by
  the DOP853 kernel (whose steps end elsewhere);
* a state starting on the section: the root at t = 0 is not a crossing;
* grazing sections (two roots a hair apart inside one step): both found, in order;
* ``max_steps`` and a non-finite state end the orbit with their status.
"""

from __future__ import annotations

import math

import numba
import numpy as np
import pytest
from numpy.typing import NDArray

from andoyer import RigidBody, from_andoyer
from andoyer.integrate.engines import get_engine
from andoyer.integrate.engines.base import Section, Tolerance
from andoyer.integrate.engines.lazy import heyoka_available
from andoyer.kernels import common
from andoyer.kernels.dop853 import flow as dop853
from andoyer.kernels.generated import equations, recurrences
from andoyer.kernels.taylor import flow as T
from andoyer.kernels.taylor import sections
from andoyer.kernels.taylor.jets import advance, fill_constants, load

MAX_STEPS = 10**7
KIND = {name: i for i, name in enumerate(equations.SECTION_KINDS + equations.EXTRA_SECTION_KINDS)}
GENERAL = RigidBody(1.3, 1.7, 2.1, mu=0.5, r=(0.3, -0.5, 0.8))


def params(body: RigidBody) -> NDArray[np.float64]:
    return np.asarray(body.engine_params, dtype=float)


def random_states(n: int, rng: np.random.Generator) -> NDArray[np.float64]:
    """States with |gamma| = 1 and |G| ~ 1."""
    gamma = rng.normal(size=(n, 3))
    gamma /= np.linalg.norm(gamma, axis=1, keepdims=True)
    return np.ascontiguousarray(np.hstack([rng.normal(size=(n, 3)), gamma]))


@numba.njit
def _step_ends(z0, p, order, n):  # pragma: no cover (compiled)
    """Times and states at the ends of the kernel's first ``n`` steps from ``z0``: the
    kernel's own ``take_step`` and ``advance`` (the steps of ``locate_crossings``)."""
    q = np.empty(recurrences.N_CONSTANTS)
    fill_constants(p, q)
    X = np.empty((1, order + 1, 6))
    load(X, z0)
    info = np.zeros(4, np.int64)
    ts = np.empty(n)
    ys = np.empty((n, 6))
    t = 0.0
    for i in range(n):
        _, t1, h = T.STATE.take_step(t, 1e300, X, order, q, info)
        advance(X, order, h)
        t = t1
        ts[i] = t
        for j in range(6):
            ys[i, j] = X[0, 0, j]
    return ts, ys


def _theta2(y: NDArray[np.float64], phi0: float) -> float:
    """The angle theta2 of a state: f = R sin(theta2 - value) of the generated section."""
    s7, s8 = equations.section(KIND["theta2"], *y, phi0, 0.0, 1.0, 0.0)
    return math.atan2(s7, s8) % (2 * math.pi)


@pytest.mark.parametrize("body", [RigidBody.paper(), GENERAL], ids=["paper", "general"])
def test_random_states_agree_with_numba_and_heyoka(body: RigidBody) -> None:
    p = tuple(body.engine_params)
    y0 = random_states(16, np.random.default_rng(26))
    tol = Tolerance(1e-12, 1e-12)
    taylor = get_engine("taylor")
    others = {"numba": (get_engine("numba"), Tolerance(1e-13, 1e-13))}
    if heyoka_available():
        others["heyoka"] = (get_engine("heyoka"), tol)
    # (One orbit of the general body passes |G| = 0.06, where the series of the tape
    # sections, a square root of |G|^2, converge slowly: their step counts them.)
    sections = [("G3", 0.0), ("G3", 0.4), ("gamma3", -0.2), ("gamma1", 0.1), ("L", 0.3),
                ("theta2", 0.0), ("G", 1.0)]
    for name, value in sections:
        for direction in (1, -1, 0):
            event = Section(name, value, direction)
            c = taylor.crossings(y0, p, event, 8, 60.0, tol)
            for other, (engine, other_tol) in others.items():
                r = engine.crossings(y0, p, event, 8, 60.0, other_tol)
                what = f"{name} = {value}, direction {direction}, against {other}"
                np.testing.assert_array_equal(c.count, r.count, err_msg=what)
                assert np.nanmax(np.abs(c.t - r.t), initial=0.0) < 1e-8, what
                assert np.nanmax(np.abs(c.y - r.y), initial=0.0) < 1e-8, what


@numba.njit
def _scaled(a, order, h, fa):  # pragma: no cover (compiled)
    b = a.copy()
    sections.scale_polynomial(b, order, h, fa)
    return b


def test_the_scaled_polynomial_starts_at_the_carried_value_and_keeps_its_end() -> None:
    """scale_polynomial: P(0) is the previous step's end value ``fa`` exactly, P(1) is
    the step's own end value, and inside the step P moves by the linear blend only."""
    rng = np.random.default_rng(1)
    order, h = 15, 0.3
    a = rng.normal(size=order + 1) / np.arange(1, order + 2) ** 2
    fa = a[0] + 1e-9
    b = _scaled(a, order, h, fa)
    assert b[0] == fa
    s = np.linspace(0.0, 1.0, 11)
    p_old = np.polyval(a[::-1], s * h)
    p_new = np.polyval(b[::-1], s)
    np.testing.assert_allclose(p_new - p_old, 1e-9 * (1.0 - s), rtol=0, atol=1e-15)


@pytest.mark.parametrize("name", ["G3", "theta2"])
@pytest.mark.parametrize("direction", [1, -1, 0])
def test_roots_at_step_ends_are_counted_once(name: str, direction: int) -> None:
    """Section values equal to the section coordinate at the kernel's own step ends
    (G3: exactly the next step's start value, so its jet's ``f^[0]`` is 0; theta2 to
    round-off): every such root is one crossing at that time, as the DOP853 kernel
    finds it, and the crossings before it agree too."""
    body = RigidBody.paper()
    p = params(body)
    z0 = np.ascontiguousarray(from_andoyer([[0.3, 1.1, 0.2, 1.0, -0.4]]).reshape(6))
    order = T.order_for(1e-12)
    ts, ys = _step_ends(z0, p, order, 400)
    hits = wanted_roots = 0
    for k in range(10, 400, 13):
        if name == "G3":
            value = ys[k, 2]
        else:
            value = _theta2(ys[k], p[7])
        kind = KIND[name]
        # which way the section is crossed there: f's rate from the jet of order 1
        f0, _ = equations.section(kind, *ys[k], p[7], value, math.cos(value), math.sin(value))
        x = T.jet(ys[k], p, 1)[0]
        tape, C = sections.section_tape(kind, p[7], value)
        rate = sections.section_jet(tape, C, x, 1)[1]
        assert abs(f0) < 1e-14 and abs(rate) > 1e-6
        t_max = ts[k] + 0.5 * (ts[k + 1] - ts[k])  # inside the next step
        tc, yc, count, info = T.locate_crossings(z0[None], p, kind, value, direction, 200,
                                                 t_max, 1e-12, MAX_STEPS)
        rt, ry, rcount, _ = dop853.locate_crossings(z0[None], p, kind, value, direction, 200,
                                                    t_max, 1e-14, 1e-14, MAX_STEPS)
        assert info[0, 0] == common.SUCCESS
        what = f"{name} = value at step end {k} (t = {ts[k]!r}), direction {direction}"
        assert count[0] == rcount[0], what
        at_end = np.flatnonzero(np.abs(tc[0, :count[0]] - ts[k]) < 1e-9)
        wanted = direction == 0 or (rate > 0) == (direction > 0)
        assert at_end.size == (1 if wanted else 0), what
        hits += at_end.size
        wanted_roots += wanted
        assert np.max(np.abs(tc[0, :count[0]] - rt[0, :count[0]]), initial=0.0) < 1e-9, what
        assert np.max(np.abs(yc[0, :count[0]] - ry[0, :count[0]]), initial=0.0) < 1e-9, what
    assert hits == wanted_roots
    # theta2 only increases on this orbit: no root is crossed downward
    assert wanted_roots >= 10 or (name, direction) == ("theta2", -1)


@pytest.mark.parametrize("name", ["G3", "gamma2", "theta2"])
def test_a_state_on_the_section_is_not_a_crossing_at_t_0(name: str) -> None:
    body = RigidBody.paper()
    p = params(body)
    z0 = np.ascontiguousarray(from_andoyer([[0.3, 1.1, 0.2, 1.0, -0.4]]))
    kind = KIND[name]
    value = {"G3": z0[0, 2], "gamma2": z0[0, 4], "theta2": _theta2(z0[0], p[7])}[name]
    tc, _, count, info = T.locate_crossings(z0, p, kind, value, 0, 3, 100.0, 1e-12,
                                            MAX_STEPS)
    rt, _, rcount, _ = dop853.locate_crossings(z0, p, kind, value, 0, 3, 100.0, 1e-14, 1e-14,
                                               MAX_STEPS)
    assert count[0] == rcount[0] >= 1
    assert tc[0, 0] > 1e-3
    np.testing.assert_allclose(tc[0], rt[0], atol=1e-9)


@pytest.mark.parametrize("depth", [1e-8, 1e-10, 1e-11])
def test_grazing_sections_give_both_roots(depth: float) -> None:
    """G3 = its maximum minus ``depth``: the orbit dips through the section and back
    within one step (roots ~sqrt(depth) apart in time); both are found in time order,
    upward then downward, each on the section."""
    body = RigidBody.paper()
    p = params(body)
    z0 = np.ascontiguousarray(from_andoyer([[0.3, 1.1, 0.2, 1.0, -0.4]]))
    t = np.linspace(0.0, 40.0, 40001)
    ref, _ = dop853.propagate(z0, t, p, 1e-13, 1e-13, MAX_STEPS)
    top = int(np.argmax(ref[0, :, 2]))
    # the top in time: midway between the roots of G3 = (grid maximum - 1e-6) around it
    # (the parabola's midpoint, off by ~1e-6 in time, so G3 there is ~1e-12 below the top)
    tl = T.locate_crossings(z0, p, KIND["G3"], ref[0, top, 2] - 1e-6, 0, 40, t[-1], 1e-12,
                            MAX_STEPS)[0][0]
    pair = tl[np.abs(tl - t[top]) < 0.05]
    assert pair.size == 2
    t_top = 0.5 * (pair[0] + pair[1])
    g3_max = T.propagate(z0, np.array([0.0, t_top]), p, 1e-13, MAX_STEPS)[0][0, 1, 2]
    value = g3_max - depth
    tc, yc, count, info = T.locate_crossings(z0, p, KIND["G3"], value, 0, 40, t[-1], 1e-12,
                                             MAX_STEPS)
    steps = info[0, 1] / t[-1]  # steps per unit time
    near = np.flatnonzero(np.abs(tc[0, :count[0]] - t_top) < 0.05)
    assert near.size == 2, (count, tc)
    assert tc[0, near[0]] < tc[0, near[1]]
    assert tc[0, near[1]] - tc[0, near[0]] < 0.1 / steps  # within a tenth of a step
    np.testing.assert_allclose(yc[0, near, 2], value, atol=1e-13)
    up = T.locate_crossings(z0, p, KIND["G3"], value, 1, 40, t[-1], 1e-12, MAX_STEPS)[0]
    assert np.any(up[0] == tc[0, near[0]]) and not np.any(up[0] == tc[0, near[1]])


def test_max_steps_and_non_finite_states_end_the_section_search() -> None:
    p = params(RigidBody.paper())
    z0 = np.ascontiguousarray(from_andoyer([[0.3, 1.1, 0.2, 1.0, -0.4]] * 2))
    tc, _, count, info = T.locate_crossings(z0, p, KIND["G3"], 0.0, 0, 100, 1e4, 1e-12, 500)
    assert (info[:, 0] == common.MAX_STEPS).all() and (info[:, 1] == 500).all()
    full, _, fcount, _ = T.locate_crossings(z0, p, KIND["G3"], 0.0, 0, 100, 1e4, 1e-12,
                                            MAX_STEPS)
    assert 0 < count[0] < fcount[0]
    np.testing.assert_array_equal(tc[0, :count[0]], full[0, :count[0]])
    z0[1, 3] = np.inf
    _, _, count, info = T.locate_crossings(z0, p, KIND["theta2"], 0.0, 0, 5, 100.0, 1e-12,
                                           MAX_STEPS)
    assert info[1, 0] == common.STEP_TOO_SMALL and count[1] == 0 and info[0, 0] == common.SUCCESS


@pytest.mark.parametrize("value", [0.0, np.pi / 2, np.pi, 3 * np.pi / 2])
def test_the_g_sections_on_the_axes_cross_as_their_full_section_function(value) -> None:
    """The reduced tapes of g = 0, pi/2, pi, 3 pi/2 (what the engine runs) against the
    full tape of f on the same orbits: the same crossings, within the integrations'
    difference at the tolerance (different steps: the section's jet enters the step
    size)."""
    from andoyer.kernels.generated import recurrences
    from andoyer.kernels.generated.equations import SECTION_KINDS
    from andoyer.kernels.taylor import flow
    from andoyer.kernels.taylor.sections import section_family, section_tape

    body = RigidBody.paper(0.01)
    p = np.asarray(body.engine_params, dtype=float)
    z0 = np.array([[0.3, 0.2, 0.25, 0.6, 0.0, 0.8], [-0.1, 0.45, 0.3, 0.0, 0.6, 0.8]])
    kind, n, tol = SECTION_KINDS.index("g"), 40, 1e-12
    tc, zc, count, info = flow.locate_crossings(z0, p, kind, value, 1, n, 1e4, tol, 10**7)
    full = np.array(recurrences.SECTION_TAPES[kind], dtype=np.int64)
    fC = np.array(recurrences.section_constants(kind, p[7], value, np.cos(value),
                                                np.sin(value)))
    wt, wC = section_tape(kind, p[7], value, margin=True)
    tf = np.full_like(tc, np.nan)
    zf = np.full_like(zc, np.nan)
    cf = np.zeros_like(count)
    inf = np.zeros_like(info)
    block = flow.CROSSINGS_BLOCKS[(False, section_family(full, fC))]
    block(z0, p, flow.order_for(tol), full, fC, wt, wC, 1, 1e4, 10**7, tf, zf, cf, inf)
    assert np.array_equal(count, cf) and np.all(count == n)
    assert np.all(info[:, 0] == 0) and np.all(inf[:, 0] == 0)
    assert np.max(np.abs(tc - tf)) < 1e-9 and np.max(np.abs(zc - zf)) < 1e-9
    if np.sin(value) ** 2 < 0.5:  # f / |G|: a shorter jet, fewer shortened steps
        assert info[:, 3].sum() < inf[:, 3].sum()
