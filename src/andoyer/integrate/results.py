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
from andoyer.charts.andoyer_deprit import singular_mask, to_andoyer
from andoyer.charts.euler_poisson import (
    STATE,
    area_integral,
    energy,
    geometric_integral,
    momentum_bound,
)
from andoyer.charts.hess import to_hess

__all__ = ["states_dataset", "provenance", "VARIABLE_ATTRS"]

#: Storage name -> (paper symbol, long name, equation). Storage names differ ignoring
#: case (l/L and g/G would collide on case-insensitive file systems).
VARIABLE_ATTRS: dict[str, tuple[str, str, str]] = {
    "G1": ("G_1", "angular momentum, body axis 1", "(1)"),
    "G2": ("G_2", "angular momentum, body axis 2", "(1)"),
    "G3": ("G_3", "angular momentum, body axis 3", "(1)"),
    "gamma1": ("\\gamma_1", "upward vertical, body axis 1", "(1)"),
    "gamma2": ("\\gamma_2", "upward vertical, body axis 2", "(1)"),
    "gamma3": ("\\gamma_3", "upward vertical, body axis 3", "(1)"),
    "l_angle": ("l", "Andoyer-Deprit angle l", "(5)-(6)"),
    "g_angle": ("g", "Andoyer-Deprit angle g", "(5)-(6)"),
    "L_action": ("L", "projection of G on body axis 3", "(5)"),
    "G_action": ("G", "length of the angular momentum", "(5)"),
    "M_action": ("M", "area integral (G, gamma)", "(4)"),
    "theta1": ("\\theta_1", "Hess-chart angle 2(l + phi0), in [0, 4 pi)", "(14)"),
    "theta2": ("\\theta_2", "Hess-chart angle g - l - phi0", "(14)"),
    "J1": ("J_1", "Hess-chart action (G + L)/2", "(14)"),
    "J2": ("J_2", "Hess-chart action G", "(14)"),
    "J3": ("J_3", "Hess-chart action M", "(14)"),
    "H": ("H", "energy", "(1)"),
    "area": ("(G, \\gamma)", "area integral", "(1)"),
    "geometric": ("|\\gamma|^2", "geometric integral", "(1)"),
    "singular": ("", "Singular flags of the Andoyer-Deprit chart (0: regular)", ""),
}
_UNITS = {"l_angle": "rad", "g_angle": "rad", "theta1": "rad", "theta2": "rad"}


@checks_body
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


@checks_body
def states_dataset(body: RigidBody, y: NDArray[np.float64], dims: Sequence[str],
                   coords: Mapping[str, Any], attrs: Mapping[str, Any],
                   extra: Mapping[str, tuple[Sequence[str], Any]] | None = None) -> xr.Dataset:
    """Dataset of states ``y`` (shape ``(*shape, 6)``, NaN allowed for padding).

    Holds the Euler-Poisson state, the Andoyer-Deprit and (for ``e3 = 0``) Hess-chart
    coordinates, the integrals H, (G, gamma), |gamma|^2, and the singular flags.
    """
    dims = tuple(dims)
    valid = np.all(np.isfinite(y), axis=-1)
    safe = np.where(valid[..., None], y, np.array([0.0, 1.0, 0.0, 0.0, 0.0, 1.0]))
    data: dict[str, tuple[tuple[str, ...], Any]] = {
        name: (dims, y[..., i]) for i, name in enumerate(STATE)}
    x = to_andoyer(safe)
    # G = 0 relative to the orbit's momentum scale (the largest |G| on its energy level),
    # not only where |G| is exactly 0.
    flags = singular_mask(safe, momentum_bound(body, safe))
    nan = np.where(valid, 1.0, np.nan)
    for i, name in enumerate(("l_angle", "g_angle", "L_action", "G_action", "M_action")):
        data[name] = (dims, x[..., i] * nan)
    if abs(body.e3) <= 1e-12:
        xh = to_hess(body, safe)
        for i, name in enumerate(("theta1", "theta2", "J1", "J2", "J3")):
            data[name] = (dims, xh[..., i] * nan)
    data["H"] = (dims, energy(body, safe) * nan)
    data["area"] = (dims, area_integral(safe) * nan)
    data["geometric"] = (dims, geometric_integral(safe) * nan)
    data["singular"] = (dims, np.where(valid, flags, -1))
    if extra:
        data.update({k: (tuple(d), v) for k, (d, v) in extra.items()})
    ds = xr.Dataset(data, coords=dict(coords), attrs=dict(attrs))
    for name, (sym, long, eq) in VARIABLE_ATTRS.items():
        if name in ds:
            ds[name].attrs.update(symbol=sym, long_name=long, equation=eq,
                                  units=_UNITS.get(name, "1"))
    return ds
