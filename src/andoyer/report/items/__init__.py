"""The report's items in report order: key, title, builder, measured cost (the CPU
seconds of each on two loaded cores, scaled to fig1's 1.4 s on an idle machine).

The builders are grouped by subject (:mod:`.unperturbed`, :mod:`.hess`, :mod:`.inertial`,
:mod:`.perturbed`, :mod:`.resonance`, :mod:`.torus`, :mod:`.theorems`);
each item's prose is ``templates/items/<key>.html.j2``.

Examples
--------
>>> [item.key for item in ITEMS][:3]
['fig1', 'fig2', 'heteroclinic']
"""

from __future__ import annotations

from andoyer.report.base import Item
from andoyer.report.items import (
    hess,
    inertial,
    perturbed,
    resonance,
    theorems,
    torus,
    unperturbed,
)

__all__ = ["ITEMS"]

ITEMS: list[Item] = [
    Item("fig1", "Fig. 1 — the unperturbed system (9) in (l, L)", unperturbed.fig1, 1.4),
    Item("fig2", "Fig. 2 — the unperturbed Euler–Poinsot portrait; all fixed points",
         unperturbed.fig2, 0.4),
    Item("heteroclinic", "Heteroclinic orbits in closed form", unperturbed.heteroclinic, 0.1),
    Item("solutions", "The Hess solution and the physical pendulum", hess.solutions, 0.8),
    Item("fig3", "Fig. 3 — trajectories of (16) near the separatrix, and the section "
         "θ2 = 0", hess.fig3, 1.0),
    Item("space", "Beyond the paper: the Hess motions in space, the heteroclinic cycle",
         inertial.space, 0.3),
    Item("manifolds", "Beyond the paper: separatrix splitting and the Melnikov function",
         perturbed.manifolds, 1.6),
    Item("chaos", "Beyond the paper: chaos maps (FLI)", perturbed.chaos, 1.8),
    Item("border", "Beyond the paper: the border of chaos near the Hess case", perturbed.border,
         2.5),
    Item("resonances", "Beyond the paper: resonances predicted, then measured",
         resonance.resonances, 29.5),
    Item("last-torus", "Beyond the paper: where the last torus breaks (Greene's residues)",
         torus.last_torus, 17.5),
    Item("proof", "Beyond the paper: the splitting proved (Melnikov zeros; transversality "
         "at finite μ)", theorems.proof, 14.5),
    Item("paper-check", "Every printed formula against the derivation",
         unperturbed.paper_check, 0.0),
]
