"""The Melnikov function enclosed in balls, and its zeros proved simple.

:mod:`andoyer.analysis.splitting.melnikov` computes, in floats,

.. math::

    M(\\theta_2^0) = \\int_{-\\infty}^{\\infty} \\{E, H_1\\}(x_0(t))\\, dt, \\qquad
    E = H_0 - c J_2^2/2,

along the unperturbed heteroclinic orbit ``x0`` of a separatrix line (``theta1 = 0`` or
``4 phi0`` of the Hess chart (14), (16)) and its closed form

.. math::

    M(\\theta_2^0) = -2 s\\, \\frac{\\pi\\rho}{\\sinh\\pi\\rho}
        \\sin\\Big(\\frac{\\theta_1}{2} + \\epsilon\\Big)
        \\cos\\Big(\\theta_2^0 + \\frac{\\theta_1}{2}\\Big),\\qquad \\rho = \\frac{c}{2\\sigma}

(``epsilon`` the turn of the centre of mass off the Hess direction). Here both are
enclosed in Arb balls (python-flint), independently:

* **the integral** by Arb's certified Gauss-Legendre quadrature (``acb.integral``, with
  error bounds from the integrand's analyticity on ellipses in the complex ``t`` plane)
  on ``|t| <= T``, plus a rigorous bound of the two tails: along ``x0``,
  ``|{E, H1}| <= |grad_G E| |X_{H1}| <= K_E K_X J2 sech(lambda t / 2)`` with
  ``|(G1, G2)| = J2 sech(lambda t / 2)`` and ``|gamma| = 1`` (the rotation chain), ``K_E``,
  ``K_X`` the Frobenius norms of the linear maps ``G -> grad_G E`` and
  ``gamma -> X_{H1}`` (derived by SymPy from H, as the integrand is: nothing typed from
  the paper), and ``sech u <= 2 e^{-|u|}``;
* **the closed form** with Arb's elementary functions.

The body is a :class:`~andoyer.integrate.validated.arithmetic.BodySpec` (decimal moments,
the branch of (2), ``epsilon`` as a decimal): the theorem is about the decimal body, not
the binary floats nearest it.

Zeros
-----
On ``[0, 2 pi)`` every zero is proved simple and isolated by the Krawczyk test on the
certified *integral* (not on the closed form): with ``m`` the midpoint of a box ``X`` and
``Y = 1/mid M'(X)``,

.. math::

    K(X) = m - Y M(m) + (1 - Y M'(X)) (X - m) \\subset \\operatorname{int} X
    \\;\\Rightarrow\\; \\text{exactly one zero in } X,\\ M' \\ne 0 \\text{ on } X,

``M'(X)`` the certified integral of ``d{E, H1}/dtheta2_0`` (the integrand carried as an
Arb power series in the phase), over the whole box. The rest of the circle is covered by
boxes on which the enclosure of ``M`` excludes 0. Simple zeros of ``M`` are, by
Melnikov's theorem, transversal intersections of the stable and unstable manifolds for
``mu`` small enough (the first-order statement; a bound on "small enough" is the
business of a validated integration, :mod:`andoyer.integrate.validated`).
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from decimal import Decimal
from functools import cache
from typing import Any

import numpy as np
import sympy as sp
from flint import acb, arb

from andoyer.analysis.splitting.melnikov import heteroclinic_line, melnikov_off_hess
from andoyer.analysis.unperturbed.separatrix import BRANCHES, DEFAULT_BRANCH
from andoyer.body import RigidBody
from andoyer.charts.andoyer_deprit import rotation_chain_expr
from andoyer.integrate.validated.arithmetic import (
    FLINT_VERSION,
    BodySpec,
    ball_text,
    body_symbols,
    correct_digits,
    decimal,
    evaluate,
    field_terms,
    precision,
    spec_of,
    working_precision,
)
from andoyer.validation import finite_array

__all__ = ["CertifiedMelnikov", "MelnikovZero", "certified_melnikov", "melnikov_coefficient",
           "heteroclinic_orbit_balls"]


#: Symbols standing for ``sin g, cos g, sin l, cos l, cos J, sin J, J2`` along ``x0``.
_SG, _CG, _SL, _CL, _CJ, _SJ, _J2 = sp.symbols("SG CG SL CL cJ sJ J2_", real=True)


@cache
def _bracket_parts() -> tuple[sp.Expr, sp.Expr, sp.Matrix, sp.Matrix]:
    """``{E, H1}`` along ``x0`` as ``u sin g + v cos g``: ``(u, v)``, and the tail matrices.

    Derived by SymPy: ``E = H0 - c |G|^2 / 2`` from the one Hamiltonian, ``X_{H1} =
    df/dmu`` of the field (1), the state of the rotation chain at ``M = 0``
    (:func:`~andoyer.charts.andoyer_deprit.rotation_chain_expr`). The bracket is checked to
    be a homogeneous linear form in ``(sin g, cos g)`` (so ``M`` is a trigonometric
    polynomial of degree 1 in the phase), ``grad E`` to lie in the (G1, G2) plane and
    ``X_{H1}`` not to depend on G (the hypotheses of the tail bound).
    """
    from andoyer.symbolic.hamiltonian import H_euler_poisson, S

    H0 = H_euler_poisson().subs(S.mu, 0)
    E = sp.expand(H0 - S.c * (S.G1**2 + S.G2**2 + S.G3**2) / 2)
    grad = [sp.expand(sp.diff(E, v)) for v in S.y]
    X1 = [sum((coef * sp.Mul(*[S.y[j] for j in idx]) for coef, idx in comp), sp.Integer(0))
          for comp in field_terms().mu_terms]
    if any(grad[j] != 0 for j in (2, 3, 4, 5)):
        raise AssertionError("grad E must lie in the (G1, G2) plane for the tail bound")
    if any(sp.diff(X1[i], S.y[j]) != 0 for i in range(3) for j in range(3)):
        raise AssertionError("X_{H1} must not depend on G for the tail bound")
    l_angle, g_angle = sp.symbols("l_ g_", real=True)
    y = rotation_chain_expr(l_angle, g_angle, _J2, _CJ, _SJ, 0, 1, sin=sp.sin, cos=sp.cos)
    bracket = sp.expand(sum((gi * xi for gi, xi in zip(grad, X1, strict=True)),
                            sp.Integer(0)).subs(dict(zip(S.y, y, strict=True))))
    bracket = sp.expand(bracket.subs({sp.sin(g_angle): _SG, sp.cos(g_angle): _CG,
                                      sp.sin(l_angle): _SL, sp.cos(l_angle): _CL}))
    poly = sp.Poly(bracket, _SG, _CG)
    if not (poly.is_homogeneous and poly.total_degree() == 1):
        raise AssertionError("{E, H1} must be linear in (sin g, cos g) along x0")
    u = sp.expand(poly.coeff_monomial(_SG))
    v = sp.expand(poly.coeff_monomial(_CG))
    KE = sp.Matrix([[sp.diff(grad[i], S.y[j]) for j in (0, 1)] for i in (0, 1)])
    KX = sp.Matrix([[sp.diff(X1[i], S.y[j]) for j in (3, 4, 5)] for i in range(3)])
    return u, v, KE, KX


def _frobenius(matrix: sp.Matrix, values: dict[Any, Any]) -> arb:
    total = arb(0)
    for entry in matrix:
        if entry != 0:
            val = arb(evaluate(entry, values))
            total += val * val
    return total.sqrt()


@dataclass
class _Setup:
    """One body, line and level at one precision."""

    spec: BodySpec
    branch: str
    sheet: int
    J2: arb
    s: int
    theta1: arb
    phi0_hess: arb
    lam: arb
    omega: arb
    values: dict[Any, Any]
    tail_constant: arb

    def weight(self, t: acb) -> acb:
        """``(v - i u)(t) e^{i (omega t + theta1/2)}``: ``{E, H1} = Re(weight e^{i theta})``."""
        u, v, _, _ = _bracket_parts()
        x = self.s * self.lam * t
        l_angle = self.theta1 / 2 - self.phi0_hess
        vals = dict(self.values)
        vals.update({_SL: acb(l_angle.sin()), _CL: acb(l_angle.cos()), _CJ: (x / 2).tanh(),
                     _SJ: (x / 2).sech(), _J2: acb(self.J2)})
        w = acb(evaluate(v, vals)) - acb(0, 1) * acb(evaluate(u, vals))
        return w * (acb(0, 1) * (self.omega * t + self.theta1 / 2)).exp()

    def tail(self, T: arb) -> arb:
        """Both tails of the integral of ``|weight|``: ``2 int_T^inf K J2 2 e^{-lambda t/2}``."""
        return 8 * self.tail_constant * self.J2 * (-self.lam * T / 2).exp() / self.lam


def _setup(spec: BodySpec, branch: str, sheet: int, J2: str, bits: int) -> _Setup:
    J2 = decimal("J2", J2, positive=True, maximum=1e6)
    bits = precision("bits", bits)
    if not isinstance(branch, str) or branch not in BRANCHES:
        raise ValueError(f"branch must be one of {BRANCHES}, got {branch!r}")
    if isinstance(sheet, bool) or sheet not in (1, -1):
        raise ValueError(f"sheet must be +1 or -1, got {sheet!r}")
    hess_spec = BodySpec(spec.A, spec.B, spec.C, spec.branch, "0", "0")
    theta1_f, s = heteroclinic_line(hess_spec.body(), float(J2), branch, sheet)
    with working_precision(bits):
        balls = spec.balls(bits)
        hess_balls = hess_spec.balls(bits)
        theta1 = arb(0) if branch == "theta1=0" else 4 * hess_balls.phi0
        if sheet == -1:
            theta1 = theta1 + 2 * arb.pi()
        if not abs(float(theta1.mid()) - theta1_f) < 1e-9:
            raise AssertionError("the line of heteroclinic_line and its ball disagree")
        J2b = arb(J2)
        values: dict[Any, Any] = dict(zip(body_symbols(), balls.params(), strict=True))
        _, _, KE, KX = _bracket_parts()
        K = _frobenius(KE, values) * _frobenius(KX, values)
        return _Setup(spec=spec, branch=branch, sheet=sheet, J2=J2b, s=s, theta1=theta1,
                      phi0_hess=hess_balls.phi0, lam=2 * hess_balls.sigma * J2b,
                      omega=hess_balls.c * J2b, values=values, tail_constant=K)


def heteroclinic_orbit_balls(body: RigidBody | BodySpec, branch: str = DEFAULT_BRANCH,
                             sheet: int = 1, J2: str = "1", bits: int = 128
                             ) -> tuple[arb, arb]:
    """``(theta1, lambda)``: the line of the heteroclinic orbit and its rate, as balls.

    Parameters
    ----------
    body : RigidBody or BodySpec
        The body.
    branch : {"theta1=0", "theta1=4phi0"}, default "theta1=0"
        The line. The default is every analysis' default, the Hess
        separatrix; on a Hess body that line does not split (M = 0).
    sheet : {+1, -1}, default 1
        Which of its orbits.
    J2 : str, default "1"
        The level.
    bits : int, default 128
        Working precision.
    """
    setup = _setup(spec_of(body), branch, sheet, J2, bits)
    return setup.theta1, setup.lam


def melnikov_coefficient(body: RigidBody | BodySpec, *, branch: str = DEFAULT_BRANCH,
                         sheet: int = 1, J2: str = "1", bits: int = 192
                         ) -> tuple[acb, acb, float]:
    """``(Z, Z_closed, T)``: ``M(theta2_0) = Re(Z e^{i theta2_0})``, two enclosures of Z.

    ``Z = int (v - i u) e^{i (omega t + theta1/2)} dt`` (``{E, H1} = u sin g + v cos g``
    along ``x0``, ``g = theta2_0 + omega t + theta1/2``): Arb's certified quadrature on
    ``|t| <= T`` plus the ball of the tails. The closed form of the module notes is
    ``Z = -2 s (pi rho / sinh pi rho) sin(theta1/2 + epsilon) e^{i theta1/2}``.

    Parameters
    ----------
    body : RigidBody or BodySpec
        The body.
    branch : {"theta1=0", "theta1=4phi0"}, default "theta1=0"
        The separatrix line. The default is every analysis' default, the Hess
        separatrix; on a Hess body that line does not split (M = 0).
    sheet : {+1, -1}, default 1
        Which of its two orbits.
    J2 : str, default "1"
        ``J2 = G`` of the level (a decimal).
    bits : int, default 192
        Working precision.

    Examples
    --------
    >>> paper = BodySpec("2.5", "2.0", "2.2")
    >>> Z, Zc, T = melnikov_coefficient(paper, branch="theta1=4phi0", bits=192)
    >>> bool(Z.overlaps(Zc)), correct_digits(Z.real) > 30
    (True, True)
    """
    spec = spec_of(body)
    setup = _setup(spec, branch, sheet, J2, bits)
    bits = precision("bits", bits)
    with working_precision(bits):
        target = arb(2) ** (-bits + 24)
        T = 2 * ((8 * setup.tail_constant * setup.J2 / setup.lam) / target).log() / setup.lam
        T = arb(math.ceil(float(T.upper())))
        Z = acb.integral(lambda t, _analytic: setup.weight(t), -T, T, abs_tol=target,
                         rel_tol=target)
        tail = setup.tail(T).upper()
        Z = acb(Z.real + arb(0, tail), Z.imag + arb(0, tail))
        rho = setup.omega / setup.lam
        x = arb.pi() * rho
        amp = -2 * setup.s * (x / x.sinh()) * (setup.theta1 / 2 + arb(spec.epsilon)).sin()
        Zc = amp * (acb(0, 1) * setup.theta1 / 2).exp()
    return Z, Zc, float(T.mid())


def _M(Z: acb, theta: arb) -> arb:
    return Z.real * theta.cos() - Z.imag * theta.sin()


def _dM(Z: acb, theta: arb) -> arb:
    return -Z.real * theta.sin() - Z.imag * theta.cos()


@dataclass(frozen=True)
class MelnikovZero:
    """A zero of ``M`` proved simple: the box ``X`` with ``K(X)`` inside it.

    Attributes
    ----------
    box : str
        The box ``X`` (a ball) of the Krawczyk test.
    zero : str
        ``K(X)``: an enclosure of the unique zero in ``X``.
    derivative : str
        The enclosure of ``M'`` over the whole box (excludes 0).
    zero_mid, zero_rad, derivative_mid, derivative_rad : float
        The balls' midpoints and radii.
    """

    box: str
    zero: str
    derivative: str
    zero_mid: float
    zero_rad: float
    derivative_mid: float
    derivative_rad: float


def _krawczyk_zero(Z: acb, guess: arb, radius: arb) -> MelnikovZero | None:
    """The Krawczyk test of ``M(theta) = Re(Z e^{i theta})`` on ``X = guess +- radius``.

    Parameters
    ----------
    Z : acb
        The enclosure of the coefficient (:func:`melnikov_coefficient`).
    guess : arb
        The box's midpoint (its midpoint is used).
    radius : arb
        Its radius.

    Returns
    -------
    MelnikovZero or None
        None when the test fails (``K(X)`` not inside ``X`` or ``M'(X)`` containing 0).
    """
    m = arb(guess.mid())
    X = arb(m, radius.upper())
    dX = _dM(Z, X)
    if dX.contains(0):
        return None
    Y = 1 / arb(dX.mid())
    K = m - Y * _M(Z, m) + (1 - Y * dX) * (X - m)
    if not (K.lower() > X.lower() and K.upper() < X.upper()):
        return None
    return MelnikovZero(box=ball_text(X), zero=ball_text(K), derivative=ball_text(dX),
                        zero_mid=float(K.mid()), zero_rad=float(K.rad()),
                        derivative_mid=float(dX.mid()), derivative_rad=float(dX.rad()))


@dataclass(frozen=True)
class CertifiedMelnikov:
    """The certified Melnikov function of one body, line and sheet.

    Attributes
    ----------
    body : BodySpec
        The body (decimals).
    branch : str
        The separatrix line.
    sheet : int
        Which of its orbits.
    J2 : str
        The level (``J2 = G``).
    bits : int
        Arb's working precision.
    coefficient, coefficient_closed_form : str
        ``Z`` with ``M(theta2_0) = Re(Z e^{i theta2_0})``: the certified integral and the
        closed form (complex balls).
    amplitude : str
        ``|Z|`` from the integral (``max |M|``).
    digits : float
        Correct significant digits of ``|Z|`` (0 where ``M`` is identically 0).
    T : float
        The quadrature's half interval (the tails are bounded beyond it).
    phases : tuple of float
        The phases ``theta2_0`` (exact binary values).
    values : tuple of str
        The balls of ``M`` at ``phases`` (from the integral).
    values_mid, values_rad : tuple of float
        Their midpoints and radii.
    float_closed_form : tuple of float
        :func:`~andoyer.analysis.splitting.melnikov.melnikov_off_hess` at ``phases``.
    zeros : tuple of MelnikovZero
        Every zero on ``[0, 2 pi)``, each proved simple by the Krawczyk test.
    complete : bool
        Whether ``zeros`` are all the zeros (``Z != 0``: a trigonometric polynomial of
        degree 1 has exactly two zeros per period; the rest of the circle is also
        covered by boxes on which ``M`` excludes 0).
    seconds : float
        Run time.
    flint_version : str
        The python-flint whose arithmetic produced the balls.
    """

    body: BodySpec
    branch: str
    sheet: int
    J2: str
    bits: int
    coefficient: str
    coefficient_closed_form: str
    amplitude: str
    digits: float
    T: float
    phases: tuple[float, ...]
    values: tuple[str, ...]
    values_mid: tuple[float, ...]
    values_rad: tuple[float, ...]
    float_closed_form: tuple[float, ...]
    zeros: tuple[MelnikovZero, ...]
    complete: bool
    seconds: float
    flint_version: str = field(default=FLINT_VERSION)

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready values (balls as strings)."""
        out: dict[str, Any] = {}
        for key in self.__dataclass_fields__:
            val = getattr(self, key)
            if key == "body":
                val = val.as_dict()
            elif key == "zeros":
                val = [z.__dict__.copy() for z in val]
            elif isinstance(val, tuple):
                val = list(val)
            out[key] = val
        return out

    def to_dataset(self) -> Any:
        """An :class:`xarray.Dataset` of the phases and zeros (balls as strings, mid/rad).

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr

        ds = xr.Dataset(
            {"M_ball": (("theta2_0",), np.array(self.values, dtype=str)),
             "M_mid": (("theta2_0",), np.array(self.values_mid)),
             "M_rad": (("theta2_0",), np.array(self.values_rad)),
             "M_float": (("theta2_0",), np.array(self.float_closed_form)),
             "zero_ball": (("zero",), np.array([z.zero for z in self.zeros], dtype=str)),
             "zero_mid": (("zero",), np.array([z.zero_mid for z in self.zeros])),
             "zero_rad": (("zero",), np.array([z.zero_rad for z in self.zeros])),
             "derivative_ball": (("zero",), np.array([z.derivative for z in self.zeros],
                                                     dtype=str))},
            coords={"theta2_0": np.array(self.phases)},
            attrs={"branch": self.branch, "sheet": self.sheet, "J2": self.J2,
                   "bits": self.bits, "digits": self.digits, "complete": int(self.complete),
                   "coefficient": self.coefficient, "amplitude": self.amplitude,
                   "coefficient_closed_form": self.coefficient_closed_form,
                   "flint_version": self.flint_version, "seconds": self.seconds,
                   **{f"body_{k}": str(v) for k, v in self.body.as_dict().items()},
                   "equations": "M(theta2_0) = int {E, H1} dt along the unperturbed "
                                "heteroclinic orbit (16) = Re(Z exp(i theta2_0)); Arb "
                                "quadrature; zeros by the Krawczyk test"})
        ds["M_mid"].attrs.update(long_name="Melnikov function, midpoint of the certified "
                                 "ball", units="energy units x time", equation="(16)")
        ds["M_rad"].attrs.update(long_name="radius of the certified ball",
                                 units="energy units x time")
        ds["M_float"].attrs.update(long_name="Melnikov function, float closed form",
                                   units="energy units x time", equation="(16)")
        ds["zero_mid"].attrs.update(long_name="simple zero of M (Krawczyk)", units="rad")
        ds["zero_rad"].attrs.update(long_name="radius of the zero's enclosure", units="rad")
        return ds


def certified_melnikov(body: RigidBody | BodySpec, *, branch: str = DEFAULT_BRANCH,
                       sheet: int = 1, J2: str = "1", digits: int = 30,
                       phases: Sequence[float] | None = None) -> CertifiedMelnikov:
    """Enclose ``M`` to ``digits`` correct digits and prove its zeros simple.

    Parameters
    ----------
    body : RigidBody or BodySpec
        A Hess or near-Hess body (``RigidBody.hess`` / ``near_hess``; read by
        :meth:`BodySpec.from_body`), or its exact spec.
    branch : {"theta1=0", "theta1=4phi0"}, default "theta1=0"
        The separatrix line. The default is every analysis' default, the Hess
        separatrix; on a Hess body that line does not split (M = 0).
    sheet : {+1, -1}, default 1
        Which of its two orbits.
    J2 : str, default "1"
        ``J2 = G`` of the level (a decimal).
    digits : int, default 30
        Correct significant digits asked of the amplitude (an integer in [5, 200]).
    phases : sequence of float, optional
        Phases to enclose ``M`` at (default 8 equal steps of ``[0, 2 pi)``).

    Returns
    -------
    CertifiedMelnikov

    Raises
    ------
    ValueError
        For a body off the (e1, e2) plane, a bad branch, sheet, level or ``digits``.
    ArithmeticError
        If the integral and the closed form do not overlap, or the digits asked are not
        reached.

    Examples
    --------
    >>> res = certified_melnikov(RigidBody.paper(), branch="theta1=4phi0", digits=30, phases=[0.0])
    >>> res.digits >= 30, len(res.zeros), res.complete
    (True, 2, True)
    """
    start = time.perf_counter()
    if isinstance(digits, bool) or not isinstance(digits, int) or not 5 <= digits <= 200:
        raise ValueError(f"digits must be an integer in [5, 200], got {digits!r}")
    spec = spec_of(body)
    J2 = decimal("J2", J2, positive=True, maximum=1e6)
    float_J2 = float(J2)
    if not isinstance(branch, str) or branch not in BRANCHES:
        raise ValueError(f"branch must be one of {BRANCHES}, got {branch!r}")
    if isinstance(sheet, bool) or sheet not in (1, -1):
        raise ValueError(f"sheet must be +1 or -1, got {sheet!r}")
    th = ((np.arange(8) * math.tau / 8).tolist() if phases is None
          else [float(p) for p in finite_array("phases", phases, ndim=1)])
    hess = BodySpec(spec.A, spec.B, spec.C, spec.branch).body()
    flt = melnikov_off_hess(hess, float(spec.epsilon), np.array(th, dtype=float),
                            J2=float_J2, branch=branch, sheet=sheet)
    amp_f = float(np.max(np.abs(melnikov_off_hess(
        hess, float(spec.epsilon), np.linspace(0.0, math.tau, 9), J2=float_J2,
        branch=branch, sheet=sheet))))
    # The integrand is ~ lambda while M ~ exp(-pi rho): buy back the cancellation.
    lost = max(0.0, -math.log2(amp_f)) if amp_f > 0.0 else 0.0
    bits = int(math.ceil((digits + 6) * math.log2(10) + lost + 24))
    Z, Zc, T = melnikov_coefficient(spec, branch=branch, sheet=sheet, J2=J2, bits=bits)
    with working_precision(bits):
        if not Z.overlaps(Zc):
            raise ArithmeticError(f"the certified integral Z = {Z} and the closed form "
                                  f"{Zc} do not overlap")
        amp = abs(Z)
        vals = [_M(Z, arb(p)) for p in th]
        # M = 0 identically on the Hess line of a Hess body and only there: the closed
        # form's factor sin(theta1/2 + epsilon) at theta1 = 0 (mod 2 pi), epsilon = 0 (the
        # floats' 0 or 4e-21 there are round-off, and a float 0 elsewhere is an underflow)
        hess_line = branch == DEFAULT_BRANCH and Decimal(spec.epsilon) == 0
        identically_zero = hess_line and amp.contains(0)
        dig = 0.0 if identically_zero else correct_digits(amp)
        if not identically_zero and dig < digits:
            why = (" (the float amplitude the precision is sized by underflows to 0)"
                   if amp_f == 0.0 else "")
            raise ArithmeticError(f"only {max(dig, 0.0):.1f} digits reached, {digits} "
                                  f"asked{why}")
        zeros: list[MelnikovZero] = []
        complete = False
        if not amp.contains(0):
            zeros, complete = _zeros(Z, digits)
    return CertifiedMelnikov(
        body=spec, branch=branch, sheet=sheet, J2=J2, bits=bits, coefficient=Z.str(
            digits + 5, radius=True), coefficient_closed_form=Zc.str(digits + 5, radius=True),
        amplitude=ball_text(amp, digits + 5), digits=dig, T=T, phases=tuple(th),
        values=tuple(ball_text(v, digits + 5) for v in vals),
        values_mid=tuple(float(v.mid()) for v in vals),
        values_rad=tuple(float(v.rad()) for v in vals),
        float_closed_form=tuple(float(v) for v in flt), zeros=tuple(zeros),
        complete=complete, seconds=time.perf_counter() - start)


def _zeros(Z: acb, digits: int) -> tuple[list[MelnikovZero], bool]:
    """Krawczyk boxes at ``pi/2 - arg Z + k pi``; the rest of the circle excluded."""
    pi = arb.pi()
    zeros = []
    wide = arb("0.1")
    centres = []
    for k in (0, 1):
        z = pi / 2 - Z.arg() + k * pi
        z = z - 2 * pi * math.floor(float(z.mid()) / math.tau)
        big = _krawczyk_zero(Z, z, wide)
        if big is None:
            raise ArithmeticError(f"the Krawczyk test failed on the box of radius 0.1 "
                                  f"around {float(z.mid())}")
        tight = _krawczyk_zero(Z, arb(big.zero), arb(10) ** (-digits + 3))
        zeros.append(tight if tight is not None else big)
        centres.append(float(z.mid()))
    zeros.sort(key=lambda zz: zz.zero_mid)
    complete = True
    cs = sorted(centres)
    for i, c in enumerate(cs):
        lo = c + 0.1
        hi = cs[(i + 1) % 2] + (math.tau if i == 1 else 0.0) - 0.1
        edges = np.linspace(lo, hi, 65)
        for a_, b_ in zip(edges[:-1], edges[1:], strict=True):
            box = arb((a_ + b_) / 2, (b_ - a_) / 2 * (1 + 1e-6))
            if _M(Z, box).contains(0):
                complete = False
    return zeros, complete
