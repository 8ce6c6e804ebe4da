"""The validated Taylor integrator: its enclosures hold the float engines' orbits and the
closed forms (Hess solution, Euler-Poinsot), its derivative the difference quotients."""

from __future__ import annotations

import numpy as np
import pytest
from flint import arb

from andoyer import RigidBody
from andoyer.analysis.hess.solution import hess_solution
from andoyer.analysis.unperturbed.euler_poinsot import euler_poinsot_momentum
from andoyer.integrate import poincare, propagate
from andoyer.integrate.validated.arithmetic import BodySpec, field_terms, working_precision
from andoyer.integrate.validated.taylor import (
    quadratic_field,
    taylor_jets,
    validated_flow,
    validated_poincare,
    variational_jets,
)

Y0 = [0.3, 0.8, 0.2, 0.6, 0.0, 0.8]
STATE = ["G1", "G2", "G3", "gamma1", "gamma2", "gamma3"]


def _float_states(body, y0, times):
    ds = propagate(body, y0, np.asarray(times), engine="taylor", rtol=1e-15, atol=1e-15)
    return np.stack([ds[c].values[0] for c in STATE], axis=-1)


@pytest.fixture(scope="module")
def point_orbit():
    return validated_flow(RigidBody.paper(), Y0, 10.0)


@pytest.fixture(scope="module")
def set_orbit():
    return validated_flow(RigidBody.paper(), Y0, 10.0, radius=1e-9)


def test_set_enclosure_holds_the_float_orbit(set_orbit):
    """The float orbit of the box's centre lies in the hull at every step, no slack."""
    ref = _float_states(RigidBody.paper(), Y0, set_orbit.times)
    for k in range(len(set_orbit.times)):
        assert set_orbit.contains(k, ref[k])


def test_point_enclosure_is_tight_and_near_the_float_orbit(point_orbit):
    ref = _float_states(RigidBody.paper(), Y0, point_orbit.times)
    assert point_orbit.rad[-1].max() < 1e-24
    for k in range(len(point_orbit.times)):
        assert point_orbit.contains(k, ref[k], slack=1e-12)
    # the slack is the float engine's error, not the enclosure's: 1e-12 off is caught
    assert not point_orbit.contains(len(point_orbit.times) - 1, ref[-1] + 1e-11)


def test_hess_closed_form_lies_in_the_enclosure():
    body = RigidBody.paper()
    t = [0.0, 30.0]
    ds = hess_solution(body, [0.0, 4.7, 0.03, 0.1, 0.0], t)
    y0 = [float(ds[c].values[0]) for c in STATE]
    orb = validated_flow(body, y0, 30.0, h_max=2.0)
    end = [float(ds[c].values[-1]) for c in STATE]
    assert orb.contains(len(orb.times) - 1, end, slack=1e-12)
    assert orb.rad[-1].max() < 1e-20


def test_euler_poinsot_elliptic_solution_lies_in_the_enclosure():
    body = RigidBody(2.5, 2.0, 2.2, 0.0, (1.0, 0.0, 0.0))
    y0 = [0.3, 0.8, 0.5, 0.0, 0.0, 1.0]
    orb = validated_flow(body, y0, 20.0, radius=1e-12)
    G = euler_poinsot_momentum(body, y0[:3], list(orb.times))
    for k in range(len(orb.times)):
        assert np.all(np.abs(G[k] - orb.mid[k, :3]) <= orb.rad[k, :3] + 1e-13)
    assert orb.rad[-1, :3].max() < 1e-9


def test_derivative_encloses_difference_quotients():
    """Over a set of radius 1e-6, Dphi's enclosure holds the difference quotient of two
    validated point orbits inside the set (the average of Dphi on a segment of the set)."""
    body = RigidBody.paper()
    T, d = 3.0, 1e-7
    big = validated_flow(body, Y0, T, radius=1e-6)
    with working_precision(128):
        D = [arb(x) for x in big.derivative]
        for j in (0, 2, 4):
            yp = list(Y0)
            ym = list(Y0)
            yp[j] += d
            ym[j] -= d
            a = validated_flow(body, yp, T)
            b = validated_flow(body, ym, T)
            for i in range(6):
                q = (arb(a.states[-1][i]) - arb(b.states[-1][i])) / (2 * arb(d))
                assert D[6 * i + j].overlaps(q), (i, j)


def test_jets_of_the_field_agree_with_the_symbolic_field():
    """The first Taylor coefficient is the field (1) derived from H (no hand-typed field)."""
    import sympy as sp

    from andoyer.symbolic.hamiltonian import S, euler_poisson_field
    body = RigidBody.paper()
    f = quadratic_field(body)
    with working_precision(128):
        Y = taylor_jets(f, [arb(v) for v in Y0], 2)
        vals = dict(zip(S.y, Y0, strict=True))
        vals.update(dict(zip(S.body, body.params, strict=True)))
        for i, e in enumerate(euler_poisson_field()):
            assert abs(float(Y[i][1].mid()) - float(sp.N(e.subs(vals)))) < 1e-15
    assert len(field_terms().terms) == 6


def test_variational_jets_are_the_jets_of_the_state_derivative():
    """``W = dY/dy0`` coefficient by coefficient, independently of the matrix recursion:
    on a quadratic field ``d/dy0_c`` of the state's jets from ``y0`` is the state's jets
    of the tangent vector e_c, taken here by forward-mode dual numbers (the jets of
    ``y0 + eps e_c`` with ``eps^2 = 0``, term by term in Arb); from a box and from a
    non-identity start matrix, each ball overlapping the other's."""
    f = quadratic_field(RigidBody.paper())
    order = 12
    with working_precision(128):
        y0 = [arb(v, 1e-9) for v in Y0]
        V0 = [[arb(1 + i + 2 * j) / 7 if i != j else arb(1) for j in range(6)]
              for i in range(6)]
        Y, W = variational_jets(f, y0, V0, order)
        for c in range(6):
            # jets of (y, v) with v' = Df(y) v by the field's terms: d(c y_j y_l) =
            # c (v_j y_l + y_j v_l), Cauchy products coefficient by coefficient
            y = [[y0[i]] for i in range(6)]
            v = [[V0[i][c]] for i in range(6)]
            for k in range(order):
                ny, nv = [], []
                for i in range(6):
                    sy, sv = arb(0), arb(0)
                    for cf, j in f.linear[i]:
                        sy += cf * y[j][k]
                        sv += cf * v[j][k]
                    for cf, j, l_ in f.quadratic[i]:
                        for m in range(k + 1):
                            sy += cf * y[j][m] * y[l_][k - m]
                            sv += cf * (v[j][m] * y[l_][k - m] + y[j][m] * v[l_][k - m])
                    ny.append(sy / (k + 1))
                    nv.append(sv / (k + 1))
                for i in range(6):
                    y[i].append(ny[i])
                    v[i].append(nv[i])
            for i in range(6):
                for k in range(order + 1):
                    assert W[i][c][k].overlaps(v[i][k]), (i, c, k)
                    assert Y[i][k].overlaps(y[i][k])
        assert any(abs(float(W[i][c][order].mid())) > 1e-12 for i in range(6)
                   for c in range(6))


def test_poincare_crossing_is_certified_and_holds_the_float_crossing():
    body = RigidBody.paper()
    c = validated_poincare(body, Y0, [0, 0, 1, 0, 0, 0], 0.0, direction=-1, radius=1e-10)
    ds = poincare(body, Y0, "G3=0:-", 1, rtol=1e-15, atol=1e-15, engine="taylor")
    ref = np.array([float(ds[n].values[0, 0]) for n in STATE])
    assert np.all(np.abs(ref - c.image_mid) <= c.image_rad)
    with working_precision(128):
        assert arb(c.time).contains(arb(float(ds.t.values[0, 0])))
        assert arb(c.image[2]).contains(0)
        assert arb(c.time_point).rad() < 1e-25
    # the map's derivative maps into the section: its G3 row vanishes
    assert np.abs(c.derivative_mid[2]).max() < 1e-20


def test_decimal_body_spec_is_accepted():
    orb = validated_flow(BodySpec("2.5", "2.0", "2.2", mu="0.01"), Y0, 1.0)
    ref = validated_flow(RigidBody.paper(), Y0, 1.0)
    # the decimal 2.2 and the float 2.2 differ by 2e-16: so do the orbits
    assert np.abs(orb.mid[-1] - ref.mid[-1]).max() < 1e-14


@pytest.mark.parametrize("kwargs, match", [
    ({"t_end": -1.0}, "t_end"), ({"t_end": float("nan")}, "t_end"),
    ({"order": 2}, "order"), ({"radius": -1.0}, "radius"), ({"y0": [1.0, 2.0]}, "y0")])
def test_bad_inputs_are_named(kwargs, match):
    args = {"body": RigidBody.paper(), "y0": Y0, "t_end": 1.0, **kwargs}
    with pytest.raises(ValueError, match=match):
        validated_flow(**args)


@pytest.mark.slow
def test_width_growth_is_reported():
    orb = validated_flow(RigidBody.paper(), Y0, 100.0, radius=1e-10)
    assert np.all(np.isfinite(orb.rad)) and orb.rad[-1].max() < 1e-4


def test_remainder_makes_long_steps_rigorous():
    """At order 6 with steps ~ (1e-4)^(1/6) of the radius of convergence the truncation
    error is ~1e-4 per step: only the Lagrange remainder keeps the float orbit inside."""
    body = RigidBody.paper()
    orb = validated_flow(body, Y0, 5.0, order=6, tol=1e-4)
    ref = _float_states(body, Y0, orb.times)
    for k in range(len(orb.times)):
        assert orb.contains(k, ref[k])
    assert orb.rad[-1].max() > 1e-8  # the remainder is what the width is made of


def test_backward_flow_returns_to_the_start():
    """Forward to t = 5 then backward from the enclosure's hull: the box holds the start."""
    body = RigidBody.paper()
    fwd = validated_flow(body, Y0, 5.0)
    with working_precision(128):
        end = [arb(x) for x in fwd.states[-1]]
        back = validated_flow(body, [arb(x.mid()) for x in end], 5.0, backward=True,
                              radius=[float(x.rad()) for x in end])
    assert back.times[-1] == -5.0
    assert back.contains(len(back.times) - 1, Y0)
    assert not back.contains(len(back.times) - 1, [Y0[0] + 1e-15, *Y0[1:]])
