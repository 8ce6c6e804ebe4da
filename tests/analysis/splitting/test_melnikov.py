"""The Melnikov function of the heteroclinic lines (issue 5, part 3).

Routes: the closed form by residues; the trapezoidal rule and scipy's quad on the
Euler-Poisson integrand ``grad E . X_{H1}`` along the closed-form orbit of
``andoyer.analysis.unperturbed.separatrix``; the Hess-chart form of ``H0``, ``H1`` and of the
integrand checked against the package's derived Hamiltonian (a private copy here, not in
src). The comparison with the measured splitting is in ``test_manifolds.py``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.splitting.manifolds import euler_poinsot_excess
from andoyer.analysis.splitting.melnikov import (
    melnikov_closed_form,
    melnikov_function,
    melnikov_integrand,
    melnikov_quadrature,
    melnikov_rho,
    predicted_splitting,
)
from andoyer.analysis.unperturbed.separatrix import heteroclinic
from andoyer.charts.hess import from_hess
from andoyer.dynamics import hamiltonian

BODIES = [RigidBody.paper(), RigidBody.hess(2.5, 1.0, 1.6),
          RigidBody.hess(2.5, 2.0, 2.2, branch=-1)]
PHASES = np.linspace(0.0, 2 * math.pi, 9)


def _H0_H1_hess(body, x):
    """The brief's Hess-chart forms at M = 0 (a private check, not used in src)."""
    theta1, theta2, J1, J2 = x[..., 0], x[..., 1], x[..., 2], x[..., 3]
    kappa, phi0 = body.a - body.b, body.phi0
    H0 = (body.c * J2**2 / 2
          + kappa * J1 * (J1 - J2) * (np.cos(theta1 - 2 * phi0) - np.cos(2 * phi0)))
    H1 = (J1 * np.sin(theta1 + theta2) + (J2 - J1) * np.sin(theta2)) / J2
    return H0, H1


@pytest.mark.parametrize("body", BODIES, ids=["paper", "rho~1", "phi0<0"])
def test_hess_chart_forms_of_H0_H1_and_E(body):
    rng = np.random.default_rng(5)
    n = 500
    J2 = rng.uniform(0.5, 2.0, n)
    x = np.stack([rng.uniform(0, 4 * np.pi, n), rng.uniform(0, 2 * np.pi, n),
                  J2 * rng.uniform(0.01, 0.99, n), J2, np.zeros(n)], axis=-1)
    H0, H1 = _H0_H1_hess(body, x)
    mu = 0.37
    H = hamiltonian(body.with_mu(mu), x, "hess")
    assert np.max(np.abs(H - (H0 + mu * H1))) < 1e-13
    E = euler_poinsot_excess(body, from_hess(body, x))
    assert np.max(np.abs(E - (H0 - body.c * J2**2 / 2))) < 1e-13


@pytest.mark.parametrize("body", BODIES, ids=["paper", "rho~1", "phi0<0"])
@pytest.mark.parametrize("branch", ["theta1=4phi0", "theta1=0"])
@pytest.mark.parametrize("sheet", [1, -1])
def test_closed_form_equals_quadrature(body, branch, sheet):
    exact = melnikov_closed_form(body, PHASES, J2=1.3, branch=branch, sheet=sheet)
    quad = melnikov_quadrature(body, PHASES, J2=1.3, branch=branch, sheet=sheet)
    assert np.max(np.abs(quad - exact)) < 1e-14
    if branch == "theta1=0":           # the Hess solutions: nothing to split
        assert np.max(np.abs(exact)) < 1e-15
    else:
        amp = melnikov_function(body, J2=1.3, branch=branch, sheet=sheet, n=4,
                                quadrature=False).attrs["amplitude"]
        assert np.max(np.abs(exact)) == pytest.approx(amp, rel=0.1)
        assert amp > 1e-6


@pytest.mark.slow
def test_scipy_quad_route():
    """Adaptive Gauss-Kronrod (scipy quad, ~1000 scalar evaluations of the orbit)."""
    body = RigidBody.hess(2.5, 1.0, 1.6)
    q = melnikov_quadrature(body, [0.4], method="quad", branch="theta1=4phi0")
    assert np.max(np.abs(q - melnikov_closed_form(body, [0.4], branch="theta1=4phi0"))) < 1e-12


def test_integrand_is_the_hess_chart_bracket():
    """grad E . X_{H1} along the orbit = -(dJ1/dt / J2) [sin(theta1 + theta2) - sin theta2]."""
    body = RigidBody.hess(2.5, 1.0, 1.6)
    J2 = 1.1
    t = np.linspace(-20, 20, 81)
    ds = heteroclinic(body, J2, t, "theta1=4phi0", theta2_0=0.7)
    f = melnikov_integrand(body, ds.y.values)
    lam = ds.attrs["lambda_rate"]
    J1dot = lam * ds.J1.values * ds.J2_minus_J1.values / J2      # logistic, J1 increasing
    th1, th2 = ds.theta1.values, ds.theta2.values
    chart = -(J1dot / J2) * (np.sin(th1 + th2) - np.sin(th2))
    assert np.max(np.abs(f - chart)) < 1e-14
    assert np.max(np.abs(f)) > 0.05


def test_rho_and_the_exponentially_small_factor():
    body = RigidBody.paper()
    sigma = math.sqrt((body.b - body.c) * (body.c - body.a))
    rho = melnikov_rho(body, 1.7)
    assert rho == pytest.approx(body.c / (2 * sigma), rel=1e-14)
    ds = melnikov_function(body, n=16, branch="theta1=4phi0")
    factor = math.pi * rho / math.sinh(math.pi * rho)
    assert ds.attrs["pi_rho_over_sinh"] == pytest.approx(factor, rel=1e-13)
    assert 1e-5 < factor < 3e-5
    # Delta G = 2 pi mu cos g / ((b - a) J2 sinh(pi rho)) on theta1 = 4 phi0 (phi0 > 0).
    g = np.linspace(0, 2 * math.pi, 7)
    dE, dG = predicted_splitting(body, g, 0.01, G=1.0, branch="theta1=4phi0")
    closed = 2 * math.pi * 0.01 * np.cos(g) / ((body.b - body.a) * math.sinh(math.pi * rho))
    assert np.max(np.abs(dG - closed)) < 1e-20
    assert np.allclose(dE, -body.c * dG, rtol=1e-14, atol=0)
    assert np.max(np.abs(ds.M_quadrature - ds.M)) < 1e-15
    for v in ("M", "M_quadrature", "g", "Delta_G_per_mu"):
        assert ds[v].attrs["long_name"]


def test_invalid_inputs():
    body = RigidBody.paper()
    with pytest.raises(ValueError, match="branch"):
        melnikov_closed_form(body, 0.0, branch="theta1=pi")
    with pytest.raises(ValueError, match="Hess body"):
        melnikov_closed_form(RigidBody(2.5, 2.0, 2.2, 0.01, (1, 0, 0)), 0.0)
    with pytest.raises(ValueError, match="method"):
        melnikov_quadrature(body, 0.0, method="simpson")


@pytest.mark.parametrize("branch", ["theta1=0", "theta1=4phi0"])
@pytest.mark.parametrize("eps", [0.0, 1e-3, 0.1, -0.3])
def test_off_hess_melnikov_closed_form_against_quadrature(branch, eps):
    from andoyer.analysis.splitting.melnikov import melnikov_off_hess

    th = np.linspace(0.0, 6.0, 7)
    for body in (RigidBody.hess(2.5, 1.0, 1.6), RigidBody.paper()):
        closed = melnikov_off_hess(body, eps, th, branch=branch)
        quad = melnikov_off_hess(body, eps, th, branch=branch, method="trapezoid")
        np.testing.assert_allclose(closed, quad, rtol=0, atol=1e-14)


def test_off_hess_amplitude_on_the_hess_branch_is_explicit_in_epsilon():
    from andoyer.analysis.splitting.melnikov import melnikov_off_hess, melnikov_rho

    body = RigidBody.hess(2.5, 1.0, 1.6)
    x = np.pi * melnikov_rho(body)
    th = np.linspace(0.0, 2 * np.pi, 65)
    for eps in (0.0, 1e-4, 0.05):
        amp = np.abs(melnikov_off_hess(body, eps, th, branch="theta1=0")).max()
        assert abs(amp - 2 * x / np.sinh(x) * abs(np.sin(eps))) < 1e-15
    # at epsilon = 0 it is the Hess body's function
    np.testing.assert_allclose(melnikov_off_hess(body, 0.0, th, branch="theta1=4phi0"),
                               melnikov_closed_form(body, th, branch="theta1=4phi0"),
                               rtol=0, atol=1e-15)
