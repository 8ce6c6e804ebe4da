"""Orbits with tangent vectors on the numba engine (:mod:`andoyer.integrate.tangent`).

* closed form: at the steady rotation about the middle axis 3 of a free body (mu = 0)
  the flow is periodic with the period ``P = 2 pi / (c G0)`` of gamma, and the
  monodromy matrix has the multipliers ``exp(+-sigma G0 P)`` (Euler's equations
  linearised there) and 1 four times (the Casimirs, H and the flow direction);
  ``ln |w|`` gains ``sigma G0 P`` per period once the unstable direction dominates;
* the numba variational engine against heyoka's (the same variables, scaled alike) on
  a torus and on a chaotic orbit, within the chaotic orbit's predictability horizon;
* input validation.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from andoyer import RigidBody, from_andoyer, from_hess
from andoyer.integrate import variational as V
from andoyer.integrate.tangent import fundamental_matrix, propagate_tangent, tangent_crossings
from andoyer.kernels.generated.equations import SECTION_KINDS

FREE = RigidBody.euler_poinsot(2.5, 2.0, 2.2)  # the paper's moments, mu = 0
G0 = 1.0
#: Steady rotation about the middle axis 3, gamma off the axis (a periodic orbit).
MIDDLE = np.array([0.0, 0.0, G0, math.sin(1.0), 0.0, math.cos(1.0)])
CHAOTIC_BODY = RigidBody.hess(3.0, 1.0, 2.0, mu=1.0)
#: Hess-chart state in the chaotic layer of CHAOTIC_BODY (as in tests/analysis/test_chaos).
CHAOTIC = [0.2617993877991494, 0.0, 1.0103629710818451, 1.712575169922734, 0.0]


def test_monodromy_of_the_middle_axis_rotation_has_the_closed_form_multipliers() -> None:
    P = 2 * math.pi / (FREE.c * G0)
    Phi = fundamental_matrix(MIDDLE, [0.0, P], FREE.engine_params)[0, -1]
    mult = np.sort(np.abs(np.linalg.eigvals(Phi)))
    rate = FREE.sigma * G0
    # measured: exponent to 7e-15 relative, the unit multipliers to 1e-15
    assert math.log(mult[-1]) / P == pytest.approx(rate, rel=1e-10)
    assert math.log(mult[0]) / P == pytest.approx(-rate, rel=1e-10)
    np.testing.assert_allclose(mult[1:-1], 1.0, atol=1e-9)


def test_log_norm_grows_at_sigma_g_per_period_at_the_middle_axis() -> None:
    P = 2 * math.pi / (FREE.c * G0)
    t = P * np.arange(31)
    res = propagate_tangent(MIDDLE, [1.0, 0.5, -0.3, 0.2, 0.1, -0.4], t, FREE.engine_params)
    gain = np.diff(res.rho[0, :, 0]) / P
    # the stable component dies like exp(-2 sigma G0 P n): gone after 30 periods
    assert gain[-1] == pytest.approx(FREE.sigma * G0, rel=1e-3)
    assert abs(res.y[0, -1, 2] - G0) < 1e-6  # still at the rotation


@pytest.mark.parametrize("case", ["torus", "chaotic"])
def test_numba_and_heyoka_variational_engines_agree(case: str) -> None:
    pytest.importorskip("heyoka", reason="the comparison needs heyoka")
    if case == "torus":
        body, y0, T = RigidBody.paper(), from_andoyer([0.3, 0.0, 0.3, 1.0, 0.0]), 1000.0
    else:  # within the predictability horizon (Lyapunov time ~17: 200 / 17 e-foldings)
        body, y0, T = CHAOTIC_BODY, from_hess(CHAOTIC_BODY, CHAOTIC), 200.0
    y0 = np.atleast_2d(y0)
    w0 = np.array([[1.0, 0.3, -0.2, 0.1, 0.4, -0.5]])
    w0 /= np.linalg.norm(w0)
    t = np.linspace(0.0, T, 51)
    ref = V.propagate_variational(y0, w0, t, body.engine_params, engine="heyoka")
    got = V.propagate_variational(y0, w0, t, body.engine_params, engine="numba")
    assert got.ok.all() and got.x.shape == ref.x.shape
    # every variable, relative to its largest value: measured 1.5e-10 (torus, the MEGNO
    # mean; the state 1.6e-13), 1.9e-9 (chaotic: round-off grown by exp(lambda t) ~ 1e5)
    scale = np.maximum(np.abs(ref.x).max(axis=1, keepdims=True), 1e-3)
    assert (np.abs(got.x - ref.x) / scale).max() < (1e-9 if case == "torus" else 1e-8)


def test_crossings_carry_the_jacobian_of_the_flow() -> None:
    body = RigidBody.paper()
    y0 = from_andoyer([0.3, 0.0, 0.3, 1.0, 0.0]).reshape(6)
    kind = SECTION_KINDS.index("G3")
    c = tangent_crossings(y0, np.eye(6), body.engine_params, kind, 0.0, 1, 2, 500.0)
    assert c.ok[0] and c.count[0] == 2
    Phi = fundamental_matrix(y0, [0.0, *c.t[0]], body.engine_params)[0, 1:]
    np.testing.assert_allclose(np.swapaxes(c.w[0], -1, -2), Phi, rtol=0, atol=1e-8)


def test_inputs_are_checked() -> None:
    p = FREE.engine_params
    with pytest.raises(ValueError, match="y0 must have shape"):
        propagate_tangent(np.zeros(5), np.eye(6)[:1], [0.0, 1.0], p)
    with pytest.raises(ValueError, match="w0 must have shape"):
        propagate_tangent(np.zeros((2, 6)), np.zeros((3, 1, 6)), [0.0, 1.0], p)
    with pytest.raises(ValueError, match="between 1 and 6"):
        propagate_tangent(MIDDLE, np.ones((7, 6)), [0.0, 1.0], p)
    with pytest.raises(ValueError, match="zero vector"):
        propagate_tangent(MIDDLE, np.zeros(6), [0.0, 1.0], p)
    with pytest.raises(ValueError, match="finite"):
        propagate_tangent(MIDDLE, [np.nan, 0, 0, 0, 0, 1.0], [0.0, 1.0], p)
    with pytest.raises(ValueError, match="increasing"):
        propagate_tangent(MIDDLE, np.eye(6)[:1], [1.0, 0.0], p)
    with pytest.raises(ValueError, match="tol"):
        propagate_tangent(MIDDLE, np.eye(6)[:1], [0.0, 1.0], p, tol=0.1)
    with pytest.raises(ValueError, match="params"):
        propagate_tangent(MIDDLE, np.eye(6)[:1], [0.0, 1.0], p[:7])


def test_a_failed_orbit_is_reported_not_raised() -> None:
    # |G| = 1e6 turns ~1e6 rad in t = 1: far beyond 1000 steps, where MIDDLE needs a few.
    # (States beyond integrate.budget.MAX_MOMENTUM are refused before any work.)
    y = np.array([MIDDLE, [1e6, 1e6, 1e6, 0.0, 0.0, 1.0]])
    res = propagate_tangent(y, np.eye(6)[:1], [0.0, 1.0], RigidBody.paper().engine_params,
                            max_steps=1000)
    assert res.ok.tolist() == [True, False]
    assert np.isnan(res.u[1]).all()
