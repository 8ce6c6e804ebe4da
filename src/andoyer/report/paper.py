"""``andoyer paper``: rebuild the paper's figures and checks from nothing, into one folder.

Each *item* of the report is built by one function of this module from the library's
analysis (data) and plot (figures) layers. It writes its figures (PNG and PDF), their
data (NetCDF) and says, for ``index.html``, what the paper prints there and what this
package corrected or added. :func:`build_paper` runs the items in order with a progress
line each, and writes ``index.html`` last (atomically), so a folder with an index is a
complete one.

Examples
--------
>>> [item.key for item in ITEMS][0]
'paper-check'
"""

from __future__ import annotations

import json
import sys
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import xarray as xr

from andoyer._atomic import atomic_path
from andoyer._version import __version__
from andoyer.body import RigidBody
from andoyer.io import write_netcdf
from andoyer.plot.section import save_figure

__all__ = ["Item", "Result", "Context", "ITEMS", "build_paper", "DEFAULT_OUT"]

#: Default output folder of ``andoyer paper``.
DEFAULT_OUT = "andoyer-paper"


@dataclass
class Context:
    """What every item builder gets: the output folder, the paper's body, the engine."""

    out: Path
    body: RigidBody
    engine: str | None = None
    quick: bool = False

    def figure(self, fig: Any, name: str) -> list[Path]:
        """Write a figure as ``name.png`` and ``name.pdf``."""
        return save_figure(fig, self.out / name, pdf=True, dpi=200)

    def data(self, ds: xr.Dataset, name: str) -> Path:
        """Write a dataset as ``name.nc`` (atomically)."""
        return write_netcdf(ds, self.out / f"{name}.nc")


@dataclass
class Result:
    """What an item wrote and what ``index.html`` says about it."""

    files: list[Path]
    paper: str
    found: list[str] = field(default_factory=list)
    html: str = ""
    numbers: dict[str, float] = field(default_factory=dict)


@dataclass(frozen=True)
class Item:
    """One section of the report: a key, a title and the function that builds it."""

    key: str
    title: str
    build: Callable[[Context], Result]


# ---------------------------------------------------------------------- items
def _paper_check(ctx: Context) -> Result:
    from andoyer.analysis.paper_check import format_table, paper_check

    rows = paper_check(n=50 if ctx.quick else 200)
    text = format_table(rows)
    txt = ctx.out / "paper-check.txt"
    with atomic_path(txt) as tmp:
        tmp.write_text(text + "\n", encoding="utf-8")
    js = ctx.out / "paper-check.json"
    with atomic_path(js) as tmp:
        tmp.write_text(json.dumps([asdict(r) for r in rows], indent=1), encoding="utf-8")
    counts = {v: sum(r.verdict == v for r in rows) for v in ("holds", "misprint", "omission")}
    html = _table(["place", "verdict", "formula", "what is wrong / missing", "corrected form"],
                  [[r.label, r.verdict, r.name, r.nature, r.corrected] for r in rows])
    return Result(
        [txt, js],
        f"{len(rows)} formulas printed in the paper, each typed as printed and evaluated at "
        "random points against the derivation from H = (G, IG)/2 + mu (r, gamma).",
        [f"{counts['holds']} hold, {counts['misprint']} are misprints, "
         f"{counts['omission']} are incomplete or missing (the table below gives each "
         "one's nature and its corrected form, itself checked against the derivation)."],
        html, {k: float(v) for k, v in counts.items()})


def _fig3(ctx: Context) -> Result:
    from andoyer.analysis.trajectories import fig3_section, fig3_trajectories
    from andoyer.plot.fig3 import plot_fig3

    traj = fig3_trajectories(ctx.body, engine=ctx.engine,
                             t_end=200.0 if ctx.quick else 400.0)
    sec, fill = fig3_section(ctx.body, engine=ctx.engine,
                             n_crossings=100 if ctx.quick else 400)
    files = ctx.figure(plot_fig3(traj, sec, fill), "fig3")
    files.append(ctx.data(traj, "fig3-trajectories"))
    files.append(ctx.data(sec.drop_vars("y0"), "fig3-section"))
    return Result(
        files,
        "Fig. 3: 'Projection of phase trajectories of the dynamic system (16) on the plane "
        "R^2(theta1, J1)' for mu = 0.01, A1 = 2.5, A2 = 2.0, A3 = 2.2; 'Area, separated by "
        "dot-dash line, is shown at the right side in the extended form.'",
        ["Trajectories are integrated in the regular Euler-Poisson variables and read in "
         "the Hess chart (14), not integrated in the chart (16), which is singular at "
         "J1 = 0, J1 = J2 (the corners the separatrix runs into).",
         "Added: the same phase space as a Poincare section theta2 = 0 at the separatrix "
         f"energy h = c/2 = {ctx.body.c / 2:.6g} (J2 = 1), which shows what the projection "
         "smears: invariant curves, islands, and the thin chaotic layer along the "
         "separatrix theta1 = 4 phi0 (enlarged in (d)); along theta1 = 0 (the Hess "
         "solution, drawn bold) there is none.",
         f"Energy conserved to {traj.attrs['H_max_drift']:.1e} (relative) along the "
         "trajectories; crossings satisfy theta2 = 0 to "
         f"{float(abs(sec.section_residual).max()):.1e}."],
        numbers={"H_max_drift": float(traj.attrs["H_max_drift"])})


ITEMS: list[Item] = [
    Item("paper-check", "Every printed formula against the derivation", _paper_check),
    Item("fig3", "Fig. 3 — trajectories of (16) near the separatrix, and the section "
         "θ2 = 0", _fig3),
]


# ---------------------------------------------------------------------- html
def _esc(text: Any) -> str:
    import html

    return html.escape(str(text))


def _table(head: list[str], rows: list[list[Any]]) -> str:
    out = ["<table><thead><tr>" + "".join(f"<th>{_esc(h)}</th>" for h in head)
           + "</tr></thead><tbody>"]
    for row in rows:
        out.append("<tr>" + "".join(f"<td>{_esc(c)}</td>" for c in row) + "</tr>")
    out.append("</tbody></table>")
    return "\n".join(out)


_CSS = """
body { font-family: system-ui, sans-serif; max-width: 72rem; margin: 2rem auto;
       padding: 0 1rem; color: #222; line-height: 1.45; }
h1 { font-size: 1.6rem; } h2 { font-size: 1.25rem; margin-top: 2.5rem;
  border-bottom: 1px solid #ccc; }
.item { display: grid; grid-template-columns: minmax(0, 3fr) minmax(0, 2fr); gap: 1.5rem; }
.item img { width: 100%; border: 1px solid #ddd; }
.paper { background: #f6f6f0; border-left: 4px solid #b9a; padding: .5rem .8rem; }
.found li { margin: .2rem 0; }
table { border-collapse: collapse; font-size: .85rem; margin-top: 1rem; }
td, th { border: 1px solid #ccc; padding: .2rem .4rem; vertical-align: top; }
.files { font-size: .85rem; color: #555; }
"""


def _write_index(out: Path, ctx: Context, done: list[tuple[Item, Result, float]]) -> Path:
    parts = [
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>",
        "<title>andoyer: the paper's results, reproduced and completed</title>",
        f"<style>{_CSS}</style></head><body>",
        "<h1>Kyrychenko, <i>Andoyer–Deprit variables use to the Hess gyroscope phase "
        "trajectories exploring</i>: results reproduced, checked and completed</h1>",
        f"<p>Built by andoyer {_esc(__version__)} for the body {_esc(ctx.body.name)} "
        f"(A, B, C) = ({ctx.body.A:g}, {ctx.body.B:g}, {ctx.body.C:g}), μ = "
        f"{ctx.body.mu:g}, φ0 = {ctx.body.phi0:.10f}, κ = a − b = {ctx.body.kappa:.6g}. "
        "Everything is derived from H = ½(G, IG) + μ(r, γ); where the paper and the "
        "derivation disagree, the derivation is used and the difference is listed. "
        "Each item: the figure (PDF beside it), what the paper says, and what was "
        "corrected or added.</p>",
    ]
    for item, res, seconds in done:
        images = [f for f in res.files if f.suffix == ".png"]
        parts.append(f"<h2 id='{_esc(item.key)}'>{_esc(item.title)}</h2>"
                     + ("<div class='item'><div>" if images else "<div><div>"))
        parts.append("".join(f"<img src='{_esc(f.name)}' alt='{_esc(item.title)}'>"
                             for f in images) + "</div>")
        parts.append(f"<div><p class='paper'><b>The paper:</b> {_esc(res.paper)}</p>")
        if res.found:
            parts.append("<p><b>Corrected or added:</b></p><ul class='found'>"
                         + "".join(f"<li>{_esc(s)}</li>" for s in res.found) + "</ul>")
        parts.append("<p class='files'>Files: " + ", ".join(
            f"<a href='{_esc(f.name)}'>{_esc(f.name)}</a>" for f in res.files)
            + f" (built in {seconds:.1f} s)</p></div></div>")
        if res.html:
            parts.append(res.html)
    parts.append("</body></html>")
    index = out / "index.html"
    with atomic_path(index) as tmp:
        tmp.write_text("\n".join(parts), encoding="utf-8")
    return index


# ---------------------------------------------------------------------- driver
def build_paper(out: str | Path = DEFAULT_OUT, *, body: RigidBody | None = None,
                engine: str | None = None, quick: bool = False,
                only: list[str] | None = None, progress: bool = True
                ) -> tuple[Path, list[tuple[Item, Result, float]]]:
    """Build the report: every item's figures and data, then ``index.html``.

    Parameters
    ----------
    out : path-like
        Output folder (created).
    body : RigidBody, optional
        Default: the paper's body, :meth:`RigidBody.paper`.
    engine : str, optional
        Integration engine (default: heyoka where installed).
    quick : bool
        Smaller grids and shorter runs (for tests).
    only : list of str, optional
        Keys of the items to build (default: all, see :data:`ITEMS`).
    progress : bool
        One line per item on stderr.

    Returns
    -------
    (index, done)
        The path of ``index.html`` and, per item, the item, its result and seconds.
    """
    keys = [i.key for i in ITEMS]
    if only:
        unknown = sorted(set(only) - set(keys))
        if unknown:
            raise ValueError(f"unknown item(s) {unknown}; choose from {keys}")
    items = [i for i in ITEMS if not only or i.key in only]
    ctx = Context(Path(out), RigidBody.paper() if body is None else body, engine, quick)
    ctx.out.mkdir(parents=True, exist_ok=True)
    done = []
    t_all = time.perf_counter()
    for k, item in enumerate(items, 1):
        if progress:
            print(f"[{k}/{len(items)}] {item.title} ...", end="", file=sys.stderr, flush=True)
        t0 = time.perf_counter()
        res = item.build(ctx)
        dt = time.perf_counter() - t0
        done.append((item, res, dt))
        if progress:
            print(f" {dt:.1f} s", file=sys.stderr, flush=True)
    index = _write_index(ctx.out, ctx, done)
    if progress:
        print(f"wrote {index} ({time.perf_counter() - t_all:.1f} s in all)", file=sys.stderr)
    return index, done
