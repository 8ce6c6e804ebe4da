"""The rotations P+- carried once around in balls: they close, their period is the
pendulum's, their multipliers are the closed form's (Hess) and the float Floquet's."""

from __future__ import annotations

import pytest
from flint import acb, arb

from andoyer import RigidBody
from andoyer.analysis.hess.floquet import floquet_multipliers
from andoyer.analysis.splitting.hyperbolic import certified_rotation
from andoyer.integrate.validated.arithmetic import working_precision


@pytest.fixture(scope="module")
def paper_rotations():
    body = RigidBody.paper()
    return body, certified_rotation(body, sign=1), certified_rotation(body, sign=-1)


def test_rotations_close_and_are_hyperbolic(paper_rotations):
    _, plus, minus = paper_rotations
    for rot in (plus, minus):
        assert rot.closes and rot.hyperbolic
        assert rot.unstable > 1.5 and abs(rot.unstable * rot.stable - 1) < 1e-15
        assert rot.return_width < 1e-30


def test_period_is_the_pendulum_integral_and_symmetric(paper_rotations):
    """T = int_0^{2 pi} dpsi / (c |G3(psi)|) by Arb's quadrature; P+ and P- alike."""
    body, plus, minus = paper_rotations
    with working_precision(128):
        c, mu = 1 / arb(body.C), arb(body.mu)
        e1, e2 = arb(body.e1), arb(body.e2)

        def f(psi, analytic):
            rad = 1 - 2 * mu * (e1 * psi.cos() + e2 * psi.sin()) / c
            return 1 / (c * rad.sqrt(analytic=analytic))

        T = acb.integral(f, 0, 2 * arb.pi()).real
        assert arb(plus.period).overlaps(T) and arb(minus.period).overlaps(T)
        assert arb(plus.period).overlaps(arb(minus.period))
        assert not arb(plus.period).overlaps(T * (1 + arb(10) ** -25))


def test_multiplier_of_a_hess_body_is_exp_2pi_sigma_over_c(paper_rotations):
    body, plus, _ = paper_rotations
    with working_precision(128):
        a, b, c = 1 / arb(body.A), 1 / arb(body.B), 1 / arb(body.C)
        lam = (2 * arb.pi() * ((b - c) * (c - a)).sqrt() / c).exp()
        assert arb(plus.multipliers[2]).overlaps(lam)
        assert not arb(plus.multipliers[2]).overlaps(lam * (1 + arb(10) ** -15))
    assert plus.imaginary_bound < 1e-15


def test_near_hess_multiplier_agrees_with_the_float_floquet():
    body = RigidBody.near_hess(2.5, 2.0, 2.2, mu=0.01, epsilon=0.1)
    rot = certified_rotation(body, sign=1)
    flt = floquet_multipliers(body, 0.5 * body.c)
    assert rot.hyperbolic
    assert abs(rot.unstable - max(abs(flt.multipliers))) < 1e-9


def test_bad_inputs_are_named():
    with pytest.raises(ValueError, match="sign"):
        certified_rotation(RigidBody.paper(), sign=0)
    with pytest.raises(ValueError, match="below the top"):
        certified_rotation(RigidBody.paper(mu=1.0), G="0.1")
