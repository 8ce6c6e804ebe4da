"""One contract that every integration engine passes, for every capability it declares.

The engines are those registered in :data:`andoyer.integrate.engines.ENGINES`; an engine
whose package is not installed (heyoka outside Linux) is skipped, and an engine
registered later joins every test here without edits: the tests of a capability
(:class:`~andoyer.integrate.engines.base.Capability`) are parametrised by the engines that
declare it. Each engine is checked for:

* shapes, NaN padding and the initial row of the :class:`Engine` protocol, and
  ``FloatingPointError`` when the integration fails;
* conservation of the integrals of (1): relative drift of H, of the area integral
  ``(G, gamma)`` (relative to ``|G|``) and of ``|gamma|^2`` below 1e-10 over
  t = 1e3 at rtol = atol = 1e-12 (t = 1e4 in a slow test);
* section points on the section: ``|f| <= 1e-12``, margin ``w > 0`` and the
  requested direction of ``f``;
* agreement with every other engine, pairwise: states to 1e-9 after t = 100 and
  the same crossings (times and states to 1e-9);
* ``backward``: a backward flow returns to the start, crossings backward are on the
  section, at negative times, in the requested direction (in physical time);
* ``tangent``: unit vectors, tangent vectors against central differences of the
  flow, the MEGNO quadratures against their definition, failures flagged ``ok = False``,
  and pairwise agreement, forward and backward;
* ``tangent_crossings``: the crossings of ``crossings`` with the tangent flow at the
  crossing time; ``extended_precision``: agrees with double precision.
"""

from __future__ import annotations

import itertools
from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

from andoyer import RigidBody, from_andoyer
from andoyer.integrate.engines import ENGINES, engine_class, engines_with
from andoyer.integrate.engines.base import (
    Capability,
    Engine,
    Params,
    Section,
    Tolerance,
)
from andoyer.integrate.engines.lazy import heyoka_available
from andoyer.kernels.generated import equations

KIND = {name: i for i, name in enumerate(equations.SECTION_KINDS)}
TOL = 1e-12
TOLERANCE = Tolerance(TOL, TOL)
X_START = np.array([[0.3, 1.1, 0.2, 1.0, -0.4],  # (l, g, L, G, M), |G| = 1, |gamma| = 1
                    [1.0, 2.0, -0.5, 1.0, 0.3]])


def make_engine(name: str) -> Engine:
    """The engine registered as ``name``; skip the test if its package is missing."""
    if name == "heyoka" and not heyoka_available():
        pytest.skip("heyoka is not installed")
    module, cls = ENGINES[name]
    return getattr(pytest.importorskip(module), cls)()


def having(capability: Capability) -> list[str]:
    """The registered engines that declare ``capability`` (the tests' parameters)."""
    return sorted(engines_with(capability))


def pairs_having(capability: Capability) -> list[tuple[str, str]]:
    return list(itertools.combinations(having(capability), 2))


@pytest.fixture(scope="module", params=sorted(ENGINES))
def engine(request: pytest.FixtureRequest) -> Engine:
    return make_engine(request.param)


PAIRS = list(itertools.combinations(sorted(ENGINES), 2))
#: The reference of single checks: heyoka where installed, else scipy's DOP853.
REFERENCE = "heyoka" if heyoka_available() else "scipy"


@pytest.fixture(scope="module", params=PAIRS, ids=["-".join(p) for p in PAIRS])
def engine_pair(request: pytest.FixtureRequest) -> tuple[Engine, Engine]:
    first, second = request.param
    return make_engine(first), make_engine(second)


@pytest.fixture(scope="module")
def bodies() -> dict[str, RigidBody]:
    """The paper's Hess body and a heavier general one (e3 != 0)."""
    return {"paper": RigidBody.paper(),
            "general": RigidBody(1.3, 1.7, 2.1, mu=0.5, r=(0.3, -0.5, 0.8))}


def params(body: RigidBody) -> Params:
    return body.engine_params


def ev(coord: str, value: float = 0.0, direction: int = 0) -> Section:
    return Section(coord, value, direction)


def integrals(body: RigidBody, y: NDArray[np.float64]) -> dict[str, NDArray[np.float64]]:
    G, gamma = y[..., :3], y[..., 3:]
    return {"H": equations.ep_hamiltonian(*np.moveaxis(y, -1, 0), *body.params),
            "area": np.sum(G * gamma, axis=-1),
            "geometric": np.sum(gamma * gamma, axis=-1),
            "G": np.linalg.norm(G, axis=-1)}


def drifts(body: RigidBody, y: NDArray[np.float64]) -> dict[str, float]:
    """Largest drift along each orbit ``y`` (n, k, 6) of the three integrals of (1)."""
    q = integrals(body, y)
    H0, area0, G0 = q["H"][:, :1], q["area"][:, :1], q["G"][:, :1]
    return {"H": float(np.abs((q["H"] - H0) / H0).max()),
            "area": float(np.abs((q["area"] - area0) / G0).max()),
            "geometric": float(np.abs(q["geometric"] - q["geometric"][:, :1]).max())}


def section_fw(body: RigidBody, kind: int, value: float, y: NDArray[np.float64]
               ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    f, w = equations.section(kind, *np.moveaxis(y, -1, 0), params(body)[-1], value,
                              np.cos(value), np.sin(value))
    zero = 0.0 * y[..., 0]
    return np.asarray(f) + zero, np.asarray(w) + zero


def dfdt(body: RigidBody, kind: int, value: float, y: NDArray[np.float64]
         ) -> NDArray[np.float64]:
    """df/dt = grad f . F(y), by a central difference along the field (1)."""
    F = np.stack(equations.ep_field(*np.moveaxis(y, -1, 0), *body.params), axis=-1)
    d = 1e-6
    return (section_fw(body, kind, value, y + d * F)[0]
            - section_fw(body, kind, value, y - d * F)[0]) / (2 * d)


SECTIONS = [  # (body, coordinate, value, direction, n_crossings, t_max)
    ("general", "G3", 0.0, 1, 6, 2000.0),
    ("general", "gamma2", 0.3, -1, 6, 2000.0),
    ("paper", "g", 1.0, 0, 8, 2000.0),
    ("paper", "theta2", 0.0, 1, 6, 2000.0),
    ("general", "l", 3.0, -1, 6, 2000.0),
]


# ------------------------------------------------------------------------ protocol
def test_shapes_and_initial_row(engine: Engine, bodies: dict[str, RigidBody]) -> None:
    body = bodies["general"]
    y0 = from_andoyer(X_START)
    t = np.array([0.0, 0.5, 1.0, 7.0])
    y = engine.propagate(y0, t, params(body), TOLERANCE)
    assert y.shape == (2, 4, 6)
    np.testing.assert_allclose(y[:, 0], y0, rtol=0, atol=1e-15)
    assert isinstance(engine.name, str) and engine.name in ENGINES
    assert {Capability.PROPAGATE, Capability.CROSSINGS} <= engine.capabilities
    assert engine.capabilities == engine_class(engine.name).capabilities
    cr = engine.crossings(y0, params(body), ev("G3", 0.0, 1), 50, 60.0, TOLERANCE)
    assert cr.t.shape == (2, 50) and cr.y.shape == (2, 50, 6) and cr.count.shape == (2,)
    assert np.issubdtype(cr.count.dtype, np.integer)
    for i, c in enumerate(cr.count):
        assert 0 < c < 50  # t_max cuts the orbits short: NaN padding
        assert np.all(np.isfinite(cr.t[i, :c])) and np.all(cr.t[i, :c] <= 60.0)
        assert np.all(np.isnan(cr.t[i, c:])) and np.all(np.isnan(cr.y[i, c:]))


def test_a_non_finite_field_raises(engine: Engine, bodies: dict[str, RigidBody]) -> None:
    """A failed integration is an error, never a silently NaN or truncated result."""
    a, b, c, _, e1, e2, e3, phi0 = params(bodies["paper"])
    bad: Params = (a, b, c, float("nan"), e1, e2, e3, phi0)
    y0 = from_andoyer(X_START)
    with pytest.raises(FloatingPointError):
        engine.propagate(y0, np.array([0.0, 10.0]), bad, TOLERANCE)
    with pytest.raises(FloatingPointError):
        engine.crossings(y0, bad, ev("G3", 0.0, 1), 3, 100.0, TOLERANCE)


# ------------------------------------------------------------------------ integrals
def _check_conservation(engine: Engine, bodies: dict[str, RigidBody], t_end: float) -> None:
    y0 = from_andoyer(X_START)
    t = np.linspace(0.0, t_end, 101)
    for name, body in bodies.items():
        orbits = y0 if engine.name != "scipy" else y0[:1]  # scipy: slow Python callbacks
        d = drifts(body, engine.propagate(orbits, t, params(body), TOLERANCE))
        assert max(d.values()) < 1e-10, (name, d)


def test_integrals_conserved_to_t_1e3(engine: Engine, bodies: dict[str, RigidBody]) -> None:
    _check_conservation(engine, bodies, 1e3)


@pytest.mark.slow
def test_integrals_conserved_to_t_1e4(engine: Engine, bodies: dict[str, RigidBody]) -> None:
    _check_conservation(engine, bodies, 1e4)


# ------------------------------------------------------------------------ sections
@pytest.mark.parametrize(("body_name", "coord", "value", "direction", "n", "t_max"), SECTIONS)
def test_section_points_satisfy_the_section_equation(
        engine: Engine, bodies: dict[str, RigidBody], body_name: str, coord: str,
        value: float, direction: int, n: int, t_max: float) -> None:
    body, kind = bodies[body_name], KIND[coord]
    cr = engine.crossings(from_andoyer(X_START), params(body), ev(coord, value, direction),
                          n, t_max, TOLERANCE)
    assert cr.count.max() == n
    found = np.isfinite(cr.t)
    assert found.sum() == cr.count.sum()
    yc = cr.y[found]
    f, w = section_fw(body, kind, value, yc)
    assert np.abs(f).max() <= 1e-12
    assert np.all(w > 0)
    if direction:
        assert np.all(np.sign(dfdt(body, kind, value, yc)) == direction)
    for i, c in enumerate(cr.count):
        assert np.all(np.diff(cr.t[i, :c]) > 0) and np.all(cr.t[i, :c] > 0)


# ------------------------------------------------------------------------ agreement
def test_engines_agree_on_orbits(engine_pair: tuple[Engine, Engine],
                                 bodies: dict[str, RigidBody]) -> None:
    first, second = engine_pair
    t = np.array([0.0, 10.0, 50.0, 100.0])
    y0 = from_andoyer(X_START)
    for name, body in bodies.items():
        a = first.propagate(y0, t, params(body), TOLERANCE)
        b = second.propagate(y0, t, params(body), TOLERANCE)
        assert np.abs(a - b).max() < 1e-9, name


@pytest.mark.parametrize(("body_name", "coord", "value", "direction", "n", "t_max"),
                         SECTIONS[::2])
def test_engines_agree_on_crossings(engine_pair: tuple[Engine, Engine],
                                    bodies: dict[str, RigidBody], body_name: str,
                                    coord: str, value: float, direction: int, n: int,
                                    t_max: float) -> None:
    body = bodies[body_name]
    # Up to t = 150: orbits of the heavy body are chaotic, the engines' 1e-13-level
    # differences grow past 1e-9 beyond that.
    args: tuple[Any, ...] = (params(body), ev(coord, value, direction), n, 150.0, TOLERANCE)
    a, b = (e.crossings(from_andoyer(X_START), *args) for e in engine_pair)
    assert a.count.sum() > 0
    np.testing.assert_array_equal(a.count, b.count)
    np.testing.assert_allclose(a.t, b.t, rtol=0, atol=1e-9, equal_nan=True)
    np.testing.assert_allclose(a.y, b.y, rtol=0, atol=1e-9, equal_nan=True)


@pytest.mark.parametrize("engine", sorted(ENGINES))
def test_initial_state_on_the_section_is_not_a_crossing(engine):
    """A state seeded on theta2 = 0 (round-off either side) is not crossing 0 (T_START)."""
    from andoyer import RigidBody, from_hess
    from andoyer.integrate import poincare

    body = RigidBody.paper()
    y0 = from_hess(body, [[1.0, 0.0, 0.3, 1.0, 0.0], [4.0, 0.0, 0.6, 1.0, 0.0]])
    ds = poincare(body, y0, "theta2=0", 2, engine=engine)
    assert float(ds.t.min()) > 1.0
    ref = poincare(body, y0, "theta2=0", 2, engine=REFERENCE)
    np.testing.assert_allclose(ds.t.values, ref.t.values, rtol=1e-8)


# ------------------------------------------------------------------------ backward
@pytest.mark.parametrize("name", having(Capability.BACKWARD))
def test_backward_flow_returns_to_the_start(name: str, bodies: dict[str, RigidBody]) -> None:
    engine = make_engine(name)
    body = bodies["general"]
    y0 = from_andoyer(X_START)
    fwd = engine.propagate(y0, np.array([0.0, 3.0, 7.0]), params(body), TOLERANCE)
    back = engine.propagate(fwd[:, -1], np.array([7.0, 3.0, 0.0]), params(body), TOLERANCE)
    np.testing.assert_allclose(back[:, 1], fwd[:, 1], rtol=0, atol=1e-10)
    np.testing.assert_allclose(back[:, -1], y0, rtol=0, atol=1e-10)


@pytest.mark.parametrize("name", having(Capability.BACKWARD))
@pytest.mark.parametrize(("coord", "value", "direction"), [("G3", 0.0, 1), ("psi", 0.4, -1),
                                                          ("g", 0.5, 1),
                                                          ("gamma2", 0.3, 0)])
def test_backward_crossings_lie_on_the_section(name: str, bodies: dict[str, RigidBody],
                                               coord: str, value: float,
                                               direction: int) -> None:
    """Backward crossings: on the section, t < 0 decreasing, direction in physical time,
    and the crossings of the forward orbit seen from its end point."""
    engine = make_engine(name)
    body = bodies["general"]
    y0 = from_andoyer(X_START)
    event = ev(coord, value, direction)
    back = engine.crossings(y0, params(body), event, 4, 400.0, TOLERANCE, backward=True)
    assert back.count.min() == 4
    assert np.all(back.t < 0) and np.all(np.diff(back.t, axis=1) < 0)
    kind = event.kind
    f, w = section_fw(body, kind, value, back.y)
    assert np.abs(f).max() <= 1e-12 and np.all(w > 0)
    if direction:
        assert np.all(np.sign(dfdt(body, kind, value, back.y)) == direction)
    # Forward from the last backward crossing's time: the same crossings, in reverse.
    t_end = -float(back.t[0, -1]) + 1e-6
    start = engine.propagate(y0[:1], np.array([0.0, -t_end]), params(body), TOLERANCE)[:, -1]
    fwd = engine.crossings(start, params(body), event, 4, t_end, TOLERANCE)
    np.testing.assert_allclose(fwd.t[0][::-1] - t_end, back.t[0], rtol=0, atol=1e-8)
    np.testing.assert_allclose(fwd.y[0][::-1], back.y[0], rtol=0, atol=1e-8)


# ------------------------------------------------------------------------ tangent
W0 = np.array([[1.0, 0.5, -0.3, 0.2, 0.1, -0.4], [0.0, 1.0, 0.2, -0.5, 0.3, 0.1]])


def _fd_tangent(engine: Engine, body: RigidBody, y0: NDArray[np.float64],
                w: NDArray[np.float64], t: NDArray[np.float64]) -> NDArray[np.float64]:
    """d y(t) / d y0 . w by a central difference of the flow."""
    d = 1e-6
    ends = engine.propagate(np.stack([y0 + d * w, y0 - d * w]), t, params(body), TOLERANCE)
    return (ends[0] - ends[1]) / (2 * d)


@pytest.mark.parametrize("name", having(Capability.TANGENT))
@pytest.mark.parametrize("backward", [False, True])
def test_tangent_vectors_are_derivatives_of_the_flow(name: str, bodies: dict[str, RigidBody],
                                                     backward: bool) -> None:
    engine = make_engine(name)
    if backward and Capability.BACKWARD not in engine.capabilities:
        pytest.skip("no backward flow")
    body = bodies["general"]
    y0 = from_andoyer(X_START)[0]
    t = np.array([0.0, 2.0, 5.0]) * (-1 if backward else 1)
    flow = engine.tangent(y0, W0, params(body), TOLERANCE, t=t)
    assert flow.u.shape == (1, 3, 2, 6) and flow.rho.shape == (1, 3, 2)
    assert bool(flow.ok[0]) and flow.count.tolist() == [3]
    np.testing.assert_allclose(flow.t[0], t)
    np.testing.assert_allclose(np.linalg.norm(flow.u, axis=-1), 1.0, rtol=0, atol=1e-10)
    np.testing.assert_allclose(flow.y[0], engine.propagate(y0[None], t, params(body),
                                                           TOLERANCE)[0], rtol=0, atol=1e-10)
    for i in range(2):
        ref = _fd_tangent(engine, body, y0, W0[i], t)
        np.testing.assert_allclose(flow.w[0, :, i], ref, rtol=0, atol=1e-6 * np.abs(ref).max())
    if backward:
        assert flow.megno is None
    else:
        assert flow.megno is not None
        # MEGNO's first quadrature: int_0^t (s + delta) d rho_1/ds ds, by parts
        # (t + delta) rho_1(t) - delta rho_1(0) - int_0^t rho_1 ds on a fine grid.
        fine = np.linspace(0.0, 5.0, 401)
        dense = engine.tangent(y0, W0[:1], params(body), TOLERANCE, t=fine)
        assert dense.megno is not None
        rho = dense.rho[0, :, 0] - dense.rho[0, 0, 0]
        parts = fine * rho - np.concatenate([[0.0], np.cumsum(np.diff(fine) * 0.5
                                                              * (rho[1:] + rho[:-1]))])
        np.testing.assert_allclose(dense.megno[0, :, 0], parts, rtol=0, atol=1e-4)


@pytest.mark.parametrize("name", having(Capability.TANGENT))
def test_tangent_failure_is_flagged_not_raised(name: str, bodies: dict[str, RigidBody]) -> None:
    engine = make_engine(name)
    a, b, c, _, e1, e2, e3, phi0 = params(bodies["paper"])
    bad: Params = (a, b, c, float("nan"), e1, e2, e3, phi0)
    flow = engine.tangent(from_andoyer(X_START), W0[:1], bad, TOLERANCE,
                          t=np.array([0.0, 1.0]))
    assert not flow.ok.any()
    assert np.all(np.isnan(flow.y[:, -1]))


@pytest.mark.parametrize(("first", "second"), pairs_having(Capability.TANGENT),
                         ids=["-".join(p) for p in pairs_having(Capability.TANGENT)])
def test_engines_agree_on_tangent_flows(first: str, second: str,
                                        bodies: dict[str, RigidBody]) -> None:
    a_eng, b_eng = make_engine(first), make_engine(second)
    body = bodies["paper"]
    y0 = from_andoyer(X_START)
    t = np.linspace(0.0, 50.0, 6)
    a, b = (e.tangent(y0, W0, params(body), TOLERANCE, t=t) for e in (a_eng, b_eng))
    assert a.megno is not None and b.megno is not None
    np.testing.assert_allclose(a.y, b.y, rtol=0, atol=1e-9)
    np.testing.assert_allclose(a.u, b.u, rtol=0, atol=1e-7)
    np.testing.assert_allclose(a.rho, b.rho, rtol=0, atol=1e-7)
    np.testing.assert_allclose(a.megno, b.megno, rtol=1e-7, atol=1e-6)


# ------------------------------------------------------------------------ tangent crossings
@pytest.mark.parametrize("name", having(Capability.TANGENT_CROSSINGS))
@pytest.mark.parametrize("backward", [False, True])
def test_tangent_crossings_carry_the_tangent_flow(name: str, bodies: dict[str, RigidBody],
                                                  backward: bool) -> None:
    engine = make_engine(name)
    if backward and Capability.BACKWARD not in engine.capabilities:
        pytest.skip("no backward flow")
    body = bodies["general"]
    y0 = from_andoyer(X_START)[:1]
    event = ev("G3", 0.0, 1)
    flow = engine.tangent(y0, np.eye(6), params(body), TOLERANCE, event=event,
                          n_crossings=3, t_max=500.0, backward=backward, renormalise=False)
    plain = engine.crossings(y0, params(body), event, 3, 500.0, TOLERANCE, backward=backward)
    assert flow.count.tolist() == plain.count.tolist() == [3] and bool(flow.ok[0])
    assert flow.megno is None
    np.testing.assert_allclose(flow.t, plain.t, rtol=0, atol=1e-9)
    np.testing.assert_allclose(flow.y, plain.y, rtol=0, atol=1e-9)
    # The tangent flow at the crossing time, by central differences.
    Phi = np.stack([_fd_tangent(engine, body, y0[0], e, np.array([0.0, float(flow.t[0, 1])]))[-1]
                    for e in np.eye(6)], axis=-1)
    np.testing.assert_allclose(flow.w[0, 1].T, Phi, rtol=0, atol=1e-6 * np.abs(Phi).max())


@pytest.mark.parametrize("name", having(Capability.EXTENDED_PRECISION))
def test_extended_precision_agrees_with_double(name: str, bodies: dict[str, RigidBody]) -> None:
    engine = make_engine(name)
    body = bodies["general"]
    y0 = from_andoyer(X_START)[:1]
    args: tuple[Any, ...] = (y0, np.eye(6), params(body), TOLERANCE)
    kw: dict[str, Any] = {"event": ev("psi", 0.4, 1), "n_crossings": 1, "t_max": 100.0,
                          "renormalise": False}
    lo = engine.tangent(*args, **kw)
    hi = engine.tangent(*args, extended_precision=True, **kw)
    np.testing.assert_allclose(hi.t, lo.t, rtol=0, atol=1e-10)
    np.testing.assert_allclose(hi.w, lo.w, rtol=1e-8, atol=1e-8)


@pytest.mark.parametrize("name", sorted(ENGINES))
def test_a_missing_capability_is_refused_by_name(name: str) -> None:
    engine = make_engine(name)
    for cap in Capability:
        if cap in engine.capabilities:
            continue
        with pytest.raises(NotImplementedError, match=cap.value):
            engine.require(cap)


def test_the_guide_shows_the_generated_capability_table() -> None:
    """docs/guide.md's "what each engine can do" is :func:`capability_table` verbatim."""
    from pathlib import Path

    from andoyer.integrate.engines import capability_table

    guide = (Path(__file__).resolve().parents[3] / "docs" / "guide.md").read_text()
    start = guide.index("<!-- capability table:")
    body = guide[guide.index("\n", start) + 1:guide.index("<!-- end of capability table")]
    assert body.strip() == capability_table(), "regenerate it with capability_table()"
