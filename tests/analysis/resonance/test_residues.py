"""Greene's residues of a noble torus's convergents and its critical mu (G1)-(G7).

The residues are checked against what does not share their route: the continued
fraction's identities, the reversing symmetry on the vector field and the charts, the
first-order pendulum of a chain (R8), and as measured laws: the decay of the residues
with the convergent's period below the critical mu and their growth above it, the
geometric convergence of mu_c(q), and the scaling mu_c(h) = h mu_c(1) on M = 0 (G7).
"""

import math
from fractions import Fraction

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.resonance.residues import (
    _Level,
    convergents,
    last_torus,
    noble_number,
)
from andoyer.charts.andoyer_deprit import from_andoyer, to_andoyer
from andoyer.dynamics import vector_field
from andoyer.integrate.engines import resolve_engine
from andoyer.integrate.engines.base import Capability, Tolerance
from andoyer.integrate.engines.values import E3_ZERO_REVERSAL

HESS = RigidBody.hess(3.0, 1.0, 2.0, mu=2e-3)


@pytest.mark.parametrize("head", [(2,), (7,), (7, 2), (3, 1, 4)])
def test_convergents_approach_the_noble_number(head):
    """(G1): ``|W - p/q| < 1/q^2``, alternately from both sides, ``p_j q_{j-1} - p_{j-1} q_j
    = +-1``; ``W`` between ``1/(n+1)`` and ``1/n``."""
    W = noble_number(head)
    n = head[0]
    assert 1.0 / (n + 1) < W < 1.0 / n
    conv = convergents(head, 16)
    for (p0, q0), (p1, q1) in zip(conv, conv[1:], strict=False):
        assert abs(p1 * q0 - p0 * q1) == 1
        assert q1 > q0
        assert (W - p0 / q0) * (W - p1 / q1) < 0          # alternate sides
    for p, q in conv:
        assert math.gcd(p, q) == 1 and abs(W - p / q) < 1.0 / q**2
    # the golden mean's tail: q_{j+1}/q_j -> phi
    assert abs(conv[-1][1] / conv[-2][1] - (1 + math.sqrt(5)) / 2) < 1e-4
    assert Fraction(*conv[0]) == Fraction(1, n)


def test_the_symmetry_reverses_the_flow_and_fixes_the_lines():
    """(G2): ``f(S y) = -S f(y)`` for a centre of mass in Oxy (not for e3 != 0), and S acts
    as ``(l, g, L, G, M) -> (l, pi - g, -L, G, M)``."""
    rng = np.random.default_rng(7)
    y = rng.normal(size=(5, 6))
    y[:, 3:] /= np.linalg.norm(y[:, 3:], axis=1, keepdims=True)
    for i in range(5):
        np.testing.assert_allclose(vector_field(HESS, E3_ZERO_REVERSAL * y[i]),
                                   -E3_ZERO_REVERSAL * vector_field(HESS, y[i]), atol=1e-14)
    tilted = RigidBody(3.0, 1.0, 2.0, 2e-3, (0.6, 0.48, 0.64))
    assert not np.allclose(vector_field(tilted, E3_ZERO_REVERSAL * y[0]),
                           -E3_ZERO_REVERSAL * vector_field(tilted, y[0]))
    x = to_andoyer(y)
    xs = to_andoyer(E3_ZERO_REVERSAL * y)
    np.testing.assert_allclose(xs[:, 0], x[:, 0], atol=1e-12)
    np.testing.assert_allclose(np.mod(xs[:, 1] + x[:, 1], 2 * np.pi), np.pi, atol=1e-12)
    np.testing.assert_allclose(xs[:, 2:], x[:, 2:] * np.array([-1.0, 1.0, 1.0]), atol=1e-12)
    # the fixed set on g = pi/2: L = 0
    on = from_andoyer([0.4, np.pi / 2, 0.0, 1.3, 0.2])
    np.testing.assert_allclose(E3_ZERO_REVERSAL * on, on, atol=1e-15)


def test_residues_of_a_main_chain_are_its_pendulum():
    """(G4) against (R8): the 1:3 chain's orbits of Hess(3, 1, 2) about axis 1 at a small
    mu, found on the symmetry lines, have the first-order residues ``sin^2(pi q Omega)`` and
    ``-sinh^2(pi q Omega)`` within O(mu) (relative)."""
    from andoyer.analysis.resonance import resonance_widths

    mu = 1e-4
    body = HESS.with_mu(mu)
    pred = resonance_widths(body, 1.0, 0.0, max_order=4)
    row = pred.where((pred.label == "3:1") & (pred.axis == 1) & (pred.sign == 1), drop=True)
    level = _Level(body, 1.0, 0.0, 1, (1 / 3, 1 / 2), resolve_engine(
        None, Capability.TANGENT_CROSSINGS), Tolerance.single(1e-13), 10.0)
    ell, hyp = level.pair(1, 3)
    assert ell is not None and hyp is not None and ell.winding == hyp.winding == 1
    assert ell.closure < 1e-10 and hyp.closure < 1e-10
    np.testing.assert_allclose(ell.residue, float(row.residue_stable[0]), rtol=0.05)
    np.testing.assert_allclose(hyp.residue, float(row.residue_unstable[0]), rtol=0.05)
    assert abs(ell.residue / float(row.residue_stable[0]) - 1) > 1e-6   # not the same route


def test_half_orbits_in_one_batch_equal_them_one_by_one():
    """(G3) ``F(l0)`` of a grid of starts from one engine batch (seeds and half orbits),
    against a fresh level's one start at a time: equal to the integration's tolerance,
    NaN at the same starts, and cached, so the single start asks the batch's value."""
    body = HESS.with_mu(1e-3)
    engine = resolve_engine("taylor", Capability.TANGENT_CROSSINGS)

    def level() -> _Level:
        return _Level(body, 1.0, 0.0, 1, (1 / 3, 1 / 2), engine, Tolerance.single(1e-13),
                      10.0)

    batch = level()
    ls = np.array([batch.l_of_W(W, -1) for W in np.linspace(0.34, 0.48, 12)])
    many = batch.halves(ls, math.pi / 2, 2, 5)
    single = level()
    one = np.array([single.half(float(x), math.pi / 2, 2, 5) for x in ls])
    assert np.isfinite(many).sum() >= 8
    np.testing.assert_array_equal(np.isnan(many), np.isnan(one))
    np.testing.assert_allclose(many, one, rtol=0, atol=1e-9, equal_nan=True)
    assert np.any(np.sign(many[np.isfinite(many)]) > 0) and np.any(many < 0)
    evaluations = batch.evaluations
    assert batch.half(float(ls[3]), math.pi / 2, 2, 5) == many[3]
    assert batch.evaluations == evaluations


def test_residues_fall_with_the_period_below_the_critical_mu():
    """(G5), measured on a cheap torus: the golden one between the 2:1 and 3:1 chains of
    Hess(3, 1, 2) about axis 2 at mu = 2e-3 (mu_overlap = 0.19). Each convergent's
    elliptic residue is below a fifth of the previous one (2/5, 3/8, 5/13: 2.3e-4,
    1.7e-5, 1.6e-8), the hyperbolic residue is minus the elliptic one to 1e-3 (the
    pendulum at small residue), and every orbit closes."""
    ds = last_torus(HESS, 1.0, head=(2,), axis=2, n_convergents=3, progress=False)
    assert [f"{p}/{q}" for p, q in zip(ds.p.values, ds.q.values, strict=True)] == \
        ["2/5", "3/8", "5/13"]
    assert ds.found_elliptic.all() and ds.found_hyperbolic.all()
    Re, Rh = ds.residue_elliptic.values, ds.residue_hyperbolic.values
    assert np.all(Re > ds.residue_resolution_elliptic.values)
    assert np.all(Re[1:] < 0.2 * Re[:-1])
    np.testing.assert_allclose(-Rh, Re, rtol=1e-3)
    assert float(ds.closure_elliptic.max()) < 1e-10
    assert math.isnan(float(ds.mu_critical))            # no mu_range: not sought
    assert float(ds.chirikov_parameter) == pytest.approx(0.1025, rel=1e-3)
    assert float(ds.mu_overlap) == pytest.approx(HESS.mu / float(ds.chirikov_parameter) ** 2)
    assert ds.residue_elliptic.attrs["equation"] == "(G4)"
    assert ds.attrs["main_chains"] == "2:1, 3:1" and ds.attrs["threshold"] == 0.25


@pytest.mark.parametrize("kwargs, message", [
    ({"head": (1,)}, "head"),
    ({"head": "2"}, "head"),
    ({"head": (2, 0)}, "head"),
    ({"axis": 3}, "axis"),
    ({"n_convergents": 0}, "n_convergents"),
    ({"mu_range": (0.1, 0.01)}, "mu_range"),
    ({"mu_range": (0.1,)}, "mu_range"),
    ({"mu_range": (-1.0, 0.1)}, "mu_range"),
    ({"head": (40,), "axis": 2}, "head"),
    ({"tol": 1.0}, "tol"),
])
def test_last_torus_refuses_bad_input_naming_it(kwargs, message):
    with pytest.raises(ValueError, match=message):
        last_torus(HESS, 1.0, **kwargs)


def test_last_torus_refuses_bodies_without_the_symmetry_and_mu_zero():
    with pytest.raises(ValueError, match="e3 = 0"):
        last_torus(RigidBody(3.0, 1.0, 2.0, 2e-3, (0.6, 0.48, 0.64)), 1.0)
    with pytest.raises(ValueError, match="mu > 0"):
        last_torus(HESS.with_mu(0.0), 1.0)


def test_last_torus_refuses_work_over_the_budget():
    from andoyer.errors import CostLimitError
    from andoyer.integrate import budget

    with budget.limits(steps=1e4), pytest.raises(CostLimitError, match="last_torus"):
        last_torus(HESS, 1.0, head=(2,), axis=2, n_convergents=3, progress=False)


@pytest.mark.slow
def test_critical_mu_converges_and_residues_follow_greene():
    """(G5) on the golden torus between the 2:1 and 3:1 chains of Hess(3, 1, 2) about
    axis 1 (h = 1): mu_c(q_j) converges (the last change below 5 % of mu_c); below
    mu_c / 2 the elliptic residues fall with q, above 2 mu_c they grow; mu_c is below the
    overlap estimate (G6)."""
    body = HESS.with_mu(1e-3)
    ds = last_torus(body, 1.0, head=(2,), axis=1, n_convergents=6, mu_range=(1e-3, 0.1),
                    progress=False)
    mu_c = float(ds.mu_critical)
    assert math.isfinite(mu_c)
    assert float(ds.mu_critical_error) < 0.05 * mu_c
    assert 0.1 < float(ds.mu_ratio) < 1.0
    below = last_torus(body.with_mu(0.5 * mu_c), 1.0, head=(2,), axis=1, n_convergents=5,
                       progress=False).residue_elliptic.values
    above = last_torus(body.with_mu(2.0 * mu_c), 1.0, head=(2,), axis=1, n_convergents=5,
                       progress=False).residue_elliptic.values
    assert np.all(below[1:] < below[:-1])
    good = above[np.isfinite(above)]
    assert good.size >= 3 and good[-1] > 1.0 > below[0]


@pytest.mark.slow
def test_critical_mu_scales_with_the_level():
    """(G7): on M = 0, mu_c(2 h) = 2 mu_c(h) (the computation does not use it)."""
    one = last_torus(HESS.with_mu(1e-3), 1.0, head=(2,), axis=1, n_convergents=4,
                     mu_range=(1e-3, 0.1), progress=False)
    two = last_torus(HESS.with_mu(2e-3), 2.0, head=(2,), axis=1, n_convergents=4,
                     mu_range=(2e-3, 0.2), progress=False)
    np.testing.assert_allclose(two.mu_critical_convergent, 2 * one.mu_critical_convergent,
                               rtol=1e-4)


@pytest.mark.slow
def test_the_paper_body_breaks_near_its_separatrix():
    """The paper's body on its level: the golden torus between the crowded chains 30:1 and
    31:1 has mu_c = 0.0079 (< the paper's 0.01; the last change 5e-5), and at mu = 0.01 its
    residues grow with q (Greene: broken), while the golden torus between the main chains
    7:1 and 8:1 has residues falling to the integration's resolution."""
    from andoyer.integrate.fill import default_h

    body = RigidBody.paper()
    h = default_h(body)
    sep = last_torus(body, h, head=(30,), axis=1, n_convergents=5, mu_range=(1e-3, 0.03),
                     progress=False)
    assert 0.0075 < float(sep.mu_critical) < 0.0083
    assert float(sep.mu_critical_error) < 2e-4
    R = sep.residue_elliptic.values
    assert sep.found_elliptic.all() and np.all(R[1:] > R[:-1]) and R[-1] > 1.0
    main = last_torus(body, h, head=(7,), axis=1, n_convergents=3, progress=False)
    Rm = np.abs(main.residue_elliptic.values)
    assert Rm[0] < 1e-6 and Rm[1] < 1e-3 * Rm[0]
    assert Rm[2] < 10 * float(main.residue_resolution_elliptic[2])
