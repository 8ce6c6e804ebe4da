"""Every Hamiltonian and every equation of motion, derived from one H with SymPy.

``H = (G, I^-1 G)/2 + mu (r, gamma)`` comes from
:func:`andoyer.charts.euler_poisson.hamiltonian_expr` (the one source); each chart's
Hamiltonian is that expression composed with the chart map, and each vector field is
obtained by differentiation:

* Euler-Poisson, the Lie-Poisson form (1):
  ``dG/dt = G x dH/dG + gamma x dH/dgamma``, ``dgamma/dt = gamma x dH/dG``;
* Andoyer-Deprit, the canonical form (4) with M a parameter and m by quadrature;
* Hess chart, the canonical equations in ``(theta, J)`` (general form of (16)) with
  ``theta3 = m`` by quadrature.

SymPy runs here only: when the kernels are (re)generated
(:mod:`andoyer.symbolic.codegen`) and in checks. Results are cached per process.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from andoyer.charts.andoyer_deprit import andoyer_to_ep_expr
from andoyer.charts.euler_poisson import hamiltonian_expr
from andoyer.charts.hess import hess_to_ep_expr

__all__ = [
    "Symbols",
    "S",
    "H_euler_poisson",
    "H_andoyer",
    "H_hess",
    "euler_poisson_field",
    "euler_poisson_jacobian",
    "andoyer_field",
    "hess_field",
]


@dataclass(frozen=True)
class Symbols:
    """The SymPy symbols of the package, named as in the paper (ASCII).

    Attributes
    ----------
    G1, G2, G3 : sympy.Symbol
        Body-frame angular momentum (real), Eq. (1).
    gamma1, gamma2, gamma3 : sympy.Symbol
        Body-frame vertical unit vector (real), Eq. (1).
    l, g, L, G, M : sympy.Symbol
        Andoyer-Deprit angles and actions, Eqs. (5)-(7) (``G`` positive).
    theta1, theta2, J1, J2, J3 : sympy.Symbol
        Hess-chart coordinates, Eqs. (13)-(14) (``J1``, ``J2`` positive).
    a, b, c : sympy.Symbol
        Inverse moments of inertia ``1/A, 1/B, 1/C`` (positive).
    mu : sympy.Symbol
        Weight times the distance of the centre of mass (non-negative).
    e1, e2, e3 : sympy.Symbol
        Unit vector ``r`` towards the centre of mass.
    phi0 : sympy.Symbol
        The Hess angle ``phi0`` of the body, Eq. (13).
    """

    G1: sp.Symbol = sp.Symbol("G1", real=True)
    G2: sp.Symbol = sp.Symbol("G2", real=True)
    G3: sp.Symbol = sp.Symbol("G3", real=True)
    gamma1: sp.Symbol = sp.Symbol("gamma1", real=True)
    gamma2: sp.Symbol = sp.Symbol("gamma2", real=True)
    gamma3: sp.Symbol = sp.Symbol("gamma3", real=True)
    l: sp.Symbol = sp.Symbol("l", real=True)
    g: sp.Symbol = sp.Symbol("g", real=True)
    L: sp.Symbol = sp.Symbol("L", real=True)
    G: sp.Symbol = sp.Symbol("G", positive=True)
    M: sp.Symbol = sp.Symbol("M", real=True)
    theta1: sp.Symbol = sp.Symbol("theta1", real=True)
    theta2: sp.Symbol = sp.Symbol("theta2", real=True)
    J1: sp.Symbol = sp.Symbol("J1", positive=True)
    J2: sp.Symbol = sp.Symbol("J2", positive=True)
    J3: sp.Symbol = sp.Symbol("J3", real=True)
    a: sp.Symbol = sp.Symbol("a", positive=True)
    b: sp.Symbol = sp.Symbol("b", positive=True)
    c: sp.Symbol = sp.Symbol("c", positive=True)
    mu: sp.Symbol = sp.Symbol("mu", nonnegative=True)
    e1: sp.Symbol = sp.Symbol("e1", real=True)
    e2: sp.Symbol = sp.Symbol("e2", real=True)
    e3: sp.Symbol = sp.Symbol("e3", real=True)
    phi0: sp.Symbol = sp.Symbol("phi0", real=True)

    @property
    def y(self) -> tuple[sp.Symbol, ...]:
        """Euler-Poisson state, order of :data:`andoyer.charts.euler_poisson.STATE`."""
        return (self.G1, self.G2, self.G3, self.gamma1, self.gamma2, self.gamma3)

    @property
    def andoyer(self) -> tuple[sp.Symbol, ...]:
        return (self.l, self.g, self.L, self.G, self.M)

    @property
    def hess(self) -> tuple[sp.Symbol, ...]:
        return (self.theta1, self.theta2, self.J1, self.J2, self.J3)

    @property
    def body(self) -> tuple[sp.Symbol, ...]:
        """``(a, b, c, mu, e1, e2, e3)``, the order of :attr:`RigidBody.params`."""
        return (self.a, self.b, self.c, self.mu, self.e1, self.e2, self.e3)

    @property
    def hess_body(self) -> tuple[sp.Symbol, ...]:
        """``(a, b, c, mu, phi0)``: a body with ``e = (cos phi0, sin phi0, 0)``."""
        return (self.a, self.b, self.c, self.mu, self.phi0)


S = Symbols()


def _factor_radicands(expr: sp.Expr) -> sp.Expr:
    """Write every square root's radicand in factored form (better round-off)."""
    return expr.replace(
        lambda e: isinstance(e, sp.Pow) and e.exp == sp.Rational(1, 2),
        lambda e: sp.sqrt(sp.factor(e.base)),
    )


@cache
def H_euler_poisson() -> sp.Expr:
    """H of Eq. (1) in the Euler-Poisson variables."""
    return hamiltonian_expr(*S.y, *S.body)


@cache
def H_andoyer() -> sp.Expr:
    """H of Eq. (7) in Andoyer-Deprit variables: Eq. (1) composed with (5)-(6)."""
    ep = andoyer_to_ep_expr(*S.andoyer, sin=sp.sin, cos=sp.cos, sqrt=sp.sqrt)
    return _factor_radicands(hamiltonian_expr(*ep, *S.body))


@cache
def H_hess() -> sp.Expr:
    """H in the Hess chart: Eq. (1) composed with (15) and (5)-(6).

    The centre of mass is ``e = (cos phi0, sin phi0, 0)``.

    Valid for any ``a, b, c``; on a Hess body it equals the paper's (theta, J) form.
    """
    theta1, theta2, J1, J2, J3 = S.hess
    G1, G2, G3, gamma1, gamma2, gamma3 = hess_to_ep_expr(
        theta1, theta2, J1, J2, J3, S.phi0, sin=sp.sin, cos=sp.cos, sqrt=sp.sqrt)
    H = hamiltonian_expr(G1, G2, G3, gamma1, gamma2, gamma3, S.a, S.b, S.c, S.mu,
                         sp.cos(S.phi0), sp.sin(S.phi0), 0)
    return _factor_radicands(H)


def _cross(u: sp.Matrix, v: sp.Matrix) -> sp.Matrix:
    return u.cross(v)


@cache
def euler_poisson_field() -> tuple[sp.Expr, ...]:
    """Right-hand side of the Lie-Poisson equations (1), order of ``STATE``."""
    H = H_euler_poisson()
    Gv = sp.Matrix(S.y[:3])
    gv = sp.Matrix(S.y[3:])
    dH_dG = sp.Matrix([sp.diff(H, s) for s in S.y[:3]])
    dH_dgamma = sp.Matrix([sp.diff(H, s) for s in S.y[3:]])
    Gdot = _cross(Gv, dH_dG) + _cross(gv, dH_dgamma)
    gdot = _cross(gv, dH_dG)
    return tuple(sp.expand(e) for e in (*Gdot, *gdot))


@cache
def euler_poisson_jacobian() -> tuple[sp.Expr, ...]:
    """Jacobian ``J = d f / d y`` of the field (1), row-major: ``J[i][j] = d f_i / d y_j``.

    The matrix of the variational (tangent) equations ``dw/dt = J(y) w`` of (1),
    obtained by differentiating :func:`euler_poisson_field` (nothing typed by hand).
    """
    f = sp.Matrix(euler_poisson_field())
    J = f.jacobian(sp.Matrix(S.y))
    return tuple(sp.expand(J[i, j]) for i in range(len(S.y)) for j in range(len(S.y)))


@cache
def andoyer_field() -> tuple[sp.Expr, ...]:
    """Canonical equations (4): ``(dl, dg, dL, dG, dM, dm)/dt``, with ``dM/dt = 0``."""
    H = H_andoyer()
    l, g, L, G, M = S.andoyer
    return (sp.diff(H, L), sp.diff(H, G), -sp.diff(H, l), -sp.diff(H, g), sp.Integer(0),
            sp.diff(H, M))


@cache
def hess_field() -> tuple[sp.Expr, ...]:
    """Canonical equations in the Hess chart: ``d(theta1, theta2, J1, J2, J3, theta3)/dt``.

    Their ``M = 0`` form is the paper's (16); ``dtheta3/dt = dH/dJ3`` is the
    quadrature for the cyclic angle.
    """
    H = H_hess()
    theta1, theta2, J1, J2, J3 = S.hess
    return (sp.diff(H, J1), sp.diff(H, J2), -sp.diff(H, theta1), -sp.diff(H, theta2),
            sp.Integer(0), sp.diff(H, J3))
