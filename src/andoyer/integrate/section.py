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

from andoyer.kernels._generated import SECTION_KINDS

__all__ = ["Section", "SECTION_KINDS"]

_CHART_OF = {
    **{k: "euler_poisson" for k in ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")},
    **{k: "andoyer" for k in ("l", "g", "L", "G")},
    **{k: "hess" for k in ("theta1", "theta2", "J1", "J2")},
}
ANGLES = ("l", "g", "theta1", "theta2")


@dataclass(frozen=True)
class Section:
    """The section ``coord = value``, crossed with ``coord`` increasing (``direction=+1``),
    decreasing (-1) or either way (0).

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
        if self.coord not in SECTION_KINDS:
            raise ValueError(f"unknown section coordinate {self.coord!r}; choose one of "
                             f"{', '.join(SECTION_KINDS)} (M and J3 are constants of motion)")
        try:
            v = float(self.value)
        except (TypeError, ValueError):
            raise ValueError(f"section value must be a number, got {self.value!r}") from None
        if not math.isfinite(v):
            raise ValueError(f"section value must be finite, got {v!r}")
        if self.direction not in (-1, 0, 1):
            raise ValueError(f"section direction must be +1, -1 or 0, got {self.direction!r}")
        if self.coord in ANGLES:
            v = math.remainder(v, 2 * math.pi) % (2 * math.pi)
        object.__setattr__(self, "value", v)

    @property
    def kind(self) -> int:
        """Index of the coordinate in :data:`SECTION_KINDS` (what engines take)."""
        return SECTION_KINDS.index(self.coord)

    @property
    def chart(self) -> str:
        """The chart the coordinate belongs to."""
        return _CHART_OF[self.coord]

    @property
    def is_angle(self) -> bool:
        return self.coord in ANGLES

    @classmethod
    def parse(cls, text: str) -> Section:
        """Parse ``"coord=value"`` with an optional ``":+"``, ``":-"`` or ``":0"`` direction."""
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
