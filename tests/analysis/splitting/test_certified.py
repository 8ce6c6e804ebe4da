"""The certified Melnikov function: balls, digits, zeros (stage 1 of the proof)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from flint import arb

from andoyer import RigidBody
from andoyer.analysis.splitting.certified import (
    _bracket_parts,
    _krawczyk_zero,
    certified_melnikov,
    melnikov_coefficient,
)
from andoyer.analysis.splitting.melnikov import melnikov_quadrature
from andoyer.integrate.validated.arithmetic import BodySpec, working_precision

CASES = [(RigidBody.paper(), "theta1=4phi0"),
         (RigidBody.near_hess(2.5, 2.0, 2.2, epsilon=0.1), "theta1=0"),
         (RigidBody.near_hess(2.5, 2.0, 2.2, epsilon=0.1), "theta1=4phi0")]


@pytest.fixture(autouse=True)
def precision():
    with working_precision(256):
        yield


@pytest.fixture(scope="module", params=range(len(CASES)))
def result(request):
    body, branch = CASES[request.param]
    return certified_melnikov(body, branch=branch, digits=30)


def test_thirty_digits_and_two_simple_zeros(result):
    assert result.digits >= 30
    assert len(result.zeros) == 2 and result.complete
    for z in result.zeros:
        assert arb(z.zero).rad() < 1e-30
        assert not arb(z.derivative).contains(0)
        assert 0.0 <= z.zero_mid < math.tau


def test_float_closed_form_lies_in_the_balls(result):
    """The float closed form agrees with each ball to its own round-off (1e-14 of M)."""
    scale = max(abs(v) for v in result.float_closed_form)
    for ball, flt in zip(result.values, result.float_closed_form, strict=True):
        x = arb(ball)
        assert x.rad() < 1e-30 * scale
        widened = arb(x.mid(), 1e-14 * scale)
        assert widened.contains(arb(flt))
        # ... and not to a looser standard: a wrong sign or factor would be caught
        assert not arb(x.mid(), 1e-14 * scale).contains(arb(-flt)) or abs(flt) < 1e-14


def test_float_zeros_lie_in_the_zero_boxes(result):
    """The closed form's zeros (float) lie in the Krawczyk boxes (to round-off)."""
    from andoyer.analysis.splitting.melnikov import heteroclinic_line
    theta1, _ = heteroclinic_line(result.body.body().nearest_hess(), 1.0, result.branch)
    expected = sorted(np.mod(math.pi / 2 - theta1 / 2 + np.array([0, math.pi]), math.tau))
    for z, e in zip(result.zeros, expected, strict=True):
        assert abs(z.zero_mid - e) < 1e-14


def test_quadrature_float_agrees():
    """The float trapezoidal rule of melnikov.py lies within 1e-14 of the certified ball."""
    body = RigidBody.paper()
    res = certified_melnikov(body, branch="theta1=4phi0", phases=[0.0, 1.0], digits=30)
    q = melnikov_quadrature(body, [0.0, 1.0], branch="theta1=4phi0")
    assert np.allclose(q, res.values_mid, rtol=0, atol=1e-14)


@pytest.mark.parametrize("sheet", [1, -1])
def test_hess_branch_of_a_hess_body_vanishes_identically(sheet):
    """On both sheets (the floats give 0 on one, 4e-21 of round-off on the other)."""
    res = certified_melnikov(RigidBody.paper(), branch="theta1=0", sheet=sheet, digits=30)
    assert res.zeros == () and not res.complete and res.digits == 0.0
    assert arb(res.amplitude).contains(0) and arb(res.amplitude).rad() < 1e-35


def test_an_underflowing_amplitude_is_no_identical_zero():
    """epsilon = 1e-400 is not the Hess body: its M is not identically zero, and the
    digits cannot be reached from a float amplitude of 0 (no false zero)."""
    with pytest.raises(ArithmeticError, match="underflows"):
        certified_melnikov(BodySpec("2.5", "2.0", "2.2", epsilon="1e-400"), digits=10)


def test_the_integral_is_independent_of_the_closed_form():
    """A wrong closed form (factor 2) would not overlap the certified integral."""
    Z, Zc, _ = melnikov_coefficient(BodySpec("2.5", "2.0", "2.2"), branch="theta1=4phi0", bits=128)
    with working_precision(128):
        assert Z.overlaps(Zc)
        assert not Z.overlaps(2 * Zc)
        assert not Z.overlaps(Zc * (1 + arb(10) ** -25))


def test_bracket_is_linear_in_the_phase():
    u, v, KE, KX = _bracket_parts()
    assert u != 0 and v != 0
    assert KE.shape == (2, 2) and KX.shape == (3, 3)


def test_krawczyk_rejects_a_box_without_a_zero():
    Z, _, _ = melnikov_coefficient(BodySpec("2.5", "2.0", "2.2"), branch="theta1=4phi0", bits=128)
    with working_precision(128):
        assert _krawczyk_zero(Z, arb(1.0), arb("0.01")) is None
        # a box around a zero that is too wide for M' to keep its sign
        assert _krawczyk_zero(Z, arb(0.091), arb(2)) is None


def test_dataset_is_self_describing(result):
    ds = result.to_dataset()
    assert ds.attrs["digits"] >= 30 and ds.attrs["body_A"] == "2.5"
    assert ds.zero_mid.attrs["units"] == "rad"
    d = result.as_dict()
    assert d["body"]["C"] == "2.2" and len(d["zeros"]) == 2


@pytest.mark.parametrize("kwargs, match", [
    ({"digits": 3}, "digits"), ({"digits": True}, "digits"), ({"branch": "x"}, "branch"),
    ({"sheet": 0}, "sheet"), ({"J2": "-1"}, "J2"), ({"J2": "abc"}, "J2")])
def test_bad_inputs_are_named(kwargs, match):
    with pytest.raises(ValueError, match=match):
        certified_melnikov(RigidBody.paper(), **kwargs)


def test_tail_bound_exceeds_the_true_tail():
    """The ball of the tails beyond T bounds what the quadrature leaves out."""
    from flint import acb

    from andoyer.analysis.splitting.certified import _setup
    spec = BodySpec("2.5", "2.0", "2.2")
    setup = _setup(spec, "theta1=4phi0", 1, "1", 128)
    Z, _, _ = melnikov_coefficient(spec, branch="theta1=4phi0", bits=128)
    for T0 in (20, 60, 120):
        part = acb.integral(lambda t, _a: setup.weight(t), -T0, T0)
        missing = abs(Z - part)
        bound = setup.tail(arb(T0))
        assert missing.upper() <= bound.lower()
