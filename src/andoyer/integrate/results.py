"""Self-describing xarray datasets of Euler-Poisson states and their chart coordinates."""

from __future__ import annotations

import threading
from collections.abc import Hashable, Mapping, Sequence
from datetime import UTC, datetime
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray
from xarray.backends import BackendArray
from xarray.core import indexing

from andoyer._version import __version__
from andoyer.body import RigidBody, checks_body
from andoyer.charts.andoyer_deprit import SINGULAR_RTOL, Singular, to_andoyer
from andoyer.charts.euler_poisson import STATE, momentum_bound
from andoyer.charts.hess import to_hess
from andoyer.charts.integrals import INTEGRALS, integrals_of
from andoyer.notation import COORDINATES, coordinates, storage_name

__all__ = ["states_dataset", "derived_values", "provenance", "describe_variables",
           "values_from_attrs", "VARIABLE_ATTRS", "VariableMeta"]

#: Storage name -> (paper symbol, long name, equation), from :mod:`andoyer.notation`.
VARIABLE_ATTRS: dict[str, tuple[str, str, str]] = {
    c.storage: (c.symbol, c.long_name, c.equation) for c in COORDINATES
    if c.code not in ("m", "theta3")}
_UNITS = {c.storage: c.units for c in COORDINATES}

#: ``(symbol, long name, units, equation)`` of a dataset variable.
VariableMeta = tuple[str, str, str, str]


def describe_variables(ds: xr.Dataset, meta: Mapping[str, VariableMeta] | None = None, *,
                       long_names: Mapping[str, str] | None = None,
                       units: bool = True) -> xr.Dataset:
    """Set ``symbol``, ``long_name``, ``units`` and ``equation`` on the variables of
    ``ds`` (in place; returned for chaining).

    The coordinates of the table :data:`andoyer.notation.COORDINATES` take their
    attributes from it, so a coordinate is described the same way in every dataset;
    ``long_names`` may say more where a dataset constrains one (e.g. ``L = G3``, zero
    on a section). Other variables take theirs from ``meta``. Names that are not in
    ``ds`` are skipped.

    Parameters
    ----------
    ds : xarray.Dataset
    meta : mapping, optional
        Variable name -> :data:`VariableMeta` for the variables outside the table.
    long_names : mapping, optional
        Coordinate storage name -> a more specific long name.
    units : bool
        Set the table's units on the coordinates too (False keeps units set before).

    Examples
    --------
    >>> ds = xr.Dataset({"L_action": ("t", [0.0]), "s": ("t", [1.0])})
    >>> _ = describe_variables(ds, {"s": ("s", "curve parameter", "1", "")},
    ...                        long_names={"L_action": "L = G3, zero on the section"})
    >>> ds.L_action.attrs["symbol"], ds.L_action.attrs["long_name"], ds.s.attrs["units"]
    ('L', 'L = G3, zero on the section', '1')
    """
    extra = dict(long_names or {})
    # ds.variables, not ds[name]: no DataArray is built per name (a short propagate
    # would spend more time here than integrating).
    variables = ds.variables
    for name, (sym, long, eq) in VARIABLE_ATTRS.items():
        if name in variables:
            variables[name].attrs.update(symbol=sym, long_name=extra.get(name, long),
                                         equation=eq)
            if units:
                variables[name].attrs["units"] = _UNITS.get(name, "1")
    for name, (sym, long, unit, eq) in (meta or {}).items():
        if name in variables:
            variables[name].attrs.update(symbol=sym, long_name=long, units=unit, equation=eq)
    return ds


def provenance(body: RigidBody, **extra: Any) -> dict[str, Any]:
    """Attributes recording body, package version and creation time.

    Parameters
    ----------
    body : RigidBody
        The body, recorded as ``body_*`` attributes.
    **extra
        Further attributes (engine, tolerances, settings of the call).
    """
    attrs: dict[str, Any] = {f"body_{k}" if not k.startswith("body") else k: v
                             for k, v in body.attrs().items()}
    attrs.update(andoyer_version=__version__,
                 created=datetime.now(UTC).isoformat(timespec="seconds"),
                 equations="Euler-Poisson equations (1) of Kyrychenko, integrated in "
                           "the regular variables (G, gamma)",
                 units="dimensionless: moments of inertia, mu and time in the body's units")
    attrs.update({k: v for k, v in extra.items() if v is not None})
    return attrs


def values_from_attrs(ds: xr.Dataset, meta: Mapping[str, VariableMeta]) -> xr.Dataset:
    """The numbers a user reads off as 0-d variables too (in place; returned).

    Each name of ``meta`` present in ``ds.attrs`` (a rate, an amplitude, a count) is
    copied into a variable of that name, described by ``meta``; the attribute stays
    (older readers look there).

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset (changed in place).
    meta : mapping of str to VariableMeta
        Which attributes to copy and how to describe them (symbol, long name, units,
        equation).

    Examples
    --------
    >>> ds = xr.Dataset(attrs={"rho": 0.5})
    >>> float(values_from_attrs(ds, {"rho": ("\\rho", "c J2/lambda", "1", "")}).rho)
    0.5
    """
    for name in meta:
        if name in ds.attrs and name not in ds:
            ds[name] = ((), ds.attrs[name])
    return describe_variables(ds, {k: v for k, v in meta.items() if k in ds.data_vars})


def _derived_names(body: RigidBody, drifts: bool) -> tuple[str, ...]:
    """Names of the variables :func:`states_dataset` derives from the states."""
    charts = ("andoyer", "hess") if abs(body.e3) <= 1e-12 else ("andoyer",)
    integrals = integrals_of(body)
    return (*(storage_name(c) for chart in charts for c in coordinates(chart)),
            *integrals, "singular",
            *((f"{k}_drift" for k in integrals) if drifts else ()))


def derived_values(body: RigidBody, y: NDArray[np.float64], drifts: bool = False
                   ) -> dict[str, NDArray[Any]]:
    """Chart coordinates, integrals, singular flags (and drifts) of states ``y``.

    Every array is computed once, the Hess chart from the Andoyer-Deprit coordinates;
    NaN states (padding) give NaN values and the flag -1. The integrals are the body's
    (:func:`andoyer.charts.integrals.integrals_of`: ``H``, ``area``, ``geometric`` and
    those its kind brings, e.g. Kovalevskaya's ``K``). The drifts are taken along the
    last axis of ``y[..., 0]``, from its first entry, each relative to its integral's
    scale (:data:`andoyer.charts.integrals.INTEGRALS`: ``H_drift`` relative to
    ``max(|H(0)|, mu)``, ``area_drift`` relative to ``|G(0)|``).

    Parameters
    ----------
    body : RigidBody
        The body (chart constants, integrals).
    y : ndarray, shape (..., 6)
        Euler-Poisson states (NaN rows allowed: padding).
    drifts : bool, default False
        Also the drifts of the integrals along the last axis.
    """
    valid = np.all(np.isfinite(y), axis=-1)
    safe = np.where(valid[..., None], y, np.array([0.0, 1.0, 0.0, 0.0, 0.0, 1.0]))
    nan = np.where(valid, 1.0, np.nan)
    x, flags = to_andoyer(safe, with_mask=True)
    values = {k: INTEGRALS[k](body, safe) for k in integrals_of(body)}
    # G = 0 relative to the orbit's momentum scale (the largest |G| on its energy level),
    # not only where |G| is exactly 0.
    G_zero = x[..., 3] <= SINGULAR_RTOL * momentum_bound(body, safe, values["H"])
    out: dict[str, NDArray[Any]] = {
        name: x[..., i] * nan for i, name in enumerate(map(storage_name, coordinates("andoyer")))}
    if abs(body.e3) <= 1e-12:
        xh = to_hess(body, safe, andoyer=(x, flags))
        out.update({name: xh[..., i] * nan
                    for i, name in enumerate(map(storage_name, coordinates("hess")))})
    out.update({k: v * nan for k, v in values.items()})
    out["singular"] = np.where(valid, np.where(G_zero, int(Singular.G_ZERO), flags), -1)
    if drifts:
        y0 = safe[..., :1, :]
        out.update({f"{k}_drift": INTEGRALS[k].drift(body, v, y0) * nan
                    for k, v in values.items()})
    return out


class _Derived:
    """:func:`derived_values` of one dataset's states, computed at first use, once."""

    def __init__(self, body: RigidBody, y: NDArray[np.float64], drifts: bool) -> None:
        self.body, self.y, self.drifts = body, y, drifts
        self.values: dict[str, NDArray[Any]] | None = None
        self.lock = threading.Lock()

    def get(self, name: str) -> NDArray[Any]:
        with self.lock:
            if self.values is None:
                self.values = derived_values(self.body, self.y, self.drifts)
                self.y = np.empty((0, 6))  # the dataset holds the states
        return self.values[name]

    def __deepcopy__(self, memo: dict[int, Any]) -> _Derived:
        # Shared by the copies: its arrays are never handed out, only copies of them
        # (:meth:`_LazyColumn._raw`), so a copied dataset is as independent as a deep
        # copy, and it derives once instead of once per variable.
        return self

    def __getstate__(self) -> dict[str, Any]:  # pickled into Dask workers: no lock
        return {k: v for k, v in self.__dict__.items() if k != "lock"}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state, lock=threading.Lock())


class _LazyColumn(BackendArray):
    """One derived variable, read from :class:`_Derived` when its values are asked for
    (xarray's backend-array protocol: the dataset is built before anything is derived)."""

    def __init__(self, derived: _Derived, name: str, shape: tuple[int, ...]) -> None:
        self.derived, self.name, self.shape = derived, name, shape
        self.dtype = np.dtype(np.int64 if name == "singular" else np.float64)

    def __getitem__(self, key: indexing.ExplicitIndexer) -> Any:
        return indexing.explicit_indexing_adapter(
            key, self.shape, indexing.IndexingSupport.OUTER, self._raw)

    def _raw(self, key: tuple[Any, ...]) -> NDArray[Any]:
        # A copy: writing into what a reader got must not change the dataset's source.
        return np.array(self.derived.get(self.name)[key])


def _dataset(data: Mapping[str, Any], coords: Mapping[str, Any],
             attrs: Mapping[str, Any]) -> xr.Dataset:
    """``xr.Dataset(data, coords=coords, attrs=attrs)``, built directly where nothing is
    left to merge or align: every variable is ``(dims, ndarray)`` or an
    :class:`xarray.Variable` (taken as it is, not copied: the caller's own), none named
    after a dimension, every coordinate a dimension's 1-D numeric array, and the sizes
    agree. There xarray's merge and alignment (about 0.6 ms for a states dataset's
    30 variables, half of a short orbit's fixed cost, ``benchmarks`` W1) change nothing;
    anything else goes through the public constructor, which also names a size
    mismatch. The two agree (``tests/integrate/test_results.py``).

    Examples
    --------
    >>> ds = _dataset({"x": (("t",), np.zeros(2))}, {"t": np.arange(2.0)}, {"a": 1})
    >>> ds.identical(xr.Dataset({"x": ("t", np.zeros(2))}, coords={"t": [0.0, 1.0]},
    ...                         attrs={"a": 1}))
    True
    """
    import pandas as pd
    from xarray.indexes import Index, PandasIndex

    variables: dict[Hashable, xr.Variable] = {}
    sizes: dict[Hashable, int] = {}
    # xarray's own direct constructor (private: where a release drops it, the public one)
    direct = hasattr(xr.Dataset, "_construct_direct")
    for name, value in data.items() if direct else ():
        if isinstance(value, xr.Variable):
            var = value
        elif (isinstance(value, tuple) and len(value) == 2
              and isinstance(value[1], np.ndarray) and len(value[0]) == value[1].ndim):
            var = xr.Variable(tuple(value[0]), value[1])
        else:
            direct = False
            break
        variables[name] = var
        for dim, n in zip(var.dims, var.shape, strict=True):
            direct = direct and sizes.setdefault(dim, n) == n
        if not direct:
            break
    direct = direct and not set(variables) & set(sizes)
    indexes: dict[Hashable, Index] = {}
    for name, value in coords.items() if direct else ():
        direct = direct and (name not in variables and isinstance(value, np.ndarray)
                             and value.ndim == 1 and value.dtype.kind in "iuf"
                             and sizes.setdefault(name, value.size) == value.size)
        if not direct:
            break
        index = PandasIndex(pd.Index(value), name, coord_dtype=value.dtype)
        indexes[name] = index
        variables.update(index.create_variables())
    if not direct:
        return xr.Dataset(dict(data), coords=dict(coords), attrs=dict(attrs))
    return xr.Dataset._construct_direct(variables, set(indexes), sizes, dict(attrs),
                                        indexes)


@checks_body
def states_dataset(body: RigidBody, y: NDArray[np.float64], dims: Sequence[str],
                   coords: Mapping[str, Any], attrs: Mapping[str, Any],
                   extra: Mapping[str, tuple[Sequence[str], Any]] | None = None, *,
                   drifts: bool = False) -> xr.Dataset:
    """Dataset of states ``y`` (shape ``(*shape, 6)``, NaN allowed for padding).

    Holds the Euler-Poisson state, the Andoyer-Deprit and (for ``e3 = 0``) Hess-chart
    coordinates, the integrals H, (G, gamma), ``|gamma|^2``, and the singular flags.
    With ``drifts=True`` (orbits along the last dimension, from its first entry) also
    ``H_drift`` (relative to ``max(|H(0)|, mu)``), ``area_drift`` (relative to
    ``|G(0)|``) and ``geometric_drift``; a body whose kind brings an integral (a
    Kovalevskaya top's ``K``) has it and its drift too
    (:data:`andoyer.charts.integrals.INTEGRALS`).

    The derived variables are lazy: :func:`derived_values` runs once, when the first of
    them is read (``.values``, arithmetic, plotting, ``load()``, writing to disk). A
    dataset nobody reads the charts of costs no chart map: a short orbit's dataset
    costs a fraction of its integration (``benchmarks``, W1).

    Parameters
    ----------
    body : RigidBody
        The body.
    y : ndarray, shape (..., 6)
        Euler-Poisson states (NaN for padding); the leading axes are ``dims``.
    dims : sequence of str
        Names of the dimensions of ``shape``.
    coords : mapping
        Coordinates of those dimensions.
    attrs : mapping
        Dataset attributes (provenance).
    extra : mapping of str to (dims, values), optional
        Further variables.
    drifts : bool, default False
        Also the drifts of the integrals along the last dimension.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.paper()
    >>> ds = states_dataset(body, np.array([[0.0, 0.6, 0.8, 0.0, 0.6, 0.8]]), ("time",),
    ...                     {"time": [0.0]}, {})
    >>> round(float(ds.G_action[0]), 12), ds.H.attrs["symbol"]
    (1.0, 'H')
    """
    dims = tuple(dims)
    y = np.asarray(y, dtype=float)
    shape = y.shape[:-1]
    data: dict[str, Any] = {name: (dims, y[..., i]) for i, name in enumerate(STATE)}
    derived = _Derived(body, y, drifts)
    whole = indexing.BasicIndexer((slice(None),) * len(shape))  # immutable: one for all
    for name in _derived_names(body, drifts):
        # Lazily indexed, then cached in memory at first read, as xarray's own backends
        # do: from then on ``.values`` is one array, and writes into it stay.
        data[name] = xr.Variable(dims, indexing.MemoryCachedArray(indexing.LazilyIndexedArray(
            _LazyColumn(derived, name, shape), whole)), fastpath=True)
    if extra:
        data.update({k: (tuple(d), v) for k, (d, v) in extra.items()})
    ds = describe_variables(_dataset(data, coords, attrs))
    for name in integrals_of(body):
        integral = INTEGRALS[name]
        if name not in VARIABLE_ATTRS:  # an integral of this kind of body only
            ds.variables[name].attrs.update(symbol=integral.symbol,
                                            long_name=integral.long_name, units="1")
        if drifts:
            ds.variables[f"{name}_drift"].attrs.update(
                units="1", long_name=f"drift of {name} since t[0]",
                relative_to=integral.scale_name)
    return ds
