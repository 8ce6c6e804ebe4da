"""``andoyer last-torus --h-values`` writes mu_c(h); ``andoyer atlas --last-torus`` draws
it on the border of chaos; a foreign, damaged or other file ends in one line naming it,
exit 2, never a traceback."""

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from andoyer import RigidBody
from andoyer.cli import main
from andoyer.io import write_netcdf
from andoyer.scan import run_scan

BORDER = {"body": {"kind": "hess", "name": "rho~1"},
          "parameters": {"A": 2.5, "B": 1.0, "C": 1.6, "mu": [0.01, 0.05],
                         "epsilon": 0.0, "h": [0.3125, 0.4]},
          "task": {"kind": "chaos_border", "n": [8, 6], "t_end": 60.0}}


@pytest.fixture(scope="module")
def border_store(tmp_path_factory) -> Path:
    store = tmp_path_factory.mktemp("border-h") / "border.zarr"
    run_scan(BORDER, store, scheduler="serial", progress=False)
    return store


def _curve_file(path: Path, **attrs) -> Path:
    h = np.array([0.3125, 0.35, 0.4])
    body = RigidBody.hess(2.5, 1.0, 1.6, mu=0.01)
    ds = xr.Dataset({"mu_critical": ("h_level", 0.08 * h),
                     "mu_critical_error": ("h_level", 0.002 * h)}, coords={"h_level": h},
                    attrs={"kind": "critical_mu_curve", "M": 0.0,
                           **{f"body_{k}" if k != "body_name" else k: v
                              for k, v in body.attrs().items()}, **attrs})
    write_netcdf(ds, path)
    return path


def test_atlas_draws_the_curve_from_its_file(border_store, tmp_path, capsys):
    curve = _curve_file(tmp_path / "muc.nc")
    out = tmp_path / "b.png"
    assert main(["atlas", str(border_store), "--rows", "mu", "--cols", "h_level",
                 "--last-torus", str(curve), "--out", str(out)]) == 0
    assert out.stat().st_size > 10_000
    assert "wrote" in capsys.readouterr().out


def _fails(argv, capsys):
    with pytest.raises(SystemExit) as info:
        main(argv)
    assert info.value.code == 2
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if line.strip()]
    assert "Traceback" not in err and len(lines) == 1
    return lines[0]


def test_atlas_refuses_a_foreign_damaged_or_other_file(border_store, tmp_path, capsys):
    base = ["atlas", str(border_store), "--rows", "mu", "--cols", "h_level",
            "--out", str(tmp_path / "b.png")]
    text = tmp_path / "notes.nc"
    text.write_text("not a netcdf file\n")
    assert "notes.nc" in _fails([*base, "--last-torus", str(text)], capsys)
    good = _curve_file(tmp_path / "good.nc")
    damaged = tmp_path / "damaged.nc"
    damaged.write_bytes(good.read_bytes()[:200])
    assert "damaged.nc" in _fails([*base, "--last-torus", str(damaged)], capsys)
    other = tmp_path / "other.nc"
    write_netcdf(xr.Dataset({"x": ("t", [1.0, 2.0])}), other)
    line = _fails([*base, "--last-torus", str(other)], capsys)
    assert "other.nc" in line and "critical_mu_curve" in line
    broken = _curve_file(tmp_path / "broken.nc")
    ds = xr.load_dataset(broken).drop_vars("mu_critical_error")
    broken.unlink()
    write_netcdf(ds, broken)
    line = _fails([*base, "--last-torus", str(broken)], capsys)
    assert "broken.nc" in line and "mu_critical_error" in line
    assert "no such file" in _fails([*base, "--last-torus", str(tmp_path / "none.nc")], capsys)
    elsewhere = _curve_file(tmp_path / "m.nc", M=0.3)
    assert "M = 0.3" in _fails([*base, "--last-torus", str(elsewhere)], capsys)
    # not the axes of mu_c(h), or not the border of chaos
    line = _fails(["atlas", str(border_store), "--cols", "epsilon", "--rows", "mu",
                   "--last-torus", str(good), "--out", str(tmp_path / "c.png")], capsys)
    assert "h_level and mu" in line or "epsilon" in line
    line = _fails([*base, "--maps", "--last-torus", str(good)], capsys)
    assert "--last-torus" in line


def test_last_torus_command_writes_the_curve(tmp_path, capsys, monkeypatch):
    """--h-values: the curve (one last_torus, scaled on M = 0), printed and written."""
    out = tmp_path / "muc.nc"
    assert main(["last-torus", "--body", "hess", "--A", "3", "--B", "1", "--C", "2",
                 "--mu", "0.002", "--h-values", "1,2", "--mu-range", "0.01", "1",
                 "--axis", "2", "--n-convergents", "2", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "scaled" in text and "wrote" in text
    ds = xr.open_dataset(out)
    assert ds.attrs["kind"] == "critical_mu_curve" and list(ds.h_level.values) == [1.0, 2.0]
    np.testing.assert_allclose(ds.mu_critical[1], 2 * ds.mu_critical[0], rtol=1e-12)


@pytest.mark.parametrize("argv, message", [
    (["--h-values", "x"], "--h-values"),
    (["--h-values", "1,2"], "--mu-range"),
    (["--h-values", "1,2", "--energy", "1", "--mu-range", "0.01", "1"], "--energy"),
    (["--h-values", "2,1", "--mu-range", "0.01", "1"], "h_values"),
])
def test_last_torus_curve_refuses_bad_input(tmp_path, capsys, argv, message):
    with pytest.raises(SystemExit) as info:
        main(["last-torus", "--body", "hess", "--A", "3", "--B", "1", "--C", "2", "--mu",
              "0.002", *argv, "--out", str(tmp_path / "t.nc")])
    assert info.value.code == 2
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if line.strip()]
    assert "Traceback" not in err and message in lines[-1]
