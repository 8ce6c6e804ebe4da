"""The unperturbed body: Euler-Poinsot motion, equilibria, fixed points, separatrices,
phase portraits."""

from __future__ import annotations

from typing import TYPE_CHECKING

from andoyer.analysis._exports import lazy_exports

if TYPE_CHECKING:
    from andoyer.analysis.unperturbed.equilibria import EquilibriumSet as EquilibriumSet
    from andoyer.analysis.unperturbed.equilibria import (
        EulerPoissonEquilibrium as EulerPoissonEquilibrium,
    )
    from andoyer.analysis.unperturbed.equilibria import PermanentRotation as PermanentRotation
    from andoyer.analysis.unperturbed.equilibria import classify as classify
    from andoyer.analysis.unperturbed.equilibria import (
        euler_poisson_equilibria as euler_poisson_equilibria,
    )
    from andoyer.analysis.unperturbed.equilibria import permanent_rotations as permanent_rotations
    from andoyer.analysis.unperturbed.equilibria import (
        require_distinct_moments as require_distinct_moments,
    )
    from andoyer.analysis.unperturbed.equilibria import sorted_eigenvalues as sorted_eigenvalues
    from andoyer.analysis.unperturbed.euler_poinsot import (
        EulerPoinsotFrequencies as EulerPoinsotFrequencies,
    )
    from andoyer.analysis.unperturbed.euler_poinsot import elliptic_f as elliptic_f
    from andoyer.analysis.unperturbed.euler_poinsot import elliptic_pi as elliptic_pi
    from andoyer.analysis.unperturbed.euler_poinsot import (
        euler_poinsot_frequencies as euler_poinsot_frequencies,
    )
    from andoyer.analysis.unperturbed.euler_poinsot import (
        euler_poinsot_momentum as euler_poinsot_momentum,
    )
    from andoyer.analysis.unperturbed.fixed_points import FixedPoint as FixedPoint
    from andoyer.analysis.unperturbed.fixed_points import FixedPointSet as FixedPointSet
    from andoyer.analysis.unperturbed.fixed_points import (
        andoyer_fixed_points as andoyer_fixed_points,
    )
    from andoyer.analysis.unperturbed.fixed_points import hess_fixed_points as hess_fixed_points
    from andoyer.analysis.unperturbed.fixed_points import theta_text as theta_text
    from andoyer.analysis.unperturbed.portraits import portrait_andoyer as portrait_andoyer
    from andoyer.analysis.unperturbed.portraits import portrait_hess as portrait_hess
    from andoyer.analysis.unperturbed.separatrix import check_grid_size as check_grid_size
    from andoyer.analysis.unperturbed.separatrix import heteroclinic as heteroclinic
    from andoyer.analysis.unperturbed.separatrix import heteroclinic_rate as heteroclinic_rate
    from andoyer.analysis.unperturbed.separatrix import separatrix_andoyer as separatrix_andoyer
    from andoyer.analysis.unperturbed.separatrix import separatrix_curves as separatrix_curves
    from andoyer.analysis.unperturbed.separatrix import separatrix_energy as separatrix_energy
    from andoyer.analysis.unperturbed.separatrix import separatrix_hess as separatrix_hess
    from andoyer.analysis.unperturbed.separatrix import separatrix_momentum as separatrix_momentum
    from andoyer.analysis.unperturbed.separatrix import separatrix_on_level as separatrix_on_level

#: Name -> the module of this package that defines it (imported on first use).
EXPORTS = {"EquilibriumSet": "equilibria", "EulerPoissonEquilibrium": "equilibria",
           "PermanentRotation": "equilibria", "classify": "equilibria", "euler_poisson_equilibria":
           "equilibria", "permanent_rotations": "equilibria", "require_distinct_moments":
           "equilibria", "sorted_eigenvalues": "equilibria", "EulerPoinsotFrequencies":
           "euler_poinsot", "elliptic_f": "euler_poinsot", "elliptic_pi": "euler_poinsot",
           "euler_poinsot_frequencies": "euler_poinsot", "euler_poinsot_momentum": "euler_poinsot",
           "FixedPoint": "fixed_points", "FixedPointSet": "fixed_points", "andoyer_fixed_points":
           "fixed_points", "hess_fixed_points": "fixed_points", "theta_text": "fixed_points",
           "portrait_andoyer": "portraits", "portrait_hess": "portraits", "check_grid_size":
           "separatrix", "heteroclinic": "separatrix", "heteroclinic_rate": "separatrix",
           "separatrix_andoyer": "separatrix", "separatrix_curves": "separatrix",
           "separatrix_energy": "separatrix", "separatrix_hess": "separatrix",
           "separatrix_momentum": "separatrix", "separatrix_on_level": "separatrix"}

__all__ = sorted(EXPORTS)

__getattr__, __dir__ = lazy_exports(__name__, EXPORTS)
