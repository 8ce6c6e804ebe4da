"""Reading and writing results: NetCDF (and later Zarr), atomically."""

from andoyer.io.netcdf import write_netcdf as write_netcdf

__all__ = ["write_netcdf"]
