"""The pendulum-like rotations ``P+-`` proved hyperbolic: period and multipliers in balls.

For every ``mu`` the set ``G1 = G2 = gamma3 = 0`` is invariant under (1): there
``G = (0, 0, G3)``, ``gamma = (cos psi, sin psi, 0)`` and ``(G3, psi)`` is a pendulum. Its
rotations ``P+`` (``G3 > 0``) and ``P-`` (``G3 < 0``) on the level ``h = c G^2 / 2`` are the
periodic orbits whose stable and unstable manifolds split
(:mod:`andoyer.analysis.splitting.manifolds`). Here one is carried once around by the
validated integrator (:func:`andoyer.integrate.validated.taylor.validated_poincare`, the
section ``gamma2 = 0``) from the state with ``gamma = (1, 0, 0)``:

* the return time (the period) is enclosed by interval Newton on the section;
* the image encloses the start (the orbit closes);
* the derivative's block on the normal directions ``(G1, G2, gamma3)`` (the invariant set
  is preserved, so the normal block of the monodromy is a ``3 x 3`` matrix of its own)
  has three simple eigenvalues, enclosed by Arb (``acb_mat.eig``): ``1`` (the area
  integral ``(G, gamma)``), ``lambda > 1`` and ``1/lambda``: the orbit is hyperbolic.

This is the first step of a computer-assisted proof of transversal splitting at finite
``mu``; :mod:`andoyer.analysis.splitting.transversal` proves the rest (local manifold,
transport, intersection).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

from flint import acb, acb_mat, arb

from andoyer.body import RigidBody
from andoyer.errors import ArgumentTypeError
from andoyer.integrate.validated.arithmetic import (
    FLINT_VERSION,
    BodySpec,
    ball_text,
    decimal,
    precision,
    working_precision,
)
from andoyer.integrate.validated.taylor import validated_poincare
from andoyer.validation import integer

__all__ = ["HyperbolicRotation", "certified_rotation"]

#: The normal directions of the invariant set ``G1 = G2 = gamma3 = 0``.
NORMAL = (0, 1, 5)


@dataclass(frozen=True)
class HyperbolicRotation:
    """A rotation ``P+-`` carried once around in balls.

    Attributes
    ----------
    sign : int
        +1 for ``P+`` (``G3 > 0``), -1 for ``P-``.
    start : tuple of str
        The state on ``gamma2 = 0`` (six balls).
    period : str
        The return time to the section.
    closes : bool
        Whether the enclosure of the return holds the start.
    multipliers : tuple of str
        The real parts of the normal block's eigenvalues (balls), ascending.
    imaginary_bound : float
        The largest ``|imaginary part|`` the enclosures allow (they are real: the block
        is real and its eigenvalues simple).
    unstable, stable : float
        Midpoints of the multipliers above and below 1.
    hyperbolic : bool
        Whether the multipliers are proved real, with ``lambda > 1 > 1/lambda``.
    return_width : float
        The largest radius of the return's enclosure.
    seconds : float
        Run time.
    flint_version : str
        python-flint's version.
    """

    sign: int
    start: tuple[str, ...]
    period: str
    closes: bool
    multipliers: tuple[str, ...]
    imaginary_bound: float
    unstable: float
    stable: float
    hyperbolic: bool
    return_width: float
    seconds: float
    flint_version: str = FLINT_VERSION


def certified_rotation(body: Any, *, G: str = "1", sign: int = 1, bits: int = 128,
                       order: int = 30) -> HyperbolicRotation:
    """Carry ``P+`` or ``P-`` of the level ``h = c G^2/2`` once around, in balls.

    Parameters
    ----------
    body : RigidBody or BodySpec
        The body (``mu > 0``; centre of mass in the (e1, e2) plane).
    G : str, default "1"
        The level ``h = c G^2 / 2`` (a decimal).
    sign : {+1, -1}, default 1
        ``P+`` (``G3 > 0``) or ``P-``.
    bits : int, default 128
        Working precision.
    order : int, default 30
        Taylor order.

    Returns
    -------
    HyperbolicRotation

    Raises
    ------
    ValueError
        For a bad ``sign``, a level below the potential's reach (``G3^2 < 0``) or a body
        with ``e3 != 0``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> rot = certified_rotation(RigidBody.paper())
    >>> rot.hyperbolic, rot.closes, rot.unstable > 1
    (True, True, True)
    """
    start_clock = time.perf_counter()
    if isinstance(sign, bool) or sign not in (1, -1):
        raise ValueError(f"sign must be +1 or -1, got {sign!r}")
    if not isinstance(body, RigidBody | BodySpec):
        raise ArgumentTypeError(f"body must be a RigidBody or a BodySpec, got "
                                f"{type(body).__name__}")
    G = decimal("G", G, positive=True, maximum=1e6)
    bits = precision("bits", bits)
    order = integer("order", order, 4, 60)
    with working_precision(bits):
        if isinstance(body, BodySpec):
            b = body.balls(bits)
            c, mu, e1, e3 = b.c, b.mu, b.e1, b.e3
        else:
            c, mu, e1, e3 = 1 / arb(body.C), arb(body.mu), arb(body.e1), arb(body.e3)
        if not e3.is_zero():
            raise ValueError("certified_rotation needs the body's centre of mass in the "
                             "(e1, e2) plane (e3 = 0)")
        Gb = arb(G)
        G3sq = Gb * Gb - 2 * mu * e1 / c
        if not G3sq > 0:
            raise ValueError(f"the level G = {G} is below the top of the pendulum: no "
                             "rotation there")
        G3 = sign * G3sq.sqrt()
        y0 = [arb(0), arb(0), G3, arb(1), arb(0), arb(0)]
        cross = validated_poincare(body, y0, [0, 0, 0, 0, 1, 0], 0.0, direction=-sign,
                                   order=order, bits=bits, skip=0.0)
        image = [arb(x) for x in cross.image]
        closes = all(image[i].contains(y0[i]) or image[i].overlaps(y0[i]) for i in range(6))
        D = [[arb(x) for x in cross.derivative[6 * i: 6 * i + 6]] for i in range(6)]
        N = acb_mat([[acb(D[i][j]) for j in NORMAL] for i in NORMAL])
        eig = sorted(N.eig(), key=lambda z: float(abs(z).mid()))
        real = all(z.imag.contains(0) and z.imag.rad() < 1e-6 for z in eig)
        lo, mid, hi = (z.real for z in eig)
        hyperbolic = bool(real and hi > 1 and lo < 1 and lo > 0 and mid.overlaps(arb(1)))
        return HyperbolicRotation(
            sign=sign, start=tuple(ball_text(x, 30) for x in y0), period=cross.time,
            closes=bool(closes), multipliers=tuple(ball_text(z.real, 25) for z in eig),
            imaginary_bound=max(float(abs(z.imag).upper()) for z in eig),
            unstable=float(hi.mid()), stable=float(lo.mid()), hyperbolic=hyperbolic,
            return_width=float(max(cross.image_rad)),
            seconds=time.perf_counter() - start_clock)
