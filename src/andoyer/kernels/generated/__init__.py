"""The kernels written by :mod:`andoyer.symbolic` (DO NOT EDIT the modules here).

* :mod:`~andoyer.kernels.generated.equations` (:mod:`andoyer.symbolic.codegen`):
  Hamiltonians, fields, the Jacobian and the section functions on scalars or
  broadcastable NumPy arrays; plain Python, compiled by Numba where a method needs it;
* :mod:`~andoyer.kernels.generated.recurrences` (:mod:`andoyer.symbolic.taylor_codegen`):
  the Taylor recurrences (jets) of the field, the tangent and attitude flows and the
  section tapes, compiled by :mod:`andoyer.kernels.taylor`.
"""
