"""One table: code name <-> paper symbol <-> meaning <-> equation <-> storage name.

Storage names differ ignoring case (``l``/``L`` and ``g``/``G`` would collide on
case-insensitive file systems such as Zarr directory stores).
"""

from __future__ import annotations

from typing import NamedTuple

__all__ = ["Symbol", "NOTATION"]


class Symbol(NamedTuple):
    code: str
    paper: str
    meaning: str
    equation: str
    storage: str


NOTATION: tuple[Symbol, ...] = (
    Symbol("A, B, C", "A, B, C", "principal moments of inertia (A > C > B for Hess)", "(1), (2)",
           "A, B, C"),
    Symbol("a, b, c", "a, b, c", "inverse moments 1/A, 1/B, 1/C", "(1)", "a, b, c"),
    Symbol("mu", "μ", "weight x distance of the centre of mass", "(1)", "mu"),
    Symbol("r = (e1, e2, e3)", "r = (e1, e2, e3)", "unit vector to the centre of mass", "(1)",
           "e1, e2, e3"),
    Symbol("G1, G2, G3", "G = (Ap, Bq, Cr)", "angular momentum, body frame", "(1)",
           "G1, G2, G3"),
    Symbol("gamma1, gamma2, gamma3", "γ", "upward vertical unit vector, body frame", "(1)",
           "gamma1, gamma2, gamma3"),
    Symbol("l", "l", "angle from Ox to the node of Σ with Oxy", "(5)-(6)", "l_angle"),
    Symbol("g", "g", "angle in Σ between the two nodes", "(5)-(6)", "g_angle"),
    Symbol("m", "m", "node longitude (cyclic)", "(4)", "m_angle"),
    Symbol("L", "L", "projection of G on the body axis 3 (= G3)", "(5)", "L_action"),
    Symbol("G", "G", "length of the angular momentum", "(5)", "G_action"),
    Symbol("M", "M", "projection of G on the vertical, area integral (G, γ)", "(4), (6)",
           "M_action"),
    Symbol("phi0", "φ0", "angle of r in the G1-G2 plane: e1 = cos φ0, e2 = sin φ0", "(11)",
           "phi0"),
    Symbol("kappa", "κ", "(a - c)/e1² = a - b", "(13)", "kappa"),
    Symbol("theta1, theta2, theta3", "θ1, θ2, θ3", "2(l + φ0), g - l - φ0, m", "(14)",
           "theta1, theta2, theta3"),
    Symbol("J1, J2, J3", "J1, J2, J3", "(G + L)/2, G, M", "(14)", "J1, J2, J3"),
    Symbol("H", "H", "Hamiltonian ½(G, IG) + μ(r, γ)", "(1), (7), (10), (13)", "H"),
)
