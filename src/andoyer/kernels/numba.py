"""Numba-compiled versions of the generated kernels (compiled on first use, cached).

``cache=True`` stores the machine code in andoyer's folder of the user's cache
(:func:`andoyer.kernels.cache.cache_folder`), so a second process pays no compile time.
"""

from __future__ import annotations

from andoyer.kernels import generated as _g
from andoyer.kernels.cache import cached_njit

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

_jit = cached_njit(fastmath=False, nogil=True)

ep_hamiltonian = _jit(_g.ep_hamiltonian)
ep_field = _jit(_g.ep_field)
ep_jacobian = _jit(_g.ep_jacobian)
attitude_field = _jit(_g.attitude_field)
andoyer_hamiltonian = _jit(_g.andoyer_hamiltonian)
andoyer_field = _jit(_g.andoyer_field)
hess_hamiltonian = _jit(_g.hess_hamiltonian)
hess_field = _jit(_g.hess_field)
