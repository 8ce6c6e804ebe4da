"""The generated kernels of :mod:`andoyer.kernels.generated.equations`, compiled with
Numba (compiled on first use, cached).

:func:`~andoyer.kernels.common.exact_jit` (``cache=True``, no fast-math) stores the
machine code in andoyer's folder of the user's cache
(:func:`andoyer.kernels.cache.cache_folder`), so a second process pays no compile time.
The DOP853 right-hand sides call them (:mod:`andoyer.kernels.dop853.flow`,
:mod:`~andoyer.kernels.dop853.tangent`, :mod:`~andoyer.kernels.dop853.attitude`).
"""

from __future__ import annotations

from andoyer.kernels.common import exact_jit
from andoyer.kernels.generated import equations as _g

__all__ = [
    "ep_hamiltonian",
    "ep_field",
    "ep_jacobian",
    "attitude_field",
    "andoyer_hamiltonian",
    "andoyer_field",
    "hess_hamiltonian",
    "hess_field",
]

ep_hamiltonian = exact_jit(_g.ep_hamiltonian)
ep_field = exact_jit(_g.ep_field)
ep_jacobian = exact_jit(_g.ep_jacobian)
attitude_field = exact_jit(_g.attitude_field)
andoyer_hamiltonian = exact_jit(_g.andoyer_hamiltonian)
andoyer_field = exact_jit(_g.andoyer_field)
hess_hamiltonian = exact_jit(_g.hess_hamiltonian)
hess_field = exact_jit(_g.hess_field)
