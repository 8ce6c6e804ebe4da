"""The Dormand-Prince 8(5,3) method (Hairer's DOP853) in Numba.

* :mod:`~andoyer.kernels.dop853.coefficients` -- the tableau, error and dense-output
  coefficients;
* :mod:`~andoyer.kernels.dop853.stepper` -- the method for any compiled field
  (:func:`~andoyer.kernels.dop853.stepper.make_stepper`);
* :mod:`~andoyer.kernels.dop853.fields` -- the generated fields compiled by Numba;
* :mod:`~andoyer.kernels.dop853.flow` -- :class:`~andoyer.kernels.dop853.flow.Flow`,
  the entry points of a field, and those of the Euler-Poisson field (1);
* :mod:`~andoyer.kernels.dop853.tangent`, :mod:`~andoyer.kernels.dop853.attitude` --
  the variational and attitude flows on the same stepper.

Importing the package loads nothing; each module compiles (or loads) its machine code
when it is imported.
"""
