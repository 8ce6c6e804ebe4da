"""Section functions in Euler-Poisson variables, derived from the chart definitions.

A Poincare section "coordinate = value" of any chart becomes a smooth function
``f(y)`` of the regular Euler-Poisson state that vanishes on it, and a margin
``w(y)`` that is positive on the true crossing:

* a smooth coordinate ``q`` (``G1``, ..., ``gamma3``, ``L``, ``G``, ``J1``, ``J2``):
  ``f = q(y) - value``, ``w = 1``;
* an angle ``alpha`` (``l``, ``g``, ``theta1``, ``theta2``) given by a pair
  ``(C, S) = k (cos alpha, sin alpha)`` with ``k > 0`` smooth in y:
  ``f = S cos(value) - C sin(value) = k sin(alpha - value)`` and
  ``w = C cos(value) + S sin(value) = k cos(alpha - value)``, so that the section is
  ``alpha = value (mod 2 pi)`` with no spurious crossing at the wrap (where
  ``alpha - value = pi``, f vanishes too but ``w < 0``). ``f`` increases when
  ``alpha`` does, so the crossing direction of ``f`` is that of the angle.

``theta1`` sections are taken mod 2 pi (the period of H on M = 0).

:data:`EXTRA_ANGLES` are section angles of the analysis modules that are not chart
coordinates: ``psi = atan2(gamma1, gamma2)``, the phase of the vertical about the body
axis 3 (the sections of the rotations about the middle axis,
:mod:`andoyer.analysis.splitting.section_map`), ``(cos psi, sin psi) ~ (gamma2, gamma1)``. They are
generated after the chart kinds (kernels take them by index) but are not offered as
coordinates of :class:`andoyer.integrate.engines.values.Section`.

The pairs come from the inverse chart maps of :mod:`andoyer.charts.andoyer_deprit`:
``(cos l, sin l) ~ (G2, G1)`` and
``(cos g, sin g) ~ (G3 (G1 gamma1 + G2 gamma2) - gamma3 (G1^2 + G2^2),
G (G2 gamma1 - G1 gamma2))``, the first written ``G3 M - gamma3 |G|^2`` with the area
``M = G . gamma`` (:data:`AREA`, the same polynomial): a first integral of (1), so the
Taylor jets take its value alone (its jet vanishes beyond order 0 on any step, a
polynomial identity of the truncated series; the tapes' ``DOT`` and ``SCALE`` rows of
:mod:`andoyer.symbolic.taylor_codegen`) and ``|G|^2`` is shared with ``|G|``.
``theta2 = g - (l + phi0)`` is crossed as ``g - (l + phi0 + value)``: the value rotates
the pair of ``l + phi0``, linear in ``(G1, G2)``, so ``f = S_g c - C_g s`` takes two
products of the state's polynomials where rotating the product pair takes four.

Where ``sin(value)`` vanishes (``value = 0, pi``) an angle's ``f`` is ``S cos(value)``,
where ``cos(value)`` does (``value = +-pi/2``) ``-C sin(value)``
(:func:`section_function_reduced`). For ``g`` both lose their square root:
``S_g = |G| (G2 gamma1 - G1 gamma2)`` is ``|G|`` times a polynomial, which has the same zeros
and signs on the regular states (``|G| > 0``), and ``C_g`` is a polynomial. The Taylor
kernels' sections ``g = 0, pi/2, pi, 3 pi/2`` take their jets from these: two products
where ``sin(value) = 0``, four and a scaling by ``M`` where ``cos(value) = 0``, instead of
seven and a square root (measured:
benchmarks/NOTES.md#scalar-angle-section). The float nearest such a value differs from it
by at most half an ulp: the dropped term moves a crossing by less than round-off.
"""

from __future__ import annotations

from functools import cache

import sympy as sp

from andoyer.notation import SECTION_ANGLES, SECTION_COORDINATES
from andoyer.symbolic.hamiltonian import S

__all__ = ["SMOOTH", "ANGLES", "EXTRA_ANGLES", "SECTION_ARGS", "AREA", "section_function",
           "angle_pair", "section_function_reduced", "VANISHING"]

value, cv, sv = sp.symbols("value cv sv", real=True)
#: Arguments of every generated section function: state, phi0, value, cos/sin(value).
SECTION_ARGS = (*S.y, S.phi0, value, cv, sv)

G1, G2, G3, gamma1, gamma2, gamma3 = S.y
_G = sp.sqrt(G1**2 + G2**2 + G3**2)
#: The area ``M = (G, gamma)``, a first integral of (1) for every body (see the notes).
AREA = G1 * gamma1 + G2 * gamma2 + G3 * gamma3

#: Smooth (non-angle) section coordinates as functions of y.
SMOOTH: dict[str, sp.Expr] = {
    "G1": G1, "G2": G2, "G3": G3, "gamma1": gamma1, "gamma2": gamma2, "gamma3": gamma3,
    "L": G3, "G": _G, "J1": (_G + G3) / 2, "J2": _G,
}
#: The chart angles a section can be taken on (:data:`andoyer.notation.SECTION_ANGLES`).
ANGLES = SECTION_ANGLES
#: Section angles that are not chart coordinates (see the module notes).
EXTRA_ANGLES = tuple(k for k, s in SECTION_COORDINATES.items() if s.chart is None)


@cache
def angle_pair(name: str) -> tuple[sp.Expr, sp.Expr]:
    """``(C, S)``, a positive multiple of ``(cos alpha, sin alpha)`` for an angle of a chart."""
    cl, sl = G2, G1
    cg = G3 * AREA - gamma3 * (G1**2 + G2**2 + G3**2)
    sg = _G * (G2 * gamma1 - G1 * gamma2)
    c0, s0 = sp.cos(S.phi0), sp.sin(S.phi0)
    if name == "l":
        return cl, sl
    if name == "psi":  # the phase of gamma about the body axis 3
        return gamma2, gamma1
    if name == "g":
        return cg, sg
    # l + phi0
    cp, sp_ = cl * c0 - sl * s0, sl * c0 + cl * s0
    if name == "theta1":  # 2 (l + phi0)
        return cp**2 - sp_**2, 2 * sp_ * cp
    if name == "theta2":  # g - (l + phi0)
        return cg * cp + sg * sp_, sg * cp - cg * sp_
    raise ValueError(f"{name!r} is not a section angle; angles: {ANGLES + EXTRA_ANGLES}")


#: Where the reduced section functions hold: ``"sin"``, values with ``sin(value) = 0``
#: (``0``, ``pi``); ``"cos"``, values with ``cos(value) = 0`` (``pi/2``, ``3 pi/2``).
VANISHING = ("sin", "cos")


@cache
def section_function_reduced(coord: str, vanishing: str) -> sp.Expr | None:
    """``f`` of the angle section ``coord = value`` where ``sin(value)`` (``vanishing =
    "sin"``) or ``cos(value)`` (``"cos"``) is zero, over its positive factor ``|G|`` if it
    has one: a polynomial in the state (and ``cos(value)``, ``sin(value)``) with the same
    zeros and signs as ``f`` on the regular states; ``None`` where ``f`` there keeps a
    square root (or had none to save) and for the smooth coordinates.

    Parameters
    ----------
    coord : str
        The section coordinate (a section kind's name).
    vanishing : {"sin", "cos"}
        Which of ``sin(value)``, ``cos(value)`` is zero (:data:`VANISHING`).

    Examples
    --------
    >>> section_function_reduced("g", "sin")
    cv*(-G1*gamma2 + G2*gamma1)
    >>> section_function_reduced("g", "cos")
    -sv*(G3*(G1*gamma1 + G2*gamma2 + G3*gamma3) - gamma3*(G1**2 + G2**2 + G3**2))
    >>> section_function_reduced("theta2", "sin") is None
    True
    """
    if vanishing not in VANISHING:
        raise ValueError(f"vanishing must be one of {VANISHING}, got {vanishing!r}")
    if coord not in ANGLES and coord not in EXTRA_ANGLES:
        return None
    f = section_function(coord)[0]
    if not f.has(_G):           # no square root to save
        return None
    f = f.subs(sv if vanishing == "sin" else cv, 0)
    if f.has(_G):               # its factor |G| > 0 goes
        f = sp.factor_terms(sp.expand(sp.cancel(f / _G)))
    roots = any(not p.exp.is_integer for p in f.atoms(sp.Pow))
    ok = not roots and f.is_polynomial(*S.y) and bool(f.free_symbols & set(S.y))
    return f if ok else None


def section_function(coord: str) -> tuple[sp.Expr, sp.Expr]:
    """``(f, w)`` of the section ``coord = value`` as expressions in :data:`SECTION_ARGS`.

    Parameters
    ----------
    coord : str
        The section coordinate (a section kind's name).
    """
    if coord in SMOOTH:
        return SMOOTH[coord] - value, sp.Integer(1)
    if coord == "theta2":  # g - (l + phi0 + value): see the module notes
        cg, sg = angle_pair("g")
        cl, sl = angle_pair("l")
        c0, s0 = sp.cos(S.phi0), sp.sin(S.phi0)
        cp, sp_ = cl * c0 - sl * s0, sl * c0 + cl * s0
        c = sp.collect(sp.expand(cp * cv - sp_ * sv), (G1, G2))
        s = sp.collect(sp.expand(sp_ * cv + cp * sv), (G1, G2))
        return sg * c - cg * s, cg * c + sg * s
    if coord in ANGLES or coord in EXTRA_ANGLES:
        C, Sn = angle_pair(coord)
        return Sn * cv - C * sv, C * cv + Sn * sv
    raise ValueError(
        f"no section for coordinate {coord!r}; choose one of "
        f"{sorted(SMOOTH) + list(ANGLES)} (M and J3 are constants of the motion)")
