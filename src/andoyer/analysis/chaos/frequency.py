r"""Frequency analysis: Laskar's NAFF and the frequency drift of an orbit.

A quasi-periodic signal :math:`z(t) = \sum_j a_j e^{i \omega_j t}` sampled on
:math:`[0, T]` is decomposed one line at a time by NAFF [1]_, [2]_: the strongest line
is the maximum of :math:`|\phi(\omega)|`,
:math:`\phi(\omega) = \frac1T \int_0^T z(t)\, \chi_p(t)\, e^{-i\omega t}\, dt` with the
Hann window :math:`\chi_p` of order ``p``, its amplitude the projection of ``z`` on
:math:`e^{i\omega t}` (orthogonalised against the lines found before), and the line is
subtracted before the next is sought. The error of a frequency decreases like
:math:`T^{-(2p+2)}` for a quasi-periodic signal [2]_.

The decomposition is ``nafflib`` (xsuite's NAFF, maintained, Numba-compiled), wrapped
here in this package's conventions: angular frequencies in rad per time unit (not tunes),
the sign of :math:`e^{+i\omega t}`, complex amplitudes of ``z`` itself. Measured against
exact signals (4001 samples, three lines, ``p = 2``): frequencies to 9e-15, the same
accuracy as a hand-written NAFF locating the maximum as the root of
:math:`d|\phi|^2/d\omega` by Brent's method (7e-15), and faster (benchmarks/NOTES.md,
"NAFF") -- so the library is used. Against the Euler-Poinsot motion in closed form
(:func:`andoyer.analysis.unperturbed.euler_poinsot.euler_poinsot_frequencies`): see
:func:`orbit_frequencies`.

The *frequency drift* of an orbit, :math:`|\omega^{(1)} - \omega^{(2)}| / |\omega|`
between its two halves, is the diffusion indicator of frequency-map analysis [1]_: at
the accuracy of NAFF on a torus, orders of magnitude larger in a chaotic zone.

References
----------
.. [1] J. Laskar, "Frequency analysis for multi-dimensional systems. Global dynamics and
   diffusion", Physica D 67, 257-281 (1993).
.. [2] J. Laskar, "Introduction to frequency map analysis", in *Hamiltonian Systems with
   Three or More Degrees of Freedom*, NATO ASI C 533, 134-150 (1999).

Examples
--------
>>> import numpy as np
>>> t = np.linspace(0.0, 400.0, 4001)
>>> z = 1.0 * np.exp(1j * 0.731 * t) + 0.3 * np.exp(-1j * 1.912 * t)
>>> lines = naff(z, t[1] - t[0], n_freq=2)
>>> np.round(lines.frequency, 10), np.round(np.abs(lines.amplitude), 10)
(array([ 0.731, -1.912]), array([1. , 0.3]))
"""

from __future__ import annotations

import math
import numbers
from typing import NamedTuple

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.body import RigidBody, checks_body
from andoyer.charts.euler_poisson import STATE
from andoyer.integrate.results import describe_variables, provenance
from andoyer.validation import checks_arguments, integer, positive

__all__ = ["Lines", "naff", "frequency_drift", "orbit_frequencies", "frequency_map",
           "resonance_label", "RESONANCE_ORDER", "RESONANCE_DRIFT", "MIN_PERIODS",
           "ROTATION_RTOL", "MAX_WINDOW"]


#: Highest order of the Hann window: its weight ``(1 + cos)^p`` reaches ``2^p``, which
#: overflows near p = 1024, and nafflib's normalisation takes factorials of ``2 p`` (a
#: window of order 1e300 never returned). Orders above a few tens only narrow the window.
MAX_WINDOW = 100


class Lines(NamedTuple):
    """Spectral lines of a signal, strongest first.

    Parameters
    ----------
    frequency : ndarray of float, shape (n_freq,)
        Angular frequencies ``omega_j`` (rad per body time unit), strongest line first.
    amplitude : ndarray of complex, shape (n_freq,)
        Complex amplitudes ``a_j`` of the signal ``z ~ sum_j a_j exp(i omega_j t)``.
    T : float
        Length of the analysed interval, ``(n - 1) dt``.
    """

    frequency: NDArray[np.float64]    #: angular frequencies omega_j (rad per time unit)
    amplitude: NDArray[np.complex128]  #: complex amplitudes a_j of z
    T: float                           #: length of the analysed interval


def _signal(z: ArrayLike) -> NDArray[np.complex128]:
    """``z`` as one finite complex signal of at least 16 samples, or ``ValueError``:
    a 2-D array is several signals, not one (it is not flattened)."""
    try:
        arr = np.asarray(z)
    except ValueError:
        raise ValueError("z must be a 1-D array of samples (a ragged sequence was "
                         "given)") from None
    if arr.dtype.kind not in "iufc":
        raise ValueError(f"z must hold real or complex numbers, got {arr.dtype} values")
    if arr.ndim != 1:
        raise ValueError(f"z must be one signal: a 1-D array of samples, got shape "
                         f"{arr.shape} (analyse each row separately)")
    if arr.size < 16:
        raise ValueError(f"z needs at least 16 samples, got {arr.size}")
    zz = arr.astype(np.complex128)
    if not np.all(np.isfinite(zz)):
        raise ValueError("z must be finite (NaN or infinity among the samples)")
    return zz


@checks_arguments(ranges={"n_freq": "count", "window": "count"})
def naff(z: ArrayLike, dt: float, n_freq: int = 1, *, window: int = 2) -> Lines:
    """The ``n_freq`` strongest spectral lines of a uniformly sampled complex signal.

    Parameters
    ----------
    z : array_like, shape (n,)
        Samples ``z(k dt)``, ``k = 0 .. n-1``; complex (a real signal has its lines at
        ``+-omega``).
    dt : float
        Sampling step (> 0).
    n_freq : int
        Number of lines (>= 1).
    window : int
        Order ``p`` of the Hann window (1 to :data:`MAX_WINDOW`; 2 by default, as in
        nafflib).

    Returns
    -------
    Lines
        Frequencies in ``[-pi/dt, pi/dt)``, amplitudes, and ``T = (n - 1) dt``.

    Raises
    ------
    ValueError
        For fewer than 16 samples, non-finite samples, a signal zero everywhere or a bad
        ``dt``, ``n_freq`` or ``window``. The signal's scale does not matter (it is
        analysed as ``z / max |z|``: 1e300 e^{0.3 i t} has its line at 0.3).
    """
    import nafflib

    from andoyer.kernels.cache import cache_library_kernels

    cache_library_kernels("nafflib")    # its Numba functions, else compiled per process
    zz = _signal(z)
    n = zz.size
    dt = positive("dt", dt)
    n_freq = integer("n_freq", n_freq, 1, n // 4)
    window = integer("window", window, 1, MAX_WINDOW)
    if not math.isfinite((n - 1) * dt):
        raise ValueError(f"dt = {dt!r}: the signal length (n - 1) dt overflows")
    # The analysis is linear in z: run it on z / max|z| (a signal of 1e300 overflows its
    # windowed sums, one of 1e-300 underflows them) and scale the amplitudes back.
    scale = float(np.max(np.abs(zz)))
    if scale == 0.0:
        raise ValueError("z is zero at every sample: it has no spectral line")
    zz = (zz.real / scale) + 1j * (zz.imag / scale)  # not complex division: scale^2
    # nafflib analyses x - i px with tunes Q in turns per sample: omega = -2 pi Q / dt
    # and the amplitudes are conjugated.
    A, Q = nafflib.harmonics(zz.real, zz.imag, num_harmonics=int(n_freq),
                             window_order=int(window), window_type="hann")
    omega = -2.0 * math.pi * np.asarray(Q, dtype=float) / dt
    if not np.all(np.isfinite(omega)):
        raise ValueError(f"z: no {n_freq} spectral line(s) could be resolved (the analysis "
                         "gave non-finite frequencies)")
    omega = (omega + math.pi / dt) % (2.0 * math.pi / dt) - math.pi / dt
    amplitude = (np.conj(np.asarray(A, dtype=np.complex128)) * scale).astype(np.complex128)
    return Lines(omega, amplitude, float((n - 1) * dt))


@checks_arguments(ranges={"window": "count"})
def frequency_drift(z: ArrayLike, dt: float, *, window: int = 2) -> float:
    """Relative change of the main frequency between the two halves of a signal.

    The diffusion indicator of frequency-map analysis: ``|w1 - w2| / |w|`` with ``w1``,
    ``w2`` the strongest lines (:func:`naff`) of the first and the second half (for a
    real signal, whose lines come in pairs ``+-omega``, their absolute values).

    Parameters
    ----------
    z : array_like, shape (n,)
        The signal sampled at equal steps (real or complex; at least 64 samples).
    dt : float
        The sampling step (body time units, > 0).
    window : int, default 2
        Order of the Hann window of :func:`naff`.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 400.0, 4001)
    >>> frequency_drift(np.exp(1j * 0.731 * t), t[1] - t[0]) < 1e-12
    True
    """
    zz = _signal(z)
    dt = positive("dt", dt)
    if zz.size < 32:
        raise ValueError(f"z needs at least 32 samples (16 in each half), got {zz.size}")
    half = zz.size // 2
    w1 = naff(zz[: half + 1], dt, window=window).frequency[0]
    w2 = naff(zz[half:], dt, window=window).frequency[0]
    if not np.any(zz.imag):  # a real signal: lines at +-omega, either may come first
        w1, w2 = abs(w1), abs(w2)
    scale = max(abs(w1), abs(w2))
    if scale == 0.0:
        return 0.0
    return float(abs(w1 - w2) / scale)


#: Largest order ``|k1| + |k2|`` of a labelled resonance ``k1 omega_l + k2 omega_g = 0``.
RESONANCE_ORDER = 8
#: Orbits whose frequencies drift more than this get no resonance label (not a torus).
RESONANCE_DRIFT = 1e-6
#: Fewest periods of its slowest motion a signal must hold for its frequencies: shorter,
#: the strongest line is the window's, not the motion's (measured on the free top: 34x
#: off below one period, 33 % off at 1.3 periods, both with a drift of exactly 0).
MIN_PERIODS = 4.0
#: ``max L - min L <= ROTATION_RTOL |G|``: a permanent rotation (no (l, L) motion).
ROTATION_RTOL = 1e-9


def resonance_label(nu: float, tol: float, max_order: int = RESONANCE_ORDER) -> str:
    """``"p:q"`` when the rotation number ``nu`` (turns of g per period of (l, L)) is
    within ``tol`` of ``p/q`` with ``|p| + q <= max_order`` (lowest order first), else
    ``""`` (also for a NaN or infinite ``nu``: an orbit without a rotation number).

    Parameters
    ----------
    nu : float
        The frequency ratio ``omega_g / omega_l`` (turns of g per period of (l, L)).
    tol : float
        Largest distance ``|nu - p/q|`` that names a resonance (> 0).
    max_order : int, default 8
        Largest order ``|p| + q`` tried (:data:`RESONANCE_ORDER`).

    Examples
    --------
    >>> resonance_label(0.5 + 1e-9, 1e-6), resonance_label(0.4142, 1e-6)
    ('1:2', '')
    """
    if isinstance(nu, bool) or not isinstance(nu, numbers.Real):
        raise ValueError(f"nu must be a real number, got {nu!r}")
    tol = positive("tol", tol)
    max_order = integer("max_order", max_order, 1, 1000)
    if not math.isfinite(nu):
        return ""
    for order in range(1, max_order + 1):
        for q in range(1, order + 1):
            p = round(nu * q)
            if abs(p) + q == order and abs(nu - p / q) <= tol:
                return f"{p}:{q}"
    return ""


@checks_body(ranges={"t_end": "time", "n_samples": "count", "window": "count"})
def orbit_frequencies(body: RigidBody, y0: ArrayLike, t_end: float, *,
                      n_samples: int = 8193, chart: str = "euler_poisson",
                      engine: str | None = None, window: int = 2,
                      progress: bool | None = None) -> xr.Dataset:
    """Fundamental frequencies of orbits by NAFF: the (l, L) motion and the rate of g.

    Each orbit is integrated (:func:`andoyer.integrate.propagate`) on ``n_samples``
    equally spaced times of ``[0, t_end]``; the frequency of the ``(l, L)`` motion --
    equally of ``(theta1, J1)`` -- is the strongest line of ``L(t) - <L>`` (``L = G3``,
    an oscillation about 0 when Oz is the middle axis, as on every Hess body), and the
    rate of ``g`` the strongest line of ``exp(i g(t))``. At ``mu = 0`` they are
    ``2 pi / T`` and ``<dg/dt>`` of :func:`andoyer.analysis.unperturbed.euler_poinsot.
    euler_poinsot_frequencies` (measured: 1.8e-13 and 4e-15 relative over 100 periods,
    32769 samples; 1.1e-11 and 1.2e-13 over 50 periods, 16385 samples).

    Parameters
    ----------
    body : RigidBody
        Oz must be the middle axis of inertia (C the middle moment).
    y0 : array_like, shape (d,) or (n, d)
        Initial states in ``chart`` coordinates.
    t_end : float
        Length of the analysed orbit (tens of periods or more).
    n_samples : int
        Samples (>= 64); ``t_end / n_samples`` must resolve the fastest motion.
    chart, engine :
        As in :func:`andoyer.integrate.propagate`.
    window : int
        Hann window order of :func:`naff`.
    progress : bool, optional
        Progress bar of the integration.

    Returns
    -------
    xarray.Dataset
        Dim ``orbit``: ``omega_l`` (> 0), ``omega_g``, ``frequency_ratio``
        ``omega_g / omega_l`` (turns of g per period of (l, L); about 8 on the paper's
        body), ``rotation_number_g_section`` ``omega_l / omega_g`` (the rotation number of
        the Poincare map of the section ``g = const``: turns of (l, L) per return; its
        inverse), ``period`` ``2 pi / omega_l``, ``drift_l``, ``drift_g``
        (:func:`frequency_drift`), ``resonance`` of ``frequency_ratio``
        (:func:`resonance_label` at 10 times the larger drift, at least 1e-9; none where
        the drift exceeds :data:`RESONANCE_DRIFT`), ``n_periods`` (periods of the
        slowest motion the signal holds), ``status`` and ``y0``. ``status`` flags what
        has no frequency: ``"short"`` (fewer than :data:`MIN_PERIODS` periods of the
        slowest motion: all frequencies NaN), ``"rotation"`` (a permanent rotation, ``L``
        constant within :data:`ROTATION_RTOL` ``|G|``: ``omega_l``, ``period`` NaN,
        ``omega_g`` the rate of the rotation), ``"undefined"`` (``g`` undefined on the
        orbit); ``"ok"`` otherwise.

    Examples
    --------
    The free top (``mu = 0``) on ``|G| = 1``, ``H0 = 0.232``, against its closed form:

    >>> from andoyer.analysis.unperturbed.euler_poinsot import euler_poinsot_frequencies
    >>> body = RigidBody(2.5, 2.0, 2.2, 0.0, (1.0, 0.0, 0.0))
    >>> ds = orbit_frequencies(body, [0.6, 0.8, 0.0, 0.0, 0.0, 1.0], 3000.0, n_samples=8193)
    >>> f = euler_poinsot_frequencies(body, 0.232, 1.0)
    >>> bool(abs(float(ds.omega_g[0]) / f.g_rate - 1.0) < 1e-9)
    True
    """
    from andoyer.integrate.api import propagate

    body.require_middle_axis("orbit_frequencies")
    T = positive("t_end", t_end)
    n_samples = integer("n_samples", n_samples, 64)
    t = np.linspace(0.0, T, n_samples)
    dt = float(t[1] - t[0])
    ds = propagate(body, y0, t, chart=chart, engine=engine, progress=progress)
    L = ds.L_action.values
    g = ds.g_angle.values
    G = ds.G.values if "G" in ds else np.sqrt(ds.G1.values ** 2 + ds.G2.values ** 2
                                              + ds.G3.values ** 2)
    n = L.shape[0]
    out = {k: np.full(n, np.nan) for k in ("omega_l", "omega_g", "drift_l", "drift_g",
                                           "n_periods")}
    status = np.full(n, "undefined", dtype=object)
    for i in range(n):
        zl = L[i] - L[i].mean()
        zg = np.exp(1j * g[i])
        if not (np.all(np.isfinite(zl)) and np.all(np.isfinite(zg))):
            continue  # g undefined somewhere on the orbit (the chart's singular set)
        out["omega_g"][i] = naff(zg, dt, window=window).frequency[0]
        out["drift_g"][i] = frequency_drift(zg, dt, window=window)
        turns_g = T * abs(out["omega_g"][i]) / (2.0 * math.pi)
        if np.ptp(L[i]) <= ROTATION_RTOL * max(float(np.max(G[i])), 1e-300):
            # L stays put: a permanent rotation (a fixed point of (l, L)), whose only
            # motion is g's; a line of L - <L> would be round-off noise.
            status[i] = "rotation"
            out["n_periods"][i] = turns_g
            if turns_g < MIN_PERIODS:
                out["omega_g"][i] = out["drift_g"][i] = np.nan
                status[i] = "short"
            continue
        omega_l = abs(naff(zl, dt, window=window).frequency[0])
        # Periods of (l, L) covered, by the measured line and, independently, by the sign
        # changes of L - <L> (two per period): a signal shorter than a few periods has
        # a meaningless line and a zero drift (both halves see the same window).
        crossings = np.count_nonzero(np.diff(np.signbit(zl)))
        periods = min(T * omega_l / (2.0 * math.pi), 0.5 * crossings, turns_g)
        out["n_periods"][i] = periods
        if not periods >= MIN_PERIODS:
            out["omega_g"][i] = out["drift_g"][i] = np.nan
            status[i] = "short"
            continue
        out["omega_l"][i] = omega_l
        out["drift_l"][i] = frequency_drift(zl, dt, window=window)
        status[i] = "ok"
    with np.errstate(divide="ignore", invalid="ignore"):
        nu = out["omega_g"] / out["omega_l"]
        section_nu = out["omega_l"] / out["omega_g"]
        period_l = 2.0 * math.pi / out["omega_l"]
    drift = np.fmax(out["drift_l"], out["drift_g"])
    tol = np.maximum(10.0 * drift, 1e-9)
    labels = [resonance_label(float(v), float(e)) if d <= RESONANCE_DRIFT else ""
              for v, e, d in zip(nu, tol, drift, strict=True)]
    res = xr.Dataset(
        {"omega_l": ("orbit", out["omega_l"]), "omega_g": ("orbit", out["omega_g"]),
         "frequency_ratio": ("orbit", nu), "rotation_number_g_section": ("orbit", section_nu),
         "period": ("orbit", period_l),
         "drift_l": ("orbit", out["drift_l"]), "drift_g": ("orbit", out["drift_g"]),
         "resonance": ("orbit", np.array(labels, dtype=str)),
         "n_periods": ("orbit", out["n_periods"]),
         "status": ("orbit", np.array(status, dtype=str)),
         "y0": (("orbit", "component"), ds.y0.values if "y0" in ds else
                np.stack([ds[c].values[:, 0] for c in STATE], axis=-1))},
        coords={"orbit": np.arange(n), "component": list(STATE)},
        attrs=provenance(body, engine=ds.attrs.get("engine"), method="NAFF (nafflib), Hann "
                         f"window of order {window}", t_end=T, n_samples=int(n_samples),
                         signals="L(t) - <L> for (l, L); exp(i g(t)) for g",
                         min_periods=MIN_PERIODS, rotation_rtol=ROTATION_RTOL))
    return describe_variables(res, {
        "omega_l": ("\\omega_l", "frequency of the (l, L) motion = of (theta1, J1)",
                    "rad/body time unit", "(9)"),
        "omega_g": ("\\omega_g", "mean rate of g", "rad/body time unit", "(7)"),
        "frequency_ratio": ("\\omega_g/\\omega_l", "omega_g / omega_l: turns of g per "
                            "period of (l, L) (the inverse of rotation_number_g_section)",
                            "1", ""),
        "rotation_number_g_section": ("\\omega_l/\\omega_g", "rotation number of the "
                                      "Poincare map of the section g = const: turns of "
                                      "(l, L) per return, omega_l / omega_g", "1", ""),
        "period": ("T", "period of the (l, L) motion", "body time units", ""),
        "drift_l": ("", "relative change of omega_l between the two halves of the orbit",
                    "1", ""),
        "drift_g": ("", "relative change of omega_g between the two halves of the orbit",
                    "1", ""),
        "resonance": ("p:q", "frequency_ratio near p/q (empty: none of order <= 8)", "1",
                      ""),
        "n_periods": ("", "periods of the slowest motion in the signal ((l, L) or g; g "
                          "alone on a permanent rotation)", "1", ""),
        "status": ("", "ok | short (fewer than min_periods periods of the slowest motion: "
                       "frequencies NaN) | rotation (a permanent rotation: L constant, no "
                       "(l, L) motion, omega_l NaN) | undefined (g undefined on the orbit)",
                   "1", ""),
        "y0": ("y_0", "initial Euler-Poisson state", "1", "(1)")})


@checks_body(ranges={"h": "energy", "M": "action", "n_orbits": "count", "t_end": "time",
             "n_samples": "count", "window": "count"})
def frequency_map(body: RigidBody, h: float, M: float, section: tuple[str, float], *,
                  n_orbits: int = 100, t_end: float = 2000.0, n_samples: int = 8193,
                  engine: str | None = None, window: int = 2,
                  progress: bool | None = None) -> xr.Dataset:
    """Frequency-map analysis over a section plane: rotation numbers and their drift.

    Initial states fill the plane (:func:`andoyer.integrate.fill_section`, one orbit per
    point, the smallest root of the missing action); each orbit's frequencies come from
    :func:`orbit_frequencies`. On a torus the drift is at NAFF's accuracy; in a chaotic
    zone it is orders of magnitude larger (Laskar 1993); resonant tori carry a ``p:q`` label.

    Parameters
    ----------
    body : RigidBody
        Oz the middle axis of inertia.
    h, M : float
        The energy level and the area constant.
    section : (coord, value)
        ``("theta2", v)`` (plane ``(theta1, J1)``) or ``("g", v)`` (plane ``(l, L)``).
    n_orbits : int
        About this many orbits.
    t_end, n_samples, engine, window, progress :
        As in :func:`orbit_frequencies`.

    Returns
    -------
    xarray.Dataset
        :func:`orbit_frequencies`'s variables with the plane coordinates of each seed
        (``plane_x``, ``plane_y`` named in attrs) and ``log10_drift`` (the larger drift).
    """
    from andoyer.integrate.fill import fill_section

    fill = fill_section(body, h, M, section, n_orbits=n_orbits, root="smallest")
    if fill.sizes["orbit"] == 0:
        raise ValueError(f"the level h = {h:g}, M = {M:g} does not meet the plane {section}")
    res = orbit_frequencies(body, fill.y0.values, t_end, n_samples=n_samples,
                            engine=engine, window=window, progress=progress)
    xname = str(fill.attrs.get("plane_x", "theta1"))
    yname = str(fill.attrs.get("plane_y", "J1"))
    for name in (xname, yname):
        if name in fill:
            res[name] = ("orbit", fill[name].values)
            res[name].attrs.update(fill[name].attrs)
    drift = np.fmax(res.drift_l.values, res.drift_g.values)
    with np.errstate(divide="ignore"):
        res["log10_drift"] = ("orbit", np.log10(np.maximum(drift, 1e-300)))
    res.log10_drift.attrs.update(long_name="log10 of the larger frequency drift "
                                           "(diffusion indicator)", units="1")
    res.attrs.update(h=float(h), M=float(M), section_coord=str(section[0]),
                     section_value=float(section[1]), plane_x=xname, plane_y=yname)
    return res
