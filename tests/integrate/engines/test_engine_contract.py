"""One contract that every integration engine passes.

The engines are those registered in :data:`andoyer.integrate.engines.ENGINES`; an engine
whose package is not installed (heyoka outside Linux) is skipped, and an engine
registered later joins every test here without edits. Each engine is checked for:

* shapes, NaN padding and the initial row of the :class:`Engine` protocol, and
  ``FloatingPointError`` when the integration fails;
* conservation of the integrals of (1): relative drift of H, of the area integral
  ``(G, gamma)`` (relative to ``|G|``) and of ``|gamma|^2`` below 1e-10 over
  t = 1e3 at rtol = atol = 1e-12 (t = 1e4 in a slow test);
* section points on the section: ``|f| <= 1e-12``, margin ``w > 0`` and the
  requested direction of ``f``;
* agreement with every other engine, pairwise: states to 1e-9 after t = 100 and
  the same crossings (times and states to 1e-9).
"""

from __future__ import annotations

import itertools
from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

from andoyer import RigidBody, from_andoyer
from andoyer.integrate.engines import ENGINES
from andoyer.integrate.engines.base import Engine, Params
from andoyer.integrate.engines.lazy import heyoka_available
from andoyer.kernels import generated

KIND = {name: i for i, name in enumerate(generated.SECTION_KINDS)}
TOL = 1e-12
X_START = np.array([[0.3, 1.1, 0.2, 1.0, -0.4],  # (l, g, L, G, M), |G| = 1, |gamma| = 1
                    [1.0, 2.0, -0.5, 1.0, 0.3]])


def make_engine(name: str) -> Engine:
    """The engine registered as ``name``; skip the test if its package is missing."""
    module, cls = ENGINES[name]
    return getattr(pytest.importorskip(module), cls)()


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
    phi0 = body.phi0 if body.e3 == 0.0 else 0.0
    return (*body.params, phi0)


def integrals(body: RigidBody, y: NDArray[np.float64]) -> dict[str, NDArray[np.float64]]:
    G, gamma = y[..., :3], y[..., 3:]
    return {"H": generated.ep_hamiltonian(*np.moveaxis(y, -1, 0), *body.params),
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
    f, w = generated.section(kind, *np.moveaxis(y, -1, 0), params(body)[-1], value,
                              np.cos(value), np.sin(value))
    zero = 0.0 * y[..., 0]
    return np.asarray(f) + zero, np.asarray(w) + zero


def dfdt(body: RigidBody, kind: int, value: float, y: NDArray[np.float64]
         ) -> NDArray[np.float64]:
    """df/dt = grad f . F(y), by a central difference along the field (1)."""
    F = np.stack(generated.ep_field(*np.moveaxis(y, -1, 0), *body.params), axis=-1)
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
    y = engine.propagate(y0, t, params(body), TOL, TOL)
    assert y.shape == (2, 4, 6)
    np.testing.assert_allclose(y[:, 0], y0, rtol=0, atol=1e-15)
    assert isinstance(engine.name, str) and engine.name in ENGINES
    cr = engine.crossings(y0, params(body), KIND["G3"], 0.0, 1, 50, 60.0, TOL, TOL)
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
        engine.propagate(y0, np.array([0.0, 10.0]), bad, TOL, TOL)
    with pytest.raises(FloatingPointError):
        engine.crossings(y0, bad, KIND["G3"], 0.0, 1, 3, 100.0, TOL, TOL)


# ------------------------------------------------------------------------ integrals
def _check_conservation(engine: Engine, bodies: dict[str, RigidBody], t_end: float) -> None:
    y0 = from_andoyer(X_START)
    t = np.linspace(0.0, t_end, 101)
    for name, body in bodies.items():
        orbits = y0 if engine.name != "scipy" else y0[:1]  # scipy: slow Python callbacks
        d = drifts(body, engine.propagate(orbits, t, params(body), TOL, TOL))
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
    cr = engine.crossings(from_andoyer(X_START), params(body), kind, value, direction, n,
                          t_max, TOL, TOL)
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
        a = first.propagate(y0, t, params(body), TOL, TOL)
        b = second.propagate(y0, t, params(body), TOL, TOL)
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
    args: tuple[Any, ...] = (params(body), KIND[coord], value, direction, n, 150.0, TOL, TOL)
    a, b = (e.crossings(from_andoyer(X_START), *args) for e in engine_pair)
    assert a.count.sum() > 0
    np.testing.assert_array_equal(a.count, b.count)
    np.testing.assert_allclose(a.t, b.t, rtol=0, atol=1e-9, equal_nan=True)
    np.testing.assert_allclose(a.y, b.y, rtol=0, atol=1e-9, equal_nan=True)


@pytest.mark.parametrize("engine", ["heyoka", "numba", "scipy"])
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
