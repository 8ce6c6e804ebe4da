"""The figure of one orbit's NAFF frequencies reads them right: L folded on the measured
period falls on one curve (a period 1 % off smears it), and g - omega_g t stays bounded
(a rate 1 % off leaves a slope)."""

import numpy as np

from andoyer import RigidBody
from andoyer.analysis.chaos.frequency import orbit_frequencies
from andoyer.integrate import propagate
from andoyer.plot.frequency import plot_orbit_frequencies

STATE = [0.3, 0.0, 0.3, 1.0, 0.0]
T_END, N = 1500.0, 4097


def _spread(phase: np.ndarray, L: np.ndarray, bins: int = 200) -> float:
    """Largest range of L among samples of one phase bin (a fold's thickness)."""
    which = np.minimum((phase * bins).astype(int), bins - 1)
    return max(float(np.ptp(L[which == b])) for b in range(bins) if np.any(which == b))


def test_the_figure_reads_the_measured_frequencies():
    body = RigidBody.paper()
    freq = orbit_frequencies(body, STATE, T_END, n_samples=N, chart="andoyer",
                             engine="numba")
    orbit = propagate(body, STATE, np.linspace(0.0, T_END, N), chart="andoyer",
                      engine="numba", progress=False)
    assert str(freq.status.values[0]) == "ok"
    fig = plot_orbit_frequencies(orbit, freq)
    phase, L = (np.asarray(v) for v in fig.axes[0].lines[0].get_data())
    residual = np.asarray(fig.axes[1].lines[0].get_ydata())
    L_range = float(np.ptp(L))
    spread = _spread(phase, L)
    assert spread < 0.1 * L_range

    # The same figure with frequencies 1 % off: the fold smears, g - omega_g t drifts.
    wrong = freq.copy()
    wrong["period"] = freq.period * 1.01
    wrong["omega_g"] = freq.omega_g * 1.01
    bad = plot_orbit_frequencies(orbit, wrong)
    bad_phase, bad_L = (np.asarray(v) for v in bad.axes[0].lines[0].get_data())
    assert _spread(bad_phase, bad_L) > 4.0 * spread
    bad_residual = np.asarray(bad.axes[1].lines[0].get_ydata())
    assert np.ptp(bad_residual) > 5.0 * np.ptp(residual)
    assert [ax.get_title()[:3] for ax in fig.axes] == ["(a)", "(b)"]
