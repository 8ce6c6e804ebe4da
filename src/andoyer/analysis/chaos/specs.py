"""What a chaos map computes, in two frozen objects: where its orbits start
(:class:`MapGrid`) and what is integrated from each start (:class:`IndicatorRun`).

:func:`~andoyer.analysis.chaos.lyapunov.chaos_map` takes the physics (body, energy
level ``h``, area constant ``M``, section) as arguments, and these two objects for the
rest, as diffrax's ``diffeqsolve`` takes a controller and an event, so that its signature
says in three words what a map is: a grid, an indicator run, an engine. Each object checks
its fields when it is made (``andoyer.validation``: the message names the field).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

from andoyer.analysis.chaos.registry import INDICATORS, MAP_CHOICES, MAP_EXTRAS, chosen
from andoyer.integrate.engines.base import Tolerance
from andoyer.validation import box, choice, grid, integer, positive

__all__ = ["MapGrid", "IndicatorRun", "INDICATOR_CHOICES", "TANGENT_SPACES", "ROOTS"]

#: One of :data:`INDICATOR_CHOICES` (the registry's map indicators, or all of them).
Indicator = str
Tangent = Literal["energy", "leaf"]
Root = Literal["largest", "smallest"]

#: What a chaos map can hold: one of the registry's map indicators (the FLI, the mean
#: MEGNO), or all of them ("both": one integration).
INDICATOR_CHOICES = MAP_CHOICES
#: Admissible initial tangent spaces (see :mod:`andoyer.analysis.chaos.lyapunov`).
TANGENT_SPACES = ("energy", "leaf")
#: Which action where the level has several sheets above a point of the plane.
ROOTS = ("largest", "smallest")


@dataclass(frozen=True)
class MapGrid:
    """Where the orbits of a chaos map start: the cell centres of an ``nx x ny`` grid on
    the section's plane.

    Above each centre the missing action is solved from ``H = h`` (Eq. (5) of [1]_ on a
    ``g`` section, (14) on a ``theta2`` section).

    Parameters
    ----------
    n : int or (nx, ny), default 64
        Grid points along the plane's axes (each >= 2); stored as ``(nx, ny)``.
    plane_bounds : ((x_min, x_max), (y_min, y_max)), optional
        The plane's box. Default: the angle's full turn and the action's range where the
        level meets the plane (:func:`~andoyer.integrate.fill.fill_section`).
    root : {"largest", "smallest"}, default "largest"
        Which action where the level has several sheets above a point.

    References
    ----------
    .. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
       trajectories exploring" (Eqs. (5), (14)).

    Examples
    --------
    >>> MapGrid(32).n, MapGrid((64, 16), root="smallest").root
    ((32, 32), 'smallest')
    >>> MapGrid(1)
    Traceback (most recent call last):
    ...
    ValueError: n must be an integer in [2, 1000000000], got 1
    """

    n: tuple[int, int] | int = 64
    plane_bounds: tuple[tuple[float, float], tuple[float, float]] | None = None
    root: Root = "largest"

    def __post_init__(self) -> None:
        object.__setattr__(self, "n", grid("n", self.n))
        if self.plane_bounds is not None:
            object.__setattr__(self, "plane_bounds", box("plane_bounds", self.plane_bounds))
        object.__setattr__(self, "root", choice("root", self.root, ROOTS))

    @property
    def shape(self) -> tuple[int, int]:
        """``(ny, nx)``: the shape of the map's arrays (rows along the action)."""
        nx, ny = self.n  # type: ignore[misc]
        return ny, nx

    @classmethod
    def of(cls, value: Any, name: str = "grid") -> MapGrid:
        """``value`` itself if it is a :class:`MapGrid`, else the grid of that size (an
        integer or ``(nx, ny)``); ``ValueError`` naming ``name`` otherwise.

        Parameters
        ----------
        value : MapGrid, int or (int, int)
            The grid, or its size.
        name : str, default "grid"
            The user's argument, named in the error.

        Examples
        --------
        >>> MapGrid.of(8).n
        (8, 8)
        """
        if isinstance(value, MapGrid):
            return value
        try:
            return cls(n=value)
        except ValueError as exc:
            raise ValueError(f"{name} must be a MapGrid or its size n or (nx, ny): "
                             f"{exc}") from None


@dataclass(frozen=True)
class IndicatorRun:
    """What is integrated from each start of a chaos map: the state and one tangent
    vector, to ``t_end``.

    The state follows the Euler-Poisson equations (1) of [1]_, the tangent vector their
    variational equations.

    Parameters
    ----------
    indicator : {"fli", "megno", "both"}, default "fli"
        The FLI (``sup ln|w|``, Froeschle et al. 1997) and/or the mean MEGNO ``<Y>``
        (Cincotta & Simo 2000); ``"fli"`` alone integrates the state and one tangent
        vector without renormalisation.
    t_end : float, default 1000
        Integration time of every orbit (> 0).
    n_samples : int, default 64
        Output times ``t_end k / n_samples``, over which the FLI's supremum is taken.
    tangent : {"leaf", "energy"}, default "leaf"
        Space of the initial tangent vector.
    tol : float, default 1e-12
        Tolerance of the integrator (one number; :class:`~andoyer.integrate.engines.base.
        Tolerance` checks its range).

    References
    ----------
    .. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
       trajectories exploring" (Eq. (1)).

    Examples
    --------
    >>> IndicatorRun("megno", t_end=500.0)
    IndicatorRun(indicator='megno', t_end=500.0, n_samples=64, tangent='leaf', tol=1e-12)
    >>> IndicatorRun(t_end=-1.0)
    Traceback (most recent call last):
    ...
    ValueError: t_end must be finite and > 0, got -1.0
    """

    indicator: Indicator = "fli"
    t_end: float = 1000.0
    n_samples: int = 64
    tangent: Tangent = "leaf"
    tol: float = 1e-12

    def __post_init__(self) -> None:
        object.__setattr__(self, "indicator",
                           choice("indicator", self.indicator, INDICATOR_CHOICES))
        object.__setattr__(self, "t_end", positive("t_end", self.t_end))
        object.__setattr__(self, "n_samples", integer("n_samples", self.n_samples, 1))
        object.__setattr__(self, "tangent", choice("tangent", self.tangent, TANGENT_SPACES))
        object.__setattr__(self, "tol", Tolerance.single(self.tol).tol)

    @classmethod
    def of(cls, value: Any, name: str = "run") -> IndicatorRun:
        """``value`` itself if it is an :class:`IndicatorRun`; ``TypeError`` naming
        ``name`` otherwise.

        Parameters
        ----------
        value : IndicatorRun
            The run.
        name : str, default "run"
            The user's argument, named in the error.

        Examples
        --------
        >>> IndicatorRun.of(IndicatorRun("megno")).indicator
        'megno'
        """
        if not isinstance(value, IndicatorRun):
            raise TypeError(f"{name} must be an IndicatorRun (indicator, t_end, n_samples, "
                            f"tangent, tol), got {value!r}")
        return value

    @property
    def renormalised(self) -> bool:
        """Whether the tangent vector is renormalised (an indicator that needs it asked
        for: MEGNO)."""
        return any(INDICATORS[k].renormalised for k in (*chosen(self.indicator), *MAP_EXTRAS))

