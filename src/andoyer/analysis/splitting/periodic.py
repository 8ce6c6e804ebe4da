"""Hyperbolic periodic orbits near the permanent rotations about the middle axis.

When ``z`` is the middle axis of inertia (``a < c < b`` or ``b < c < a``) the
permanent rotations ``G = (0, 0, +-G)`` of the free body are saddles: in the Hess
chart (14) they are the lines ``J1 = J2`` (``L = +G``) and ``J1 = 0`` (``L = -G``), the
four "fixed points" of the unperturbed system after Fig. 3 of [1]_, joined by the
heteroclinic orbits on ``theta1 = 0`` and ``theta1 = 4 phi0``. On an energy level of
the full system they are periodic orbits, and for ``mu > 0`` they persist as hyperbolic
periodic orbits; on ``M = 0`` for a body with ``e3 = 0`` they are exactly the rotations
of the physical pendulum about ``z`` (``G1 = G2 = gamma3 = 0`` is invariant: Eq. (8),
``G^2 = L^2``, ``M = 0``).

The section and its coordinates
-------------------------------
The Hess and Andoyer-Deprit charts are singular exactly on these orbits, so they are
found on a section of the regular Euler-Poisson variables. Let

.. math::

    \\psi = \\operatorname{atan2}(\\gamma_1, \\gamma_2),

the angle of the projection of the vertical on the body plane ``Oxy``, counted like
``l`` from axis 2 towards axis 1. Near ``G = (0, 0, +-G)`` the vertical is nearly in that
plane (``M = (G, gamma)`` small) and turns with ``dpsi/dt = c G3``; on ``L = +G``
``psi = theta1 + theta2 - phi0`` and on ``L = -G`` ``psi = pi - theta2 - phi0``. The
section :class:`RotationSection` is ``Sigma = {psi = psi0}`` crossed in the sense of the
rotation (``dpsi/dt`` of the sign of ``L``), on the level ``H = h``, ``(G, gamma) = M``.
Its points have the coordinates

.. math::

    (x_1, x_2) = (G_1, G_2) / |G|,

the components of the unit angular momentum across the axis: regular, and zero at the
permanent rotations and the pendulum rotations. The state is completed from
``(x1, x2)`` by solving ``H = h`` and ``(G, gamma) = M`` for ``|G|`` and ``gamma3``
(:func:`section_state`).

Newton's method
---------------
The Poincare map ``P: (x1, x2) -> (x1, x2)`` of ``Sigma`` is differentiated exactly:

.. math::

    DP = D\\pi \\, \\Big(I - \\frac{F \\, \\nabla f^T}{\\nabla f \\cdot F}\\Big)
         \\, \\Phi \\, D\\iota,

with ``Phi`` the state-transition matrix of the Euler-Poisson equations (1) from
their variational equations, the bracket the event sensitivity (``f`` the section
function, ``F`` the vector field at the return), ``D iota`` the derivative of the
completion (implicit-function theorem) and ``D pi`` that of ``(G1, G2)/|G|``. No finite
differences. Newton's iteration ``x <- x - (DP - I)^{-1} (P(x) - x)`` is continued in
``mu`` from the permanent rotation at ``mu = 0`` (:func:`continue_rotation_orbit`).
The multipliers are the eigenvalues of ``DP`` (``Lambda_u Lambda_s = 1``). At ``mu = 0``
``Lambda_u = exp(2 pi sigma / c)``, ``sigma = sqrt((b - c)(c - a))``; on a Hess body this
holds for every ``mu``: ``(G, r)`` obeys ``d(G, r)/dt = -sigma G3 (G, r)`` exactly and
``int G3 dt = 2 pi / c`` over a pendulum rotation (``dpsi/dt = c G3``).

Integrators
-----------
heyoka's Taylor method where heyoka is installed (``tol = 1e-15`` by default;
``long_double=True`` for 80-bit extended precision), compiled once per process and
section kind and reused for every body through runtime parameters; the variational
system is compiled in compact mode (about a second instead of a minute). The compiled
integrators are shared, so these functions are not thread-safe. Without heyoka the
flow to the section runs on the Numba DOP853 with the variational equations generated
by SymPy (tolerance ``max(tol, 1e-13)``, double precision only; see
:mod:`andoyer.analysis.splitting.section_map`): the multipliers of the Hess rotations agree with
the closed form to 1e-10, the periodic orbits with heyoka's to 1e-11.

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring", National Aviation University, Kyiv (``andoyer.cite("paper")``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.analysis.splitting.section_map import (
    DEFAULT_TOL,
    FLOW_ENGINES,
    Crossing,
    RotationSection,
    SectionReturn,
    event_projector,
    flow_engine,
    flow_to_section,
    gamma_phase,
    middle_axis_rate,
    return_map,
    rotation_energy,
    section_coords,
    section_state,
)
from andoyer.body import RigidBody, checks_body
from andoyer.charts.euler_poisson import STATE
from andoyer.integrate.results import VariableMeta, describe_variables, provenance
from andoyer.kernels.constants import T_START
from andoyer.validation import checks_arguments, finite_array, integer

__all__ = [
    "DEFAULT_TOL",
    "T_START",
    "RotationSection",
    "RotationOrbit",
    "Crossing",
    "SectionReturn",
    "gamma_phase",
    "section_coords",
    "section_state",
    "flow_to_section",
    "event_projector",
    "return_map",
    "rotation_orbit",
    "continue_rotation_orbit",
    "orbits_dataset",
    "pendulum_rotation",
    "rotation_energy",
    "middle_axis_rate",
]


# ----------------------------------------------------------------------------- Newton
@dataclass(frozen=True)
class RotationOrbit:
    """A periodic orbit near the rotation about ``sign * z``, fixed point of the section map.

    Attributes
    ----------
    body, h, M, section :
        The problem.
    x : ndarray (2,)
        Fixed point ``(G1, G2)/|G|`` on the section.
    y : ndarray (6,)
        Its Euler-Poisson state.
    period : float
        Return time (the period of the orbit).
    multipliers : ndarray (2,)
        ``(Lambda_u, Lambda_s)``, the eigenvalues of ``DP``, ``|Lambda_u| > 1``.
    eigenvectors : ndarray (2, 2)
        Columns: unit unstable and stable eigenvectors in the ``(x1, x2)`` plane.
    DP : ndarray (2, 2)
        Jacobian of the section map at the fixed point.
    monodromy : ndarray (6, 6)
        State-transition matrix over one period.
    iterations : int
        Newton iterations used.
    residual : float
        ``|P(x) - x|`` at the returned point.
    tol : float
        Integration tolerance.
    long_double : bool
        Extended precision (heyoka only).
    engine : {"heyoka", "numba"}
        The engine of the section map (:func:`~andoyer.analysis.splitting.section_map.flow_engine`).
    """

    body: RigidBody
    h: float
    M: float
    section: RotationSection
    x: NDArray[np.float64]
    y: NDArray[np.float64]
    period: float
    multipliers: NDArray[np.float64]
    eigenvectors: NDArray[np.float64]
    DP: NDArray[np.float64]
    monodromy: NDArray[np.float64]
    iterations: int
    residual: float
    tol: float = DEFAULT_TOL
    long_double: bool = field(default=False)
    engine: str = field(default_factory=flow_engine)

    @property
    def lyapunov_exponent(self) -> float:
        """``ln |Lambda_u| / period`` (``sigma G`` at ``mu = 0``)."""
        return math.log(abs(float(self.multipliers[0]))) / self.period

    def attrs(self) -> dict[str, Any]:
        return {**self.section.attrs(), "energy": self.h, "area": self.M,
                "tolerance": self.tol, "long_double": int(self.long_double)}


def _eigen(DP: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    w, V = np.linalg.eig(DP)
    if np.any(np.abs(w.imag) > 1e-12 * np.abs(w)):
        raise ValueError(f"the periodic orbit is not hyperbolic: multipliers {w} are "
                         "complex (elliptic); no stable/unstable manifolds")
    w, V = w.real, V.real
    order = np.argsort(-np.abs(w))
    w, V = w[order], V[:, order]
    V = V / np.linalg.norm(V, axis=0)
    return w, V


@checks_body
def rotation_orbit(body: RigidBody, h: float, M: float = 0.0,
                   section: RotationSection | None = None, *, guess: ArrayLike | None = None,
                   tol: float = DEFAULT_TOL, xtol: float = 1e-13, max_iter: int = 12,
                   long_double: bool = False, engine: str | None = None) -> RotationOrbit:
    """Newton's method on the section map for the periodic orbit near the rotation.

    Parameters
    ----------
    body : RigidBody
        Any body with ``z`` the middle axis of inertia.
    h : float
        Energy of the level (e.g. :func:`rotation_energy`).
    M : float
        Area constant ``(G, gamma)``.
    section : RotationSection
        Which rotation (``sign``) and where to cut it (``psi0``).
    guess : array_like (2,), optional
        Starting point ``(x1, x2)``; default the permanent rotation ``(0, 0)``.
    tol : float
        Integration tolerance (heyoka's ``tol``; the numba engine's DOP853 gets
        ``max(tol, 1e-13)`` for both ``rtol`` and ``atol``).
    xtol : float
        Stop when the Newton step is below ``xtol``.
    max_iter : int
        Raise ``RuntimeError`` if not converged after this many iterations.
    long_double : bool
        Extended precision integration (heyoka only).
    engine : {"heyoka", "numba"}, optional
        The engine of the section map; default heyoka where installed, else numba
        (:func:`~andoyer.analysis.splitting.section_map.flow_engine`).

    Returns
    -------
    RotationOrbit

    Examples
    --------
    >>> body = RigidBody.paper()
    >>> orb = rotation_orbit(body, rotation_energy(body), section=RotationSection(0.0, -1))
    >>> bool(abs(orb.x).max() < 1e-12)            # the pendulum rotation G1 = G2 = 0
    True
    >>> bool(abs(orb.multipliers.prod() - 1) < 1e-10)
    True
    """
    sec = RotationSection() if section is None else section
    engine = flow_engine(engine)
    middle_axis_rate(body)
    if guess is None:
        x = np.zeros(2)
    else:
        x = finite_array("guess", guess, copy=True)
        if x.shape != (2,):
            raise ValueError(f"guess must be a section point (x1, x2), shape (2,), got shape "
                             f"{x.shape}")
    step, iterations = np.inf, 0
    while step > xtol:
        if iterations == max_iter:
            raise RuntimeError(f"Newton's method did not converge in {max_iter} iterations "
                               f"(last step {step:.3g}); continue in mu with smaller steps")
        r = return_map(body, x, h, M, sec, tol=tol, long_double=long_double, engine=engine)
        assert r.DP is not None
        step_v = np.linalg.solve(r.DP - np.eye(2), x - r.x)
        x = x + step_v
        step = float(np.linalg.norm(step_v))
        iterations += 1
    r = return_map(body, x, h, M, sec, tol=tol, long_double=long_double, engine=engine)
    assert r.DP is not None and r.stm is not None
    w, V = _eigen(r.DP)
    y0 = section_state(body, x, h, M, sec)
    return RotationOrbit(body, float(h), float(M), sec, x, y0, r.T, w, V, r.DP, r.stm, iterations,
                         float(np.linalg.norm(r.x - x)), tol, long_double, engine)


@checks_body
def continue_rotation_orbit(body: RigidBody, h: float, M: float = 0.0,
                            section: RotationSection | None = None, *,
                            mu: ArrayLike | None = None, steps: int = 4,
                            tol: float = DEFAULT_TOL, long_double: bool = False,
                            engine: str | None = None,
                            ) -> tuple[list[RotationOrbit], xr.Dataset]:
    """Continue the periodic orbit in ``mu`` from the permanent rotation at ``mu = 0``.

    Parameters
    ----------
    body : RigidBody
        Its ``mu`` is the end of the continuation unless ``mu`` is given.
    h, M, section, tol, long_double, engine :
        As in :func:`rotation_orbit`.
    mu : array_like, optional
        Increasing values of ``mu`` starting at 0 (default ``steps + 1`` equal steps
        from 0 to ``body.mu``). A step whose Newton iteration fails is halved.
    steps : int
        Number of equal steps when ``mu`` is not given.

    Returns
    -------
    orbits : list of RotationOrbit
        One per value of ``mu`` (the last is at the largest ``mu``).
    ds : xarray.Dataset
        Dim ``mu``: fixed point ``x1, x2``, state ``y`` (mu, component), ``period``,
        ``Lambda_u``, ``Lambda_s``, ``lyapunov_exponent``, the eigenvectors
        ``v_unstable``, ``v_stable`` (mu, coord), ``newton_iterations``, ``residual``.
    """
    sec = RotationSection() if section is None else section
    if mu is None:
        steps = integer("steps", steps, 1)
        mus = np.linspace(0.0, body.mu, steps + 1) if body.mu > 0 else np.zeros(1)
    else:
        mus = np.atleast_1d(np.asarray(mu, dtype=float))
        if mus.ndim != 1 or mus.size == 0 or not np.all(np.isfinite(mus)):
            raise ValueError("mu must be a non-empty 1-D array of finite values")
        if mus[0] != 0.0 or np.any(np.diff(mus) <= 0.0):
            raise ValueError("mu must start at 0 (the permanent rotation) and increase")

    def solve(m: float, guess: NDArray[np.float64]) -> RotationOrbit:
        return rotation_orbit(body.with_mu(m), h, M, sec, guess=guess, tol=tol,
                              long_double=long_double, engine=engine)

    def reach(m0: float, x0: NDArray[np.float64], slope: NDArray[np.float64], m1: float,
              depth: int = 0) -> RotationOrbit:
        """From the orbit at m0 to m1; halve the step when Newton fails."""
        try:
            return solve(m1, x0 + slope * (m1 - m0))
        except (RuntimeError, ValueError, np.linalg.LinAlgError):
            if depth >= 8:
                raise
        mid = 0.5 * (m0 + m1)
        half = reach(m0, x0, slope, mid, depth + 1)
        return reach(mid, half.x, (half.x - x0) / (mid - m0), m1, depth + 1)

    orbits = [solve(float(mus[0]), np.zeros(2))]
    slope = np.zeros(2)
    for m in mus[1:]:
        prev = orbits[-1]
        orb = reach(prev.body.mu, prev.x, slope, float(m))
        slope = (orb.x - prev.x) / (orb.body.mu - prev.body.mu)
        orbits.append(orb)
    return orbits, orbits_dataset(orbits)


@checks_arguments
def orbits_dataset(orbits: list[RotationOrbit]) -> xr.Dataset:
    """Dataset (dim ``mu``) of periodic orbits found by :func:`rotation_orbit`.

    Parameters
    ----------
    orbits : list of RotationOrbit
        Orbits of :func:`rotation_orbit`, one per ``mu`` (of one body, level and section).
    """
    if not orbits:
        raise ValueError("no orbits")
    if not (isinstance(orbits, list | tuple) and orbits
            and all(isinstance(o, RotationOrbit) for o in orbits)):
        raise ValueError(f"orbits must be a non-empty list of RotationOrbit, got "
                         f"{orbits!r}"[:200])
    first = orbits[0]
    mus = np.array([o.body.mu for o in orbits])
    ds = xr.Dataset(
        {"x1": (("mu",), [o.x[0] for o in orbits]),
         "x2": (("mu",), [o.x[1] for o in orbits]),
         "y": (("mu", "component"), np.stack([o.y for o in orbits])),
         "period": (("mu",), [o.period for o in orbits]),
         "Lambda_u": (("mu",), [o.multipliers[0] for o in orbits]),
         "Lambda_s": (("mu",), [o.multipliers[1] for o in orbits]),
         "lyapunov_exponent": (("mu",), [o.lyapunov_exponent for o in orbits]),
         "v_unstable": (("mu", "coord"), np.stack([o.eigenvectors[:, 0] for o in orbits])),
         "v_stable": (("mu", "coord"), np.stack([o.eigenvectors[:, 1] for o in orbits])),
         "newton_iterations": (("mu",), [o.iterations for o in orbits]),
         "residual": (("mu",), [o.residual for o in orbits])},
        coords={"mu": mus, "component": list(STATE), "coord": ["x1", "x2"]},
        attrs=provenance(first.body, engine=FLOW_ENGINES[first.engine],
                         method="Newton on the section map psi = psi0, Jacobian from the "
                                "variational equations and the event sensitivity; "
                                "continuation in mu from the permanent rotation",
                         **first.attrs()))
    meta: dict[str, VariableMeta] = {
        "x1": ("x_1", "G1/|G| at the fixed point of the section map", "1", "(1)"),
        "x2": ("x_2", "G2/|G| at the fixed point of the section map", "1", "(1)"),
        "y": ("(G, \\gamma)", "Euler-Poisson state of the fixed point", "1", "(1)"),
        "period": ("T", "period (return time to the section)", "body time units", "(1)"),
        "Lambda_u": ("\\Lambda_u", "unstable multiplier", "1", "(1)"),
        "Lambda_s": ("\\Lambda_s", "stable multiplier", "1", "(1)"),
        "lyapunov_exponent": ("\\ln|\\Lambda_u|/T", "Lyapunov exponent of the orbit",
                              "1/body time unit", "(1)"),
        "v_unstable": ("v_u", "unstable eigenvector in (x1, x2)", "1", "(1)"),
        "v_stable": ("v_s", "stable eigenvector in (x1, x2)", "1", "(1)"),
        "newton_iterations": ("", "Newton iterations", "1", "(1)"),
        "residual": ("|P(x) - x|", "fixed-point residual", "1", "(1)"),
    }
    describe_variables(ds, meta)
    ds.mu.attrs.update(symbol="\\mu", long_name="weight x distance of the centre of mass",
                       units="1", equation="(1)")
    return ds


# ----------------------------------------------------------------------------- exact orbit
@checks_body
def pendulum_rotation(body: RigidBody, h: float, section: RotationSection | None = None
                      ) -> tuple[NDArray[np.float64], float]:
    """The pendulum rotation about ``sign * z`` on ``M = 0`` (bodies with ``e3 = 0``).

    ``G1 = G2 = gamma3 = 0`` is invariant (Eq. (8), ``G^2 = L^2``, ``M = 0``): the body
    turns about z like a physical pendulum, ``dpsi/dt = c G3``,
    ``c G3^2 / 2 + mu sin(psi + phi0) = h``.

    Parameters
    ----------
    body : RigidBody
        A body with ``e3 = 0`` and Oz the middle axis.
    h : float
        Energy level (above the pendulum's separatrix ``h > mu``).
    section : RotationSection, optional
        The section ``psi = psi0`` and the sense of the rotation (default
        ``RotationSection()``: ``psi0 = 0`` about ``+z``).

    Returns
    -------
    y : ndarray (6,)
        State on the section ``psi = psi0``.
    period : float
        ``T = int_0^{2 pi} dpsi / (c |G3(psi)|)`` (quadrature).
    """
    from scipy.integrate import quad

    sec = RotationSection() if section is None else section
    body.require_planar("pendulum_rotation")
    a, b, c, mu, e1, e2, _ = body.params

    def G3(psi: float) -> float:
        V = mu * (e1 * math.sin(psi) + e2 * math.cos(psi))
        if not h - V > 0.0:
            raise ValueError(f"h = {h:g} is below the top of the pendulum potential "
                             f"(mu = {mu:g}): the pendulum librates, it does not rotate")
        return math.sqrt(2.0 * (h - V) / c)

    period = quad(lambda p: 1.0 / (c * G3(p)), 0.0, 2.0 * math.pi, epsabs=1e-15, epsrel=1e-13,
                  limit=200)[0]
    G = G3(sec.psi0)
    y = np.array([0.0, 0.0, sec.sign * G, math.sin(sec.psi0), math.cos(sec.psi0), 0.0])
    return y, period
