"""``andoyer orbit``: integrate one orbit and write it as NetCDF."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.cli._common import (
    add_body_args,
    add_engine_args,
    body_from_args,
    count,
    floats,
    output_file,
    real,
)

NAME = "orbit"
ORDER = 30


def run(args: argparse.Namespace) -> int:
    import numpy as np

    from andoyer.integrate.api import initial_states, propagate
    from andoyer.io import write_netcdf

    out_path = output_file(args.out, ".nc")
    body = body_from_args(args)
    given = [(n, v) for n, v in (("euler_poisson", args.y0), ("andoyer", args.andoyer),
                                 ("hess", args.hess)) if v is not None]
    if len(given) != 1:
        raise ValueError("give exactly one initial state: --y0, --andoyer or --hess")
    chart, text = given[0]
    flag = {"euler_poisson": "--y0", "andoyer": "--andoyer", "hess": "--hess"}[chart]
    state = floats(text, 6 if chart == "euler_poisson" else 5, flag)
    initial_states(body, state, chart, name=flag)  # errors name the flag, not y0
    if args.t_end <= 0 or args.n_out < 2:
        raise ValueError("--t-end must be > 0 and --n-out >= 2")
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
    st = p.add_argument_group("initial state (one of)")
    st.add_argument("--y0", help="Euler-Poisson state 'G1,G2,G3,gamma1,gamma2,gamma3'")
    st.add_argument("--andoyer", help="Andoyer-Deprit state 'l,g,L,G,M'")
    st.add_argument("--hess", help="Hess-chart state 'theta1,theta2,J1,J2,J3'")
    p.add_argument("--t-end", type=real(positive=True), default=1000.0,
                   help="final time (default 1000)")
    p.add_argument("--n-out", type=count(2), default=1001, help="output times (default 1001)")
    add_engine_args(p)
    p.add_argument("--out", default="orbit.nc", help="output NetCDF file")
    p.set_defaults(func=run)

