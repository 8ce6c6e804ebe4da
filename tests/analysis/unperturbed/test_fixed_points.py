"""Fixed points of the unperturbed system and Euler-Poisson equilibria.

The expected lists are written here from the derivation (not from the module): the
numerical roots must match them, with their types and eigenvalues; a mutated system is
caught by the module's own numerics-vs-closed-form check.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from _eigs import close_eigs as _close_eigs
from andoyer import RigidBody
from andoyer.analysis.unperturbed import fixed_points as fpmod
from andoyer.analysis.unperturbed.equilibria import classify, euler_poisson_equilibria
from andoyer.analysis.unperturbed.fixed_points import andoyer_fixed_points, hess_fixed_points

PI = math.pi


def _expected_andoyer(body: RigidBody, G0: float) -> dict[tuple[float, float], tuple]:
    """(l, L) -> (chart type, motion, real, chart eigenvalue pair) for a Hess body."""
    a, b, c, phi0 = body.a, body.b, body.c, abs(body.phi0)
    sig = math.sqrt((b - c) * (c - a))
    wy = G0 * math.sqrt((b - c) * (b - a))        # y: minor axis (largest b)
    wx = G0 * math.sqrt((a - c) * (a - b))        # x: major axis
    out = {(0.0, 0.0): ("centre", "+y", True, (1j * wy, -1j * wy)),
           (PI, 0.0): ("centre", "-y", True, (1j * wy, -1j * wy)),
           (PI / 2, 0.0): ("centre", "+x", True, (1j * wx, -1j * wx)),
           (3 * PI / 2, 0.0): ("centre", "-x", True, (1j * wx, -1j * wx))}
    for L, m in ((G0, "+z"), (-G0, "-z")):
        for l in (phi0, PI - phi0, PI + phi0, 2 * PI - phi0):
            out[(l, L)] = ("saddle", m, False, (2 * sig * G0, -2 * sig * G0))
    return out


@pytest.mark.parametrize("G0", [1.0, 2.5])
def test_andoyer_fixed_points_of_the_paper_body(paper_body: RigidBody, G0: float) -> None:
    fps = andoyer_fixed_points(paper_body, G0)
    expected = _expected_andoyer(paper_body, G0)
    assert len(fps.points) == len(expected) == 12
    for fp in fps.points:
        key = min(expected, key=lambda k: math.hypot(k[0] - fp.q, k[1] - fp.p))
        assert math.hypot(key[0] - fp.q, key[1] - fp.p) < 1e-10 * G0
        kind, motion, real, ev = expected[key]
        assert (fp.linear_type, fp.motion, fp.real_equilibrium) == (kind, motion, real)
        assert _close_eigs(fp.eigenvalues, ev)
        assert _close_eigs(fp.eigenvalues_closed, ev)
        assert fp.residual < 1e-12
        assert fp.physical_type == ("saddle" if motion.endswith("z") else "centre")
        expected.pop(key)
    assert not expected


def test_hess_fixed_points_the_paper_four_and_the_centres(paper_body: RigidBody) -> None:
    """theta1 in [0, 2 pi): the paper's four on J1 = 0, J2 plus the two centres."""
    phi0 = paper_body.phi0
    fps = hess_fixed_points(paper_body, 1.0)
    got = {(round(fp.q, 9), round(fp.p, 9)): fp for fp in fps.points}
    want = {(0.0, 0.0): ("saddle", "-z", False), (round(4 * phi0, 9), 0.0): ("saddle", "-z",
                                                                             False),
            (0.0, 1.0): ("saddle", "+z", False), (round(4 * phi0, 9), 1.0): ("saddle", "+z",
                                                                             False),
            (round(2 * phi0, 9), 0.5): ("centre", "+y, -y", True),
            (round(2 * phi0 + PI, 9), 0.5): ("centre", "+x, -x", True)}
    assert set(got) == set(want)
    for k, (kind, motion, real) in want.items():
        assert (got[k].linear_type, got[k].motion, got[k].real_equilibrium) == (kind, motion,
                                                                                real)
    labels = {fp.closed_form: fp.label for fp in fps.points}
    assert labels == {"(0, 0)": 2, "(4 phi0, 0)": 2, "(0, J2)": 1, "(4 phi0, J2)": 1,
                      "(2 phi0, J2/2)": 3, "(2 phi0 + pi, J2/2)": 4}


def test_double_cover_is_one_to_one_with_l_L(paper_body: RigidBody) -> None:
    J2 = 1.3
    dc = hess_fixed_points(paper_body, J2, double_cover=True)
    al = andoyer_fixed_points(paper_body, J2)
    assert len(dc.points) == len(al.points) == 12
    mapped = sorted((round(float(np.mod(2 * (fp.q + paper_body.phi0), 4 * PI)) % (4 * PI), 8),
                     round((J2 + fp.p) / 2, 8), fp.motion) for fp in al.points)
    mine = sorted((round(fp.q, 8) % round(4 * PI, 8), round(fp.p, 8), fp.motion)
                  for fp in dc.points)
    assert mapped == mine


def test_other_branch_and_other_bodies(hess_minus_body: RigidBody) -> None:
    fps = hess_fixed_points(hess_minus_body, 1.0)
    assert len(fps.points) == 6 and len(fps.by_type("centre")) == 2
    # z an extreme axis (C the major moment): no point on L = +-G0; y middle: saddles.
    body = RigidBody(1.0, 2.0, 3.0)
    fps = andoyer_fixed_points(body, 1.0)
    assert len(fps.points) == 4
    types = {(round(fp.q, 9), fp.p): fp.linear_type for fp in fps.points}
    assert types == {(0.0, 0.0): "saddle", (round(PI, 9), 0.0): "saddle",
                     (round(PI / 2, 9), 0.0): "centre", (round(3 * PI / 2, 9), 0.0): "centre"}
    assert all(fp.real_equilibrium for fp in fps.points)
    rot = {r.name: r.linear_type for r in fps.rotations}
    assert rot == {"+x": "centre", "-x": "centre", "+y": "saddle", "-y": "saddle",
                   "+z": "centre", "-z": "centre"}


def test_mutated_system_is_caught(paper_body: RigidBody, monkeypatch) -> None:
    """Mutation: + cos 2 phi0 for - cos 2 phi0 in the bracket (a sign inside kappa's
    factor) moves the fixed points: the numerics no longer match the closed forms."""
    import sympy as sp

    th, J1, J2, a, b, c, phi0 = sp.symbols("theta1 J1 J2 a b c phi0")
    H = c * J2**2 / 2 + (a - b) * J1 * (J1 - J2) * (sp.cos(th - 2 * phi0) + sp.cos(2 * phi0))
    F = sp.Matrix([sp.diff(H, J1), -sp.diff(H, th)])
    args = (th, J1, J2, a, b, c, phi0)
    fake = (sp.lambdify(args, H), sp.lambdify(args, list(F)),
            sp.lambdify(args, F.jacobian([th, J1]).tolist()))
    monkeypatch.setattr(fpmod, "_reduced", lambda chart: fake)
    with pytest.raises(RuntimeError, match="closed form"):
        hess_fixed_points(paper_body, 1.0)


def test_mutated_closed_form_is_caught(paper_body: RigidBody, monkeypatch) -> None:
    orig = fpmod._l_closed_forms

    def wrong(body, G0):  # kappa -> -kappa in sin^2 l* = (b - c)/(b - a): l* -> pi/2 - l*
        return [(PI / 2 - l if line else l, L, t, m, line) for l, L, t, m, line in
                orig(body, G0)]

    monkeypatch.setattr(fpmod, "_l_closed_forms", wrong)
    with pytest.raises(RuntimeError):
        andoyer_fixed_points(paper_body, 1.0)


def test_classify_and_validation(paper_body: RigidBody) -> None:
    assert classify([1j, -1j], 1.0) == "centre"
    assert classify([2.0, -2.0], 1.0) == "saddle"
    assert classify([1e-12, -1e-12], 1.0) == "degenerate"
    assert classify([1.0, -1.0, 1j, -1j], 1.0) == "saddle-centre"
    with pytest.raises(ValueError, match="distinct moments"):
        andoyer_fixed_points(RigidBody(2.0, 2.0, 1.0), 1.0)
    with pytest.raises(ValueError, match="G0"):
        andoyer_fixed_points(paper_body, 0.0)
    with pytest.raises(ValueError, match="n_seed"):
        hess_fixed_points(paper_body, 1.0, n_seed=(4, 2))


def test_datasets(paper_body: RigidBody, tmp_path) -> None:
    from andoyer.io import write_netcdf

    fps = hess_fixed_points(paper_body, 1.0)
    ds = fps.to_dataset()
    assert ds.sizes["fixed_point"] == 6 and ds.sizes["rotation"] == 6
    assert int(ds.real_equilibrium.sum()) == 2
    assert ds.attrs["chart"] == "hess" and ds.attrs["body_mu"] == 0.0
    assert all("long_name" in ds[v].attrs for v in ("theta1", "J1", "eig_real", "motion"))
    write_netcdf(ds, tmp_path / "fp.nc")
    eq = euler_poisson_equilibria(paper_body)
    write_netcdf(eq.to_dataset(), tmp_path / "eq.nc")
