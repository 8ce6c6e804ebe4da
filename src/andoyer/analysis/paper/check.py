"""Every formula the paper prints, encoded literally and checked against the derivation.

Each :class:`Formula` holds the paper's expression typed as printed (misprints
included), the expression derived by this package from ``H = (G, I^-1 G)/2 + mu (r,
gamma)`` (the generated kernels), and -- where the two disagree -- a corrected form
that is itself checked against the derivation. :func:`paper_check` evaluates them at
many random points (random bodies of the stated family, random regular states) and
returns one :class:`CheckRow` per formula with the verdict:

``holds``
    paper and derivation agree to ``RTOL`` at every point;
``misprint``
    they do not; ``nature`` says how (classified numerically where possible: the
    sign of the whole expression, of its mu-term, a constant factor) and
    ``corrected`` gives the formula the code uses;
``omission``
    what is printed holds but is incomplete or missing; ``corrected`` completes it.

Equation numbers are the paper's; "after (7)" etc. name unnumbered formulas.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from andoyer.charts.andoyer_deprit import from_andoyer, to_andoyer
from andoyer.kernels.generated import equations as K
from andoyer.validation import integer

__all__ = ["Formula", "CheckRow", "FORMULAS", "paper_check", "RTOL"]

#: Agreement threshold, relative to the largest magnitude of the derived value.
RTOL = 1e-9

Array = NDArray[np.float64]
Fn = Callable[[Any], Any]

sin, cos, sqrt, pi = np.sin, np.cos, np.sqrt, np.pi


@dataclass(frozen=True)
class Formula:
    """One printed formula and its derived counterpart.

    Attributes
    ----------
    label : str
        The paper's equation number or place ("(9)", "after (7)").
    name : str
        What the formula is.
    paper : callable
        ``paper(P)`` -> value(s): the formula as printed; ``P`` has attributes
        ``l, g, L, G, M, theta1, theta2, J1, J2, J3, a, b, c, mu, e1, e2, phi0,
        kappa, s, cc, G1..G3, gamma1..gamma3`` (arrays) where ``s = e1 sin l + e2 cos l``
        and ``cc = e1 cos l - e2 sin l``.
    derived : callable
        The same quantity from the package's derivation.
    points : str
        Point family: "general" (e3 = 0, any moments), "hess" (Hess bodies),
        with suffix "_M0" for ``M = 0``; "hess_solution" (theta1 = 0, Hess),
        "pendulum" (L = G, M = 0, Hess).
    corrected, corrected_text : callable, str
        The corrected formula (checked against ``derived``) and its text.
    nature : str
        How the printed formula is wrong, where the numbers alone cannot say it.
    omission : str
        For a formula that holds but is incomplete: what is missing.
    angle : bool
        The quantity is an angle: compared modulo ``2 pi``.
    """

    label: str
    name: str
    paper: Fn
    derived: Fn
    points: str = "general"
    corrected: Fn | None = None
    corrected_text: str = ""
    nature: str = ""
    omission: str = ""
    angle: bool = False


@dataclass(frozen=True)
class CheckRow:
    """Result of checking one :class:`Formula`.

    Attributes
    ----------
    label : str
        The paper's equation number or place, as in :class:`Formula`.
    name : str
        What the formula is.
    verdict : str
        ``"holds"``, or how it fails.
    max_rel_error : float
        Largest relative difference between the printed and the derived values over the
        points.
    nature : str
        How the printed formula is wrong, where the numbers alone cannot say it.
    corrected : str
        Text of the corrected formula ("" where none is needed).
    corrected_holds : bool or None
        Whether the corrected formula agrees with the derivation (None: none given).
    details : dict of str to float
        Further numbers of the check (e.g. the error of each variant).
    """

    label: str
    name: str
    verdict: str
    max_rel_error: float
    nature: str = ""
    corrected: str = ""
    corrected_holds: bool | None = None
    details: dict[str, float] = field(default_factory=dict)


# ---------------------------------------------------------------------- points
def _random_body(rng: np.random.Generator, n: int, hess: bool) -> dict[str, Array]:
    if hess:
        B = rng.uniform(1.0, 2.0, n)
        C = B * rng.uniform(1.05, 1.4, n)
        A = C + B * rng.uniform(0.05, 0.9, n)  # C < A < B + C (triangle inequality)
        phi0 = np.arctan(np.sqrt(A * (C - B) / (B * (A - C))))
    else:
        A, B, C = (rng.uniform(1.0, 2.0, n) for _ in range(3))
        phi0 = rng.uniform(0.0, 2.0 * pi, n)
    return {"A": A, "B": B, "C": C, "a": 1 / A, "b": 1 / B, "c": 1 / C,
            "e1": cos(phi0), "e2": sin(phi0), "phi0": phi0,
            "mu": rng.uniform(0.05, 1.0, n)}


def make_points(family: str, n: int = 200, seed: int = 20261121) -> SimpleNamespace:
    """Random points of a family (see :class:`Formula`), as a namespace of arrays."""
    rng = np.random.default_rng(seed)
    base, _, rest = family.partition("_")
    hess = base in ("hess", "pendulum")
    rest = "M0" if family in ("hess_solution", "pendulum") else rest
    P = _random_body(rng, n, hess)
    G = rng.uniform(0.5, 2.0, n)
    L = G * rng.uniform(-0.95, 0.95, n)
    M = np.zeros(n) if rest == "M0" else G * rng.uniform(-0.95, 0.95, n)
    l = rng.uniform(0.0, 2.0 * pi, n)
    g = rng.uniform(0.0, 2.0 * pi, n)
    if family == "hess_solution":
        l = np.mod(-P["phi0"], 2 * pi)  # theta1 = 0
    if family == "pendulum":
        L, M = G.copy(), np.zeros(n)
    P.update(l=l, g=g, L=L, G=G, M=M)
    P["kappa"] = P["a"] - P["b"]
    P["theta1"] = 2 * (l + P["phi0"])
    P["theta2"] = g - l - P["phi0"]
    P["J1"], P["J2"], P["J3"] = (G + L) / 2, G, M
    P["s"] = P["e1"] * sin(l) + P["e2"] * cos(l)
    P["cc"] = P["e1"] * cos(l) - P["e2"] * sin(l)
    y = from_andoyer(np.stack([l, g, L, G, M], axis=-1))
    for i, name in enumerate(("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")):
        P[name] = y[:, i]
    return SimpleNamespace(**P)


# ---------------------------------------------------------------------- derived values
def _H(P: Any, mu: Any = None) -> Array:
    m = P.mu if mu is None else mu
    return K.andoyer_hamiltonian(P.l, P.g, P.L, P.G, P.M, P.a, P.b, P.c, m, P.e1, P.e2, 0.0)


def _F(P: Any, i: int, mu: Any = None) -> Array:
    """Component i of d(l, g, L, G, M, m)/dt."""
    m = P.mu if mu is None else mu
    out = K.andoyer_field(P.l, P.g, P.L, P.G, P.M, P.a, P.b, P.c, m, P.e1, P.e2, 0.0)[i]
    return np.broadcast_to(out, P.l.shape)


def _HH(P: Any, mu: Any = None) -> Array:
    m = P.mu if mu is None else mu
    return K.hess_hamiltonian(P.theta1, P.theta2, P.J1, P.J2, P.J3, P.a, P.b, P.c, m, P.phi0)


def _FH(P: Any, i: int, mu: Any = None) -> Array:
    """Component i of d(theta1, theta2, J1, J2, J3, theta3)/dt."""
    m = P.mu if mu is None else mu
    out = K.hess_field(P.theta1, P.theta2, P.J1, P.J2, P.J3, P.a, P.b, P.c, m, P.phi0)[i]
    return np.broadcast_to(out, P.l.shape)


def _Pi(P: Any) -> Array:
    """Potential energy from the Euler-Poisson state: mu (r, gamma)."""
    return P.mu * (P.e1 * P.gamma1 + P.e2 * P.gamma2)


def _ep(P: Any) -> Array:
    return np.stack([P.G1, P.G2, P.G3, P.gamma1, P.gamma2, P.gamma3])


# Shorthands for the literal encodings.
def _rL(P: Any) -> Array:
    return sqrt(P.G**2 - P.L**2)


def _rM(P: Any) -> Array:
    return sqrt(P.G**2 - P.M**2)


def _Tl(P: Any) -> Array:  # a sin^2 l + b cos^2 l
    return P.a * sin(P.l) ** 2 + P.b * cos(P.l) ** 2


def _bracket(P: Any) -> Array:  # cos(theta1 - 2 phi0) - cos 2 phi0
    return cos(P.theta1 - 2 * P.phi0) - cos(2 * P.phi0)


def _gamma_paper(P: Any) -> Array:
    sL = sqrt(1 - (P.L / P.G) ** 2)
    sM = sqrt(1 - (P.M / P.G) ** 2)
    return np.stack([
        P.M / P.G * sL * sin(P.l) + P.L / P.G * sM * sin(P.l) * cos(P.g) + sM * cos(P.l) * sin(P.g),
        P.M / P.G * sL * cos(P.l) + P.L / P.G * sM * cos(P.l) * cos(P.g) - sM * sin(P.l) * sin(P.g),
        P.L * P.M / P.G**2 - sL * sM * cos(P.g),
    ])


def _fixed_points_residual(P: Any, theta1: Array, J1: Array) -> Array:
    """``|field|`` of the unperturbed (theta1, J1) system at given points (derived)."""
    # The points lie on the singular lines J1 = 0, J2: approach them to 1e-13.
    eps = 1e-13 * P.J2
    J1 = np.clip(J1, eps, P.J2 - eps)
    Q = SimpleNamespace(**{**vars(P), "theta1": theta1, "J1": J1, "J3": 0.0 * P.J3})
    return np.hypot(_FH(Q, 0, 0.0), _FH(Q, 2, 0.0)) / (np.abs(P.kappa) * P.J2**2)


_OMEGA = np.block([[np.zeros((3, 3)), np.eye(3)], [-np.eye(3), np.zeros((3, 3))]])


def _symplectic_defect(P: Any) -> Array:
    """``D^T Omega D`` of the map (15), D by central differences (the map is affine)."""
    from andoyer.charts.hess import hess_to_andoyer_expr

    def chart(z: Array) -> Array:
        t1, t2, t3, j1, j2, j3 = z
        l, g, L, G, M = hess_to_andoyer_expr(t1, t2, j1, j2, j3, P.phi0)
        return np.stack([l, g, t3 + 0.0 * l, L, G, M])

    z0 = np.stack([P.theta1, P.theta2, 0.0 * P.l, P.J1, P.J2, P.J3])
    D = np.empty((P.l.size, 6, 6))
    for j in range(6):
        dz = np.zeros_like(z0)
        dz[j] = 1e-3
        D[:, :, j] = ((chart(z0 + dz) - chart(z0 - dz)) / 2e-3).T
    return np.einsum("nji,jk,nkl->nil", D, _OMEGA, D)


# ---------------------------------------------------------------------- the formulas
FORMULAS: tuple[Formula, ...] = (
    Formula("(5)", "G in Andoyer-Deprit variables",
            lambda P: np.stack([_rL(P) * sin(P.l), _rL(P) * cos(P.l), P.L]),
            lambda P: _ep(P)[:3]),
    Formula("(6)", "gamma in Andoyer-Deprit variables", _gamma_paper, lambda P: _ep(P)[3:]),
    Formula("after (6)", "inverse map: l = arctg(G1/G2)",
            lambda P: np.arctan(P.G1 / P.G2),
            lambda P: to_andoyer(_ep(P).T)[:, 0], angle=True,
            nature="arctg(G1/G2) gives l only mod pi (the quadrant of (G1, G2) is lost)",
            corrected=lambda P: np.arctan2(P.G1, P.G2),
            corrected_text="l = atan2(G1, G2) (the paper's own sin l, cos l formulas)"),
    Formula("after (6)", "inverse map: sqrt(1 - M^2/G^2) sin g",
            lambda P: (P.G2 * P.gamma1 - P.G1 * P.gamma2) / sqrt(P.G1**2 + P.G2**2),
            lambda P: _rM(P) / P.G * sin(to_andoyer(_ep(P).T)[:, 1]),
            omission="cos g is not given; the code uses sqrt(1 - M^2/G^2) cos g = "
                     "(G3 (G1 gamma1 + G2 gamma2) - gamma3 (G1^2 + G2^2)) / (G sqrt(G1^2 + G2^2)) "
                     "and g = atan2"),
    Formula("(7)", "H0", lambda P: (_rL(P) ** 2 * _Tl(P) + P.L**2 * P.c) / 2,
            lambda P: _H(P, 0.0)),
    Formula("(7)", "H1, first form",
            lambda P: P.e1 * _gamma_paper(P)[0] + P.e2 * _gamma_paper(P)[1],
            lambda P: _H(P, 1.0) - _H(P, 0.0)),
    Formula("(7)", "H1, second form",
            lambda P: P.s * (P.M * _rL(P) + P.L * _rM(P) * cos(P.g)) / P.G**2
            + _rM(P) / P.G * sin(P.g) * P.cc,
            lambda P: _H(P, 1.0) - _H(P, 0.0)),
    Formula("after (7)", "dl/dt",
            lambda P: P.L * (P.c - _Tl(P))
            - P.mu / P.G**2 * (_rM(P) * cos(P.g) - P.M * P.L / _rL(P)) * P.s,
            lambda P: _F(P, 0),
            corrected=lambda P: P.L * (P.c - _Tl(P))
            + P.mu / P.G**2 * (_rM(P) * cos(P.g) - P.M * P.L / _rL(P)) * P.s,
            corrected_text="dl/dt = L (c - a sin^2 l - b cos^2 l) + mu/G^2 (sqrt(G^2 - M^2) cos g"
                           " - M L / sqrt(G^2 - L^2)) (e1 sin l + e2 cos l)"),
    Formula("after (7)", "dg/dt",
            lambda P: P.G * _Tl(P) - P.mu / (P.G**3 * _rM(P) * _rL(P)) * (
                P.G * P.M**2 * _rL(P) * sin(P.g) * P.cc
                - (P.M * _rM(P) * (P.G**2 - 2 * P.L**2)
                   + P.L * _rL(P) * (P.G**2 - 2 * P.M**2) * cos(P.g)) * P.s),
            lambda P: _F(P, 1),
            corrected=lambda P: P.G * _Tl(P) + P.mu / (P.G**3 * _rM(P) * _rL(P)) * (
                P.G * P.M**2 * _rL(P) * sin(P.g) * P.cc
                - (P.M * _rM(P) * (P.G**2 - 2 * P.L**2)
                   + P.L * _rL(P) * (P.G**2 - 2 * P.M**2) * cos(P.g)) * P.s),
            corrected_text="dg/dt = G (a sin^2 l + b cos^2 l) + mu/(G^3 sqrt(G^2-M^2) sqrt(G^2-L^2))"
                           " [G M^2 sqrt(G^2-L^2) sin g (e1 cos l - e2 sin l) - (M sqrt(G^2-M^2)"
                           " (G^2 - 2L^2) + L sqrt(G^2-L^2) (G^2 - 2M^2) cos g)"
                           " (e1 sin l + e2 cos l)]"),
    Formula("after (7)", "dm/dt",
            lambda P: -P.mu / (P.G**2 * _rM(P)) * (
                (_rM(P) * _rL(P) - P.M * P.L * cos(P.g)) * P.s - P.M * P.G * sin(P.g) * P.cc),
            lambda P: _F(P, 5),
            corrected=lambda P: P.mu / (P.G**2 * _rM(P)) * (
                (_rM(P) * _rL(P) - P.M * P.L * cos(P.g)) * P.s - P.M * P.G * sin(P.g) * P.cc),
            corrected_text="dm/dt = + mu/(G^2 sqrt(G^2-M^2)) [(sqrt(G^2-M^2) sqrt(G^2-L^2)"
                           " - M L cos g)(e1 sin l + e2 cos l) - M G sin g (e1 cos l - e2 sin l)]"),
    Formula("after (7)", "dL/dt",
            lambda P: -0.5 * _rL(P) ** 2 * (P.a - P.b) * sin(2 * P.l) + P.mu / P.G**2 * (
                -P.G * _rM(P) * sin(P.g) * P.s + (P.M * _rL(P) + P.L * _rM(P) * cos(P.g)) * P.cc),
            lambda P: _F(P, 2),
            corrected=lambda P: -0.5 * _rL(P) ** 2 * (P.a - P.b) * sin(2 * P.l) + P.mu / P.G**2 * (
                P.G * _rM(P) * sin(P.g) * P.s - (P.M * _rL(P) + P.L * _rM(P) * cos(P.g)) * P.cc),
            corrected_text="dL/dt = -(G^2 - L^2)(a - b) sin 2l / 2 + mu/G^2 [G sqrt(G^2-M^2) sin g"
                           " (e1 sin l + e2 cos l) - (M sqrt(G^2-L^2) + L sqrt(G^2-M^2) cos g)"
                           " (e1 cos l - e2 sin l)]"),
    Formula("after (7)", "dC/dt (a line with no variable C)",
            lambda P: -P.mu / 2 * _rM(P) * (P.L * sin(P.g) - P.s + P.G * cos(P.g) - P.cc),
            lambda P: _F(P, 3),
            nature="garbled duplicate of the dG/dt line: 'C' for G, 'mu/2' for mu/G^2, "
                   "'-' for products; there is no variable C",
            corrected=lambda P: P.mu / P.G**2 * _rM(P) * (
                P.L * sin(P.g) * P.s - P.G * cos(P.g) * P.cc),
            corrected_text="delete the line (see dG/dt)"),
    Formula("after (7)", "dG/dt",
            lambda P: P.mu / P.G**2 * _rM(P) * (P.L * sin(P.g) * P.s + P.G * cos(P.g) * P.cc),
            lambda P: _F(P, 3),
            nature="the term G cos g (e1 cos l - e2 sin l) has the wrong sign",
            corrected=lambda P: P.mu / P.G**2 * _rM(P) * (
                P.L * sin(P.g) * P.s - P.G * cos(P.g) * P.cc),
            corrected_text="dG/dt = mu/G^2 sqrt(G^2-M^2) [L sin g (e1 sin l + e2 cos l)"
                           " - G cos g (e1 cos l - e2 sin l)]"),
    Formula("after (7)", "dM/dt = 0", lambda P: 0.0 * P.l, lambda P: _F(P, 4)),
    Formula("(8)", "Hess condition (c - b) e1^2 = (a - c) e2^2, equivalent to (2)",
            lambda P: ((P.c - P.b) * P.e1**2 - (P.a - P.c) * P.e2**2) * (-P.A * P.B * P.C),
            lambda P: P.e1**2 * P.A * (P.C - P.B) - P.e2**2 * P.B * (P.A - P.C)),
    Formula("(8)", "invariant relation sqrt(G^2 - L^2)(e1 sin l + e2 cos l) = e1 G1 + e2 G2",
            lambda P: _rL(P) * P.s, lambda P: P.e1 * P.G1 + P.e2 * P.G2),
    Formula("(8)", "G^2 = L^2, M = 0 is invariant (physical pendulum): d(G1, G2, gamma3)/dt",
            lambda P: np.zeros((3, P.l.size)),
            lambda P: np.stack([np.asarray(K.ep_field(
                P.G1, P.G2, P.G3, P.gamma1, P.gamma2, P.gamma3, P.a, P.b, P.c, P.mu,
                P.e1, P.e2, 0.0)[i]) for i in (0, 1, 5)]),
            points="pendulum"),
    Formula("(9)", "unperturbed dl/dt", lambda P: P.L * (P.c - _Tl(P)),
            lambda P: _F(P, 0, 0.0)),
    Formula("(9)", "unperturbed dL/dt",
            lambda P: 0.5 * (P.G**2 - P.L**2) * (P.a - P.b) * sin(2 * P.l),
            lambda P: _F(P, 2, 0.0),
            corrected=lambda P: -0.5 * (P.G**2 - P.L**2) * (P.a - P.b) * sin(2 * P.l),
            corrected_text="dL/dt = -(G0^2 - L^2)(a - b) sin 2l / 2"),
    Formula("after (9)", "fixed points of (9) 'with any G0 > 0'",
            lambda P: 0.0 * P.l, lambda P: 0.0 * P.l,
            omission="the list is missing from the text",
            corrected_text="(l, L) = (0, 0), (pi, 0) [rotation about axis 2, centre], "
                           "(pi/2, 0), (3 pi/2, 0) [about axis 1, centre]; on L = +-G0 (the "
                           "chart's singular lines, rotation about the middle axis 3, a saddle) "
                           "the points sin^2 l = (b - c)/(b - a), i.e. l = +-phi0, pi +- phi0"),
    Formula("M = 0 eqs", "dl/dt at M = 0",
            lambda P: P.L * (P.c - _Tl(P)) - P.mu / P.G * cos(P.g) * P.s,
            lambda P: _F(P, 0), points="general_M0",
            corrected=lambda P: P.L * (P.c - _Tl(P)) + P.mu / P.G * cos(P.g) * P.s,
            corrected_text="dl/dt = L (c - a sin^2 l - b cos^2 l) + mu/G cos g (e1 sin l + e2 cos l)"),
    Formula("M = 0 eqs", "dg/dt at M = 0",
            lambda P: P.G * _Tl(P) + P.mu / P.G**2 * P.L * cos(P.g) * P.s,
            lambda P: _F(P, 1), points="general_M0",
            corrected=lambda P: P.G * _Tl(P) - P.mu / P.G**2 * P.L * cos(P.g) * P.s,
            corrected_text="dg/dt = G (a sin^2 l + b cos^2 l) - mu L/G^2 cos g (e1 sin l + e2 cos l)"),
    Formula("M = 0 eqs", "dm/dt at M = 0",
            lambda P: -P.mu / P.G**2 * _rL(P) * P.s,
            lambda P: _F(P, 5), points="general_M0",
            corrected=lambda P: P.mu / P.G**2 * _rL(P) * P.s,
            corrected_text="dm/dt = + mu/G^2 sqrt(G^2 - L^2)(e1 sin l + e2 cos l)"),
    Formula("M = 0 eqs", "dL/dt at M = 0",
            lambda P: -0.5 * _rL(P) ** 2 * (P.a - P.b) * sin(2 * P.l) + P.mu / P.G * (
                P.L * cos(P.g) * P.cc - P.G * sin(P.g) * P.s + P.G * cos(P.g) * P.cc),
            lambda P: _F(P, 2), points="general_M0",
            corrected=lambda P: -0.5 * _rL(P) ** 2 * (P.a - P.b) * sin(2 * P.l) + P.mu / P.G * (
                -P.L * cos(P.g) * P.cc + P.G * sin(P.g) * P.s),
            corrected_text="dL/dt = -(G^2 - L^2)(a - b) sin 2l / 2 + mu/G [G sin g (e1 sin l +"
                           " e2 cos l) - L cos g (e1 cos l - e2 sin l)]",
            nature="the mu-bracket has the wrong sign and a spurious term G cos g (e1 cos l - "
                   "e2 sin l)"),
    Formula("M = 0 eqs", "dG/dt at M = 0 (not printed)",
            lambda P: 0.0 * P.l, lambda P: 0.0 * P.l,
            omission="the M = 0 list gives no dG/dt, though G is not conserved for mu > 0",
            corrected_text="dG/dt = mu/G [L sin g (e1 sin l + e2 cos l) - G cos g "
                           "(e1 cos l - e2 sin l)]"),
    Formula("(10)", "H at M = 0",
            lambda P: (_rL(P) ** 2 * _Tl(P) + P.L**2 * P.c) / 2
            + P.mu * (P.L / P.G * cos(P.g) * P.s + sin(P.g) * P.cc),
            lambda P: _H(P), points="general_M0"),
    Formula("after (10)", "Pi = mu (e1 gamma1 + e2 gamma2) at M = 0",
            lambda P: P.mu * P.L / P.G * cos(P.g) * P.s + P.mu * sin(P.g) * P.cc,
            _Pi, points="general_M0"),
    Formula("(11)", "Pi with e1 = cos phi0, e2 = sin phi0",
            lambda P: P.mu * (P.L / P.G * cos(P.g) * sin(P.l + P.phi0)
                              + sin(P.g) * cos(P.l + P.phi0)),
            _Pi, points="hess_M0"),
    Formula("after (11)", "phi0 = arctg(sqrt(c - b)/sqrt(a - c)) in (0, pi/2)",
            lambda P: np.real(np.arctan(np.sqrt((P.c - P.b) + 0j) / np.sqrt((P.a - P.c) + 0j))),
            lambda P: P.phi0, points="hess",
            omission="both radicands are negative (a < c < b since A > C > B); only their "
                     "ratio is real: phi0 = arctg sqrt((c - b)/(a - c))"),
    Formula("after (11)", "Pi = mu sin g on the Hess solution",
            lambda P: P.mu * sin(P.g), _Pi, points="hess_solution",
            omission="holds on the branch theta1 = 0 (l = -phi0) at M = 0; on theta1 = 2 pi "
                     "(l = pi - phi0) Pi = -mu sin g, and for M != 0 "
                     "Pi = mu sqrt(1 - M^2/G^2) sin g"),
    Formula("after (11)", "Pi = mu^-1 sin(g + l - phi0) on the physical pendulum",
            lambda P: P.mu**-1 * sin(P.g + P.l - P.phi0), _Pi, points="pendulum",
            nature="mu^-1 for mu, and -phi0 for +phi0",
            corrected=lambda P: P.mu * sin(P.g + P.l + P.phi0),
            corrected_text="Pi = mu sin(g + l + phi0) on L = G (and mu sin(g - l - phi0) on L = -G)"),
    Formula("(12)", "H0 = (a G1^2 + b G2^2 + c G3^3)/2",
            lambda P: (P.a * P.G1**2 + P.b * P.G2**2 + P.c * P.G3**3) / 2,
            lambda P: _H(P, 0.0),
            nature="exponent: c G3^3 for c G3^2",
            corrected=lambda P: (P.a * P.G1**2 + P.b * P.G2**2 + P.c * P.G3**2) / 2,
            corrected_text="H0 = (a G1^2 + b G2^2 + c G3^2)/2"),
    Formula("after (12)", "2T - cG^2 = (a - c) G1^2 - (c - b) G2^2",
            lambda P: (P.a - P.c) * P.G1**2 - (P.c - P.b) * P.G2**2,
            lambda P: 2 * _H(P, 0.0) - P.c * P.G**2,
            omission="the intermediate line repeats the c G3^3 misprint of (12) twice; "
                     "the two cancel, the result holds"),
    Formula("after (12)", "(a - c)G1^2 - (c - b)G2^2 = kappa (G^2 - L^2) sin(l + phi0) sin(l - phi0)",
            lambda P: (P.a - P.c) / P.e1**2 * _rL(P) ** 2 * sin(P.l + P.phi0) * sin(P.l - P.phi0),
            lambda P: 2 * _H(P, 0.0) - P.c * P.G**2, points="hess"),
    Formula("after (12)", "kappa = (a - c)/e1^2 = a - b on a Hess body",
            lambda P: (P.a - P.c) / P.e1**2, lambda P: P.a - P.b, points="hess"),
    Formula("(13)", "H0 = (c G^2 + kappa (G^2 - L^2) sin(l + phi0) sin(l - phi0))/2",
            lambda P: (P.c * P.G**2 + P.kappa * _rL(P) ** 2 * sin(P.l + P.phi0)
                       * sin(P.l - P.phi0)) / 2,
            lambda P: _H(P, 0.0), points="hess"),
    Formula("(14)-(15)", "the change is canonical: D^T Omega D = Omega for D = d(l,g,m,L,G,M)/"
            "d(theta1,theta2,theta3,J1,J2,J3)",
            lambda P: np.broadcast_to(_OMEGA, (P.l.size, 6, 6)),
            _symplectic_defect, points="hess"),
    Formula("(14)-(15)", "H is invariant under the change: H(theta, J) = H(l, g, L, G, M)",
            lambda P: _HH(P), lambda P: _H(P), points="hess"),
    Formula("after (15)", "H(theta, J), general M",
            lambda P: P.J1 * (P.J1 - P.J2) * (P.a - P.b) * _bracket(P) + P.c * P.J2**2 / 2
            + P.mu * (P.J1 * sin(P.theta1 + P.theta2) + (P.J2 - P.J1) * sin(P.theta2))
            * sqrt(P.J2**2 - P.J3**2) / P.J2**2
            + 2 * P.mu * sin(P.theta1 / 2) * P.J3 * sqrt(P.J1 * (P.J2 - P.J1)) / P.J2**2,
            lambda P: _HH(P), points="hess"),
    Formula("after (15)", "Hess relation sqrt(J1 (J2 - J1)) sin(theta1/2) = (e1 G1 + e2 G2)/2",
            lambda P: sqrt(P.J1 * (P.J2 - P.J1)) * sin(P.theta1 / 2),
            lambda P: (P.e1 * P.G1 + P.e2 * P.G2) / 2, points="hess"),
    Formula("before (16)", "H(theta, J) at M = 0",
            lambda P: P.c / 2 * P.J2**2 + P.kappa * P.J1 * (P.J1 - P.J2) * _bracket(P)
            + P.mu / P.J2 * (P.J1 * sin(P.theta1 + P.theta2) + (P.J2 - P.J1) * sin(P.theta2)),
            lambda P: _HH(P), points="hess_M0"),
    Formula("(16)", "dtheta1/dt",
            lambda P: P.kappa * (2 * P.J1 - P.J2) * _bracket(P)
            + P.mu / P.J2 * (sin(P.theta1 + P.theta2) - sin(P.theta2)),
            lambda P: _FH(P, 0), points="hess_M0"),
    Formula("(16)", "dtheta2/dt",
            lambda P: P.c * P.J2 - P.kappa * P.J1 * _bracket(P)
            + P.mu * P.J1 / P.J2**2 * (sin(P.theta2) - sin(P.theta1 + P.theta2)),
            lambda P: _FH(P, 1), points="hess_M0"),
    Formula("(16)", "dJ1/dt",
            lambda P: P.kappa * P.J1 * (P.J1 - P.J2) * sin(P.theta1 - 2 * P.phi0)
            - P.mu * P.J1 / P.J2 * cos(P.theta1 + P.theta2),
            lambda P: _FH(P, 2), points="hess_M0"),
    Formula("(16)", "dJ2/dt",
            lambda P: -P.mu / P.J2 * ((P.J2 - P.J1) * cos(P.theta2)
                                      + P.J1 * cos(P.theta1 + P.theta2)),
            lambda P: _FH(P, 3), points="hess_M0"),
    Formula("after (16)", "dtheta3/dt = 2 mu sqrt(J1 (J2 - J1))/J2^2 sin(theta1/2)",
            lambda P: 2 * P.mu * sqrt(P.J1 * (P.J2 - P.J1)) / P.J2**2 * sin(P.theta1 / 2),
            lambda P: _FH(P, 5), points="hess_M0",
            omission="correct, and so contradicts the paper's own dm/dt at M = 0 (theta3 = m), "
                     "whose sign is wrong"),
    Formula("after Fig. 3", "unperturbed dtheta1/dt",
            lambda P: P.kappa * (2 * P.J1 - P.J2) * _bracket(P),
            lambda P: _FH(P, 0, 0.0), points="hess_M0"),
    Formula("after Fig. 3", "unperturbed dJ1/dt",
            lambda P: P.kappa * P.J1 * (P.J1 - P.J2) * sin(P.theta1 - 2 * P.phi0),
            lambda P: _FH(P, 2, 0.0), points="hess_M0"),
    Formula("after Fig. 3", "the four fixed points of the unperturbed system",
            lambda P: np.stack([0.0 * P.l] * 4),
            lambda P: np.stack([
                _fixed_points_residual(P, 0.0 * P.l, 0.0 * P.l),
                _fixed_points_residual(P, 0.0 * P.l, P.J2),
                _fixed_points_residual(P, 4 * P.phi0, 0.0 * P.l),
                _fixed_points_residual(P, 4 * P.phi0, P.J2)]),
            points="hess_M0",
            omission="all four lie on the chart's singular lines J1 = 0 (L = -G) and J1 = J2 "
                     "(L = G), where a whole line of theta1 is one state (rotation about the "
                     "middle axis 3, a saddle); the centres are missing",
            corrected_text="also (theta1, J1) = (2 phi0, J2/2) [rotation about axis 2] and "
                           "(2 phi0 + pi, J2/2) [about axis 1], both centres (mod 2 pi)"),
)


# ---------------------------------------------------------------------- checking
def _compare(f: Fn, d: Fn, P: Any, angle: bool) -> float:
    vf = np.asarray(f(P), dtype=float)
    vd = np.asarray(d(P), dtype=float)
    diff = vf - vd
    if angle:
        diff = np.angle(np.exp(1j * diff))
    if angle:
        return float(np.max(np.abs(diff)))
    scale = max(float(np.max(np.abs(vd))), float(np.max(np.abs(vf))))
    # Where both sides vanish (identities "= 0") the error is absolute.
    return float(np.max(np.abs(diff)) / (scale if scale > 1e-12 else 1.0))


def _classify(form: Formula, P: Any) -> str:
    """Say numerically how a printed formula differs from the derivation."""
    vf = np.asarray(form.paper(P), dtype=float)
    vd = np.asarray(form.derived(P), dtype=float)
    if form.angle:
        d = np.angle(np.exp(1j * (vf - vd)))
        if np.allclose(np.abs(d[np.abs(d) > 1e-9]), pi):
            return "angle off by pi on half of the points (quadrant lost)"
        return "wrong angle"
    ok = np.abs(vd) > 1e-8 * np.max(np.abs(vd))
    ratio = vf[ok] / vd[ok]
    if ratio.size and np.allclose(ratio, -1.0, rtol=1e-8):
        return "sign of the whole expression is wrong"
    if ratio.size and np.allclose(ratio, ratio.flat[0], rtol=1e-8):
        return f"constant factor {ratio.flat[0]:.6g}"
    # Split into the unperturbed part and the mu-term.
    P0 = SimpleNamespace(**{**vars(P), "mu": 0.0 * P.mu})
    try:
        e0 = _compare(form.paper, form.derived, P0, False)
    except (TypeError, ValueError, ZeroDivisionError, FloatingPointError):
        return "wrong expression"
    if e0 < RTOL:
        dm_f = vf - np.asarray(form.paper(P0), dtype=float)
        dm_d = vd - np.asarray(form.derived(P0), dtype=float)
        ok = np.abs(dm_d) > 1e-8 * np.max(np.abs(dm_d))
        r = dm_f[ok] / dm_d[ok]
        if r.size and np.allclose(r, -1.0, rtol=1e-8):
            return "the mu-independent part holds; the mu-term has the wrong sign"
        return "the mu-independent part holds; the mu-term is wrong"
    return "wrong expression"


def paper_check(n: int = 200, seed: int = 20261121) -> list[CheckRow]:
    """Check every printed formula of the paper against the derivation.

    Parameters
    ----------
    n : int
        Random points per formula.
    seed : int
        Seed of the points (the check is deterministic).

    Returns
    -------
    list of CheckRow
        In the order of the paper.

    Examples
    --------
    >>> rows = paper_check(n=20)
    >>> next(r.verdict for r in rows if r.label == "(12)")
    'misprint'
    """
    n, seed = integer("n", n, 1), integer("seed", seed, 0)
    rows = []
    cache: dict[str, SimpleNamespace] = {}
    with np.errstate(divide="ignore", invalid="ignore"):
        for form in FORMULAS:
            P = cache.setdefault(form.points, make_points(form.points, n, seed))
            err = _compare(form.paper, form.derived, P, form.angle)
            corrected_holds = None
            if form.corrected is not None:
                corrected_holds = _compare(form.corrected, form.derived, P, form.angle) < RTOL
            if err < RTOL:
                verdict = "omission" if form.omission else "holds"
                nature = form.omission
            else:
                verdict = "misprint"
                auto = _classify(form, P)
                nature = f"{form.nature} ({auto})" if form.nature else auto
            rows.append(CheckRow(form.label, form.name, verdict, err, nature,
                                 form.corrected_text if verdict != "holds" else "",
                                 corrected_holds))
    return rows
