"""Self-describing xarray datasets of Euler-Poisson states and their chart coordinates."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from datetime import UTC, datetime
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from andoyer._version import __version__
from andoyer.body import RigidBody, checks_body
from andoyer.charts.andoyer_deprit import SINGULAR_RTOL, Singular, to_andoyer
from andoyer.charts.euler_poisson import (
    STATE,
    area_integral,
    energy,
    geometric_integral,
    momentum_bound,
)
from andoyer.charts.hess import to_hess
from andoyer.notation import COORDINATES, coordinates, storage_name

__all__ = ["states_dataset", "provenance", "describe_variables", "values_from_attrs",
           "VARIABLE_ATTRS", "VariableMeta"]

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
    for name, (sym, long, eq) in VARIABLE_ATTRS.items():
        if name in ds:
            ds[name].attrs.update(symbol=sym, long_name=extra.get(name, long), equation=eq)
            if units:
                ds[name].attrs["units"] = _UNITS.get(name, "1")
    for name, (sym, long, unit, eq) in (meta or {}).items():
        if name in ds:
            ds[name].attrs.update(symbol=sym, long_name=long, units=unit, equation=eq)
    return ds


def provenance(body: RigidBody, **extra: Any) -> dict[str, Any]:
    """Attributes recording body, package version and creation time."""
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

    >>> ds = xr.Dataset(attrs={"rho": 0.5})
    >>> float(values_from_attrs(ds, {"rho": ("\\rho", "c J2/lambda", "1", "")}).rho)
    0.5
    """
    for name in meta:
        if name in ds.attrs and name not in ds:
            ds[name] = ((), ds.attrs[name])
    return describe_variables(ds, {k: v for k, v in meta.items() if k in ds.data_vars})


@checks_body
def states_dataset(body: RigidBody, y: NDArray[np.float64], dims: Sequence[str],
                   coords: Mapping[str, Any], attrs: Mapping[str, Any],
                   extra: Mapping[str, tuple[Sequence[str], Any]] | None = None) -> xr.Dataset:
    """Dataset of states ``y`` (shape ``(*shape, 6)``, NaN allowed for padding).

    Holds the Euler-Poisson state, the Andoyer-Deprit and (for ``e3 = 0``) Hess-chart
    coordinates, the integrals H, (G, gamma), ``|gamma|^2``, and the singular flags.
    """
    dims = tuple(dims)
    valid = np.all(np.isfinite(y), axis=-1)
    safe = np.where(valid[..., None], y, np.array([0.0, 1.0, 0.0, 0.0, 0.0, 1.0]))
    data: dict[str, tuple[tuple[str, ...], Any]] = {
        name: (dims, y[..., i]) for i, name in enumerate(STATE)}
    x, flags = to_andoyer(safe, with_mask=True)
    H = energy(body, safe)
    # G = 0 relative to the orbit's momentum scale (the largest |G| on its energy level),
    # not only where |G| is exactly 0.
    flags = np.where(x[..., 3] <= SINGULAR_RTOL * momentum_bound(body, safe, H),
                     int(Singular.G_ZERO), flags)
    nan = np.where(valid, 1.0, np.nan)
    for i, name in enumerate(map(storage_name, coordinates("andoyer"))):
        data[name] = (dims, x[..., i] * nan)
    if abs(body.e3) <= 1e-12:
        xh = to_hess(body, safe)
        for i, name in enumerate(map(storage_name, coordinates("hess"))):
            data[name] = (dims, xh[..., i] * nan)
    data["H"] = (dims, H * nan)
    data["area"] = (dims, area_integral(safe) * nan)
    data["geometric"] = (dims, geometric_integral(safe) * nan)
    data["singular"] = (dims, np.where(valid, flags, -1))
    if extra:
        data.update({k: (tuple(d), v) for k, (d, v) in extra.items()})
    return describe_variables(xr.Dataset(data, coords=dict(coords), attrs=dict(attrs)))
