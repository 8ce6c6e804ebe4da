"""Constants of the numeric layer, defined once (no Numba import here).

A section root at ``t <= T_START`` is the initial state lying on the section (to
round-off), not a crossing: "crossings after t = 0" must not depend on the sign of the
round-off in the section function at ``y0``. Every engine and the periodic-orbit
section maps apply it.
"""

__all__ = ["T_START"]

T_START = 1e-10
