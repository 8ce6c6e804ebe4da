"""Orbits and Poincare sections (friendly layer over the engines).

Imported on demand (it loads xarray), not by ``import andoyer``.
"""

from andoyer.integrate.api import initial_states as initial_states
from andoyer.integrate.api import integrate_canonical as integrate_canonical
from andoyer.integrate.api import poincare as poincare
from andoyer.integrate.api import propagate as propagate
from andoyer.integrate.fill import fill_section as fill_section
from andoyer.integrate.hess_manifold import propagate_hess_manifold as propagate_hess_manifold
from andoyer.integrate.section import Section as Section

__all__ = ["Section", "fill_section", "initial_states", "integrate_canonical", "poincare",
           "propagate", "propagate_hess_manifold"]
