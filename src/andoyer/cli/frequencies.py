"""``andoyer frequencies``: fundamental frequencies by NAFF of one orbit, or a frequency map
over a section plane; NetCDF + PNG."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.cli._common import (
    Inputs,
    add_body_args,
    add_engine_args,
    add_level_args,
    add_state_args,
    add_term,
    count,
    inputs_from_args,
    real,
)

NAME = "frequencies"
ORDER = 47


def run(args: argparse.Namespace) -> int:
    import matplotlib

    matplotlib.use("Agg")
    inputs = inputs_from_args(args, state="optional", level=True)
    if inputs.state is None:
        return _map(args, inputs)
    import numpy as np

    from andoyer.analysis.chaos.frequency import orbit_frequencies
    from andoyer.integrate.api import propagate
    from andoyer.io import write_netcdf
    from andoyer.plot.frequency import plot_orbit_frequencies
    from andoyer.plot.section import save_figure

    out, body, state, chart = inputs.out, inputs.body, inputs.state, inputs.chart
    assert chart is not None
    ds = orbit_frequencies(body, state, args.t_end, n_samples=args.n_samples, chart=chart,
                           engine=args.engine, window=args.window, progress=True)
    write_netcdf(ds, out)
    # The figure reads the orbit's own signals: the samples NAFF analysed, integrated
    # again on the same times and engine (one orbit; orbit_frequencies keeps only the
    # frequencies).
    samples = propagate(body, state, np.linspace(0.0, args.t_end, args.n_samples),
                        chart=chart, engine=ds.attrs.get("engine"), progress=False)
    title = (f"{body.name or 'body'}: NAFF of the {chart} state {state} over t = "
             f"{args.t_end:g} ({args.n_samples} samples, engine {ds.attrs.get('engine')})")
    (png,) = save_figure(plot_orbit_frequencies(samples, ds, title=title),
                         out.with_suffix(".png"))
    o = ds.isel(orbit=0)
    res = str(o.resonance.values) or "none of order <= 8"
    print(f"{body.name or 'body'}, NAFF over t = {args.t_end:g} ({args.n_samples} samples):\n"
          f"  omega_l = {float(o.omega_l):.12g}   (frequency of (l, L); period "
          f"{float(o.period):.10g})\n"
          f"  omega_g = {float(o.omega_g):.12g}   (mean rate of g)\n"
          f"  frequency_ratio = omega_g/omega_l = {float(o.frequency_ratio):.12g}   (turns of "
          f"g per period of (l, L))\n"
          f"  rotation_number_g_section = omega_l/omega_g = "
          f"{float(o.rotation_number_g_section):.12g}   (rotation number of the section map "
          f"g = const)\n"
          f"  frequency drift: l {float(o.drift_l):.1e}, g {float(o.drift_g):.1e}; "
          f"resonance: {res}")
    print(f"wrote {out} and {png}")
    return 0


def _map(args: argparse.Namespace, inputs: Inputs) -> int:
    from andoyer.analysis.chaos.frequency import frequency_map
    from andoyer.io import write_netcdf
    from andoyer.plot.border import plot_frequency_map
    from andoyer.plot.section import save_figure
    from andoyer.plot.style import new_figure, paper_style

    out, body, sec, h = inputs.out, inputs.body, inputs.section, inputs.h
    assert h is not None
    ds = frequency_map(body, h, args.M, (sec.coord, sec.value), n_orbits=args.n_orbits,
                       t_end=args.t_end, n_samples=args.n_samples, engine=args.engine,
                       window=args.window, progress=True)
    write_netcdf(ds, out)
    with paper_style():
        fig = new_figure(1, 1, aspect=0.8)
        ax = fig.axes[0]
        sc = plot_frequency_map(ds, ax=ax)
        fig.colorbar(sc, ax=ax, label="log$_{10}$ frequency drift")
        ax.set_title(f"{body.name or 'body'}: frequency drift on H = {h:.6g}, "
                     f"M = {args.M:g}, {sec.coord} = {sec.value:g}", fontsize=8)
    (png,) = save_figure(fig, out.with_suffix(".png"))
    print(f"{ds.sizes['orbit']} orbits on H = {h:g}, M = {args.M:g}: frequency_ratio "
          f"omega_g/omega_l in [{float(ds.frequency_ratio.min()):.6g}, "
          f"{float(ds.frequency_ratio.max()):.6g}]")
    print(f"wrote {out} and {png}")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="frequencies by NAFF: one orbit, or a frequency map over a "
                                  "section plane: NetCDF + PNG",
                       description="Fundamental frequencies by NAFF (andoyer.analysis.chaos."
                                   "frequency): omega_l of (l, L), the mean rate omega_g of "
                                   "g, their ratio and the rotation number of the section "
                                   "map g = const, the frequency drift. With an initial "
                                   "state: that orbit (NetCDF + PNG: L folded on the "
                                   "measured period, g - omega_g t); without: a frequency "
                                   "map of "
                                   "--n-orbits orbits seeded on the section plane (NetCDF + "
                                   "PNG of the drift).")
    add_body_args(p)
    add_state_args(p, required=False)
    add_level_args(p)
    add_term(p, "n_orbits", type=count(1), default=100,
             help="orbits of the frequency map (default 100)")
    add_term(p, "t_end", type=real(positive=True), default=2000.0,
             help="length of each analysed orbit (default 2000: tens of periods)")
    add_term(p, "n_samples", type=count(64), default=8193,
             help="samples of each orbit (default 8193)")
    add_term(p, "window", type=count(1), default=2, help="Hann window order (default 2)")
    add_engine_args(p, tolerances=False)
    p.add_argument("--out", default="frequencies.nc",
                   help="output NetCDF (PNG beside it)")
    p.set_defaults(func=run)
