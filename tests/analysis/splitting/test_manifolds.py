"""Invariant manifolds, heteroclinic points and separatrix splitting (issue 5, parts 2, 3, 6).

The fast tests use a Hess body with ``rho = c/(2 sigma) = 1.08`` (A, B, C = 2.5, 1, 1.6),
whose splitting is of order mu; the paper's body (``rho = 4.56``, splitting 7.4e-5 mu) is
the slow test. Routes: the first-order Melnikov prediction (closed form, itself checked
against quadrature in ``test_melnikov.py``); the exact reversing symmetry
``(G1, G2, G3, gamma1, gamma2, gamma3) -> (G1, G2, -G3, gamma1, gamma2, -gamma3)``
that maps ``W^u(P-)`` onto ``W^s(P+)`` (computed independently, backwards in time) and
fixes ``g = pi/2, 3 pi/2`` on ``L = 0``; the Hess invariant relation (3).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from andoyer import RigidBody
from andoyer.analysis.splitting.manifolds import grow_manifold, manifold_branch
from andoyer.analysis.splitting.measure import measure_splitting, separatrix_splitting, splitting_at
from andoyer.analysis.splitting.periodic import rotation_energy
from andoyer.charts.andoyer_deprit import to_andoyer
from andoyer.cli import main

TEST_BODY = RigidBody.hess(2.5, 1.0, 1.6, name="rho~1")
MUS = [0.005, 0.01]


@pytest.fixture(scope="module")
def result():
    return separatrix_splitting(TEST_BODY, MUS, n_phase=16, branch="theta1=4phi0")


@pytest.fixture(scope="module")
def curves():
    body = TEST_BODY.with_mu(0.02)
    h = rotation_energy(body)
    wu = grow_manifold(manifold_branch(body, h, "unstable", "theta1=4phi0"))
    ws = grow_manifold(manifold_branch(body, h, "stable", "theta1=4phi0"))
    return wu, ws


def test_splitting_agrees_with_melnikov_to_first_order(result):
    sp = result["splitting"]
    err = sp.relative_error.values
    assert err[1] < 0.05                       # measured 0.031 at mu = 0.01
    assert 1.7 < err[1] / err[0] < 2.3         # the error is O(mu): halves with mu
    dE, dE1 = sp.Delta_E.values, sp.Delta_E_melnikov.values
    amp = np.max(np.abs(dE1), axis=1)
    errE = np.max(np.abs(dE - dE1), axis=1) / amp
    assert errE[1] < 0.05 and 1.7 < errE[1] / errE[0] < 2.3
    # Delta G = -Delta E / (c G) (1 + O(mu)).
    ok = np.abs(sp.Delta_E.values) > 1e-3 * amp[:, None]
    ratio = sp.Delta_G.values[ok] / (-sp.Delta_E.values[ok] / TEST_BODY.c)
    assert np.max(np.abs(ratio - 1)) < 0.05


def test_heteroclinic_points_are_located_on_the_symmetry_line(result):
    it = result["intersections"]
    assert it.sizes["intersection"] == 2
    g = it.g.values
    assert np.max(np.abs(g - np.array([math.pi / 2, 3 * math.pi / 2]))) < 1e-10
    assert np.max(it.state_distance.values) < 1e-12
    assert np.max(np.abs(it.Delta_G.values)) < 1e-14


def test_angle_and_lobe_area(result):
    it = result["intersections"]
    lobes = it.lobe_area.values
    assert np.all(lobes[:, 0] * lobes[:, 1] < 0)                    # turnstile: in, out
    assert np.max(np.abs(lobes.sum(axis=1))) < 1e-9 * np.max(np.abs(lobes))
    for k in range(len(MUS)):
        assert np.abs(lobes[k]) == pytest.approx(
            [float(it.lobe_area_melnikov[k])] * 2, rel=0.05)
        assert np.abs(it.angle.values[k]) == pytest.approx(
            [float(it.angle_melnikov[k])] * 2, rel=0.12)


def test_reversor_maps_unstable_onto_stable(curves):
    """W^s, computed backwards from P+, is the image of W^u under (G3, gamma3) -> -(...)."""
    wu, ws = curves
    for g in (0.3, 1.2, 2.5, 4.0, 5.5):
        yu = wu.point_at_phase(g).y
        ys = ws.point_at_phase(math.pi - g).y
        image = yu * np.array([1, 1, -1, 1, 1, -1])
        assert np.max(np.abs(image - ys)) < 1e-12


def test_curves_lie_on_the_level_and_the_section(curves):
    wu, ws = curves
    h = rotation_energy(TEST_BODY)
    for curve in (wu, ws):
        ds = curve.dataset()
        assert float(abs(ds.H - h).max()) < 1e-13
        assert float(abs(ds.L_action).max()) < 1e-14
        assert np.all(np.diff(ds.arclength.values) > 0)
        assert np.all(np.diff(ds.s.values) > 0)
        assert float(ds.g_unwrapped.max() - ds.g_unwrapped.min()) > 2 * math.pi
        assert float(abs(ds.l_angle - TEST_BODY.phi0).max()) < 0.2    # the theta1 = 4 phi0 line
        assert ds.attrs["stability"] == curve.branch.stability
    assert float(np.sign(wu.t).min()) > 0 and float(np.sign(ws.t).max()) < 0


def test_adaptive_insertion_keeps_the_curve_resolved(curves):
    wu, _ = curves
    fine = grow_manifold(wu.branch, n_initial=8, max_gap=0.05, max_angle=0.02)
    gaps = np.hypot(np.diff(fine.g), np.diff(fine.G))
    assert np.max(gaps) <= 0.05
    assert fine.s.size > 8 * (2 * math.pi / 0.05) / 8 / 2
    assert np.ptp(np.diff(fine.s)) > 0          # refined where needed, not uniformly


def test_hess_branch_does_not_split():
    """theta1 = 0 is the invariant Hess relation (3): W^u(P+) = W^s(P-) for every mu."""
    body = TEST_BODY.with_mu(0.02)
    h = rotation_energy(body)
    wu = grow_manifold(manifold_branch(body, h, "unstable", "theta1=0"))
    ws = grow_manifold(manifold_branch(body, h, "stable", "theta1=0"))
    sp, it = measure_splitting(wu, ws, n_phase=8)
    assert sp.attrs["manifolds_coincide"] == 1 and it.sizes["intersection"] == 0
    assert float(abs(sp.Delta_G).max()) < 1e-13        # the other line splits by 1.4e-2
    for curve in (wu, ws):
        assert np.max(np.abs(curve.y[:, 0] * body.e1 + curve.y[:, 1] * body.e2)) < 1e-13
    assert wu.branch.orbit.section.sign == 1 and ws.branch.orbit.section.sign == -1


def test_splitting_at_single_phase(curves):
    wu, ws = curves
    r = splitting_at(wu, ws, 0.0)
    for key, y in (("y_u", r["y_u"]), ("y_s", r["y_s"])):
        assert abs(math.remainder(float(to_andoyer(y)[1]), 2 * math.pi)) < 1e-12, key
    assert r["Delta_G"] == pytest.approx(0.0142, rel=0.02)      # ~ mu * 0.71 cos g, mu = 0.02


def test_cli_writes_netcdf_and_png(tmp_path, capsys):
    out = tmp_path / "mf"
    code = main(["manifolds", "--body", "hess", "--A", "2.5", "--B", "1", "--C", "1.6",
                 "--mu-list", "0.01", "--n-phase", "8", "--delta", "1e-4", "--out", str(out)])
    assert code == 0
    for name in ("splitting", "intersections", "melnikov", "manifold_unstable",
                 "manifold_stable", "periodic_orbits", "hess_branch"):
        assert (out / f"{name}.nc").exists(), name
    assert (out / "manifolds.png").stat().st_size > 10_000
    with xr.open_dataset(out / "splitting.nc") as sp:
        assert sp.attrs["branch"] == "theta1=4phi0"
        assert float(sp.relative_error[0]) < 0.05
    with xr.open_dataset(out / "hess_branch.nc") as hb:
        assert float(hb.amplitude[0]) < 1e-13
    text = capsys.readouterr().out
    assert "rel.err" in text and "Hess" in text


def test_invalid_inputs(tmp_path):
    body = RigidBody(2.0, 2.5, 3.0, 0.01, (0.6, 0.8, 0.0))     # no Hess body: C not middle
    with pytest.raises(ValueError, match="A > C > B"):
        separatrix_splitting(body, [0.01])
    lifted = RigidBody(2.5, 2.0, 2.2, 0.01, (0.6, 0.0, 0.8))    # off the (e1, e2) plane
    with pytest.raises(ValueError, match="e3 = 0"):
        separatrix_splitting(lifted, [0.01])
    with pytest.raises(ValueError, match="increasing"):
        separatrix_splitting(TEST_BODY, [0.02, 0.01])
    with pytest.raises(ValueError, match="> 0"):
        separatrix_splitting(TEST_BODY, [0.0])
    with pytest.raises(ValueError, match="stability"):
        manifold_branch(TEST_BODY.with_mu(0.01), 0.3, "neutral")   # type: ignore[arg-type]
    with pytest.raises(SystemExit) as exc:
        main(["manifolds", "--body", "general", "--A", "2.5", "--B", "2", "--C", "2.2",
              "--r", "0.6", "0.8", "0", "--out", str(tmp_path)])
    assert exc.value.code == 2


# ---------------------------------------------------------------------- slow: paper's body
@pytest.mark.slow
def test_paper_body_splitting_converges_to_melnikov():
    """rho = 4.56: the splitting is 7.4e-5 mu cos g; first order holds with error ~24 mu."""
    out = separatrix_splitting(RigidBody.paper(), [0.00125, 0.0025, 0.005], n_phase=16,
                               branch="theta1=4phi0")
    err = out["splitting"].relative_error.values
    assert err[0] < 0.04
    assert 1.8 < err[1] / err[0] < 2.2 and 1.8 < err[2] / err[1] < 2.2
    amp = out["splitting"].amplitude.values
    assert amp[0] == pytest.approx(9.29e-8, rel=0.01)
    it = out["intersections"]
    assert np.max(np.abs(it.g.values[:, 0] - math.pi / 2)) < 1e-8
    assert np.max(it.state_distance.values) < 1e-12
    hess = separatrix_splitting(RigidBody.paper(), [0.01], branch="theta1=0", n_phase=8)
    assert float(hess["splitting"].amplitude[0]) < 1e-14


@pytest.mark.slow
def test_paper_body_splitting_is_converged_in_delta_tolerance_and_precision():
    """Delta G ~ 1.8e-7 at mu = 0.0025 changes by < 1e-14 with delta, tol, long double."""
    body = RigidBody.paper(0.0025)
    h = rotation_energy(body)
    phases = [0.0, 0.7, 2.0]
    values = []
    for kw in ({}, {"delta": 3e-6}, {"tol": 1e-13}, {"tol": 1e-16, "long_double": True}):
        wu = grow_manifold(manifold_branch(body, h, "unstable", "theta1=4phi0", **kw))
        ws = grow_manifold(manifold_branch(body, h, "stable", "theta1=4phi0", **kw))
        values.append([splitting_at(wu, ws, g)["Delta_G"] for g in phases])
    values = np.array(values)
    assert np.max(np.abs(values - values[0])) < 1e-14
    assert np.min(np.abs(values)) > 8e-8
