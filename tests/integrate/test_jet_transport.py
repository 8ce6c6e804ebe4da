"""Jet transport of the section map (J1)-(J4): the jets' constant and linear terms against
the engine's section map and its finite differences; area preservation; the jet
arithmetic against plain numbers."""

import math

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.charts.andoyer_deprit import from_andoyer
from andoyer.integrate.api import poincare
from andoyer.integrate.fill import section_roots
from andoyer.integrate.jet_transport import (
    Jet,
    JetBasis,
    jet_cos,
    jet_sin,
    jet_sqrt,
    reciprocal,
    section_map_jet,
)

BODY = RigidBody.hess(3.0, 1.0, 2.0, mu=1e-2)


def _engine_map(l, L):
    G = float(section_roots(BODY, 1.0, 0.0, ("g", 0.0), [l], [L])[0][0])
    ds = poincare(BODY, from_andoyer([l, 0.0, L, G, 0.0]), "g=0:+", 1, engine="numba",
                  rtol=1e-13, atol=1e-13)
    return (np.array([math.atan2(float(ds.G1[0, 0]), float(ds.G2[0, 0])), float(ds.G3[0, 0])]),
            float(ds.t[0, 0]), G)


def test_jet_arithmetic_matches_numbers():
    basis = JetBasis(9)
    x = Jet(basis.variable(0, 0.7), basis)
    y = Jet(basis.variable(1, 1.3), basis)
    f = jet_sin(x) * jet_sqrt(y) / (1.0 + x * y) + jet_cos(y) ** 2 - reciprocal(y)
    u, v = 1e-2, -2e-2
    exact = (math.sin(0.7 + u) * math.sqrt(1.3 + v) / (1 + (0.7 + u) * (1.3 + v))
             + math.cos(1.3 + v) ** 2 - 1 / (1.3 + v))
    assert abs(basis.evaluate(f.c, u, v) - exact) < 1e-14      # O(0.02^10) truncation


def test_section_map_jet_matches_the_engine():
    l0, L0 = 0.1, 0.05
    p0, T, G0 = _engine_map(l0, L0)
    jet = section_map_jet(BODY, 1.0, 0.0, 0.0, l0, L0, G0, T, degree=4, n_steps=96)
    assert abs(jet.l[0] - p0[0]) < 1e-11 and abs(jet.L[0] - p0[1]) < 1e-11
    assert abs(jet.time - T) < 1e-9
    e = 1e-5
    J = np.column_stack([(_engine_map(l0 + e, L0)[0] - _engine_map(l0 - e, L0)[0]) / (2 * e),
                         (_engine_map(l0, L0 + e)[0] - _engine_map(l0, L0 - e)[0]) / (2 * e)])
    assert np.max(np.abs(J - jet.matrix())) < 1e-7             # finite differences: O(e^2)
    assert abs(np.linalg.det(jet.matrix()) - 1.0) < 1e-12      # (l, L) canonical: area kept
    # a point of the map off the base point, by the polynomial and by the engine
    du, dv = 2e-3, -1e-3
    p1 = _engine_map(l0 + du, L0 + dv)[0]
    q1 = np.array([jet.basis.evaluate(jet.l, du, dv), jet.basis.evaluate(jet.L, du, dv)])
    assert np.max(np.abs(p1 - q1)) < 1e-12                     # degree 4: O(2e-3^5)
    assert jet.error.max() < 1e-11


def test_section_map_jet_refuses_bad_options():
    with pytest.raises(ValueError, match="degree"):
        section_map_jet(BODY, 1.0, 0.0, 0.0, 0.0, 0.0, 1.4, 4.4, degree=0, n_steps=10)
    with pytest.raises(ValueError, match="n_steps"):
        section_map_jet(BODY, 1.0, 0.0, 0.0, 0.0, 0.0, 1.4, 4.4, degree=2, n_steps=7)
