"""Kernels on plain floats and arrays: no bodies, no validation, no units.

:mod:`andoyer.kernels.generated` holds the NumPy-broadcastable right-hand sides and
Hamiltonians generated from the symbolic layer; :mod:`andoyer.kernels.numba` compiles
the same functions with Numba (imported lazily: Numba is not loaded by ``import
andoyer``).
"""

from andoyer.kernels import generated as generated

__all__ = ["generated"]
