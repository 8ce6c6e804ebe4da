"""The report's item of the proofs: the Melnikov zeros proved simple (first order) and the
transversal splitting proved at finite ``mu`` (:mod:`andoyer.analysis.splitting.transversal`),
each written as a certificate that ``andoyer verify`` re-checks.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import Any

from andoyer.report.base import Context, Result, Table, concurrently

__all__ = ["proof", "THEOREM_BODY"]

#: The near-Hess body of the finite-mu theorem: (A, B, C, branch, epsilon, mu), decimals.
THEOREM_BODY = ("2.5", "1.0", "1.6", 1, "0.1", "0.05")


def proof(ctx: Context) -> Result:
    """Certificates of the first-order and of the finite-``mu`` transversality; the proved
    splitting angle against the measured one.

    The first-order certificate is verified here (:func:`verify_certificate`: ``Z`` and
    the Krawczyk test of each box, a fraction of a second). The finite-``mu`` one is proved
    once: its verification re-runs that same proof from the recorded manifold and piece
    (as long again as the proof) and is left to ``andoyer verify proof-transversal.json``
    (the prose says so).

    Parameters
    ----------
    ctx : Context
        Output folder, body, engine, quick (quick: the measurement's phase grid is
        coarser).
    """
    import numpy as np
    from flint import arb

    from andoyer.analysis.splitting.certificate import (
        prove_certificate,
        prove_transversal_certificate,
        verify_certificate,
        write_certificate,
    )
    from andoyer.analysis.splitting.measure import separatrix_splitting
    from andoyer.body import RigidBody
    from andoyer.integrate.validated.arithmetic import BodySpec
    from andoyer.plot.words import branch_words

    spec = BodySpec(*THEOREM_BODY)

    def proved() -> tuple[dict[str, Any], dict[str, Any], dict[str, Any]]:
        first = prove_certificate(ctx.body, branch="theta1=4phi0", digits=20)
        checked = verify_certificate(first)
        theorem = prove_transversal_certificate(spec)
        return first, checked, theorem

    body = RigidBody.near_hess(float(spec.A), float(spec.B), float(spec.C),
                               mu=float(spec.mu), epsilon=float(spec.epsilon))
    # The measurement integrates without the GIL: it runs beside the proofs' arithmetic.
    tasks: list[Callable[[], Any]] = [proved, partial(
        separatrix_splitting, body, [float(spec.mu)], branch="theta1=0", sheet=-1,
        n_phase=8 if ctx.quick else 16, delta=1e-5, progress=False)]
    (first, checked, theorem), splitting = concurrently(tasks)
    files = [write_certificate(first, ctx.out / "proof-melnikov.json"),
             write_certificate(theorem, ctx.out / "proof-transversal.json")]
    boxes = theorem["boxes"]
    angle = arb(boxes["angle"])
    inter = splitting["intersections"]
    measured_all = inter.angle.values[0]
    measured = float(measured_all[np.nanargmin(np.abs(measured_all - float(angle.mid())))])
    lm = theorem["local_manifold"]
    # the prose writes the certificates' theorems in TeX (their statements are plain text)
    unstable, stable = ("P_-", "P_+") if lm["rotation"] == -1 else ("P_+", "P_-")
    rows = [["period multiplier lambda of P+ (return to gamma2 = 0)", boxes["multiplier"]],
            ["cone slope kappa on N = [-r, r]^2", f"{lm['kappa']:.3e} (r = {lm['radius']:g})"],
            ["gamma3 at the two ends of the piece on L = 0", " / ".join(boxes["ends_gamma3"])],
            ["crossing time from gamma2 = 0 to L = 0", boxes["crossing_time"]],
            ["slope sigma = dG/dg of W^u at the point", boxes["slope"]],
            ["splitting angle 2 atan(sigma) (proved)", boxes["angle"]],
            ["splitting angle measured (separatrix_splitting)", f"{measured:.10f}"]]
    return Result(
        files,
        {"angle_proved": float(angle.mid()), "angle_radius": float(angle.rad()),
         "angle_measured": measured, "theorem_seconds": float(theorem["run_seconds"]),
         "melnikov_digits": float(checked["digits"])},
        {"first": {"body": first["body"], "J2": first["level"]["J2"],
                   "branch": branch_words(first["branch"]).strip("$"),
                   "sheet": first["sheet"], "zeros": checked["zeros"]},
         "theorem": {"body": theorem["body"], "G": theorem["level"]["G"],
                     "mu": (theorem["mu_interval"]["lower"], theorem["mu_interval"]["upper"]),
                     "unstable": unstable, "stable": stable, "angle": boxes["angle"]},
         "seconds": theorem["run_seconds"], "inside": bool(
             abs(measured - float(angle.mid())) <= float(angle.rad())),
         "mu": spec.mu, "epsilon": spec.epsilon},
        Table(["quantity", "enclosure (Arb ball)"], rows))
