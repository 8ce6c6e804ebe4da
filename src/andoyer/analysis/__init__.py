"""The science: fixed points, separatrices, the Hess solution, chaos indicators, splitting.

Every function takes a :class:`~andoyer.body.RigidBody` and returns data (an xarray
dataset or a small frozen dataclass) with the equations of the paper it evaluates; the
figures are drawn by :mod:`andoyer.plot`. One module per concept, imported on demand
(``from andoyer.analysis.chaos import indicators``):

- the unperturbed system: :mod:`~andoyer.analysis.fixed_points`,
  :mod:`~andoyer.analysis.separatrix`, :mod:`~andoyer.analysis.portraits`,
  :mod:`~andoyer.analysis.equilibria`, :mod:`~andoyer.analysis.euler_poinsot`;
- the Hess solution and the pendulum: :mod:`~andoyer.analysis.hess_solution`,
  :mod:`~andoyer.analysis.hess_periods`, :mod:`~andoyer.analysis.pendulum`,
  :mod:`~andoyer.analysis.floquet`;
- chaos: :mod:`~andoyer.analysis.chaos` (FLI, MEGNO, chaos maps),
  :mod:`~andoyer.analysis.alignment` (SALI, GALI), :mod:`~andoyer.analysis.frequency`
  (NAFF, frequency drift), :mod:`~andoyer.analysis.chaos_border`;
- splitting of the separatrices: :mod:`~andoyer.analysis.periodic`,
  :mod:`~andoyer.analysis.section_map`, :mod:`~andoyer.analysis.manifolds`,
  :mod:`~andoyer.analysis.splitting`, :mod:`~andoyer.analysis.melnikov`;
- the paper itself: :mod:`~andoyer.analysis.trajectories` (Fig. 3) and
  :mod:`~andoyer.analysis.paper_check` (every printed formula against the derivation).
"""
