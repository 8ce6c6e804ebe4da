"""The taylor engine beyond the common contract (``test_engine_contract.py`` runs it too).

* bad options are refused naming the argument; one tolerance, the smaller;
* random states, also next to the singular sets of the Andoyer-Deprit chart
  (``G1 = G2 = 0``, where the angle ``l`` is undefined, and ``|G3| = |G|``), give the
  numba engine's orbits and crossings;
"""

from __future__ import annotations

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.integrate.engines import get_engine
from andoyer.integrate.engines.base import Section, Tolerance
from andoyer.integrate.engines.taylor_engine import TaylorEngine


def params(body: RigidBody) -> tuple[float, ...]:
    return tuple(body.engine_params)


def random_states(n: int, rng: np.random.Generator, near_axis: float = 0.0) -> np.ndarray:
    """States with |gamma| = 1 and |G| ~ 1; ``near_axis > 0``: G within that distance of
    the body axis 3 (G1 = G2 = 0, a singular set of the chart)."""
    gamma = rng.normal(size=(n, 3))
    gamma /= np.linalg.norm(gamma, axis=1, keepdims=True)
    G = rng.normal(size=(n, 3))
    if near_axis:
        G[:, :2] *= near_axis / np.linalg.norm(G[:, :2], axis=1, keepdims=True)
        G[:, 2] = np.sign(G[:, 2])
    return np.ascontiguousarray(np.hstack([G, gamma]))


def test_options_are_checked() -> None:
    with pytest.raises(ValueError, match="max_steps"):
        TaylorEngine(max_steps=0)
    with pytest.raises(ValueError, match="n_threads"):
        TaylorEngine(n_threads=0)
    assert repr(get_engine("taylor")).startswith("TaylorEngine(")


def test_the_single_tolerance_is_the_smaller_one() -> None:
    """rtol = 1e-6 with atol = 1e-12 integrates at 1e-12 (as heyoka's engine)."""
    p = params(RigidBody.paper())
    y0 = random_states(2, np.random.default_rng(0))
    t = np.array([0.0, 10.0])
    a = TaylorEngine().propagate(y0, t, p, Tolerance(1e-6, 1e-12))
    b = TaylorEngine().propagate(y0, t, p, Tolerance(1e-12, 1e-12))
    np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("near_axis", [0.0, 1e-7])
def test_random_states_agree_with_the_numba_engine(near_axis: float) -> None:
    body = RigidBody(1.3, 1.7, 2.1, mu=0.5, r=(0.3, -0.5, 0.8))
    p = params(body)
    y0 = random_states(6, np.random.default_rng(3), near_axis)
    t = np.linspace(0.0, 30.0, 7)
    a = TaylorEngine().propagate(y0, t, p, Tolerance(1e-12, 1e-12))
    b = get_engine("numba").propagate(y0, t, p, Tolerance(1e-13, 1e-13))
    assert np.max(np.abs(a - b)) < 1e-9
    for name, value in (("l", 0.5), ("G3", 0.0), ("theta2", 0.0)):
        event = Section(name, value, 0)
        ca = TaylorEngine().crossings(y0, p, event, 4, 100.0, Tolerance(1e-12, 1e-12))
        cb = get_engine("numba").crossings(y0, p, event, 4, 100.0, Tolerance(1e-13, 1e-13))
        np.testing.assert_array_equal(ca.count, cb.count)
        assert np.nanmax(np.abs(ca.t - cb.t), initial=0.0) < 1e-8
        assert np.nanmax(np.abs(ca.y - cb.y), initial=0.0) < 1e-8
