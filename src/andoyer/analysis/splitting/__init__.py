"""Separatrix splitting: the section map, periodic orbits, invariant manifolds, the Melnikov
function, the splitting measured. The functions and classes of its modules are names of
this package too (``from andoyer.analysis.splitting import separatrix_splitting``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from andoyer.analysis._exports import lazy_exports

if TYPE_CHECKING:
    from andoyer.analysis.splitting.certificate import prove_certificate as prove_certificate
    from andoyer.analysis.splitting.certificate import (
        prove_transversal_certificate as prove_transversal_certificate,
    )
    from andoyer.analysis.splitting.certificate import read_certificate as read_certificate
    from andoyer.analysis.splitting.certificate import verify_certificate as verify_certificate
    from andoyer.analysis.splitting.certificate import write_certificate as write_certificate
    from andoyer.analysis.splitting.certified import CertifiedMelnikov as CertifiedMelnikov
    from andoyer.analysis.splitting.certified import MelnikovZero as MelnikovZero
    from andoyer.analysis.splitting.certified import certified_melnikov as certified_melnikov
    from andoyer.analysis.splitting.certified import (
        heteroclinic_orbit_balls as heteroclinic_orbit_balls,
    )
    from andoyer.analysis.splitting.certified import melnikov_coefficient as melnikov_coefficient
    from andoyer.analysis.splitting.hyperbolic import HyperbolicRotation as HyperbolicRotation
    from andoyer.analysis.splitting.hyperbolic import certified_rotation as certified_rotation
    from andoyer.analysis.splitting.manifolds import ManifoldBranch as ManifoldBranch
    from andoyer.analysis.splitting.manifolds import ManifoldCurve as ManifoldCurve
    from andoyer.analysis.splitting.manifolds import euler_poinsot_excess as euler_poinsot_excess
    from andoyer.analysis.splitting.manifolds import grow_manifold as grow_manifold
    from andoyer.analysis.splitting.manifolds import heteroclinic_line_of as heteroclinic_line_of
    from andoyer.analysis.splitting.manifolds import manifold_branch as manifold_branch
    from andoyer.analysis.splitting.measure import measure_splitting as measure_splitting
    from andoyer.analysis.splitting.measure import separatrix_splitting as separatrix_splitting
    from andoyer.analysis.splitting.measure import splitting_at as splitting_at
    from andoyer.analysis.splitting.measure import splitting_vs_epsilon as splitting_vs_epsilon
    from andoyer.analysis.splitting.melnikov import heteroclinic_line as heteroclinic_line
    from andoyer.analysis.splitting.melnikov import melnikov_closed_form as melnikov_closed_form
    from andoyer.analysis.splitting.melnikov import melnikov_function as melnikov_function
    from andoyer.analysis.splitting.melnikov import melnikov_integrand as melnikov_integrand
    from andoyer.analysis.splitting.melnikov import melnikov_off_hess as melnikov_off_hess
    from andoyer.analysis.splitting.melnikov import melnikov_quadrature as melnikov_quadrature
    from andoyer.analysis.splitting.melnikov import melnikov_rho as melnikov_rho
    from andoyer.analysis.splitting.melnikov import predicted_splitting as predicted_splitting
    from andoyer.analysis.splitting.periodic import RotationOrbit as RotationOrbit
    from andoyer.analysis.splitting.periodic import (
        continue_rotation_orbit as continue_rotation_orbit,
    )
    from andoyer.analysis.splitting.periodic import orbits_dataset as orbits_dataset
    from andoyer.analysis.splitting.periodic import pendulum_rotation as pendulum_rotation
    from andoyer.analysis.splitting.periodic import rotation_orbit as rotation_orbit
    from andoyer.analysis.splitting.problem import SplittingProblem as SplittingProblem
    from andoyer.analysis.splitting.problem import splitting_problem as splitting_problem
    from andoyer.analysis.splitting.section_map import Crossing as Crossing
    from andoyer.analysis.splitting.section_map import RotationSection as RotationSection
    from andoyer.analysis.splitting.section_map import SectionReturn as SectionReturn
    from andoyer.analysis.splitting.section_map import event_projector as event_projector
    from andoyer.analysis.splitting.section_map import flow_engine as flow_engine
    from andoyer.analysis.splitting.section_map import flow_to_section as flow_to_section
    from andoyer.analysis.splitting.section_map import gamma_phase as gamma_phase
    from andoyer.analysis.splitting.section_map import middle_axis_rate as middle_axis_rate
    from andoyer.analysis.splitting.section_map import return_map as return_map
    from andoyer.analysis.splitting.section_map import rotation_energy as rotation_energy
    from andoyer.analysis.splitting.section_map import section_coords as section_coords
    from andoyer.analysis.splitting.section_map import section_state as section_state
    from andoyer.analysis.splitting.transversal import LocalManifold as LocalManifold
    from andoyer.analysis.splitting.transversal import TransversalProof as TransversalProof
    from andoyer.analysis.splitting.transversal import (
        local_unstable_manifold as local_unstable_manifold,
    )
    from andoyer.analysis.splitting.transversal import mu_interval as mu_interval
    from andoyer.analysis.splitting.transversal import prove_transversal as prove_transversal

#: Name -> the module of this package that defines it (imported on first use).
EXPORTS = {"ManifoldBranch": "manifolds", "ManifoldCurve": "manifolds", "euler_poinsot_excess":
           "manifolds", "grow_manifold": "manifolds", "heteroclinic_line_of": "manifolds",
           "manifold_branch": "manifolds", "measure_splitting": "measure", "separatrix_splitting":
           "measure", "splitting_at": "measure", "splitting_vs_epsilon": "measure",
           "heteroclinic_line": "melnikov", "melnikov_closed_form": "melnikov", "melnikov_function":
           "melnikov", "melnikov_integrand": "melnikov", "melnikov_off_hess": "melnikov",
           "melnikov_quadrature": "melnikov", "melnikov_rho": "melnikov", "predicted_splitting":
           "melnikov", "RotationOrbit": "periodic", "continue_rotation_orbit": "periodic",
           "orbits_dataset": "periodic", "pendulum_rotation": "periodic", "rotation_orbit":
           "periodic", "Crossing": "section_map", "RotationSection": "section_map", "SectionReturn":
           "section_map", "event_projector": "section_map", "flow_engine": "section_map",
           "flow_to_section": "section_map", "gamma_phase": "section_map", "middle_axis_rate":
           "section_map", "return_map": "section_map", "rotation_energy": "section_map",
           "section_coords": "section_map", "section_state": "section_map", "prove_certificate":
           "certificate", "write_certificate": "certificate", "read_certificate": "certificate",
           "verify_certificate": "certificate", "CertifiedMelnikov": "certified", "MelnikovZero":
           "certified", "certified_melnikov": "certified", "melnikov_coefficient": "certified",
           "heteroclinic_orbit_balls": "certified", "HyperbolicRotation": "hyperbolic",
           "certified_rotation": "hyperbolic", "SplittingProblem": "problem", "splitting_problem":
           "problem", "LocalManifold": "transversal", "TransversalProof": "transversal",
           "local_unstable_manifold": "transversal", "prove_transversal": "transversal",
           "mu_interval": "transversal",
           "prove_transversal_certificate": "certificate"}

__all__ = sorted(EXPORTS)

__getattr__, __dir__ = lazy_exports(__name__, EXPORTS)
