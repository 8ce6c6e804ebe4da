"""Poincare sections as frozen objects: ``coordinate = value`` crossed in a direction.

The coordinate may belong to any chart: Euler-Poisson (``G1``..``gamma3``),
Andoyer-Deprit (``l``, ``g``, ``L``, ``G``) or Hess (``theta1``, ``theta2``, ``J1``,
``J2``). Angles are taken mod 2 pi without spurious crossings at the wrap: the section
function is ``sin(angle - value)`` times a positive factor and a crossing counts only
where ``cos(angle - value) > 0`` (:mod:`andoyer.symbolic.sections`).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.charts.andoyer_deprit import singular_distances
from andoyer.integrate.engines.base import SectionEvent
from andoyer.kernels.generated.equations import SECTION_KINDS
from andoyer.notation import SECTION_ANGLES, SECTION_COORDINATES

__all__ = ["Section", "SectionPlane", "SECTION_PLANES", "SECTION_KINDS", "SECTION_SINGULAR_RTOL"]

#: A crossing of an angle section counts only where the state's relative distance to
#: every singular set the angle depends on (G = 0 relative to the orbit's momentum
#: scale, L = +-G, ``|M| = G``) exceeds this: closer, the angle is resolved no better than
#: (state error) / distance, i.e. to worse than ~1e-6 rad, and at the set itself it is
#: undefined (a "singular passage", reported apart from the crossings).
SECTION_SINGULAR_RTOL = 1e-6

#: Columns of :func:`andoyer.charts.andoyer_deprit.singular_distances` an angle needs:
#: 0 (G = 0), 1 (L = +-G: the node of the invariant and body planes), 2 (``|M| = G``: the
#: node of the invariant and horizontal planes) -- from :data:`andoyer.notation.
#: SECTION_COORDINATES`, as the chart of each coordinate and the angles.
_ANGLE_NEEDS = {k: s.needs for k, s in SECTION_COORDINATES.items() if s.needs}
_CHART_OF = {k: s.chart for k, s in SECTION_COORDINATES.items() if s.chart is not None}
ANGLES = SECTION_ANGLES


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


@dataclass(frozen=True)
class Section:
    """The section ``coord = value``, crossed with ``coord`` increasing (``direction=+1``),
    decreasing (-1) or either way (0).

    Parameters
    ----------
    coord : str
        A coordinate of any chart (:data:`SECTION_KINDS`: ``"G3"``, ``"gamma1"``, ...,
        ``"L"``, ``"g"``, ``"theta2"``, ...); not ``M`` or ``J3``, constants of motion.
    value : float, default 0
        The plane ``coord = value``; an angle is reduced to ``[0, 2 pi)``.
    direction : {1, -1, 0}, default 1
        Crossings with ``coord`` increasing, decreasing, or both.

    Examples
    --------
    >>> Section("theta2", 0.0)
    Section(coord='theta2', value=0.0, direction=1)
    >>> Section.parse("G3=0:-")
    Section(coord='G3', value=0.0, direction=-1)
    """

    coord: str
    value: float = 0.0
    direction: int = 1

    def __post_init__(self) -> None:
        if not isinstance(self.coord, str) or self.coord not in SECTION_KINDS:
            raise ValueError(f"unknown section coordinate {self.coord!r}; choose one of "
                             f"{', '.join(SECTION_KINDS)} (M and J3 are constants of motion)")
        try:
            if isinstance(self.value, bool | str | bytes):
                raise TypeError
            v = float(self.value)
        except (TypeError, ValueError):
            raise ValueError(f"section value must be a number, got {self.value!r}") from None
        if not math.isfinite(v):
            raise ValueError(f"section value must be finite, got {v!r}")
        if isinstance(self.direction, bool) or self.direction not in (-1, 0, 1):
            raise ValueError(f"section direction must be +1, -1 or 0, got {self.direction!r}")
        if self.coord in ANGLES:
            v = math.remainder(v, 2 * math.pi) % (2 * math.pi)
        object.__setattr__(self, "value", v)

    @property
    def kind(self) -> int:
        """Index of the coordinate in :data:`SECTION_KINDS` (what engines take)."""
        return SECTION_KINDS.index(self.coord)

    def event(self) -> SectionEvent:
        """What engines take: :class:`~andoyer.integrate.engines.base.SectionEvent`.

        >>> Section.parse("G3=0:-").event()
        SectionEvent(coord='G3', value=0.0, direction=-1)
        """
        return SectionEvent(self.coord, self.value, self.direction)

    @property
    def chart(self) -> str:
        """The chart the coordinate belongs to."""
        return _CHART_OF[self.coord]

    @property
    def plane(self) -> SectionPlane:
        """The plane filled on this section (``g`` and ``theta2`` sections only).

        >>> Section.parse("theta2=0").plane.x
        'theta1'
        """
        if self.coord not in SECTION_PLANES:
            raise ValueError(f"a section of {self.coord!r} has no filled plane: choose 'g' "
                             "(plane (l, L)) or 'theta2' (plane (theta1, J1))")
        return SECTION_PLANES[self.coord]

    @property
    def is_angle(self) -> bool:
        return self.coord in ANGLES

    def defined_distance(self, y: ArrayLike, scale: ArrayLike) -> NDArray[np.float64]:
        """Relative distance of Euler-Poisson states to where the coordinate is undefined.

        ``inf`` for the smooth coordinates (``G1``, ..., ``J2``: defined everywhere);
        for an angle the smallest :func:`~andoyer.charts.andoyer_deprit.singular_distances`
        column it depends on, ``G`` measured against ``scale`` (the orbit's momentum
        scale, :func:`~andoyer.charts.euler_poisson.momentum_bound`).

        Examples
        --------
        >>> y = [[0.0, 0.6, 0.8, 0.0, 0.0, 1.0], [0.0, 0.0, 1e-9, 0.0, 0.0, 1.0]]
        >>> Section("l", 0.0).defined_distance(y, 1.0).round(12).tolist()
        [0.6, 0.0]
        >>> Section("G3", 0.0).defined_distance(y, 1.0).tolist()
        [inf, inf]
        """
        arr = np.asarray(y, dtype=float)
        if self.coord not in _ANGLE_NEEDS:
            return np.full(arr.shape[:-1], np.inf)
        d = singular_distances(arr, scale)
        return np.min(d[..., list(_ANGLE_NEEDS[self.coord])], axis=-1)

    @classmethod
    def parse(cls, text: str) -> Section:
        """Parse ``"coord=value"`` with an optional ``":+"``, ``":-"`` or ``":0"`` direction.

        Parameters
        ----------
        text : str
            The section as the command line writes it: ``"theta2=0"``, ``"G3=0:-"``.

        Examples
        --------
        >>> Section.parse("theta2=1.5:-").direction
        -1
        """
        m = re.fullmatch(r"\s*(\w+)\s*=\s*([^:\s]+)\s*(?::\s*([+-]?[01]?|[+-]))?\s*", text)
        if not m:
            raise ValueError(f"cannot parse section {text!r}; write e.g. 'g=0', "
                             "'theta2=1.5:+' or 'G3=0:-'")
        coord, value, d = m.groups()
        direction = {None: 1, "": 1, "+": 1, "+1": 1, "1": 1, "-": -1, "-1": -1, "0": 0}.get(d)
        if direction is None:
            raise ValueError(f"bad section direction {d!r} in {text!r}; use +, - or 0")
        try:
            val = float(value)
        except ValueError:
            raise ValueError(f"section value {value!r} in {text!r} is not a number") from None
        return cls(coord, val, direction)

    def attrs(self) -> dict[str, str | float | int]:
        """Flat attributes for datasets."""
        return {"section_coord": self.coord, "section_value": self.value,
                "section_direction": self.direction, "section_chart": self.chart}
