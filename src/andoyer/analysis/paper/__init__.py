"""The paper itself: the check of its printed formulas and the trajectories of Fig. 3.

The functions and classes of its modules are names of this package too.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from andoyer.analysis._exports import lazy_exports

if TYPE_CHECKING:
    from andoyer.analysis.paper.check import CheckRow as CheckRow
    from andoyer.analysis.paper.check import Formula as Formula
    from andoyer.analysis.paper.check import paper_check as paper_check
    from andoyer.analysis.paper.trajectories import fig3_section as fig3_section
    from andoyer.analysis.paper.trajectories import fig3_trajectories as fig3_trajectories
    from andoyer.analysis.paper.trajectories import zoom_box as zoom_box

#: Name -> the module of this package that defines it (imported on first use).
EXPORTS = {"CheckRow": "check", "Formula": "check", "paper_check": "check",
           "fig3_section": "trajectories",
           "fig3_trajectories": "trajectories", "zoom_box": "trajectories"}

__all__ = sorted(EXPORTS)

__getattr__, __dir__ = lazy_exports(__name__, EXPORTS)
