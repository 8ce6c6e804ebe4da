"""Heteroclinic orbits and separatrices of the unperturbed system
(andoyer.analysis.unperturbed.separatrix).

Routes: the closed forms against integration of the regular Euler-Poisson equations
(heyoka, rtol 1e-13) and of the Hess-chart equations (scipy DOP853); the separatrix
curves against the generated Hamiltonian kernel.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.unperturbed.portraits import portrait_andoyer, portrait_hess
from andoyer.analysis.unperturbed.separatrix import (
    heteroclinic,
    heteroclinic_rate,
    separatrix_andoyer,
    separatrix_energy,
    separatrix_hess,
)
from andoyer.dynamics import hamiltonian, vector_field
from andoyer.integrate import integrate_canonical, propagate

BRANCHES = ("theta1=0", "theta1=4phi0")


def _sigma(body: RigidBody) -> float:
    return math.sqrt((body.b - body.c) * (body.c - body.a))


def _angle_diff(u: np.ndarray, v: np.ndarray, period: float) -> np.ndarray:
    d = np.mod(u - v + period / 2, period) - period / 2
    return np.abs(d)


def test_unperturbed_hess_hamiltonian_form(paper_body: RigidBody) -> None:
    """H0 = c J2^2/2 + kappa J1 (J1 - J2)[cos(theta1 - 2 phi0) - cos 2 phi0] (mu = 0, M = 0)."""
    rng = np.random.default_rng(3)
    body = paper_body.with_mu(0.0)
    J2 = rng.uniform(0.3, 2.0, 200)
    x = np.column_stack([rng.uniform(0, 4 * np.pi, 200), rng.uniform(0, 2 * np.pi, 200),
                         rng.uniform(0, 1, 200) * J2, J2, np.zeros(200)])
    th1, _, J1, J2, _ = x.T
    phi0, kappa = body.phi0, body.a - body.b
    H0 = body.c * J2**2 / 2 + kappa * J1 * (J1 - J2) * (np.cos(th1 - 2 * phi0)
                                                       - np.cos(2 * phi0))
    assert np.max(np.abs(hamiltonian(body, x, "hess") - H0)) < 1e-14


@pytest.mark.parametrize("body", [RigidBody.paper(), RigidBody.hess(3.0, 1.0, 2.0, 0.2),
                                  RigidBody.hess(2.5, 2.0, 2.2, 0.3, branch=-1)])
def test_rate_is_the_logistic_constant(body: RigidBody) -> None:
    """lambda = 2 sigma J2 and dJ1/dt = +-lambda J1 (J2 - J1)/J2 on the lines (the field)."""
    J2 = 1.7
    lam = heteroclinic_rate(body, J2)
    assert lam == pytest.approx(2 * _sigma(body) * J2, rel=1e-15)
    for branch in BRANCHES:
        ds = heteroclinic(body, J2, [0.3], branch=branch)
        x = [float(ds.theta1[0]), 0.4, float(ds.J1[0]), J2, 0.0]
        rate = vector_field(body.with_mu(0.0), x, "hess")[2]
        s = 1.0 if ds.attrs["J1_direction"] == "increasing" else -1.0
        J1 = float(ds.J1[0])
        assert rate == pytest.approx(s * lam * J1 * (J2 - J1) / J2, rel=1e-12)


def test_direction_on_each_branch(paper_body: RigidBody, hess_minus_body: RigidBody) -> None:
    assert heteroclinic(paper_body, 1.0, [0.0]).attrs["J1_direction"] == "decreasing"
    assert heteroclinic(paper_body, 1.0, [0.0], branch="theta1=4phi0"
                        ).attrs["J1_direction"] == "increasing"
    assert heteroclinic(hess_minus_body, 1.0, [0.0]).attrs["J1_direction"] == "increasing"


@pytest.mark.parametrize("branch", BRANCHES)
@pytest.mark.parametrize("sign", [+1, -1])
def test_heteroclinic_matches_euler_poisson_integration(paper_body: RigidBody, branch: str,
                                                        sign: int) -> None:
    """Closed form vs heyoka (rtol 1e-13) from the EP state at t0 (forward) and from
    t0 - 60 (through t0): states, J1, theta2 agree to 1e-10."""
    J2, t0 = 1.3, 5.0
    body0 = paper_body.with_mu(0.0)
    for start in (t0, t0 - 60.0):
        t = np.linspace(start, start + 60.0, 61)
        ds = heteroclinic(paper_body, J2, t, branch=branch, t0=t0, sign=sign)
        orbit = propagate(body0, ds.y.values[0], t, rtol=1e-13, atol=1e-13)
        y = np.stack([orbit[v].values[0] for v in ds.component.values], axis=-1)
        assert np.max(np.abs(y - ds.y.values)) < 1e-10
        assert np.max(np.abs(orbit.J1.values[0] - ds.J1.values)) < 1e-10
        assert np.max(_angle_diff(orbit.theta2.values[0], ds.theta2.values, 2 * np.pi)) < 1e-10
        assert np.max(_angle_diff(orbit.theta1.values[0], ds.theta1.values, 4 * np.pi)) < 1e-10


def test_heteroclinic_matches_canonical_integration(paper_body: RigidBody) -> None:
    """Second route: the Hess-chart equations by scipy's DOP853 (away from J1 = 0, J2)."""
    J2 = 0.8
    t = np.linspace(-25.0, 25.0, 51)
    for branch in BRANCHES:
        ds = heteroclinic(paper_body, J2, t, branch=branch, theta2_0=0.7)
        x0 = [float(ds.theta1[0]), float(ds.theta2[0]), float(ds.J1[0]), J2, 0.0]
        c = integrate_canonical(paper_body.with_mu(0.0), x0, t, chart="hess", rtol=1e-13,
                                atol=1e-13)
        assert np.max(np.abs(c.J1.values - ds.J1.values)) < 1e-10
        assert np.max(np.abs(c.theta2.values - ds.theta2.values)) < 1e-10
        assert np.max(np.abs(c.theta1.values - ds.theta1.values)) < 1e-10


def test_heteroclinic_dataset_contents(paper_body: RigidBody) -> None:
    t = np.array([-1e5, -3.0, 0.0, 2.0, 1e5])
    ds = heteroclinic(paper_body, 2.0, t, t0=0.0)
    assert np.all(np.isfinite(ds.y.values))
    assert np.allclose(ds.J1 + ds.J2_minus_J1, 2.0, rtol=0, atol=1e-15)
    assert float(ds.J1[2]) == 1.0 and float(ds.J1[0]) == 2.0 and float(ds.J1[-1]) == 0.0
    assert np.allclose(ds.L_action, 2 * ds.J1 - ds.J2, atol=1e-15)
    assert np.all(ds.J3 == 0.0)
    G = np.linalg.norm(ds.y.values[:, :3], axis=1)
    assert np.allclose(G, 2.0, rtol=1e-15)
    assert np.allclose(np.linalg.norm(ds.y.values[:, 3:], axis=1), 1.0, rtol=1e-15)
    assert np.allclose(np.einsum("ij,ij->i", ds.y.values[:, :3], ds.y.values[:, 3:]), 0.0,
                       atol=1e-15)
    # Hess invariant relation (3) on the theta1 = 0 branch: e1 G1 + e2 G2 = 0.
    rel = paper_body.e1 * ds.y.values[:, 0] + paper_body.e2 * ds.y.values[:, 1]
    assert np.max(np.abs(rel)) < 1e-15
    assert ds.attrs["body_mu"] == 0.0 and ds.attrs["body_mu_given"] == paper_body.mu
    for v in ("theta1", "theta2", "J1", "y"):
        assert {"long_name", "units", "symbol", "equation"} <= set(ds[v].attrs)


def test_heteroclinic_validation(paper_body: RigidBody, general_body: RigidBody) -> None:
    with pytest.raises(ValueError, match="Hess body"):
        heteroclinic(general_body, 1.0, [0.0])
    with pytest.raises(ValueError, match="branch"):
        heteroclinic(paper_body, 1.0, [0.0], branch="theta1=pi")
    with pytest.raises(ValueError, match="sign"):
        heteroclinic(paper_body, 1.0, [0.0], sign=0)
    with pytest.raises(ValueError, match="J2"):
        heteroclinic(paper_body, -1.0, [0.0])
    with pytest.raises(ValueError, match="middle moment"):
        heteroclinic_rate(RigidBody(1.0, 2.0, 3.0), 1.0)


# ---------------------------------------------------------------------- separatrices
def _H0_andoyer(body: RigidBody, l: np.ndarray, L: np.ndarray, G0: float) -> np.ndarray:
    x = np.stack(np.broadcast_arrays(l, 0.0, L, G0, 0.0), axis=-1)
    return hamiltonian(body.with_mu(0.0), x, "andoyer")


@pytest.mark.parametrize("body", [RigidBody.paper(),
                                  RigidBody(2.0, 2.2, 2.5, r=(0.6, 0.8, 0.0)),   # y middle
                                  RigidBody(2.2, 2.0, 2.5, r=(0.6, 0.8, 0.0))])  # x middle
def test_separatrix_is_the_saddle_level_set(body: RigidBody) -> None:
    """H0 along every sampled curve equals I_mid G0^2/2 (kernel), in both charts."""
    G0 = 1.4
    h = separatrix_energy(body, G0)
    ds = separatrix_andoyer(body, G0, n=101)
    H = _H0_andoyer(body, ds.separatrix_l_angle.values, ds.separatrix_L_action.values, G0)
    assert np.max(np.abs(H - h)) < 1e-14
    dh = separatrix_hess(body, G0, n=101)
    x = np.stack(np.broadcast_arrays(dh.separatrix_theta1.values, 0.0,
                                     dh.separatrix_J1.values, G0, 0.0), axis=-1)
    assert np.max(np.abs(hamiltonian(body.with_mu(0.0), x, "hess") - h)) < 1e-14


def test_paper_separatrices_closed_form(paper_body: RigidBody) -> None:
    """Lines l = +-phi0 (mod pi) and L = +-G0; the Hess ones are l = -phi0 (mod pi)."""
    phi0 = paper_body.phi0
    ds = separatrix_andoyer(paper_body, 1.0, n=21)
    sep = ds.separatrix_kind.values == "separatrix"
    ls = np.sort(ds.separatrix_l_angle.values[sep, 0])
    assert np.allclose(ls, [phi0, np.pi - phi0, np.pi + phi0, 2 * np.pi - phi0], atol=1e-14)
    assert np.all(np.ptp(ds.separatrix_l_angle.values[sep], axis=1) == 0.0)
    hess_l = ds.separatrix_l_angle.values[ds.separatrix_hess.values, 0]
    assert np.allclose(np.sin(hess_l + phi0), 0.0, atol=1e-14) and hess_l.size == 2
    sing = ds.separatrix_L_action.values[~sep]
    assert sorted(np.unique(sing)) == [-1.0, 1.0]
    dh = separatrix_hess(paper_body, 1.0, n=21)
    t1 = dh.separatrix_theta1.values[dh.separatrix_kind.values == "separatrix", 0]
    assert np.allclose(np.sort(t1), [0.0, 4 * phi0, 2 * np.pi], atol=1e-14)
    assert set(dh.separatrix_theta1.values[dh.separatrix_hess.values, 0]) == {0.0, 2 * np.pi}


def test_general_separatrix_passes_through_saddles() -> None:
    """y middle: the curves cross at the regular saddles (0, 0) and (pi, 0)."""
    body = RigidBody(2.0, 2.2, 2.5)
    ds = separatrix_andoyer(body, 1.0, n=201)
    for l0 in (0.0, np.pi):
        d = np.hypot(ds.separatrix_l_angle.values - l0, ds.separatrix_L_action.values)
        assert np.min(d) < 1e-12


def test_portraits_hold_what_a_plot_needs(paper_body: RigidBody, tmp_path) -> None:
    from andoyer.io import write_netcdf

    for ds, (x, y) in ((portrait_andoyer(paper_body, 1.0, n=(65, 33)), ("l_angle",
                                                                        "L_action")),
                       (portrait_hess(paper_body, 1.0, n=(65, 17)), ("theta1", "J1"))):
        saddles = ds.fp_H0.values[ds.fp_type.values == "saddle"]
        assert saddles.size and np.all(np.min(np.abs(
            ds.levels.values[:, None] - saddles[None, :]), axis=0) < 1e-15)
        assert ds.levels.values[ds.level_is_separatrix.values].tolist() == [
            pytest.approx(paper_body.c / 2, abs=1e-15)]
        assert ds.H0.dims == (y, x)
        assert set(ds.annotation_text.values.tolist()) == {"1", "2", "3", "4"}
        assert ds.attrs["plane_x"] == x and "caption" in ds.attrs
        write_netcdf(ds, tmp_path / f"{x}.nc")
        assert (tmp_path / f"{x}.nc").stat().st_size > 0
