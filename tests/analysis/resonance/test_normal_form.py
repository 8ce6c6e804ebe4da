"""Birkhoff normal forms at periodic orbits (P1)-(P5): the twist's prediction against NAFF
rotation numbers of orbits about the fixed point, the error falling like the amplitude to
the power 2K + 2 (K twist coefficients, degree N = 2K + 1); at mu = 0 the rotation and the
first twist against the free top's closed form and its Birkhoff form at fixed G (B4)."""

import math

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.resonance.birkhoff import birkhoff_normal_form
from andoyer.analysis.resonance.normal_form import (
    orbit_rotation_numbers,
    periodic_orbit_normal_form,
)

#: The rotation about y of Hess(3, 1, 2) on h = 1, moved by mu: l* ~ 0, L* ~ -1.5 mu.
BODY = RigidBody.hess(3.0, 1.0, 2.0, mu=1e-2)
AMPS = np.geomspace(0.02, 0.16, 5)


def _slope(degree, amps=AMPS, body=BODY):
    nf = periodic_orbit_normal_form(body, 1.0, 0.0, (0.0, 0.0), degree=degree, engine="numba")
    r = orbit_rotation_numbers(body, 1.0, 0.0, nf, amps, n_returns=2048, engine="numba")
    err = np.abs(r.rotation_error.values)
    return nf, r, float(np.polyfit(np.log(amps), np.log(err), 1)[0])


@pytest.mark.parametrize("degree", [3, pytest.param(5, marks=pytest.mark.slow)])
def test_rotation_error_falls_like_the_degree_predicts(degree):
    # measured: slope 4.17 (N = 3), 6.00 (N = 5), 8.05 (N = 7; slow test); |P(x) - x| of the
    # fixed point 9e-18, the radial defect (area) 1e-16
    nf, r, slope = _slope(degree)
    assert abs(slope - (degree + 1)) < 0.5, slope
    assert float(nf.fixed_point_step) < 1e-12
    assert np.max(np.abs(nf.radial_defect.values)) < 1e-12
    assert abs(float(nf.determinant) - 1.0) < 1e-12
    # without the twist the error is O(a^2): the normal form carries the amplitude law
    lin = np.abs(r.rotation_naff.values - float(nf.rotation))
    assert float(np.polyfit(np.log(AMPS), np.log(lin), 1)[0]) < 2.5
    assert np.all(np.abs(r.rotation_error.values) < 0.05 * lin)


@pytest.mark.slow
def test_rotation_error_degree_seven():
    _nf, r, slope = _slope(7)
    assert abs(slope - 8.0) < 0.5, slope


def test_free_top_rotation_and_first_twist():
    # mu = 0: the centre l = 0, L = 0 at |G| = sqrt(2 h / b); W = omega_l / omega_g =
    # sqrt((b - a)(b - c)) / b and, from H_NF = H*(G) + c1 I + c2 I^2 (B4) on the level,
    # dW/dI = (2 c2 - c1(1)^2 / kappa) / (kappa G), kappa = b, with W = c1(1) / kappa signed
    # as omega_l (c1 < 0 here); the map turns the (l, L) plane the other way round from the
    # normal coordinate w: rho = 1 - |W|, tau_1 = -sign(c1) dW/dI (|W| falls towards the
    # separatrix: tau_1 > 0).
    body = BODY.with_mu(0.0)
    nf = periodic_orbit_normal_form(body, 1.0, 0.0, (0.0, 0.0), degree=3, engine="numba")
    a, b, c = body.a, body.b, body.c
    G = math.sqrt(2.0 / b)
    W = math.sqrt((b - a) * (b - c)) / b
    assert abs(float(nf.rotation) - (1.0 - W)) < 1e-13
    bnf = birkhoff_normal_form(body, G, order=4, lstar=0.0)
    c1, c2 = (float(v) for v in bnf.coefficient.values[:2])
    dW = (2 * c2 - (c1 / G) ** 2 / b) / (b * G)
    expected = -math.copysign(1.0, c1) * dW
    assert expected > 0.0
    assert abs(float(nf.twist[1]) - expected) < 1e-9 * expected, (float(nf.twist[1]), expected)


def test_inputs_are_checked_naming_the_argument():
    with pytest.raises(ValueError, match="seed"):
        periodic_orbit_normal_form(BODY, 1.0, 0.0, (0.0, 0.0, 1.0))
    with pytest.raises(ValueError, match="degree"):
        periodic_orbit_normal_form(BODY, 1.0, 0.0, (0.0, 0.0), degree=2)
    with pytest.raises(ValueError, match="n_steps"):
        periodic_orbit_normal_form(BODY, 1.0, 0.0, (0.0, 0.0), n_steps=9)
    with pytest.raises(ValueError, match="seed"):
        periodic_orbit_normal_form(BODY, 1.0, 0.0, (0.0, 5.0))          # off the level
    with pytest.raises(ValueError, match="normal_form"):
        orbit_rotation_numbers(BODY, 1.0, 0.0, None, [0.1])


@pytest.mark.slow
def test_chain_stable_orbit_of_period_three():
    # the 3:1 chain about x of Hess(3, 1, 2) at mu = 1e-2: its stable orbit is a fixed point
    # of P^3 (residue 0.565, omega0 0.27080, tau_1 -12.43); degree 5 on amplitudes 15-60 %
    # of the half-width: slope 6.41 (measured; 4.09 at N = 3, 7.92 at N = 7)
    from andoyer.analysis.resonance import resonance_widths

    w = resonance_widths(BODY, 1.0, 0.0, "g=0", max_order=5)
    r = w.where((w.label == "3:1") & (w.axis == 1) & (w.sign == 1), drop=True).isel(resonance=0)
    hw = float(r.half_width)
    nf = periodic_orbit_normal_form(BODY, 1.0, 0.0, (float(r.stable_x[0]), float(r.stable_y[0])),
                                    period=3, degree=5, engine="numba", G=float(r.G_action))
    assert float(nf.residue) == pytest.approx(0.5652, abs=1e-3)
    amps = np.geomspace(0.15 * hw, 0.6 * hw, 5)
    rot = orbit_rotation_numbers(BODY, 1.0, 0.0, nf, amps, n_returns=4096, engine="numba")
    slope = np.polyfit(np.log(amps), np.log(np.abs(rot.rotation_error.values)), 1)[0]
    assert abs(slope - 6.0) < 0.6, slope
