"""The adaptive Taylor method in Numba, on the recurrences of
:mod:`andoyer.kernels.generated.recurrences`.

* :mod:`~andoyer.kernels.taylor.jets` -- jets, step size and the Horner steps;
* :mod:`~andoyer.kernels.taylor.sections` -- section tapes, Bernstein root isolation;
* :mod:`~andoyer.kernels.taylor.flow` -- the entry points of one orbit at a time
  (states, tangent vectors, attitude; output times and crossings);
* :mod:`~andoyer.kernels.taylor.tangent` -- the renormalised tangent flow with MEGNO;
* :mod:`~andoyer.kernels.taylor.lanes`, :mod:`~andoyer.kernels.taylor.lane_crossings`
  -- one vector register of orbits per step on SIMD lanes (8 with AVX-512, 4 with
  AVX2: :func:`andoyer.kernels.simd.lane_width`; the vector intrinsics of
  :mod:`andoyer.kernels.simd`, which the generated lane recurrences call too), every
  section's crossings on them; :mod:`~andoyer.kernels.taylor.lane_sections` -- a
  section tape's jet and the section step on the lanes;
  :mod:`~andoyer.kernels.taylor.lane_tangent` -- the renormalised tangent flow with
  MEGNO on the lanes.

Importing the package loads nothing; each module compiles (or loads) its machine code
when it is imported.
"""
