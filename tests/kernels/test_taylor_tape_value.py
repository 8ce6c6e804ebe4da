"""The section tape's value at a state (``taylor_sections.tape_value``, the step's end
value ``f_b`` of every tape section) against the tape interpreter ``tape_jet`` at order 0:
the same floats, bit for bit, for every section kind's function and margin tape on random
states (a zero-sign or NaN included: compared as bits)."""

from __future__ import annotations

import numba
import numpy as np
import pytest

from andoyer.kernels import taylor_generated
from andoyer.kernels.taylor_sections import FASTMATH, section_tape, tape_jet, tape_value

_jit = numba.njit(nogil=True, fastmath=FASTMATH)


@_jit
def _values(tape, C, states, u):  # type: ignore[no-untyped-def]
    """(tape_value, tape_jet at order 0) at each state (n, 6)."""
    out = np.empty((states.shape[0], 2))
    Y = np.empty((1, 6))
    for i in range(states.shape[0]):
        for j in range(6):
            Y[0, j] = states[i, j]
        out[i, 0] = tape_value(tape, C, Y, u)
        tape_jet(tape, C, Y, Y.shape[0] - 1, u)
        out[i, 1] = u[tape.shape[0] - 1, 0]
    return out


def _states(rng: np.random.Generator, n: int) -> np.ndarray:
    """States (G, gamma) of |G| in [0.05, 2], unit gamma, plus exact zeros and a G = 0
    (the angles' square root of 0)."""
    G = rng.normal(size=(n, 3))
    G *= rng.uniform(0.05, 2.0, size=(n, 1)) / np.linalg.norm(G, axis=1, keepdims=True)
    g = rng.normal(size=(n, 3))
    g /= np.linalg.norm(g, axis=1, keepdims=True)
    y = np.concatenate([G, g], axis=1)
    y[0, :3] = 0.0
    y[1, 1] = -0.0
    y[2, 3:] = 0.0
    return y


@pytest.mark.parametrize("margin", [False, True])
def test_tape_value_is_tape_jet_at_order_0_for_every_kind(margin: bool) -> None:
    rng = np.random.default_rng(26)
    states = _states(rng, 200)
    checked = 0
    for kind in range(len(taylor_generated.SECTION_TAPES)):
        for phi0, value in ((0.0, 0.0), (0.7, 1.3), (-2.1, -0.4)):
            tape, C = section_tape(kind, phi0, value, margin=margin)
            u = np.empty((tape.shape[0], 1))
            out = _values(tape, C, states, u)
            assert np.array_equal(out[:, 0].view(np.int64), out[:, 1].view(np.int64)), (
                kind, phi0, value)
            checked += int(np.isfinite(out[:, 0]).sum())
    assert checked > 0.9 * 3 * 200 * len(taylor_generated.SECTION_TAPES)

