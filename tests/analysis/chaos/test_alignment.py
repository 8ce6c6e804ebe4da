"""SALI and GALI_k (:mod:`andoyer.analysis.chaos.alignment`) where the answer is known.

Theory (Skokos, Bountis & Antonopoulos 2007) for the reduced system on a symplectic
leaf, N = 2 degrees of freedom, vectors in the leaf's 4-dimensional tangent space:

* regular orbit on a 2-torus: ``GALI_2`` tends to a constant (k <= N), ``GALI_3 ~ t^-2``
  and ``GALI_4 ~ t^-4`` (``t^-2(k - N)``); SALI stays of order 0.01 .. 1;
* chaotic orbit: ``GALI_2 ~ exp(-lambda t)``, ``GALI_3 ~ exp(-2 lambda t)`` (exponents
  ``(lambda, 0, 0, -lambda)``), SALI -> 0 like GALI_2.

Also the pure identities of the indices and the initial vectors' tangency.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from andoyer import RigidBody, from_andoyer
from andoyer.analysis.chaos.alignment import alignment_indices, gali, initial_tangents, sali
from andoyer.analysis.chaos.lyapunov import initial_tangent
from andoyer.integrate.engines import engines_with
from andoyer.integrate.engines.base import Capability

PAPER = RigidBody.paper()
TORUS = [0.3, 0.0, 0.3, 1.0, 0.0]  # Andoyer-Deprit: a torus of the paper's body
CHAOTIC_BODY = RigidBody.hess(3.0, 1.0, 2.0, mu=1.0)
#: Hess-chart states on H = 1, M = 0 of CHAOTIC_BODY (as in tests/analysis/test_chaos).
CHAOTIC = [0.2617993877991494, 0.0, 1.0103629710818451, 1.712575169922734, 0.0]
REGULAR = [2.8797932657906435, 0.0, 0.7216878364870322, 1.3852961954031033, 0.0]
#: Log-spaced output times for power laws.
T_LOG = np.concatenate([[0.0], np.geomspace(1.0, 1e4, 81)])


def loglog_slope(t: np.ndarray, g: np.ndarray, t_min: float = 100.0) -> float:
    late = t >= t_min
    return float(np.polyfit(np.log(t[late]), np.log(g[late]), 1)[0])


def test_sali_and_gali_2_are_functions_of_the_angle() -> None:
    rng = np.random.default_rng(11)
    w1, w2 = rng.normal(size=(2, 200, 6))
    cos = np.einsum("ni,ni->n", w1, w2) / (np.linalg.norm(w1, axis=1)
                                          * np.linalg.norm(w2, axis=1))
    angle = np.arccos(cos)
    np.testing.assert_allclose(gali(np.stack([w1, 3.0 * w2], axis=1)), np.sin(angle),
                               rtol=1e-12)
    np.testing.assert_allclose(sali(w1, -w2),
                               2 * np.minimum(np.sin(angle / 2), np.cos(angle / 2)),
                               rtol=1e-12)
    assert float(gali(np.eye(6))) == pytest.approx(1.0)
    dependent = np.array([[1.0, 2, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], [2, 5, 0, 0, 0, 0]])
    assert float(gali(dependent)) < 1e-15


@pytest.mark.parametrize("tangent", ["leaf", "energy"])
def test_initial_vectors_are_orthonormal_and_tangent(tangent: str) -> None:
    y = from_andoyer(np.array([TORUS, [1.0, 2.0, -0.5, 1.0, 0.3]]))
    k = 4 if tangent == "leaf" else 3
    W = initial_tangents(PAPER, y, k, tangent)  # type: ignore[arg-type]
    gram = np.einsum("nki,nji->nkj", W, W)
    np.testing.assert_allclose(gram, np.broadcast_to(np.eye(k), (2, k, k)), atol=1e-14)
    np.testing.assert_allclose(W[:, 0], initial_tangent(PAPER, y, tangent), atol=1e-15)  # type: ignore[arg-type]
    G, gamma = y[:, :3], y[:, 3:]
    normals = [np.concatenate([gamma, G], axis=1),
               np.concatenate([np.zeros_like(gamma), gamma], axis=1)]
    if tangent == "energy":
        normals.append(np.concatenate([np.array([PAPER.a, PAPER.b, PAPER.c]) * G,
                                       np.broadcast_to(PAPER.mu * np.array(
                                           [PAPER.e1, PAPER.e2, PAPER.e3]), G.shape)],
                                      axis=1))
    for n in normals:
        assert np.abs(np.einsum("ni,nki->nk", n, W)).max() < 1e-13


def test_gali_power_laws_on_a_torus() -> None:
    """GALI_2 -> const, GALI_3 ~ t^-2, GALI_4 ~ t^-4 on the paper's torus (N = 2)."""
    slopes = {}
    for k in (2, 3, 4):
        ds = alignment_indices(PAPER, TORUS, chart="andoyer", k=k, t=T_LOG)
        g = ds.gali.isel(orbit=0).values
        slopes[k] = loglog_slope(T_LOG, g)
        if k == 2:
            # measured: GALI_2 0.0579 at t = 1e3, 0.0573 at t = 1e4; slope -0.12 over
            # [1e2, 1e4] (still settling from 0.2 at t = 100); SALI >= 0.051 throughout
            assert g[-1] > 0.04 and abs(g[-1] / g[60] - 1.0) < 0.05
            assert float(ds.sali.isel(orbit=0).min()) > 0.04
    # measured -0.121, -2.008, -4.003
    assert -0.2 < slopes[2] < 0.0
    assert slopes[3] == pytest.approx(-2.0, abs=0.05)
    assert slopes[4] == pytest.approx(-4.0, abs=0.05)


def test_gali_power_laws_on_a_torus_of_the_hess_body() -> None:
    for k, expected in ((3, -2.0), (4, -4.0)):  # measured -2.019, -4.021
        ds = alignment_indices(CHAOTIC_BODY, REGULAR, chart="hess", k=k, t=T_LOG)
        assert loglog_slope(T_LOG, ds.gali.isel(orbit=0).values) == pytest.approx(
            expected, abs=0.1)


def test_gali_decays_exponentially_and_sali_vanishes_on_a_chaotic_orbit() -> None:
    t = np.linspace(0.0, 600.0, 601)
    ds2 = alignment_indices(CHAOTIC_BODY, CHAOTIC, chart="hess", k=2, t=t)
    ds3 = alignment_indices(CHAOTIC_BODY, CHAOTIC, chart="hess", k=3, t=t)
    lam = ds2.mle.isel(orbit=0).values  # finite-time: 0.066 .. 0.037 .. 0.057
    g2, g3 = ds2.gali.isel(orbit=0).values, ds3.gali.isel(orbit=0).values
    # mean rates over the whole run (finite-time rates wander in the sticky layer):
    # measured -ln GALI_2(600)/600 = 0.88 lambda, -ln GALI_3(400)/400 = 1.02 (2 lambda)
    assert -math.log(g2[600]) / 600 == pytest.approx(lam[600], rel=0.3)
    assert -math.log(g3[400]) / 400 == pytest.approx(2 * lam[400], rel=0.3)
    sali_ = ds2.sali.isel(orbit=0).values
    assert sali_[600] < 1e-10  # measured 9e-14; a power law t^-2 would be ~3e-6
    small = (g2 < 1e-2) & (t < 400)  # SALI = 2 sin(angle/2) ~ sin(angle) = GALI_2 -> 0
    assert small.sum() > 200
    np.testing.assert_allclose(sali_[small], g2[small], rtol=1e-4)
    # the same vector-1 exponent as the heyoka-free FLI/MEGNO path
    assert lam[600] > 0.03


@pytest.mark.parametrize("engine", engines_with(Capability.TANGENT))
def test_dataset_and_input_checks(engine: str) -> None:
    ds = alignment_indices(PAPER, TORUS, 10.0, chart="andoyer", k=3, n_times=5,
                           engine=engine)
    assert ds.gali.dims == ("orbit", "time") and ds.log_norm.dims == ("orbit", "time", "vector")
    assert ds.attrs["engine"] == engine and ds.attrs["k"] == 3
    assert ds.gali.attrs["symbol"] == "GALI_3"
    assert float(abs(ds.H_drift).max()) < 1e-12
    with pytest.raises(ValueError, match="k must be an integer from 2 to 4"):
        alignment_indices(PAPER, TORUS, 10.0, chart="andoyer", k=5)
    with pytest.raises(ValueError, match="from 2 to 3"):
        alignment_indices(PAPER, TORUS, 10.0, chart="andoyer", k=4, tangent="energy")
    with pytest.raises(ValueError, match="unknown tangent space"):
        alignment_indices(PAPER, TORUS, 10.0, chart="andoyer", tangent="full")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="t_end"):
        alignment_indices(PAPER, TORUS, -1.0, chart="andoyer")
    with pytest.raises(ValueError, match="starting at 0"):
        alignment_indices(PAPER, TORUS, chart="andoyer", t=[1.0, 2.0])
