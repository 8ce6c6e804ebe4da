"""``andoyer orbit``: integrate one orbit and write it as NetCDF."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.cli._common import (
    add_body_args,
    add_engine_args,
    add_state_args,
    count,
    inputs_from_args,
    real,
)

NAME = "orbit"
ORDER = 30


def run(args: argparse.Namespace) -> int:
    import numpy as np

    from andoyer.integrate import budget
    from andoyer.integrate.api import propagate
    from andoyer.io import write_netcdf

    out_path, body, state, chart, _, _ = inputs_from_args(args, state="required", beside=())
    assert state is not None and chart is not None  # required: given, or refused
    if args.t_end <= 0 or args.n_out < 2:
        raise ValueError("--t-end must be > 0 and --n-out >= 2")
    # Costed before the output times are even allocated (--n-out 1e9: 8 GB of times).
    budget.check(f"--n-out {args.n_out}", memory=budget.DATASET_BYTES * args.n_out)
    t = np.linspace(0.0, args.t_end, args.n_out)
    ds = propagate(body, state, t, chart=chart, engine=args.engine, rtol=args.rtol, atol=args.atol,
                   progress=True)
    out = write_netcdf(ds, out_path)
    drift = float(abs(ds.H_drift).max())
    print(f"wrote {out}: {args.n_out} states to t = {args.t_end:g} "
          f"(engine {ds.attrs['engine']}, max |relative energy drift| {drift:.2e})")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="integrate one orbit; write NetCDF")
    add_body_args(p)
    add_state_args(p)
    p.add_argument("--t-end", type=real(positive=True), default=1000.0,
                   help="final time (default 1000)")
    p.add_argument("--n-out", type=count(2), default=1001, help="output times (default 1001)")
    add_engine_args(p)
    p.add_argument("--out", default="orbit.nc", help="output NetCDF file")
    p.set_defaults(func=run)

