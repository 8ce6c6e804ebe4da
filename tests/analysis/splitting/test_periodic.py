"""Hyperbolic periodic orbits near the rotations about the middle axis (issue 5, part 1).

Independent routes: the exact pendulum rotations of a body with ``e3 = 0`` on ``M = 0``
(``G1 = G2 = gamma3 = 0`` invariant, period by quadrature); the exact multipliers of a
Hess body, ``exp(+-2 pi sigma / c)`` for every mu (from the growth law
``d(G, r)/dt = -sigma G3 (G, r)`` and ``int G3 dt = 2 pi / c`` over a period); the
other integration engines (scipy DOP853, Numba DOP853) for general orbits; central
finite differences for the Jacobian of the section map.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.splitting.periodic import (
    RotationSection,
    continue_rotation_orbit,
    gamma_phase,
    middle_axis_rate,
    pendulum_rotation,
    return_map,
    rotation_energy,
    rotation_orbit,
    section_coords,
    section_state,
)
from andoyer.charts.euler_poisson import area_integral, energy
from andoyer.integrate import engines
from andoyer.integrate.api import propagate

STATE = ["G1", "G2", "G3", "gamma1", "gamma2", "gamma3"]
#: No symmetry, centre of mass off the principal planes, z still the middle axis.
GENERAL = RigidBody(2.5, 2.0, 2.2, 0.05, (0.3, 0.5, 0.8), "general")


def _final_state(ds) -> np.ndarray:
    last = ds.isel(orbit=0, time=-1)
    return np.array([float(last[v]) for v in STATE])


@pytest.mark.parametrize("sign", [1, -1])
def test_newton_converges_to_the_exact_pendulum_rotation(paper_body, sign):
    """From an off-orbit guess Newton lands on G1 = G2 = gamma3 = 0, period by quadrature."""
    h = rotation_energy(paper_body)
    sec = RotationSection(0.7, sign)
    orb = rotation_orbit(paper_body, h, 0.0, sec, guess=[2e-3, -3e-3])
    y_exact, T_exact = pendulum_rotation(paper_body, h, sec)
    assert 2 <= orb.iterations <= 6          # quadratic convergence from 4e-3
    assert np.max(np.abs(orb.x)) < 1e-13
    assert np.max(np.abs(orb.y - y_exact)) < 1e-13
    assert abs(orb.period - T_exact) < 1e-11 * T_exact
    assert orb.residual < 1e-13


@pytest.mark.parametrize("mu", [0.0, 0.01, 0.1])
def test_hess_multipliers_are_exp_two_pi_sigma_over_c(mu):
    """On a Hess body the multipliers do not depend on mu: exp(+-2 pi sigma/c)."""
    for body in (RigidBody.paper(mu), RigidBody.hess(2.5, 1.0, 1.6, mu)):
        h = rotation_energy(body)
        expected = math.exp(2 * math.pi * middle_axis_rate(body) / body.c)
        for sign in (1, -1):
            orb = rotation_orbit(body, h, 0.0, RotationSection(0.3, sign))
            assert orb.multipliers[0] == pytest.approx(expected, rel=1e-11)
            assert orb.multipliers[1] == pytest.approx(1 / expected, rel=1e-11)
            if mu == 0.0:   # Euler-Poinsot: the Lyapunov exponent is sigma |G|
                assert orb.lyapunov_exponent == pytest.approx(middle_axis_rate(body),
                                                              rel=1e-12)
    # The eigenvector pairs: at p- the stable direction is the Hess plane e1 x1 + e2 x2 = 0.
    body = RigidBody.paper(0.1)
    orb = rotation_orbit(body, rotation_energy(body), 0.0, RotationSection(0.3, -1))
    v_s = orb.eigenvectors[:, 1]
    assert abs(body.e1 * v_s[0] + body.e2 * v_s[1]) < 1e-12


def test_monodromy_has_four_unit_multipliers():
    """The 6 x 6 state-transition matrix over the period: {Lambda, 1/Lambda, 1, 1, 1, 1}."""
    h = rotation_energy(GENERAL)
    orb = rotation_orbit(GENERAL, h, -0.3, RotationSection(0.4, 1))
    w = np.sort(np.abs(np.linalg.eigvals(orb.monodromy)))
    assert w[0] == pytest.approx(orb.multipliers[1], rel=1e-8)
    assert w[-1] == pytest.approx(orb.multipliers[0], rel=1e-8)
    assert np.max(np.abs(w[1:5] - 1.0)) < 1e-6
    assert orb.multipliers.prod() == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize("engine", ["default", "numba"])
def test_section_jacobian_matches_finite_differences(engine, monkeypatch):
    """DP from the variational equations + event sensitivity vs central differences (on
    the default engine, and on numba as where heyoka is missing)."""
    if engine == "numba":

        monkeypatch.setattr(engines, "default_engine_name", lambda *capabilities, **_: "numba")
    h = rotation_energy(GENERAL)
    sec = RotationSection(0.4, -1)
    x0 = np.array([0.01, 0.15])
    DP = return_map(GENERAL, x0, h, 0.2, sec).DP
    eps = 1e-6
    fd = np.zeros((2, 2))
    for j in range(2):
        dx = np.zeros(2)
        dx[j] = eps
        fd[:, j] = (return_map(GENERAL, x0 + dx, h, 0.2, sec, jacobian=False).x
                    - return_map(GENERAL, x0 - dx, h, 0.2, sec, jacobian=False).x) / (2 * eps)
    assert np.max(np.abs(DP - fd)) < 1e-8


@pytest.mark.parametrize("engine", ["scipy", "numba"])
def test_general_orbit_is_periodic_for_another_engine(engine):
    """Newton in general (e3 != 0, M != 0): the orbit closes when integrated by DOP853."""
    h = rotation_energy(GENERAL)
    orb = rotation_orbit(GENERAL, h, -0.3, RotationSection(0.4, 1))
    assert np.max(np.abs(orb.x)) > 0.05                 # not the trivial rotation
    ds = propagate(GENERAL, orb.y, [0.0, orb.period], engine=engine, rtol=1e-13, atol=1e-13)
    assert np.max(np.abs(_final_state(ds) - orb.y)) < 1e-10


def test_continuation_from_the_permanent_rotation():
    body = RigidBody.paper(0.05)
    h = rotation_energy(body)
    orbits, ds = continue_rotation_orbit(body, h, 0.2, RotationSection(0.0, 1), steps=3)
    assert list(ds.mu.values) == pytest.approx([0.0, body.mu / 3, 2 * body.mu / 3, body.mu])
    assert float(abs(ds.x1[0])) < 1e-14 and float(abs(ds.x2[0])) < 1e-14   # mu = 0: (0, 0)
    assert np.all(ds.newton_iterations.values <= 6)
    # M != 0 moves the orbit off G1 = G2 = 0 as mu grows, continuously.
    r = np.hypot(ds.x1.values, ds.x2.values)
    assert np.all(np.diff(r) > 0)
    assert np.all(ds.residual.values < 1e-12)
    for v in ("x1", "period", "Lambda_u", "v_unstable"):
        assert ds[v].attrs["long_name"] and "units" in ds[v].attrs
    assert ds.attrs["area"] == 0.2 and ds.attrs["rotation_sign"] == 1
    with pytest.raises(ValueError, match="start at 0"):
        continue_rotation_orbit(body, h, mu=[0.01, 0.02])


def test_the_engine_argument_reaches_the_flow_and_the_provenance():
    """engine='numba' (no heyoka needed) finds the same orbit; the dataset says which."""
    from andoyer.analysis.splitting.section_map import FLOW_ENGINES, flow_engine

    body = RigidBody.paper(0.05)
    h = rotation_energy(body)
    orbits, ds = continue_rotation_orbit(body, h, 0.2, RotationSection(0.0, 1), steps=1,
                                         engine="numba")
    assert orbits[-1].engine == "numba" and ds.attrs["engine"] == FLOW_ENGINES["numba"]
    ref = rotation_orbit(body, h, 0.2, RotationSection(0.0, 1), guess=orbits[-1].x)
    assert ref.engine == flow_engine().name
    np.testing.assert_allclose(orbits[-1].x, ref.x, rtol=0, atol=1e-11)
    assert orbits[-1].period == pytest.approx(ref.period, rel=1e-11)
    with pytest.raises(ValueError, match="engine must be 'heyoka' or 'numba'"):
        rotation_orbit(body, h, engine="scipy")


def test_section_state_lies_on_the_level_and_the_section():
    body = GENERAL
    h, M = rotation_energy(body), -0.3
    sec = RotationSection(2.0, -1)
    x = np.array([0.1, -0.2])
    y, dy = section_state(body, x, h, M, sec, jacobian=True)
    assert float(energy(body, y)) == pytest.approx(h, abs=1e-15)
    assert float(area_integral(y)) == pytest.approx(M, abs=1e-15)
    assert np.linalg.norm(y[3:]) == pytest.approx(1.0, abs=1e-15)
    assert float(gamma_phase(y)) == pytest.approx(2.0, abs=1e-15)
    assert np.allclose(section_coords(y), x, rtol=0, atol=1e-16)
    assert y[2] < 0
    eps = 1e-7
    fd = np.stack([(section_state(body, x + d, h, M, sec) - section_state(body, x - d, h, M, sec))
                   / (2 * eps) for d in (np.array([eps, 0]), np.array([0, eps]))], axis=1)
    assert np.max(np.abs(dy - fd)) < 1e-7


def test_invalid_inputs():
    with pytest.raises(ValueError, match="sign"):
        RotationSection(0.0, 0)
    with pytest.raises(ValueError, match="middle moment"):
        rotation_orbit(RigidBody(2.0, 2.2, 2.5, 0.01), 0.2)
    with pytest.raises(ValueError, match="unit disc"):
        section_state(GENERAL, [0.8, 0.7], 0.2)
    with pytest.raises(ValueError, match="librates"):
        pendulum_rotation(RigidBody.paper(0.5), 0.3)
    with pytest.raises(ValueError, match="level"):
        section_state(RigidBody.paper(0.5), [0.0, 0.0], 0.1, 0.0, RotationSection(1.0, 1))
