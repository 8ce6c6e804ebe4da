"""A section tape's value and jet. ``sections.tape_value`` (the step's end value
``f_b`` of every tape section) against the tape interpreter ``tape_jet`` at order 0: the
same floats, bit for bit, for every section kind's function and margin tape on random
states (a zero's sign or NaN included: compared as bits). ``tape_jet`` (its products four
orders at a time) against an extended-precision reading of the tape: round-off. Along
the jets of a solution of (1), the tapes' first integral (the area ``M``, its value
alone) gives the jet of the section function written with ``M``'s own products: every
angle, both directions' values, to round-off. ``solve_root`` stops where Newton's step no
longer moves: a step's root to 2 ulps."""

from __future__ import annotations

import math

import numpy as np
import pytest

from andoyer.kernels.common import fast_jit
from andoyer.kernels.generated import recurrences
from andoyer.kernels.taylor.sections import (
    pair_jet,
    section_jet,
    section_tape,
    solve_root,
    tape_jet,
    tape_value,
)


@fast_jit
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
    for kind in range(len(recurrences.SECTION_TAPES)):
        for phi0, value in ((0.0, 0.0), (0.7, 1.3), (-2.1, -0.4)):
            tape, C = section_tape(kind, phi0, value, margin=margin)
            u = np.empty((tape.shape[0], 1))
            out = _values(tape, C, states, u)
            assert np.array_equal(out[:, 0].view(np.int64), out[:, 1].view(np.int64)), (
                kind, phi0, value)
            checked += int(np.isfinite(out[:, 0]).sum())
    assert checked > 0.9 * 3 * 200 * len(recurrences.SECTION_TAPES)



def _sqrt_series(u: np.ndarray, n: int, a: int, order: int) -> None:
    """Row ``n`` of ``u`` as the square root of row ``a`` (the tape's sqrt node), order
    by order from ``(u_n)^2 = u_a``, term by term."""
    u[n, 0] = np.sqrt(u[a, 0])
    for k in range(1, order + 1):
        s = sum(u[n, j] * u[n, k - j] for j in range(1, k))
        u[n, k] = (u[a, k] - s) / (2 * u[n, 0])


def _reference_jet(tape: np.ndarray, C: np.ndarray, x: np.ndarray, order: int
                   ) -> np.ndarray:
    """The tape's jet in extended precision (np.longdouble), each Cauchy sum term by term
    in order: an independent reading of the tape's rows (op, a, b, ca, cb, cc)."""
    LD = np.longdouble
    u = np.zeros((tape.shape[0], order + 1), dtype=LD)
    c = C.astype(LD)
    for n, (op, a, b, ca, cb, cc) in enumerate(tape.tolist()):
        if op == 0:
            u[n] = x[:, a].astype(LD)
        elif op == 1:
            u[n] = c[ca] * u[a] + (c[cb] * u[b] if b >= 0 else 0)
            u[n, 0] += c[cc] if cc >= 0 else 0
        elif op == 2:
            u[n] = [sum(u[a, j] * u[b, k - j] for j in range(k + 1)) for k in range(order + 1)]
        elif op == 4:  # a first integral: its value, zero above (DOT)
            u[n, 0] = sum(x[0, a + i].astype(LD) * x[0, b + i].astype(LD) for i in range(3))
        elif op == 5:  # the product with a first integral (SCALE)
            u[n] = u[a, 0] * u[b]
        else:
            _sqrt_series(u, n, a, order)
    return u[-1]


@pytest.mark.parametrize("order", [15, 6, 2])
def test_tape_jet_is_the_tapes_jet_to_round_off_for_every_kind(order: int) -> None:
    """``tape_jet`` (four orders at a time in each product, ``sections.cauchy``)
    against the extended-precision reading of the tape: every coefficient within
    ``1e-13`` of the jet's scale ``max_k |f^[k]| r^k`` (r = 1/2: the state jets below are
    of radius about 1). Measured: at most 4e-16 of it (every kind, order 15)."""
    rng = np.random.default_rng(2026)
    worst = 0.0
    for kind in range(len(recurrences.SECTION_TAPES)):
        for trial in range(6):
            G = rng.normal(size=3)
            G *= rng.uniform(0.5, 2.0) / np.linalg.norm(G)
            g = rng.normal(size=3)
            g /= np.linalg.norm(g)
            x = rng.normal(size=(order + 1, 6)) * 0.5 ** np.arange(order + 1)[:, None]
            x[0] = np.concatenate([G, g])
            tape, C = section_tape(kind, rng.uniform(-3, 3), rng.uniform(-1, 1))
            ref = _reference_jet(tape, C, x, order)
            got = section_jet(tape, C, x, order)
            scale = float(np.max(np.abs(ref) * 0.5 ** np.arange(order + 1)))
            err = np.abs(got - ref.astype(float)) * 0.5 ** np.arange(order + 1)
            worst = max(worst, float(err.max()) / scale)
            assert err.max() <= 1e-13 * scale, (kind, trial, err.max(), scale)
    assert worst > 0.0  # the comparison sees round-off: it is not vacuous


def _full_products_jet(tape: np.ndarray, C: np.ndarray, x: np.ndarray, order: int
                       ) -> np.ndarray:
    """The tape's jet in extended precision with its first integral (``DOT``) as the
    Cauchy products of the state's jets and ``SCALE`` as a product: the section
    function's jet as if ``M`` were not an integral."""
    LD = np.longdouble
    y = x.astype(LD)
    prod = [[sum(y[j, a] * y[k - j, b] for j in range(k + 1)) for k in range(order + 1)]
            for a in range(6) for b in range(6)]
    t = tape.copy()
    u = np.zeros((tape.shape[0], order + 1), dtype=LD)
    c = C.astype(LD)
    for n, (op, a, b, ca, cb, cc) in enumerate(t.tolist()):
        if op == 0:
            u[n] = y[:, a]
        elif op == 1:
            u[n] = c[ca] * u[a] + (c[cb] * u[b] if b >= 0 else 0)
            u[n, 0] += c[cc] if cc >= 0 else 0
        elif op in (2, 5):
            u[n] = [sum(u[a, j] * u[b, k - j] for j in range(k + 1)) for k in range(order + 1)]
        elif op == 4:
            u[n] = [sum(prod[6 * (a + i) + b + i][k] for i in range(3))
                    for k in range(order + 1)]
        else:
            _sqrt_series(u, n, a, order)
    return u[-1]


@pytest.mark.parametrize("name", ["theta2", "g", "l", "theta1", "psi"])
def test_the_area_integral_leaves_the_jets_of_a_solution_unchanged(name: str) -> None:
    """``M = G . gamma`` by its value alone (``DOT``, ``SCALE``): along the jets of (1)
    (``flow.jet``, order 15, random bodies and states), each coefficient within 1e-13 of
    the jet's scale of the one with ``M``'s products (measured: 3e-16 at most)."""
    from andoyer import RigidBody
    from andoyer.kernels.generated import equations
    from andoyer.kernels.taylor import flow

    kind = (equations.SECTION_KINDS + equations.EXTRA_SECTION_KINDS).index(name)
    rng = np.random.default_rng(36)
    order = 15
    for trial in range(4):
        A, B, C3 = rng.uniform(1.0, 3.0, 3)
        body = RigidBody(A, B, C3, mu=rng.uniform(0.1, 1.0), r=tuple(rng.normal(size=3)))
        p = np.asarray(body.engine_params, dtype=float)
        G = rng.normal(size=3)
        g = rng.normal(size=3)
        x = flow.jet(np.concatenate([G, g / np.linalg.norm(g)]), p, order)[0]
        r = 0.5 / max(1.0, float(np.max(np.abs(x[order]) ** (1.0 / order))))
        for value in (0.3, -2.0):
            for margin in (False, True):
                tape, C = section_tape(kind, float(p[7]), value, margin=margin)
                ref = _full_products_jet(tape, C, x, order)
                got = section_jet(tape, C, x, order)
                w = r ** np.arange(order + 1)
                scale = float(np.max(np.abs(ref) * w))
                err = np.abs(got - ref.astype(float)) * w
                assert err.max() <= 1e-13 * scale, (name, trial, value, margin, err.max(),
                                                    scale)


@pytest.mark.parametrize("value, vanishing", [
    (0.0, "sin"), (np.pi, "sin"), (-np.pi, "sin"), (2 * np.pi, "sin"),
    (np.pi / 2, "cos"), (3 * np.pi / 2, "cos"), (-np.pi / 2, "cos")])
def test_the_g_sections_on_the_axes_take_the_tape_without_the_square_root(value, vanishing
                                                                          ) -> None:
    """At g = 0, pi (the float nearest it) the tape is f / |G| (two products), at
    +-pi/2 it is f without its cos(value) term: on random states the same signs as
    the full tape of f and its value (times |G| where sin vanishes) within round-off; a
    value 4 ulps off takes the full tape."""
    from andoyer.kernels.generated.equations import SECTION_KINDS
    from andoyer.kernels.taylor.sections import SQRT

    kind = SECTION_KINDS.index("g")
    reduced, Cr = section_tape(kind, 0.3, value)
    full = np.array(recurrences.SECTION_TAPES[kind], dtype=np.int64)
    Cf = np.array(recurrences.section_constants(kind, 0.3, value, np.cos(value),
                                                np.sin(value)))
    assert reduced.shape[0] < full.shape[0] and SQRT not in reduced[:, 0]
    assert SQRT in full[:, 0]
    other, _ = section_tape(kind, 0.3, value + 4 * math.ulp(value) if value else 1e-300)
    assert np.array_equal(other, full)
    states = _states(np.random.default_rng(3), 300)[3:]
    u = np.empty((recurrences.TAPE_NODES, 1))
    fr = _values(reduced, Cr, states, u)[:, 0]
    ff = _values(full, Cf, states, u)[:, 0]
    G = np.linalg.norm(states[:, :3], axis=1)
    factor = G if vanishing == "sin" else 1.0
    assert np.allclose(ff, factor * fr, rtol=1e-13, atol=1e-15 * G.max() ** 3)
    assert np.array_equal(np.sign(ff), np.sign(fr))


@fast_jit
def _both_jets(tape, C, x, order, pair):  # type: ignore[no-untyped-def]
    """(tape_jet's rows, pair_jet's rows) of one state jet."""
    u1 = np.zeros((tape.shape[0], order + 1))
    u2 = np.zeros((tape.shape[0], order + 1))
    tape_jet(tape, C, x, order, u1)
    pair_jet(tape, C, x, order, u2, pair[0], pair[1], pair[2], pair[3])
    return u1, u2


@pytest.mark.parametrize("order", [14, 15, 5, 2])
def test_pair_jet_is_the_tapes_jet_for_the_g_axes_and_no_other_tape(order: int) -> None:
    """The reduced g = 0, pi tapes are of ``product_pair``'s form (``G2 gamma1``,
    ``G1 gamma2``); ``pair_jet`` gives their rows 2, 5, 6, 7 within round-off of the
    interpreter (1e-15 of the jet's scale: LLVM's reassociation may sum a product's
    terms in another order). Every other section tape, function or margin, is not of
    that form."""
    from andoyer.kernels.generated.equations import EXTRA_SECTION_KINDS, SECTION_KINDS
    from andoyer.kernels.taylor.sections import product_pair

    test = getattr(product_pair, "py_func", product_pair)
    kind = SECTION_KINDS.index("g")
    rng = np.random.default_rng(11)
    r = 0.5 ** np.arange(order + 1)
    for value in (0.0, np.pi, -np.pi):
        tape, C = section_tape(kind, rng.uniform(-3, 3), value)
        pair = test(tape)
        assert tuple(int(v) for v in pair) == (1, 3, 0, 4)
        x = rng.normal(size=(order + 1, 6)) * r[:, None]
        u1, u2 = _both_jets(tape, C, x, order, np.array(pair, dtype=np.int64))
        for row in (2, 5, 6, 7):
            scale = float(np.max(np.abs(u1[row]) * r))
            assert np.max(np.abs(u1[row] - u2[row]) * r) <= 1e-15 * scale, (value, row)
    for k in range(len(recurrences.SECTION_TAPES)):
        for value in (0.0, 0.4, np.pi / 2):
            for margin in (False, True):
                tape, C = section_tape(k, 0.3, value, margin=margin)
                name = (SECTION_KINDS + EXTRA_SECTION_KINDS)[k]
                axes = name == "g" and value == 0.0 and not margin
                assert (test(tape)[0] >= 0) == axes, (name, value, margin)


@fast_jit
def _roots(A, flo):  # type: ignore[no-untyped-def]
    """solve_root of each row of ``A`` on [0, 1] (compiled as in the kernels: fused
    multiply-adds, so P at its float root is rarely exactly 0)."""
    out = np.empty(A.shape[0])
    for i in range(A.shape[0]):
        out[i] = solve_root(A[i], A.shape[1] - 1, 0.0, 1.0, flo[i])
    return out


def test_solve_root_stops_where_newton_has_converged():
    # Steps' polynomials of order 14 with one root r in (0, 1), well conditioned
    # (|P'| ~ sum |a_k|): the root to 2 ulps of the exact one (mpmath, 40 digits). A
    # converged Newton step that no longer moved s used to be taken for a step out of
    # the bracket: the whole bracket was bisected again, 20-50 more evaluations of P,
    # ending up to 4 eps (7-8 ulps) off.
    import mpmath

    rng = np.random.default_rng(7)
    n, order = 300, 14
    r = rng.uniform(0.02, 0.98, n)
    A = np.zeros((n, order + 1))
    A[:, 2:] = rng.normal(size=(n, order - 1)) * 0.3 ** np.arange(2, order + 1)
    A[:, 1] = rng.choice([-1.0, 1.0], n) * rng.uniform(0.5, 2.0, n)
    A[:, 0] = -np.array([np.polyval(a[::-1], x) for a, x in zip(A, r, strict=True)])
    flo = A[:, 0]
    got = _roots(A, flo)
    far = 0
    with mpmath.workdps(40):   # not mpmath.mp.dps: that would last into later tests
        for a, s in zip(A, got, strict=True):
            coeffs = [mpmath.mpf(float(c)) for c in a[::-1]]
            exact = mpmath.findroot(lambda x, c=coeffs: mpmath.polyval(c, x), mpmath.mpf(s))
            far += abs(float(exact) - s) > 2 * math.ulp(float(exact))
    assert far == 0, far
