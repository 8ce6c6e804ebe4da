"""The integrals' table (:mod:`andoyer.charts.integrals`): each row is a first integral of
(1) (SymPy, with the field of :mod:`andoyer.symbolic.hamiltonian`), its value is the
charts' function, and the datasets, the indicators and the explorer read it (one
definition of a drift; an integral a preset brings reaches every one of them)."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from andoyer.body import RigidBody
from andoyer.charts.euler_poisson import area_integral, energy, geometric_integral
from andoyer.charts.integrals import COMMON, INTEGRALS, drift_scale, integrals_of

#: A body of each kind an integral holds for.
BODIES = {"paper": RigidBody.paper(), "kovalevskaya": RigidBody.kovalevskaya(1.3, 0.7),
          "general": RigidBody(2.5, 1.0, 2.0, 0.01, (0.6, 0.48, 0.64))}


def _symbolic_body(kind: str):
    """The body of ``kind`` with symbols for its free numbers (a stand-in with the
    attributes the integrals read) and the substitutions that put it in the field."""
    from types import SimpleNamespace

    from andoyer.symbolic.hamiltonian import S

    if kind == "kovalevskaya":  # A = B = 2C, r = (1, 0, 0)
        C = sp.Symbol("C", positive=True)
        sub = {S.a: 1 / (2 * C), S.b: 1 / (2 * C), S.c: 1 / C, S.e1: 1, S.e2: 0, S.e3: 0}
        stand_in = SimpleNamespace(A=2 * C, B=2 * C, C=C, mu=S.mu,
                                   params=(sub[S.a], sub[S.b], sub[S.c], S.mu, 1, 0, 0))
        return stand_in, sub
    stand_in = SimpleNamespace(A=1 / S.a, B=1 / S.b, C=1 / S.c, mu=S.mu,
                               params=(S.a, S.b, S.c, S.mu, S.e1, S.e2, S.e3))
    return stand_in, {}


@pytest.mark.parametrize("kind", sorted(BODIES))
def test_every_integral_of_a_body_is_conserved_by_its_flow(kind):
    """``dI/dt = grad I . f`` vanishes identically (SymPy) for each integral the table
    gives the body, evaluated on an object array of the state's symbols."""
    from andoyer.symbolic.hamiltonian import S, euler_poisson_field

    stand_in, sub = _symbolic_body(kind)
    field = [f.subs(sub) for f in euler_poisson_field()]
    y = np.array(S.y, dtype=object)
    for name in integrals_of(BODIES[kind]):
        expr = sp.sympify(INTEGRALS[name].value(stand_in, y))
        rate = sp.expand(sum(sp.diff(expr, v) * f for v, f in zip(S.y, field, strict=True)))
        assert sp.simplify(rate) == 0, (kind, name, rate)


def test_the_check_catches_a_wrong_integral():
    from andoyer.symbolic.hamiltonian import S, euler_poisson_field

    field = [f.subs(_symbolic_body("kovalevskaya")[1]) for f in euler_poisson_field()]
    wrong = S.y[0] ** 2 + S.y[1] ** 2  # G1^2 + G2^2 is not conserved
    rate = sp.expand(sum(sp.diff(wrong, v) * f for v, f in zip(S.y, field, strict=True)))
    assert sp.simplify(rate) != 0


def test_which_bodies_have_which_integrals():
    assert integrals_of(BODIES["paper"]) == COMMON == ("H", "area", "geometric")
    assert integrals_of(BODIES["kovalevskaya"]) == (*COMMON, "K")
    assert integrals_of(BODIES["general"]) == COMMON


def test_the_values_are_the_charts_functions():
    rng = np.random.default_rng(3)
    y = rng.normal(size=(4, 6))
    body = BODIES["paper"]
    np.testing.assert_array_equal(INTEGRALS["H"](body, y), energy(body, y))
    np.testing.assert_array_equal(INTEGRALS["area"](body, y), area_integral(y))
    np.testing.assert_array_equal(INTEGRALS["geometric"](body, y), geometric_integral(y))


def test_a_drift_is_one_definition_everywhere():
    """The states datasets, the indicators and the explorer measure H's drift against
    the same scale, max(|H0|, mu): here a level below mu, where |H0| alone would blow
    the drift up."""
    from andoyer.integrate.results import derived_values

    body = RigidBody.paper()
    y = np.array([[[0.0, 0.01, 0.0, 0.0, 1.0, 0.0], [0.0, 0.011, 0.0, 0.0, 1.0, 0.0]]])
    H = INTEGRALS["H"](body, y)
    assert abs(H[0, 0]) < body.mu
    d = derived_values(body, y, drifts=True)
    expected = (H - H[:, :1]) / np.maximum(np.abs(H[:, :1]), body.mu)
    np.testing.assert_array_equal(d["H_drift"], expected)
    assert float(drift_scale("H", body, y[:, :1])[0, 0]) == body.mu


def test_a_preset_that_brings_an_integral_gets_it_in_datasets_and_the_explorer():
    from andoyer.explore.orbits import integral_drifts
    from andoyer.integrate import propagate

    body = BODIES["kovalevskaya"]
    ds = propagate(body, [0.3, 0.2, 0.5, 0.6, 0.0, 0.8], np.linspace(0.0, 20.0, 41),
                   engine="numba", progress=False)
    assert {"K", "K_drift"} <= set(ds.data_vars)
    assert ds.K.attrs["long_name"].startswith("Kovalevskaya")
    assert float(abs(ds.K_drift).max()) < 1e-9
    d = integral_drifts(ds, float(ds.H.values.ravel()[0]), float(ds.area.values.ravel()[0]),
                        body)
    assert set(d) == {"H", "area", "geometric", "K"} and d["K"] < 1e-9
    assert "K" not in propagate(RigidBody.paper(), [0.3, 0.2, 0.5, 0.6, 0.0, 0.8],
                                np.linspace(0.0, 1.0, 3), engine="numba",
                                progress=False).data_vars
