"""One table of names: code name <-> paper symbol <-> meaning <-> equation <-> storage name,
plot label and units. Dataset variables, Zarr names, plot labels and the README's notation
table all take their names from here; and one vocabulary (:data:`TERMS`) of what users
pass: the API parameter, the CLI flag and the scan key of each quantity.

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

from dataclasses import dataclass
from typing import Literal, NamedTuple

__all__ = ["Symbol", "NOTATION", "Coordinate", "COORDINATES", "COORDINATE", "CHART_COORDS",
           "ANGLES", "SectionCoordinate", "SECTION_COORDINATES", "SECTION_ANGLES",
           "SectionPlane", "SECTION_PLANES",
           "section_symbol", "storage_name", "coordinates", "label", "Term", "TERMS", "VOCABULARY"]


class Symbol(NamedTuple):
    """A row of the notation table of the README (several coordinates per row).

    Parameters
    ----------
    code : str
        Name(s) in the code.
    paper : str
        The paper's symbol(s).
    meaning : str
        What they are.
    equation : str
        The paper's equation that defines them.
    storage : str
        Name(s) in datasets.
    """

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
    Symbol("H", "H", "Hamiltonian ½(G, I⁻¹G) + μ(r, γ)", "(1), (7), (10), (13)", "H"),
)


class Coordinate(NamedTuple):
    """One coordinate or integral as the code stores and draws it.

    Parameters
    ----------
    code : str
        Name in the code (``"l"``, ``"theta1"``).
    storage : str
        Name in datasets (``"l_angle"``, ``"theta1"``).
    symbol : str
        Its symbol (mathtext) in figures.
    long_name : str
        The ``long_name`` attribute of its dataset variable.
    equation : str
        The paper's equation that defines it (e.g. ``"(7)"``).
    units : str
        Its units (``"rad"``, ``"1"``).
    """

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


class SectionCoordinate(NamedTuple):
    """A coordinate a Poincare section ``coord = value`` can be taken on.

    Parameters
    ----------
    code : str
        Its name (a section kind of the generated kernels,
        :data:`andoyer.kernels.generated.equations.SECTION_KINDS`).
    chart : str or None
        The chart it belongs to (None: an angle of the analysis modules only, not a
        chart coordinate: ``psi``).
    needs : tuple of int
        The columns of :func:`andoyer.charts.andoyer_deprit.singular_distances` where
        it is undefined (an angle: 0 ``G = 0``, 1 ``L = +-G``, 2 ``|M| = G``; empty:
        smooth, defined everywhere).
    reversal : int or None
        ``s`` with ``f(R y; s value) = s f(y; value)`` under the time reversal
        ``R = diag(-1, -1, -1, 1, 1, 1)`` of (1) (checked by SymPy in
        ``tests/symbolic/test_sections.py``); None: ``R`` does not map its sections onto
        sections of it.
    """

    code: str
    chart: str | None
    needs: tuple[int, ...]
    reversal: int | None


#: Every section coordinate, by code (the one table: the charts of the sections, the
#: angles and where they are undefined, which sections a forward-only engine can run
#: backward, and their symbols via :data:`COORDINATE`, derive from it).
SECTION_COORDINATES: dict[str, SectionCoordinate] = {s.code: s for s in (
    *(SectionCoordinate(k, "euler_poisson", (), -1) for k in ("G1", "G2", "G3")),
    *(SectionCoordinate(k, "euler_poisson", (), 1) for k in ("gamma1", "gamma2", "gamma3")),
    SectionCoordinate("l", "andoyer", (0, 1), None),
    SectionCoordinate("g", "andoyer", (0, 1, 2), -1),
    SectionCoordinate("L", "andoyer", (), -1),
    SectionCoordinate("G", "andoyer", (), 1),
    SectionCoordinate("theta1", "hess", (0, 1), 1),
    SectionCoordinate("theta2", "hess", (0, 1, 2), None),
    SectionCoordinate("J1", "hess", (), None),
    SectionCoordinate("J2", "hess", (), 1),
    SectionCoordinate("psi", None, (), 1),
)}
#: The angles of the charts a section can be taken on.
SECTION_ANGLES = tuple(k for k, s in SECTION_COORDINATES.items()
                       if s.needs and s.chart is not None)


@dataclass(frozen=True)
class SectionPlane:
    """The plane of a filled section: ``coord = const`` spans two coordinates of its
    chart, and the remaining action is solved from ``H = h``.

    Coordinates are ordered ``(plane x, section angle, plane y, solved action, area
    constant)``: ``storage`` gives their dataset names, ``symbols`` their ASCII names,
    ``text`` the axis labels ``(x, y, action, section coordinate)`` in plain Unicode.

    Attributes
    ----------
    chart : {"andoyer", "hess"}
        The chart whose coordinates span the plane.
    coord : str
        The section coordinate (``"g"`` or ``"theta2"``).
    storage : tuple of 5 str
        Dataset names of ``(plane x, section angle, plane y, solved action, area
        constant)``.
    symbols : tuple of 5 str
        Their ASCII names.
    text : tuple of 4 str
        Axis labels ``(x, y, action, section coordinate)`` in plain Unicode.
    equations : str
        The paper's equations of the chart (e.g. ``"(7)"``, ``"(14)"``).
    """

    chart: Literal["andoyer", "hess"]
    coord: str
    storage: tuple[str, str, str, str, str]
    symbols: tuple[str, str, str, str, str]
    text: tuple[str, str, str, str]
    equations: str

    @property
    def x(self) -> str:
        """Storage name of the horizontal axis."""
        return self.storage[0]

    @property
    def y(self) -> str:
        """Storage name of the vertical axis."""
        return self.storage[2]

    @property
    def action(self) -> str:
        """Storage name of the action solved from ``H = h``."""
        return self.storage[3]


#: Section coordinate -> its plane: the one definition (fill, explorer, plots).
SECTION_PLANES: dict[str, SectionPlane] = {
    "g": SectionPlane("andoyer", "g",
                      ("l_angle", "g_angle", "L_action", "G_action", "M_action"),
                      ("l", "g", "L", "G", "M"), ("l", "L", "G", "g"),
                      "H of Eq. (7) in the Andoyer-Deprit variables (5)-(6) of Kyrychenko; "
                      "section g = const, G solved from H(l, g, L, G, M) = h"),
    "theta2": SectionPlane("hess", "theta2",
                           ("theta1", "theta2", "J1", "J2", "J3"),
                           ("theta1", "theta2", "J1", "J2", "J3"), ("θ1", "J1", "J2", "θ2"),
                           "H in the Hess variables (14)-(15) of Kyrychenko (the Hamiltonian "
                           "after Eq. (15)); section theta2 = const, J2 solved from "
                           "H(theta1, theta2, J1, J2, J3 = M) = h"),
}


def section_symbol(code: str) -> str:
    """The symbol (mathtext, without ``$``) of a section coordinate given by its code.

    Parameters
    ----------
    code : str
        A section coordinate's code (``"theta2"``) or storage name (``"g_angle"``).

    Examples
    --------
    >>> section_symbol("theta2"), section_symbol("g_angle"), section_symbol("psi")
    ('\\\\theta_2', 'g', 'psi')
    """
    c = COORDINATE.get(code)
    return c.symbol if c is not None and c.symbol else code


def storage_name(code: str) -> str:
    """The dataset name of a coordinate given by its code name (or its storage name).

    Parameters
    ----------
    code : str
        A coordinate's code name (or its storage name).
    """
    try:
        return COORDINATE[code].storage
    except KeyError:
        raise ValueError(f"unknown coordinate {code!r}; known: "
                         f"{', '.join(c.code for c in COORDINATES)}") from None


def coordinates(chart: str) -> tuple[str, ...]:
    """The code names of a chart's coordinates, in state order.

    Parameters
    ----------
    chart : str
        ``"euler_poisson"``, ``"andoyer"`` or ``"hess"``.
    """
    try:
        return CHART_COORDS[chart]
    except KeyError:
        raise ValueError(f"unknown chart {chart!r}; choose one of "
                         f"{', '.join(CHART_COORDS)}") from None


def label(name: str) -> str:
    """The axis label (mathtext) of a coordinate given by code or storage name.

    Parameters
    ----------
    name : str
        A coordinate's code or storage name.
    """
    return COORDINATE[name].label if name in COORDINATE else name


# ---------------------------------------------------------------------- the vocabulary
class Term(NamedTuple):
    """One thing a user passes, under its one name in the API, on the command line, in a
    scan file.

    Parameters
    ----------
    api : str
        The parameter's name in the Python API.
    meaning : str
        What it is (the start of the flag's help).
    config : str, optional
        Its key in a scan file (None: scan files do not take it).
    cli : str, optional
        Its command-line flag (None: ``--`` and the API name with ``-`` for ``_``).
    """

    api: str                  #: the Python parameter name
    meaning: str              #: what it is (CLI help and docs start from it)
    config: str | None = None  #: key in a scan's TOML (None: not a scan key)
    cli: str | None = None    #: the flag, when it is not ``--`` + api with ``-`` for ``_``

    @property
    def flag(self) -> str:
        """The command-line flag: derived from the API name, unless the row says why not.

        >>> VOCABULARY["n_crossings"].flag, VOCABULARY["h"].flag
        ('--n-crossings', '--energy')
        """
        return self.cli or "--" + self.api.replace("_", "-")


#: The vocabulary of the API, the CLI and the scan files: one row per quantity. A CLI flag
#: is ``--`` + the API name (``_`` -> ``-``) except ``--energy`` (``-h`` is help); a scan
#: key is the API name. ``tests/test_vocabulary.py`` checks every command, every scan task
#: and the analyses' signatures against this table.
TERMS: tuple[Term, ...] = (
    Term("h", "energy level H = h", "h", cli="--energy"),
    Term("M", "area constant (G, gamma) = M", "M"),
    Term("mu", "weight x distance of the centre of mass", "mu"),
    Term("epsilon", "turn of the centre of mass off the Hess direction in the (e1, e2) "
         "plane", "epsilon"),
    Term("A", "principal moment of inertia A", "A"),
    Term("B", "principal moment of inertia B", "B"),
    Term("C", "principal moment of inertia C", "C"),
    Term("r", "direction of the centre of mass (e1, e2, e3)", "r"),
    Term("section", "section 'theta2=VALUE' (plane theta1, J1) or 'g=VALUE' (plane l, L); "
         "':-' for the decreasing direction", "section"),
    Term("n_orbits", "orbits seeded on the section plane (about this many plane points)",
         "n_orbits"),
    Term("n_crossings", "crossings of the section per orbit", "n_crossings"),
    Term("sampling", "how the orbits are seeded on the plane: grid, sobol or halton",
         "sampling"),
    Term("seed", "seed of the scrambled Sobol/Halton points", "seed"),
    Term("boundary_grid", "grid of the accessible-region search", "boundary_grid"),
    Term("t_max", "integrate at most to this time", "t_max"),
    Term("t_end", "integration time of every orbit", "t_end"),
    Term("precession0", "initial precession angle about the vertical (rad): the attitude "
         "about the vertical that the state (G, gamma) leaves free"),
    Term("n", "grid of the section plane: N (N x N) or (NX, NY)", "n"),
    Term("indicator", "chaos indicator: fli, megno", "indicator"),
    Term("tangent", "space of the initial tangent vectors: leaf or energy", "tangent"),
    Term("root", "which root of the missing action where the level has several sheets",
         "root"),
    Term("chunk", "orbits per chunk (bounds memory)"),
    Term("n_times", "output times of the indicators"),
    Term("n_samples", "samples of each orbit for NAFF"),
    Term("window", "Hann window order of NAFF"),
    Term("margin", "MEGNO threshold above the regular reference", "margin"),
    Term("engine", "integration engine (a name of andoyer.integrate.engines.ENGINES)", "engine"),
    Term("rtol", "relative tolerance of the mixed criterion atol + rtol abs(y)", "rtol"),
    Term("atol", "absolute tolerance of the mixed criterion atol + rtol abs(y)", "atol"),
    Term("tol", "tolerance of a method that takes one number", "tol"),
    Term("G", "level h = c G^2/2 of the rotation about the middle axis", "G"),
    Term("branch", "heteroclinic line: 'theta1=0' (the Hess separatrix) or "
         "'theta1=4phi0'", "branch"),
    Term("sheet", "which orbit of the heteroclinic line: +1, or -1 for theta1 + 2 pi"),
    Term("digits", "correct significant digits asked of a certified (ball) result"),
    Term("kind", "which theorem a certificate states: 'melnikov' (first order in mu) or "
         "'transversal' (at a finite mu)"),
    Term("rotation", "whose unstable manifold a finite-mu proof follows: +1 (P+) or -1 (P-)"),
    Term("mu_radius", "half-width of the mu interval a finite-mu proof covers at once"),
    Term("half_width", "relative half-width of the piece of W^u a finite-mu proof carries"),
    Term("n_phase", "phases g of the splitting grid (even)", "n_phase"),
    Term("delta", "distance of the fundamental domains from the periodic orbits", "delta"),
    Term("psi0", "section psi = atan2(gamma1, gamma2) = psi0 of the rotation orbits"),
    Term("long_double", "integrate in 80-bit extended precision"),
    Term("max_order", "largest order p + q of the p/q resonances (island chains) listed"),
    Term("order", "degree N of the normal form in the distance to the centre (even)"),
    Term("order_mu", "order in mu of the Lie-Deprit normal form of the island chains"),
    Term("degree", "degree N of the section map's Taylor polynomial (jet transport) and its "
                   "Birkhoff normal form at an elliptic periodic orbit"),
    Term("head", "partial quotients of a noble rotation number before its tail of ones"),
    Term("axis", "body axis (1 or 2) of the regime of tori"),
    Term("n_convergents", "continued-fraction convergents p/q followed"),
    Term("mu_range", "interval of mu where a critical mu is sought"),
    Term("h_values", "energy levels h of a curve over the levels (the critical mu's)"),
)

#: API name -> its term.
VOCABULARY: dict[str, Term] = {t.api: t for t in TERMS}
