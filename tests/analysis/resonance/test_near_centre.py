"""The resonant normal form near a centre (issue 28, item 3): a 2:1 chain close to the
permanent rotation about axis 2, checked against the torus route (resonance_widths), the
Birkhoff form at another G, and a measurement on sections."""

import math

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.resonance import (
    birkhoff_normal_form,
    resonance_widths,
    resonant_normal_form,
    resonant_tori,
)

R = (0.6, 0.48, 0.64)   # centre of mass off Hess and out of the (e1, e2) plane


def _body(A: float, mu: float = 1e-3) -> RigidBody:
    # inverse moments a = 1/A, b = 1, c = 1/2: W at the centre about axis 2 is
    # sqrt((1 - 1/A) / 2), just above 1/2 for A slightly above 2 (the 2:1 chain near it)
    return RigidBody(A, 1.0, 2.0, mu, R)


def _row(ds, label: str, axis: int, sign: int = 1) -> int:
    sel = (ds.label.values == label) & (ds.axis.values == axis) & (ds.sign.values == sign)
    return int(np.nonzero(sel)[0][0])


def test_resonant_torus_agrees_with_the_elliptic_integrals():
    body = _body(2.3)
    nf = resonant_normal_form(body, 1.0, 0.0, "2:1", axis=2)
    assert float(nf.rotation_number_g_section) == pytest.approx(0.5, abs=1e-13)
    tori = resonant_tori(body, 1.0, 0.0, max_order=3)
    G_exact = float(tori.G_action[_row(tori, "2:1", 2)])
    assert abs(float(nf.G_action) - G_exact) < 1e-5
    assert nf.attrs["label"] == "2:1" and nf.half_width.attrs["units"] == "1"


def test_homogeneity_of_the_birkhoff_coefficients():
    # (N1): c_k(G) = c_k(1) G^(2-k), checked against the Lie series run at G = 1.7
    body = _body(2.3)
    one = birkhoff_normal_form(body, 1.0, order=8).coefficient.values
    other = birkhoff_normal_form(body, 1.7, order=8).coefficient.values
    k = np.arange(1, one.size + 1)
    np.testing.assert_allclose(other, one * 1.7 ** (2 - k), rtol=1e-10)


def test_agreement_with_resonance_widths_improves_as_the_resonant_action_shrinks():
    I, err, v = [], [], []
    for A in (2.5, 2.3, 2.2):
        body = _body(A)
        nf = resonant_normal_form(body, 1.0, 0.0, "2:1", axis=2, order=8)
        rw = resonance_widths(body, 1.0, 0.0, "g=0", max_order=3)
        i = _row(rw, "2:1", 2)
        I.append(float(nf.action))
        err.append(abs(float(nf.half_width) / float(rw.half_width[i]) - 1.0))
        v.append(float(nf.dalembert_coefficient))
        # the same resonant harmonic, the same pendulum frequency, to the truncation
        assert float(nf.fourier_amplitude) == pytest.approx(
            float(rw.fourier_amplitude[i]), rel=1e-3)
        assert float(nf.libration_frequency) == pytest.approx(
            float(rw.libration_frequency[i]), rel=1e-3)
    assert I[0] > I[1] > I[2]
    assert max(err) < 1e-3
    slope = np.polyfit(np.log(I), np.log(err), 1)[0]
    assert slope > 3.0, (I, err, slope)        # O(I*^(N/2)) with N = 8: measured ~5
    # (N4): |V_k| ~ v I^(q/2) with v tending to a constant as I* -> 0
    assert abs(v[2] / v[1] - 1.0) < abs(v[1] / v[0] - 1.0) < 0.05


def test_higher_order_is_closer_to_the_torus_route():
    body = _body(2.5)
    rw = resonance_widths(body, 1.0, 0.0, "g=0", max_order=3)
    ref = float(rw.half_width[_row(rw, "2:1", 2)])
    e4, e8 = (abs(float(resonant_normal_form(body, 1.0, 0.0, "2:1", axis=2,
                                              order=n).half_width) / ref - 1.0)
              for n in (4, 8))
    assert e8 < 0.2 * e4, (e4, e8)


def test_pendulum_relations():
    a = resonant_normal_form(_body(2.3, 1e-3), 1.0, 0.0, "2:1", axis=2)
    b = resonant_normal_form(_body(2.3, 4e-3), 1.0, 0.0, "2:1", axis=2)
    assert float(b.half_width) / float(a.half_width) == pytest.approx(2.0, rel=1e-9)
    assert float(a.half_width) == pytest.approx(
        float(a.rotation_number_g_section * a.half_width_action), rel=1e-12)
    d = math.remainder(float(a.unstable_angle - a.stable_angle), 2 * math.pi)
    assert abs(abs(d) - math.pi) < 1e-12
    assert 0.0 < float(a.residue_stable) < 1.0 and float(a.residue_unstable) < 0.0
    assert int(a.mu_order) == 1


def test_second_order_chain_has_no_first_order_width():
    nf = resonant_normal_form(_body(2.5), 1.0, 0.0, "9:4", axis=2)
    assert int(nf.mu_order) == 2 and math.isnan(float(nf.half_width))


@pytest.mark.parametrize("kwargs, exc, word", [
    ({"resonance": 2}, ValueError, "resonance"),
    ({"resonance": "2:2"}, ValueError, "resonance"),
    ({"resonance": "x"}, ValueError, "resonance"),
    ({"resonance": "1:1"}, ValueError, "not reached"),
    ({"axis": 3}, ValueError, "axis"),
    ({"sign": 0}, ValueError, "sign"),
    ({"order": 7}, ValueError, "order"),
    ({"h": math.nan}, ValueError, "h"),
    ({"h": -1.0}, ValueError, "h"),
    ({"M": 10.0}, ValueError, "axis 2"),
])
def test_bad_inputs_are_refused(kwargs, exc, word):
    args = {"h": 1.0, "M": 0.0, "resonance": "2:1", "axis": 2} | kwargs
    with pytest.raises(exc, match=word):
        resonant_normal_form(_body(2.3), **args)


def _measured(A: float, mu: float, n_rounds: int = 5):
    from andoyer.analysis.resonance.measure import measure_island

    body = _body(A, mu)
    nf = resonant_normal_form(body, 1.0, 0.0, "2:1", axis=2)
    m = measure_island(body, 1.0, 0.0, "2:1", axis=2, n_seeds=3, n_rounds=n_rounds,
                       engine="numba")
    return nf, m


def test_measured_half_width():
    # Sections of the perturbed flow (the engine seam): the locked interval's half-width
    # against (N5). Tolerance: the edge resolution plus the truncation of the Birkhoff
    # polynomial at I* = 0.27 (|nf / resonance_widths - 1| = 5.3e-4); measured 7.8e-4.
    nf, m = _measured(2.5, 1e-3)
    unc = float(m.edge_uncertainty) / float(nf.half_width)
    trunc = abs(float(nf.half_width) / float(m.predicted_half_width) - 1.0)
    err = abs(float(m.measured_half_width) / float(nf.half_width) - 1.0)
    assert err < unc + trunc + 2e-4, (err, unc, trunc)


@pytest.mark.slow
def test_measured_half_width_nearer_the_centre():
    # at I* = 0.126 the truncation is 1.2e-5: the normal form meets the measurement at
    # the edge resolution, at two mu
    for mu in (1e-4, 1e-3):
        nf, m = _measured(2.2, mu)
        unc = float(m.edge_uncertainty) / float(nf.half_width)
        err = abs(float(m.measured_half_width) / float(nf.half_width) - 1.0)
        assert err < unc + 1e-4, (mu, err, unc)


@pytest.mark.slow
def test_measured_half_width_with_the_island_near_the_centre():
    # The pendulum holds while the island stays off the centre: Delta I / I* = 0.34, 0.62,
    # 0.87 at mu = 3e-3, 1e-2, 2e-2 (I* = 0.126). With 7 rounds (edge resolution 6.1e-5 of
    # the width) the measured errors are -1.5e-4, -3.3e-4, -4.2e-4, growing like mu^0.54
    # (the pendulum's neglected I-dependence across the island, ~5e-4 Delta I / I*); the
    # tolerance is the resolution plus 6e-4 Delta I / I*. (At mu = 3e-2, Delta I / I* = 1.06,
    # the chain is 12 % narrower: the documented failure, not asserted here.)
    for mu in (3e-3, 1e-2, 2e-2):
        nf, m = _measured(2.2, mu, n_rounds=7)
        reach = float(nf.half_width_action) / float(nf.action)
        assert reach < 0.9
        unc = float(m.edge_uncertainty) / float(nf.half_width)
        err = abs(float(m.measured_half_width) / float(nf.half_width) - 1.0)
        assert err < unc + 6e-4 * reach, (mu, err, unc, reach)


def test_stable_and_unstable_angles_match_the_torus_route():
    # the sign of the twist from the polynomial picks the same equilibrium of the
    # pendulum as the elliptic-integral twist does (R7), for both copies of the chain
    from andoyer.analysis.resonance.predict import ResonantChain, resonant_rows
    from andoyer.integrate import Section

    body = _body(2.3)
    for sign in (1, -1):
        nf = resonant_normal_form(body, 1.0, 0.0, "2:1", axis=2, sign=sign)
        row = [r for r in resonant_rows(body, 1.0, 0.0, 3)
               if (r["p"], r["q"], r["axis"], r["sign"]) == (1, 2, 2, sign)][0]
        chain = ResonantChain(body, 1.0, 0.0, row, Section("g", 0.0, 1))
        for mine, theirs in ((nf.stable_angle, chain.psi_s), (nf.unstable_angle, chain.psi_u)):
            assert abs(math.remainder(float(mine) - theirs, 2 * math.pi)) < 1e-6


def test_the_resonance_predictions_scale_to_the_largest_levels_without_overflow():
    """At mu = 0 both routes scale exactly: the action and G like sqrt(h), the
    rotation number not at all. Up to the largest level taken (|G| <= 1e100), with no
    overflow on the way: |G|^4 (the sum of squares of two energies) and I^k at degree 8
    overflowed near |G| = 1e77 before, and the normal form's root search then failed
    with NaN."""
    import warnings

    from andoyer.analysis.resonance import resonance_widths

    free = RigidBody(2.2, 1.0, 2.0, mu=0.0, r=(0.6, 0.48, 0.64))
    near = resonant_normal_form(free, 1.0, 0.0, "2:1")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        far = resonant_normal_form(free, 1e180, 0.0, "2:1")
        far_widths = resonance_widths(free, 1e180, 0.0)
    assert float(far.action) == pytest.approx(float(near.action) * 1e90, rel=1e-12)
    assert float(far.G_action) == pytest.approx(float(near.G_action) * 1e90, rel=1e-12)
    near_widths = resonance_widths(free, 1.0, 0.0)
    assert near_widths.sizes == far_widths.sizes
    np.testing.assert_allclose(far_widths.G_action, near_widths.G_action * 1e90, rtol=1e-12)
    np.testing.assert_allclose(far_widths.rotation_number_g_section,
                               near_widths.rotation_number_g_section, rtol=1e-12)
