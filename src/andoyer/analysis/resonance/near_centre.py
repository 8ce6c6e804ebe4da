r"""The resonant normal form near a centre of the free top: a ``p/q`` chain at small amplitude.

About a centre (the permanent rotation about axis 1 or 2) the motions near it have two
frequencies, ``omega_l(I)`` (of ``(l, L)`` about the centre) and ``omega_g(I)``. Where
``p omega_l(I*) = q omega_g(I*)`` at a small action ``I*`` the Birkhoff normal form
(:mod:`~andoyer.analysis.resonance.birkhoff`) has a small divisor once ``mu > 0``: the
resonant harmonic of ``mu (r, gamma)`` cannot be removed. Kept, it gives the resonant
normal form, a pendulum in the slow angle:

(N1) Birkhoff in ``I`` at any ``G``: ``H0 = G^2 h* + sum_k c_k G^(2-k) I^k`` -- ``H0`` is
     homogeneous of degree 2 in ``(G, L)`` at fixed ``l``, so ``c_k(G) = c_k(1) G^(2-k)``
     (:func:`~andoyer.analysis.resonance.birkhoff.birkhoff_normal_form` at ``G = 1``,
     order ``N``); ``omega_l = dH0/dI``, ``omega_g = dH0/dG``.
(N2) On the level ``H0 = h``, ``G = G(I)`` (Newton on (N1)) and
     ``W(I) = |omega_l| / omega_g``; the resonant action ``I*`` solves ``W(I*) = p/q``
     (Brent, on the first crossing from the centre, ``I`` up to the action of the torus
     half-way in ``G`` between the centre and the separatrix). ``G* = G(I*)``.
(N3) As (R2) of :mod:`~andoyer.analysis.resonance.predict`: ``K0'' = -W dW/dG`` along the
     level, ``dW/dG = (dW/dI)/(dG/dI)`` from the polynomial (5-point differences).
(N4) The resonant harmonic ``V_k``, ``k = (q, -p)``, of ``V = (r, gamma)`` on the torus
     ``G*`` (:mod:`~andoyer.analysis.resonance.torus`, FFT). Near the centre
     ``|V_k| ~ v I^(q/2)`` (the lowest term ``z^q`` of ``V`` in the centre's complex
     coordinate; ``v = |V_k| / I*^(q/2)`` is reported).
(N5) The pendulum (R5)-(R8) with these: ``A = 2 mu |V_k| / omega_g``,
     ``Delta I = 2 sqrt(A / |K0''|)``, ``Delta G = W Delta I``, ``beta = q^2 K0''``,
     ``Omega = sqrt(|beta| A)``; stable at ``chi = psi + arg V_k = 0`` if ``beta < 0``,
     ``pi`` if ``beta > 0`` (``psi = q phi1 - p phi2``), unstable half a turn away;
     residues ``sin^2(pi q Omega)`` and ``-sinh^2(pi q Omega)``. ``|p| >= 2``: no
     first-order harmonic (R3), ``half_width`` NaN, ``mu_order = 2``.

The differences from :func:`~andoyer.analysis.resonance.predict.resonance_widths` are the
resonant torus and the twist: there from the elliptic-integral frequencies, here from the
truncated Birkhoff polynomial; they agree to ``O(I*^(N/2))``, and both with measurement to
``O(mu)`` relative (the pendulum is first order in ``mu``).

What it does not give: the pendulum needs the island away from the centre,
``Delta I < I*``; where the chain reaches the centre (``|V_k| ~ I^(q/2)`` then changes the
model near ``I = 0``: the centre itself bifurcates) the half-width is wrong (measured on
the 2:1 chain at ``I* = 0.126``: ``Delta I / I* = 0.61`` at ``mu = 0.01``, 0.03 % off,
0.87 at ``mu = 0.02``, 0.04 % off -- an error growing like ``mu^0.54``, about
``5e-4 Delta I / I*``; 1.06 at ``mu = 0.03``, 12 % too wide). The expansion of ``V`` in
the centre's complex coordinates is not done: ``V_k`` comes from the torus (exact for the
free-top torus).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from scipy.optimize import brentq

from andoyer.analysis.resonance.birkhoff import birkhoff_normal_form
from andoyer.analysis.resonance.torus import converged_torus, regimes
from andoyer.body import RigidBody, checks_body
from andoyer.integrate import budget
from andoyer.integrate.results import describe_variables, provenance
from andoyer.validation import finite, integer

__all__ = ["resonant_normal_form"]

#: ``l*`` of the centre about each body axis (Oz the middle axis).
_LSTAR = {1: math.pi / 2, 2: 0.0}

_META = {
    "action": ("I^*", "Birkhoff action of the resonant torus (N2)", "1", "(N2)"),
    "G_action": ("G^*", "G of the resonant torus on the level (N2)", "1", "(N2)"),
    "rotation_number_g_section": ("W", "|omega_l| / omega_g at I* (p/q)", "1", "(N2)"),
    "omega_l": ("\\omega_l", "frequency of (l, L) about the centre at I*",
                "rad/body time unit", "(N1)"),
    "omega_g": ("\\omega_g", "rate of g at I*", "rad/body time unit", "(N1)"),
    "omega0": ("\\omega_0", "frequency of the small oscillations about the centre",
               "rad/body time unit", "(B2)"),
    "twist": ("dW/dG", "derivative of W along the level, from the normal form", "1", "(N3)"),
    "fourier_amplitude": ("|V_k|", "modulus of the resonant harmonic of (r, gamma) on the "
                          "torus G*", "1", "(N4)"),
    "fourier_phase": ("\\arg V_k", "phase of the resonant harmonic", "rad", "(N4)"),
    "dalembert_coefficient": ("v", "|V_k| / I*^(q/2)", "1", "(N4)"),
    "mu_order": ("", "lowest order in mu of the chain's width", "1", "(N5)"),
    "half_width_action": ("\\Delta I", "half-width of the chain in the action", "1", "(N5)"),
    "half_width": ("\\Delta G", "half-width of the chain in G on the level", "1", "(N5)"),
    "libration_frequency": ("\\Omega", "small-oscillation frequency of the pendulum, per "
                            "radian of phi2", "1", "(N5)"),
    "stable_angle": ("\\psi_s", "slow angle q phi1 - p phi2 of the stable periodic orbit",
                     "rad", "(N5)"),
    "unstable_angle": ("\\psi_u", "slow angle of the unstable periodic orbit", "rad", "(N5)"),
    "residue_stable": ("R_s", "Greene's residue of the stable periodic orbit", "1", "(N5)"),
    "residue_unstable": ("R_u", "Greene's residue of the unstable periodic orbit", "1",
                         "(N5)"),
}


def _parse(resonance: object) -> tuple[int, int]:
    if not isinstance(resonance, str):
        raise ValueError(f"resonance must be a string 'q:p' (frequency_ratio q/p), got "
                        f"{resonance!r}")
    try:
        q, p = (int(x) for x in resonance.split(":"))
    except ValueError:
        raise ValueError(f"resonance must be 'q:p' with whole numbers, got "
                         f"{resonance!r}") from None
    if not (1 <= q <= 100 and 1 <= p <= 100 and math.gcd(p, q) == 1):
        raise ValueError(f"resonance {resonance!r}: q and p must be coprime, 1 to 100")
    return p, q


class _Level:
    """(N1)-(N2): the Birkhoff polynomial on the level ``H0 = h``."""

    def __init__(self, hstar: float, c: np.ndarray, h: float, g_centre: float) -> None:
        self.hstar, self.c, self.h, self.gc = hstar, c, h, g_centre
        self.k = np.arange(1, c.size + 1)

    # G^(2-k) I^k written G^2 (I/G)^k (and so on): I^k alone overflows for |G| near 1e77
    # at degree 8, where every term of the form is an energy ~G^2.
    def energy(self, I: float, G: float) -> float:
        return float(G * G * (self.hstar + np.sum(self.c * (I / G) ** self.k)))

    def omegas(self, I: float, G: float) -> tuple[float, float]:
        k, c, x = self.k, self.c, I / G
        wl = float(G * np.sum(k * c * x ** (k - 1)))
        wg = float(G * (2 * self.hstar + np.sum((2 - k) * c * x ** k)))
        return wl, wg

    def G_of(self, I: float) -> float:
        G = self.gc
        for _ in range(60):
            f = self.energy(I, G) - self.h
            step = f / self.omegas(I, G)[1]
            G -= step
            if abs(step) <= 1e-16 * G:
                break
        return G

    def W(self, I: float) -> float:
        wl, wg = self.omegas(I, self.G_of(I))
        return abs(wl) / wg


def _d5(f: object, x: float, d: float) -> float:
    v = [f(x + j * d) for j in (-2, -1, 1, 2)]  # type: ignore[operator]
    return float((8.0 * (v[2] - v[1]) - (v[3] - v[0])) / (12.0 * d))


@checks_body(ranges={"h": "energy", "M": "action"})
def resonant_normal_form(body: RigidBody, h: float, M: float, resonance: str, *,
                         axis: int = 2, sign: int = 1, order: int = 8) -> xr.Dataset:
    r"""The resonant normal form of a ``q:p`` chain near a centre of the free top.

    Birkhoff's polynomial in the action ``I`` about the permanent rotation (N1) plus the
    resonant harmonic of the perturbation ``mu (r, gamma)`` (N4) give a pendulum in the
    slow angle ``psi = q phi1 - p phi2`` (N5); see the module's docstring for (N1)-(N5).

    Parameters
    ----------
    body : RigidBody
        Oz the middle axis of inertia; ``mu`` is the perturbation's size.
    h : float
        Energy level ``H0 = h`` (> 0, Eq. (9)).
    M : float
        Area constant ``(G, gamma) = M`` (``|M| < G*``).
    resonance : str
        ``"q:p"``: ``p omega_l = q omega_g`` (``W = p/q``; the label of
        :func:`~andoyer.analysis.resonance.predict.resonant_tori`).
    axis : int
        Body axis of the centre, 1 or 2.
    sign : int
        Sign of the momentum on that axis (+1 or -1: the two copies of the chain).
    order : int
        Degree ``N`` of the Birkhoff polynomial (even, 4 to 16).

    Returns
    -------
    xarray.Dataset
        0-d variables ``action`` ``I*``, ``G_action`` ``G*``,
        ``rotation_number_g_section``, ``omega_l``, ``omega_g``, ``omega0``, ``twist``,
        ``fourier_amplitude``, ``fourier_phase``, ``dalembert_coefficient``, ``mu_order``,
        ``half_width_action``, ``half_width``, ``libration_frequency``, ``stable_angle``,
        ``unstable_angle``, ``residue_stable``, ``residue_unstable``; attrs ``p``, ``q``,
        ``axis``, ``sign``, ``order``, ``h``, ``M``, provenance.

    Raises
    ------
    ValueError
        If ``p/q`` is not a rotation number of the tori near that centre (between the
        centre's ``W(0)`` and the torus half-way to the separatrix).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody(2.5, 1.0, 2.0, 1e-3, (0.6, 0.48, 0.64))
    >>> nf = resonant_normal_form(body, 1.0, 0.0, "2:1", axis=2)
    >>> round(float(nf.rotation_number_g_section), 12)
    0.5
    >>> bool(0.0 < float(nf.half_width) < 0.05)
    True
    """
    h, M = finite("h", h), finite("M", M)
    p, q = _parse(resonance)
    axis = integer("axis", axis, 1, 2)
    sign = integer("sign", sign, -1, 1)
    if sign == 0:
        raise ValueError("sign must be +1 or -1, got 0")
    N = integer("order", order, 4, 16)
    if N % 2:
        raise ValueError(f"order must be even, got {order!r}")
    if not h > 0.0:
        raise ValueError(f"h must be > 0 (the free top's energy is positive), got {h!r}")
    budget.check_level(body, h)
    body.require_middle_axis("resonant_normal_form")
    regime = [r for r in regimes(body, h, M) if r[0] == axis]
    if not regime:
        raise ValueError(f"no tori about axis {axis} on h = {h!r} with |M| = {abs(M)!r}")
    inv = (body.a, body.b)[axis - 1]
    g_centre = math.sqrt(2.0 * h / inv)
    g_sep = math.sqrt(2.0 * h / body.c)
    nf = birkhoff_normal_form(body, 1.0, order=N, lstar=_LSTAR[axis])
    lev = _Level(float(nf.H_star), nf.coefficient.values.astype(float), h, g_centre)
    # (N2): the largest action considered, the torus half-way in G to the separatrix
    g_half = 0.5 * (g_centre + g_sep)
    i_hi = brentq(lambda x: lev.G_of(x) - g_half, 0.0, 4.0 * abs(g_half - g_centre)
                  / max(lev.W(0.0), 1e-3), xtol=1e-15)
    grid = np.linspace(0.0, i_hi, 65)
    w = np.array([lev.W(float(x)) for x in grid]) - p / q
    cross = np.nonzero(np.sign(w[:-1]) * np.sign(w[1:]) <= 0)[0]
    if cross.size == 0:
        raise ValueError(f"resonance {resonance!r}: W = {p}/{q} is not reached near the "
                         f"centre about axis {axis} (W runs from {w[0] + p / q:.6g} to "
                         f"{w[-1] + p / q:.6g} up to half-way to the separatrix)")
    j = int(cross[0])
    I_star = brentq(lambda x: lev.W(x) - p / q, float(grid[j]), float(grid[j + 1]),
                    xtol=1e-15, rtol=4 * np.finfo(float).eps)
    G_star = lev.G_of(I_star)
    if not G_star > abs(M):
        raise ValueError(f"the resonant torus G* = {G_star:.6g} is not above |M| = {abs(M)!r}")
    wl, wg = lev.omegas(I_star, G_star)
    W = abs(wl) / wg
    d = 1e-3 * I_star
    twist = _d5(lev.W, I_star, d) / _d5(lev.G_of, I_star, d)            # (N3)
    K0pp = -W * twist
    beta = q * q * K0pp
    torus, Vk = converged_torus(body, h, G_star, M, sign)              # (N4)
    n1, n2 = Vk.shape
    coeff = complex(Vk[q % n1, (-p) % n2])
    mu_order = 1 if p == 1 else 2
    amp = abs(coeff) if mu_order == 1 else 0.0
    A = 2.0 * body.mu * amp / wg                                        # (N5)
    if mu_order == 1:
        dI = 2.0 * math.sqrt(A / abs(K0pp))
        Om = math.sqrt(abs(beta) * A)
    else:
        dI = Om = math.nan
    alpha = math.atan2(coeff.imag, coeff.real)
    chi_s = 0.0 if beta < 0 else math.pi
    psi_s = float(np.remainder(chi_s - alpha, 2 * math.pi))
    psi_u = float(np.remainder(psi_s + math.pi, 2 * math.pi))
    values = {
        "action": I_star, "G_action": G_star, "rotation_number_g_section": W,
        "omega_l": abs(wl), "omega_g": wg, "omega0": abs(float(nf.omega0)) * g_centre,
        "twist": twist, "fourier_amplitude": abs(coeff), "fourier_phase": alpha,
        "dalembert_coefficient": abs(coeff) / I_star ** (q / 2), "mu_order": mu_order,
        "half_width_action": dI, "half_width": W * dI, "libration_frequency": Om,
        "stable_angle": psi_s, "unstable_angle": psi_u,
        "residue_stable": math.sin(math.pi * q * Om) ** 2,
        "residue_unstable": -math.sinh(math.pi * q * Om) ** 2,
    }
    ds = xr.Dataset({k: ((), v) for k, v in values.items()},
                    attrs=provenance(body, h=h, M=M, p=p, q=q, label=f"{q}:{p}", axis=axis,
                                     sign=sign, order=N, n_fourier=int(torus.phi1.size),
                                     method="Birkhoff polynomial (Lie series) in the action "
                                            "about the centre + the resonant harmonic of "
                                            "(r, gamma) by FFT on the torus G*",
                                     derivation="andoyer.analysis.resonance."
                                                "resonant_normal_form (N1)-(N5)"))
    return describe_variables(ds, _META)
