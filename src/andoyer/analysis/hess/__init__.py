"""The Hess case: the Hess solution, its periods, the pendulums and their Floquet multipliers.

The functions and classes of its modules are names of this package too.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from andoyer.analysis._exports import lazy_exports

if TYPE_CHECKING:
    from andoyer.analysis.hess.floquet import Floquet as Floquet
    from andoyer.analysis.hess.floquet import Monodromy as Monodromy
    from andoyer.analysis.hess.floquet import floquet_multipliers as floquet_multipliers
    from andoyer.analysis.hess.floquet import floquet_scan as floquet_scan
    from andoyer.analysis.hess.floquet import hess_rotation_multiplier as hess_rotation_multiplier
    from andoyer.analysis.hess.floquet import monodromy as monodromy
    from andoyer.analysis.hess.floquet import (
        physical_pendulum_monodromy as physical_pendulum_monodromy,
    )
    from andoyer.analysis.hess.pendulum import paper_pendulum_potential as paper_pendulum_potential
    from andoyer.analysis.hess.pendulum import pendulum_energy as pendulum_energy
    from andoyer.analysis.hess.pendulum import pendulum_modulus as pendulum_modulus
    from andoyer.analysis.hess.pendulum import pendulum_motion as pendulum_motion
    from andoyer.analysis.hess.pendulum import pendulum_period as pendulum_period
    from andoyer.analysis.hess.pendulum import pendulum_potential as pendulum_potential
    from andoyer.analysis.hess.pendulum import pendulum_solution as pendulum_solution
    from andoyer.analysis.hess.pendulum import pendulum_state as pendulum_state
    from andoyer.analysis.hess.pendulum import physical_pendulum as physical_pendulum
    from andoyer.analysis.hess.pendulum import require_pendulum_body as require_pendulum_body
    from andoyer.analysis.hess.periods import hess_periods as hess_periods
    from andoyer.analysis.hess.reduced import classify_motion as classify_motion
    from andoyer.analysis.hess.reduced import cubic_roots as cubic_roots
    from andoyer.analysis.hess.reduced import drift_rate as drift_rate
    from andoyer.analysis.hess.reduced import energy_minimum as energy_minimum
    from andoyer.analysis.hess.reduced import period as period
    from andoyer.analysis.hess.reduced import reduced_field as reduced_field
    from andoyer.analysis.hess.reduced import reduced_hamiltonian as reduced_hamiltonian
    from andoyer.analysis.hess.solution import hess_solution as hess_solution
    from andoyer.analysis.hess.solution import hess_state as hess_state
    from andoyer.analysis.hess.solution import signed_to_hess as signed_to_hess

#: Name -> the module of this package that defines it (imported on first use).
EXPORTS = {"Floquet": "floquet", "Monodromy": "floquet", "floquet_multipliers": "floquet",
           "floquet_scan": "floquet", "hess_rotation_multiplier": "floquet", "monodromy": "floquet",
           "physical_pendulum_monodromy": "floquet", "hess_state": "solution", "signed_to_hess":
           "solution", "hess_solution": "solution", "hess_periods": "periods",
           "paper_pendulum_potential": "pendulum", "pendulum_energy": "pendulum",
           "pendulum_modulus": "pendulum", "pendulum_motion": "pendulum", "pendulum_period":
           "pendulum", "pendulum_potential": "pendulum", "pendulum_solution": "pendulum",
           "pendulum_state": "pendulum", "physical_pendulum": "pendulum", "require_pendulum_body":
           "pendulum", "classify_motion": "reduced", "cubic_roots": "reduced", "drift_rate":
           "reduced", "energy_minimum": "reduced", "period": "reduced", "reduced_field": "reduced",
           "reduced_hamiltonian": "reduced"}

__all__ = sorted(EXPORTS)

__getattr__, __dir__ = lazy_exports(__name__, EXPORTS)
