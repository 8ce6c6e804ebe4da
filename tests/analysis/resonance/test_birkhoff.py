"""Birkhoff normal forms of the free top at its centres (issue 28, item 3), against the
period in elliptic integrals (closed form) and NAFF on integrated orbits."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from andoyer import RigidBody
from andoyer.analysis.chaos.frequency import orbit_frequencies
from andoyer.analysis.resonance.birkhoff import birkhoff_normal_form, normal_form_frequency
from andoyer.analysis.unperturbed.euler_poinsot import euler_poinsot_frequencies
from andoyer.charts.andoyer_deprit import from_andoyer

PAPER = RigidBody.paper()


def _predicted(nf, h):
    """omega_l, omega_g of the normal form on the orbit of energy h."""
    I = brentq(lambda a: float(normal_form_frequency(nf, [a]).energy[0]) - h, 0.0, 1.0)
    f = normal_form_frequency(nf, [I])
    return abs(float(f.omega_l[0])), float(f.omega_g[0])


def _level(body, lstar, amp, G=1.0):
    l = lstar + amp
    return 0.5 * (body.a * math.sin(l) ** 2 + body.b * math.cos(l) ** 2) * G * G


@pytest.mark.parametrize("lstar", [0.0, math.pi / 2])
@pytest.mark.parametrize("order", [4, 6, 8])
def test_frequency_error_falls_like_amplitude_to_the_order(lstar, order):
    """(B4): truncated at degree N, omega_l errs by O(amplitude^N): the measured slope of
    log(error) against log(amplitude) (0.025 .. 0.1 rad) is N within 0.3."""
    nf = birkhoff_normal_form(PAPER, 1.0, order=order, lstar=lstar)
    amps = np.array([0.025, 0.05, 0.1])
    err = []
    for amp in amps:
        h = _level(PAPER, lstar, amp)
        f = euler_poinsot_frequencies(PAPER, h, 1.0)
        w_l, w_g = _predicted(nf, h)
        err.append(abs(w_l - 2 * math.pi / f.period) / (2 * math.pi / f.period))
        assert w_g == pytest.approx(f.g_rate, rel=1e-8)
    slope = np.polyfit(np.log(amps), np.log(err), 1)[0]
    assert abs(slope - order) < 0.3, (slope, err)


@pytest.mark.parametrize("lstar", [0.0, math.pi / 2])
@pytest.mark.parametrize("order", [10, 12])
def test_high_orders_fall_like_amplitude_to_the_order(lstar, order):
    """The terms of degree 10 and 12 (the Lie series' third and later brackets reach them):
    against the closed form at 0.15, 0.2, 0.3 rad, where their error is above rounding, the
    fitted slope is N within 0.4 (measured 10.21-10.28, 12.22-12.29). Keeping only three
    brackets of each Lie series leaves N <= 8 exact but gives slopes 7.4-8.0 here."""
    nf = birkhoff_normal_form(PAPER, 1.0, order=order, lstar=lstar)
    amps = np.array([0.15, 0.2, 0.3])
    err = []
    for amp in amps:
        h = _level(PAPER, lstar, amp)
        w = 2 * math.pi / euler_poinsot_frequencies(PAPER, h, 1.0).period
        I = brentq(lambda a, h=h: float(normal_form_frequency(nf, [a]).energy[0]) - h,
                   0.0, 0.5, xtol=1e-17)
        err.append(abs(abs(float(normal_form_frequency(nf, [I]).omega_l[0])) - w) / w)
    slope = np.polyfit(np.log(amps), np.log(err), 1)[0]
    assert abs(slope - order) < 0.4, (slope, err)


def test_small_oscillations_and_symmetric_centres():
    nf = birkhoff_normal_form(PAPER, 1.0, order=6, lstar=0.0)
    a, b, c = PAPER.a, PAPER.b, PAPER.c
    assert abs(float(nf.omega0)) == pytest.approx(math.sqrt((b - a) * (b - c)), rel=1e-14)
    twin = birkhoff_normal_form(PAPER, 1.0, order=6, lstar=math.pi)
    np.testing.assert_allclose(twin.coefficient, nf.coefficient, rtol=1e-12)
    # homogeneity: omega0 ~ G, c_k ~ G^(2 - k)
    big = birkhoff_normal_form(PAPER, 2.0, order=6, lstar=0.0)
    k = nf.power.values
    np.testing.assert_allclose(big.coefficient, nf.coefficient * 2.0 ** (2 - k), rtol=1e-10)


def test_normal_form_against_naff():
    """An orbit at 0.15 rad from the rotation about x, integrated (mu = 0) and analysed by
    NAFF: omega_l and omega_g of the order-10 normal form within 1e-7."""
    nf = birkhoff_normal_form(PAPER, 1.0, order=10, lstar=math.pi / 2)
    amp = 0.15
    h = _level(PAPER, math.pi / 2, amp)
    w_l, w_g = _predicted(nf, h)
    y0 = from_andoyer([math.pi / 2 + amp, 0.0, 0.0, 1.0, 0.0])
    ds = orbit_frequencies(PAPER.with_mu(0.0), y0, 60 * 2 * math.pi / w_l, n_samples=16385,
                           engine="numba")
    assert float(ds.omega_l[0]) == pytest.approx(w_l, rel=1e-7)
    assert float(ds.omega_g[0]) == pytest.approx(w_g, rel=1e-7)


@pytest.mark.parametrize("lstar", [math.pi / 2, 0.0])
def test_frequency_error_against_naff_falls_like_amplitude_to_the_order(lstar):
    """Issue 28 item 3's check, on integrated orbits: NAFF's omega_l of free-top orbits
    started 0.05, 0.1, 0.2 rad from the rotation (mu = 0, numba engine, 60 periods) against
    the normal form of degree N = 4, 6, 8. The fitted slope of log(error) against
    log(amplitude) is N within 0.3 (measured 4.07/4.08, 6.05/6.06, 8.04/8.06 about x/y),
    over the points 30 times above NAFF's own error (NAFF vs the closed form <= 4e-11)."""
    amps = np.array([0.05, 0.1, 0.2])
    measured = []
    for amp in amps:
        h = _level(PAPER, lstar, amp)
        w_l = 2 * math.pi / euler_poinsot_frequencies(PAPER, h, 1.0).period
        y0 = from_andoyer([lstar + amp, 0.0, 0.0, 1.0, 0.0])
        ds = orbit_frequencies(PAPER.with_mu(0.0), y0, 60 * 2 * math.pi / w_l,
                               n_samples=16385, engine="numba")
        measured.append(abs(float(ds.omega_l[0])))
        assert measured[-1] == pytest.approx(w_l, rel=1e-10)    # NAFF's floor
    for order in (4, 6, 8):
        nf = birkhoff_normal_form(PAPER, 1.0, order=order, lstar=lstar)
        err = np.array([abs(_predicted(nf, _level(PAPER, lstar, a))[0] - w) / w
                        for a, w in zip(amps, measured, strict=True)])
        ok = err > 1e-10
        assert ok.sum() >= 2, (order, err)
        slope = np.polyfit(np.log(amps[ok]), np.log(err[ok]), 1)[0]
        assert abs(slope - order) < 0.3, (order, slope, err)


@pytest.mark.parametrize("kwargs, match", [
    ({"order": 5}, "even"), ({"order": 30}, "order"), ({"lstar": 0.3}, "lstar"),
    ({"G": -1.0}, "G")])
def test_bad_input(kwargs, match):
    args = {"G": 1.0, **kwargs}
    G = args.pop("G")
    with pytest.raises(ValueError, match=match):
        birkhoff_normal_form(PAPER, G, **args)
    with pytest.raises(ValueError, match="middle axis"):
        birkhoff_normal_form(RigidBody.lagrange(2.0, 1.0, 1.0), 1.0)


def test_homogeneity_over_the_range_of_G_and_refusal_beyond():
    """(B5): c_k(G) = c_k(1) G^(2-k), omega0 ~ G, H* ~ G^2, dc_k/dG = (2-k) c_k/G, over
    G = 1e-25 .. 1e25 at order 24 (1e-100 .. 1e100 at order 8) to rounding; the Lie series
    run at G itself agrees where its algebra holds the numbers (G = 0.01 .. 100); G = 1e120
    at order 8 (its c_4 ~ 1e-240, dc_4/dG below the doubles) is refused, naming G."""
    from andoyer.analysis.resonance.birkhoff import _normalise, _taylor, _to_complex

    for order, Gs in ((24, np.logspace(-25, 25, 11)), (8, np.logspace(-100, 100, 9))):
        ref = birkhoff_normal_form(PAPER, 1.0, order=order)
        k = ref.power.values
        for G in Gs:
            nf = birkhoff_normal_form(PAPER, float(G), order=order)
            np.testing.assert_allclose(nf.coefficient / G ** (2.0 - k), ref.coefficient,
                                       rtol=1e-14)
            odd = k != 2
            np.testing.assert_allclose(nf.g_coefficient[odd] * G / (2.0 - k[odd])
                                       / nf.coefficient[odd], 1.0, rtol=1e-14)
            assert float(nf.g_coefficient[~odd][0]) == 0.0
            assert float(nf.omega0) == pytest.approx(G * float(ref.omega0), rel=1e-15)
            assert float(nf.H_star) == pytest.approx(G * G * float(ref.H_star), rel=1e-15)
            f = normal_form_frequency(nf, [0.01 * G])
            f1 = normal_form_frequency(ref, [0.01])
            assert float(f.energy[0]) == pytest.approx(G * G * float(f1.energy[0]), rel=1e-14)
            assert float(f.omega_l[0]) == pytest.approx(G * float(f1.omega_l[0]), rel=1e-14)
            assert float(f.omega_g[0]) == pytest.approx(G * float(f1.omega_g[0]), rel=1e-14)
    for G in (0.01, 0.7, 3.0, 100.0):   # the algebra at G itself
        h = _taylor(PAPER, 0.0, G, 8)
        poly, w0 = _to_complex(h, 8)
        direct = _normalise(poly, w0, 8)
        np.testing.assert_allclose(birkhoff_normal_form(PAPER, G, order=8).coefficient,
                                   direct, rtol=1e-11)
    with pytest.raises(ValueError, match=r"G = 1e\+120 .*order 8"):
        birkhoff_normal_form(PAPER, 1e120)
    with pytest.raises(ValueError, match=r"G = 1e-120"):
        birkhoff_normal_form(PAPER, 1e-120, order=24)
