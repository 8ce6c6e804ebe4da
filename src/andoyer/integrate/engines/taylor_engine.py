"""The taylor engine: an adaptive Taylor method compiled with Numba, events in the kernel.

A thin adapter from the :class:`~andoyer.integrate.engines.base.Engine` protocol to
:mod:`andoyer.kernels.taylor.flow`: it checks shapes, makes the arrays contiguous floats,
runs the ensemble kernel (blocks of orbits in Numba's number of threads,
:mod:`andoyer.kernels.threads`) and turns a failed orbit into an exception.

The method is heyoka's (Jorba & Zou's order and step size from the jets, the jets by
recurrences generated from the SymPy field), without heyoka: it runs wherever Numba
does. Section crossings are isolated on each step's Taylor polynomial inside the
compiled loop, so a crossing costs no Python call (heyoka's engine pays one callback
per crossing).

Tolerances: as heyoka, one tolerance :attr:`Tolerance.tol` = ``min(rtol, atol)``
(absolute error control while ``||y||_inf <= 1``, relative above); the order is
:func:`andoyer.kernels.taylor.flow.order_for` (15 at 1e-12). Backward flows come from the
base class (time reversal).

Tangent flows at output times (``tangent``): renormalised, by
:mod:`andoyer.kernels.taylor.tangent` (the vectors' jets of :mod:`andoyer.kernels.taylor.flow`,
each vector rescaled to unit length at every step's start, the MEGNO quadratures as
extra jet variables of the same step); without renormalisation, the linear flow's own
vectors (``6 + 6 k`` floats: the FLI map's route).

Many orbits (from :data:`LANES_FROM` on; states alone or with tangent vectors, not
renormalised) run on SIMD lanes, :mod:`andoyer.kernels.taylor.lanes`, and so do
renormalised tangent flows with the MEGNO quadratures
(:mod:`andoyer.kernels.taylor.lane_tangent`: MEGNO maps, SALI/GALI): the jets of one
vector register of orbits (8 with AVX-512, 4 with AVX2:
:func:`andoyer.kernels.simd.lane_width`) in one vector instruction, each orbit with its
own steps (the scalar kernel's),
at a fraction of the scalar kernel's CPU per orbit-step; so do the crossings of many
states alone, of every section (a state component's, ``G3 = c``, and the angles',
``theta2 = c``, whose section function's jet runs on the lanes too:
:mod:`andoyer.kernels.taylor.lane_crossings`; measured:
benchmarks/NOTES.md#taylor-lane-crossings).

The machine code is cached on disk (:mod:`andoyer.kernels.cache`): the first process on
a machine compiles what it calls (a few seconds), later processes load it.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from andoyer.integrate.engines.base import (
    Capability,
    Crossings,
    EngineBase,
    Section,
    TangentFlow,
    Tolerance,
    unit_vectors,
)
from andoyer.kernels import common
from andoyer.kernels.taylor import flow

__all__ = ["TaylorEngine"]

_N = 6


#: Orbits from which many-orbit propagations run on SIMD lanes
#: (:mod:`andoyer.kernels.taylor.lanes`), one vector of lanes: fewer orbits than lanes
#: fill one block on one thread, where the scalar kernel runs one orbit per thread, so
#: below 8 the wall times are about even and the scalar kernel is kept (measured:
#: benchmarks/NOTES.md#taylor-lanes).
LANES_FROM = 8


def _lanes() -> Any:
    from andoyer.kernels.taylor import lanes  # its machine code loads here, not at import

    return lanes


#: Crossings asked (orbits x crossings per orbit) from which a component section's
#: crossings run on SIMD lanes (and from :data:`LANES_FROM` orbits). Below, the lanes
#: would save less than compiling their kernel costs once (measured:
#: benchmarks/NOTES.md#taylor-lane-crossings).
LANE_CROSSINGS_FROM = 1000


def _lane_crossings() -> Any:
    from andoyer.kernels.taylor import lane_crossings  # its machine code loads here

    return lane_crossings


def _tangent_kernels() -> Any:
    from andoyer.kernels.taylor import tangent  # its machine code loads here, not at import

    return tangent


def _lane_tangent() -> Any:
    from andoyer.kernels.taylor import lane_tangent  # its machine code loads here

    return lane_tangent


class TaylorEngine(EngineBase):
    """Adaptive Taylor method (Jorba-Zou order and step) in Numba, orbits in parallel.

    Parameters
    ----------
    max_steps : int, default 10**9
        Steps allowed per orbit before it is reported as failed (at most
        :data:`~andoyer.integrate.engines.values.MAX_STEPS`).
    chunksize : int, default 1
        Orbits handed to a thread at a time (:func:`andoyer.kernels.threads.over_orbits`).
    n_threads : int, optional
        Threads running blocks of orbits; default Numba's :func:`numba.get_num_threads`.

    Notes
    -----
    Tangent vectors at crossings (``tangent(event=..., renormalise=False)``) are the
    linear flow's own vectors, integrated with the state (``u, rho`` split at the end).
    At output times with ``renormalise`` (chaos indicators) each vector is rescaled to
    unit length at every step's start and the MEGNO quadratures are jet variables of the
    same step (:mod:`andoyer.kernels.taylor.tangent`).

    Examples
    --------
    >>> import numpy as np
    >>> from andoyer import RigidBody, from_andoyer
    >>> from andoyer.integrate.engines.base import Tolerance
    >>> body = RigidBody.paper()
    >>> y0 = from_andoyer([[0.3, 1.1, 0.2, 1.0, -0.4]])
    >>> y = TaylorEngine().propagate(y0, np.array([0.0, 10.0]), body.engine_params,
    ...                              Tolerance(1e-12, 1e-12))
    >>> y.shape
    (1, 2, 6)
    """

    name = "taylor"
    method = "Taylor integration"
    repr_options = ("max_steps", "chunksize", "n_threads")
    tangent_method = ("the Taylor jets of the variational equations (generated from the "
                      "SymPy field), Numba Taylor method")
    capabilities = frozenset({Capability.PROPAGATE, Capability.CROSSINGS,
                              Capability.BACKWARD, Capability.TANGENT,
                              Capability.TANGENT_CROSSINGS, Capability.ATTITUDE})

    def __init__(self, *, max_steps: int = 10**9, chunksize: int = 1,
                 n_threads: int | None = None) -> None:
        self._ensemble_options(max_steps, chunksize, n_threads)
        self._ensemble = 0  # for_ensemble: the kernels are those of this many orbits

    def for_ensemble(self, n: int) -> TaylorEngine:
        """This engine with the kernels of ``n`` orbits fixed (the SIMD lanes from
        :data:`LANES_FROM` orbits on), so that chunks of fewer orbits (the last one) run
        on the same kernel: the same round-off however the orbits are chunked."""
        engine = TaylorEngine(max_steps=self.max_steps, chunksize=self.chunksize,
                              n_threads=self.n_threads)
        engine._ensemble = max(int(n), self._ensemble)
        return engine

    def _on_lanes(self, n: int) -> bool:
        """Whether ``n`` orbits (or the ensemble of :meth:`for_ensemble`) run on lanes."""
        return max(n, self._ensemble) >= LANES_FROM

    def versions(self) -> dict[str, str]:
        """Numba's version, and the Taylor kernels' own: the hash of their sources
        (:data:`andoyer.kernels.taylor.flow.TAYLOR_STAMP`, the key of their compiled code)."""
        import numba

        return {"taylor_version": f"kernels {flow.TAYLOR_STAMP[:12]}",
                "numba_version": str(numba.__version__)}

    def _run(self, z0: NDArray[np.float64], t: NDArray[np.float64],
             par: NDArray[np.float64], tolerance: Tolerance
             ) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
        """States (with tangent vectors, not renormalised) of ``z0`` at times ``t``: from
        :data:`LANES_FROM` orbits on (or an ensemble of as many, :meth:`for_ensemble`),
        :data:`andoyer.kernels.taylor.lanes.LANES` orbits
        per vector step (the same steps as the scalar kernel, results equal to round-off);
        else :func:`andoyer.kernels.taylor.flow.propagate`."""
        if self._on_lanes(z0.shape[0]):
            return _lanes().propagate(z0, t, self._kernel_params(par),
                                      flow.order_for(tolerance.tol), self.max_steps,
                                      threads=self.n_threads)
        return flow.propagate(z0, t, self._kernel_params(par), tolerance.tol,
                                self.max_steps, block=self.chunksize, threads=self.n_threads)

    def _propagate(self, y0: NDArray[np.float64], t: NDArray[np.float64],
                   par: NDArray[np.float64], tolerance: Tolerance) -> NDArray[np.float64]:
        """States at times ``t`` (non-decreasing): each step's Taylor polynomial there."""
        out, info = self._run(y0, t, par, tolerance)
        self._raise_on_failure(info, common, "in propagate")
        return out

    def _attitude(self, z0: NDArray[np.float64], t: NDArray[np.float64],
                  par: NDArray[np.float64], tolerance: Tolerance) -> NDArray[np.float64]:
        """(1) with the quaternion: its jet by the generated bilinear recurrence
        (:func:`andoyer.kernels.taylor.flow.propagate_attitude`), one step size for both."""
        out, info = flow.propagate_attitude(z0, t, self._kernel_params(par), tolerance.tol,
                                              self.max_steps, block=self.chunksize,
                                              threads=self.n_threads)
        self._raise_on_failure(info, common, "integrating the attitude")
        return out

    def _crossings(self, y0: NDArray[np.float64], par: NDArray[np.float64],
                   event: Section, n_crossings: int, t_max: float,
                   tolerance: Tolerance) -> Crossings:
        """Crossings on each step's polynomial; from :data:`LANES_FROM` orbits and
        :data:`LANE_CROSSINGS_FROM` crossings asked on, on SIMD lanes
        (:mod:`andoyer.kernels.taylor.lane_crossings`: the lanes' steps and section jets,
        the scalar kernel's root isolation lane by lane), every section kind."""
        p = self._kernel_params(par)
        kernels: Any = flow
        if y0.shape[0] >= LANES_FROM and y0.shape[0] * n_crossings >= LANE_CROSSINGS_FROM:
            kernels = _lane_crossings()
        tc, yc, count, info = kernels.locate_crossings(
            y0, p, event.kind, event.value, event.direction, n_crossings, t_max,
            tolerance.tol, self.max_steps, threads=self.n_threads,
            **({"block": self.chunksize} if kernels is flow else {}))
        self._raise_on_failure(info, common, "while locating crossings")
        return Crossings(tc, yc, count)

    def _tangent(self, y0: NDArray[np.float64], w0: NDArray[np.float64],
                 t: NDArray[np.float64], par: NDArray[np.float64], tolerance: Tolerance,
                 renormalise: bool, scale: float) -> TangentFlow:
        """Renormalised: :mod:`andoyer.kernels.taylor.tangent` (the quadratures unscaled,
        each jet block with its own error scale, so ``scale`` is not used), from
        :data:`LANES_FROM` orbits up on SIMD lanes (:mod:`andoyer.kernels.taylor.lane_tangent`:
        the same steps, rows equal to round-off); else the linear flow's own vectors
        (``megno`` None; an overflow fails the orbit)."""
        n, k = w0.shape[:2]
        m = t.size
        if renormalise:
            u0, rho0 = unit_vectors(w0)
            z0 = np.ascontiguousarray(np.concatenate([y0, u0.reshape(n, k * _N)], axis=1))
            if self._on_lanes(n):
                out, info = _lane_tangent().propagate(
                    z0, rho0, t, self._kernel_params(par), tolerance.tol, self.max_steps,
                    threads=self.n_threads)
            else:
                out, info = _tangent_kernels().propagate(
                    z0, rho0, t, self._kernel_params(par), tolerance.tol, self.max_steps,
                    block=self.chunksize, threads=self.n_threads)
        else:
            z0 = np.ascontiguousarray(np.concatenate([y0, w0.reshape(n, k * _N)], axis=1))
            out, info = self._run(z0, t, par, tolerance)
        ok = (info[:, 0] == common.SUCCESS) & np.all(np.isfinite(out), axis=(1, 2))
        out[~ok] = np.nan
        times = np.broadcast_to(t, (n, m)).copy()
        count = np.full(n, m, dtype=np.int64)
        if not renormalise:
            u, rho = unit_vectors(out[..., _N:].reshape(n, m, k, _N))
            return TangentFlow(times, out[..., :_N], u, rho, None, count, ok)
        u = out[..., _N:_N + _N * k].reshape(n, m, k, _N)
        return TangentFlow(times, out[..., :_N], u, out[..., _N + _N * k:_N + 7 * k],
                           out[..., -2:], count, ok)

    def _tangent_crossings(self, y0: NDArray[np.float64], w0: NDArray[np.float64],
                           par: NDArray[np.float64], event: Section, n_crossings: int,
                           t_max: float, tolerance: Tolerance,
                           extended_precision: bool) -> TangentFlow:
        n, k = w0.shape[:2]
        z0 = np.ascontiguousarray(np.concatenate([y0, w0.reshape(n, k * _N)], axis=1))
        tc, zc, count, info = flow.locate_crossings(
            z0, self._kernel_params(par), event.kind, event.value, event.direction,
            n_crossings, t_max, tolerance.tol, self.max_steps, block=self.chunksize,
            threads=self.n_threads)
        ok = info[:, 0] == common.SUCCESS
        u, rho = unit_vectors(zc[..., _N:].reshape(n, n_crossings, k, _N))
        return TangentFlow(tc, zc[..., :_N], u, rho, None, count, ok)
