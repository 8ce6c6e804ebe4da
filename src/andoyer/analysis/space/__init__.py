"""The body in space: closed forms of the attitude and inertial-space analysis, on the
datasets of :func:`andoyer.integrate.attitude`: :mod:`~andoyer.analysis.space.lagrange_top`
(nutation bounds and mean precession of the Lagrange top) and
:mod:`~andoyer.analysis.space.inertial` (axis traces on the unit sphere, precession and
nutation of orbits, the herpolhode, the Hess heteroclinic cycle in space)."""
