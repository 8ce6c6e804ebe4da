"""Euler-Poinsot motion (mu = 0) in closed form: Jacobi elliptic functions.

With ``mu = 0`` the Hamiltonian (7) is ``H0 = ((a sin^2 l + b cos^2 l)(G^2 - L^2) + c L^2)/2``
(Eq. (9)): ``G`` is constant, ``(l, L)`` move on the level curves of ``H0`` and ``g``
advances at the rate ``dg/dt = dH0/dG = G (a G1^2 + b G2^2) / (G1^2 + G2^2)``.

Derivation (written here once, checked against integration in the tests). Order the
inverse moments ``p > q > r`` (``a, b, c`` sorted) and call ``u`` the momentum component
on the axis of ``q`` (the middle axis). From ``2h = p Gp^2 + q u^2 + r Gr^2`` and
``G^2 = Gp^2 + u^2 + Gr^2``::

    (p - r) Gp^2 = A1 - B1 u^2,   A1 = 2h - r G^2,  B1 = q - r
    (p - r) Gr^2 = A2 - B2 u^2,   A2 = p G^2 - 2h,  B2 = p - q
    (du/dt)^2 = (p - r)^2 Gp^2 Gr^2 = (A1 - B1 u^2)(A2 - B2 u^2)

so ``u = U sn(lambda t, k)`` with, for ``2h < q G^2`` (motion about the axis of ``r``),
``U^2 = A1/B1``, ``lambda^2 = B1 A2``, ``k^2 = B2 A1 / (B1 A2)``, and for ``2h > q G^2``
(about the axis of ``p``) ``U^2 = A2/B2``, ``lambda^2 = B2 A1``, ``k^2 = B1 A2 / (B2 A1)``.
The body-frame motion has period ``T = 4 K(k) / lambda``. Every squared component is
``alpha + beta sn^2``; with ``G3^2 = alpha + beta sn^2`` and
``dg/dt = G c + G (2h - c G^2) / (G^2 - G3^2)``, the mean rate of ``g`` over a period is

    <dg/dt> = G c + G (2h - c G^2) Pi(n | k^2) / ((G^2 - alpha) K(k)),  n = beta/(G^2 - alpha)

with ``Pi`` the complete elliptic integral of the third kind, from Carlson's symmetric
forms: ``Pi(n|m) = R_F(0, 1-m, 1) + n R_J(0, 1-m, 1, 1-n) / 3`` (``scipy.special``). The
frequency ratio ``omega_g / omega_l`` is the advance of ``g`` over one period of
``(l, L)``, in turns; its inverse is the rotation number of the Poincare map of the
section ``g = const`` (turns of ``(l, L)`` per return).
At ``2h = q G^2`` (the separatrix, ``k = 1``) the period is infinite: refused.

Examples
--------
>>> from andoyer import RigidBody
>>> body = RigidBody(2.5, 2.0, 2.2, 0.0, (1.0, 0.0, 0.0))
>>> f = euler_poinsot_frequencies(body, 0.21, 1.0)
>>> round(f.period, 6), round(f.g_rate, 6), round(f.frequency_ratio, 6)
(100.751098, 0.410847, 6.587954)
>>> round(f.rotation_number_g_section, 6)
0.151792
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import ellipj, ellipk, elliprf, elliprj

from andoyer.body import RigidBody, checks_body
from andoyer.validation import checks_arguments, finite, positive, real_array

__all__ = ["EulerPoinsotFrequencies", "euler_poinsot_frequencies", "elliptic_pi", "elliptic_f",
           "euler_poinsot_momentum", "MAX_PERIODS"]

#: Closed forms: levels and actions up to ``|G| = MAX_ACTION``, not only what the integrators
#: take (:func:`andoyer.validation.momentum_limit`).
CLOSED_FORM = True

#: Most periods :func:`euler_poinsot_momentum` follows: beyond, the phase ``lambda t`` has
#: lost about ``log10(MAX_PERIODS) + 1`` of its 16 digits (a 1e-5 rad phase error here).
MAX_PERIODS = 1e10


@checks_arguments
def elliptic_pi(n: float, m: float) -> float:
    """Complete elliptic integral of the third kind ``Pi(n | m)``, ``n < 1``, ``m < 1``.

    ``int_0^(pi/2) dphi / ((1 - n sin^2 phi) sqrt(1 - m sin^2 phi))``, by Carlson's forms.

    Parameters
    ----------
    n : float
        Characteristic (``n < 1``).
    m : float
        Parameter ``m = k^2`` (``m < 1``).

    Examples
    --------
    >>> round(elliptic_pi(0.0, 0.5), 12) == round(float(ellipk(0.5)), 12)
    True
    """
    n, m = finite("n", n), finite("m", m)
    if not (n < 1.0 and m < 1.0):
        raise ValueError(f"elliptic_pi needs n < 1 and m < 1, got n = {n!r}, m = {m!r}")
    value = float(elliprf(0.0, 1.0 - m, 1.0) + n * elliprj(0.0, 1.0 - m, 1.0, 1.0 - n) / 3.0)
    if not math.isfinite(value):
        raise ValueError(f"elliptic_pi(n = {n!r}, m = {m!r}) is beyond the float range")
    return value


@checks_arguments
def elliptic_f(phi: ArrayLike, m: ArrayLike) -> NDArray[np.float64]:
    """Incomplete elliptic integral of the first kind ``F(phi | m)``, any real ``phi``.

    Parameters
    ----------
    phi : array_like
        Amplitude (finite, ``|phi| <= 1e15``).
    m : array_like
        Parameter ``k^2`` in ``[0, 1)``.

    Returns
    -------
    ndarray
        ``F(phi | m)``, broadcast.

    Notes
    -----
    Carlson's form ``F = sin(phi) R_F(cos^2 phi, 1 - m sin^2 phi, 1)`` on
    ``|phi| <= pi/2``, extended by ``F(phi + n pi) = F(phi) + 2 n K(m)``. Not
    ``scipy.special.ellipkinc``: SciPy 1.17.1 returns ``F(1.0895147838119381 |
    0.08843945589556104) = 1.30599`` where the value is 1.10507 (mpmath; its neighbours
    in ``phi`` are right), a 20 % error at isolated points.

    Examples
    --------
    >>> round(float(elliptic_f(1.0895147838119381, 0.08843945589556104)), 12)
    1.105065497269
    """
    phi = real_array("phi", phi)
    m = real_array("m", m)
    if not np.all(np.isfinite(phi)) or np.any(np.abs(phi) > 1e15):
        raise ValueError("phi must be finite, |phi| <= 1e15 (beyond, no digit of its "
                         "remainder mod pi is left)")
    if not np.all((m >= 0.0) & (m < 1.0)):
        raise ValueError(f"m must lie in [0, 1), got {m!r}")
    n = np.round(phi / math.pi)
    x = phi - n * math.pi
    s, c = np.sin(x), np.cos(x)
    return np.asarray(s * elliprf(c * c, 1.0 - m * s * s, 1.0) + 2.0 * n * ellipk(m))


class EulerPoinsotFrequencies(NamedTuple):
    """The Euler-Poinsot motion on ``H0 = h``, ``|G| = G``.

    Parameters
    ----------
    period : float
        Period ``T`` of the body-frame motion, of ``(l, L)`` (body time units).
    g_rate : float
        Mean rate of ``g``, ``omega_g`` (rad per body time unit).
    frequency_ratio : float
        ``omega_g / omega_l``: the advance of ``g`` over one period ``T``, in turns.
    modulus : float
        ``k^2`` of the Jacobi elliptic functions.
    regime : str
        About which axis the momentum turns (that of the smallest or largest inverse
        moment).
    """

    period: float           #: period T of the body-frame motion, of (l, L)
    g_rate: float           #: mean rate of g
    frequency_ratio: float  #: omega_g / omega_l: advance of g over one period T, in turns
    modulus: float          #: k^2 of the Jacobi functions
    regime: str             #: "about the axis of the smallest/largest inverse moment"

    @property
    def rotation_number_g_section(self) -> float:
        """``omega_l / omega_g``: the rotation number of the Poincare map of the section
        ``g = const`` (turns of ``(l, L)`` per return), the inverse of
        :attr:`frequency_ratio`."""
        return 1.0 / self.frequency_ratio


@checks_body(ranges={"h": "energy", "G": "length"}, closed_form=CLOSED_FORM)
def euler_poinsot_frequencies(body: RigidBody, h: float, G: float) -> EulerPoinsotFrequencies:
    """Period of ``(l, L)``, mean rate of ``g`` and rotation number of the free top.

    Parameters
    ----------
    body : RigidBody
        Its moments (``mu`` is ignored: this is the ``mu = 0`` motion); distinct moments.
    h : float
        Energy ``H0 = (a G1^2 + b G2^2 + c G3^2)/2``; ``r G^2 <= 2h <= p G^2``,
        ``2h != q G^2``. The ends are the stable permanent rotations about the axes of the
        largest and the smallest moment: there the values are the limits (the period of
        the small oscillations about the rotation, ``k^2 = 0``).
    G : float
        Length of the angular momentum, ``> 0``.

    Returns
    -------
    EulerPoinsotFrequencies
        Finite for every accepted input: the motion is computed on ``|G| = 1`` at
        ``h / G^2`` (the flow is homogeneous: ``T ~ 1/G``, ``<dg/dt> ~ G``), so huge or
        tiny ``G`` do not overflow; a period or rate beyond the float range is refused.

    Examples
    --------
    The permanent rotation about the axis of the largest moment (``2h = r G^2``):

    >>> from andoyer import RigidBody
    >>> body = RigidBody(2.5, 2.0, 2.2, 0.0, (1.0, 0.0, 0.0))
    >>> f = euler_poinsot_frequencies(body, 0.5 * body.a, 1.0)
    >>> lam = math.sqrt((body.c - body.a) * (body.b - body.a))
    >>> bool(abs(f.period - 2 * math.pi / lam) < 1e-12), f.modulus
    (True, 0.0)
    """
    h, G = finite("h", h), positive("G", G)
    p, q, r = sorted((body.a, body.b, body.c), reverse=True)
    if not p > q > r:
        raise ValueError(f"euler_poinsot_frequencies needs three distinct moments, got "
                         f"A={body.A}, B={body.B}, C={body.C}")
    x = 2.0 * ((h / G) / G)   # 2h / G^2 without overflow
    ulp = 4.0 * np.finfo(float).eps
    if r * (1.0 - ulp) <= x < r:      # the rotation about the axis of r, up to round-off
        x = r
    elif p < x <= p * (1.0 + ulp):
        x = p
    if not r <= x <= p:
        raise ValueError(f"h = {h!r} is off the accessible range [{0.5 * r * G * G!r}, "
                         f"{0.5 * p * G * G!r}] for G = {G!r} (r G^2 <= 2h <= p G^2)")
    # The motion on |G| = 1 at 2h = x.
    A1, B1, A2, B2 = x - r, q - r, p - x, p - q
    if abs(x - q) <= 1e-14 * q:
        raise ValueError("2h = q G^2 is the separatrix: the period is infinite")
    # Squared components alpha + beta sn^2 on the axes of p, q, r.
    if x < q:
        lam, m, U2 = math.sqrt(B1 * A2), B2 * A1 / (B1 * A2), A1 / B1
        regime = "about the axis of the smallest inverse moment (largest moment)"
    else:
        lam, m, U2 = math.sqrt(B2 * A1), B1 * A2 / (B2 * A1), A2 / B2
        regime = "about the axis of the largest inverse moment (smallest moment)"
    comp = {p: (A1 / (p - r), -B1 * U2 / (p - r)), q: (0.0, U2),
            r: (A2 / (p - r), -B2 * U2 / (p - r))}
    K = float(ellipk(m))
    T1 = 4.0 * K / lam
    c = body.c
    alpha, beta = comp[c]
    rest = 1.0 - alpha
    if not rest > 0.0:
        raise ValueError("the motion reaches L = +-G (G along body axis 3): g is undefined")
    nn = beta / rest
    mean_inv = elliptic_pi(nn, m) / (rest * K)  # <1 / (1 - G3^2)> on |G| = 1
    g1 = c + (x - c) * mean_inv
    with np.errstate(over="ignore"):
        T, g_rate = T1 / G, g1 * G
    if not (math.isfinite(T) and math.isfinite(g_rate)):
        raise ValueError(f"G = {G!r}: the period {T1!r}/G or the rate of g {g1!r} G "
                         "is beyond the float range")
    return EulerPoinsotFrequencies(T, g_rate, g1 * T1 / (2.0 * math.pi), m, regime)


@checks_body(ranges={"G0": "length"}, closed_form=CLOSED_FORM)
def euler_poinsot_momentum(body: RigidBody, G0: ArrayLike, t: ArrayLike) -> NDArray[np.float64]:
    """The body-frame angular momentum of the free top at times ``t``, in closed form.

    With the notation of the module: ``u = U sn(theta)``, ``theta = lambda t + theta0``, and
    on the other two axes ``sqrt(A1/(p - r)) cn`` and ``sqrt(A2/(p - r)) dn`` (for
    ``2h < q G^2``; ``dn`` and ``cn`` swap for ``2h > q G^2``), with the constant signs
    that Euler's equations ``dG_i/dt = (a_k - a_j) G_j G_k`` ((i, j, k) cyclic) require:
    the ``dn`` component keeps the sign it starts with, and the ``cn`` one has the sign
    making ``du/dt = U lambda cn dn``. ``theta0`` is ``F(phi0 | k^2)`` with ``phi0`` the
    amplitude of the initial state (``sn = u0/U``, ``cn`` from the ``cn`` component), by
    :func:`elliptic_f` (SciPy's ``ellipkinc`` is wrong at isolated points: the motion
    then did not start at ``G0``).

    Parameters
    ----------
    body : RigidBody
        Distinct moments; ``mu`` is ignored.
    G0 : array_like, shape (3,)
        Initial ``(G1, G2, G3)``, finite, off the separatrices (``2h != q G^2``). Along a
        principal axis (a permanent rotation, or 0: at rest) the motion is ``G0`` itself.
    t : array_like, shape (k,)
        Finite times from ``t = 0``, within :data:`MAX_PERIODS` periods.

    Returns
    -------
    ndarray, shape (k, 3)

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody(2.5, 2.0, 2.2, 0.0, (1.0, 0.0, 0.0))
    >>> G = euler_poinsot_momentum(body, [0.3, 0.8, 0.5], [0.0, 10.0])
    >>> bool(np.allclose(G[0], [0.3, 0.8, 0.5])), bool(np.isclose(np.linalg.norm(G[1]),
    ...                                                             np.linalg.norm(G[0])))
    (True, True)
    """
    g0 = real_array("G0", G0)
    if g0.shape != (3,) or not np.all(np.isfinite(g0)):
        raise ValueError(f"G0 must be 3 finite numbers (G1, G2, G3), got {G0!r}")
    times = real_array("t", t)
    if times.ndim > 1 or not np.all(np.isfinite(times)):
        raise ValueError(f"t must be a finite number or a 1-D array of finite times, got "
                         f"shape {times.shape}")
    times = times.reshape(-1)
    inv = np.array([body.a, body.b, body.c])
    order = np.argsort(inv)[::-1]            # indices of p, q, r
    ip, iq, ir = (int(i) for i in order)
    p, q, r = inv[order]
    if not p > q > r:
        raise ValueError(f"euler_poinsot_momentum needs three distinct moments, got "
                         f"A={body.A}, B={body.B}, C={body.C}")
    if np.count_nonzero(g0) <= 1:
        # At rest or a permanent rotation about a principal axis (stable about the axes
        # of p and r, unstable about that of q): an equilibrium of Euler's equations.
        return np.tile(g0, (times.size, 1))
    # The flow is homogeneous of degree 2: G(t) = s n(s t) with n(0) = G0 / s; huge and
    # tiny G0 are scaled to 1 so that no square overflows or underflows.
    scale = float(np.max(np.abs(g0)))
    if 1e-100 < scale < 1e100:
        scale = 1.0
    g0n = g0 / scale
    Gp, u, Gr = g0n[ip], g0n[iq], g0n[ir]
    # 2h - r G^2 and p G^2 - 2h from the components: no cancellation near a rotation.
    A1 = (p - r) * Gp * Gp + (q - r) * u * u
    A2 = (p - q) * u * u + (p - r) * Gr * Gr
    B1, B2 = q - r, p - q
    sep = (p - q) * Gp * Gp - (q - r) * Gr * Gr   # 2h - q G^2
    if abs(sep) <= 1e-14 * q * float(g0n @ g0n):
        raise ValueError("2h = q G^2: the state is on a separatrix (no periodic solution)")
    # Euler: dG_q/dt = kq G_p G_r, kq = a_k - a_j for (q, j, k) cyclic.
    j, k = (iq + 1) % 3, (iq + 2) % 3
    kq = inv[k] - inv[j]
    sq = math.copysign(1.0, kq)
    if sep < 0.0:   # about the axis of r: G_r = sr sqrt(A2/(p-r)) dn, G_p = sp ... cn
        lam, m, U = math.sqrt(B1 * A2), B2 * A1 / (B1 * A2), math.sqrt(A1 / B1)
        i_cn, i_dn, amp_cn, amp_dn = ip, ir, math.sqrt(A1 / (p - r)), math.sqrt(A2 / (p - r))
    else:           # about the axis of p: G_p = sp sqrt(A1/(p-r)) dn, G_r = sr ... cn
        lam, m, U = math.sqrt(B2 * A1), B1 * A2 / (B2 * A1), math.sqrt(A2 / B2)
        i_cn, i_dn, amp_cn, amp_dn = ir, ip, math.sqrt(A2 / (p - r)), math.sqrt(A1 / (p - r))
    s_dn = math.copysign(1.0, g0n[i_dn])
    # du/dt = kq G_p G_r = U lam cn dn  =>  sign(kq) s_cn s_dn = +1.
    s_cn = sq * s_dn
    phi0 = math.atan2(g0n[iq] / U, s_cn * g0n[i_cn] / amp_cn)
    with np.errstate(over="ignore"):
        theta = (lam * scale) * times + float(elliptic_f(phi0, m))
    turns = float(np.max(np.abs(theta), initial=0.0)) / (4.0 * float(ellipk(m)))
    if not turns <= MAX_PERIODS:
        raise ValueError(f"t reaches {turns:.3g} periods of the motion (|t| up to "
                         f"{float(np.max(np.abs(times))):.3g}): beyond {MAX_PERIODS:.0e} "
                         "periods the phase has lost more than 10 of its 16 digits; ask for "
                         "shorter times")
    sn, cn, dn, _ = ellipj(theta, m)
    out = np.empty((times.size, 3))
    out[:, iq] = U * sn
    out[:, i_cn] = s_cn * amp_cn * cn
    out[:, i_dn] = s_dn * amp_dn * dn
    return scale * out
