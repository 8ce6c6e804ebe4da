"""Parameter scans: configuration checks, Zarr store, Dask runs, resume, atlas figure.

The reference is a serial scan (no Dask) of a tiny grid; it is checked point by point
against the public API (fill_section + poincare), then every other way of running the
scan (a LocalCluster of 2 workers, a killed and resumed process, a killed worker, other
chunkings) must give exactly the same store.
"""

from __future__ import annotations

import copy
import os
import shutil
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from andoyer import RigidBody
from andoyer.cli import main
from andoyer.integrate import fill_section, poincare
from andoyer.integrate.engines import default_engine_name
from andoyer.integrate.engines.base import Capability
from andoyer.scan import estimate_cost, load_config, run_scan
from andoyer.scan.cost import check_size
from andoyer.scan.store import Schema, Variable, _check_names

# 2 x 2 grid; 5 orbits (one SIMD batch of 4 plus a refilled lane) x 20 crossings.
TINY = {"body": {"kind": "hess", "name": "paper"},
        "parameters": {"mu": [0.01, 0.3], "h": [0.3, 0.5]},
        "task": {"kind": "section", "section": "theta2=0", "n_orbits": 5, "n_crossings": 20}}


def _toml(cfg: dict) -> str:
    """The TOML text of a (two-level) configuration."""
    def val(v: object) -> str:
        if isinstance(v, dict):
            return "{" + ", ".join(f"{k} = {val(x)}" for k, x in v.items()) + "}"
        if isinstance(v, str):
            return f'"{v}"'
        if isinstance(v, list):
            return "[" + ", ".join(val(x) for x in v) + "]"
        return repr(v)
    return "\n".join(f"[{name}]\n" + "\n".join(f"{k} = {val(v)}" for k, v in table.items())
                     for name, table in cfg.items()) + "\n"


def _with(cfg: dict, table: str, **changes: object) -> dict:
    out = copy.deepcopy(cfg)
    out.setdefault(table, {}).update(changes)
    return out


def assert_same_store(a: Path | xr.Dataset, b: Path | xr.Dataset, *,
                      ignore_attrs: tuple[str, ...] = ()) -> None:
    """Every variable equal to the bit (NaN where NaN), same dtypes, same attrs (but
    ``created`` and ``ignore_attrs``)."""
    da = a if isinstance(a, xr.Dataset) else xr.open_zarr(a).load()
    db = b if isinstance(b, xr.Dataset) else xr.open_zarr(b).load()
    assert sorted(da.variables) == sorted(db.variables)
    for name in da.variables:
        x, y = da[name], db[name]
        assert x.dims == y.dims and x.dtype == y.dtype, name
        assert np.array_equal(x.values, y.values, equal_nan=x.dtype.kind == "f"), name
        assert x.attrs == y.attrs, name
    drop = ("created", *ignore_attrs)
    assert ({k: v for k, v in da.attrs.items() if k not in drop}
            == {k: v for k, v in db.attrs.items() if k not in drop})


@pytest.fixture(scope="module")
def reference(tmp_path_factory) -> Path:
    """The tiny scan, run serially."""
    store = tmp_path_factory.mktemp("scan") / "reference.zarr"
    report = run_scan(TINY, store, scheduler="serial", progress=False)
    assert (report.tasks, report.computed, report.resumed) == (4, 4, 0)
    return store


@pytest.fixture(scope="module")
def client():
    """A LocalCluster of 2 single-threaded workers (threads: cheap to start)."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as c:
        yield c


# ---------------------------------------------------------------------- the numbers
@pytest.mark.parametrize("i, j", [(1, 1), (0, 0)])
def test_each_point_is_the_public_api_result(reference, i, j):
    """Stored section = fill_section + poincare (default engine, its own threads)."""
    ds = xr.open_zarr(reference)
    mu, h = float(ds.mu[i]), float(ds.h_level[j])
    body = RigidBody.paper(mu)
    fill = fill_section(body, h, 0.0, ("theta2", 0.0), n_orbits=5, sampling="sobol", seed=0,
                        boundary_grid=64)
    # The scan's engine (its default also has tangent flows: taylor where heyoka is
    # absent, as a bare poincare's default there).
    engine = default_engine_name(Capability.TANGENT, Capability.TANGENT_CROSSINGS)
    direct = poincare(body, fill["y0"].values[:5], "theta2=0", 20, engine=engine)
    point = ds.isel(mu=i, h_level=j).load()
    assert int(point.n_orbits) == 5
    for name in ("t", "theta1", "J1", "J2", "G1", "gamma3", "H", "l_angle", "L_action",
                 "section_residual", "crossings_found", "y0"):
        assert np.array_equal(point[name].values, direct[name].values, equal_nan=True), name
    # The physics holds too: on the section, on the energy level.
    assert float(abs(point.section_residual).max()) < 1e-12
    assert float(abs(point.H - h).max()) < 1e-10


def test_orbits_are_a_fixed_number_of_fill_rows():
    from andoyer.scan.tasks import _pick_orbits

    rows = np.arange(10.0)[:, None] * np.ones((1, 6))
    assert list(_pick_orbits(rows, 4, "sobol")[:, 0]) == [0, 1, 2, 3]  # a QMC prefix
    assert list(_pick_orbits(rows, 4, "grid")[:, 0]) == [0, 3, 6, 9]   # spread on the plane
    assert _pick_orbits(rows[:3], 4, "grid").shape == (3, 6)           # fewer: all, padded


def test_store_is_self_describing(reference):
    ds = xr.open_zarr(reference)
    cfg = load_config(TINY)
    assert dict(ds.sizes) == {"mu": 2, "h_level": 2, "orbit": 5, "crossing": 20,
                              "component": 6}
    assert ds.theta1.dims == ("mu", "h_level", "orbit", "crossing")
    assert list(ds.mu.values) == [0.01, 0.3] and list(ds.h_level.values) == [0.3, 0.5]
    assert ds.h_level.attrs["long_name"] == "energy level H = h"
    assert ds.theta1.attrs["equation"] == "(14)"
    assert ds.attrs["scan_config"] == cfg.to_json()
    assert ds.attrs["engine"] == cfg.integrator.engine and ds.attrs["rtol"] == 1e-12
    assert ds.attrs["andoyer_version"] and ds.attrs["body_mu"] == "swept: coordinate mu"
    assert ds.attrs["body_A"] == 2.5 and ds.attrs["M_level"] == 0.0
    assert ds.attrs["section_coord"] == "theta2"
    assert bool(ds.done.all()) and not bool(ds.empty.any())
    # Names differ ignoring case (Zarr directories on case-insensitive file systems).
    names = [str(n) for n in ds.variables]
    assert len({n.lower() for n in names}) == len(names)
    # The configuration can be read back from the store.
    assert type(cfg).from_json(ds.attrs["scan_config"]) == cfg


def test_case_collisions_are_refused():
    cfg = load_config(TINY)
    v = Variable((), (), np.dtype(float), {})
    with pytest.raises(ValueError, match="differ only by case"):
        _check_names(cfg, Schema({"x": v, "X": v}, {}))
    with pytest.raises(ValueError, match="differ only by case"):
        _check_names(cfg, Schema({"H_LEVEL": v}, {}))


def test_cluster_gives_the_serial_store(reference, client, tmp_path):
    """2 workers, tasks of 2 points each: the serial store to the bit."""
    cfg = _with(TINY, "store", chunks={"h": 2})
    report = run_scan(cfg, tmp_path / "cluster.zarr", client=client, max_in_flight=1,
                  progress=False)
    assert (report.tasks, report.computed) == (2, 2)
    assert xr.open_zarr(tmp_path / "cluster.zarr").theta1.encoding["chunks"] == (1, 2, 5, 20)
    assert_same_store(reference, tmp_path / "cluster.zarr",
                      ignore_attrs=("scan_config",))


# ---------------------------------------------------------------------- resume
def _region_write(store: Path, name: str, value: object, **region: int) -> None:
    ds = xr.open_zarr(store)
    v = ds[name]
    sl = {d: slice(i, i + 1) for d, i in region.items()}
    shape = tuple(1 if d in sl else ds.sizes[d] for d in v.dims)
    xr.Dataset({name: (v.dims, np.full(shape, value, dtype=v.dtype))}).to_zarr(
        store, region=sl, mode="r+", consolidated=False)


def test_resume_recomputes_unmarked_chunks_only(reference, tmp_path):
    store = tmp_path / "s.zarr"
    shutil.copytree(reference, store)
    # Chunk (0, 1): data half-written, no mark -> recomputed.
    _region_write(store, "theta1", -1.0, mu=0, h_level=1)
    _region_write(store, "done", False, mu=0, h_level=1)
    # Chunk (1, 0): marked done -> trusted, not recomputed (garbage stays).
    _region_write(store, "J1", 99.0, mu=1, h_level=0)
    (store / "J1" / "c" / "leftover.abc.partial").write_bytes(b"x")
    report = run_scan(TINY, store, scheduler="serial", progress=False)
    assert (report.resumed, report.computed) == (3, 1)
    ds = xr.open_zarr(store).load()
    ref = xr.open_zarr(reference).load()
    assert np.array_equal(ds.theta1, ref.theta1, equal_nan=True)
    assert bool(ds.done.all())
    assert float(ds.J1[1, 0].max()) == 99.0
    assert not list(store.rglob("*.partial"))
    # A complete store: nothing to do.
    assert run_scan(TINY, store, scheduler="serial").computed == 0


def test_chunk_cut_between_data_and_mark_is_recomputed(reference, tmp_path, monkeypatch):
    """The mark is written after the data: a run stopped in between leaves the chunk
    unmarked, and the resume computes it again (and only what is missing)."""
    calls: list[tuple[str, ...]] = []
    write = xr.Dataset.to_zarr

    def cut(self, *args, **kwargs):
        calls.append(tuple(sorted(map(str, self.data_vars))))
        if calls.count(("done",)) == 2:
            raise RuntimeError("power cut")
        return write(self, *args, **kwargs)

    monkeypatch.setattr(xr.Dataset, "to_zarr", cut)
    store = tmp_path / "s.zarr"
    with pytest.raises(RuntimeError, match="power cut"):
        run_scan(TINY, store, scheduler="serial", progress=False)
    # Layout, then (data, mark) per chunk; the second mark never came.
    assert [c == ("done",) for c in calls[1:]] == [False, True, False, True]
    assert "theta1" in calls[1] and "empty" in calls[1]
    monkeypatch.setattr(xr.Dataset, "to_zarr", write)
    done = xr.open_zarr(store).done.values
    assert done.sum() == 1
    report = run_scan(TINY, store, scheduler="serial", progress=False)
    assert (report.resumed, report.computed) == (1, 3)
    assert_same_store(reference, store)


def test_progress_line(capsys):
    from andoyer.progress import Progress

    bar = Progress(4, "scan", True, postfix="Dask dashboard http://127.0.0.1:8787/status",
                   initial=1)
    bar.update()
    bar.close()
    err = capsys.readouterr().err
    # stderr is no terminal here: one plain line, counting the unit resumed
    assert err.startswith("[2/4] scan: 50 %") and err.count("\n") == 1, err
    assert err.rstrip().endswith("; Dask dashboard http://127.0.0.1:8787/status")


def test_resume_refuses_another_configuration(reference, tmp_path):
    store = tmp_path / "s.zarr"
    shutil.copytree(reference, store)
    other = _with(_with(TINY, "task", n_crossings=30), "parameters", mu=[0.01])
    with pytest.raises(ValueError, match=r"another configuration \(parameters.mu: \[0.01, "
                                         r"0.3\] in the store, \[0.01\] now; task.n_crossings: "
                                         r"20 in the store, 30 now\).*--overwrite"):
        run_scan(other, store, scheduler="serial")
    report = run_scan(other, store, scheduler="serial", overwrite=True, progress=False)
    assert report.computed == 2 and xr.open_zarr(store).sizes["crossing"] == 30


def test_never_removes_what_is_not_a_scan_store(tmp_path):
    folder = tmp_path / "data.zarr"
    folder.mkdir()
    (folder / "precious.txt").write_text("keep")
    for overwrite in (False, True):
        with pytest.raises(ValueError, match="not an andoyer scan store"):
            run_scan(TINY, folder, scheduler="serial", overwrite=overwrite)
    assert (folder / "precious.txt").read_text() == "keep"


def _done_files(store: Path) -> int:
    return len([p for p in (store / "done" / "c").rglob("*") if p.is_file()]) \
        if (store / "done" / "c").exists() else 0


@pytest.mark.slow
def test_killed_process_resumes_to_the_same_store(tmp_path):
    """`andoyer scan` killed (SIGKILL) mid-way, rerun: the uninterrupted store."""
    cfg = _with(TINY, "parameters", mu=[0.01, 0.1, 0.3, 0.6])
    (tmp_path / "cfg.toml").write_text(_toml(cfg))
    store = tmp_path / "killed.zarr"
    cmd = [sys.executable, "-m", "andoyer", "scan", str(tmp_path / "cfg.toml"), "--store",
           str(store), "--scheduler", "serial", "--no-progress"]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 120
        while _done_files(store) < 1 and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.005)
        proc.send_signal(signal.SIGKILL)
    finally:
        proc.communicate(timeout=60)
    partial = _done_files(store)
    assert 1 <= partial < 8, "the scan was not interrupted mid-way"
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=300, check=True)
    assert f"{8 - partial} computed now, {partial} done before" in out.stdout
    run_scan(cfg, tmp_path / "whole.zarr", scheduler="serial", progress=False)
    assert_same_store(tmp_path / "whole.zarr", store)


@pytest.mark.slow
def test_worker_killed_mid_task_loses_nothing(reference, tmp_path):
    """A worker process killed while it runs a task: the task is rerun elsewhere."""
    distributed = pytest.importorskip("distributed")
    store = tmp_path / "s.zarr"
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as c:
        pids = c.run(os.getpid)
        out: dict = {}
        thread = threading.Thread(target=lambda: out.update(
            report=run_scan(TINY, store, client=c, max_in_flight=2, progress=False)))
        thread.start()
        deadline = time.monotonic() + 60
        busy: list = []
        while not busy and time.monotonic() < deadline:
            busy = [w for w, keys in c.processing().items() if keys]
            time.sleep(0.01)
        assert busy, "no task started"
        victim = busy[0]
        os.kill(pids[victim], signal.SIGKILL)
        thread.join(timeout=240)
        assert "report" in out
    assert out["report"].computed == 4
    assert_same_store(reference, store)


# ---------------------------------------------------------------------- empty points
def test_points_that_miss_the_section_are_stored_empty(tmp_path):
    # At M = 0.5 the level h = 0.041 lies below the section's minimum of H (~0.0418).
    cfg = {"parameters": {"mu": 0.01, "M": 0.5, "h": [0.041, 0.05]},
           "task": {"kind": "section", "n_orbits": 3, "n_crossings": 5}}
    report = run_scan(cfg, tmp_path / "e.zarr", scheduler="serial", progress=False)
    assert len(report.empty) == 1 and "does not intersect the section" in report.empty[0][1]
    ds = xr.open_zarr(tmp_path / "e.zarr").load()
    assert list(ds.empty.values) == [True, False] and bool(ds.done.all())
    assert bool(ds.theta1[0].isnull().all()) and int(ds.n_orbits[0]) == 0
    assert bool(ds.theta1[1].notnull().any())
    nothing = _with(cfg, "parameters", h=[0.0405, 0.041])
    with pytest.raises(ValueError, match="no point of the scan had anything to compute"):
        run_scan(nothing, tmp_path / "n.zarr", scheduler="serial")
    assert not (tmp_path / "n.zarr").exists()


# ---------------------------------------------------------------------- bad configs
BAD = [
    (_with(TINY, "integrater", engine="heyoka"), r"unknown key 'integrater' \(did you mean "
                                                 r"'integrator'\?\)"),
    (_with(TINY, "parameters", nu=0.1), r"\[parameters\]: unknown key 'nu' \(did you mean "
                                        r"'mu'\?\)"),
    (_with(TINY, "task", orbit=3), r"unknown key 'orbit' \(did you mean 'n_orbits'\?\)"),
    (_with(TINY, "task", kind="sections"), r"unknown kind 'sections' \(did you mean "
                                           r"'section'\?\)"),
    (_with(TINY, "task", kind="splitting"), r"\[parameters\] h: the splitting task does "
                                            r"not take it \(its level is h = c G\^2 / 2"),
    ({"body": {"kind": "general", "r": [0.6, 0.0, 0.8]},
      "parameters": {"A": 2.5, "B": 2.0, "C": 2.2, "mu": [0.01, 0.02]},
      "task": {"kind": "splitting"}}, "the splitting task needs a Hess body"),
    ({"body": {"kind": "general", "r": [0.6, 0.8, 0.0]},
      "parameters": {"A": 2.5, "B": 2.0, "C": 2.2, "mu": [0.01, 0.02], "epsilon": 0.1,
                     "h": 0.3},
      "task": {"kind": "chaos_border"}}, "epsilon turns a Hess body's centre of mass"),
    (TINY | {"task": {"kind": "chaos_border", "section": "G3=0"}}, "'theta2=VALUE'"),
    (TINY | {"task": {"kind": "chaos_border", "margin": 0.0}}, "margin must be"),
    ({"parameters": {"mu": [0.0, 0.01]}, "task": {"kind": "splitting"}},
     r"needs mu > 0 \(at mu = 0 the separatrices coincide\)"),
    ({"parameters": {"mu": [0.01, 0.02]}, "task": {"kind": "splitting", "n_phase": 7}},
     "n_phase must be even"),
    (_with(TINY, "integrator", engine="scipy") | {"parameters": {"mu": [0.01, 0.02]},
                                                  "task": {"kind": "splitting"}},
     "the splitting task grows the manifolds with heyoka or numba"),
    (_with(TINY, "task", n_orbits=0), "n_orbits must be an integer >= 1"),
    (_with(TINY, "task", section="J3=0"), "unknown section coordinate"),
    (_with(TINY, "task", section="G3=0"), "'theta2=VALUE'"),
    (_with(TINY, "parameters", C=[2.2, 2.6]), r"grid point A = 2.5, B = 2, C = 2.6, "
                                              r"mu = 0.01 makes no hess body: .*A > C > B"),
    ({"body": {"kind": "general", "r": [1.0, 0.0, 0.0]},
      "parameters": {"A": [1.0, 2.5], "B": 1.0, "C": 1.0, "mu": 0.1, "h": 1.0},
      "task": {"kind": "section", "section": "g=0"}}, "triangle inequality"),
    ({"body": {"kind": "general", "r": [0.0, 0.6, 0.8]},
      "parameters": {"A": [1.0, 1.5], "B": 1.2, "C": 1.3, "mu": 0.1, "h": 1.0},
      "task": {"kind": "section"}}, r"needs the centre of mass in the G1-G2 plane"),
    ({"body": {"kind": "general", "r": [1.0, 0.0, 0.0]}, "parameters": {"h": [1.0, 2.0]},
      "task": {"kind": "section"}}, r"needs mu, A, B, C \(a general body"),
    (_with(TINY, "parameters", h=[-0.5, 0.3]), r"h = -0.5 at mu = 0.01 is below the "
                                               r"minimum -mu of H"),
    (_with(TINY, "parameters", M=2.0), "M = 2 is out of reach on the level h = 0.3"),
    (_with(TINY, "parameters", h=[0.3, 0.3]), r"repeated values \[0.3\]"),
    (_with(TINY, "parameters", mu=[]), "an empty list sweeps nothing"),
    (_with(TINY, "parameters", mu=0.1, h=0.3), r"sweeps nothing: give at least one"),
    (_with(TINY, "parameters", mu={"start": 0, "stop": 1}), "missing num"),
    (_with(TINY, "parameters", mu={"start": 0.0, "stop": 1.0, "num": 2000},
           h={"start": 0.3, "stop": 1.0, "num": 1000}),
     r"2000 x 1000 = 2000000 points, more than 1000000"),
    (_with(TINY, "integrator", engine="rk4"), "engine must be one of heyoka, numba, scipy"),
    (_with(TINY, "store", chunks={"A": 2}), "'A' is not a swept parameter"),
]


@pytest.mark.parametrize("cfg, message", BAD)
def test_bad_configurations_are_refused_clearly(cfg, message):
    with pytest.raises(ValueError, match=message):
        load_config(cfg)


CHAOS = {"parameters": {"mu": [0.01, 0.3], "h": 0.5},
         "task": {"kind": "chaos_map", "n": [4, 3], "t_end": 20.0}}


@pytest.fixture(scope="module")
def chaos_store(tmp_path_factory) -> Path:
    store = tmp_path_factory.mktemp("chaos") / "chaos.zarr"
    run_scan(CHAOS, store, scheduler="serial", progress=False)
    return store


@pytest.mark.parametrize("i", [0, 1])
def test_chaos_map_points_are_the_public_api_result(chaos_store, i):
    from andoyer.analysis.chaos.lyapunov import IndicatorRun, chaos_map

    ds = xr.open_zarr(chaos_store).isel(mu=i).load()
    direct = chaos_map(RigidBody.paper(float(ds.mu)), 0.5, 0.0, "theta2=0", (4, 3),
                       IndicatorRun(t_end=20.0))  # default threads: results do not depend on them
    assert ds.fli.dims == ("J1", "theta1")
    for name in ("fli", "mle", "J2", "accessible"):
        assert np.array_equal(ds[name].values, direct[name].values, equal_nan=True), name
    assert np.array_equal(ds.theta1_values.values, direct.theta1.values)
    assert np.array_equal(ds.J1_values.values, direct.J1.values)
    assert int(ds.n_failed) == 0 and int(ds.n_accessible) == int(direct.accessible.sum())
    assert xr.open_zarr(chaos_store).attrs["indicator"] == "fli"


def test_chaos_atlas_draws_images(chaos_store):
    from andoyer.plot.atlas import plot_atlas

    fig = plot_atlas(xr.open_zarr(chaos_store))
    panels = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
    assert len(panels) == 2 and all(len(ax.collections) == 1 for ax in panels)
    assert panels[0].get_xlabel() == r"$\theta_1$" and panels[0].get_ylabel() == "$J_1$"


BORDER = {"body": {"kind": "hess", "name": "rho~1"},
          "parameters": {"A": 2.5, "B": 1.0, "C": 1.6, "mu": [0.01, 0.05],
                         "epsilon": [0.0, 0.3], "h": 0.3125},
          "task": {"kind": "chaos_border", "n": [8, 6], "t_end": 60.0}}


@pytest.fixture(scope="module")
def border_store(tmp_path_factory) -> Path:
    store = tmp_path_factory.mktemp("border") / "border.zarr"
    run_scan(BORDER, store, scheduler="serial", progress=False)
    return store


def test_border_scan_points_are_the_public_api_result(border_store):
    from andoyer.analysis.chaos.border import chaos_border

    ds = xr.open_zarr(border_store).load()
    assert ds.epsilon.attrs["units"] == "rad" and ds.chaotic_fraction.dims == ("mu", "epsilon")
    for i, j in ((0, 0), (1, 1)):
        p = ds.isel(mu=i, epsilon=j)
        body = RigidBody.near_hess(2.5, 1.0, 1.6, float(p.mu), float(p.epsilon))
        direct = chaos_border(body, 0.3125, 0.0, n=(8, 6), t_end=60.0)
        for name in ("megno", "chaotic", "chaotic_fraction", "layer_width", "threshold",
                     "hess_line"):
            assert np.array_equal(p[name].values, direct[name].values, equal_nan=True), name
        assert np.allclose([float(p.e1), float(p.e2)], body.r[:2], rtol=0, atol=1e-15)
    # the turned line: theta1 = 2 epsilon
    assert float(ds.hess_line[0, 1]) == pytest.approx(0.6, abs=1e-12)


def test_border_atlas_draws_the_fraction_and_the_width(border_store, tmp_path, capsys):
    from andoyer.plot.atlas import plot_border

    fig = plot_border(xr.open_zarr(border_store))
    panels = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
    assert len(panels) == 2 and panels[0].get_xlabel().startswith(r"$\epsilon$")
    assert panels[0].get_ylabel() == r"$\mu$"
    assert main(["atlas", str(border_store), "--out", str(tmp_path / "b.png")]) == 0
    assert (tmp_path / "b.png").stat().st_size > 10_000
    assert main(["atlas", str(border_store), "--maps", "--out", str(tmp_path / "m.png")]) == 0
    with pytest.raises(ValueError, match="not of a chaos_border scan"):
        plot_border(xr.open_zarr(border_store).assign_attrs(scan_task="chaos_map"))


@pytest.mark.slow
def test_splitting_scan_scales_with_mu(tmp_path):
    """Splitting at two mu: the public API's numbers; first order in mu (Melnikov)."""
    from andoyer.analysis.splitting.measure import separatrix_splitting

    cfg = {"parameters": {"mu": [0.005, 0.01]},
           "task": {"kind": "splitting", "n_phase": 8, "delta": 1e-4,
                    "branch": "theta1=4phi0"}}
    ds = run_scan(cfg, tmp_path / "s.zarr", scheduler="serial", progress=False).open().load()
    direct = separatrix_splitting(RigidBody.paper(), [0.01], n_phase=8, delta=1e-4,
                                  branch="theta1=4phi0")
    assert np.array_equal(ds.Delta_G[1].values, direct["splitting"].Delta_G[0].values)
    ratio = float(ds.amplitude[1] / ds.amplitude[0])
    assert 1.6 < ratio < 2.2  # Delta_G = mu M / (c G) (1 + O(mu))
    assert ds.attrs["branch"] == "theta1=4phi0" and "h_level" not in ds.dims


def test_unreasonable_cost_is_refused_with_its_estimate():
    cfg = load_config(_with(TINY, "task", n_orbits=1000, n_crossings=100000))
    cost = estimate_cost(cfg)
    # 4 points x 1e8 crossings x 5e-5 s and 25 stored values of 8 bytes each.
    assert cost.core_seconds == pytest.approx(4 * (0.1 + 5e3))
    assert cost.store_bytes == pytest.approx(4 * 25 * 1e8 * 8)
    with pytest.raises(ValueError, match=r"unreasonably large: 2 x 2 grid, 4 points in 4 "
                                         r"tasks: about 5.56 core-hours .*80 GB.*more than "
                                         r"50 GB"):
        check_size(cfg, 100.0, 50.0)
    assert check_size(cfg, 100.0, 100.0) == cost


def test_toml_file_errors_name_the_file(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[task\nkind = 1\n")
    with pytest.raises(ValueError, match="bad.toml: not valid TOML"):
        load_config(bad)
    with pytest.raises(ValueError, match="not found"):
        load_config(tmp_path / "missing.toml")
    good = tmp_path / "good.toml"
    good.write_text(_toml(TINY))
    assert load_config(good) == load_config(TINY)


def test_example_configurations_are_valid():
    for path in sorted(Path(__file__).resolve().parents[2].joinpath("examples").glob("*.toml")):
        cfg = load_config(path)
        check_size(cfg, 1.0, 1.0)  # examples stay small


# ---------------------------------------------------------------------- CLI and atlas
def test_cli_scan_then_atlas(reference, tmp_path, capsys):
    cfg = _with(TINY, "parameters", h=0.3)  # the column h = 0.3 of the reference
    (tmp_path / "tiny.toml").write_text(_toml(cfg))
    store = tmp_path / "tiny.zarr"
    assert main(["scan", str(tmp_path / "tiny.toml"), "--dry-run"]) == 0
    assert "2 points in 2 tasks" in capsys.readouterr().out and not store.exists()
    assert main(["scan", str(tmp_path / "tiny.toml"), "--store", str(store),
                 "--scheduler", "serial", "--no-progress"]) == 0
    assert "2 computed now, 0 done before" in capsys.readouterr().out
    column = xr.open_zarr(reference).isel(h_level=0, drop=True).load()
    assert_same_store(column, store, ignore_attrs=("scan_config", "scan_dims", "title", "h_level"))
    assert xr.open_zarr(store).attrs["h_level"] == 0.3
    png = tmp_path / "atlas.png"
    assert main(["atlas", str(store), "--out", str(png)]) == 0
    assert png.stat().st_size > 10_000
    with pytest.raises(SystemExit) as exc:
        main(["scan", str(tmp_path / "missing.toml")])
    assert exc.value.code == 2
    assert "missing.toml' not found" in capsys.readouterr().err


def test_atlas_panels(reference):
    from andoyer.plot.atlas import plot_atlas

    ds = xr.open_zarr(reference).load()
    ds["done"][0, 1] = False
    # The other sheet of the double cover theta1 in [0, 4 pi) (drawn folded at M = 0).
    ds["theta1"][0, 0, 1:3] += 2 * np.pi
    fig = plot_atlas(ds)
    axes = fig.axes
    assert len(axes) == 4
    assert [ax.get_title() for ax in axes] == [
        "$\\mu = 0.01$, $h = 0.3$", "$\\mu = 0.01$, $h = 0.5$",
        "$\\mu = 0.3$, $h = 0.3$", "$\\mu = 0.3$, $h = 0.5$"]
    (points,) = axes[0].collections
    assert len(points.get_offsets()) == int(ds.theta1[0, 0].notnull().sum())
    # theta1 folded mod 2 pi at M = 0 (H is 2 pi-periodic there).
    assert float(np.max(points.get_offsets()[:, 0])) < 2 * np.pi
    assert not axes[1].collections and axes[1].texts[0].get_text() == "not done"
    one = plot_atlas(ds, rows="h_level", cols="mu")
    assert one.axes[1].get_title() == "$h = 0.3$, $\\mu = 0.3$"
    with pytest.raises(ValueError, match="not a swept dim"):
        plot_atlas(ds, rows="A")


@pytest.mark.parametrize("dry", [[], ["--dry-run"]], ids=["run", "dry run"])
@pytest.mark.parametrize("kind", ["file", "foreign folder"])
def test_cli_scan_refuses_a_path_that_is_not_a_store_before_anything(kind, dry, tmp_path,
                                                                    capsys, monkeypatch):
    """``andoyer scan --store`` on a regular file or a foreign folder printed its cost and
    "computed on a local cluster" lines, then refused: the refusal is now the only line,
    and no cluster is started. A dry run says the same (it used to report the cost and
    exit 0 for a store the run then refused)."""
    distributed = pytest.importorskip("distributed")

    def no_cluster(*args, **kwargs):
        raise AssertionError("a local cluster was started")

    monkeypatch.setattr(distributed, "LocalCluster", no_cluster)
    (tmp_path / "tiny.toml").write_text(_toml(TINY))
    store = tmp_path / "not-a-store"
    if kind == "file":
        store.write_text("keep")
    else:
        store.mkdir()
        (store / "precious.txt").write_text("keep")
    with pytest.raises(SystemExit) as exc:
        main(["scan", str(tmp_path / "tiny.toml"), "--store", str(store), "--no-progress",
              *dry])
    out, err = capsys.readouterr()
    assert exc.value.code == 2
    assert out == "", out
    assert err.splitlines() == [f"andoyer scan: error: {store} exists and is not an andoyer "
                                "scan store; choose another store path"]
    assert (store if kind == "file" else store / "precious.txt").read_text() == "keep"
