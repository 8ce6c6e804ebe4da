"""Chaos: indicators (FLI, MEGNO, the Lyapunov exponent: :mod:`.lyapunov`, listed once in
:mod:`.registry`), alignment indices (SALI, GALI), the border of chaos, frequency analysis.

The public functions and classes of its modules are names of this package too
(``from andoyer.analysis.chaos import indicators, chaos_map, sali, naff``), imported on
first use so that the light modules (:mod:`.registry`, read by the CLI's argument parser)
stay light.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from andoyer.analysis._exports import lazy_exports

if TYPE_CHECKING:
    from andoyer.analysis.chaos.alignment import alignment_indices as alignment_indices
    from andoyer.analysis.chaos.alignment import gali as gali
    from andoyer.analysis.chaos.alignment import initial_tangents as initial_tangents
    from andoyer.analysis.chaos.alignment import sali as sali
    from andoyer.analysis.chaos.border import chaos_border as chaos_border
    from andoyer.analysis.chaos.border import chaos_border_map as chaos_border_map
    from andoyer.analysis.chaos.border import hess_line as hess_line
    from andoyer.analysis.chaos.border import layer_width as layer_width
    from andoyer.analysis.chaos.border import regular_reference as regular_reference
    from andoyer.analysis.chaos.frequency import Lines as Lines
    from andoyer.analysis.chaos.frequency import frequency_drift as frequency_drift
    from andoyer.analysis.chaos.frequency import frequency_map as frequency_map
    from andoyer.analysis.chaos.frequency import naff as naff
    from andoyer.analysis.chaos.frequency import orbit_frequencies as orbit_frequencies
    from andoyer.analysis.chaos.frequency import resonance_label as resonance_label
    from andoyer.analysis.chaos.lyapunov import chaos_map as chaos_map
    from andoyer.analysis.chaos.lyapunov import indicators as indicators
    from andoyer.analysis.chaos.lyapunov import output_times as output_times
    from andoyer.analysis.chaos.registry import INDICATORS as INDICATORS
    from andoyer.analysis.chaos.registry import IndicatorSpec as IndicatorSpec
    from andoyer.analysis.chaos.registry import chosen as chosen
    from andoyer.analysis.chaos.specs import TANGENT_SPACES as TANGENT_SPACES
    from andoyer.analysis.chaos.specs import IndicatorRun as IndicatorRun
    from andoyer.analysis.chaos.specs import MapGrid as MapGrid
    from andoyer.analysis.chaos.tangent_space import initial_tangent as initial_tangent

#: Name -> the module of this package that defines it.
EXPORTS = {"indicators": "lyapunov", "chaos_map": "lyapunov", "output_times": "lyapunov",
           "initial_tangent": "tangent_space", "MapGrid": "specs", "IndicatorRun": "specs",
           "TANGENT_SPACES": "specs", "INDICATORS": "registry", "IndicatorSpec": "registry",
           "chosen": "registry", "sali": "alignment", "gali": "alignment",
           "alignment_indices": "alignment", "initial_tangents": "alignment",
           "chaos_border": "border", "chaos_border_map": "border", "regular_reference": "border",
           "layer_width": "border", "hess_line": "border", "Lines": "frequency",
           "naff": "frequency", "frequency_drift": "frequency",
           "orbit_frequencies": "frequency", "frequency_map": "frequency",
           "resonance_label": "frequency"}

__all__ = sorted(EXPORTS)

__getattr__, __dir__ = lazy_exports(__name__, EXPORTS)
