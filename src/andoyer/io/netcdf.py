"""NetCDF output written atomically: a temporary file in the same folder, then rename."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import xarray as xr

__all__ = ["write_netcdf"]


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike[str]) -> Path:
    """Write ``ds`` to ``path`` (NetCDF-4); nothing half-written is left on failure.

    Attribute values that NetCDF cannot store (booleans, None) are converted first.
    """
    out = Path(path)
    if out.parent and not out.parent.exists():
        raise ValueError(f"folder {str(out.parent)!r} does not exist; create it first")
    clean = ds.copy()
    clean.attrs = {k: (int(v) if isinstance(v, bool) else v)
                   for k, v in ds.attrs.items() if v is not None}
    fd, tmp = tempfile.mkstemp(dir=out.parent, prefix=f".{out.name}.", suffix=".tmp")
    os.close(fd)
    try:
        clean.to_netcdf(tmp, engine="netcdf4")
        os.replace(tmp, out)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return out
