"""Kernels on plain floats and arrays: no bodies, no validation, no units.

By method, each a sub-package that imports :mod:`andoyer.kernels.common` and
:mod:`andoyer.kernels.generated` but never another method (an import contract):

* :mod:`andoyer.kernels.generated` -- the files written by :mod:`andoyer.symbolic`:
  NumPy-broadcastable right-hand sides, Hamiltonians and section functions
  (:mod:`~andoyer.kernels.generated.equations`) and the Taylor recurrences
  (:mod:`~andoyer.kernels.generated.recurrences`);
* :mod:`andoyer.kernels.dop853` -- the Dormand-Prince 8(5,3) method in Numba;
* :mod:`andoyer.kernels.taylor` -- the adaptive Taylor method in Numba (scalar and SIMD);
* :mod:`andoyer.kernels.common` -- what they share (status codes, the tangent layout,
  ``MEGNO_DELTA``, the JIT decorators and the fast-math flags), with
  :mod:`~andoyer.kernels.cache` (where compiled code is kept),
  :mod:`~andoyer.kernels.threads` (orbits in threads),
  :mod:`~andoyer.kernels.link_only` (helpers compiled into their callers) and
  :mod:`~andoyer.kernels.simd` (vector intrinsics of the SIMD lanes: the generated lane
  recurrences call them, so they cannot live in a method's package).

Numba is imported by the methods only: ``import andoyer.kernels`` and the generated
equations stay light.
"""
