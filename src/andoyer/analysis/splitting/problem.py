"""The problem a separatrix-splitting computation prepares once and passes down: the body,
its nearest Hess body, the energy level, the heteroclinic branch and sheet, the engine.

:func:`~andoyer.analysis.splitting.measure.separatrix_splitting` and
:func:`~andoyer.analysis.splitting.manifolds.manifold_branch` build one
:class:`SplittingProblem`; the periodic orbits, the manifolds and the Melnikov function
read it instead of deriving the nearest Hess body (:meth:`~andoyer.body.RigidBody.
nearest_hess`), the line and the engine again. The engine is the object the caller
gave (or the default one), so its options reach the kernels.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from andoyer.analysis.splitting.melnikov import heteroclinic_line
from andoyer.analysis.splitting.section_map import flow_engine
from andoyer.analysis.unperturbed.separatrix import (
    BRANCHES,
    DEFAULT_BRANCH,
    separatrix_momentum,
)
from andoyer.body import RigidBody, checks_body
from andoyer.integrate.engines import EngineLike
from andoyer.integrate.engines.base import EngineBase

__all__ = ["SplittingProblem", "splitting_problem"]


@dataclass(frozen=True)
class SplittingProblem:
    """A separatrix-splitting problem, prepared once.

    Parameters
    ----------
    body : RigidBody
        The body (a Hess body, or one turned off it in the (e1, e2) plane).
    hess : RigidBody
        Its nearest Hess body (:meth:`~andoyer.body.RigidBody.nearest_hess`), whose
        chart and separatrices it shares.
    h : float
        The energy level ``h = c J2^2 / 2``.
    branch : str
        The heteroclinic line (``"theta1=0"``, ``"theta1=4phi0"``).
    sheet : int
        Which of its two orbits (+1: ``theta1``, -1: ``theta1 + 2 pi``).
    theta1_line : float
        ``theta1`` of the unperturbed line (Eq. (14) of Kyrychenko) in the chart of
        ``hess``.
    j1_direction : int
        Sign of ``dJ1/dt`` along the line.
    engine : Engine
        The engine of every flow to a section (an instance keeps its options).

    Examples
    --------
    >>> p = splitting_problem(RigidBody.paper(), 0.1, "theta1=4phi0", engine="numba")
    >>> p.engine.name, p.hess is p.body, p.rotation("unstable") == -p.rotation("stable")
    ('numba', True, True)
    """

    body: RigidBody
    hess: RigidBody
    h: float
    branch: str
    sheet: int
    theta1_line: float
    j1_direction: int
    engine: EngineBase

    @property
    def epsilon(self) -> float:
        """The turn of the centre of mass off the Hess direction (0 on a Hess body;
        :attr:`~andoyer.body.RigidBody.hess_epsilon`)."""
        return float(math.remainder(self.body.phi0 - self.hess.phi0, math.tau))

    def rotation(self, stability: str) -> int:
        """The sense (``+1``: ``L = +G``) of the rotation whose manifold ``stability``
        (``"unstable"``: the one the line leaves; ``"stable"``: the one it reaches)
        follows the line.

        Parameters
        ----------
        stability : {"unstable", "stable"}
            Which manifold.
        """
        leaves, reaches = (-1, 1) if self.j1_direction > 0 else (1, -1)
        return leaves if stability == "unstable" else reaches

    def with_mu(self, mu: float) -> SplittingProblem:
        """The same problem for the body with weight ``mu`` (the line, the nearest Hess
        body's chart and the engine do not depend on it).

        Parameters
        ----------
        mu : float
            The new ``mu``.
        """
        return dataclasses.replace(self, body=self.body.with_mu(float(mu)))


@checks_body(ranges={"h": "energy", "sheet": "sheet"})
def splitting_problem(body: RigidBody, h: float, branch: str = DEFAULT_BRANCH,
                      sheet: int = 1, engine: EngineLike = None) -> SplittingProblem:
    """Prepare a separatrix-splitting problem: the nearest Hess body, the line, the engine.

    Parameters
    ----------
    body : RigidBody
        A Hess body, or one turned off it in the (e1, e2) plane.
    h : float
        Energy level ``h = c J2^2 / 2`` (> 0).
    branch : {"theta1=0", "theta1=4phi0"}, default "theta1=0"
        Which heteroclinic line.
    sheet : {+1, -1}, default 1
        Which of its two orbits.
    engine : str or Engine, optional
        The engine of the flows (:func:`~andoyer.analysis.splitting.section_map.
        flow_engine`): an instance is kept as given.
    """
    if branch not in BRANCHES:
        raise ValueError(f"branch must be one of {BRANCHES}, got {branch!r}")
    if sheet not in (1, -1):
        raise ValueError(f"sheet must be +1 or -1, got {sheet!r}")
    hess = body.nearest_hess()
    theta1_line, j1 = heteroclinic_line(hess, separatrix_momentum(hess, h), branch, sheet)
    return SplittingProblem(body, hess, float(h), branch, sheet, float(theta1_line), int(j1),
                            flow_engine(engine))
