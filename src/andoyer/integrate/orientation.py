"""The body in space: orbits of (1) with the attitude, as self-describing datasets.

:func:`attitude` integrates the Euler-Poisson state with the unit quaternion of the
rotation body -> space on any engine with :attr:`Capability.ATTITUDE
<andoyer.integrate.engines.base.Capability.ATTITUDE>` (``dq/dt = q (x) (0, I^-1 G) / 2``,
the regular route: no singular set) and returns the quaternion, the rotation matrix,
the angular momentum in space and the Euler angles as variables of the dataset
:func:`andoyer.integrate.propagate` returns. Conventions (stated in the dataset's
attributes too): quaternion scalar first; ``R`` active, body -> space
(``x_space = R x_body``); space frame ``(X, Y, Z)`` inertial with ``Z`` the upward
vertical, body frame ``(x, y, z)`` the principal axes; Euler angles ``z-x-z``,
``R = Rz(psi) Rx(theta) Rz(phi)`` (:mod:`andoyer.charts.rotation`).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike

from andoyer.body import RigidBody, checks_body
from andoyer.charts.rotation import (
    BODY_AXES,
    EULER_SINGULAR_RTOL,
    QUATERNION,
    SPACE_AXES,
    euler_angles,
    quaternion_from_vertical,
    rotation_matrix,
)
from andoyer.integrate import budget
from andoyer.integrate.api import orbit_dataset, orbit_docstring, orbit_inputs
from andoyer.integrate.engines import EngineLike, resolve_engine
from andoyer.integrate.engines.base import Capability
from andoyer.integrate.results import describe_variables, provenance
from andoyer.progress import Progress
from andoyer.validation import finite_array

__all__ = ["attitude", "attitude_variables", "CONVENTIONS", "ATTITUDE_BYTES"]

#: The conventions, as dataset attributes.
CONVENTIONS = {
    "quaternion_convention": "scalar first (q0, q1, q2, q3), unit length",
    "rotation_convention": "active rotation body -> space: x_space = R x_body; "
                           "R[i, j] = space component i of body axis j",
    "space_frame": "inertial (X, Y, Z), Z the upward vertical: gamma = R^T e_Z",
    "body_frame": "principal axes (x, y, z) of the body, those of G and gamma",
    "euler_convention": "z-x-z: R = Rz(psi) Rx(theta) Rz(phi); psi precession about Z, "
                        "theta nutation (cos theta = gamma3), phi proper rotation about z",
    "euler_singular_rtol": EULER_SINGULAR_RTOL,
}
#: Bytes per (orbit, time) of the attitude variables (4 + 9 + 3 + 4 floats, one flag).
ATTITUDE_BYTES = 21 * 8

_META: dict[str, tuple[str, str, str, str]] = {
    "quaternion": ("q", "attitude quaternion (scalar first, body -> space)", "1", ""),
    "rotation": ("R", "rotation matrix body -> space (x_space = R x_body)", "1", ""),
    "space_momentum": ("R G", "angular momentum in the space frame", "1", ""),
    "precession": ("ψ", "precession angle about the vertical (z-x-z Euler angle)", "rad",
                   ""),
    "nutation": ("θ", "nutation angle: tilt of the body axis z (cos θ = γ3)", "rad", ""),
    "proper_rotation": ("φ", "proper rotation about the body axis z (z-x-z Euler angle)",
                        "rad", ""),
    "euler_singular": ("", "sin θ <= euler_singular_rtol: ψ and φ undefined (NaN)", "1",
                       ""),
    "quaternion_drift": ("", "|q| - 1 (an integral of the attitude flow)", "1", ""),
}


def attitude_variables(q: ArrayLike, G: ArrayLike, dims: tuple[str, ...]
                       ) -> dict[str, tuple[tuple[str, ...], Any]]:
    """The attitude variables of quaternions ``q`` (..., 4) with momenta ``G`` (..., 3).

    Returns ``name -> (dims, values)`` for a dataset with leading dimensions ``dims``:
    ``quaternion``, ``rotation``, ``space_momentum`` (``R G``), the Euler angles
    ``precession``, ``nutation``, ``proper_rotation`` (NaN where ``euler_singular``) and
    ``quaternion_drift``.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Unit quaternions (scalar first) of the attitude, body to space.
    G : array_like, shape (..., 3)
        Body-frame angular momenta.
    dims : tuple of str
        Names of the leading dimensions of ``q`` and ``G`` (e.g. ``("orbit", "time")``).

    Examples
    --------
    >>> v = attitude_variables([[1.0, 0.0, 0.0, 0.0]], [[0.0, 0.0, 1.0]], ("time",))
    >>> bool(v["euler_singular"][1][0]), v["space_momentum"][1][0].tolist()
    (True, [0.0, 0.0, 1.0])
    """
    Q = finite_array("q", q)
    Gm = finite_array("G", G)
    if Q.ndim == 0 or Q.shape[-1] != 4:
        raise ValueError(f"q must have shape (..., 4), got {Q.shape}")
    if Gm.shape != (*Q.shape[:-1], 3):
        raise ValueError(f"G must have shape {(*Q.shape[:-1], 3)} (one momentum per "
                         f"quaternion of q), got {Gm.shape}")
    if (not isinstance(dims, tuple | list) or len(dims) != Q.ndim - 1
            or not all(isinstance(d, str) for d in dims)):
        raise ValueError(f"dims must name the {Q.ndim - 1} leading dimension(s) of q, "
                         f"got {dims!r}")
    dims = tuple(dims)
    if Gm.size:
        budget.check_momentum(float(np.max(np.abs(Gm))), "G")
    R = rotation_matrix(Q)
    e = euler_angles(Q)
    return {
        "quaternion": ((*dims, "component"), Q),
        "rotation": ((*dims, "space", "body"), R),
        "space_momentum": ((*dims, "space"), np.einsum("...ij,...j->...i", R, Gm)),
        "precession": (dims, e.psi),
        "nutation": (dims, e.theta),
        "proper_rotation": (dims, e.phi),
        "euler_singular": (dims, e.singular),
        "quaternion_drift": (dims, np.linalg.norm(Q, axis=-1) - 1.0),
    }


@checks_body(ranges={"rtol": "tolerance", "atol": "tolerance"})
@orbit_docstring
def attitude(body: RigidBody, y0: ArrayLike, t: ArrayLike, *, precession0: ArrayLike = 0.0,
             engine: EngineLike = None, rtol: float = 1e-12, atol: float = 1e-12,
             chart: str = "euler_poisson", progress: bool | None = None) -> xr.Dataset:
    """Orbits of (1) with the orientation of the body in space.

    The state ``(G, gamma)`` fixes the attitude up to a rotation about the vertical;
    the initial one is ``R(0) = Rz(precession0) Rx(theta0) Rz(phi0)`` with ``theta0, phi0`` of
    ``gamma(0)`` (:func:`andoyer.charts.rotation.quaternion_from_vertical`). The
    quaternion is integrated with the state, ``dq/dt = q (x) (0, omega) / 2``,
    ``omega = I^-1 G`` (:mod:`andoyer.symbolic.attitude`), regular everywhere; the Euler
    angles are read off it, with the precession rate
    ``dpsi/dt = (omega1 gamma1 + omega2 gamma2) / (gamma1^2 + gamma2^2)`` implied
    (:mod:`andoyer.charts.rotation`: ``psi = m + psi(Rx(I) Rz(g) Rx(J) Rz(l))``, ``m``
    the Andoyer-Deprit node).

    Parameters
    ----------
    body : RigidBody
    {y0}
    {t}
    precession0 : float or array_like, shape (n,)
        Initial precession angle(s) (rad): the orientation about the vertical.
    engine : str or Engine, optional
        An engine with the attitude capability (default heyoka where installed, else
        the first of taylor, numba that has it).
    {tolerances}
    {chart}
    {progress}

    Returns
    -------
    xarray.Dataset
        Everything :func:`andoyer.integrate.propagate` returns (dims ``(orbit, time)``),
        and ``quaternion`` (dim ``component`` = q0..q3), ``rotation`` (``space`` = X, Y, Z
        by ``body`` = x, y, z), ``space_momentum`` (``R G``, constant but for its
        vertical-free part: gravity's torque is horizontal), ``precession`` ψ,
        ``nutation`` θ, ``proper_rotation`` φ (rad, in (-π, π], [0, π], (-π, π]; ψ and
        φ NaN where ``euler_singular``: ``sin θ <= euler_singular_rtol``) and
        ``quaternion_drift``; the conventions as attributes.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = attitude(RigidBody.paper(), [0.3, 1.0, 0.2, 1.0, 0.0], [0.0, 1.0, 2.0],
    ...               chart="andoyer", engine="scipy")
    >>> ds.quaternion.sizes["component"], ds.attrs["quaternion_convention"][:12]
    (4, 'scalar first')
    >>> gamma = ds.rotation.isel(orbit=0).sel(space="Z").values  # the last row of R
    >>> bool(np.allclose(gamma, ds[["gamma1", "gamma2", "gamma3"]].isel(orbit=0)
    ...                  .to_array().T.values, atol=1e-10))
    True
    """
    y, times, tolerance = orbit_inputs(body, y0, t, rtol, atol, chart)
    n = y.shape[0]
    psi = finite_array("precession0", precession0)
    if psi.ndim > 1 or (psi.ndim == 1 and psi.shape[0] not in (1, n)):
        raise ValueError(f"precession0 must be one angle or one per orbit ({n}), got shape "
                         f"{psi.shape}")
    psi = np.broadcast_to(psi, (n,))
    budget.check("attitude", steps=1.3 * budget.estimate_steps(body, y, times[-1] - times[0],
                                                               tolerance.rtol),
                 memory=(budget.DATASET_BYTES + ATTITUDE_BYTES) * n * times.size)
    eng = resolve_engine(engine, Capability.ATTITUDE)
    q0 = quaternion_from_vertical(y[:, 3:], psi)
    bar = Progress(n, f"attitude ({eng.name})", progress)
    Y, Q = eng.attitude(y, q0, times, body.engine_params, tolerance)
    bar.update(n)
    bar.close()
    ds = orbit_dataset(
        body, Y, times,
        provenance(body, engine=eng.name, rtol=tolerance.rtol, atol=tolerance.atol,
                   initial_chart=chart,
                   equations="Euler-Poisson equations (1) with the attitude quaternion "
                             "dq/dt = q (x) (0, I^-1 G)/2", **CONVENTIONS),
        attitude_variables(Q, Y[..., :3], ("orbit", "time")),
        {"component": list(QUATERNION), "space": list(SPACE_AXES), "body": list(BODY_AXES)})
    ds["precession0"] = ("orbit", np.array(psi, dtype=float))
    describe_variables(ds, {**_META, "precession0": ("ψ0", "initial precession angle", "rad",
                                                     "")})
    return ds
