"""Counts and sizes: one check (``andoyer.validation.integer``) everywhere, so that a
bool, a fraction, a string or NaN is refused with a message naming the argument, and a
whole number written as a float (``1e3``) is accepted."""

import math

import numpy as np
import pytest

from andoyer import RigidBody, from_hess, to_andoyer
from andoyer.analysis.chaos.frequency import naff
from andoyer.analysis.chaos.lyapunov import IndicatorRun, chaos_map, indicators
from andoyer.analysis.paper.check import paper_check
from andoyer.analysis.splitting.melnikov import melnikov_function, melnikov_rho
from andoyer.analysis.unperturbed.portraits import portrait_andoyer
from andoyer.analysis.unperturbed.separatrix import separatrix_on_level
from andoyer.integrate import fill_section, poincare, propagate, propagate_hess_manifold
from andoyer.integrate.engines.heyoka_engine import HeyokaEngine
from andoyer.integrate.engines.numba_engine import NumbaEngine
from andoyer.integrate.tangent import propagate_tangent
from andoyer.validation import integer

B = RigidBody.paper()
Y0 = [0.0, 0.0, 1.0, 0.0, 0.6, 0.8]


@pytest.mark.parametrize("value, expected", [
    (3, 3), (np.int64(4), 4), (5.0, 5), (np.float64(6.0), 6), (1e3, 1000), (0, 0)])
def test_integer_accepts_whole_numbers(value, expected):
    k = integer("n", value)
    assert k == expected and type(k) is int


@pytest.mark.parametrize("value", [True, False, "3", 2.5, math.nan, math.inf, None, [3],
                                   np.array([3])])
def test_integer_refuses_what_is_not_a_whole_number(value):
    with pytest.raises(ValueError, match=r"^n_things must be an integer, got "):
        integer("n_things", value)


@pytest.mark.parametrize("value, maximum, message", [
    (0, None, r"an integer >= 1, got 0"), (11, 10, r"an integer in \[1, 10\], got 11"),
    (-1, 10, r"an integer in \[1, 10\], got -1")])
def test_integer_range_is_in_the_message(value, maximum, message):
    with pytest.raises(ValueError, match=message):
        integer("n", value, 1, maximum)


# (argument named in the message, call)
CALLS = [
    ("n_crossings", lambda v: poincare(B, Y0, "G3=0", v, engine="numba")),
    (r"n_orbits \(number of plane points\)",
     lambda v: fill_section(B, h=0.2466, M=0.0, section=("theta2", 0.0), n_orbits=v)),
    ("n_freq", lambda v: naff(np.exp(1j * np.arange(256.0)), 1.0, v)),
    ("window", lambda v: naff(np.exp(1j * np.arange(256.0)), 1.0, 1, window=v)),
    ("n", lambda v: melnikov_function(B, n=v, quadrature=False)),
    ("n_levels", lambda v: portrait_andoyer(B, n=16, n_levels=v)),
    ("max_steps", lambda v: NumbaEngine(max_steps=v)),
    ("max_steps", lambda v: propagate_tangent(Y0, np.eye(6)[:1], [0.0, 1.0], B.engine_params,
                                              max_steps=v)),
    ("batch_size", lambda v: HeyokaEngine(batch_size=v)),
    ("n_threads", lambda v: HeyokaEngine(n_threads=v)),
    ("seed", lambda v: paper_check(n=4, seed=v)),
]


@pytest.mark.parametrize("name, call", CALLS, ids=[f"{i}-{n}" for i, (n, _) in enumerate(CALLS)])
@pytest.mark.parametrize("value", [True, 2.5, "4", math.nan])
def test_public_counts_refuse_non_integers_naming_the_argument(name, call, value):
    with pytest.raises(ValueError, match=rf"^{name} must be an integer"):
        call(value)


def test_a_whole_float_is_a_count():
    ds = poincare(B, Y0, "G3=0", 2.0, engine="numba")
    assert ds.sizes["crossing"] == 2


# (argument named in the message, call): real numbers refuse a bool and a non-number
REALS = [
    ("mu", lambda v: RigidBody(2.5, 2.0, 2.2, v, (1.0, 0.0, 0.0))),
    ("t_max", lambda v: poincare(B, Y0, "G3=0", 2, t_max=v, engine="numba")),
    ("t_end", lambda v: chaos_map(B, 0.2466, 0.0, "theta2=0", 3, IndicatorRun(t_end=v))),
    ("J2", lambda v: melnikov_rho(B, J2=v)),
    ("J2", lambda v: melnikov_function(B, n=4, J2=v, quadrature=False)),
    ("h", lambda v: separatrix_on_level(B, v, "andoyer")),
    ("rtol", lambda v: propagate(B, Y0, [0.0, 1.0], rtol=v)),
]


@pytest.mark.parametrize("name, call", REALS, ids=[f"{i}-{n}" for i, (n, _) in enumerate(REALS)])
@pytest.mark.parametrize("value", [True, "abc", [0.1]])
def test_public_reals_refuse_non_numbers_naming_the_argument(name, call, value):
    with pytest.raises(ValueError, match=rf"^{name} must be a (real|finite) number"):
        call(value)


def test_numpy_scalars_are_tolerances():
    ds = propagate(B, Y0, [0.0, 1.0], rtol=np.float32(1e-10), atol=np.float32(1e-10),
                   engine="numba")
    assert ds.attrs["rtol"] == pytest.approx(1e-10)


# Arrays: ragged rows, text, complex and boolean values are refused naming the argument
# (NumPy's own messages, or a silently dropped imaginary part, before).
ARRAYS = [
    ("y0", lambda v: propagate(B, v, [0.0, 1.0], engine="numba")),
    ("t", lambda v: propagate(B, Y0, v, engine="numba")),
    ("y0", lambda v: propagate(B, v, [0.0, 1.0], chart="andoyer", engine="numba")),
    ("x", lambda v: from_hess(B, v)),
    ("y", lambda v: to_andoyer(v)),
    ("r", lambda v: RigidBody(2.5, 2.0, 2.2, 0.01, v)),
    (r"w0 \(initial tangent direction\)", lambda v: indicators(B, Y0, 5.0, w0=v)),
    ("theta2_0", lambda v: melnikov_function(B, theta2_0=v, quadrature=False)),
    ("x0", lambda v: propagate_hess_manifold(B, v, [0.0, 1.0])),
]


@pytest.mark.parametrize("name, call", ARRAYS, ids=[f"{i}-{n}" for i, (n, _) in enumerate(ARRAYS)])
@pytest.mark.parametrize("value, message", [
    ([[0.0, 0.0, 1.0, 0.0, 0.6, 0.8], [0.0, 1.0]], "must be a rectangular array"),
    (np.array([0.0, 0.0, 1.0, 0.0, 0.6, 0.8]) + 0j, "must be real, got complex values"),
    (["a", "b"], "must hold real numbers, got"),
    ([True, False], "must hold real numbers, got booleans")])
def test_arrays_refuse_what_is_not_real_naming_the_argument(name, call, value, message):
    with pytest.raises(ValueError, match=rf"^{name} {message}"):
        call(value)


def test_engines_refuse_states_beyond_the_integrators_by_name():
    """The engine seam (every engine's entry) refuses |G| > MAX_MOMENTUM with a
    ValueError naming y0, not an engine failure (analysis code builds states itself)."""
    from andoyer.integrate.engines import resolve_engine
    from andoyer.integrate.engines.base import Tolerance
    from andoyer.validation import MAX_MOMENTUM

    eng = resolve_engine("numba")
    with pytest.raises(ValueError, match=r"y0: \|G\| = 1e\+120 is beyond"):
        eng.propagate([1e120, 0, 0, 0, 0, 1], [0.0, 1.0], [2.5, 2.0, 2.2, 0.01, 1, 0, 0],
                      Tolerance.single(1e-12))
    assert MAX_MOMENTUM == 1e100
