"""The Numba DOP853 kernels (:mod:`andoyer.kernels.dop853.flow`).

Checked against what is known exactly:

* the tableau identities and Hairer's numbers (as transcribed by SciPy);
* the free axisymmetric top (A = B, mu = 0), whose motion is a uniform precession:
  ``G`` turns about the body axis 3 at the rate ``omega = (c - a) G3`` and, in space,
  the body turns about the fixed ``G`` at the rate ``a |G|``, so
  ``gamma(t) = Rz(-omega t) Rot(G0/|G|, -a |G| t) gamma0`` (body frame);
* measured orders: 8 for the method (global error, regression slope of log error
  against log step), 7 for the dense output (local error ~ h^8);
* the step-size control of Hairer/SciPy (the same steps as ``solve_ivp(DOP853)``);
* section points: ``|f| <= 1e-12``, the requested direction, ``w > 0``, and angle
  sections that agree with the chart angles and a brute-force count (no spurious
  crossings at the wrap).
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from _numba_cache import fresh_process_cache_stats
from andoyer import RigidBody, from_andoyer, to_andoyer, to_hess
from andoyer.charts.euler_poisson import STATE
from andoyer.kernels import common
from andoyer.kernels.dop853 import coefficients as coef
from andoyer.kernels.dop853 import flow as dop
from andoyer.kernels.generated import equations

KIND = {name: i for i, name in enumerate(equations.SECTION_KINDS)}
TOL = 1e-12
MAX_STEPS = 10**8
X_START = np.array([[0.3, 1.1, 0.2, 1.0, -0.4],  # (l, g, L, G, M), |G| = 1
                    [1.0, 2.0, -0.5, 1.0, 0.3],
                    [2.5, 0.7, 0.6, 1.0, 0.05]])


def kernel_params(body: RigidBody) -> NDArray[np.float64]:
    phi0 = body.phi0 if body.e3 == 0.0 else 0.0
    return np.array([*body.params, phi0])


def _rotate(v: NDArray[np.float64], k: NDArray[np.float64], angle: float) -> NDArray[np.float64]:
    """Rodrigues: ``v`` turned by ``angle`` about the unit vector ``k``."""
    c, s = np.cos(angle), np.sin(angle)
    return v * c + np.cross(k, v) * s + k * np.dot(k, v) * (1.0 - c)


def axisymmetric_exact(body: RigidBody, y0: NDArray[np.float64],
                       t: NDArray[np.float64]) -> NDArray[np.float64]:
    """Exact Euler-Poinsot motion of a body with ``A = B``: shape ``(len(t), 6)``."""
    assert body.A == body.B and body.mu == 0.0
    G0, gamma0 = y0[:3], y0[3:]
    G = np.linalg.norm(G0)
    omega = (body.c - body.a) * G0[2]
    e3 = np.array([0.0, 0.0, 1.0])
    rows = []
    for s in np.atleast_1d(t):
        gamma = _rotate(_rotate(gamma0, G0 / G, -body.a * G * s), e3, -omega * s)
        rows.append(np.concatenate([_rotate(G0, e3, -omega * s), gamma]))
    return np.array(rows)


def slope(h: list[float], err: list[float]) -> float:
    """Regression slope of log(err) against log(h)."""
    return float(np.polyfit(np.log(h), np.log(err), 1)[0])


@pytest.fixture(scope="module")
def free_top() -> RigidBody:
    return RigidBody.euler_poinsot(2.0, 2.0, 1.3)


@pytest.fixture(scope="module")
def y_start() -> NDArray[np.float64]:
    return from_andoyer(X_START)


# ------------------------------------------------------------------------ tableau
def test_tableau_identities() -> None:
    assert coef.B.sum() == pytest.approx(1.0, abs=1e-15)
    # Row sums of A are the nodes (stage i approximates y at t + c_i h).
    np.testing.assert_allclose(coef.A.sum(axis=1), coef.C, atol=1e-14)
    np.testing.assert_array_equal(np.triu(coef.A), 0.0)  # explicit
    np.testing.assert_array_equal(coef.A[coef.N_STAGES, :coef.N_STAGES], coef.B)  # FSAL
    assert coef.C[coef.N_STAGES] == 1.0
    # Error weights annihilate constants: both embedded solutions are consistent.
    assert coef.ER.sum() == pytest.approx(0.0, abs=1e-14)
    assert coef.E3.sum() == pytest.approx(0.0, abs=1e-14)
    assert coef.BHH.sum() == pytest.approx(1.0, abs=1e-15)
    # Order conditions sum b_i c_i^(q-1) = 1/q up to q = 8.
    for q in range(1, 9):
        assert coef.B @ coef.C[:coef.N_STAGES] ** (q - 1) == pytest.approx(1.0 / q, abs=1e-14)


def test_coefficients_are_hairers_as_in_scipy() -> None:
    sc = pytest.importorskip("scipy.integrate._ivp.dop853_coefficients")
    np.testing.assert_array_equal(coef.A, sc.A)
    np.testing.assert_array_equal(coef.B, sc.B)
    np.testing.assert_array_equal(coef.C, sc.C)
    np.testing.assert_array_equal(coef.ER, sc.E5)
    np.testing.assert_allclose(coef.E3, sc.E3, rtol=0, atol=1e-16)
    np.testing.assert_array_equal(coef.D, sc.D)


# ------------------------------------------------------------------------ orders
def test_global_order_8_on_the_exact_precession(free_top: RigidBody,
                                                y_start: NDArray[np.float64]) -> None:
    p, y0, T = kernel_params(free_top), y_start[0], 20.0
    exact = axisymmetric_exact(free_top, y0, np.array([T]))[0]
    h, err = [], []
    for n in (10, 14, 20, 28, 40, 56):
        h.append(T / n)
        err.append(np.abs(dop.integrate_fixed(y0, p, T / n, n)[-1] - exact).max())
    assert err[-1] < 1e-11
    assert slope(h, err) == pytest.approx(8.0, abs=0.15)


def test_global_order_8_on_a_heavy_top(general_body: RigidBody,
                                       y_start: NDArray[np.float64]) -> None:
    p, y0, T = kernel_params(general_body), y_start[0], 20.0
    reference = dop.integrate_fixed(y0, p, T / 2000, 2000)[-1]  # error ~ 1e-8 smaller
    h, err = [], []
    for n in (28, 40, 56, 80, 113, 160):
        h.append(T / n)
        err.append(np.abs(dop.integrate_fixed(y0, p, T / n, n)[-1] - reference).max())
    assert slope(h, err) == pytest.approx(8.0, abs=0.6)


def test_dense_output_order_7(free_top: RigidBody, y_start: NDArray[np.float64]) -> None:
    """Interpolation error inside one step ~ h^8 (an order-7 continuous extension)."""
    p, y0 = kernel_params(free_top), y_start[1]
    x = np.array([0.1, 0.25, 0.5, 0.8, 0.95])
    h_list, err = [], []
    for h in (2.0, 1.4, 1.0, 0.7, 0.5, 0.35):
        y = dop.interpolate_step(y0, p, h, x)
        h_list.append(h)
        err.append(np.abs(y - axisymmetric_exact(free_top, y0, x * h)).max())
    assert slope(h_list, err) == pytest.approx(8.0, abs=0.3)
    # The ends of the interpolant are the step's ends.
    ends = dop.interpolate_step(y0, p, 0.3, np.array([0.0, 1.0]))
    np.testing.assert_array_equal(ends[0], y0)
    np.testing.assert_allclose(ends[1], dop.integrate_fixed(y0, p, 0.3, 1)[-1],
                               rtol=0, atol=1e-15)


def test_dense_output_order_on_a_heavy_top(general_body: RigidBody,
                                           y_start: NDArray[np.float64]) -> None:
    p, y0 = kernel_params(general_body), y_start[0]
    x = np.array([0.25, 0.5, 0.8])
    h_list, err = [], []
    for h in (0.7, 0.5, 0.35, 0.25):
        reference = np.array([dop.integrate_fixed(y0, p, xi * h / 50, 50)[-1] for xi in x])
        h_list.append(h)
        err.append(np.abs(dop.interpolate_step(y0, p, h, x) - reference).max())
    assert slope(h_list, err) == pytest.approx(8.0, abs=0.6)


# ------------------------------------------------------------------------ adaptive
def test_adaptive_matches_exact_precession_between_steps(
        free_top: RigidBody, y_start: NDArray[np.float64]) -> None:
    """Output times fall between steps: the dense output keeps the tolerance's accuracy."""
    p = kernel_params(free_top)
    t = np.concatenate([[0.0], np.sort(np.random.default_rng(0).uniform(0, 200, 500)),
                        [200.0]])
    y, info = dop.propagate(y_start, t, p, TOL, TOL, MAX_STEPS)
    assert np.all(info[:, common.INFO.index("status")] == common.SUCCESS)
    # Output times do not shorten steps: the same steps as without them.
    _, info_ends = dop.propagate(y_start, t[[0, -1]], p, TOL, TOL, MAX_STEPS)
    accepted = common.INFO.index("accepted")
    np.testing.assert_array_equal(info[:, accepted], info_ends[:, accepted])
    for i, y0 in enumerate(y_start):
        exact = axisymmetric_exact(free_top, y0, t)
        np.testing.assert_array_equal(y[i, 0], y0)
        assert np.abs(y[i] - exact).max() < 1e-10


def test_step_control_is_hairers(general_body: RigidBody,
                                 y_start: NDArray[np.float64]) -> None:
    """Same accepted steps and field evaluations as SciPy's DOP853 (same controller)."""
    p = kernel_params(general_body)

    def fun(t: float, y: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.array(equations.ep_field(*y.tolist(), *general_body.params))

    for tol in (1e-6, 1e-12):
        _, info = dop.propagate(y_start[:1], np.array([0.0, 100.0]), p, tol, tol, MAX_STEPS)
        sol = solve_ivp(fun, (0.0, 100.0), y_start[0], method="DOP853", rtol=tol, atol=tol)
        accepted = info[0, common.INFO.index("accepted")]
        nfev = info[0, common.INFO.index("nfev")]
        assert abs(accepted - (sol.t.size - 1)) <= 0.01 * accepted
        assert abs(nfev - sol.nfev) <= 0.01 * nfev


def test_failure_is_reported_not_hidden(general_body: RigidBody,
                                        y_start: NDArray[np.float64]) -> None:
    p = kernel_params(general_body)
    y0 = y_start[:2].copy()
    y0[1, 0] = np.nan
    y, info = dop.propagate(y0, np.array([0.0, 1.0, 2.0]), p, TOL, TOL, MAX_STEPS)
    status = info[:, common.INFO.index("status")]
    assert status[0] == common.SUCCESS and status[1] == common.STEP_TOO_SMALL
    assert np.all(np.isfinite(y[0])) and np.all(np.isnan(y[1, 1:]))
    _, info = dop.propagate(y0[:1], np.array([0.0, 100.0]), p, TOL, TOL, 10)
    assert info[0, common.INFO.index("status")] == common.MAX_STEPS


# ------------------------------------------------------------------------ sections
def _section_fw(body: RigidBody, kind: int, value: float,
                y: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    phi0 = kernel_params(body)[-1]
    f, w = equations.section(kind, *np.moveaxis(y, -1, 0), phi0, value, np.cos(value),
                              np.sin(value))
    return np.asarray(f) + 0.0 * y[..., 0], np.asarray(w) + 0.0 * y[..., 0]


def _dfdt(body: RigidBody, kind: int, value: float, y: NDArray[np.float64]
          ) -> NDArray[np.float64]:
    """df/dt = grad f . F(y), by a central difference along the field."""
    F = np.stack(equations.ep_field(*np.moveaxis(y, -1, 0), *body.params), axis=-1)
    d = 1e-6
    return (_section_fw(body, kind, value, y + d * F)[0]
            - _section_fw(body, kind, value, y - d * F)[0]) / (2 * d)


SECTION_CASES = [  # (body fixture, coordinate, value, direction)
    ("general_body", "G3", 0.0, 1),
    ("general_body", "G1", 0.2, -1),
    ("general_body", "gamma3", 0.1, 0),
    ("general_body", "J1", 0.5, 1),
    ("general_body", "l", 1.0, 0),
    ("general_body", "g", 0.0, 1),
    ("paper_body", "g", 2.5, 1),
    ("paper_body", "theta1", 1.5, 0),
    ("paper_body", "theta2", 0.0, 1),
    ("paper_body", "theta2", 4.0, 0),
]


@pytest.mark.parametrize(("body_name", "coord", "value", "direction"), SECTION_CASES)
def test_crossings_lie_on_the_section_with_the_right_direction(
        request: pytest.FixtureRequest, y_start: NDArray[np.float64], body_name: str,
        coord: str, value: float, direction: int) -> None:
    body = request.getfixturevalue(body_name)
    kind, n = KIND[coord], 12
    tc, yc, count, info = dop.locate_crossings(y_start, kernel_params(body), kind, value,
                                               direction, n, 1e4, TOL, TOL, MAX_STEPS)
    assert np.all(info[:, common.INFO.index("status")] == common.SUCCESS)
    assert count.max() == n  # some orbits may never reach the section
    for i, c in enumerate(count):
        assert np.all(np.diff(tc[i, :c]) > 0) and np.all(tc[i, :c] > 0)
    found = ~np.isnan(tc)
    assert found.sum() == count.sum()
    yc = yc[found]
    f, w = _section_fw(body, kind, value, yc)
    assert np.abs(f).max() <= 1e-12
    assert np.all(w > 0)
    slope_f = _dfdt(body, kind, value, yc)
    if direction:
        assert np.all(np.sign(slope_f) == direction)
    else:
        assert np.all(slope_f != 0)


def test_fewer_crossings_are_nan_padded(general_body: RigidBody,
                                        y_start: NDArray[np.float64]) -> None:
    tc, yc, count, _ = dop.locate_crossings(y_start, kernel_params(general_body),
                                            KIND["G3"], 0.0, 1, 50, 60.0, TOL, TOL,
                                            MAX_STEPS)
    assert np.all(count < 50)
    for i, c in enumerate(count):
        assert np.all(tc[i, :c] <= 60.0) and np.all(np.isnan(tc[i, c:]))
        assert np.all(np.isnan(yc[i, c:])) and np.all(np.isfinite(yc[i, :c]))


def test_a_pair_of_roots_inside_one_step_is_found(general_body: RigidBody,
                                                 y_start: NDArray[np.float64]) -> None:
    """G3 = (its local maximum - 1e-7): the orbit crosses up and down about 1e-3 apart,
    well inside one step (~0.3), with no sign change of f over that step."""
    p, kind = kernel_params(general_body), KIND["G3"]
    t = np.linspace(0.0, 30.0, 3001)
    y, _ = dop.propagate(y_start[:1], t, p, TOL, TOL, MAX_STEPS)
    G3 = y[0, :, STATE.index("G3")]
    k = 1 + int(np.argmax((G3[1:-1] > G3[:-2]) & (G3[1:-1] >= G3[2:])))  # first maximum
    t_fine = np.linspace(t[k - 1], t[k + 1], 20001)
    y_fine, _ = dop.propagate(y_start[:1], np.concatenate([[0.0], t_fine]), p, TOL, TOL,
                              MAX_STEPS)
    peak = y_fine[0, 1:, STATE.index("G3")].max()
    value = peak - 1e-7
    # Start 3 time units before the maximum: several steps, then the pair.
    t_start = t[k - 300]
    start, window = y[:, k - 300], 6.0
    tc, yc, count, _ = dop.locate_crossings(start, p, kind, value, 0, 2, window, TOL, TOL,
                                            MAX_STEPS)
    assert count[0] == 2
    assert abs(tc[0, 1] - tc[0, 0]) < 1e-2
    assert t[k - 1] - t_start < tc[0, 0] < tc[0, 1] < t[k + 1] - t_start
    assert np.abs(yc[0, :, STATE.index("G3")] - value).max() <= 1e-12
    signs = np.sign(_dfdt(general_body, kind, value, yc[0]))
    np.testing.assert_array_equal(signs, [1.0, -1.0])
    # Only the first root with direction +1, only the second with -1.
    for direction, j in ((1, 0), (-1, 1)):
        tc1, _, count1, _ = dop.locate_crossings(start, p, kind, value, direction, 2,
                                                 window, TOL, TOL, MAX_STEPS)
        assert count1[0] == 1 and tc1[0, 0] == tc[0, j]


def _angle(body: RigidBody, coord: str, y: NDArray[np.float64]) -> NDArray[np.float64]:
    if coord == "g":
        return to_andoyer(y)[..., 1]
    if coord == "theta1":  # sections take theta1 mod 2 pi
        return np.mod(to_hess(body, y)[..., 0], 2 * np.pi)
    return to_hess(body, y)[..., 1]  # theta2


@pytest.mark.parametrize(("body_name", "coord", "value", "direction"), [
    ("general_body", "g", 0.0, 1),
    ("general_body", "g", 5.0, 0),
    ("paper_body", "g", 0.0, 0),
    ("paper_body", "theta2", 0.0, 1),
    ("paper_body", "theta2", 3.0, 0),
    ("paper_body", "theta1", 1.5, -1),
])
def test_angle_sections_have_no_spurious_crossings_at_the_wrap(
        request: pytest.FixtureRequest, y_start: NDArray[np.float64], body_name: str,
        coord: str, value: float, direction: int) -> None:
    """Each crossing's chart angle is ``value (mod 2 pi)``, and the crossings are
    exactly the passages of the unwrapped angle through ``value + 2 pi k`` seen on a
    fine grid (so neither the wrap at 2 pi nor the antipode ``value + pi`` counts)."""
    body = request.getfixturevalue(body_name)
    p, t_max = kernel_params(body), 300.0
    tc, yc, count, _ = dop.locate_crossings(y_start, p, KIND[coord], value, direction,
                                            1000, t_max, TOL, TOL, MAX_STEPS)
    t = np.linspace(0.0, t_max, 30001)
    y, _ = dop.propagate(y_start, t, p, TOL, TOL, MAX_STEPS)
    assert count.sum() > 0
    for i in range(y_start.shape[0]):
        c = count[i]
        miss = np.mod(_angle(body, coord, yc[i, :c]) - value + np.pi, 2 * np.pi) - np.pi
        assert np.all(np.abs(miss) < 1e-10)
        level = (np.unwrap(_angle(body, coord, y[i])) - value) / (2 * np.pi)
        jumps = np.diff(np.floor(level))
        expected = {1: np.sum(jumps > 0), -1: np.sum(jumps < 0),
                    0: np.sum(jumps != 0)}[direction]
        assert c == expected


# ------------------------------------------------------------------------ cache
def test_entry_points_are_keyed_on_the_generated_kernels() -> None:
    for fn in (dop.propagate_block, dop.locate_crossings_block, dop.integrate_fixed,
               dop.interpolate_step):
        assert fn.py_func.__closure__ is not None
        cells = [c.cell_contents for c in fn.py_func.__closure__]
        assert dop.KERNEL_STAMP in cells


def test_a_second_process_loads_the_compiled_kernels(
        general_body: RigidBody, y_start: NDArray[np.float64]) -> None:
    """After this process compiled (or loaded) them, a new process pays no compile."""
    p = kernel_params(general_body)
    dop.propagate(y_start[:1], np.array([0.0, 1.0]), p, TOL, TOL, MAX_STEPS)
    dop.locate_crossings(y_start[:1], p, KIND["G3"], 0.0, 1, 1, 50.0, TOL, TOL, MAX_STEPS)
    y0, pp = y_start[:1].tolist(), p.tolist()
    out = fresh_process_cache_stats("andoyer.kernels.dop853.flow", {
        "propagate_block": f"m.propagate(np.array({y0}), np.array([0.0, 1.0]), np.array({pp}), "
                     f"1e-12, 1e-12, {MAX_STEPS})",
        "locate_crossings_block": f"m.locate_crossings(np.array({y0}), np.array({pp}), "
                            f"{KIND['G3']}, 0.0, 1, 1, 50.0, 1e-12, 1e-12, {MAX_STEPS})"})
    assert out["misses"] == [0, 0] and out["hits"] == [1, 1]
    assert out["seconds"] < 5.0


def test_state_order_is_the_charts() -> None:
    # The kernels unpack y in this order (see dop853._field); fail loudly if it moves.
    assert STATE == ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")
    assert equations.SECTION_KINDS[:6] == STATE
