"""Ball arithmetic of the body and the field: exact decimals, exact evaluation."""

from __future__ import annotations

import pytest
import sympy as sp
from flint import arb

from andoyer import RigidBody
from andoyer.integrate.validated.arithmetic import (
    BodySpec,
    ball_from_text,
    ball_text,
    correct_digits,
    evaluate,
    field_terms,
    working_precision,
)


def test_body_spec_validation():
    with pytest.raises(ValueError, match="A > C > B"):
        BodySpec("2.0", "2.5", "2.2")
    with pytest.raises(ValueError, match="branch"):
        BodySpec("2.5", "2.0", "2.2", branch=0)
    with pytest.raises(ValueError, match="epsilon"):
        BodySpec("2.5", "2.0", "2.2", epsilon="nan")
    spec = BodySpec.from_body(RigidBody.near_hess(2.5, 2.0, 2.2, mu=0.01, epsilon=0.1))
    assert spec.epsilon == "0.1" and spec.C == "2.2"


def test_decimal_moments_are_exact_decimals():
    """C = 2.2 is the decimal 2.2: its ball holds 11/5, not only the float nearest."""
    with working_precision(200):
        C = BodySpec("2.5", "2.0", "2.2").balls(200).C
        assert C.overlaps(arb(11) / 5) and C.rad() < 1e-55
        assert not arb(2.2).overlaps(arb(11) / 5)  # the float is not 11/5


def test_evaluate_is_exact_on_rationals_and_refuses_floats():
    x = sp.Symbol("x")
    with working_precision(200):
        v = evaluate(x / 3, {x: arb(1)})
        assert v.contains(arb(1) / 3) and v.rad() < 1e-55
        with pytest.raises(ValueError, match="exactly"):
            evaluate(sp.Float(0.1) * x, {x: arb(1)})
        with pytest.raises(ValueError, match="exactly"):
            evaluate(sp.sin(x), {x: arb(1)})


def test_ball_text_round_trips():
    with working_precision(128):
        x = arb(1) / 3
        y = ball_from_text(ball_text(x))
        assert y.contains(x) and correct_digits(y) > 30


def test_field_is_quadratic_with_a_linear_mu_part():
    terms = field_terms()
    assert all(len(idx) in (1, 2) for comp in terms.terms for _, idx in comp)
    assert all(len(idx) == 1 for comp in terms.mu_terms for _, idx in comp)
    assert sum(len(c) for c in terms.mu_terms) == 6  # gamma x r
    assert RigidBody.paper().is_hess
