"""The examples of issue 24 item 7, each one of a class the hunt (tests/test_hunt.py)
covers for the whole public API: refused naming the argument, never a leaked message, a
silent NaN or a half-applied change."""

from __future__ import annotations

import math

import numpy as np
import pytest

import andoyer
from andoyer import RigidBody
from andoyer.analysis.chaos.alignment import gali, sali
from andoyer.analysis.chaos.border import chaos_border, chaos_border_map
from andoyer.analysis.splitting.measure import splitting_vs_epsilon
from andoyer.analysis.splitting.melnikov import melnikov_off_hess
from andoyer.integrate import budget

HESS = RigidBody.hess(2.5, 1.0, 1.6)


def test_gali_refuses_more_vectors_than_dimensions_and_zero_vectors():
    rng = np.random.default_rng(1)
    with pytest.raises(ValueError, match="k <= d"):
        gali(rng.normal(size=(7, 6)))     # returned 1.41
    with pytest.raises(ValueError, match="W holds a zero vector"):
        gali([[1.0, 0, 0, 0, 0, 0], [0.0, 0, 0, 0, 0, 0]])
    for w1, w2, name in (([0.0] * 6, [1.0] + [0.0] * 5, "w1"),
                         ([1.0] + [0.0] * 5, [0.0] * 6, "w2")):
        with pytest.raises(ValueError, match=f"{name} holds a zero vector"):
            sali(w1, w2)                  # returned NaN
    assert float(gali(np.eye(6))) == 1.0  # k = d is a volume
    assert math.isclose(float(sali([1e300, 0], [0, 1e-300])), math.sqrt(2.0))


def test_set_limits_is_all_or_nothing_and_takes_no_bools():
    before = dict(budget.LIMITS)
    with pytest.raises(ValueError, match="memory"):
        budget.set_limits(steps=1e3, memory=-1)
    assert budget.LIMITS == before        # the step limit was changed before
    for bad in (True, "1e3", math.nan, 0.0):
        with pytest.raises(ValueError, match="steps"):
            budget.set_limits(steps=bad)
        assert budget.LIMITS == before
    with budget.limits(steps=math.inf):
        assert budget.LIMITS["steps"] == math.inf
    assert budget.LIMITS == before


@pytest.mark.parametrize("branch", [True, False, 1.5, "1", None])
def test_near_hess_refuses_a_bool_or_another_branch(branch):
    with pytest.raises(ValueError, match="branch"):
        RigidBody.near_hess(2.5, 1.0, 1.6, epsilon=0.1, branch=branch)


@pytest.mark.parametrize("theta2_0", [[math.nan], [0.0, math.inf], "x", [["a"]]])
def test_melnikov_refuses_non_finite_phases(theta2_0):
    for method in ("closed_form", "trapezoid"):
        with pytest.raises(ValueError, match="theta2_0"):
            melnikov_off_hess(HESS, 0.05, theta2_0, method=method)


@pytest.mark.parametrize("call, name", [
    (lambda: chaos_border(HESS, 0.3125, section="x", n=4, t_end=5.0), "section"),
    (lambda: chaos_border(HESS, 0.3125, section=5, n=4, t_end=5.0), "section"),
    (lambda: chaos_border(HESS, 0.3125, section=("theta2",), n=4, t_end=5.0), "section"),
    (lambda: chaos_border(HESS, 0.3125, n="x", t_end=5.0), "n"),
    (lambda: chaos_border(HESS, 0.3125, n=math.inf, t_end=5.0), "n"),
    (lambda: chaos_border(HESS, "0.3", n=4, t_end=5.0), "h"),
    (lambda: chaos_border(HESS, 0.3125, n=4, t_end=5.0, engine=["numba"]), "engine"),
    (lambda: chaos_border(HESS, 0.3125, n=4, t_end=5.0, progress="no"), "progress"),
    (lambda: chaos_border_map("paper", [0.01], [0.0], 0.3125), "body"),
    (lambda: chaos_border_map(HESS, "x", [0.0], 0.3125, n=4, t_end=5.0), "mu"),
    (lambda: chaos_border_map(HESS, [0.01], [[math.nan]], 0.3125, n=4, t_end=5.0),
     "epsilon"),
    (lambda: splitting_vs_epsilon(HESS, "x", [0.01]), "epsilon"),
    (lambda: splitting_vs_epsilon(HESS, [0.1], [0.01], branch=["theta1=0"]), "branch"),
    (lambda: splitting_vs_epsilon(HESS, [0.1], {"mu": 1}), "mu"),
    (lambda: melnikov_off_hess(HESS, "0.1", [0.0]), "epsilon"),
    (lambda: melnikov_off_hess(HESS, 0.1, [0.0], method=["trapezoid"]), "method"),
    (lambda: andoyer.cite(["tool"]), "what"),
    (lambda: andoyer.cite(None), "what"),
])
def test_strings_and_malformed_arguments_are_named(call, name):
    with pytest.raises((ValueError, TypeError), match=rf"\b{name}\b"):
        call()
