"""Equilibria of the heavy top: permanent rotations of the free top (the Euler-Poinsot
fixed points on ``|G| = G0``) and the Euler-Poisson equilibria (hanging and upright), with
their types from the linearised flow.

The chart fixed points of (9) and (16) are built on these in
:mod:`andoyer.analysis.unperturbed.fixed_points`.

Euler-Poisson equilibria
------------------------
At ``G = 0``, ``gamma = s r`` (``s = -1`` hanging: the centre of mass below the fixed
point; ``s = +1`` upright) the linearisation on the symplectic leaf ``|gamma| = 1``,
``(G, gamma) = 0`` (tangent space ``dG, dgamma`` orthogonal to ``r``) is
``d^2 dG/dt^2 = s mu P I P dG``, ``P`` the projection orthogonal to ``r``. The two
eigenvalues ``k`` of ``P I P`` on ``r^perp`` have sum ``a + b + c - (r, I r)`` and
product ``b c e1^2 + c a e2^2 + a b e3^2``; the eigenvalues are ``+-i sqrt(mu k)``
(hanging: centre-centre) and ``+-sqrt(mu k)`` (upright: saddle-saddle). On a Hess body
``k = c`` twice (the circular sections of the gyration ellipsoid): a 1:1 resonance.
The Euler-Poisson system has other equilibria in the body frame, the permanent
rotations of Staude (``G`` parallel to the vertical, ``G != 0``); they are not
treated here.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from andoyer.body import RigidBody, checks_body
from andoyer.integrate.results import provenance
from andoyer.validation import MAX_ACTION, checks_arguments
from andoyer.validation import positive as _positive

__all__ = [
    "AXES", "EquilibriumSet", "EulerPoissonEquilibrium", "PermanentRotation",
    "ROTATION_LABELS", "TYPE_RTOL", "classify", "euler_poisson_equilibria",
    "permanent_rotations", "require_distinct_moments", "sorted_eigenvalues",
]

#: Closed forms only: levels and actions up to ``|G| = MAX_ACTION``
#: (:func:`andoyer.validation.momentum_limit`).
CLOSED_FORM = True


#: Principal axis -> (moment name, index in (a, b, c)).
AXES: dict[str, tuple[str, int]] = {"x": ("A", 0), "y": ("B", 1), "z": ("C", 2)}


#: Labels of the uniform rotations in Fig. 2 (this package's convention): 1, 2 are the
#: rotations about the z axis that the pendulum motions approach, 3, 4 the others.
ROTATION_LABELS: dict[tuple[str, int], int] = {
    ("z", +1): 1, ("z", -1): 2, ("y", +1): 3, ("y", -1): 3, ("x", +1): 4, ("x", -1): 4}


#: Relative size of an eigenvalue below which the linear type is "degenerate".
TYPE_RTOL = 1e-8


@cache
def _ep_jacobian() -> Callable[..., Any]:
    """Jacobian of the Euler-Poisson field (1), lambdified: ``(*y, *body.params)``."""
    import sympy as sp

    from andoyer.symbolic.hamiltonian import S, euler_poisson_field

    jac = sp.Matrix(euler_poisson_field()).jacobian(S.y)
    return sp.lambdify((*S.y, *S.body), jac.tolist(), "numpy")


def _eigenvalues(name: str, value: Any) -> NDArray[np.complex128]:
    """A finite 1-D array of an even number of eigenvalues (a Hamiltonian system's come
    in pairs), or ``ValueError`` naming ``name``."""
    try:
        ev = np.asarray(value)
    except ValueError:
        ev = np.asarray([], dtype=object)
    if ev.dtype.kind not in "iufc" or ev.ndim != 1 or ev.size % 2 or not ev.size \
            or not np.all(np.isfinite(ev)):
        raise ValueError(f"{name} must be a 1-D array of an even number of finite "
                         f"eigenvalues, got {value!r}"[:200])
    return ev.astype(complex)


@checks_arguments
def classify(eigenvalues: Sequence[complex] | NDArray[np.complex128], scale: float) -> str:
    """Linear type of a fixed point of a Hamiltonian system from its eigenvalues.

    ``"centre"`` (all eigenvalues imaginary), ``"saddle"`` (all real), ``"saddle-centre"``
    (mixed, 4-D), ``"degenerate"`` (an eigenvalue below ``TYPE_RTOL * scale``). For
    4-D: ``"centre-centre"``, ``"saddle-saddle"``.

    Parameters
    ----------
    eigenvalues : sequence of complex
        Eigenvalues of the linearised field at the fixed point (2 or 4).
    scale : float
        Scale of the field: eigenvalues below :data:`TYPE_RTOL` times it count as zero.

    Examples
    --------
    >>> classify([1j, -1j], 1.0), classify([0.5, -0.5], 1.0), classify([0, 0], 1.0)
    ('centre', 'saddle', 'degenerate')
    """
    ev = _eigenvalues("eigenvalues", eigenvalues)
    tol = TYPE_RTOL * scale
    if np.any(np.abs(ev) <= tol):
        return "degenerate"
    real = np.abs(ev.real) > tol
    imag = np.abs(ev.imag) > tol
    if np.any(real & imag):
        return "complex-saddle"
    n_saddle = int(real.sum()) // 2
    n_centre = len(ev) // 2 - n_saddle
    if len(ev) <= 2:
        return "saddle" if n_saddle else "centre"
    return "-".join(["saddle"] * n_saddle + ["centre"] * n_centre)


@checks_arguments
def sorted_eigenvalues(ev: NDArray[np.complex128]) -> tuple[complex, ...]:
    """Eigenvalues in a fixed order: by real part, then imaginary part.

    Parameters
    ----------
    ev : array_like of complex
        Eigenvalues: 1-D, an even number (a Hamiltonian system's come in pairs),
        finite.

    Returns
    -------
    tuple of complex

    Examples
    --------
    >>> [v.real for v in sorted_eigenvalues(np.array([0.5, 2.0, -0.5, -2.0]))]
    [-2.0, -0.5, 0.5, 2.0]
    """
    ev = _eigenvalues("ev", ev)
    order = np.lexsort((ev.imag, ev.real))
    return tuple(complex(v) for v in ev[order])


@checks_body
def require_distinct_moments(body: RigidBody) -> None:
    """``ValueError`` unless the three moments of inertia are distinct (relative gap
    above 1e-12): an axisymmetric body has whole circles of permanent rotations.

    Parameters
    ----------
    body : RigidBody
        The body to check.
    """
    I = (body.a, body.b, body.c)
    gaps = [abs(I[i] - I[j]) for i, j in ((0, 1), (1, 2), (0, 2))]
    if min(gaps) <= 1e-12 * max(I):
        raise ValueError(
            f"the fixed-point classification needs three distinct moments of inertia, got "
            f"A={body.A}, B={body.B}, C={body.C}: an axisymmetric body has whole circles "
            "of permanent rotations (lines of fixed points); break the symmetry slightly")


# ---------------------------------------------------------------------- rotations
@dataclass(frozen=True)
class PermanentRotation:
    """A permanent rotation of the free body, ``G = sense * G0 * e_axis`` (mu = 0).

    Attributes
    ----------
    axis : {"x", "y", "z"}
        Principal axis (1, 2, 3 of the paper).
    sense : {+1, -1}
        Sign of the angular momentum along the axis.
    moment : {"A", "B", "C"}
        Its moment of inertia; ``moment_value`` the number.
    inertia_rank : {"major", "middle", "minor"}
        Largest, middle or smallest moment of inertia.
    eigenvalues : tuple of 2 complex
        Of the Euler equations ``dG/dt = G x I^-1 G`` linearised on the sphere
        ``|G| = G0`` (the regular route).
    eigenvalues_closed : tuple of 2 complex
        ``+-G0 sqrt(-(I_k - I_i)(I_k - I_j))``.
    linear_type : str
        ``"centre"`` (major and minor axes) or ``"saddle"`` (middle axis).
    label : int
        Its digit in Fig. 2 (:data:`ROTATION_LABELS`).
    moment_value : float
        The value of that moment of inertia.
    """

    axis: str
    sense: int
    moment: str
    moment_value: float
    inertia_rank: str
    eigenvalues: tuple[complex, complex]
    eigenvalues_closed: tuple[complex, complex]
    linear_type: str
    label: int

    @property
    def name(self) -> str:
        """Short name, e.g. ``"+z"``."""
        return f"{'+' if self.sense > 0 else '-'}{self.axis}"

    @property
    def description(self) -> str:
        return (f"permanent rotation about {self.name} ({self.inertia_rank} axis, "
                f"moment {self.moment} = {self.moment_value:g}): {self.linear_type}")


@checks_body(ranges={"G0": "length"}, closed_form=CLOSED_FORM)
def permanent_rotations(body: RigidBody, G0: float = 1.0) -> tuple[PermanentRotation, ...]:
    """The six permanent rotations of the free body and their linear type.

    The Euler equations (1) at ``mu = 0`` are linearised at ``G = +-G0 e_k`` with the
    Jacobian derived from the Hamiltonian, restricted to the tangent plane of the
    invariant sphere ``|G| = G0`` (the radial direction carries the Casimir ``|G|``).

    Parameters
    ----------
    body : RigidBody
        Three distinct moments; ``mu`` and ``r`` are ignored.
    G0 : float
        Length of the angular momentum.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> [(r.name, r.inertia_rank, r.linear_type) for r in permanent_rotations(
    ...     RigidBody.paper()) if r.sense > 0]
    [('+x', 'major', 'centre'), ('+y', 'minor', 'centre'), ('+z', 'middle', 'saddle')]
    """
    require_distinct_moments(body)
    G0 = _positive("G0", G0, maximum=MAX_ACTION)
    jac = _ep_jacobian()
    I = np.array([body.a, body.b, body.c])
    moments = np.array([body.A, body.B, body.C])
    rank = {int(np.argmax(moments)): "major", int(np.argmin(moments)): "minor"}
    out = []
    for axis, (mname, k) in AXES.items():
        for sense in (+1, -1):
            G = np.zeros(3)
            G[k] = sense * G0
            y = (*G, 0.0, 0.0, 1.0)
            J = np.array(jac(*y, body.a, body.b, body.c, 0.0, 1.0, 0.0, 0.0),
                         dtype=float)[:3, :3]
            basis = np.delete(np.eye(3), k, axis=1)  # tangent plane of |G| = G0
            ev = np.linalg.eigvals(basis.T @ J @ basis)
            i, j = (m for m in range(3) if m != k)
            sq = complex(-(I[k] - I[i]) * (I[k] - I[j]))
            root = G0 * np.sqrt(sq)
            out.append(PermanentRotation(
                axis=axis, sense=sense, moment=mname, moment_value=float(moments[k]),
                inertia_rank=rank.get(k, "middle"), eigenvalues=sorted_eigenvalues(ev),  # type: ignore[arg-type]
                eigenvalues_closed=sorted_eigenvalues(np.array([root, -root])),  # type: ignore[arg-type]
                linear_type=classify(ev, G0 * float(np.max(I))),
                label=ROTATION_LABELS[(axis, sense)]))
    return tuple(out)


# ---------------------------------------------------------------------- EP equilibria
@dataclass(frozen=True)
class EulerPoissonEquilibrium:
    """An equilibrium ``G = 0, gamma = s r`` of the Euler-Poisson equations (1).

    Attributes
    ----------
    name : {"hanging", "upright"}
        ``s = -1`` (centre of mass below the fixed point) or ``s = +1``.
    y : tuple of 6 float
        The state ``(G1, G2, G3, gamma1, gamma2, gamma3)``.
    eigenvalues : tuple of 4 complex
        Of the Jacobian restricted to the symplectic leaf ``|gamma| = 1``,
        ``(G, gamma) = 0`` (the two Casimir directions dropped).
    eigenvalues_closed : tuple of 4 complex
        ``+-sqrt(s mu k)``, ``k`` the eigenvalues of ``I`` on the plane orthogonal to r.
    linear_type : str
        ``"centre-centre"``, ``"saddle-saddle"`` (``"degenerate"`` at ``mu = 0``).
    """

    name: str
    y: tuple[float, ...]
    eigenvalues: tuple[complex, ...]
    eigenvalues_closed: tuple[complex, ...]
    linear_type: str


@dataclass(frozen=True)
class EquilibriumSet:
    """The hanging and the upright equilibria of a body.

    Attributes
    ----------
    body : RigidBody
        The body.
    equilibria : tuple of EulerPoissonEquilibrium
        Its equilibria (hanging and upright), with their eigenvalues and types.
    """

    body: RigidBody
    equilibria: tuple[EulerPoissonEquilibrium, ...]

    def to_dataset(self) -> xr.Dataset:
        """Dims ``equilibrium``, ``component``, ``eig``."""
        from andoyer.charts.euler_poisson import STATE

        eqs = self.equilibria
        ev = np.array([e.eigenvalues for e in eqs], dtype=complex)
        evc = np.array([e.eigenvalues_closed for e in eqs], dtype=complex)
        ds = xr.Dataset(
            {"y": (("equilibrium", "component"), np.array([e.y for e in eqs])),
             "eig_real": (("equilibrium", "eig"), ev.real),
             "eig_imag": (("equilibrium", "eig"), ev.imag),
             "eig_closed_real": (("equilibrium", "eig"), evc.real),
             "eig_closed_imag": (("equilibrium", "eig"), evc.imag),
             "linear_type": (("equilibrium",), np.array([e.linear_type for e in eqs],
                                                        dtype=str))},
            coords={"equilibrium": [e.name for e in eqs], "component": list(STATE),
                    "eig": np.arange(4)},
            attrs=provenance(self.body, engine="numpy.linalg.eigvals",
                             equations="Euler-Poisson equations (1) linearised on the "
                                       "symplectic leaf |gamma| = 1, (G, gamma) = 0"))
        ds["y"].attrs.update(long_name="equilibrium state (G, gamma)", units="1")
        ds["eig_real"].attrs.update(long_name="eigenvalues on the leaf, real part", units="1")
        ds["eig_imag"].attrs.update(long_name="eigenvalues on the leaf, imaginary part",
                                    units="1")
        ds["linear_type"].attrs.update(long_name="linear type on the leaf")
        return ds


@checks_body
def euler_poisson_equilibria(body: RigidBody) -> EquilibriumSet:
    """The equilibria ``G = 0``, ``gamma = -+ r`` of (1) and their leaf eigenvalues.

    Parameters
    ----------
    body : RigidBody
        Any body (``mu = 0`` gives degenerate, zero eigenvalues).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> eqs = euler_poisson_equilibria(RigidBody.paper()).equilibria
    >>> [(e.name, e.linear_type) for e in eqs]
    [('hanging', 'centre-centre'), ('upright', 'saddle-saddle')]
    """
    from scipy.linalg import null_space

    jac = _ep_jacobian()
    r = np.array(body.r)
    I = np.diag([body.a, body.b, body.c])
    trace = float(np.trace(I) - r @ I @ r)
    det = body.b * body.c * r[0]**2 + body.c * body.a * r[1]**2 + body.a * body.b * r[2]**2
    disc = max(trace**2 - 4.0 * det, 0.0)
    ks = ((trace + math.sqrt(disc)) / 2.0, (trace - math.sqrt(disc)) / 2.0)
    out = []
    for name, s in (("hanging", -1.0), ("upright", +1.0)):
        y = np.concatenate([np.zeros(3), s * r])
        J = np.array(jac(*y, *body.params), dtype=float)
        # Tangent space of the leaf: kernel of the Casimir gradients d|gamma|^2, d(G, gamma).
        grads = np.array([np.concatenate([np.zeros(3), 2.0 * y[3:]]),
                          np.concatenate([y[3:], y[:3]])])
        Q = null_space(grads)
        ev = np.linalg.eigvals(Q.T @ J @ Q)
        roots = [np.sqrt(complex(s * body.mu * k)) for k in ks]
        closed = np.array([v for rt in roots for v in (rt, -rt)])
        scale = math.sqrt(body.mu * max(body.a, body.b, body.c)) if body.mu > 0 else 1.0
        out.append(EulerPoissonEquilibrium(
            name=name, y=tuple(float(v) for v in y), eigenvalues=sorted_eigenvalues(ev),
            eigenvalues_closed=sorted_eigenvalues(closed),
            linear_type=classify(ev, scale) if body.mu > 0 else "degenerate"))
    return EquilibriumSet(body=body, equilibria=tuple(out))
