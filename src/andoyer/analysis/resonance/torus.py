r"""The free top on its tori: action-angle samples, the perturbation's Fourier coefficients.

At ``mu = 0`` (Eq. (9)) ``G`` is constant and the body-frame momentum moves on the
closed curves of ``H0 = h``; the reduced system (``M`` fixed) is integrable with the
tori labelled, on one energy level, by ``G``. On each torus the canonical angles are

* ``phi1 = omega_l t`` (mod 2 pi), the phase of the ``(l, L)`` motion, ``omega_l = 2 pi / T``;
* ``phi2 = g - rho(phi1)``, advancing uniformly at ``omega_g = <dg/dt>``: ``rho`` is the
  periodic part of ``g(t)``, ``dg/dt = dH0/dG = G (a G1^2 + b G2^2) / (G1^2 + G2^2)``
  (:mod:`andoyer.analysis.unperturbed.euler_poinsot`), integrated here spectrally (exact to rounding
  for the analytic, periodic motion).

The origin ``phi1 = 0`` is the state with zero momentum on the middle axis 3 (``L = 0``,
``sn = 0``), the other two components positive-signed as :func:`reference_momentum`
chooses; ``phi2`` is fixed by ``rho(0) = 0``. The phase of any body-frame momentum on
its own free-top orbit is :func:`free_top_phase` (Jacobi's amplitude, the inverse of
:func:`~andoyer.analysis.unperturbed.euler_poinsot.euler_poinsot_momentum`).

The perturbation is ``V = (H - H0) / mu = (r, gamma)``, taken from the one Hamiltonian
:func:`andoyer.charts.euler_poisson.hamiltonian_expr` (evaluated at ``mu = 1`` and
``mu = 0``), never written again here. On a ``(phi1, phi2)`` grid its Fourier
coefficients ``V_k``, ``V = sum_k V_k exp(i (k1 phi1 + k2 phi2))``, follow by a 2-D FFT.
``gamma`` depends on ``g`` only through ``cos g``, ``sin g`` (the rotation chain of
:mod:`andoyer.charts.andoyer_deprit`), so ``V_k = 0`` for ``|k2| >= 2``: the grid in
``phi2`` needs four points, and the FFT's ``k2 = +-2`` columns measure round-off.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import ellipk

from andoyer.analysis.unperturbed.euler_poinsot import (
    elliptic_f,
    euler_poinsot_frequencies,
    euler_poinsot_momentum,
)
from andoyer.body import RigidBody, checks_body
from andoyer.charts.andoyer_deprit import from_andoyer
from andoyer.charts.euler_poisson import hamiltonian_expr
from andoyer.validation import finite, integer, positive, real_array

__all__ = ["Torus", "sample_torus", "free_top_phase", "MAX_FOURIER"]

#: Largest number of samples of a torus in ``phi1`` (the FFT is refined by doubling
#: until the last quarter of the spectrum is below 1e-13 of its peak, up to this).
MAX_FOURIER = 2 ** 16


class Torus(NamedTuple):
    """A torus of the free top on ``H0 = h``, ``|G| = G``, sampled in its angle ``phi1``.

    Parameters
    ----------
    h : float
        Energy ``H0 = h`` of the free top.
    G : float
        ``|G|``.
    M : float
        Area constant ``(G, gamma) = M``.
    axis : int
        Body axis (1, 2, 3) the momentum turns about.
    sign : int
        Sign of the momentum on that axis.
    omega_l : float
        ``2 pi / T``: frequency of the (l, L) motion (rad per body time unit).
    omega_g : float
        ``<dg/dt>``: mean rate of g.
    phi1 : ndarray, shape (n,)
        The samples' phase ``2 pi j / n``.
    momentum : ndarray, shape (n, 3)
        Body-frame momentum ``G`` at ``phi1``.
    l, L : ndarray, shape (n,)
        Andoyer-Deprit angle ``l`` and action ``L = G3`` at ``phi1``.
    rho : ndarray, shape (n,)
        ``g - phi2`` at ``phi1`` (``rho(0) = 0``).
    ldot, gdot : ndarray, shape (n,)
        ``dl/dt`` and ``dg/dt`` at ``phi1``.
    """

    h: float
    G: float
    M: float
    axis: int                    #: body axis (1, 2, 3) the momentum turns about
    sign: int                    #: sign of the momentum on that axis
    omega_l: float               #: 2 pi / T
    omega_g: float               #: <dg/dt>
    phi1: NDArray[np.float64]    #: the samples' phase, 2 pi j / n
    momentum: NDArray[np.float64]  #: (n, 3) body-frame momentum at phi1
    l: NDArray[np.float64]       #: the Andoyer angle l at phi1
    L: NDArray[np.float64]       #: L = G3 at phi1
    rho: NDArray[np.float64]     #: g - phi2 at phi1 (rho(0) = 0)
    ldot: NDArray[np.float64]    #: dl/dt at phi1
    gdot: NDArray[np.float64]    #: dg/dt at phi1

    @property
    def rotation_number(self) -> float:
        """``omega_l / omega_g``: the rotation number of the section map ``g = const``."""
        return self.omega_l / self.omega_g


def _sorted_axes(body: RigidBody) -> tuple[int, int, int, float, float, float]:
    inv = np.array([body.a, body.b, body.c])
    ip, iq, ir = (int(i) for i in np.argsort(inv)[::-1])
    return ip, iq, ir, float(inv[ip]), float(inv[iq]), float(inv[ir])


def regimes(body: RigidBody, h: float, M: float) -> list[tuple[int, float, float]]:
    """The free-top regimes on ``H0 = h`` at area constant ``M``: ``(axis, G_lo, G_hi)``.

    ``axis`` (1, 2 or 3) is the body axis of the permanent rotation the tori surround;
    ``G`` runs over the open interval between that rotation (``2h = p G^2`` or
    ``r G^2``) and the separatrix ``2h = q G^2``, cut to ``G > |M|`` (``g`` is undefined
    at ``G = |M|``). Needs Oz the middle axis (``q = c``).
    """
    ip, iq, ir, p, q, r = _sorted_axes(body)
    if iq != 2:
        raise ValueError("the resonances are computed in the Andoyer-Deprit chart, which "
                         "needs Oz the middle axis of inertia (C the middle moment); got "
                         f"A={body.A}, B={body.B}, C={body.C}")
    if not h > 0.0:
        raise ValueError(f"h must be > 0 (the free top's energy), got {h!r}")
    g_sep = math.sqrt(2.0 * h / q)
    out = []
    for axis, lo, hi in ((ip, math.sqrt(2.0 * h / p), g_sep), (ir, g_sep, math.sqrt(2.0 * h / r))):
        lo = max(lo, abs(M))
        if hi > lo * (1.0 + 1e-12):
            out.append((axis + 1, lo, hi))
    return out


def reference_momentum(body: RigidBody, h: float, G: float, sign: int = 1
                       ) -> tuple[NDArray[np.float64], int]:
    """The body-frame momentum at ``phi1 = 0`` on ``H0 = h``, ``|G| = G``, and its axis.

    ``G3 = 0`` (the middle axis: ``sn = 0``), the component on the axis of the rotation
    (the ``dn`` one of :func:`~andoyer.analysis.unperturbed.euler_poinsot.euler_poinsot_momentum`)
    of sign ``sign``, the third (the ``cn`` one) of the sign Euler's equations give
    ``cn = +1``: Jacobi's amplitude is 0 there.
    """
    ip, iq, ir, p, q, r = _sorted_axes(body)
    inv = (body.a, body.b, body.c)
    x = 2.0 * h / (G * G)
    A1, A2 = max(x - r, 0.0), max(p - x, 0.0)
    g = np.zeros(3)
    about_p = x > q
    i_dn, i_cn = (ip, ir) if about_p else (ir, ip)
    a_dn, a_cn = (A1, A2) if about_p else (A2, A1)
    j, k = (iq + 1) % 3, (iq + 2) % 3
    s_cn = math.copysign(1.0, inv[k] - inv[j]) * sign
    g[i_dn] = sign * G * math.sqrt(a_dn / (p - r))
    g[i_cn] = s_cn * G * math.sqrt(a_cn / (p - r))
    return g, i_dn + 1


@checks_body
def free_top_phase(body: RigidBody, momentum: ArrayLike) -> NDArray[np.float64]:
    """The phase ``phi1`` in ``(-pi, pi]`` of body-frame momenta on their free-top orbits.

    Jacobi's amplitude ``phi`` of the state (``sn = sin phi``, ``cn = cos phi``, the
    notation of :func:`~andoyer.analysis.unperturbed.euler_poinsot.euler_poinsot_momentum`),
    its argument ``theta = F(phi | k^2)`` (:func:`elliptic_f`) and
    ``phi1 = pi theta / (2 K)``; ``phi = 0`` at the reference state of the same regime
    and sign (:func:`reference_momentum`). Along the free motion ``phi1`` grows as
    ``2 pi t / T``.

    Parameters
    ----------
    body : RigidBody
        Distinct moments; ``mu`` is ignored.
    momentum : array_like, shape (3,) or (n, 3)
        Body-frame angular momenta ``(G1, G2, G3)``, finite, off the separatrices
        ``2 H0 = q |G|^2`` (there the phase is undefined) and off the permanent rotations.

    Returns
    -------
    ndarray, shape (n,)

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody(2.5, 2.0, 2.2, 0.0, (1.0, 0.0, 0.0))
    >>> T = sample_torus(body, 0.2466, 1.0, 0.0, n=64)
    >>> bool(np.allclose(free_top_phase(body, T.momentum[:5]), T.phi1[:5], atol=1e-13))
    True
    """
    g = np.atleast_2d(real_array("momentum", momentum))
    if g.ndim != 2 or g.shape[1] != 3 or not np.all(np.isfinite(g)):
        raise ValueError(f"momentum must be finite (G1, G2, G3) rows, shape (n, 3), got "
                         f"shape {np.shape(momentum)}")
    ip, iq, ir, p, q, r = _sorted_axes(body)
    if not p > q > r:
        raise ValueError(f"free_top_phase needs three distinct moments, got A={body.A}, "
                         f"B={body.B}, C={body.C}")
    inv = np.array([body.a, body.b, body.c])
    Gp, u, Gr = g[:, ip], g[:, iq], g[:, ir]
    A1 = (p - r) * Gp**2 + (q - r) * u**2
    A2 = (p - q) * u**2 + (p - r) * Gr**2
    B1, B2 = q - r, p - q
    about_p = (p - q) * Gp**2 - (q - r) * Gr**2 > 0.0
    m = np.where(about_p, B1 * A2 / (B2 * A1), B2 * A1 / (B1 * A2))
    U = np.sqrt(np.where(about_p, A2 / B2, A1 / B1))
    g_cn = np.where(about_p, Gr, Gp)
    g_dn = np.where(about_p, Gp, Gr)
    amp_cn = np.sqrt(np.where(about_p, A2, A1) / (p - r))
    j, k = (iq + 1) % 3, (iq + 2) % 3
    sq = math.copysign(1.0, inv[k] - inv[j])
    s_cn = sq * np.sign(g_dn)
    phi = np.arctan2(u / U, s_cn * g_cn / amp_cn)   # 0 at the reference state
    K = ellipk(m)
    bad = ~((m >= 0.0) & (m < 1.0) & (U > 0.0) & (amp_cn > 0.0))
    if np.any(bad):
        raise ValueError(f"momentum: {int(bad.sum())} of {bad.size} rows are on a separatrix "
                         "2 H0 = q |G|^2 or a permanent rotation (no phase there)")
    theta = elliptic_f(phi, m)
    return np.asarray(np.remainder(math.pi * theta / (2.0 * K) + math.pi, 2 * math.pi)
                      - math.pi)


def perturbation(body: RigidBody, states: NDArray[np.float64]) -> NDArray[np.float64]:
    """``V = (H - H0) / mu = (r, gamma)`` at Euler-Poisson states, from
    :func:`andoyer.charts.euler_poisson.hamiltonian_expr` at ``mu = 1`` minus ``mu = 0``."""
    a, b, c, _mu, e1, e2, e3 = body.params
    G1, G2, G3, g1, g2, g3 = np.moveaxis(states, -1, 0)
    return np.asarray(hamiltonian_expr(G1, G2, G3, g1, g2, g3, a, b, c, 1.0, e1, e2, e3)
                      - hamiltonian_expr(G1, G2, G3, g1, g2, g3, a, b, c, 0.0, e1, e2, e3))


@checks_body(ranges={"h": "energy", "G": "length", "M": "action", "n": "count"})
def sample_torus(body: RigidBody, h: float, G: float, M: float, sign: int = 1,
                 n: int = 256) -> Torus:
    """The torus ``(h, G)`` of the free top, sampled at ``n`` phases ``phi1 = 2 pi j/n``.

    Parameters
    ----------
    body : RigidBody
        Oz the middle axis of inertia; ``mu`` is ignored.
    h : float
        Energy ``H0``; ``r G^2 < 2h < p G^2``, ``2h != q G^2`` (the regime follows).
    G : float
        ``|G|`` (> 0).
    M : float
        The area constant (``|M| < G``): it enters ``gamma`` (Eq. (5)-(6)), not the motion.
    sign : int
        Sign (+1, -1) of the momentum on the axis of the rotation.
    n : int
        Samples (16 to :data:`MAX_FOURIER`).

    Returns
    -------
    Torus

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> T = sample_torus(RigidBody.paper(), 0.2466, 1.0, 0.0, n=256)
    >>> T.axis, round(T.rotation_number, 10), round(float(T.rho[0]), 12)
    (2, 0.1281401077, 0.0)
    """
    h, G, M = finite("h", h), positive("G", G), finite("M", M)
    if isinstance(sign, bool) or sign not in (1, -1):
        raise ValueError(f"sign must be +1 or -1, got {sign!r}")
    n = integer("n", n, 16, MAX_FOURIER)
    body.require_middle_axis("sample_torus")
    if not abs(M) < G:
        raise ValueError(f"M must satisfy |M| < G (g is undefined at |M| = G), got M = {M!r}, "
                         f"G = {G!r}")
    f = euler_poinsot_frequencies(body, h, G)
    if f.modulus == 0.0:
        raise ValueError(f"h = {h!r}, G = {G!r} is a permanent rotation: no torus")
    g0, axis = reference_momentum(body, h, G, sign)
    omega_l = 2.0 * math.pi / f.period
    phi1 = 2.0 * math.pi * np.arange(n) / n
    mom = euler_poinsot_momentum(body, g0, phi1 / omega_l)
    if not np.allclose(mom[0], g0, rtol=0.0, atol=1e-12 * G):  # amplitude 0: F = 0 exactly
        raise RuntimeError(f"the free-top motion does not start at its reference state: "
                           f"{mom[0]} != {g0}")
    G1, G2, G3 = mom.T
    perp = G1**2 + G2**2
    gdot = G * (body.a * G1**2 + body.b * G2**2) / perp
    # dl/dt = dH0/dL = L (c - a sin^2 l - b cos^2 l), sin^2 l = G1^2 / (G1^2 + G2^2).
    ldot = G3 * (body.c - (body.a * G1**2 + body.b * G2**2) / perp)
    spec = np.fft.fft(gdot)
    omega_g = float(spec[0].real / n)
    k = np.fft.fftfreq(n, 1.0 / n)
    with np.errstate(divide="ignore", invalid="ignore"):
        integ = np.where(k != 0, spec / (1j * k * omega_l), 0.0)
    if n % 2 == 0:
        integ[n // 2] = 0.0
    rho = np.fft.ifft(integ).real
    rho -= rho[0]
    return Torus(float(h), float(G), float(M), axis, int(sign), omega_l, omega_g, phi1, mom,
                 np.arctan2(G1, G2), G3, rho, ldot, gdot)


def fourier_coefficients(body: RigidBody, torus: Torus, n2: int = 8) -> NDArray[np.complex128]:
    """``V_k`` on the torus: array ``(n1, n2)`` indexed like ``numpy.fft.fft2``."""
    n1 = torus.phi1.size
    phi2 = 2.0 * math.pi * np.arange(n2) / n2
    g = phi2[None, :] + torus.rho[:, None]
    x = np.empty((n1, n2, 5))
    x[..., 0] = torus.l[:, None]
    x[..., 1] = g
    x[..., 2] = torus.L[:, None]
    x[..., 3] = torus.G
    x[..., 4] = torus.M
    V = perturbation(body, from_andoyer(x.reshape(-1, 5)).reshape(n1, n2, 6))
    return np.asarray(np.fft.fft2(V) / (n1 * n2))


def converged_torus(body: RigidBody, h: float, G: float, M: float, sign: int = 1,
                    n: int = 256) -> tuple[Torus, NDArray[np.complex128]]:
    """:func:`sample_torus` and :func:`fourier_coefficients`, doubling the samples until
    the upper half of the resolved spectrum (``n/4 < |k1| < n/2``) is below 1e-13 of
    its peak (ValueError beyond :data:`MAX_FOURIER`: the torus is too near the
    separatrix for its spectrum to be resolved)."""
    while True:
        torus = sample_torus(body, h, G, M, sign, n)
        Vk = fourier_coefficients(body, torus)
        k = np.abs(np.fft.fftfreq(n, 1.0 / n))
        tail = np.max(np.abs(Vk[k > n // 4]), initial=0.0)
        peak = np.max(np.abs(Vk))
        if tail <= 1e-13 * max(peak, 1e-300):
            return torus, Vk
        n *= 2
        if n > MAX_FOURIER:
            raise ValueError(f"the torus G = {G!r} on h = {h!r} is too near the separatrix: "
                             f"its Fourier spectrum is unresolved with {MAX_FOURIER} samples")
