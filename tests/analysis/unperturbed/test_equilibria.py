"""Permanent rotations of the free top and equilibria of the Euler-Poisson equations."""

from __future__ import annotations

import math

import numpy as np
import pytest

from _eigs import close_eigs as _close_eigs
from andoyer import RigidBody
from andoyer.analysis.unperturbed.equilibria import euler_poisson_equilibria, permanent_rotations
from andoyer.analysis.unperturbed.fixed_points import andoyer_fixed_points


def test_permanent_rotations_regular_route(paper_body: RigidBody) -> None:
    """Euler equations on |G| = G0: centre about major/minor, saddle about the middle
    axis with exponent sigma G0 = half the chart eigenvalue on the singular line."""
    G0 = 1.7
    rots = {r.name: r for r in permanent_rotations(paper_body, G0)}
    a, b, c = paper_body.a, paper_body.b, paper_body.c
    sig = math.sqrt((b - c) * (c - a))
    assert rots["+z"].inertia_rank == "middle" and rots["+x"].inertia_rank == "major"
    assert rots["+y"].inertia_rank == "minor"
    assert _close_eigs(rots["-z"].eigenvalues, (sig * G0, -sig * G0))
    fp = andoyer_fixed_points(paper_body, G0).by_type("saddle")[0]
    assert max(abs(v) for v in fp.eigenvalues) == pytest.approx(2 * sig * G0, rel=1e-12)
    for r in rots.values():
        assert _close_eigs(r.eigenvalues, r.eigenvalues_closed)


def test_euler_poisson_equilibria_hess_body(paper_body: RigidBody) -> None:
    """Hess body: the restricted inertia on r-perp is c Id -> a 1:1 resonance."""
    eqs = {e.name: e for e in euler_poisson_equilibria(paper_body).equilibria}
    w = math.sqrt(paper_body.mu * paper_body.c)
    assert eqs["hanging"].linear_type == "centre-centre"
    assert eqs["upright"].linear_type == "saddle-saddle"
    assert _close_eigs(eqs["hanging"].eigenvalues, (1j * w, 1j * w, -1j * w, -1j * w), 1e-9)
    assert _close_eigs(eqs["upright"].eigenvalues, (w, w, -w, -w), 1e-9)
    assert np.allclose(eqs["hanging"].y[3:], -np.array(paper_body.r))


def test_euler_poisson_equilibria_any_body(general_body: RigidBody) -> None:
    """r along x: eigenvalues +-i sqrt(mu b), +-i sqrt(mu c); any r: the 2x2 route."""
    body = RigidBody(1.3, 1.7, 2.1, mu=0.7, r=(1.0, 0.0, 0.0))
    eqs = {e.name: e for e in euler_poisson_equilibria(body).equilibria}
    wb, wc = math.sqrt(body.mu * body.b), math.sqrt(body.mu * body.c)
    assert _close_eigs(eqs["hanging"].eigenvalues, (1j * wb, -1j * wb, 1j * wc, -1j * wc))
    assert _close_eigs(eqs["upright"].eigenvalues, (wb, -wb, wc, -wc))
    r = np.array(general_body.r)
    U = np.linalg.svd(r[None, :])[2][1:].T                 # basis of r-perp
    k = np.linalg.eigvalsh(U.T @ np.diag([general_body.a, general_body.b, general_body.c]) @ U)
    for e in euler_poisson_equilibria(general_body).equilibria:
        s = -1.0 if e.name == "hanging" else 1.0
        roots = [np.sqrt(complex(s * general_body.mu * kk)) for kk in k]
        assert _close_eigs(e.eigenvalues, [v for rt in roots for v in (rt, -rt)])
        assert _close_eigs(e.eigenvalues, e.eigenvalues_closed)
    free = euler_poisson_equilibria(general_body.with_mu(0.0)).equilibria
    assert {e.linear_type for e in free} == {"degenerate"}
