"""Resonances predicted, then measured: the ``p/q`` island chains of the heavy top.

- :mod:`~andoyer.analysis.resonance.torus`: the free top's tori in their angle
  variables, the phase of a state, the Fourier coefficients of the perturbation
  ``(r, gamma)`` by FFT;
- :mod:`~andoyer.analysis.resonance.predict`: where (the resonant tori ``W = p/q``) and
  how wide (the first-order pendulum: half-widths, periodic orbits, their stability);
- :mod:`~andoyer.analysis.resonance.measure`: the same half-widths measured on
  Poincare sections of the perturbed flow;
- :mod:`~andoyer.analysis.resonance.birkhoff`: the Birkhoff normal form of the free top
  at its centres (Lie series), the frequencies as functions of the action;
- :mod:`~andoyer.analysis.resonance.near_centre` (``resonant_normal_form``): near a
  centre, where the two frequencies resonate, the Birkhoff polynomial plus the resonant
  harmonic (a pendulum).
"""

from andoyer.analysis.resonance.birkhoff import birkhoff_normal_form, normal_form_frequency
from andoyer.analysis.resonance.near_centre import resonant_normal_form
from andoyer.analysis.resonance.predict import (
    resonance_widths,
    resonant_tori,
    section_rotation_number,
)

__all__ = ["resonant_tori", "resonance_widths", "section_rotation_number",
           "birkhoff_normal_form", "normal_form_frequency", "resonant_normal_form"]
