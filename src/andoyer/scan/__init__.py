"""Parameter scans on Dask, streamed into a Zarr store, resumable.

Sweep any of mu, h, M, A, B, C over a grid and run a task per point (a Poincare
section, a chaos map): :func:`run_scan` with a TOML configuration (:func:`load_config`),
or ``andoyer scan CONFIG.toml`` on the command line. Imported on demand (it loads
xarray and Dask), not by ``import andoyer``.
"""

from andoyer.scan.config import ScanConfig as ScanConfig
from andoyer.scan.config import load_config as load_config
from andoyer.scan.cost import estimate_cost as estimate_cost
from andoyer.scan.run import ScanReport as ScanReport
from andoyer.scan.run import run_scan as run_scan
from andoyer.scan.tasks import TASKS as TASKS

__all__ = ["ScanConfig", "ScanReport", "TASKS", "estimate_cost", "load_config", "run_scan"]
