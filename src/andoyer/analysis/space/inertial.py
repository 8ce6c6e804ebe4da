r"""The body in inertial space: axis traces, precession and nutation, the herpolhode, and
the heteroclinic cycle of the Hess case.

All of it reads the datasets of :func:`andoyer.integrate.attitude` (conventions of
:mod:`andoyer.charts.rotation`: ``R`` body -> space, ``Z`` the upward vertical, Euler
angles ``z-x-z``).

* :func:`axis_trace`: where a body axis points, ``R a / |a|`` on the unit sphere (the
  loops, cusps and waves of the heavy top's apex), with its colatitude from ``Z`` and
  its azimuth about ``Z``. For the symmetry axis ``z`` the colatitude is the nutation
  ``theta`` and the azimuth is ``psi - pi/2``. Where the axis is undefined (``G = 0``
  for ``momentum``, ``omega = 0`` for ``angular_velocity``) the trace is NaN and flagged
  (``undefined``), and where it is vertical its azimuth is NaN and flagged (``at_pole``),
  as :func:`andoyer.charts.rotation.euler_angles` flags ``psi``.
* :func:`precession_nutation`: per orbit, the nutation bounds (sampled) and the mean
  precession rate ``(psi(t_end) - psi(t_0)) / (t_end - t_0)`` of the unwrapped
  precession. An orbit through the pole (``sin theta`` below the flag of
  :func:`andoyer.charts.rotation.euler_angles`) has NaN rate and says so in its flags.
  Aliasing is detected from the rates the states give at every sample,
  ``dpsi/dt = (omega1 gamma1 + omega2 gamma2)/(gamma1^2 + gamma2^2)`` and
  ``dtheta/dt = -(gamma1 omega2 - gamma2 omega1)/sin theta``. The precession is
  resolved where every sampled step of ``psi`` (wrapped to ``(-pi, pi]``) stays below
  ``pi/2`` and within ``pi/2`` of the trapezoidal integral of its rate (sampled every
  1.01 precession periods, the steps look small but the rate says a turn each); the
  nutation where every step of ``theta`` follows the integral of its rate to
  :data:`ALIASING_RTOL` of the orbit's ``max |dtheta/dt| dt`` (about ten samples a
  nutation period). An aliased precession has NaN rate (``undersampled``); aliased
  nutation bounds are kept as sampled and flagged (``nutation_undersampled``).
* :func:`herpolhode`: the free top (``mu = 0``): the angular velocity in space,
  ``R I^-1 G``, whose tip moves on the invariable plane ``(omega, L) = 2T`` with ``L = R G``
  fixed (Poinsot); its coordinates in that plane and its distance ``2T/|L|``.
* :func:`heteroclinic_cycle`: the Hess case at ``M = 0`` (and bodies turned off the Hess
  direction, from the separatrices of their nearest Hess body). On the Hess relation (3)
  (``theta1 = 0``) every rotation of ``theta2`` is heteroclinic: ``L/G`` goes from
  ``+1`` to ``-1`` (:mod:`andoyer.analysis.hess.solution`), from the pendulum-like
  rotation ``P+`` about ``+z`` to ``P-`` about ``-z``; the other unperturbed separatrix
  ``theta1 = 4 phi0`` takes ``P-`` back to ``P+`` and splits for ``mu > 0``: its orbit
  here is the asymptotic motion near the split separatrices. Both are integrated with
  the attitude from their middle (``L = 0``), backward and forward.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr

from andoyer.analysis.unperturbed.separatrix import BRANCHES, heteroclinic, heteroclinic_rate
from andoyer.body import RigidBody, checks_body
from andoyer.charts.rotation import (
    BODY_AXES,
    EULER_SINGULAR_RTOL,
    QUATERNION,
    SPACE_AXES,
    quaternion_from_vertical,
)
from andoyer.integrate import budget
from andoyer.integrate.api import check_tolerances
from andoyer.integrate.engines import EngineLike, resolve_engine
from andoyer.integrate.engines.base import Capability, Tolerance
from andoyer.integrate.orientation import CONVENTIONS, attitude_variables
from andoyer.integrate.results import (
    VariableMeta,
    describe_variables,
    provenance,
    states_dataset,
)
from andoyer.validation import MAX_ACTION, integer
from andoyer.validation import positive as _positive

__all__ = ["AXES", "ALIASING_RTOL", "axis_trace", "precession_nutation", "herpolhode",
           "heteroclinic_cycle"]

#: Named body axes of :func:`axis_trace` (``centre_of_mass`` is ``r``, ``momentum`` is
#: ``G/|G|``, ``angular_velocity`` is ``I^-1 G / |I^-1 G|``; the last two move in the body).
AXES = ("x", "y", "z", "centre_of_mass", "momentum", "angular_velocity")

#: A sample step resolves the nutation where its sampled change agrees with the
#: trapezoidal integral of its rate to this fraction of ``max |dtheta/dt| dt`` (a
#: sinusoid's trapezoidal error is ``x^2/12`` of it at a phase step ``x``: about ten
#: samples a period pass, four do not).
ALIASING_RTOL = 0.1
#: Changes of an angle below this (rad) are round-off, whatever the rate says.
_ANGLE_FLOOR = 1e-10

_STATE = ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")
_REQUIRED = ("rotation", "precession", "nutation", "euler_singular")


def _check_attitude(ds: Any, name: str = "ds") -> xr.Dataset:
    if not isinstance(ds, xr.Dataset):
        raise TypeError(f"{name} must be an attitude dataset (andoyer.integrate.attitude), "
                        f"got {type(ds).__name__}")
    missing = [v for v in (*_REQUIRED, *_STATE) if v not in ds]
    if missing:
        raise ValueError(f"{name} is not an attitude dataset (andoyer.integrate.attitude): "
                         f"it lacks {', '.join(missing)}")
    if "time" not in ds.dims or ds.sizes["time"] < 2:
        raise ValueError(f"{name} must hold at least 2 times")
    return ds


def _body_of(ds: xr.Dataset) -> RigidBody:
    try:
        A, B, C, mu = (float(ds.attrs[f"body_{k}"]) for k in ("A", "B", "C", "mu"))
        e1, e2, e3 = (float(ds.attrs[f"body_e{i}"]) for i in (1, 2, 3))
    except KeyError as exc:
        raise ValueError(f"ds does not record its body (attribute {exc.args[0]!r}); pass a "
                         "dataset of andoyer.integrate.attitude") from None
    return RigidBody(A, B, C, mu, (e1, e2, e3))


def _states(ds: xr.Dataset) -> np.ndarray:
    return np.stack([ds[v].values for v in _STATE], axis=-1)


_TRACE_META: dict[str, VariableMeta] = {
    "trace": ("R a", "the body axis a in space (unit vector) (NaN: where undefined)", "1",
              ""),
    "colatitude": ("ϑ_a", "angle of the axis from the vertical Z (NaN: where undefined)",
                   "rad", ""),
    "azimuth": ("λ_a", "azimuth of the axis about Z, from X towards Y (NaN: where "
                "undefined or at the pole)", "rad", ""),
    "undefined": ("", "the axis is undefined: a zero vector (G = 0 for momentum, ω = 0 "
                  "for angular_velocity)", "1", ""),
    "at_pole": ("", "the axis is vertical (sin of its colatitude <= "
                "euler_singular_rtol): its azimuth is undefined", "1", ""),
}


def axis_trace(ds: xr.Dataset, axis: str = "z") -> xr.Dataset:
    """The trace of a body axis on the unit sphere of the space frame.

    Parameters
    ----------
    ds : xarray.Dataset
        An attitude dataset (:func:`andoyer.integrate.attitude`).
    axis : {"x", "y", "z", "centre_of_mass", "momentum", "angular_velocity"}
        The body axis: a principal axis, the direction ``r`` of the centre of mass, or
        the (moving) directions of ``G`` and of ``omega = I^-1 G``.

    Returns
    -------
    xarray.Dataset
        ``trace`` (dims of ``ds`` and ``space`` = X, Y, Z), ``colatitude`` (from ``Z``)
        and ``azimuth`` (about ``Z``, in (-pi, pi]); the flags ``undefined`` (the axis
        is a zero vector there: ``G = 0`` or ``omega = 0``; everything NaN) and
        ``at_pole`` (the axis vertical: the azimuth NaN); attr ``axis``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.integrate import attitude
    >>> ds = attitude(RigidBody.paper(), [0.3, 1.0, 0.2, 1.0, 0.0], [0.0, 1.0],
    ...               chart="andoyer", engine="scipy")
    >>> tr = axis_trace(ds, "z")
    >>> bool(np.allclose(tr.colatitude, ds.nutation))
    True
    """
    ds = _check_attitude(ds)
    if not isinstance(axis, str) or axis not in AXES:
        raise ValueError(f"axis must be one of {', '.join(AXES)}, got {axis!r}")
    R = ds.rotation.values
    Y = _states(ds)
    if axis in BODY_AXES:
        a = np.broadcast_to(np.eye(3)[BODY_AXES.index(axis)], Y[..., :3].shape)
    elif axis == "centre_of_mass":
        body = _body_of(ds)
        a = np.broadcast_to(np.array([body.e1, body.e2, body.e3]), Y[..., :3].shape)
    elif axis == "momentum":
        a = Y[..., :3]
    else:
        body = _body_of(ds)
        a = Y[..., :3] * np.array([body.a, body.b, body.c])
    norm = np.linalg.norm(a, axis=-1, keepdims=True)
    # A zero vector has no direction (G = 0, omega = 0): NaN, flagged.
    undefined = norm[..., 0] <= EULER_SINGULAR_RTOL * float(np.max(norm, initial=0.0))
    safe = np.where(undefined[..., None], 1.0, norm)
    u = np.einsum("...ij,...j->...i", R, a / safe)
    u[undefined] = np.nan
    horizontal = np.hypot(u[..., 0], u[..., 1])
    at_pole = ~undefined & (horizontal <= EULER_SINGULAR_RTOL)
    dims = ds.precession.dims
    out = xr.Dataset(
        {"trace": ((*dims, "space"), u),
         "colatitude": (dims, np.arctan2(horizontal, u[..., 2])),
         "azimuth": (dims, np.where(at_pole, np.nan, np.arctan2(u[..., 1], u[..., 0]))),
         "undefined": (dims, undefined), "at_pole": (dims, at_pole)},
        coords={d: ds[d].values for d in dims if d in ds.coords} | {"space": list(SPACE_AXES)},
        attrs={**{k: v for k, v in ds.attrs.items() if k != "created"}, "axis": axis})
    return describe_variables(out, _TRACE_META)


_PN_META: dict[str, VariableMeta] = {
    "nutation_min": ("θ_min", "least sampled nutation angle", "rad", ""),
    "nutation_max": ("θ_max", "largest sampled nutation angle", "rad", ""),
    "nutation_mean": ("<θ>", "time average of the nutation (trapezoidal)", "rad", ""),
    "precession_rate": ("<dψ/dt>", "mean precession rate (ψ(t_end) - ψ(t0)) / (t_end - t0) "
                        "(NaN: through the pole or aliased)", "rad/body time unit", ""),
    "precession_turns": ("Δψ/2π", "turns of the precession over the orbit (NaN: through "
                         "the pole or aliased)", "1", ""),
    "passes_pole": ("", "the orbit comes within the flag of θ = 0 or π (ψ undefined)",
                    "1", ""),
    "undersampled": ("", "the precession is aliased: a sample step of ψ disagrees with its "
                     "rate, or its change exceeds π/2 (too sparse to unwrap)", "1", ""),
    "nutation_undersampled": ("", "the nutation is aliased: a sample step of θ disagrees "
                              "with its rate (the sampled bounds miss the extremes)", "1",
                              ""),
}


def _euler_rates(body: RigidBody, Y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(dpsi/dt, dtheta/dt)`` at every state (module notes; NaN at the poles)."""
    w = Y[..., :3] * np.array([body.a, body.b, body.c])
    g1, g2 = Y[..., 3], Y[..., 4]
    s2 = g1 * g1 + g2 * g2
    pole = np.sqrt(s2) <= EULER_SINGULAR_RTOL
    safe = np.where(pole, 1.0, s2)
    psi_rate = np.where(pole, np.nan, (w[..., 0] * g1 + w[..., 1] * g2) / safe)
    theta_rate = np.where(pole, np.nan, -(g1 * w[..., 1] - g2 * w[..., 0]) / np.sqrt(safe))
    return psi_rate, theta_rate


def _mismatch(change: np.ndarray, rate: np.ndarray, dt: np.ndarray) -> np.ndarray:
    """``|change - trapezoidal integral of rate|`` per sample step (NaN where a pole makes
    the rate undefined: ``passes_pole`` says so)."""
    return np.abs(change - 0.5 * dt * (rate[:, 1:] + rate[:, :-1]))


def precession_nutation(ds: xr.Dataset) -> xr.Dataset:
    """Nutation bounds and mean precession rate of each orbit of an attitude dataset.

    Parameters
    ----------
    ds : xarray.Dataset
        An attitude dataset (:func:`andoyer.integrate.attitude`), dims ``(orbit, time)``.

    Returns
    -------
    xarray.Dataset
        Per orbit: ``nutation_min``, ``nutation_max``, ``nutation_mean`` (rad),
        ``precession_rate`` (the mean over the whole time span; over whole nutation
        periods it is the secular rate), ``precession_turns``, and the flags
        ``passes_pole``, ``undersampled`` (the precession aliased by the sampling: the
        rate is NaN where either is set) and ``nutation_undersampled`` (the nutation
        aliased: the sampled bounds are flagged, not exact); see the module notes.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.integrate import attitude
    >>> body = RigidBody.lagrange(1.0, 0.6, 1.0)
    >>> ds = attitude(body, [0.2, 0.1, 1.5, 0.0, 0.6, 0.8], np.linspace(0, 20, 801),
    ...               engine="scipy")
    >>> pn = precession_nutation(ds)
    >>> bool(pn.nutation_min[0] < pn.nutation_max[0]), bool(pn.passes_pole[0])
    (True, False)
    """
    ds = _check_attitude(ds)
    if ds.precession.dims != ("orbit", "time"):
        raise ValueError(f"ds must have dims (orbit, time), got {ds.precession.dims}")
    t = ds.time.values.astype(float)
    theta = ds.nutation.values
    psi = ds.precession.values
    pole = ds.euler_singular.values.any(axis=1)
    steps = np.angle(np.exp(1j * np.diff(np.nan_to_num(psi), axis=1)))
    psi_rate, theta_rate = _euler_rates(_body_of(ds), _states(ds))
    dt = np.diff(t)
    with np.errstate(invalid="ignore"):
        # psi: the rate must pick the sampled branch (within pi/2 of its integral).
        sparse = np.any((_mismatch(steps, psi_rate, dt) > 0.5 * math.pi)
                        | (np.abs(steps) > 0.5 * math.pi), axis=1)
        # theta: each step must follow the rate to ALIASING_RTOL of the orbit's reach.
        reach = dt * np.nanmax(np.abs(theta_rate), axis=1, initial=0.0)[:, None]
        nutation_sparse = np.any(_mismatch(np.diff(theta, axis=1), theta_rate, dt)
                                 > ALIASING_RTOL * reach + _ANGLE_FLOOR, axis=1)
    advance = np.sum(steps, axis=1)
    bad = pole | sparse
    span = t[-1] - t[0]
    rate = np.where(bad, np.nan, advance / span)
    mean = np.trapezoid(theta, t, axis=1) / span
    out = xr.Dataset(
        {"nutation_min": ("orbit", theta.min(axis=1)),
         "nutation_max": ("orbit", theta.max(axis=1)),
         "nutation_mean": ("orbit", mean),
         "precession_rate": ("orbit", rate),
         "precession_turns": ("orbit", np.where(bad, np.nan, advance / (2 * math.pi))),
         "passes_pole": ("orbit", pole), "undersampled": ("orbit", sparse),
         "nutation_undersampled": ("orbit", nutation_sparse)},
        coords={"orbit": ds.orbit.values},
        attrs={**{k: v for k, v in ds.attrs.items() if k != "created"},
               "duration": float(span)})
    return describe_variables(out, _PN_META)


_HERPOLHODE_META: dict[str, VariableMeta] = {
    "omega_space": ("R ω", "angular velocity in the space frame", "1/body time unit", ""),
    "polhode": ("ω", "angular velocity in the body frame (the polhode)",
                "1/body time unit", ""),
    "herpolhode": ("", "tip of R ω in the invariable plane (u, v)", "1/body time unit", ""),
    "plane_distance": ("2T/|L|", "distance of the tip of R ω from the fixed point along "
                       "L: constant (the invariable plane)", "1/body time unit", ""),
    "momentum_space": ("L = R G", "angular momentum in space (fixed), time average", "1",
                       ""),
}


def herpolhode(ds: xr.Dataset) -> xr.Dataset:
    """The polhode and herpolhode of the free top (Poinsot's construction).

    Parameters
    ----------
    ds : xarray.Dataset
        An attitude dataset of a body with ``mu = 0`` (:func:`andoyer.integrate.attitude`).

    Returns
    -------
    xarray.Dataset
        ``omega_space`` (``R I^-1 G``), ``polhode`` (``I^-1 G``, body frame), ``herpolhode``
        (dim ``plane`` = u, v: the tip of ``R omega`` in the invariable plane, ``u``
        along ``Z x L`` or ``X`` where ``L`` is vertical, ``v = L x u / |L|``),
        ``plane_distance`` (``(R omega, L)/|L| = 2T/|L|``, constant) and
        ``momentum_space`` (``L = R G``, per orbit). An orbit with ``G = 0`` (at rest:
        no invariable plane) is refused, naming ``ds``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.integrate import attitude
    >>> free = RigidBody.euler_poinsot(2.5, 2.0, 2.2)
    >>> ds = attitude(free, [0.3, 0.8, 0.5, 0.0, 0.6, 0.8], np.linspace(0, 10, 11),
    ...               engine="scipy")
    >>> hp = herpolhode(ds)
    >>> bool(np.ptp(hp.plane_distance.values) < 1e-12)
    True
    """
    ds = _check_attitude(ds)
    body = _body_of(ds)
    if body.mu != 0.0:
        raise ValueError(f"herpolhode is the free top's (mu = 0); ds holds mu = {body.mu}")
    Y = _states(ds)
    R = ds.rotation.values
    omega = Y[..., :3] * np.array([body.a, body.b, body.c])
    w = np.einsum("...ij,...j->...i", R, omega)
    L_t = np.einsum("...ij,...j->...i", R, Y[..., :3])
    L = L_t.mean(axis=-2, keepdims=True)
    Ln = np.linalg.norm(L, axis=-1, keepdims=True)
    G_size = np.linalg.norm(Y[..., :3], axis=-1).max(axis=-1)
    still = np.flatnonzero((Ln.reshape(-1) <= EULER_SINGULAR_RTOL * G_size.reshape(-1))
                           | (G_size.reshape(-1) == 0.0))
    if still.size:
        raise ValueError(f"ds: G = 0 on {still.size} orbit(s) (first {int(still[0])}): a "
                         "free top at rest has no invariable plane and no herpolhode")
    n = L / Ln
    u = np.cross([0.0, 0.0, 1.0], n)
    un = np.linalg.norm(u, axis=-1, keepdims=True)
    u = np.where(un > 1e-12, u / np.where(un > 0, un, 1.0), [1.0, 0.0, 0.0])
    v = np.cross(n, u)
    dims = ds.precession.dims
    plane = np.stack([np.sum(w * u, axis=-1), np.sum(w * v, axis=-1)], axis=-1)
    out = xr.Dataset(
        {"omega_space": ((*dims, "space"), w), "polhode": ((*dims, "body"), omega),
         "herpolhode": ((*dims, "plane"), plane),
         "plane_distance": (dims, np.sum(w * n, axis=-1)),
         "momentum_space": ((*dims[:-1], "space"), L[..., 0, :])},
        coords={d: ds[d].values for d in dims if d in ds.coords}
        | {"space": list(SPACE_AXES), "body": list(BODY_AXES), "plane": ["u", "v"]},
        attrs={k: v for k, v in ds.attrs.items() if k != "created"})
    return describe_variables(out, _HERPOLHODE_META)


@checks_body(ranges={"J2": "action", "n_times": "count", "rtol": "tolerance", "atol": "tolerance"})
def heteroclinic_cycle(body: RigidBody, J2: float = 1.0, *, t_half: float | None = None,
                       n_times: int = 2001, engine: EngineLike = None, rtol: float = 1e-12,
                       atol: float = 1e-12) -> xr.Dataset:
    """The heteroclinic cycle ``P+ -> P- -> P+`` of a Hess body at ``M = 0``, in space.

    Parameters
    ----------
    body : RigidBody
        A Hess body (``mu >= 0``), or a body turned off the Hess direction
        (:meth:`~andoyer.body.RigidBody.near_hess`): its orbits start on the separatrices
        of its nearest Hess body (:meth:`~andoyer.body.RigidBody.nearest_hess`: the free
        top's, shared by every centre of mass in the (e1, e2) plane) and are integrated
        with the body itself -- the asymptotic motions near its split separatrices.
    J2 : float
        ``G``, the length of the angular momentum at the middle of each branch.
    t_half : float, optional
        Each branch is integrated over ``[-t_half, t_half]`` about its middle
        (``L = 0``); default ``12 / lambda`` with ``lambda`` the unperturbed rate
        (:func:`andoyer.analysis.unperturbed.separatrix.heteroclinic_rate`): ``L/G``
        reaches ``+-1`` to about ``1e-5``.
    n_times : int
        Output times per branch (>= 3).
    engine : str or Engine, optional
        An engine with the attitude capability.
    rtol, atol : float
        Tolerances.

    Returns
    -------
    xarray.Dataset
        Dims ``(branch, time)`` (``branch`` = ``theta1=0``, ``theta1=4phi0``; ``time``
        from ``-t_half``): the attitude variables of :func:`andoyer.integrate.attitude`
        (both branches start with the precession ``psi = 0`` at ``t = 0``),
        ``L_over_G`` (``+1`` at ``P+``, ``-1`` at ``P-``) and the Euler-Poisson state.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> cyc = heteroclinic_cycle(RigidBody.paper(mu=0.0), n_times=5, engine="scipy")
    >>> [round(float(v), 3) for v in cyc.L_over_G.isel(time=[0, -1]).values.ravel()]
    [1.0, -1.0, -1.0, 1.0]
    """
    hess = body.nearest_hess()  # ValueError unless r is in the (e1, e2) plane, A > C > B
    G = _positive("J2", J2, maximum=MAX_ACTION)
    n = integer("n_times", n_times, 3)
    rtol, atol = check_tolerances(rtol, atol)
    lam = heteroclinic_rate(hess, G)
    T = 12.0 / lam if t_half is None else _positive("t_half", t_half)
    y0 = np.stack([heteroclinic(hess, G, [0.0], branch)["y"].values[0]
                   for branch in BRANCHES])
    budget.check("heteroclinic_cycle",
                 steps=1.3 * budget.estimate_steps(body, np.repeat(y0, 2, axis=0), T, rtol),
                 memory=(budget.DATASET_BYTES + 21 * 8) * len(BRANCHES) * n)
    eng = resolve_engine(engine, Capability.ATTITUDE)
    q0 = quaternion_from_vertical(y0[:, 3:], 0.0)
    half = (n + 1) // 2
    forward = np.linspace(0.0, T, half)
    tol = Tolerance(rtol, atol)
    yf, qf = eng.attitude(y0, q0, forward, body.engine_params, tol)
    yb, qb = eng.attitude(y0, q0, -forward, body.engine_params, tol)
    times = np.concatenate([-forward[::-1], forward[1:]])
    Y = np.concatenate([yb[:, ::-1], yf[:, 1:]], axis=1)
    Q = np.concatenate([qb[:, ::-1], qf[:, 1:]], axis=1)
    if times.size != n:  # an even n_times: drop the last point
        times, Y, Q = times[:n], Y[:, :n], Q[:, :n]
    dims = ("branch", "time")
    extra = attitude_variables(Q, Y[..., :3], dims)
    Gn = np.linalg.norm(Y[..., :3], axis=-1)
    extra["L_over_G"] = (dims, Y[..., 2] / Gn)
    ds = states_dataset(
        body, Y, dims, {"branch": list(BRANCHES), "time": times,
                        "component": list(QUATERNION), "space": list(SPACE_AXES),
                        "body": list(BODY_AXES)},
        provenance(body, engine=eng.name, rtol=rtol, atol=atol, J2=G, t_half=T,
                   lambda_rate=lam, hess_epsilon=body.hess_epsilon,
                   equations="Euler-Poisson equations (1) with the attitude quaternion, "
                             "from the middle (L = 0) of the unperturbed separatrices",
                   **CONVENTIONS),
        extra)
    ds.variables["time"].attrs.update(units="body time units",
                                      long_name="time from the middle of the branch")
    return describe_variables(ds, {
        "L_over_G": ("L/G", "cosine of the angle of G from the body axis z: +1 at P+, "
                     "-1 at P-", "1", "")})
