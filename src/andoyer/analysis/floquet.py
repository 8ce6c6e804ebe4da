"""Stability of the physical pendulum in the full system: the monodromy matrix over one
period (variational equations -- heyoka's Taylor integrator where installed, else the
Numba DOP853 -- or finite differences of the flow map as an independent check) and its
Floquet multipliers; see the 'Stability' notes of :mod:`andoyer.analysis.pendulum`.
"""

from __future__ import annotations

import math
import threading
from functools import cache
from typing import Any, NamedTuple

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.analysis.pendulum import (
    MOTIONS,
    STABILITY,
    TRANSVERSE,
    pendulum_motion,
    pendulum_period,
    pendulum_state,
    require_pendulum_body,
)
from andoyer.body import RigidBody, checks_body
from andoyer.charts.euler_poisson import STATE, as_state
from andoyer.integrate.engines import default_engine_name, resolve_engine
from andoyer.integrate.engines.base import Capability, Tolerance
from andoyer.integrate.results import provenance, values_from_attrs
from andoyer.validation import positive as _positive

__all__ = [
    "NUMBA_TOL", "Floquet", "Monodromy", "floquet_multipliers", "floquet_scan",
    "hess_rotation_multiplier", "monodromy", "physical_pendulum_monodromy",
]


_T_IDX = [STATE.index(s) for s in TRANSVERSE]


def _initial_bottom(body: RigidBody, h: float) -> tuple[float, float]:
    """``(vartheta0, L0)``: the bottom ``vartheta = 3 pi/2`` with ``L0 > 0`` at energy ``h``."""
    e = h + body.mu
    if not (math.isfinite(h) and e >= 0.0):
        raise ValueError(f"energy h = {h!r} is below the physical pendulum's minimum "
                         f"-mu = {-body.mu:g} (the body hanging at rest)")
    return 1.5 * math.pi, math.sqrt(2.0 * e / body.c)


# ----------------------------------------------------------------------------- monodromy
class Monodromy(NamedTuple):
    """Monodromy matrix ``Phi[i, j] = d y_i(T) / d y_j(0)`` of the Euler-Poisson flow (1)."""

    matrix: NDArray[np.float64]
    period: float
    y0: NDArray[np.float64]
    y_end: NDArray[np.float64]
    method: str


_VAR_LOCK = threading.Lock()

#: Smallest tolerance the numba variational route is given: DOP853 in double precision
#: cannot resolve less (its controller gets 0.025 tol). Measured against heyoka at
#: tol = 1e-15 on the paper body's pendulum orbits (h/mu = 0.5, 5, 20): the monodromy
#: matrices agree to 8e-13 (entries up to 54), 6e-14, 8e-15.
NUMBA_TOL = 1e-13


@cache
def _variational_integrator_cached(tol: float) -> Any:
    from andoyer.integrate.engines.heyoka_symbolic import heyoka_system
    from andoyer.integrate.engines.lazy import heyoka as hy

    # The one SymPy -> heyoka builder; heyoka derives the variational equations.
    vsys = hy.var_ode_sys(list(heyoka_system()), hy.var_args.vars, order=1)
    # compact_mode: the 42 equations compile in about a second instead of ten.
    return hy.taylor_adaptive(vsys, [0.0] * 6, tol=tol, compact_mode=True)


def _variational_monodromy(body: RigidBody, y0: NDArray[np.float64], T: float,
                           tol: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    from andoyer.integrate.engines.lazy import heyoka as hy

    with _VAR_LOCK:
        ta = _variational_integrator_cached(tol)
        ta.time = 0.0
        ta.state[:6] = y0
        ta.state[ta.get_vslice(order=1)] = np.eye(6).ravel()  # row-major d y_i / d y0_j
        ta.pars[:] = body.params
        outcome = ta.propagate_until(T)[0]
        if outcome != hy.taylor_outcome.time_limit:
            raise FloatingPointError(f"heyoka stopped with outcome {outcome!r}")
        return (np.array(ta.state[ta.get_vslice(order=1)]).reshape(6, 6),
                np.array(ta.state[:6]))


def _numba_monodromy(body: RigidBody, y0: NDArray[np.float64], T: float,
                     tol: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    from andoyer.errors import IntegrationError
    from andoyer.integrate.tangent import propagate_tangent

    res = propagate_tangent(y0, np.eye(6), np.array([0.0, T]), body.engine_params,
                            tol=max(tol, NUMBA_TOL))
    if not res.ok[0]:
        raise IntegrationError("the variational integration failed (non-finite state)")
    return np.ascontiguousarray(res.w[0, -1].T), res.y[0, -1]


def _fd_monodromy(body: RigidBody, y0: NDArray[np.float64], T: float, step: float,
                  engine: str, rtol: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    eng = resolve_engine(engine, Capability.PROPAGATE)
    starts = np.concatenate([y0 + step * np.eye(6), y0 - step * np.eye(6), y0[None]])
    out = eng.propagate(starts, np.array([0.0, T]), body.engine_params,
                        Tolerance.single(rtol))[:, -1, :]
    Phi = (out[:6] - out[6:12]).T / (2.0 * step)  # column j = d y(T) / d y0_j
    return Phi, out[12]


@checks_body
def monodromy(body: RigidBody, y0: ArrayLike, T: float, *, method: str = "variational",
              tol: float = 1e-15, step: float = 1e-6,
              engine: str | None = None) -> Monodromy:
    """Monodromy matrix of the Euler-Poisson flow (1) over ``[0, T]`` from ``y0``.

    Parameters
    ----------
    body : RigidBody
    y0 : array_like, shape (6,)
        Start of the (periodic) orbit.
    T : float
        Its period (> 0).
    method : {"variational", "finite_difference"}
        ``"variational"``: the first-order variational equations: heyoka's
        (``heyoka.var_ode_sys``, Taylor tolerance ``tol``) or, for ``engine="numba"``,
        the Numba DOP853 on the Jacobian generated by SymPy (tolerance
        ``max(tol, NUMBA_TOL)``). ``"finite_difference"``:
        central differences ``(y_T(y0 + step e_j) - y_T(y0 - step e_j)) / (2 step)``
        with the compiled DOP853 of ``engine`` at ``rtol = atol = tol`` (use a loose
        ``tol`` such as 1e-13: the error is about ``step^2 |D^3 y_T| + tol / step``).
    engine : {"heyoka", "numba"}, optional
        For ``"variational"``: default heyoka where installed, else numba. For
        ``"finite_difference"``: the engine of the flow map (default numba).

    Returns
    -------
    Monodromy
        ``matrix[i, j] = d y_i(T) / d y_j(0)``, the period, ``y0`` and ``y(T)``.
    """
    y = as_state(y0, "y0")
    if y.shape != (6,):
        raise ValueError(f"y0 must be one Euler-Poisson state, shape (6,), got {y.shape}")
    T = _positive("T (the period)", T)
    if not math.isfinite(T):
        raise ValueError("T must be finite (a separatrix has no period)")
    tol = _positive("tol", tol)
    if method == "variational":
        name = default_engine_name() if engine is None else engine
        if name == "heyoka":
            Phi, yT = _variational_monodromy(body, y, T, tol)
        elif name == "numba":
            Phi, yT = _numba_monodromy(body, y, T, tol)
        else:
            raise ValueError(f"engine must be 'heyoka' or 'numba' for the variational "
                             f"monodromy, got {engine!r}")
    elif method == "finite_difference":
        Phi, yT = _fd_monodromy(body, y, T, _positive("step", step), engine or "numba",
                                max(tol, 1e-14))
    else:
        raise ValueError(f"method must be 'variational' or 'finite_difference', got {method!r}")
    return Monodromy(Phi, T, y, yT, method)


@checks_body
def physical_pendulum_monodromy(body: RigidBody, h: float, *, method: str = "variational",
                                tol: float = 1e-15, step: float = 1e-6,
                                engine: str | None = None) -> Monodromy:
    """Monodromy of the physical-pendulum orbit of energy ``h`` over one period.

    The orbit starts at the bottom, ``vartheta = 3 pi / 2`` (``gamma = -r``), with
    ``L > 0``; the period is the closed form :func:`pendulum_period`.
    """
    require_pendulum_body(body, "the physical pendulum")
    if pendulum_motion(body.mu, h) in ("separatrix", "equilibrium"):
        raise ValueError(f"h = {h!r}: the separatrix (h = mu) and the equilibrium "
                         "(h = -mu) are not periodic orbits of finite period here")
    th0, L0 = _initial_bottom(body, h)
    y0 = pendulum_state(body, th0, L0)
    return monodromy(body, y0, pendulum_period(body.c, body.mu, h), method=method, tol=tol,
                     step=step, engine=engine)


class Floquet(NamedTuple):
    """Floquet multipliers of a physical-pendulum orbit."""

    trace: float                 #: ``lambda + 1/lambda = tr Phi_perp - 1``
    multipliers: NDArray[np.complex128]  #: ``(lambda, 1/lambda)``, ``|lambda| >= 1``
    stability: str               #: ``"elliptic"``, ``"parabolic"`` or ``"hyperbolic"``
    leaf_matrix: NDArray[np.float64]  #: 2x2 transverse monodromy on the leaf ``dM = 0``
    shear: float                 #: ``|leaf_matrix - lambda I|`` (Jordan block if > 0)
    monodromy: Monodromy


def _leaf_basis(y: NDArray[np.float64]) -> NDArray[np.float64]:
    """Orthonormal basis (3, 2) of transverse variations with ``dM = 0``.

    ``dM = gamma1 dG1 + gamma2 dG2 + G3 dgamma3`` on the pendulum set.
    """
    row = np.array([y[3], y[4], y[2]])
    _, _, vt = np.linalg.svd(row[None, :])
    return np.asarray(vt[1:].T)


@checks_body
def floquet_multipliers(body: RigidBody, h: float, *, method: str = "variational",
                        tol: float = 1e-15, parabolic_tol: float = 1e-6,
                        engine: str | None = None) -> Floquet:
    """Floquet multipliers of the physical-pendulum orbit of energy ``h`` in the full system.

    The six multipliers are ``1, 1, 1`` (in-plane: flow, energy, ``|gamma|^2``), ``1``
    (area integral) and ``lambda, 1/lambda`` with ``lambda + 1/lambda = tr Phi_perp - 1``
    (module notes). ``|trace| < 2 - parabolic_tol``: elliptic; ``> 2 + parabolic_tol``:
    hyperbolic; else parabolic (multipliers 1; with ``shear > 0`` a Jordan block, i.e.
    linearly unstable). ``method``, ``tol`` and ``engine`` as in :func:`monodromy`.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.paper()
    >>> f = floquet_multipliers(body, 5 * body.mu)           # a rotation
    >>> f.stability, bool(np.isclose(f.multipliers[0].real, hess_rotation_multiplier(body)))
    ('hyperbolic', True)
    """
    mono = physical_pendulum_monodromy(body, h, method=method, tol=tol, engine=engine)
    P = mono.matrix[np.ix_(_T_IDX, _T_IDX)]
    s = float(np.trace(P) - 1.0)
    root = np.sqrt(complex(0.25 * s * s - 1.0))
    lam = 0.5 * s + root if s >= 0 else 0.5 * s - root
    pair = np.array([lam, 1.0 / lam], dtype=complex)
    if abs(s) > 2.0 + parabolic_tol:
        stability = "hyperbolic"
    elif abs(s) < 2.0 - parabolic_tol:
        stability = "elliptic"
    else:
        stability = "parabolic"
        pair = np.array([np.sign(s), np.sign(s)], dtype=complex)
    B = _leaf_basis(mono.y0)
    leaf = B.T @ P @ B
    shear = float(np.linalg.norm(leaf - pair[0].real * np.eye(2), 2)) if stability == \
        "parabolic" else 0.0
    return Floquet(s, pair, stability, leaf, shear, mono)


@checks_body
def hess_rotation_multiplier(body: RigidBody) -> float:
    """``exp(2 pi sigma / c)``, ``sigma = sqrt((b - c)(c - a))``: the multiplier of every
    physical-pendulum rotation of a Hess body (and the ``mu -> 0`` limit of any body with
    the middle axis ``Oz``).

    Exact: along the pendulum ``d(G, r)/dt = -branch sigma G3 (G, r)`` and
    ``int G3 dt = 2 pi / c`` over one rotation.
    """
    sigma = body.require_middle_axis("hyperbolic pendulum rotations (in the mu -> 0 limit)")
    return math.exp(2.0 * math.pi * sigma / body.c)


@checks_body
def floquet_scan(body: RigidBody, h: ArrayLike, *, method: str = "variational",
                 tol: float = 1e-15, parabolic_tol: float = 1e-6,
                 engine: str | None = None) -> xr.Dataset:
    """Floquet multipliers of the physical-pendulum orbits over a range of energies.

    Parameters
    ----------
    body : RigidBody
        ``e3 = 0``, ``mu > 0``.
    h : array_like, shape (n,)
        Energies (``> -mu``, ``!= mu``): librations below ``mu``, rotations above.
    method, tol, parabolic_tol, engine
        As in :func:`floquet_multipliers`.

    Returns
    -------
    xarray.Dataset
        Dim ``H`` (the energies). Variables: ``H_over_mu``, ``period``, ``motion`` and
        ``stability`` (codes, CF ``flag_values``/``flag_meanings``), ``floquet_trace``
        (``lambda + 1/lambda``), ``multiplier_re``/``multiplier_im`` (dim ``pair``:
        ``lambda``, ``1/lambda``), ``abs_multiplier`` (``max |lambda|``),
        ``floquet_exponent`` (``log max|lambda| / T``), ``shear``, ``return_error``
        (``max |y(T) - y(0)|``, the check of the closed-form period) and
        ``monodromy`` (``H, row, col``). Attrs: provenance, method, tolerance and, for a
        Hess body, ``hess_rotation_multiplier``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.paper()
    >>> ds = floquet_scan(body, [-0.5 * body.mu, 3 * body.mu])
    >>> [str(s) for s in ds.stability.attrs["flag_meanings"].split()]
    ['elliptic', 'parabolic', 'hyperbolic']
    >>> ds.stability.values.tolist()
    [1, 2]
    """
    require_pendulum_body(body, "the physical pendulum")
    energies = np.atleast_1d(np.asarray(h, dtype=float))
    if energies.ndim != 1 or energies.size == 0:
        raise ValueError(f"h must be a 1-D array of energies, got shape {energies.shape}")
    n = energies.size
    out: dict[str, NDArray[Any]] = {
        k: np.empty(n) for k in ("period", "trace", "abs", "exponent", "shear", "ret")}
    motion = np.empty(n, dtype=np.int8)
    stab = np.empty(n, dtype=np.int8)
    lam = np.empty((n, 2), dtype=complex)
    mats = np.empty((n, 6, 6))
    for i, hi in enumerate(energies):
        f = floquet_multipliers(body, float(hi), method=method, tol=tol,
                                parabolic_tol=parabolic_tol, engine=engine)
        T = f.monodromy.period
        motion[i] = MOTIONS[pendulum_motion(body.mu, float(hi))]
        stab[i] = STABILITY[f.stability]
        lam[i] = f.multipliers
        mats[i] = f.monodromy.matrix
        amax = float(np.max(np.abs(f.multipliers)))
        out["period"][i] = T
        out["trace"][i] = f.trace
        out["abs"][i] = amax
        out["exponent"][i] = math.log(amax) / T
        out["shear"][i] = f.shear
        out["ret"][i] = float(np.max(np.abs(f.monodromy.y_end - f.monodromy.y0)))
    dims = ("H",)
    ds = xr.Dataset(
        {"H_over_mu": (dims, energies / body.mu), "period": (dims, out["period"]),
         "motion": (dims, motion), "stability": (dims, stab),
         "floquet_trace": (dims, out["trace"]),
         "multiplier_re": (("H", "pair"), lam.real), "multiplier_im": (("H", "pair"), lam.imag),
         "abs_multiplier": (dims, out["abs"]), "floquet_exponent": (dims, out["exponent"]),
         "shear": (dims, out["shear"]), "return_error": (dims, out["ret"]),
         "monodromy": (("H", "row", "col"), mats)},
        coords={"H": energies, "pair": ["lambda", "1/lambda"], "row": list(STATE),
                "col": list(STATE)})
    if method == "variational":
        name = default_engine_name() if engine is None else engine
        how = ("heyoka variational equations (var_ode_sys)" if name == "heyoka" else
               "variational equations (Jacobian derived by SymPy) on the Numba DOP853")
    else:
        how = "central finite differences of the flow map"
    attrs = provenance(
        body, method=how,
        tolerance=tol, parabolic_tol=parabolic_tol,
        orbit="physical pendulum G1 = G2 = gamma3 = 0 from the bottom vartheta = 3 pi/2, L > 0",
        trivial_multipliers="1, 1, 1 in-plane (flow, energy, |gamma|^2); 1 transverse (area M)")
    if body.is_hess:
        attrs["hess_rotation_multiplier"] = hess_rotation_multiplier(body)
    ds.attrs.update(attrs)
    values_from_attrs(ds, {"hess_rotation_multiplier": (
        "\\exp(2\\pi\\sigma/c)", "Floquet multiplier of every rotation of a Hess body",
        "1", "")})
    ds.H.attrs.update(symbol="H", long_name="energy of the pendulum orbit", units="1",
                      equation="(1)")
    ds.H_over_mu.attrs.update(symbol="H/\\mu", long_name="energy over mu (libration < 1 < "
                              "rotation)", units="1")
    ds.period.attrs.update(symbol="T", long_name="period (closed form, elliptic K)",
                           units="body time units")
    ds.motion.attrs.update(long_name="motion of the pendulum",
                           flag_values=np.array(list(MOTIONS.values()), dtype=np.int8),
                           flag_meanings=" ".join(MOTIONS))
    ds.stability.attrs.update(long_name="linear stability of the orbit in the full system",
                              flag_values=np.array(list(STABILITY.values()), dtype=np.int8),
                              flag_meanings=" ".join(STABILITY))
    ds.floquet_trace.attrs.update(symbol="\\lambda + 1/\\lambda", units="1",
                                  long_name="trace of the transverse monodromy minus 1")
    for v in ("multiplier_re", "multiplier_im"):
        ds[v].attrs.update(symbol="\\lambda", units="1", long_name=f"non-trivial Floquet "
                           f"multipliers, {'real' if v.endswith('re') else 'imaginary'} part")
    ds.abs_multiplier.attrs.update(symbol="|\\lambda|", units="1",
                                   long_name="largest modulus of the multipliers")
    ds.floquet_exponent.attrs.update(symbol="\\log|\\lambda|/T", units="1/body time units",
                                     long_name="largest Floquet (Lyapunov) exponent")
    ds.shear.attrs.update(units="1", long_name="norm of (leaf monodromy - lambda I) when "
                          "parabolic: > 0 is a Jordan block (linear divergence)")
    ds.return_error.attrs.update(units="1", long_name="max |y(T) - y(0)| (period check)")
    ds.monodromy.attrs.update(symbol="\\Phi", units="1",
                              long_name="monodromy matrix d y_row(T) / d y_col(0)")
    return ds
