"""One table of names: code name <-> paper symbol <-> meaning <-> equation <-> storage name,
plot label and units. Dataset variables, Zarr names, plot labels and the README's notation
table all take their names from here.

Storage names differ ignoring case (``l``/``L`` and ``g``/``G`` would collide on
case-insensitive file systems such as Zarr directory stores), hence ``l_angle``,
``L_action`` and the like. The problem is nondimensional: moments of inertia, ``mu``,
times and actions are in the body's units; angles in radians (units ``"rad"``),
everything else has units ``"1"``.

Examples
--------
>>> storage_name("l"), storage_name("theta1"), storage_name("l_angle")
('l_angle', 'theta1', 'l_angle')
>>> COORDINATE["L_action"].label, COORDINATE["theta1"].units
('$L$', 'rad')
>>> coordinates("andoyer")
('l', 'g', 'L', 'G', 'M')
"""

from __future__ import annotations

from typing import NamedTuple

__all__ = ["Symbol", "NOTATION", "Coordinate", "COORDINATES", "COORDINATE", "CHART_COORDS",
           "ANGLES", "storage_name", "coordinates", "label"]


class Symbol(NamedTuple):
    """A row of the notation table of the README (several coordinates per row)."""

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


class Coordinate(NamedTuple):
    """One coordinate or integral as the code stores and draws it."""

    code: str       #: the name in the code and the API (the paper's symbol in ASCII)
    storage: str    #: the dataset / Zarr variable name
    symbol: str     #: LaTeX symbol (dataset attr ``symbol``)
    long_name: str  #: dataset attr ``long_name``
    equation: str   #: the paper's equation numbers
    units: str      #: ``"rad"`` for angles, ``"1"`` otherwise

    @property
    def label(self) -> str:
        """Axis label with the paper's symbol (matplotlib mathtext)."""
        return f"${self.symbol}$" if self.symbol else self.storage


COORDINATES: tuple[Coordinate, ...] = (
    Coordinate("G1", "G1", "G_1", "angular momentum, body axis 1", "(1)", "1"),
    Coordinate("G2", "G2", "G_2", "angular momentum, body axis 2", "(1)", "1"),
    Coordinate("G3", "G3", "G_3", "angular momentum, body axis 3", "(1)", "1"),
    Coordinate("gamma1", "gamma1", "\\gamma_1", "upward vertical, body axis 1", "(1)", "1"),
    Coordinate("gamma2", "gamma2", "\\gamma_2", "upward vertical, body axis 2", "(1)", "1"),
    Coordinate("gamma3", "gamma3", "\\gamma_3", "upward vertical, body axis 3", "(1)", "1"),
    Coordinate("l", "l_angle", "l", "Andoyer-Deprit angle l", "(5)-(6)", "rad"),
    Coordinate("g", "g_angle", "g", "Andoyer-Deprit angle g", "(5)-(6)", "rad"),
    Coordinate("m", "m_angle", "m", "Andoyer-Deprit cyclic angle m (node longitude)", "(4)",
               "rad"),
    Coordinate("L", "L_action", "L", "projection of G on body axis 3", "(5)", "1"),
    Coordinate("G", "G_action", "G", "length of the angular momentum", "(5)", "1"),
    Coordinate("M", "M_action", "M", "area integral (G, gamma)", "(4)", "1"),
    Coordinate("theta1", "theta1", "\\theta_1", "Hess-chart angle 2(l + phi0), in [0, 4 pi)",
               "(14)", "rad"),
    Coordinate("theta2", "theta2", "\\theta_2", "Hess-chart angle g - l - phi0", "(14)", "rad"),
    Coordinate("theta3", "theta3", "\\theta_3", "Hess-chart cyclic angle m", "(14)", "rad"),
    Coordinate("J1", "J1", "J_1", "Hess-chart action (G + L)/2", "(14)", "1"),
    Coordinate("J2", "J2", "J_2", "Hess-chart action G", "(14)", "1"),
    Coordinate("J3", "J3", "J_3", "Hess-chart action M", "(14)", "1"),
    Coordinate("H", "H", "H", "energy", "(1)", "1"),
    Coordinate("area", "area", "(G, \\gamma)", "area integral", "(1)", "1"),
    Coordinate("geometric", "geometric", "|\\gamma|^2", "geometric integral", "(1)", "1"),
    Coordinate("singular", "singular", "",
               "Singular flags of the Andoyer-Deprit chart (0: regular)", "", "1"),
)

#: Storage name -> its coordinate (code names that differ are keys too).
COORDINATE: dict[str, Coordinate] = {
    **{c.storage: c for c in COORDINATES}, **{c.code: c for c in COORDINATES
                                              if c.code not in {d.storage for d in COORDINATES}}}

#: The state order of each chart (the cyclic angle, m or theta3, last where it exists).
CHART_COORDS: dict[str, tuple[str, ...]] = {
    "euler_poisson": ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3"),
    "andoyer": ("l", "g", "L", "G", "M"),
    "hess": ("theta1", "theta2", "J1", "J2", "J3"),
}

#: Storage names of the angles (NaN-aware wrapping in plots, units rad).
ANGLES: tuple[str, ...] = tuple(c.storage for c in COORDINATES
                                if c.units == "rad" and c.code not in ("m", "theta3"))


def storage_name(code: str) -> str:
    """The dataset name of a coordinate given by its code name (or its storage name)."""
    try:
        return COORDINATE[code].storage
    except KeyError:
        raise ValueError(f"unknown coordinate {code!r}; known: "
                         f"{', '.join(c.code for c in COORDINATES)}") from None


def coordinates(chart: str) -> tuple[str, ...]:
    """The code names of a chart's coordinates, in state order."""
    try:
        return CHART_COORDS[chart]
    except KeyError:
        raise ValueError(f"unknown chart {chart!r}; choose one of "
                         f"{', '.join(CHART_COORDS)}") from None


def label(name: str) -> str:
    """The axis label (mathtext) of a coordinate given by code or storage name."""
    return COORDINATE[name].label if name in COORDINATE else name
