"""The science: fixed points, separatrices, the Hess solution, chaos indicators, splitting.

Every function takes a :class:`~andoyer.body.RigidBody` and returns data (an xarray
dataset or a small frozen dataclass) with the equations of the paper it evaluates; the
figures are drawn by :mod:`andoyer.plot`. One sub-package per concept, one module per
topic, imported on demand (``from andoyer.analysis.chaos.lyapunov import indicators``):

- :mod:`~andoyer.analysis.unperturbed`, the unperturbed system:
  :mod:`~andoyer.analysis.unperturbed.fixed_points`,
  :mod:`~andoyer.analysis.unperturbed.separatrix`,
  :mod:`~andoyer.analysis.unperturbed.portraits`,
  :mod:`~andoyer.analysis.unperturbed.equilibria`,
  :mod:`~andoyer.analysis.unperturbed.euler_poinsot`;
- :mod:`~andoyer.analysis.hess`, the Hess solution and the pendulum:
  :mod:`~andoyer.analysis.hess.reduced`,
  :mod:`~andoyer.analysis.hess.solution`, :mod:`~andoyer.analysis.hess.periods`,
  :mod:`~andoyer.analysis.hess.pendulum`, :mod:`~andoyer.analysis.hess.floquet`;
- :mod:`~andoyer.analysis.chaos`: :mod:`~andoyer.analysis.chaos.lyapunov` (FLI, MEGNO,
  chaos maps), :mod:`~andoyer.analysis.chaos.alignment` (SALI, GALI),
  :mod:`~andoyer.analysis.chaos.frequency` (NAFF, frequency drift),
  :mod:`~andoyer.analysis.chaos.border`;
- :mod:`~andoyer.analysis.splitting`, splitting of the separatrices:
  :mod:`~andoyer.analysis.splitting.periodic`, :mod:`~andoyer.analysis.splitting.section_map`,
  :mod:`~andoyer.analysis.splitting.manifolds`, :mod:`~andoyer.analysis.splitting.measure`,
  :mod:`~andoyer.analysis.splitting.melnikov`;
- :mod:`~andoyer.analysis.resonance`, the ``p/q`` island chains predicted at first order
  in ``mu`` and measured on sections: :mod:`~andoyer.analysis.resonance.torus`,
  :mod:`~andoyer.analysis.resonance.predict`, :mod:`~andoyer.analysis.resonance.measure`;
- :mod:`~andoyer.analysis.paper`, the paper itself:
  :mod:`~andoyer.analysis.paper.trajectories` (Fig. 3) and
  :mod:`~andoyer.analysis.paper.check` (every printed formula against the derivation);
- :mod:`~andoyer.analysis.space`, the body in space:
  :mod:`~andoyer.analysis.space.lagrange` (the Lagrange top in closed form),
  :mod:`~andoyer.analysis.space.inertial` (axis traces, precession and nutation, the
  herpolhode, the Hess heteroclinic cycle in space).

Each sub-package re-exports the functions and classes of its modules
(``from andoyer.analysis.splitting import separatrix_splitting``).
"""
