r"""Where the ``p/q`` island chains sit and how wide they are: first order in ``mu``.

The derivation, referred to as (R1)-(R9) in the docstrings and tests.

(R1) On the tori of the free top (:mod:`andoyer.analysis.resonance.torus`), with angles
``phi1`` (of the ``(l, L)`` motion) and ``phi2`` (``g`` less its periodic part), actions
``I1`` and ``G`` (``m``, ``M`` cyclic/constant), the Hamiltonian (1) reads
``H = H0(I1, G) + mu V(phi1, phi2; I1, G)``, ``V = (r, gamma)``,
``dH0/dI1 = omega_l``, ``dH0/dG = omega_g``.

(R2) On ``H = h`` the section map of ``g = const`` (equally of ``phi2 = const``) is the
flow over one turn of ``phi2`` of the one-degree-of-freedom Hamiltonian ``K = -G``
(``dl/dg = (dH/dL)/(dH/dG) = d(-G)/dL`` on the level). Solving ``H = h`` for ``G`` to
first order: ``K = K0(I1) + mu V / omega_g + O(mu^2)`` with ``K0 = -G0(I1)``,
``K0' = omega_l / omega_g = W`` -- the rotation number of the section map,
``rotation_number_g_section`` -- and, since ``dG0/dI1 = -W`` on the level,
``K0'' = dW/dI1 = -W dW/dG`` (``dW/dG`` along the level ``H0 = h``).

(R3) ``V = sum_k V_k exp(i (k1 phi1 + k2 phi2))``; ``gamma`` is linear in ``cos g``,
``sin g``, so ``V_k = 0`` for ``|k2| >= 2``.

(R4) A resonant torus has ``W(G*) = p/q`` (``gcd(p, q) = 1``, ``q > 0``; ``W > 0``
because ``dg/dt > 0``). With the slow angle ``psi = q phi1 - p phi2`` and ``I1 = q J``
(generating function ``J (q phi1 - p phi2)``), averaging over the fast ``phi2`` keeps the
harmonics ``k = j (q, -p)``:
``Kbar = K0(q J) - p J + mu sum_j V_{jk} exp(i j psi) / omega_g``.

(R5) By (R3) only ``j = +-1`` of ``|p| = 1`` survive, and ``Kbar`` is a pendulum about
``J*``: ``Kbar = beta (J - J*)^2 / 2 + A cos(psi + alpha)``, ``beta = q^2 K0''``,
``A = 2 mu |V_k| / omega_g``, ``alpha = arg V_k``, ``k = (q, -p)``. For ``|p| >= 2`` the
resonant harmonic is absent: the chain's width is ``O(mu)``, from the second order
(not computed here: ``half_width`` NaN, ``mu_order = 2``).

(R6) The separatrix of (R5) reaches ``|J - J*| = 2 sqrt(A / |beta|)`` (at the stable
point), i.e. ``Delta I1 = q Delta J = 2 sqrt(A / |K0''|)`` and on the energy level
``Delta G = W Delta I1 = 2 sqrt(2 mu |V_k| W / (omega_g |dW/dG|))``.

(R7) The equilibria ``chi = psi + alpha = 0, pi``; the linearised pendulum
``chi'' = beta A cos(chi) chi`` is stable where ``beta A cos chi < 0`` (``chi = 0`` if
``beta < 0``, ``chi = pi`` if ``beta > 0``), with the libration frequency
``Omega = sqrt(|beta| A)`` per radian of ``phi2``.

(R8) The stable and unstable periodic orbits close after ``q`` returns (``phi2`` advances
``2 pi q``): eigenvalues of the ``q``-th power of the section map
``exp(+-2 pi i q Omega)`` and ``exp(+-2 pi q Omega)``; Greene's residues
``R = (2 - trace) / 4 = sin^2(pi q Omega)`` and ``-sinh^2(pi q Omega)``.

(R9) In the section plane the torus ``G* + dG`` is the level curve
``H0(l, L, G* + dG) = h`` (Eq. (9)); to first order it lies off the centre line
(``G*``) by ``-(dH0/dG) dG grad H0 / |grad H0|^2`` (gradient in ``(l, L)``). At the
point of phase ``phi1`` of the centre line the slow angle is ``psi = q phi1 - p phi2``
with ``phi2 = g - rho(phi1)`` and ``g`` the section's (``g*``, or
``theta2* + l + phi0`` on ``theta2 = theta2*``); the chain's separatrices are there at
``dG = +- Delta G |sin((psi - psi_u) / 2)|``, ``psi_u`` the unstable equilibrium.

(R10) Where the stable periodic orbit crosses the section, to first order in ``mu`` (in
the ``g`` section's free-top label ``G``, the ``G`` of the torus ``H0 = h`` through the
plane point): the equilibrium of the averaged ``Kbar`` (R4) moves the action by
``dI1 = -mu d(V_00 + 2 |V_k| cos chi_s)/dI1 / (omega_g K0'')``, i.e.
``-mu (d/dG)[(V_00 + 2 |V_k| cos chi_s)/omega_g] / (dW/dG)``; the non-resonant harmonics
deform the torus by ``dI1(phi) = -mu sum_k k1 V_k exp(i k.phi) / (omega_g (k1 W + k2))``
(``k`` not a multiple of ``(q, -p)``, ``k1 != 0``); ``G = G0(I1) - mu V / omega_g`` on the
level, and the plane point's label is ``G + mu V / (s(l) G)`` (``dH0/dG`` at fixed
``(l, L)``, ``s = a sin^2 l + b cos^2 l``). Together
``dG_label = -W (dI1 + dI1(phi)) + mu V (1/(s G) - 1/omega_g)`` (``stable_shift``).

(R12) Where (R10) holds: its error is ``O(mu^2)`` (measured on Hess(3, 1, 2), the 3:1
chain about axis 1 at ``M = 0``: ``stable_s - stable_shift = -0.55 mu^2`` over
``mu = 1e-4 .. 3e-3``, fitted slope 2.0), while the half-width grows like
``sqrt(mu |V_k|)``: the first-order point lies inside the island only for
``mu^(3/2) < ~sqrt(|V_k|)``. At ``M = 0`` the mean ``V_00 = (r, <gamma>)`` vanishes on every
torus (``<gamma>`` over ``g`` is ``M G / G^2``), so on thin chains (``|V_k| ~ 1e-8``, the
paper's body) the first-order offset is only the slope of the tiny resonant harmonic and
the ``O(mu^2)`` terms decide the position: the first-order point is theory-limited there,
not wrong. The estimate of the next order (``stable_shift_next_order``) is the mean part
of the second-order Lie-Deprit normal form of ``K``: with ``K2 = -G2`` the ``mu^2`` term of
``-G`` solving ``H = h``, ``G2 = V V_G / omega_g^2 - (d omega_g/dG) V^2 / (2 omega_g^3)``
(derivatives at fixed ``I1``: ``d/dG|_I = d/dG|_h + omega_g d/dh|_G``, from tori off the
level), and ``S = sum k1 |K1_k|^2 / (k1 W + k2)`` over the non-resonant harmonics,
``Kbar2 = <K2> + W (dS/dG) / 2`` and the centre moves by ``mu^2 W (dKbar2/dG) / (dW/dG)``.
The oscillating second-order terms at the section point are of the same size and are not
included (on the Hess chain the mean part is ``+0.76 mu^2`` against the measured
``-0.55 mu^2``): the estimate is a size, not a correction. ``stable_shift_holds`` says
whether it is below the half-width.

(R11) The tori are labelled, to rounding, by their gap to the separatrix
``e = q G^2/(2h) - 1`` (:func:`free_top_at_gap`): ``W`` depends on ``G`` only through
``2h/G^2`` and, in Carlson's forms of the elliptic integrals, only through products with
``e`` near the separatrix, where ``W ~ pi lambda / (q ln(1/e))``. The double ``G`` of a
torus at ``e`` misses it by ``eps/e`` relative in ``e``, ``~W^2 eps/(2 e)`` in ``W``.

What first order does not give: the width of chains with ``|p| >= 2``; the ``O(mu)``
asymmetry of the chain (the cubic term of ``K0`` and the slope of ``|V_k|`` in the action
move the midpoint of its two separatrices off the stable point); and the chaotic layers
along the separatrices (exponentially thin in ``1/sqrt(mu)``).
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, NamedTuple

import numpy as np
import xarray as xr
from numpy.typing import NDArray
from scipy.optimize import brentq
from scipy.special import elliprf, elliprj

from andoyer.analysis.resonance.torus import (
    MAX_FOURIER,
    Torus,
    converged_torus,
    reference_momentum,
    regimes,
)
from andoyer.analysis.unperturbed.euler_poinsot import (
    euler_poinsot_frequencies,
    euler_poinsot_momentum,
)
from andoyer.body import RigidBody, checks_body
from andoyer.integrate import Section, budget
from andoyer.integrate.results import describe_variables, provenance
from andoyer.validation import finite, integer, positive

__all__ = ["resonant_tori", "resonance_widths", "section_rotation_number", "free_top_at_gap",
           "FreeTopTorus", "LABEL_TOLERANCE", "MAX_ORDER",
           "N_CURVE"]

#: Largest order ``p + q`` asked for (the chains of higher order crowd the separatrix,
#: where the tori's spectra need more than :data:`MAX_FOURIER` samples).
MAX_ORDER = 100
#: Points of each chain's centre line and separatrices in the section plane.
N_CURVE = 512
#: The scan's geometric part starts at ``|e| = _SEP_GAP`` of the regime's extent and
#: goes down (by factors 1e-4) until ``W`` is below the smallest fraction asked for.
_SEP_GAP = 1e-12
#: Smallest ``|e|`` scanned (R11 is exact to rounding there; ``W ~ 1/ln(1/e)``: 4e-3 on
#: the paper's body).
_MIN_GAP = 1e-120
#: A torus's double ``G`` labels it when ``|W(G) - p/q| <= LABEL_TOLERANCE p/q``
#: (``resolved``); nearer the separatrix ``G`` cannot hold it, the gap ``e`` does (R11).
LABEL_TOLERANCE = 1e-13
#: Refinement of the torus samples where the section points are bracketed.
_FINE = 16


def section_rotation_number(body: RigidBody, h: float, G: float) -> float:
    """``W = omega_l / omega_g`` of the free top on ``H0 = h``, ``|G| = G`` (R2): the
    :attr:`~andoyer.analysis.unperturbed.euler_poinsot.EulerPoinsotFrequencies.rotation_number_g_section`
    of :func:`~andoyer.analysis.unperturbed.euler_poinsot.euler_poinsot_frequencies`.

    Parameters
    ----------
    body : RigidBody
        Oz the middle axis (``mu`` ignored: the free top).
    h : float
        Energy ``H0 = h`` of the free top (Eq. (7) at ``mu = 0``; > 0).
    G : float
        ``|G|`` of the torus (> 0).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> round(section_rotation_number(RigidBody.paper(), 0.2466, 1.0), 10)
    0.1281401077
    """
    return float(euler_poinsot_frequencies(body, h, G).rotation_number_g_section)


class FreeTopTorus(NamedTuple):
    """The free top's torus on ``H0 = h`` labelled by its gap to the separatrix (R11).

    Parameters
    ----------
    gap : float
        ``e = q G^2 / (2 h) - 1`` (``q`` the middle inverse moment): ``> 0`` about the axis
        of the largest moment, ``< 0`` about that of the smallest.
    G : float
        ``|G| = sqrt(2 h (1 + e) / q)`` rounded to a double.
    rotation_number : float
        ``W = omega_l / omega_g`` of the torus ``e`` (R2).
    omega_l, omega_g : float
        Frequency of ``(l, L)`` and mean rate of ``g`` on the torus.
    """

    gap: float
    G: float
    rotation_number: float
    omega_l: float
    omega_g: float


@checks_body(ranges={"h": "energy"})
def free_top_at_gap(body: RigidBody, h: float, gap: float) -> FreeTopTorus:
    """(R11): ``W``, ``omega_l``, ``omega_g`` of the torus ``q G^2 = 2 h (1 + gap)``,
    computed from ``gap`` without cancellation near the separatrix.

    With ``x = 2h/G^2 = q/(1 + e)`` the small quantities ``q - x = q e/(1 + e)``, the
    complementary parameter ``1 - m`` and ``1 - n`` of the elliptic integrals are
    products with ``e`` (never differences), and Carlson's forms take them as they are:
    ``K = R_F(0, 1 - m, 1)``, ``Pi(n | m) = K + n R_J(0, 1 - m, 1, 1 - n) / 3``. The
    frequency ratio ``omega_g / omega_l = 2 (x K - (q - x) n R_J / 3) / (pi lambda)``
    (from :func:`~andoyer.analysis.unperturbed.euler_poinsot.euler_poinsot_frequencies`
    with ``c = q``) is then exact to rounding at any ``e``, where ``W(G)`` from the
    double ``G`` loses ``eps / e`` (relative) to the difference ``q G^2 - 2h``.

    Parameters
    ----------
    body : RigidBody
        Oz the middle axis of inertia (``c = q``); ``mu`` ignored.
    h : float
        Energy ``H0 = h`` (> 0).
    gap : float
        ``e``, non-zero, between the permanent rotations
        (``q/p - 1 <= e <= q/r - 1``).

    Returns
    -------
    FreeTopTorus

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> t = free_top_at_gap(RigidBody.paper(), 0.2466, 1e-14)
    >>> round(t.rotation_number, 12), t.G == math.sqrt(2 * 0.2466 / RigidBody.paper().c)
    (0.010782131543, False)
    """
    h, e = positive("h", h), finite("gap", gap)
    body.require_middle_axis("free_top_at_gap")
    p, q, r = sorted((body.a, body.b, body.c), reverse=True)
    if not (q / p - 1.0 <= e <= q / r - 1.0 and e != 0.0):
        raise ValueError(f"gap must be non-zero, between the permanent rotations "
                         f"{q / p - 1.0!r} and {q / r - 1.0!r} (e = q G^2/(2h) - 1), got "
                         f"{gap!r}")
    x = q / (1.0 + e)
    d = q * e / (1.0 + e)                                   # q - x, exact to rounding
    if e > 0.0:
        lam = math.sqrt((q - r) * (p - x))
        m1 = (p - r) * d / ((q - r) * (p - x))
        n, n1 = (x - r) / (q - r), d / (q - r)
    else:
        lam = math.sqrt((p - q) * (x - r))
        m1 = -(p - r) * d / ((p - q) * (x - r))
        n, n1 = (p - x) / (p - q), -d / (p - q)
    K = float(elliprf(0.0, m1, 1.0))
    ratio = 2.0 * (x * K - d * n * float(elliprj(0.0, m1, 1.0, n1)) / 3.0) / (math.pi * lam)
    g_sep = math.sqrt(2.0 * h / q)
    G = g_sep + g_sep * e / (1.0 + math.sqrt(1.0 + e))      # g_sep sqrt(1 + e)
    omega_l = math.pi * G * lam / (2.0 * K)
    return FreeTopTorus(e, G, 1.0 / ratio, omega_l, omega_l * ratio)


def _gap_of(body: RigidBody, h: float, G: float) -> float:
    """``e = q G^2/(2h) - 1`` of the double ``G``, exactly (rational arithmetic), rounded
    once."""
    q = Fraction(sorted((body.a, body.b, body.c))[1])
    return float(q * Fraction(G) ** 2 / (2 * Fraction(h)) - 1)


def _fractions(lo: float, hi: float, max_order: int) -> list[tuple[int, int]]:
    out = []
    for q in range(1, max_order):
        for p in range(1, max_order - q + 1):
            if math.gcd(p, q) == 1 and lo < p / q < hi:
                out.append((p, q))
    return sorted(out, key=lambda f: f[0] / f[1])


def _gap_range(body: RigidBody, h: float, lo: float, hi: float
               ) -> tuple[float, float, float]:
    """The regime ``(G_lo, G_hi)`` in the gap: ``(sign of e, |e| at the end nearer the
    separatrix (0 there), |e| at the other end)``."""
    p, q, r = sorted((body.a, body.b, body.c), reverse=True)
    g_sep = math.sqrt(2.0 * h / q)
    near, far = (hi, lo) if abs(hi - g_sep) < abs(lo - g_sep) else (lo, hi)
    e_near = 0.0 if near == g_sep else abs(_gap_of(body, h, near))
    rotation = {math.sqrt(2.0 * h / p): q / p - 1.0, math.sqrt(2.0 * h / r): q / r - 1.0}
    e_far = abs(rotation[far]) if far in rotation else abs(_gap_of(body, h, far))
    return math.copysign(1.0, far - g_sep), e_near, e_far


def _scan(body: RigidBody, h: float, side: float, e_near: float, e_far: float,
          w_min: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``ln |e|`` and ``W`` on a grid over the regime, its ends included (``W`` at the
    permanent rotation is the limit of the tori's): uniform in ``e`` and, when the
    regime reaches the separatrix, geometric towards it (20 points a decade) down to the
    gap where ``W < w_min`` (the smallest fraction asked for) or :data:`_MIN_GAP`."""
    grid = e_near + (e_far - e_near) * np.linspace(0.0, 1.0, 201)[int(e_near == 0.0):]
    if e_near == 0.0:
        low = e_far * _SEP_GAP
        while low > _MIN_GAP and free_top_at_gap(
                body, h, side * low).rotation_number >= w_min:
            low *= 1e-4
        low = max(low, _MIN_GAP)
        near = np.geomspace(low, e_far, int(20 * math.log10(e_far / low)) + 2)[:-1]
        grid = np.concatenate([near, grid])
    u = np.log(np.unique(grid))
    W = np.array([free_top_at_gap(body, h, side * math.exp(v)).rotation_number for v in u])
    return u, W


def resonant_rows(body: RigidBody, h: float, M: float, max_order: int) -> list[dict[str, Any]]:
    """The resonant tori (R4), (R11): per fraction ``p/q`` and sign, the torus's gap
    ``e`` (``W(e) = p/q`` by Brent in ``ln |e|``), its ``G``, and whether that double
    ``G`` labels the torus to :data:`LABEL_TOLERANCE` (``label_error``)."""
    rows: list[dict[str, Any]] = []
    w_min = 1.0 / max(max_order - 1, 1)
    for axis, lo, hi in regimes(body, h, M):
        side, e_near, e_far = _gap_range(body, h, lo, hi)
        us, Ws = _scan(body, h, side, e_near, e_far, w_min)
        if us.size < 2:
            continue
        ends = Ws[[0, -1]] if e_near > 0.0 else Ws[[-1]]   # no torus at a rotation or |G| = |M|
        for p, q in _fractions(float(Ws.min()), float(Ws.max()), max_order):
            if np.any(np.abs(ends - p / q) <= 8 * np.finfo(float).eps * p / q):
                continue
            d = Ws - p / q
            for i in np.nonzero(np.sign(d[:-1]) * np.sign(d[1:]) < 0)[0]:
                u = brentq(lambda v, w=p / q, side=side: free_top_at_gap(
                    body, h, side * math.exp(v)).rotation_number - w,
                    float(us[i]), float(us[i + 1]), xtol=1e-15,
                    rtol=4 * np.finfo(float).eps)
                t = free_top_at_gap(body, h, side * math.exp(u))
                e_G = _gap_of(body, h, t.G)
                miss = (abs(free_top_at_gap(body, h, e_G).rotation_number - p / q)
                        if e_G != 0.0 else p / q)
                for sign in (1, -1):
                    rows.append({"p": p, "q": q, "axis": axis, "sign": sign, "G": t.G,
                                 "gap": t.gap, "torus": t, "label_error": miss,
                                 "resolved": miss <= LABEL_TOLERANCE * p / q,
                                 "lo": lo, "hi": hi})
    return rows


def check_level_args(body: RigidBody, h: float, M: float, max_order: int
                  ) -> tuple[float, float, int]:
    h, M = finite("h", h), finite("M", M)
    max_order = integer("max_order", max_order, 2, MAX_ORDER)
    budget.check_level(body, h)
    body.require_middle_axis("the resonances of the free top")
    if not h > 0.0:
        raise ValueError(f"h must be > 0 (the free top's energy is positive), got {h!r}")
    return h, M, max_order


_TORI_META = {
    "p": ("p", "turns of (l, L) per q returns to the section g = const", "1", "(R4)"),
    "q": ("q", "returns to the section g = const per period of the chain", "1", "(R4)"),
    "axis": ("", "body axis of the permanent rotation the torus surrounds", "1", "(9)"),
    "sign": ("", "sign of the angular momentum on that axis (the two copies of a chain)",
             "1", ""),
    "G_action": ("G^*", "G of the resonant torus of the free top (the chain's centre)",
                 "1", "(R4)"),
    "rotation_number_g_section": ("W", "omega_l / omega_g of the resonant torus: p/q",
                                  "1", "(R2)"),
    "separatrix_gap": ("e", "q G*^2 / (2h) - 1: the torus's gap to the separatrix, its "
                       "label to rounding", "1", "(R11)"),
    "label_error": ("", "|W - p/q| of the torus the double G_action labels", "1", "(R11)"),
    "resolved": ("", "G_action labels the torus to LABEL_TOLERANCE p/q", "1", "(R11)"),
    "frequency_ratio": ("\\omega_g/\\omega_l", "omega_g / omega_l = q/p (the ratio "
                        "andoyer.analysis.chaos.frequency measures)", "1", ""),
    "label": ("q:p", "the resonance label of andoyer.analysis.chaos.frequency (frequency_ratio "
              "q/p)", "1", ""),
    "omega_l": ("\\omega_l", "frequency of the (l, L) motion", "rad/body time unit", "(R1)"),
    "omega_g": ("\\omega_g", "mean rate of g", "rad/body time unit", "(R1)"),
}


@checks_body(ranges={"h": "energy", "M": "action"})
def resonant_tori(body: RigidBody, h: float, M: float, *, max_order: int = 12
                  ) -> xr.Dataset:
    """The resonant tori of the free top on one energy level: ``W(G*) = p/q``, ``p + q <=
    max_order``.

    On ``H0 = h`` (``mu`` ignored) the tori are labelled by ``G``; each regime (the
    momentum about the axis of the largest or of the smallest moment) has the rotation
    number ``W(G)`` of the section map ``g = const`` (R2) between 0 (at the separatrix)
    and its value at the permanent rotation. Each torus is found in its gap to the
    separatrix ``e = q G^2/(2h) - 1`` (R11), where ``W(e)`` is exact to rounding: ``W`` is
    scanned on a grid of ``ln |e|`` (geometric towards the separatrix, down to the gap
    where ``W`` is below every fraction asked for) and each sign change of ``W - p/q``
    closed by Brent's method, so ``W = p/q`` to rounding on every row. Near the separatrix
    the double ``G*`` cannot hold the torus (``W`` varies like ``1/ln(1/e)``: one ulp of
    ``G`` is a change of ``W`` of ``~W^2 eps/e``); ``label_error`` says by how much the
    torus of the double ``G_action`` misses ``p/q`` and ``resolved`` whether that is within
    :data:`LABEL_TOLERANCE` (relative) -- the gap ``separatrix_gap`` is the label then.
    Each torus is listed twice, once per sign of the momentum on its axis (two copies of
    the chain, mirror images).

    Parameters
    ----------
    body : RigidBody
        Oz the middle axis of inertia (every Hess body); ``mu`` is not used.
    h : float
        The energy level (> 0).
    M : float
        The area constant; tori with ``G <= |M|`` are left out (``g`` undefined).
    max_order : int
        Largest ``p + q`` (2 to :data:`MAX_ORDER`).

    Returns
    -------
    xarray.Dataset
        Dim ``resonance``, ordered by regime and ``p/q``: ``p``, ``q``, ``axis``,
        ``sign``, ``separatrix_gap`` (``e`` of the torus, R11), ``G_action`` (``G*``,
        its double), ``rotation_number_g_section`` (``W(e)``, equal to ``p/q`` to
        rounding), ``label_error`` (``|W(G_action) - p/q|``), ``resolved`` (``G_action``
        labels the torus to :data:`LABEL_TOLERANCE`), ``frequency_ratio`` ``q/p``,
        ``label`` ``"q:p"`` (as :func:`andoyer.analysis.chaos.frequency.resonance_label`
        names ``frequency_ratio``), ``omega_l``, ``omega_g``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = resonant_tori(RigidBody.paper(), 0.2466, 0.0, max_order=10)
    >>> sorted(set(ds.label.values.tolist()))
    ['6:1', '7:1', '8:1', '9:1']
    >>> bool(abs(ds.rotation_number_g_section - ds.p / ds.q).max() < 1e-14)
    True
    >>> big = resonant_tori(RigidBody.paper(), 0.2466, 0.0, max_order=100)
    >>> bool(abs(big.rotation_number_g_section / (big.p / big.q) - 1).max() < 1e-14)
    True
    >>> int((~big.resolved).sum()) > 0    # the tori whose double G* misses p/q
    True
    """
    h, M, max_order = check_level_args(body, h, M, max_order)
    return _tori_dataset(body, h, M, max_order, resonant_rows(body, h, M, max_order))


def _tori_dataset(body: RigidBody, h: float, M: float, max_order: int,
                  rows: list[dict[str, Any]]) -> xr.Dataset:
    n = len(rows)
    tori = [r["torus"] for r in rows]
    ds = xr.Dataset(
        {"p": ("resonance", np.array([r["p"] for r in rows], dtype=np.int64)),
         "q": ("resonance", np.array([r["q"] for r in rows], dtype=np.int64)),
         "axis": ("resonance", np.array([r["axis"] for r in rows], dtype=np.int64)),
         "sign": ("resonance", np.array([r["sign"] for r in rows], dtype=np.int64)),
         "separatrix_gap": ("resonance", np.array([t.gap for t in tori], dtype=float)),
         "G_action": ("resonance", np.array([r["G"] for r in rows], dtype=float)),
         "rotation_number_g_section": ("resonance", np.array(
             [t.rotation_number for t in tori], dtype=float)),
         "label_error": ("resonance", np.array([r["label_error"] for r in rows],
                                               dtype=float)),
         "resolved": ("resonance", np.array([r["resolved"] for r in rows], dtype=bool)),
         "frequency_ratio": ("resonance", np.array([1.0 / t.rotation_number for t in tori],
                                                   dtype=float)),
         "label": ("resonance", np.array([f"{r['q']}:{r['p']}" for r in rows], dtype=str)),
         "omega_l": ("resonance", np.array([t.omega_l for t in tori], dtype=float)),
         "omega_g": ("resonance", np.array([t.omega_g for t in tori], dtype=float))},
        coords={"resonance": np.arange(n)},
        attrs=provenance(body, h=h, M=M, max_order=max_order,
                         label_tolerance=LABEL_TOLERANCE,
                         method="W(e) in the gap to the separatrix e = q G^2/(2h) - 1 "
                                "(Carlson's forms, no cancellation) on a grid of ln|e|, "
                                "sign changes of W - p/q closed by Brent's method",
                         derivation="andoyer.analysis.resonance.predict (R1)-(R11)"))
    return describe_variables(ds, _TORI_META)


# ------------------------------------------------------------------------ widths
def _twist(body: RigidBody, h: float, row: dict[str, Any]) -> float:
    """``dW/dG`` along ``H0 = h``: Richardson's 5-point central difference in the gap
    ``e`` (R11), step ``1e-4`` of the distance to the nearer end of the regime;
    ``dW/dG = (dW/de) 2 (1 + e) / G``."""
    e = row["gap"]
    _side, e_near, e_far = _gap_range(body, h, row["lo"], row["hi"])
    d = math.copysign(1e-4 * min(abs(e) - e_near, e_far - abs(e)), e)
    w = [free_top_at_gap(body, h, e + k * d).rotation_number for k in (-2, -1, 1, 2)]
    return (8.0 * (w[2] - w[1]) - (w[3] - w[0])) / (12.0 * d) * 2.0 * (1.0 + e) / row["G"]


def _upsample(values: NDArray[np.float64], factor: int) -> NDArray[np.float64]:
    """The trigonometric interpolant of ``n`` periodic samples on ``factor * n`` points
    (zero-padded FFT), the first repeated at the end."""
    n = values.size
    c = np.fft.rfft(values)
    if n % 2 == 0:
        c[-1] *= 0.5
    fine = np.fft.irfft(c, factor * n) * factor
    return np.append(fine, fine[0])


def trig_interpolate(torus: Torus, values: NDArray[np.float64], phi: NDArray[np.float64]
            ) -> NDArray[np.float64]:
    """The trigonometric interpolant of periodic samples at phases ``phi`` (flattened).

    ``e^{i k phi}`` for the ``m`` harmonics as ``e^{i s a phi} e^{i b phi}``, ``k = s a + b``,
    ``s ~ sqrt(m)``: ``2 sqrt(m)`` exponentials per phase instead of ``m`` (5x faster on a
    torus of 256 samples at 32,174 phases, the same values to 1e-16).
    """
    n = torus.phi1.size
    c = np.fft.rfft(values) / n
    if n % 2 == 0:
        c[-1] *= 0.5
    phi = np.asarray(phi, dtype=float).ravel()
    s = math.isqrt(c.size - 1) + 1
    r = -(-c.size // s)
    C = np.zeros(r * s, dtype=complex)
    C[:c.size] = c
    low = np.exp(1j * np.outer(phi, np.arange(s)))
    high = np.exp(1j * np.outer(phi, s * np.arange(r)))
    total = np.einsum("na,na->n", high, low @ C.reshape(r, s).T)
    return np.asarray(2.0 * total.real - c[0].real)


def _second_order_mean(body: RigidBody, h: float, G: float, M: float, sign: int, n: int,
                       p: int, q: int) -> tuple[float, float, float]:
    """(R12) on the torus ``(h, G)``: ``<K2>``, ``S = sum k1 |K1_k|^2 / (k1 W + k2)``
    (non-resonant ``k``, ``k1 != 0``) and ``W``; derivatives at fixed ``I1`` from tori
    off the level, ``d/dG|_I = d/dG|_h + omega_g d/dh|_G``."""
    from andoyer.analysis.resonance.torus import fourier_coefficients, sample_torus

    def at(hh: float, GG: float) -> tuple[Torus, NDArray[np.complex128]]:
        t = sample_torus(body, hh, GG, M, sign, n)
        return t, fourier_coefficients(body, t)

    T, V = at(h, G)
    wg, W = T.omega_g, T.omega_l / T.omega_g
    dh, dG = 1e-5 * h, 1e-5 * G
    (tp, vp), (tm, vm) = at(h + dh, G), at(h - dh, G)
    (gp, wp), (gm, wm) = at(h, G + dG), at(h, G - dG)
    V_G = (wp - wm) / (2 * dG) + wg * (vp - vm) / (2 * dh)            # at fixed I1
    H0_GG = ((gp.omega_g - gm.omega_g) / (2 * dG)
             + wg * (tp.omega_g - tm.omega_g) / (2 * dh))
    K2 = (-float(np.sum((V * np.conj(V_G)).real)) / wg**2
          + H0_GG * float(np.sum(np.abs(V) ** 2)) / (2 * wg**3))
    n1, n2 = V.shape
    k1 = np.fft.fftfreq(n1, 1.0 / n1)[:, None]
    k2 = np.fft.fftfreq(n2, 1.0 / n2)[None, :]
    skip = (k1 * p + k2 * q == 0) | (k1 == 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        S = np.where(skip, 0.0, k1 * np.abs(V / wg) ** 2 / (k1 * W + k2))
    return K2, float(np.sum(S)), W


class ResonantChain:
    """One resonant torus with its pendulum (R5)-(R8) and its place in a section."""

    def __init__(self, body: RigidBody, h: float, M: float, row: dict[str, Any],
                 section: Section) -> None:
        self.body, self.h, self.M, self.row, self.section = body, h, M, row, section
        p, q = row["p"], row["q"]
        self.p, self.q = p, q
        self.torus, Vk = converged_torus(body, h, row["G"], M, row["sign"])
        n1 = self.torus.phi1.size
        self.n_fourier = n1
        T = self.torus
        self.W = row["torus"].rotation_number                          # (R11): p/q
        self.twist = _twist(body, h, row)
        self.K0pp = -self.W * self.twist                               # (R2)
        self.beta = q * q * self.K0pp                                  # (R5)
        self.mu_order = 1 if abs(p) == 1 else 2
        coeff = complex(Vk[q % n1, (-p) % Vk.shape[1]])
        self.V_k = coeff if self.mu_order == 1 else complex(0.0)
        self.A = 2.0 * body.mu * abs(self.V_k) / T.omega_g              # (R5)
        self.alpha = math.atan2(coeff.imag, coeff.real)
        if self.mu_order == 1:
            self.dI1 = 2.0 * math.sqrt(self.A / abs(self.K0pp))          # (R6)
            self.dG = self.W * self.dI1
            self.Omega = math.sqrt(abs(self.beta) * self.A)             # (R7)
        else:
            self.dI1 = self.dG = self.Omega = math.nan
        chi_s = 0.0 if self.beta < 0 else math.pi                       # (R7)
        self.psi_s = chi_s - self.alpha
        self.psi_u = chi_s + math.pi - self.alpha
        self.chi_s = chi_s
        self.Vk = Vk

    def stable_shift(self, phi1: NDArray[np.float64]) -> NDArray[np.float64]:
        """(R10): the O(mu) offset of the chain's stable points at section phases ``phi1``,
        in the free-top label ``G`` of the ``g`` section's plane (NaN on other sections
        and for chains without a first-order width)."""
        body, T, mu, W = self.body, self.torus, self.body.mu, self.W
        if self.section.coord != "g" or self.mu_order != 1:
            return np.full(np.shape(phi1), np.nan)
        lo, hi = self.row["lo"], self.row["hi"]
        d = 1e-4 * min(T.G - lo, hi - T.G)
        mean = []
        for Gn in (T.G - d, T.G + d):
            tn, vk = converged_torus(body, self.h, Gn, self.M, T.sign)
            amp = 2.0 * abs(vk[self.q % vk.shape[0], (-self.p) % vk.shape[1]])
            mean.append((float(vk[0, 0].real) + amp * math.cos(self.chi_s)) / tn.omega_g)
        shift = -mu * ((mean[1] - mean[0]) / (2 * d)) / self.twist
        n1, n2 = self.Vk.shape
        k1 = np.fft.fftfreq(n1, 1.0 / n1)[:, None]
        k2 = np.fft.fftfreq(n2, 1.0 / n2)[None, :]
        resonant = (k1 * self.p + k2 * self.q == 0) | (k1 == 0)
        with np.errstate(divide="ignore", invalid="ignore"):
            gen = np.where(resonant, 0.0, -mu * k1 * self.Vk / (T.omega_g * (k1 * W + k2)))
        phi1 = np.atleast_1d(np.asarray(phi1, dtype=float))
        l = trig_interpolate(T, np.unwrap(T.l), phi1)
        phi2 = self.section_g(phi1, l) - trig_interpolate(T, T.rho, phi1)
        e = np.exp(1j * (k1[None] * phi1[:, None, None] + k2[None] * phi2[:, None, None]))
        deform = np.real(np.sum(gen[None] * e, axis=(1, 2)))
        V = np.real(np.sum(self.Vk[None] * e, axis=(1, 2)))
        S = body.a * np.sin(l) ** 2 + body.b * np.cos(l) ** 2
        return np.asarray(-W * (shift + deform) + mu * V * (1.0 / (S * T.G) - 1.0 / T.omega_g))

    def second_order_mean_shift(self) -> float:
        """(R12): the ``O(mu^2)`` shift in ``G`` of the chain's centre from the mean part of
        the second-order normal form, ``mu^2 W (d Kbar2/dG) / (dW/dG)`` (NaN where
        :attr:`mu_order` is not 1 or off ``g`` sections)."""
        if self.section.coord != "g" or self.mu_order != 1:
            return math.nan
        T, G = self.torus, self.torus.G
        d = 1e-3 * min(G - self.row["lo"], self.row["hi"] - G)
        parts = [_second_order_mean(self.body, self.h, G + j * d, self.M, T.sign,
                                    T.phi1.size, self.p, self.q) for j in (-2, -1, 0, 1, 2)]
        K2 = np.array([x[0] for x in parts])
        S = np.array([x[1] for x in parts])
        W = np.array([x[2] for x in parts])
        dS = (S[2:] - S[:-2]) / (2.0 * d)                    # at G - d, G, G + d
        Kbar2 = K2[1:4] + 0.5 * W[1:4] * dS                  # (R12)
        return float(self.body.mu ** 2 * self.W * (Kbar2[2] - Kbar2[0]) / (2.0 * d)
                     / self.twist)

    # ------------------------------------------------------------ section geometry
    def section_g(self, phi1: NDArray[np.float64], l: NDArray[np.float64]
                  ) -> NDArray[np.float64]:
        """The value of g on the section at the torus points of phase ``phi1``."""
        if self.section.coord == "g":
            return np.full_like(phi1, self.section.value)
        return self.section.value + l + self.body.phi0                 # theta2 = g - l - phi0

    def states(self, phi1: NDArray[np.float64]) -> NDArray[np.float64]:
        """Body momentum on the torus at phases ``phi1``, in closed form."""
        T = self.torus
        g0, _ = reference_momentum(self.body, self.h, T.G, T.sign)
        return euler_poinsot_momentum(self.body, g0, np.asarray(phi1) / T.omega_l)

    def plane(self, mom: NDArray[np.float64], G: float | NDArray[np.float64]
              ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        l = np.arctan2(mom[:, 0], mom[:, 1])
        L = mom[:, 2]
        if self.section.coord == "g":
            return np.remainder(l, 2 * math.pi), L     # the fill plane's l in [0, 2 pi)
        return np.remainder(2.0 * (l + self.body.phi0), 4 * math.pi), (G + L) / 2.0

    def psi(self, phi1: NDArray[np.float64] | None = None
            ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Slow angle (R4) at the section points of phase ``phi1``, and ``d theta2/dt``
        (or ``dg/dt``) there, whose sign says the crossing's direction; ``None``: on the
        grid of :data:`_FINE` times the torus's samples (by FFT)."""
        T = self.torus
        l = np.unwrap(T.l)   # l librates on every torus about axis 1 or 2: periodic
        if phi1 is None:
            phi1 = np.linspace(0.0, 2 * math.pi, _FINE * T.phi1.size + 1)
            li, rho = _upsample(l, _FINE), _upsample(T.rho, _FINE)
            rate = _upsample(T.gdot - (T.ldot if self.section.coord == "theta2" else 0.0),
                             _FINE)
        else:
            li, rho = trig_interpolate(T, l, phi1), trig_interpolate(T, T.rho, phi1)
            rate = trig_interpolate(T, T.gdot - (T.ldot if self.section.coord == "theta2" else 0.0),
                           phi1)
        phi2 = self.section_g(phi1, li) - rho
        return self.q * phi1 - self.p * phi2, rate

    def points(self, psi0: float) -> NDArray[np.float64]:
        """Phases ``phi1`` of the section points where ``psi = psi0`` mod 2 pi, in the
        section's direction."""
        fine = np.linspace(0.0, 2 * math.pi, _FINE * self.torus.phi1.size + 1)
        psi, rate = self.psi()
        turns = (psi - psi0) / (2 * math.pi)
        k = np.floor(turns)
        out = []
        for i in np.nonzero(k[1:] != k[:-1])[0]:
            level = max(k[i], k[i + 1])
            f0, f1 = turns[i] - level, turns[i + 1] - level
            x = fine[i] + (fine[i + 1] - fine[i]) * f0 / (f0 - f1)
            for _ in range(3):   # secant steps on the interpolant
                v, _r = self.psi(np.array([x, x + 1e-7]))
                dv = (v[1] - v[0]) / 1e-7
                x -= ((v[0] - psi0) / (2 * math.pi) - level) * 2 * math.pi / dv
            r = float(self.psi(np.array([x]))[1][0])
            if self.section.direction == 0 or np.sign(r) == self.section.direction:
                out.append(x % (2 * math.pi))
        return np.array(sorted(set(np.round(out, 13))))

    def _psi_curve(self, n: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        fine = np.linspace(0.0, 2 * math.pi, _FINE * self.torus.phi1.size + 1)
        psi, rate = self.psi()
        phi = np.linspace(0.0, 2 * math.pi, n)
        return np.interp(phi, fine, np.unwrap(psi)), np.interp(phi, fine, rate)

    def normal(self, mom: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(R9): the displacement of the level curve per unit ``dG`` in the plane ``(l, L)``."""
        b, G = self.body, self.torus.G
        G1, G2, L = mom[:, 0], mom[:, 1], mom[:, 2]
        perp = G1**2 + G2**2
        s2, c2 = G1**2 / perp, G2**2 / perp
        sc = G1 * G2 / perp
        S = b.a * s2 + b.b * c2
        dHdG = S * G
        dHdl = (b.a - b.b) * sc * (G * G - L * L)
        dHdL = (b.c - S) * L
        n = np.hypot(dHdl, dHdL)  # not the sum of squares: ~|G|^4 overflows near 1e77
        return -(dHdG / n) * (dHdl / n), -(dHdG / n) * (dHdL / n)

    def curves(self, n: int) -> dict[str, NDArray[np.float64]]:
        phi = np.linspace(0.0, 2 * math.pi, n)
        mom = self.states(phi)
        x, y = self.plane(mom, self.torus.G)
        out = {"centre_x": x, "centre_y": y}
        if self.mu_order != 1:
            nan = np.full(n, np.nan)
            out.update(upper_x=nan, upper_y=nan, lower_x=nan, lower_y=nan)
            return out
        psi, _ = self.psi(phi) if n <= 64 else self._psi_curve(n)
        dG = self.dG * np.abs(np.sin((psi - self.psi_u) / 2.0))          # (R9)
        dl, dL = self.normal(mom)
        for name, s in (("upper", 1.0), ("lower", -1.0)):
            m2 = mom.copy()
            l = np.arctan2(mom[:, 0], mom[:, 1]) + s * dG * dl
            L = mom[:, 2] + s * dG * dL
            Gn = self.torus.G + s * dG
            if self.section.coord == "g":
                out[f"{name}_x"], out[f"{name}_y"] = np.remainder(l, 2 * math.pi), L
            else:
                out[f"{name}_x"] = np.remainder(2.0 * (l + self.body.phi0), 4 * math.pi)
                out[f"{name}_y"] = (Gn + L) / 2.0
            del m2
        return out


_WIDTH_META = {
    "twist": ("dW/dG", "derivative of the rotation number along the level H0 = h", "1",
              "(R2)"),
    "fourier_amplitude": ("|V_k|", "modulus of the resonant Fourier coefficient of "
                          "(r, gamma) on the torus, k = (q, -p)", "1", "(R3), (R5)"),
    "fourier_phase": ("\\arg V_k", "phase of the resonant Fourier coefficient", "rad",
                      "(R5)"),
    "mu_order": ("", "lowest order in mu of the chain's width (1: predicted here; 2: the "
                     "resonant harmonic is absent at first order, width not computed)", "1",
                 "(R3), (R5)"),
    "half_width": ("\\Delta G", "half-width of the chain in G on the energy level", "1",
                   "(R6)"),
    "half_width_action": ("\\Delta I_1", "half-width of the chain in the action of the "
                          "(l, L) motion", "1", "(R6)"),
    "libration_frequency": ("\\Omega", "small-oscillation frequency of the pendulum, per "
                            "radian of g", "1", "(R7)"),
    "residue_stable": ("R_s", "Greene's residue of the stable periodic orbit (q returns)",
                       "1", "(R8)"),
    "residue_unstable": ("R_u", "Greene's residue of the unstable periodic orbit", "1",
                         "(R8)"),
    "n_fourier": ("", "samples of the torus in phi1 (the FFT's length)", "1", ""),
    "stable_x": ("", "section-plane x of the stable periodic orbit's points", "", "(R7)"),
    "stable_y": ("", "section-plane y of the stable periodic orbit's points", "", "(R7)"),
    "unstable_x": ("", "section-plane x of the unstable periodic orbit's points", "",
                   "(R7)"),
    "unstable_y": ("", "section-plane y of the unstable periodic orbit's points", "",
                   "(R7)"),
    "stable_phase": ("\\varphi_1", "free-top phase phi1 of the stable points", "rad", "(R9)"),
    "stable_shift": ("\\delta G", "O(mu) offset of the stable points in the free-top label G "
                     "of the plane (g sections; NaN otherwise)", "1", "(R10)"),
    "stable_shift_next_order": ("", "estimated size of the O(mu^2) term of stable_shift: the "
                                "mean part of the second-order normal form (g sections)",
                                "1", "(R12)"),
    "stable_shift_holds": ("", "stable_shift_next_order < half_width: the first-order "
                           "stable point lies inside the island", "1", "(R12)"),
    "unstable_phase": ("\\varphi_1", "free-top phase phi1 of the unstable points", "rad",
                       "(R9)"),
    "centre_x": ("", "section-plane x of the chain's centre line (the resonant torus)", "",
                 "(R9)"),
    "centre_y": ("", "section-plane y of the chain's centre line", "", "(R9)"),
    "upper_x": ("", "section-plane x of the chain's outer separatrix (G* + dG)", "", "(R9)"),
    "upper_y": ("", "section-plane y of the chain's outer separatrix", "", "(R9)"),
    "lower_x": ("", "section-plane x of the chain's inner separatrix (G* - dG)", "", "(R9)"),
    "lower_y": ("", "section-plane y of the chain's inner separatrix", "", "(R9)"),
}


@checks_body(ranges={"h": "energy", "M": "action"})
def resonance_widths(body: RigidBody, h: float, M: float, section: str = "g=0", *,
                     max_order: int = 12) -> xr.Dataset:
    """The ``p/q`` island chains of ``body`` on ``H = h``: centre, half-width, periodic
    orbits and their stability, to first order in ``mu`` (R1)-(R9).

    Each resonant torus of :func:`resonant_tori` is sampled over its angles
    (:mod:`andoyer.analysis.resonance.torus`), the perturbation ``(r, gamma) = (H - H0)/mu``
    expanded by FFT (R3), the resonant harmonic ``k = (q, -p)`` kept and the pendulum
    (R5) solved: half-width in ``G`` and in the action ``I1`` (R6), the stable and
    unstable periodic orbits (R7) with Greene's residues (R8), and their points, the
    centre line and the separatrices in the section's plane (R9).

    Parameters
    ----------
    body : RigidBody
        Oz the middle axis of inertia; its ``mu`` sets the widths.
    h : float
        The energy level (> 0).
    M : float
        The area constant.
    section : str
        ``"g=VALUE"`` (plane ``(l, L)``) or ``"theta2=VALUE"`` (plane ``(theta1, J1)``,
        planar centre of mass), with an optional direction ``":+"``, ``":-"``, ``":0"``.
    max_order : int
        Largest ``p + q`` (2 to :data:`MAX_ORDER`).

    Returns
    -------
    xarray.Dataset
        The variables of :func:`resonant_tori` and, per resonance, ``twist`` (``dW/dG``),
        ``fourier_amplitude`` / ``fourier_phase`` (``V_k``), ``mu_order``,
        ``half_width`` (``Delta G``), ``half_width_action`` (``Delta I1``),
        ``libration_frequency``, ``residue_stable``, ``residue_unstable``,
        ``n_fourier``; per island (dim ``island``, NaN-padded) ``stable_x``,
        ``stable_y``, ``unstable_x``, ``unstable_y`` and their phases, ``stable_shift``
        (R10: the stable points' ``O(mu)`` offset in ``G``, ``g`` sections) with, per
        resonance, ``stable_shift_next_order`` (R12: the estimated size of its ``O(mu^2)``
        term) and ``stable_shift_holds`` (that estimate below the half-width: the
        first-order stable point lies inside the island); per point of the
        curves (dim ``point``) ``centre_x``, ``centre_y``, ``upper_x``, ``upper_y``,
        ``lower_x``, ``lower_y``. Attrs ``plane_x``, ``plane_y`` name the plane.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = resonance_widths(RigidBody.paper(1e-3), 0.2466, 0.0, max_order=9)
    >>> row = ds.isel(resonance=0)
    >>> str(row.label.values), int(row.mu_order), int(np.isfinite(row.stable_x).sum())
    ('8:1', 1, 8)
    >>> f"{float(row.half_width):.2e}"   # thin: |V_k| ~ 1e-8 on the paper's body
    '3.86e-06'
    """
    h, M, max_order = check_level_args(body, h, M, max_order)
    if not isinstance(section, str):
        raise ValueError(f"section must be a string like 'g=0' or 'theta2=0', got "
                         f"{section!r}")
    sec = Section.parse(section)
    plane = sec.plane
    if sec.coord == "theta2":
        body.require_planar("the Hess-chart section 'theta2'")
    rows = resonant_rows(body, h, M, max_order)
    budget.check("resonance_widths",
                 memory=len(rows) * (MAX_FOURIER * 8 * 16 * 8 + N_CURVE * 6 * 8))
    base = _tori_dataset(body, h, M, max_order, rows)
    chains = [ResonantChain(body, h, M, r, sec) for r in rows]
    n = len(rows)
    stab = [c.points(c.psi_s) if c.mu_order == 1 else np.empty(0) for c in chains]
    unst = [c.points(c.psi_u) if c.mu_order == 1 else np.empty(0) for c in chains]
    n_isl = max([s.size for s in stab] + [s.size for s in unst] + [1])
    arrs = {k: np.full((n, n_isl), np.nan) for k in
            ("stable_x", "stable_y", "unstable_x", "unstable_y", "stable_phase",
             "unstable_phase", "stable_shift")}
    curves = {k: np.full((n, N_CURVE), np.nan) for k in
              ("centre_x", "centre_y", "upper_x", "upper_y", "lower_x", "lower_y")}
    for i, c in enumerate(chains):
        for kind, ph in (("stable", stab[i]), ("unstable", unst[i])):
            if ph.size:
                x, y = c.plane(c.states(ph), c.torus.G)
                arrs[f"{kind}_x"][i, :ph.size] = x
                arrs[f"{kind}_y"][i, :ph.size] = y
                arrs[f"{kind}_phase"][i, :ph.size] = ph
                if kind == "stable":
                    arrs["stable_shift"][i, :ph.size] = c.stable_shift(ph)
        for k, v in c.curves(N_CURVE).items():
            curves[k][i] = v
    next_order = [abs(c.second_order_mean_shift()) for c in chains]
    ds = base.assign({
        **{k: (("resonance", "island"), v) for k, v in arrs.items()},
        **{k: (("resonance", "point"), v) for k, v in curves.items()}})
    ds = ds.assign(
        twist=("resonance", np.array([c.twist for c in chains], dtype=float)),
        fourier_amplitude=("resonance", np.array([abs(c.V_k) for c in chains], dtype=float)),
        fourier_phase=("resonance", np.array([c.alpha for c in chains], dtype=float)),
        mu_order=("resonance", np.array([c.mu_order for c in chains], dtype=np.int64)),
        half_width=("resonance", np.array([c.dG for c in chains], dtype=float)),
        half_width_action=("resonance", np.array([c.dI1 for c in chains], dtype=float)),
        libration_frequency=("resonance", np.array([c.Omega for c in chains], dtype=float)),
        residue_stable=("resonance", np.array(
            [math.sin(math.pi * c.q * c.Omega) ** 2 for c in chains], dtype=float)),
        residue_unstable=("resonance", np.array(
            [-math.sinh(math.pi * c.q * c.Omega) ** 2 for c in chains], dtype=float)),
        n_fourier=("resonance", np.array([c.n_fourier for c in chains], dtype=np.int64)),
        stable_shift_next_order=("resonance", np.array(next_order, dtype=float)),
        stable_shift_holds=("resonance", np.array(next_order, dtype=float)
                            < np.array([c.dG for c in chains], dtype=float)))
    ds.attrs.update(section=section, **sec.attrs(), plane_x=plane.x, plane_y=plane.y,
                    order_in_mu=1)
    describe_variables(ds, _WIDTH_META)
    for k in ("stable_x", "unstable_x", "centre_x", "upper_x", "lower_x"):
        ds[k].attrs["units"] = "rad"
    for k in ("stable_y", "unstable_y", "centre_y", "upper_y", "lower_y"):
        ds[k].attrs["units"] = "1"
    return ds
