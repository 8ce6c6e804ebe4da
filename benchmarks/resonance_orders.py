"""``python -m benchmarks.resonance_orders``: the island chains predicted to orders 1-3 in mu
against the sections.

For each case (Hess(3, 1, 2) at h = 1: the 3:1 and 2:1 chains about axis 1, mu = 1e-4 ...
1e-3; the paper's body at h = 0.2466: the 7:1 and 8:1 chains about axis 1, mu = 0.0025
... 0.01; M = 0, section g = 0) it records

* the measurement, :func:`andoyer.analysis.resonance.measure.measure_island` on the numba
  engine (3 seeds, ``n_rounds`` rounds; its edges, half-width, edge uncertainty, the
  stable periodic orbit ``stable_s``, the first-order predictions R6 and R10 it gives);
* the predictions of :func:`andoyer.analysis.resonance.island_prediction` to orders 1, 2
  and 3 (half-width, stable point, libration frequency) on the same seed line;
* for some cases the libration frequency at the stable point, measured: NAFF of the
  slow angle on orbits seeded at 5, 10 and 15 % of the half-width off the stable point,
  extrapolated to zero amplitude (``Omega(a) = Omega_0 + c a^2``).

``--measure`` runs everything (about an hour on two cores; the paper's chains take 5-10
minutes each: ``12 / Omega`` returns per orbit), ``--predict`` recomputes the predictions
only and keeps the measurements, and no option rewrites ``RESONANCE_ORDERS.md`` from
``resonance_orders.json`` (the tutorial ``docs/tutorials/resonances.md`` includes it;
``tests/benchmarks/test_resonance_orders.py`` checks that it is this rendering and that
the laws hold on these numbers).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import warnings
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
RESULTS = HERE / "resonance_orders.json"
TABLES = HERE / "RESONANCE_ORDERS.md"
#: Energy level of each body.
LEVELS = {"hess": 1.0, "paper": 0.2466}
#: A relative error below this many edge uncertainties is the measurement's resolution,
#: not the theory's error: shown in brackets and left out of the fitted slopes.
RESOLUTION = 4.0


@dataclass(frozen=True)
class Case:
    """One chain at one mu."""

    body: str
    label: str
    mu: float
    n_rounds: int
    libration: bool = False
    axis: int = 1


CASES = tuple(
    [Case("hess", lab, mu, 13, libration=(lab == "3:1" and mu >= 2e-4))
     for lab in ("3:1", "2:1") for mu in (1e-4, 2e-4, 5e-4, 1e-3)]
    + [Case("paper", lab, mu, 8, libration=(lab == "7:1" and mu in (2.5e-3, 5e-3, 1e-2))
            or (lab == "8:1" and mu == 1e-2))
       for lab in ("7:1", "8:1") for mu in (2.5e-3, 5e-3, 7.5e-3, 1e-2)])


def make_body(case: Case) -> Any:
    from andoyer import RigidBody

    if case.body == "hess":
        return RigidBody.hess(3.0, 1.0, 2.0, mu=case.mu)
    return RigidBody.paper(case.mu)


def predict(case: Case) -> dict[str, Any]:
    """``island_prediction`` to order 3: per order the half-width, stable point and
    libration frequency."""
    from andoyer.analysis.resonance import island_prediction

    ds = island_prediction(make_body(case), LEVELS[case.body], 0.0, case.label,
                           axis=case.axis, order_mu=3)
    return {"half_width": ds.half_width.values.tolist(),
            "stable_s": ds.stable_s.values.tolist(),
            "stable_s_error": ds.stable_s_error.values.tolist(),
            "libration_frequency": ds.libration_frequency.values.tolist()}


def measure(case: Case) -> dict[str, Any]:
    """``measure_island`` on the numba engine (3 seeds, ``case.n_rounds`` rounds)."""
    from andoyer.analysis.resonance.measure import measure_island

    m = measure_island(make_body(case), LEVELS[case.body], 0.0, case.label, axis=case.axis,
                       n_seeds=3, n_rounds=case.n_rounds, engine="numba")
    keys = ("measured_half_width", "edge_uncertainty", "s_inner", "s_outer", "stable_s",
            "predicted_half_width", "predicted_stable_s")
    out = {k: float(m[k]) for k in keys}
    out["n_crossings"] = int(m.attrs["n_crossings"])
    return out


def measure_libration(case: Case, stable_s: float, half_width: float) -> float:
    """The libration frequency (turns per return) at the stable point ``stable_s`` of the
    seed line: NAFF of the slow angle at 5, 10, 15 % of ``half_width`` off it, 40
    libration periods, extrapolated to zero amplitude."""
    from andoyer.analysis.chaos.frequency import naff
    from andoyer.analysis.resonance.measure import _Setup
    from andoyer.analysis.resonance.predict import trig_interpolate
    from andoyer.analysis.resonance.torus import free_top_phase
    from andoyer.integrate.api import poincare

    body = make_body(case)
    setup = _Setup(body, LEVELS[case.body], 0.0, case.label, case.axis, 0, 0.0, None,
                   "numba", 1e-12, "slow_angle")
    probe, chain = setup.probe, setup.chain
    frac = np.array([0.05, 0.1, 0.15])
    n = int(40 / setup.Omega)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = poincare(body, probe.seeds(stable_s + frac * half_width), probe.section, n,
                      engine="numba", rtol=1e-12, atol=1e-12,
                      t_max=2.0 * n * 2 * math.pi / chain.torus.omega_g)
    G = np.stack([ds.G1.values, ds.G2.values, ds.G3.values], axis=-1)
    omegas = []
    for j in range(frac.size):
        phi1 = free_top_phase(body, G[j])
        rho = trig_interpolate(chain.torus, chain.torus.rho, phi1)
        k = np.arange(phi1.size) + 1.0
        psi = chain.q * phi1 - chain.p * (2 * math.pi * k - rho)
        path = np.concatenate([[0.0], np.cumsum(np.angle(np.exp(1j * np.diff(psi))))])
        lines = naff(path - path.mean(), 1.0, 2).frequency
        omegas.append(float(np.max(np.abs(lines))) / (2 * math.pi))
    return float(np.polyfit(frac**2, np.array(omegas), 1)[1])


def run_case(case: Case) -> dict[str, Any]:
    rec: dict[str, Any] = {"case": asdict(case), **measure(case), "predicted": predict(case)}
    if case.libration:
        rec["measured_libration_frequency"] = measure_libration(
            case, rec["stable_s"], rec["measured_half_width"])
    rec["load"] = os.getloadavg()[0]
    return rec


# ---------------------------------------------------------------- the tables
def width_errors(rec: dict[str, Any]) -> dict[str, float]:
    """Relative errors of the half-width: R6 and orders 1-3 (predicted / measured - 1)."""
    m = rec["measured_half_width"]
    out = {"R6": rec["predicted_half_width"] / m - 1.0}
    for n, w in enumerate(rec["predicted"]["half_width"], 1):
        out[f"order {n}"] = w / m - 1.0
    return out


def position_misses(rec: dict[str, Any]) -> dict[str, float]:
    """The stable point's miss, measured - predicted (G units): R10 and orders 1-3."""
    s = rec["stable_s"]
    out = {"R10": s - rec["predicted_stable_s"]}
    for n, p in enumerate(rec["predicted"]["stable_s"], 1):
        out[f"order {n}"] = s - p
    return out


def resolution(rec: dict[str, Any]) -> float:
    """The smallest relative width error the measurement resolves."""
    return RESOLUTION * rec["edge_uncertainty"] / rec["measured_half_width"]


def slopes(records: list[dict[str, Any]]) -> dict[str, dict[str, float]]:
    """Per chain (``body label``): fitted slopes of log |error| against log mu of the
    width's relative errors (``width R6`` ...) and of the stable point's misses
    (``position R10`` ...), over the points above the measurement's resolution (at least
    two)."""
    chains: dict[str, list[dict[str, Any]]] = {}
    for r in records:
        chains.setdefault(f"{r['case']['body']} {r['case']['label']}", []).append(r)
    out: dict[str, dict[str, float]] = {}
    for name, recs in chains.items():
        row: dict[str, float] = {}
        for kind, errors, floor in (
                ("width", width_errors, resolution),
                ("position", position_misses,
                 lambda r: 1e-6 * r["measured_half_width"])):   # the stable search's xatol
            for key in errors(recs[0]):
                pts = [(r["case"]["mu"], abs(errors(r)[key])) for r in recs
                       if abs(errors(r)[key]) > floor(r) and math.isfinite(errors(r)[key])]
                if len(pts) >= 2:
                    mu, err = np.array(pts).T
                    row[f"{kind} {key}"] = float(np.polyfit(np.log(mu), np.log(err), 1)[0])
        out[name] = row
    return out


def _rel(x: float, floor: float) -> str:
    text = f"{x:+.2e}"
    return f"({text})" if abs(x) <= floor else text


def _name(rec: dict[str, Any]) -> tuple[str, str, str]:
    c = rec["case"]
    body = "Hess(3, 1, 2)" if c["body"] == "hess" else "paper"
    return body, f"{c['label']} (axis {c['axis']})", f"{c['mu']:g}"


def render(records: list[dict[str, Any]]) -> str:
    """The Markdown tables of ``records`` (the tutorial includes them)."""
    lines = [
        "<!-- written by python -m benchmarks.resonance_orders from resonance_orders.json;"
        " do not edit -->",
        "",
        "Half-width: relative error of each prediction, predicted / measured - 1 "
        f"(in brackets: below {RESOLUTION:g} edge uncertainties of the measurement).",
        "",
        "| body | chain | mu | measured half-width | edge uncertainty | R6 (pendulum) "
        "| order 1 | order 2 | order 3 |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in records:
        e, floor = width_errors(r), resolution(r)
        lines.append("| " + " | ".join([*_name(r), f"{r['measured_half_width']:.6e}",
                                        f"{r['edge_uncertainty']:.1e}"]
                                       + [_rel(e[k], floor) for k in e]) + " |")
    lines += [
        "",
        "Stable periodic orbit on the seed line: measured position (G units from the "
        "resonant torus) and the miss of each prediction, measured - predicted, in "
        "half-widths; inside: the order-2 point lies between the measured edges.",
        "",
        "| body | chain | mu | measured stable point | R10 | order 1 | order 2 | order 3 "
        "| inside (order 2) |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in records:
        miss, hw = position_misses(r), r["measured_half_width"]
        inside = r["s_inner"] < r["predicted"]["stable_s"][1] < r["s_outer"]
        lines.append("| " + " | ".join([*_name(r), f"{r['stable_s']:+.6e}"]
                                       + [f"{miss[k] / hw:+.2e}" for k in miss]
                                       + ["yes" if inside else "no"]) + " |")
    lines += [
        "",
        "Fitted slopes of log |error| against log mu (the points above the resolution): "
        "the width's relative error and the stable point's miss.",
        "",
        "| chain | width R6 | width order 1 | width order 2 | width order 3 | position R10 "
        "| position order 2 | position order 3 |",
        "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for name, row in slopes(records).items():
        keys = ("width R6", "width order 1", "width order 2", "width order 3",
                "position R10", "position order 2", "position order 3")
        lines.append(f"| {name} | " + " | ".join(
            f"{row[k]:.2f}" if k in row else "-" for k in keys) + " |")
    lib = [r for r in records if "measured_libration_frequency" in r]
    if lib:
        lines += [
            "",
            "Libration frequency at the stable point (turns per return): measured (NAFF "
            "of the slow angle, extrapolated to zero amplitude) and the relative error "
            "of each order.",
            "",
            "| body | chain | mu | measured | order 1 | order 2 | order 3 |",
            "| --- | --- | --- | --- | --- | --- | --- |"]
        for r in lib:
            om = r["measured_libration_frequency"]
            lines.append("| " + " | ".join(
                [*_name(r), f"{om:.6e}"]
                + [f"{w / om - 1:+.2e}" for w in r["predicted"]["libration_frequency"]])
                + " |")
    loads = [r["load"] for r in records if "load" in r]
    if loads:
        lines += ["", f"Measured on the numba engine, load average {min(loads):.0f} to "
                      f"{max(loads):.0f} on two cores."]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.resonance_orders",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("--measure", action="store_true", help="measure and predict every case")
    ap.add_argument("--predict", action="store_true",
                    help="recompute the predictions, keep the measurements")
    args = ap.parse_args(argv)
    if args.measure:
        records = [run_case(c) for c in CASES]
    else:
        records = json.loads(RESULTS.read_text())
        if args.predict:
            for r in records:
                r["predicted"] = predict(Case(**r["case"]))
    if args.measure or args.predict:
        RESULTS.write_text(json.dumps(records, indent=1) + "\n")
    TABLES.write_text(render(records))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
