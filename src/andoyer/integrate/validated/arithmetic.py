"""Ball arithmetic (Arb, through python-flint) for the heavy top: the body, the field (1).

Every certified computation of :mod:`andoyer.integrate.validated` and of
:mod:`andoyer.analysis.splitting.certified` reads the body and the equations from
here:

* :class:`BodySpec` -- the body as *decimal strings* (``A = "2.5"``, ``B = "2.0"``,
  ``C = "2.2"``, the branch of (2), the turn ``epsilon`` of the centre of mass off the Hess
  direction, ``mu``), so that a theorem is about the body the user named (the decimal
  2.2, not the binary float nearest it). :meth:`BodySpec.balls` encloses its derived
  parameters (``a = 1/A``, ``phi0`` of (2) and (11), ``r``) in Arb balls.
* :func:`field_terms` -- the Lie-Poisson field (1) derived by SymPy from the one
  Hamiltonian (:func:`andoyer.symbolic.hamiltonian.euler_poisson_field`) and split into
  constant, linear and quadratic monomials of the state with coefficients that are
  polynomials of the body's parameters; nothing is typed from the paper.
* :func:`evaluate` -- a SymPy expression evaluated exactly in any ring with ``+``, ``*``
  and integer powers (``arb``, ``acb``, ``acb_series``, plain numbers): rationals become
  exact quotients of integers, never binary floats.

Notes
-----
The Arb precision is python-flint's global ``flint.ctx.prec``;
:func:`working_precision` sets it for a block and restores it.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from functools import cache
from typing import Any

import flint
import sympy as sp
from flint import arb

__all__ = [
    "BodySpec",
    "BodyBalls",
    "working_precision",
    "evaluate",
    "field_terms",
    "ball_text",
    "ball_from_text",
    "correct_digits",
    "decimal",
    "precision",
    "spec_of",
    "FLINT_VERSION",
]

#: The python-flint version whose Arb arithmetic produced a result (recorded in
#: certificates: a certificate is re-checked with the same arithmetic).
FLINT_VERSION: str = str(flint.__version__)


@contextlib.contextmanager
def working_precision(bits: int) -> Iterator[None]:
    """Set Arb's working precision to ``bits`` inside the block (restored after).

    Parameters
    ----------
    bits : int
        Binary digits of the balls' midpoints (53 is double precision).

    Examples
    --------
    >>> with working_precision(200):
    ...     int(flint.ctx.prec)
    200
    """
    old = flint.ctx.prec
    flint.ctx.prec = int(bits)
    try:
        yield
    finally:
        flint.ctx.prec = old


def decimal(name: str, value: Any, *, positive: bool = False,
            maximum: float | None = None) -> str:
    """A decimal number as its text (a ``str`` kept as typed, a real as its shortest
    repr), or ``ValueError`` naming ``name``.

    Parameters
    ----------
    name : str
        The argument's name, for the error.
    value : str or real
        The number.
    positive : bool, default False
        Require ``value > 0``.
    maximum : float, optional
        Require ``value <= maximum``.

    Examples
    --------
    >>> decimal("G", "2.2"), decimal("G", 1.5)
    ('2.2', '1.5')
    """
    if isinstance(value, bool) or not isinstance(value, str | int | float):
        raise ValueError(f"{name} must be a decimal number (a string or a real), got "
                         f"{value!r}")
    text = value.strip() if isinstance(value, str) else repr(float(value))
    try:
        number = float(text)
    except ValueError:
        raise ValueError(f"{name} must be a decimal number, got {value!r}") from None
    if not math.isfinite(number):
        raise ValueError(f"{name} must be finite, got {value!r}")
    if positive and not number > 0.0:
        raise ValueError(f"{name} must be > 0, got {value!r}")
    if maximum is not None and abs(number) > maximum:
        raise ValueError(f"{name} must be at most {maximum:g} in size, got {value!r}")
    return text


def precision(name: str, bits: Any) -> int:
    """Arb's working precision, an integer in ``[53, 4096]``, or ``ValueError`` naming it.

    Parameters
    ----------
    name : str
        The argument's name.
    bits : int
        The precision.
    """
    from andoyer.validation import integer

    return integer(name, bits, 53, 4096)


def spec_of(body: Any, name: str = "body") -> BodySpec:
    """``body`` as a :class:`BodySpec` (a ``RigidBody`` read by :meth:`BodySpec.from_body`),
    or :class:`~andoyer.errors.ArgumentTypeError` naming ``name``.

    Parameters
    ----------
    body : RigidBody or BodySpec
        The body.
    name : str, default "body"
        The argument's name.
    """
    from andoyer.body import RigidBody
    from andoyer.errors import ArgumentTypeError

    if isinstance(body, BodySpec):
        return body
    if isinstance(body, RigidBody):
        try:
            return BodySpec.from_body(body)
        except ValueError as exc:
            raise ValueError(f"{name}: {exc}") from None
    raise ArgumentTypeError(f"{name} must be a RigidBody or a BodySpec, got "
                            f"{type(body).__name__} {body!r:.60}")


def ball_text(x: Any, digits: int | None = None) -> str:
    """A ball as the text Arb reads back (``"[m +/- r]"``), enclosing ``x``.

    Parameters
    ----------
    x : arb
        The ball.
    digits : int, optional
        Decimal digits of the midpoint (default: all the working precision carries).
    """
    n = digits if digits is not None else max(int(flint.ctx.prec * 0.30103) + 5, 17)
    return str(x.str(n, radius=True, more=True))


def ball_from_text(text: str) -> arb:
    """The ball of :func:`ball_text` (a ball that contains the one written).

    Parameters
    ----------
    text : str
        ``"[m +/- r]"`` or a decimal.
    """
    return arb(text)


def correct_digits(x: Any) -> float:
    """Correct significant decimal digits of a ball: ``-log10(rad / |mid|)`` (inf if exact).

    Parameters
    ----------
    x : arb
        The ball.
    """
    mid = abs(float(x.mid()))
    rad = float(x.rad())
    if rad == 0.0:
        return math.inf
    if mid == 0.0:
        return 0.0
    return -math.log10(rad / mid)


def evaluate(expr: sp.Expr, values: Mapping[sp.Symbol, Any]) -> Any:
    """Evaluate a polynomial-rational SymPy expression with ``+``, ``*`` and ``**`` only.

    Parameters
    ----------
    expr : sympy.Expr
        Sums, products, integer powers, rationals and symbols (no functions).
    values : mapping
        A value (an ``arb``, ``acb``, series or number) for every symbol of ``expr``.

    Raises
    ------
    ValueError
        For a function, a non-integer power or a float in ``expr`` (which would not be
        exact).

    Examples
    --------
    >>> x = sp.Symbol("x")
    >>> with working_precision(64):
    ...     print(evaluate(x**2 / 3 + 1, {x: arb(2)}).str(10))
    [2.333333333 +/- 3.34e-10]
    """
    if isinstance(expr, sp.Symbol):
        return values[expr]
    if isinstance(expr, sp.Integer):
        return int(expr)
    if isinstance(expr, sp.Rational):
        return arb(int(expr.p)) / int(expr.q)
    if isinstance(expr, sp.Add):
        total: Any = 0
        for term in expr.args:
            total = total + evaluate(term, values)
        return total
    if isinstance(expr, sp.Mul):
        prod: Any = 1
        for factor in expr.args:
            prod = prod * evaluate(factor, values)
        return prod
    if isinstance(expr, sp.Pow) and isinstance(expr.exp, sp.Integer) and expr.exp > 0:
        base = evaluate(expr.base, values)
        out = base
        for _ in range(int(expr.exp) - 1):
            out = out * base
        return out
    raise ValueError(f"cannot evaluate {expr!r} exactly in ball arithmetic (only sums, "
                     "products, positive integer powers, rationals and symbols)")


@dataclass(frozen=True)
class BodyBalls:
    """The derived parameters of a :class:`BodySpec` as Arb balls (one precision).

    Attributes
    ----------
    A, B, C, a, b, c, mu : arb
        Moments, inverse moments, ``mu``.
    phi0 : arb
        The Hess angle of the body's branch (2), (11): ``tan^2 phi0 = (c - b)/(a - c)``,
        with the branch's sign.
    epsilon : arb
        The turn of the centre of mass off the Hess direction.
    e1, e2, e3 : arb
        ``r = (cos(phi0 + epsilon), sin(phi0 + epsilon), 0)``.
    sigma : arb
        ``sqrt((b - c)(c - a))``.
    """

    A: arb
    B: arb
    C: arb
    a: arb
    b: arb
    c: arb
    mu: arb
    phi0: arb
    epsilon: arb
    e1: arb
    e2: arb
    e3: arb
    sigma: arb

    def params(self) -> tuple[arb, ...]:
        """``(a, b, c, mu, e1, e2, e3)``, the order of :attr:`RigidBody.params`."""
        return (self.a, self.b, self.c, self.mu, self.e1, self.e2, self.e3)


@dataclass(frozen=True)
class BodySpec:
    """A near-Hess body given exactly, by decimal strings.

    The centre of mass is at the angle ``branch * phi0 + epsilon`` in the (e1, e2) plane,
    ``phi0`` of the Hess condition (2) (``epsilon = 0``: a Hess body), as
    :meth:`andoyer.body.RigidBody.near_hess` builds it.

    Parameters
    ----------
    A, B, C : str
        Principal moments (decimals, ``A > C > B``).
    branch : {+1, -1}
        The branch of (2).
    epsilon : str
        The turn of the centre of mass (rad, decimal).
    mu : str
        Weight times the distance of the centre of mass (decimal).

    Examples
    --------
    >>> spec = BodySpec("2.5", "2.0", "2.2")
    >>> round(spec.body().phi0, 12) == round(spec.balls(64).phi0.mid().__float__(), 12)
    True
    """

    A: str
    B: str
    C: str
    branch: int = 1
    epsilon: str = "0"
    mu: str = "0"

    def __post_init__(self) -> None:
        for name in ("A", "B", "C", "epsilon", "mu"):
            text = getattr(self, name)
            if isinstance(text, bool) or not isinstance(text, str | int | float):
                raise ValueError(f"{name} must be a decimal number, got {text!r}")
            try:
                value = float(text)
            except (TypeError, ValueError):
                raise ValueError(f"{name} must be a decimal number, got {text!r}") from None
            if not math.isfinite(value):
                raise ValueError(f"{name} must be finite, got {text!r}")
            object.__setattr__(self, name, text if isinstance(text, str) else repr(value))
        A, B, C = float(self.A), float(self.B), float(self.C)
        if not (A > C > B > 0.0):
            raise ValueError(f"the Hess conditions (2) need A > C > B > 0, got A={self.A}, "
                             f"B={self.B}, C={self.C}")
        if float(self.mu) < 0.0:
            raise ValueError(f"mu must be >= 0, got {self.mu}")
        if isinstance(self.branch, bool) or self.branch not in (1, -1):
            raise ValueError(f"branch must be +1 or -1, got {self.branch!r}")

    @classmethod
    def from_body(cls, body: Any, epsilon: float | str | None = None) -> BodySpec:
        """The spec of a :class:`~andoyer.body.RigidBody` built by ``hess`` or ``near_hess``.

        The moments are read as the shortest decimals of their floats (``2.2`` is the
        decimal 2.2); ``epsilon`` defaults to the body's
        :attr:`~andoyer.body.RigidBody.hess_epsilon` rounded to 12 significant digits (the
        decimal a user typed, e.g. ``0.1``).

        Parameters
        ----------
        body : RigidBody
            A body with its centre of mass in the (e1, e2) plane and ``A > C > B``.
        epsilon : float or str, optional
            The turn, if known exactly.
        """
        hess = body.nearest_hess()
        branch = 1 if hess.e2 >= 0.0 else -1
        if epsilon is None:
            eps = body.hess_epsilon
            epsilon = "0" if eps == 0.0 else repr(float(f"{eps:.12g}"))
        return cls(repr(body.A), repr(body.B), repr(body.C), branch, str(epsilon),
                   repr(body.mu))

    def with_mu(self, mu: str) -> BodySpec:
        """The same body with another ``mu`` (a decimal).

        Parameters
        ----------
        mu : str
            The new ``mu``.
        """
        return BodySpec(self.A, self.B, self.C, self.branch, self.epsilon, mu)

    def body(self) -> Any:
        """The float :class:`~andoyer.body.RigidBody` nearest this spec (``near_hess``)."""
        from andoyer.body import RigidBody

        return RigidBody.near_hess(float(self.A), float(self.B), float(self.C),
                                   float(self.mu), float(self.epsilon), branch=self.branch)

    def balls(self, bits: int) -> BodyBalls:
        """Every derived parameter enclosed at ``bits`` of precision.

        Parameters
        ----------
        bits : int
            Working precision.
        """
        with working_precision(bits):
            A, B, C = arb(self.A), arb(self.B), arb(self.C)
            a, b, c = 1 / A, 1 / B, 1 / C
            phi0 = ((A * (C - B)) / (B * (A - C))).sqrt().atan() * self.branch
            eps = arb(self.epsilon)
            phi = phi0 + eps
            return BodyBalls(A=A, B=B, C=C, a=a, b=b, c=c, mu=arb(self.mu), phi0=phi0,
                             epsilon=eps, e1=phi.cos(), e2=phi.sin(), e3=arb(0),
                             sigma=((b - c) * (c - a)).sqrt())

    def as_dict(self) -> dict[str, Any]:
        """The spec as JSON-ready values."""
        return {"A": self.A, "B": self.B, "C": self.C, "branch": self.branch,
                "epsilon": self.epsilon, "mu": self.mu}


@dataclass(frozen=True)
class FieldTerms:
    """The field (1) as monomials: ``f_i = sum_k coef_ik(body) * y^(monomial_k)``.

    Attributes
    ----------
    terms : tuple
        Per component ``i``, a tuple of ``(coefficient, indices)``: ``indices`` is
        ``()`` (constant), ``(j,)`` or ``(j, k)`` with ``j <= k`` (the monomial
        ``y_j y_k``); ``coefficient`` a SymPy polynomial of the body symbols.
    mu_terms : tuple
        The same for ``df/dmu`` (the field is affine in ``mu``).
    """

    terms: tuple[tuple[tuple[sp.Expr, tuple[int, ...]], ...], ...]
    mu_terms: tuple[tuple[tuple[sp.Expr, tuple[int, ...]], ...], ...]


def _monomials(expr: sp.Expr, y: tuple[sp.Symbol, ...]
               ) -> tuple[tuple[sp.Expr, tuple[int, ...]], ...]:
    poly = sp.Poly(sp.expand(expr), *y)
    out = []
    for powers, coef in poly.terms():
        if coef == 0:
            continue
        if sum(powers) > 2:
            raise ValueError("the field (1) is quadratic; got a monomial of degree > 2")
        idx = tuple(j for j, p in enumerate(powers) for _ in range(p))
        out.append((sp.expand(coef), idx))
    return tuple(sorted(out, key=lambda t: (len(t[1]), t[1])))


@cache
def field_terms() -> FieldTerms:
    """The Euler-Poisson field (1), derived from H by SymPy, as monomials of the state.

    Examples
    --------
    >>> terms = field_terms().terms
    >>> len(terms), max(len(idx) for comp in terms for _, idx in comp)
    (6, 2)
    """
    from andoyer.symbolic.hamiltonian import S, euler_poisson_field

    f = euler_poisson_field()
    y = S.y
    terms = tuple(_monomials(e, y) for e in f)
    mu_terms = tuple(_monomials(sp.diff(e, S.mu), y) for e in f)
    return FieldTerms(terms=terms, mu_terms=mu_terms)


def body_symbols() -> tuple[sp.Symbol, ...]:
    """``(a, b, c, mu, e1, e2, e3)``: the SymPy symbols of :meth:`BodyBalls.params`."""
    from andoyer.symbolic.hamiltonian import S

    return S.body
