"""Fig. 3 data and the ``andoyer paper`` report."""

from __future__ import annotations

import json

import numpy as np
import pytest

from andoyer import RigidBody
from andoyer.analysis.paper.trajectories import (
    fig3_section,
    fig3_trajectories,
    separatrix_energy,
    zoom_box,
)
from andoyer.cli import main
from andoyer.dynamics import hamiltonian


def test_fig3_trajectories_follow_unperturbed_levels_at_mu0():
    """At mu = 0 the projected trajectories are level curves of H0 (13) at fixed J2."""
    body = RigidBody.paper(0.0)
    ds = fig3_trajectories(body, J1=[0.05, 0.3], t_end=200.0, dt=1.0, engine="numba")
    x = np.stack([ds.theta1, np.zeros_like(ds.J1), ds.J1, ds.J2, np.zeros_like(ds.J1)], -1)
    H0 = hamiltonian(body, x.reshape(-1, 5), "hess").reshape(ds.J1.shape)
    assert np.ptp(H0, axis=1).max() < 1e-12
    assert np.ptp(ds.J2.values, axis=1).max() < 1e-12
    # The orbit seeded at the centre line theta1 = 2 phi0 with J1 = 0.05 J2 comes close
    # to the saddles (J1 -> 0 at theta1 -> 0, 4 phi0): its theta1 range is wide.
    assert float(ds.theta1[0].max() - ds.theta1[0].min()) > 2.0
    assert ds.attrs["figure"] == "Fig. 3" and ds.attrs["body_mu"] == 0.0


def test_fig3_section_energy_and_zoom_seeds():
    body = RigidBody.paper()
    sec, fill = fig3_section(body, n_orbits=6, n_zoom=3, n_crossings=5, engine="numba")
    assert np.isclose(sec.attrs["h"], separatrix_energy(body)) and sec.attrs["h"] == body.c / 2
    assert abs(sec.section_residual).max() < 1e-11
    (x0, x1), (y0, y1) = zoom_box(body)
    th, J1 = np.mod(sec.theta1.isel(crossing=0), 2 * np.pi), sec.J1.isel(crossing=0)
    # The zoom seeds start inside the box around the saddle (4 phi0, 0).
    y = sec.y0.values[-3:]
    from andoyer import to_hess
    t = to_hess(body, y)
    assert np.all((np.mod(t[:, 0], 2 * np.pi) >= x0) & (np.mod(t[:, 0], 2 * np.pi) <= x1))
    assert np.all((t[:, 2] >= y0) & (t[:, 2] <= y1))
    assert np.all(np.isfinite(th)) and np.all(np.isfinite(J1))


def test_fig3_bad_input():
    body = RigidBody.paper()
    with pytest.raises(ValueError, match="J1 seeds"):
        fig3_trajectories(body, J1=[0.7])
    with pytest.raises(ValueError, match="dt"):
        fig3_trajectories(body, t_end=1.0, dt=2.0)
    with pytest.raises(ValueError):
        fig3_trajectories(RigidBody(2.5, 2.0, 2.2, 0.01, (0.0, 0.6, 0.8)))


def test_paper_command_writes_index(tmp_path, capsys, monkeypatch):
    from _figures import overlapping_texts, unlabelled_colour_bars
    from andoyer.report.base import Context

    figures = {}
    save = Context.figure

    def keep(self, fig, name):
        figures[name] = fig
        return save(self, fig, name)

    monkeypatch.setattr(Context, "figure", keep)
    out = tmp_path / "paper"
    assert main(["paper", "--out", str(out), "--quick", "--only", "paper-check", "fig3",
                 "solutions", "heteroclinic",
                 "--engine", "numba", "--jobs", "1"]) == 0
    # The report's figures are readable: no label over another, every colour bar named.
    assert set(figures) == {"fig3", "solutions"}
    for name, fig in figures.items():
        assert overlapping_texts(fig) == [], name
        assert unlabelled_colour_bars(fig) == [], name
    names = {p.name for p in out.iterdir()}
    assert {"index.html", "fig3.png", "fig3.pdf", "fig3-trajectories.nc",
            "paper-check.txt", "paper-check.json", "solutions.png", "hess-periods.nc",
            "heteroclinic.nc"} <= names
    html = (out / "index.html").read_text()
    assert "fig3.png" in html and "misprint" in html and "The paper:" in html
    from matplotlib.image import imread
    img = imread(out / "fig3.png")
    assert img.shape[0] > 500 and img.std() > 0.05
    import xarray as xr
    with xr.open_dataset(out / "fig3-trajectories.nc") as ds:
        assert ds.attrs["figure"] == "Fig. 3"
    # The closed forms agree with the integrations the report ran.
    with xr.open_dataset(out / "hess-periods.nc") as ds:
        T = ds.T_integrated.values
        assert np.all(np.isfinite(T)) and T.size >= 4
    import json
    summary = json.loads((out / "summary.json").read_text())
    assert summary["items"]["heteroclinic"]["numbers"]["max_error"] < 1e-11
    assert summary["items"]["solutions"]["numbers"]["max_rel_period_error"] < 1e-9
    assert summary["body"]["body_name"] == "paper"


def test_paper_command_unknown_item(tmp_path):
    with pytest.raises(SystemExit) as exc:
        main(["paper", "--out", str(tmp_path), "--only", "fig9"])
    assert exc.value.code == 2


def test_border_of_chaos_item(tmp_path):
    """The report's border-of-chaos section: the Hess branch splits only off the Hess
    direction, as Melnikov says; the chaotic fraction grows with mu."""
    import json

    out = tmp_path / "paper"
    assert main(["paper", "--out", str(out), "--quick", "--only", "border"]) == 0
    names = {p.name for p in out.iterdir()}
    assert {"border-of-chaos.png", "splitting-vs-epsilon.nc", "border-of-chaos.nc",
            "frequency-map.nc"} <= names
    import xarray as xr
    with xr.open_dataset(out / "splitting-vs-epsilon.nc") as sp:
        assert float(sp.amplitude[0, 0]) < 1e-12                  # epsilon = 0
        assert float(sp.relative_error[1, 0]) < 0.02               # epsilon = 0.2
    with xr.open_dataset(out / "border-of-chaos.nc") as b:
        f = b.chaotic_fraction.values
        assert np.all(f[1] >= f[0]) and f[1].sum() > f[0].sum()     # mu = 0.1 vs 0.01
    numbers = json.loads((out / "summary.json").read_text())["items"]["border"]["numbers"]
    assert numbers["border_splitting_eps0"] < 1e-12
    assert "border of chaos" in (out / "index.html").read_text()


def test_items_in_two_processes_match_one(tmp_path):
    """Two processes build the same report as one (the schedule changes nothing but the
    time); the summary lists the items in the report's order."""
    import json

    from andoyer.report.paper import ITEMS, build_paper, default_jobs

    only = ["heteroclinic", "fig2", "paper-check"]
    numbers = []
    for jobs in (1, 2):
        _, done = build_paper(tmp_path / f"j{jobs}", quick=True, only=only, jobs=jobs,
                              progress=False)
        assert [i.key for i, _, _ in done] == [i.key for i in ITEMS if i.key in only]
        summary = json.loads((tmp_path / f"j{jobs}" / "summary.json").read_text())
        numbers.append({k: v["numbers"] for k, v in summary["items"].items()})
    assert numbers[0] == numbers[1]
    assert default_jobs([i for i in ITEMS if i.key in only]) == 1  # 0.8 s: no worker
    with pytest.raises(ValueError, match="jobs"):
        build_paper(tmp_path / "bad", only=only, jobs=0, progress=False)


def test_report_names_the_engine_that_ran(tmp_path):
    """Without heyoka (here: engine="numba") no line of the report says heyoka ran: the
    prose takes the engine from the runs themselves (issue 24, "Words")."""
    from andoyer.report.html import render_item
    from andoyer.report.paper import build_paper

    _, done = build_paper(tmp_path / "p", quick=True, only=["heteroclinic", "chaos"],
                          engine="numba", progress=False, jobs=1)
    body = RigidBody.paper()
    texts = {item.key: render_item(item, res, dt, body) for item, res, dt in done}
    assert "integration of the Euler-Poisson equations (numba, tol 1e-13)" in \
        texts["heteroclinic"]
    assert "variational equations of (1) (numba, tol 1e-12" in texts["chaos"]
    page = (tmp_path / "p" / "index.html").read_text(encoding="utf-8")
    summary = (tmp_path / "p" / "summary.json").read_text(encoding="utf-8")
    for text in (*texts.values(), page, summary):
        assert "heyoka" not in text
    assert '"engine": "numba"' in summary


def test_report_prose_names_no_engine():
    """The item templates never write an engine's name: it is a value of the run."""
    from importlib.resources import files

    folder = files("andoyer.report") / "templates"
    names = [f for d in (folder, folder / "items") for f in d.iterdir()
             if f.name.endswith(".j2")]
    assert len(names) >= 10
    for f in names:
        text = f.read_text(encoding="utf-8").lower()
        for engine in ("heyoka", "numba", "scipy", "dop853"):
            assert engine not in text, (f.name, engine)


@pytest.mark.slow
def test_resonances_item(tmp_path, monkeypatch):
    """The resonances item: measured half-widths within 4 % of the first-order prediction
    (quick: the 3:1 chain at mu = 1e-3), the normal form's error falling like amplitude^N
    (fitted slopes within 0.3 of N = 2 .. 8), the resonant normal form of the tilted body's
    2:1 chain near the centre against the torus route and the sections, and a readable
    figure (fails when the report's resonant normal form is taken at degree 4)."""
    from _figures import overlapping_texts
    from andoyer.report.base import Context

    figures = {}
    save = Context.figure

    def keep(self, fig, name):
        figures[name] = fig
        return save(self, fig, name)

    monkeypatch.setattr(Context, "figure", keep)
    out = tmp_path / "paper"
    assert main(["paper", "--out", str(out), "--quick", "--only", "resonances",
                 "--engine", "numba", "--jobs", "1"]) == 0
    assert overlapping_texts(figures["resonances"]) == []
    summary = json.loads((out / "summary.json").read_text())
    text = json.dumps(summary)
    assert "half_width_3:1_mu_0.001" in text
    html = (out / "index.html").read_text()
    assert "multiplies it by \\(2^{ 4.0 }\\)" in html and "multiplies it by \\(2^{ 8.0 }\\)" in html
    numbers = summary["items"]["resonances"]["numbers"]
    # Birkhoff at growing amplitude (0.05 to 0.2 rad): the fitted slope is the order
    for order in (2, 4, 6, 8):
        assert abs(numbers[f"birkhoff_slope_order_{order}"] - order) < 0.3, order
    # the resonant normal form near the centre: the torus route to its truncation
    # (5.3e-4 at I* = 0.27), the sections to the edge resolution plus that truncation
    nf, torus = (numbers["normal_form_half_width_2:1_mu_0.001"],
                 numbers["torus_half_width_2:1_mu_0.001"])
    measured = numbers["half_width_near_centre_2:1_mu_0.001"]
    unc = numbers["edge_uncertainty_near_centre_2:1_mu_0.001"]
    assert 1e-4 < abs(nf / torus - 1) < 1e-3
    assert abs(measured - nf) < unc + 1e-3 * nf
    assert "near the centre" in html



def test_the_sections_items_take_the_angle_sections_measured_engine():
    """The resonances and last-torus items integrate single orbits' g sections: without
    --engine they run on the angle sections' default (MEASURED_DEFAULTS where heyoka is
    installed), which --engine overrides; a workload's engine lacking the capability is
    not taken."""
    from pathlib import Path

    from andoyer.integrate.engines import default_engine_name
    from andoyer.integrate.engines.base import Capability
    from andoyer.report.base import Context

    ctx = Context(Path("."), RigidBody.paper())
    for cap in (Capability.CROSSINGS, Capability.TANGENT_CROSSINGS):
        assert ctx.engine_name(cap, workload="angle_section") == \
            default_engine_name(cap, workload="angle_section")
    assert Context(Path("."), RigidBody.paper(), "numba").engine_name(
        Capability.CROSSINGS, workload="angle_section") == "numba"
    # taylor has no extended precision: the workload's engine is not taken for it
    assert ctx.engine_name(Capability.EXTENDED_PRECISION, workload="angle_section") != "taylor"
    import inspect

    from andoyer.report.items import resonance, torus
    for module in (resonance, torus):
        assert 'workload="angle_section"' in inspect.getsource(module)
