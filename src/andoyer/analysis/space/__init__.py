"""The body in space: closed forms of the attitude and inertial-space analysis, on the
datasets of :func:`andoyer.integrate.attitude`: :mod:`~andoyer.analysis.space.lagrange`
(nutation bounds and mean precession of the Lagrange top) and
:mod:`~andoyer.analysis.space.inertial` (axis traces on the unit sphere, precession and
nutation of orbits, the herpolhode, the Hess heteroclinic cycle in space).

The functions of its modules are names of this package too.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from andoyer.analysis._exports import lazy_exports

if TYPE_CHECKING:
    from andoyer.analysis.space.inertial import axis_trace as axis_trace
    from andoyer.analysis.space.inertial import herpolhode as herpolhode
    from andoyer.analysis.space.inertial import heteroclinic_cycle as heteroclinic_cycle
    from andoyer.analysis.space.inertial import precession_nutation as precession_nutation
    from andoyer.analysis.space.lagrange import lagrange_top as lagrange_top

#: Name -> the module of this package that defines it (imported on first use).
EXPORTS = {"axis_trace": "inertial", "herpolhode": "inertial", "heteroclinic_cycle": "inertial",
           "precession_nutation": "inertial", "lagrange_top": "lagrange"}

__all__ = sorted(EXPORTS)

__getattr__, __dir__ = lazy_exports(__name__, EXPORTS)
