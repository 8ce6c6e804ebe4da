r"""Birkhoff normal form of the free top at its elliptic fixed points: frequency vs amplitude.

The unperturbed system (9) in ``(l, L)`` at fixed ``G`` has centres at the permanent
rotations about the axes of the largest and the smallest moment (with Oz the middle axis:
``l* = 0, pi`` about y, ``pi/2, 3 pi/2`` about x; :mod:`andoyer.analysis.unperturbed.
fixed_points` types them). About a centre, to order ``N`` in the distance, the Lie series
removes every term but the powers of the action:

(B1) ``H0(l* + x, y) = H(l*, 0) + sum_{2 <= i + j <= N} h_ij x^i y^j`` -- the Taylor
     polynomial of ``H0``, derived with SymPy from :func:`andoyer.charts.euler_poisson.
     hamiltonian_expr` through the chart map :func:`andoyer.charts.andoyer_deprit.
     andoyer_to_ep_expr` at ``mu = 0`` (nothing transcribed);
(B2) ``x = alpha q``, ``y = p / alpha``, ``alpha = (h_02 / h_20)^(1/4)`` (symplectic),
     ``z = (q + i p)/sqrt(2)``: the quadratic part is ``omega0 z zbar``,
     ``omega0 = 2 sign(h_20) sqrt(h_20 h_02)``; ``{f, g} = -i (f_z g_zbar - f_zbar g_z)``;
(B3) at each degree ``n = 3 .. N`` the generating function
     ``chi_n = sum_{a != b} -i H_ab / (omega0 (b - a)) z^a zbar^b`` solves
     ``{omega0 z zbar, chi_n} = -H_n + (H_n)_{a = b}``, and the whole truncated polynomial is
     replaced by ``exp(L_chi) H = H + {H, chi} + {{H, chi}, chi}/2 + ...`` (Lie series);
(B4) what remains is ``H_NF(I) = H(l*, 0) + sum_k c_k I^k``, ``I = z zbar`` (the action:
     the scaling is symplectic), ``k <= N/2``; the frequency of ``(l, L)`` is
     ``omega_l(I) = dH_NF/dI = sum_k k c_k I^(k-1)``. Truncated at degree ``N``, the first
     term left out is ``O(I^(N/2 + 1))`` (``N`` even), so ``omega_l`` errs by
     ``O(I^(N/2)) = O(amplitude^N)``.

(B5) ``H0`` is homogeneous of degree 2 in ``(G, L)`` at fixed ``l``, and the scaling
     ``x = alpha q``, ``y = p/alpha`` keeps ``I`` an action: the form at ``|G|`` is the form
     at ``|G| = 1`` with ``c_k(G) = c_k(1) G^(2 - k)``, ``H* ~ G^2``, ``omega0 ~ G``; it is
     computed at ``|G| = 1`` and rescaled (the algebra at ``|G| = 1e120`` would lose the
     coefficients to the range of the doubles), ``dc_k/dG = (2 - k) c_k / G`` exactly.

The check is the closed form (the period of the free top in elliptic integrals,
:func:`~andoyer.analysis.unperturbed.euler_poinsot.euler_poinsot_frequencies`) and NAFF on
integrated orbits, at growing amplitude.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.body import RigidBody, checks_body
from andoyer.integrate.results import describe_variables, provenance
from andoyer.validation import integer, momentum_limit, positive, real_array

__all__ = ["birkhoff_normal_form", "normal_form_frequency", "CENTRES"]

#: Closed forms only: levels and actions up to ``|G| = MAX_ACTION``
#: (:func:`andoyer.validation.momentum_limit`).
CLOSED_FORM = True

#: The fixed points of (9) that are centres when Oz is the middle axis: ``l*`` and the
#: body axis of the rotation they stand for (L = 0 at all four).
CENTRES = {0.0: 2, math.pi / 2: 1, math.pi: 2, 3 * math.pi / 2: 1}


@functools.cache
def _taylor_functions(order: int) -> Callable[..., Any]:
    """SymPy: the Taylor coefficients ``h_ij`` of ``H0(l* + x, L)`` in ``x`` and ``L``,
    lambdified as ``f(lstar, G, a, b, c) -> array (order + 1, 3)`` (``L`` enters as
    ``L^0``, ``L^2`` only)."""
    import sympy as sp

    from andoyer.charts.andoyer_deprit import andoyer_to_ep_expr
    from andoyer.charts.euler_poisson import hamiltonian_expr

    ls, x, L, G, M, a, b, c = sp.symbols("lstar x L G M a b c", real=True)
    ep = andoyer_to_ep_expr(ls + x, sp.Symbol("g"), L, G, M, sin=sp.sin, cos=sp.cos,
                            sqrt=sp.sqrt)
    G1, G2, G3, g1, g2, g3 = ep
    H0 = sp.expand(hamiltonian_expr(G1, G2, G3, g1, g2, g3, a, b, c, 0, 1, 0, 0))
    poly = sp.Poly(H0, L)
    coeffs = {m[0]: e for m, e in zip(poly.monoms(), poly.coeffs(), strict=True)}
    if set(coeffs) - {0, 2}:
        raise RuntimeError(f"H0 is not A(l) + B(l) L^2: powers {sorted(coeffs)}")
    rows = []
    for k in (0, 2):
        e = coeffs.get(k, sp.Integer(0))
        rows.append([sp.diff(e, x, n).subs(x, 0) / sp.factorial(n) for n in range(order + 1)])
    return sp.lambdify((ls, G, a, b, c), sp.Matrix(rows), modules="numpy")


def _taylor(body: RigidBody, lstar: float, G: float, order: int) -> NDArray[np.float64]:
    """``h[i, j]`` of ``x^i y^j``, ``i + j <= order``."""
    f = _taylor_functions(order)
    rows = np.asarray(f(lstar, G, body.a, body.b, body.c), dtype=float)
    h = np.zeros((order + 1, order + 1))
    h[:, 0] = rows[0]
    h[: order - 1, 2] = rows[1][: order - 1]
    return h


def _mul(f: NDArray[np.complex128], g: NDArray[np.complex128], N: int
         ) -> NDArray[np.complex128]:
    """Product of two polynomials ``sum f[a, b] z^a zbar^b``, truncated at degree N."""
    out = np.zeros((N + 1, N + 1), dtype=complex)
    for a, b in zip(*np.nonzero(f), strict=True):
        lim = N - a - b
        if lim < 0:
            continue
        sub = g[: lim + 1, : lim + 1].copy()
        i, j = np.indices(sub.shape)
        sub[i + j > lim] = 0.0
        out[a: a + lim + 1, b: b + lim + 1] += f[a, b] * sub
    return out


def _bracket(f: NDArray[np.complex128], g: NDArray[np.complex128], N: int
             ) -> NDArray[np.complex128]:
    """``{f, g} = -i (f_z g_zbar - f_zbar g_z)``, truncated at degree N."""
    n = N + 1
    k = np.arange(n)
    fz = np.zeros_like(f)
    fz[:-1, :] = f[1:, :] * k[1:, None]
    fzb = np.zeros_like(f)
    fzb[:, :-1] = f[:, 1:] * k[None, 1:]
    gz = np.zeros_like(g)
    gz[:-1, :] = g[1:, :] * k[1:, None]
    gzb = np.zeros_like(g)
    gzb[:, :-1] = g[:, 1:] * k[None, 1:]
    return -1j * (_mul(fz, gzb, N) - _mul(fzb, gz, N))


def _to_complex(h: NDArray[np.float64], N: int) -> tuple[NDArray[np.complex128], float]:
    """(B2): ``sum h_ij x^i y^j`` in ``z, zbar``; returns the polynomial and ``omega0``."""
    h20, h02 = h[2, 0], h[0, 2]
    if not h20 * h02 > 0.0:
        raise ValueError("not a centre: the quadratic part of H0 is indefinite there")
    alpha = (h02 / h20) ** 0.25
    s2 = math.sqrt(2.0)
    x = np.zeros((N + 1, N + 1), dtype=complex)      # x = alpha (z + zbar)/sqrt2
    x[1, 0] = x[0, 1] = alpha / s2
    y = np.zeros((N + 1, N + 1), dtype=complex)      # y = -i (z - zbar)/(sqrt2 alpha)
    y[1, 0], y[0, 1] = -1j / (s2 * alpha), 1j / (s2 * alpha)
    one = np.zeros((N + 1, N + 1), dtype=complex)
    one[0, 0] = 1.0
    xp = [one]
    yp = [one]
    for _ in range(N):
        xp.append(_mul(xp[-1], x, N))
        yp.append(_mul(yp[-1], y, N))
    out = np.zeros((N + 1, N + 1), dtype=complex)
    for i, j in zip(*np.nonzero(h), strict=True):
        if 2 <= i + j <= N:
            out += h[i, j] * _mul(xp[i], yp[j], N)
    omega0 = 2.0 * math.copysign(math.sqrt(h20 * h02), h20)
    return out, omega0


def _normalise(H: NDArray[np.complex128], omega0: float, N: int) -> NDArray[np.float64]:
    """(B3)-(B4): the Lie series order by order; returns ``c_k``, ``k = 1, ..., N // 2``."""
    for n in range(3, N + 1):
        chi = np.zeros_like(H)
        for a in range(n + 1):
            b = n - a
            if a != b and H[a, b] != 0.0:
                chi[a, b] = -1j * H[a, b] / (omega0 * (b - a))
        if not np.any(chi):
            continue
        term, total, k = H, H.copy(), 1
        while True:
            term = _bracket(term, chi, N) / k
            if not np.any(np.abs(term) > 0.0):
                break
            total = total + term
            k += 1
        H = total
    return np.array([H[k, k].real for k in range(1, N // 2 + 1)])


@checks_body(ranges={"G": "length"}, closed_form=CLOSED_FORM)
def birkhoff_normal_form(body: RigidBody, G: float, *, order: int = 8,
                         lstar: float = 0.0) -> xr.Dataset:
    """The Birkhoff normal form of the free top ``(l, L)`` about a centre, to ``order``.

    Parameters
    ----------
    body : RigidBody
        Oz the middle axis of inertia (the rotations about x and y are then centres);
        ``mu`` is not used (the unperturbed system (9)).
    G : float
        ``|G|`` (> 0), within the range where every ``c_k ~ G^(2 - k)`` and
        ``dc_k/dG`` of the order asked are normal doubles (B5) (on the paper's body: up to
        :data:`~andoyer.validation.MAX_ACTION` to order 6, ``1e-103 .. 1e101`` at order 8,
        ``1e-28 .. 1e27`` at 24); outside it a ValueError gives the range.
    order : int
        Degree ``N`` of the truncation in the distance to the centre (even, 2 to 24).
    lstar : float
        The centre: one of :data:`CENTRES` (0, pi/2, pi, 3 pi/2).

    Returns
    -------
    xarray.Dataset
        ``coefficient`` (dim ``power``, ``k = 1 .. N/2``): ``c_k`` of
        ``H_NF = H* + sum c_k I^k`` (B4), by (B5) from the form at ``|G| = 1``;
        ``g_coefficient``: ``dc_k/dG = (2 - k) c_k / G`` (B5), with which
        ``omega_g(I) = dH*/dG + sum dc_k/dG I^k``; ``omega0``
        (``c_1``), ``H_star`` (``H`` at the centre), ``dH_star_dG``; attrs ``order``,
        ``lstar``, ``axis``, ``G``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> nf = birkhoff_normal_form(RigidBody.paper(), 1.0, order=6)
    >>> round(abs(float(nf.omega0)), 12) == round(math.sqrt((0.5 - 0.4) * (0.5 - 1 / 2.2)), 12)
    True
    """
    G = positive("G", G, maximum=momentum_limit(CLOSED_FORM))
    N = integer("order", order, 2, 24)
    if N % 2:
        raise ValueError(f"order must be even (the normal form has whole powers of the "
                         f"action), got {order!r}")
    body.require_middle_axis("birkhoff_normal_form")
    match = [k for k in CENTRES if isinstance(lstar, int | float)
             and not isinstance(lstar, bool) and abs(k - float(lstar)) < 1e-12]
    if not match:
        raise ValueError(f"lstar must be one of the centres 0, pi/2, pi, 3 pi/2, got {lstar!r}")
    ls = match[0]

    # (B5): the form at |G| = 1, rescaled by the homogeneity c_k(G) = c_k(1) G^(2 - k).
    h1 = _taylor(body, ls, 1.0, N)
    poly, w1 = _to_complex(h1, N)
    c1 = _normalise(poly, w1, N)
    k = np.arange(1, N // 2 + 1)
    _check_range(G, c1, N)
    half, half_g = G ** (1.0 - k / 2.0), G ** ((1.0 - k) / 2.0)   # two factors: no overflow
    c = (c1 * half) * half
    dc = ((2.0 - k) * c1 * half_g) * half_g
    H_star, w0 = float(h1[0, 0]) * G * G, w1 * G
    dH = 2.0 * float(h1[0, 0]) * G
    ds = xr.Dataset(
        {"coefficient": ("power", c), "g_coefficient": ("power", dc),
         "omega0": ((), w0), "H_star": ((), H_star), "dH_star_dG": ((), dH)},
        coords={"power": np.arange(1, N // 2 + 1)},
        attrs=provenance(body, G=G, order=N, lstar=ls, axis=CENTRES[ls],
                         method="Lie series (Deprit) on the Taylor polynomial of H0 in "
                                "z, zbar; SymPy for the expansion, NumPy for the algebra",
                         derivation="andoyer.analysis.resonance.birkhoff (B1)-(B5)"))
    return describe_variables(ds, {
        "coefficient": ("c_k", "coefficient of I^k in the normal form", "1", "(B4)"),
        "g_coefficient": ("\\partial c_k/\\partial G", "derivative of c_k in G", "1", "(B4)"),
        "omega0": ("\\omega_0", "frequency of the small oscillations", "rad/body time unit",
                   "(B2)"),
        "H_star": ("H^*", "energy of the centre (the permanent rotation)", "1", "(9)"),
        "dH_star_dG": ("\\partial H^*/\\partial G", "rate of g at the centre",
                       "rad/body time unit", "(9)")})


def _check_range(G: float, c1: NDArray[np.float64], N: int) -> None:
    """(B5): refuse a ``G`` where some ``c_k(1) G^(2-k)`` or ``(2-k) c_k(1) G^(1-k)`` (``c_k``
    non-zero) leaves the normal doubles; the message gives the range for this order."""
    tiny, huge = math.log(np.finfo(float).tiny), math.log(np.finfo(float).max)
    lo, hi = -math.inf, math.inf
    for k, ck in enumerate(c1, start=1):
        if ck == 0.0:
            continue
        for power, scale in ((2 - k, abs(ck)), (1 - k, abs((2 - k) * ck))):
            if power == 0 or scale == 0.0:
                continue
            # tiny <= log(scale) + power log G <= huge
            a, b = (tiny - math.log(scale)) / power, (huge - math.log(scale)) / power
            lo, hi = max(lo, min(a, b)), min(hi, max(a, b))
    if not lo < math.log(G) < hi:
        raise ValueError(f"G = {G!r} is beyond the range where the normal form of order {N} "
                         f"holds its coefficients c_k ~ G^(2-k) in double precision: "
                         f"G in ({math.exp(lo):.3g}, {math.exp(hi):.3g})")


def normal_form_frequency(nf: xr.Dataset, I: ArrayLike) -> xr.Dataset:
    """``omega_l(I) = dH_NF/dI`` and ``omega_g(I) = dH_NF/dG`` of a normal form (B4), and
    the energy ``H_NF(I)`` (to invert for the action of an orbit of known energy).

    Parameters
    ----------
    nf : xarray.Dataset
        :func:`birkhoff_normal_form`'s result.
    I : array_like
        Actions, ``0 <= I <= G`` (the normal form is a series about the centre: it
        describes small actions; the largest action of the ``(l, L)`` motion is of order
        ``G``).

    Returns
    -------
    xarray.Dataset
        ``omega_l``, ``omega_g``, ``energy`` on dim ``action``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> nf = birkhoff_normal_form(RigidBody.paper(), 1.0, order=4)
    >>> f = normal_form_frequency(nf, [0.0])
    >>> bool(float(f.omega_l[0]) == float(nf.omega0))
    True
    """
    if not isinstance(nf, xr.Dataset) or "coefficient" not in nf:
        raise ValueError("nf must be a birkhoff_normal_form dataset")
    acts = np.atleast_1d(real_array("I", I))
    G = float(nf.attrs.get("G", 1.0))
    if acts.ndim != 1 or not np.all(np.isfinite(acts)) or np.any(acts < 0.0) \
            or np.any(acts > G):
        raise ValueError(f"I must be actions in [0, G] = [0, {G:g}] (a number or a 1-D "
                         "array)")
    # (B5): in x = I/G with the coefficients at |G| = 1 (I^k alone overflows at large G)
    k = nf.power.values
    half = G ** (k / 2.0 - 1.0)
    c1 = (nf.coefficient.values * half) * half
    h1 = float(nf.H_star) / G / G
    x = acts[:, None] / G
    energy = G * G * (h1 + (x ** k[None, :]) @ c1)
    omega_l = G * ((x ** (k - 1)[None, :]) @ (k * c1))
    omega_g = G * (2.0 * h1 + (x ** k[None, :]) @ ((2.0 - k) * c1))
    return xr.Dataset({"omega_l": ("action", omega_l), "omega_g": ("action", omega_g),
                       "energy": ("action", energy)}, coords={"action": acts},
                      attrs={"order": int(nf.attrs["order"])})
