"""NetCDF output written atomically: a temporary file in the same folder, then rename."""

from __future__ import annotations

import os
from pathlib import Path

import xarray as xr

from andoyer.atomic import atomic_path

__all__ = ["write_netcdf"]


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike[str]) -> Path:
    """Write ``ds`` to ``path`` (NetCDF-4); nothing half-written is left on failure.

    Attribute values that NetCDF cannot store (booleans, None) are converted first.

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset (its attrs are not changed).
    path : str or os.PathLike
        The file to write (replaced atomically if it exists).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    out = Path(path)
    clean = ds.copy()
    clean.attrs = {k: (int(v) if isinstance(v, bool) else v)
                   for k, v in ds.attrs.items() if v is not None}
    with atomic_path(out) as tmp:
        clean.to_netcdf(tmp, engine="netcdf4")
    return out
