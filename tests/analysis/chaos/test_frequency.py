"""NAFF and frequency-map analysis against exact signals and the Euler-Poinsot closed form.

Independent routes: synthetic quasi-periodic signals (exact frequencies and amplitudes),
the free top's period and mean rate of g in elliptic integrals
(:mod:`andoyer.analysis.unperturbed.euler_poinsot`), and the chaos indicators (a chaotic orbit's
frequencies drift, a torus's do not).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.chaos.frequency import (
    frequency_drift,
    frequency_map,
    naff,
    orbit_frequencies,
    resonance_label,
)
from andoyer.analysis.unperturbed.euler_poinsot import euler_poinsot_frequencies

FREE = RigidBody(2.5, 2.0, 2.2, 0.0, (1.0, 0.0, 0.0))  # the paper's moments, mu = 0
CHAOTIC_BODY = RigidBody.hess(3.0, 1.0, 2.0, mu=1.0)
#: Hess-chart states on H = 1, M = 0 of CHAOTIC_BODY: in the chaotic layer, on a torus
#: (as in tests/analysis/chaos/test_lyapunov.py, from a 12 x 12 FLI map).
CHAOTIC = [0.2617993877991494, 0.0, 1.0103629710818451, 1.712575169922734, 0.0]
REGULAR = [2.8797932657906435, 0.0, 0.7216878364870322, 1.3852961954031033, 0.0]


def _free_state(h: float) -> np.ndarray:
    """A state on H0 = h, |G| = 1 with G3 = 0."""
    a, b, _ = FREE.params[:3]
    g1 = (b - 2 * h) / (b - a)
    return np.array([math.sqrt(g1), math.sqrt(1 - g1), 0.0, 0.0, 0.0, 1.0])


def test_naff_recovers_exact_lines() -> None:
    t = np.arange(8001) * 0.05
    w = np.array([0.731, -1.912, 2 * 0.731 - 1.912])
    a = np.array([1.0, 0.3j, 0.05 - 0.02j])
    z = (a[None, :] * np.exp(1j * w[None, :] * t[:, None])).sum(axis=1)
    lines = naff(z, 0.05, n_freq=3)
    np.testing.assert_allclose(lines.frequency, w, rtol=0, atol=1e-12)
    np.testing.assert_allclose(lines.amplitude, a, rtol=0, atol=1e-9)
    assert lines.T == pytest.approx(400.0)


@pytest.mark.parametrize("h", [0.21, 0.235])   # about the axis of a, of b
def test_frequencies_match_euler_poinsot(h: float) -> None:
    f = euler_poinsot_frequencies(FREE, h, 1.0)
    ds = orbit_frequencies(FREE, _free_state(h), 50 * f.period, n_samples=16385)
    assert float(ds.omega_l[0]) == pytest.approx(2 * math.pi / f.period, rel=1e-10)
    assert float(ds.omega_g[0]) == pytest.approx(f.g_rate, rel=1e-12)
    assert float(ds.frequency_ratio[0]) == pytest.approx(f.frequency_ratio, rel=1e-10)
    assert float(ds.rotation_number_g_section[0]) == pytest.approx(
        f.rotation_number_g_section, rel=1e-10)
    assert float(ds.drift_l[0]) < 1e-8 and float(ds.drift_g[0]) < 1e-10


def test_accuracy_grows_with_the_length_of_the_orbit() -> None:
    """The error of NAFF falls like T^-(2p+2) = T^-6 (Hann window of order 2)."""
    f = euler_poinsot_frequencies(FREE, 0.21, 1.0)
    w = 2 * math.pi / f.period
    errs = []
    for periods, n in ((10, 2049), (20, 4097)):
        ds = orbit_frequencies(FREE, _free_state(0.21), periods * f.period, n_samples=n)
        errs.append(abs(float(ds.omega_l[0]) / w - 1.0))
    assert errs[1] < errs[0] / 20.0      # 2^6 = 64 in the limit


def test_a_chaotic_orbit_drifts_and_a_torus_does_not() -> None:
    ds = orbit_frequencies(CHAOTIC_BODY, [CHAOTIC, REGULAR], 1000.0, n_samples=8193,
                           chart="hess")
    chaotic, regular = (max(float(ds.drift_l[i]), float(ds.drift_g[i])) for i in (0, 1))
    # measured: torus 6.3e-10, chaotic layer 0.41
    assert regular < 1e-8
    assert chaotic > 1e-3
    assert str(ds.resonance.values[0]) == ""      # no label in the chaotic layer


def test_resonance_labels() -> None:
    assert resonance_label(0.5, 1e-9) == "1:2"
    assert resonance_label(-1.0 / 3.0 + 1e-12, 1e-9) == "-1:3"
    assert resonance_label(math.sqrt(2.0), 1e-9) == ""
    assert resonance_label(float("nan"), 1.0) == ""


def test_frequency_map_over_a_plane() -> None:
    body = RigidBody.paper()
    fm = frequency_map(body, 0.2466, 0.0, ("theta2", 0.0), n_orbits=6, t_end=600.0,
                       n_samples=2049)
    assert fm.sizes["orbit"] >= 4
    for v in ("omega_l", "omega_g", "frequency_ratio", "rotation_number_g_section",
              "log10_drift", "theta1", "J1"):
        assert v in fm and np.all(np.isfinite(fm[v].values)), v
    assert fm.attrs["plane_x"] == "theta1" and fm.omega_l.attrs["units"]


def test_bad_input_is_refused() -> None:
    with pytest.raises(ValueError, match="middle axis"):
        orbit_frequencies(RigidBody(2.0, 2.5, 3.0, 0.0, (1, 0, 0)), [1, 0, 0, 0, 0, 1], 10.0)
    with pytest.raises(ValueError, match="n_samples"):
        orbit_frequencies(FREE, _free_state(0.21), 10.0, n_samples=10)
    with pytest.raises(ValueError, match="t_end"):
        orbit_frequencies(FREE, _free_state(0.21), -1.0)
    with pytest.raises(ValueError, match="at least 16"):
        naff(np.ones(8), 0.1)
    with pytest.raises(ValueError, match="dt"):
        naff(np.ones(64), 0.0)
    with pytest.raises(ValueError, match="finite"):
        naff(np.full(64, np.nan), 0.1)
    assert frequency_drift(np.ones(64, dtype=complex), 0.1) >= 0.0


@pytest.mark.parametrize("periods", [0.2, 1.0, 2.0, 3.3])
def test_a_signal_shorter_than_a_few_periods_is_flagged_not_converged(periods) -> None:
    """Below one period NAFF returned omega_l 34x off with a drift of exactly 0, as if
    converged: such orbits are ``short`` with NaN frequencies and drifts."""
    f = euler_poinsot_frequencies(FREE, 0.232, 1.0)
    y0 = [0.6, 0.8, 0.0, 0.0, 0.0, 1.0]
    ds = orbit_frequencies(FREE, [y0, y0], periods * f.period, n_samples=1025)
    assert list(ds.status.values) == ["short", "short"]
    for v in ("omega_l", "omega_g", "drift_l", "drift_g", "period", "frequency_ratio",
              "rotation_number_g_section"):
        assert np.all(np.isnan(ds[v].values)), v
    assert np.all(ds.n_periods.values < 4.0) and list(ds.resonance.values) == ["", ""]
    long = orbit_frequencies(FREE, y0, 20 * f.period, n_samples=4097)
    assert str(long.status.values[0]) == "ok"
    assert abs(float(long.omega_l[0]) * f.period / (2 * math.pi) - 1.0) < 1e-6
    assert 19.0 < float(long.n_periods[0]) < 21.0


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_permanent_rotations_are_flagged_with_their_rate(axis) -> None:
    """A permanent rotation has no (l, L) motion: it was reported as a torus with
    period = t_end; now ``rotation``, omega_l NaN, omega_g the rotation's rate."""
    y0 = np.zeros(6)
    y0[axis] = 1.5
    y0[3 + (axis + 1) % 3] = 1.0
    ds = orbit_frequencies(FREE, y0, 300.0, n_samples=1025)
    assert str(ds.status.values[0]) == "rotation"
    assert np.isnan(float(ds.omega_l[0])) and np.isnan(float(ds.period[0]))
    if axis < 2:   # about axis 1 or 2, g advances at a_axis G (about axis 3 g is singular)
        rate = FREE.params[axis] * 1.5
        assert abs(float(ds.omega_g[0]) - rate) < 1e-10


def test_naff_takes_one_1d_signal_and_numpy_scalars() -> None:
    t = np.linspace(0.0, 400.0, 4001)
    z = np.exp(1j * 0.731 * t)
    for dt in (np.float32(0.1), np.float64(0.1), np.int64(1)):
        assert np.isfinite(naff(z, dt).frequency[0])
    for bad in (z.reshape(1, -1), z.reshape(-1, 1), np.stack([z, z])):
        with pytest.raises(ValueError, match="1-D"):
            naff(bad, 0.1)
        with pytest.raises(ValueError, match="1-D"):
            frequency_drift(bad, 0.1)
    for bad_dt in (True, "0.1", np.nan, -0.1, 1e306):
        with pytest.raises(ValueError, match="dt"):
            naff(z, bad_dt)
    with pytest.raises(ValueError, match="z must"):
        naff(["x"] * 20, 0.1)


@pytest.mark.parametrize("scale", [1e300, 1.7e308, 1e-300, 1.0])
def test_naff_is_blind_to_the_signal_scale(scale):
    """1e300 e^{0.3 i t}: the windowed sums overflowed and the frequency came out NaN."""
    t = np.arange(512)
    lines = naff(scale * np.exp(0.3j * t), 1.0)
    assert abs(lines.frequency[0] - 0.3) <= 1e-12
    assert abs(abs(lines.amplitude[0]) / scale - 1.0) <= 1e-10


def test_naff_refuses_a_signal_without_a_line():
    with pytest.raises(ValueError, match="^z is zero"):
        naff(np.zeros(64), 1.0)
