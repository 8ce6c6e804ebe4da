"""Resonances predicted, then measured: the ``p/q`` island chains of the heavy top.

- :mod:`~andoyer.analysis.resonance.torus`: the free top's tori in their angle
  variables, the phase of a state, the Fourier coefficients of the perturbation
  ``(r, gamma)`` by FFT;
- :mod:`~andoyer.analysis.resonance.predict`: where (the resonant tori ``W = p/q``) and
  how wide (the first-order pendulum: half-widths, periodic orbits, their stability);
- :mod:`~andoyer.analysis.resonance.deprit`: the Lie-Deprit series to order ``N``
  (Deprit's triangle) on jets in the action with Fourier coefficients in the angles;
- :mod:`~andoyer.analysis.resonance.second_order` (``island_prediction``): the chain's
  stable point, width and libration frequency to second order in ``mu`` from it;
- :mod:`~andoyer.analysis.resonance.residues` (``last_torus``, ``critical_mu_curve``):
  Greene's residues of the
  periodic orbits of a noble torus's convergents and the critical ``mu`` at which it
  breaks, beside the chains' overlap estimate;
- :mod:`~andoyer.analysis.resonance.measure`: the same half-widths measured on
  Poincare sections of the perturbed flow (any island of the chain, ``p >= 2`` chains
  against their second-order width), and the NAFF route (``island_rotation_numbers``);
- :mod:`~andoyer.analysis.resonance.birkhoff`: the Birkhoff normal form of the free top
  at its centres (Lie series), the frequencies as functions of the action;
- :mod:`~andoyer.analysis.resonance.normal_form` (``periodic_orbit_normal_form``,
  ``orbit_rotation_numbers``): the Birkhoff normal form of the perturbed section map at an
  elliptic periodic orbit (jet transport), its twist against NAFF rotation numbers;
- :mod:`~andoyer.analysis.resonance.near_centre` (``resonant_normal_form``): near a
  centre, where the two frequencies resonate, the Birkhoff polynomial plus the resonant
  harmonic (a pendulum).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from andoyer.analysis._exports import lazy_exports

if TYPE_CHECKING:
    from andoyer.analysis.resonance.birkhoff import birkhoff_normal_form as birkhoff_normal_form
    from andoyer.analysis.resonance.birkhoff import normal_form_frequency as normal_form_frequency
    from andoyer.analysis.resonance.deprit import JetSpace as JetSpace
    from andoyer.analysis.resonance.deprit import lie_deprit as lie_deprit
    from andoyer.analysis.resonance.deprit import transform as transform
    from andoyer.analysis.resonance.measure import (
        island_rotation_numbers as island_rotation_numbers,
    )
    from andoyer.analysis.resonance.measure import measure_island as measure_island
    from andoyer.analysis.resonance.near_centre import resonant_normal_form as resonant_normal_form
    from andoyer.analysis.resonance.normal_form import (
        orbit_rotation_numbers as orbit_rotation_numbers,
    )
    from andoyer.analysis.resonance.normal_form import (
        periodic_orbit_normal_form as periodic_orbit_normal_form,
    )
    from andoyer.analysis.resonance.predict import FreeTopTorus as FreeTopTorus
    from andoyer.analysis.resonance.predict import free_top_at_gap as free_top_at_gap
    from andoyer.analysis.resonance.predict import resonance_widths as resonance_widths
    from andoyer.analysis.resonance.predict import resonant_tori as resonant_tori
    from andoyer.analysis.resonance.predict import (
        section_rotation_number as section_rotation_number,
    )
    from andoyer.analysis.resonance.residues import convergents as convergents
    from andoyer.analysis.resonance.residues import critical_mu_curve as critical_mu_curve
    from andoyer.analysis.resonance.residues import last_torus as last_torus
    from andoyer.analysis.resonance.residues import noble_number as noble_number
    from andoyer.analysis.resonance.second_order import SecondOrderChain as SecondOrderChain
    from andoyer.analysis.resonance.second_order import island_prediction as island_prediction
    from andoyer.analysis.resonance.torus import Torus as Torus
    from andoyer.analysis.resonance.torus import free_top_phase as free_top_phase
    from andoyer.analysis.resonance.torus import sample_torus as sample_torus

#: Name -> the module of this package that defines it (imported on first use).
EXPORTS = {"birkhoff_normal_form": "birkhoff", "normal_form_frequency": "birkhoff",
           "measure_island": "measure", "resonant_normal_form": "near_centre", "resonance_widths":
           "predict", "resonant_tori": "predict", "section_rotation_number": "predict", "Torus":
           "torus", "free_top_phase": "torus", "sample_torus": "torus", "free_top_at_gap":
           "predict", "FreeTopTorus": "predict", "island_prediction": "second_order", "JetSpace":
           "deprit", "lie_deprit": "deprit", "transform": "deprit", "SecondOrderChain":
           "second_order", "periodic_orbit_normal_form": "normal_form",
           "orbit_rotation_numbers": "normal_form", "last_torus": "residues",
           "critical_mu_curve": "residues",
           "convergents": "residues", "noble_number": "residues",
           "island_rotation_numbers": "measure"}

__all__ = sorted(EXPORTS)

__getattr__, __dir__ = lazy_exports(__name__, EXPORTS)
