"""``andoyer resonances``: the predicted chains written and drawn; bad input ends in a
message, never a traceback."""

import numpy as np
import pytest
import xarray as xr

from andoyer import RigidBody
from andoyer.analysis.resonance import resonance_widths
from andoyer.cli import main


def test_resonances_command_writes_the_predictions(tmp_path, capsys):
    out = tmp_path / "res.nc"
    assert main(["resonances", "--body", "hess", "--A", "3", "--B", "1", "--C", "2",
                 "--mu", "0.001", "--energy", "1", "--max-order", "4",
                 "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "2:1" in text and "(2nd order)" not in text
    ds = xr.open_dataset(out)
    ref = resonance_widths(RigidBody.hess(3.0, 1.0, 2.0, mu=0.001), 1.0, 0.0, "g=0",
                           max_order=4)
    np.testing.assert_allclose(ds.half_width, ref.half_width, rtol=1e-12)
    assert (tmp_path / "res.png").read_bytes()[:4] == b"\x89PNG"


def test_resonances_command_with_a_section(tmp_path):
    out = tmp_path / "res.nc"
    assert main(["resonances", "--body", "hess", "--A", "3", "--B", "1", "--C", "2",
                 "--mu", "0.003", "--energy", "1", "--max-order", "3", "--n-orbits", "4",
                 "--n-crossings", "20", "--engine", "numba", "--out", str(out)]) == 0
    assert (tmp_path / "res.png").stat().st_size > 0


@pytest.mark.parametrize("argv, message", [
    (["--max-order", "1"], "--max-order"),
    (["--section", "x=1"], "section"),
    (["--energy", "-1"], "h"),
    (["--body", "lagrange", "--A", "2", "--C", "1", "--mu", "1"], "middle axis"),
])
def test_resonances_command_refuses_bad_input(tmp_path, capsys, argv, message):
    with pytest.raises(SystemExit) as info:
        main(["resonances", *argv, "--out", str(tmp_path / "r.nc")])
    assert info.value.code != 0
    err = capsys.readouterr().err
    assert "Traceback" not in err and message in err


def test_resonances_command_writes_the_normal_forms(tmp_path, capsys):
    """--order 8: beside the chains, the Birkhoff coefficients at the two centres of the
    level and each chain's resonant normal form. Checked against routes that share none of
    the Lie series: the linearised frequency of a permanent rotation (Euler), and the torus
    route's half-width (elliptic-integral W) of the 2:1 chain near the y centre."""
    out = tmp_path / "res.nc"
    assert main(["resonances", "--body", "hess", "--A", "3", "--B", "1", "--C", "2",
                 "--mu", "0.001", "--energy", "1", "--max-order", "4", "--order", "8",
                 "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "normal forms of degree 8" in text and "res-normal-form.nc" in text
    nf = xr.open_dataset(tmp_path / "res-normal-form.nc")
    assert int(nf.attrs["order"]) == 8 and nf.sizes["power"] == 4
    a, b, c = 1 / 3, 1.0, 0.5                  # inverse moments of hess(3, 1, 2)
    for axis, (inv, others) in {1: (a, (b, c)), 2: (b, (a, c))}.items():
        G = np.sqrt(2.0 / inv)                 # the rotation about the axis on H = 1
        euler = G * np.sqrt(abs((others[0] - inv) * (others[1] - inv)))
        r = nf.sel(centre=axis)
        np.testing.assert_allclose(float(r.G_centre), G, rtol=1e-14)
        np.testing.assert_allclose(abs(float(r.omega0)), euler, rtol=1e-12)
        np.testing.assert_allclose(float(r.H_star), 1.0, rtol=1e-12)
    near = nf.where(np.isfinite(nf.nf_half_width), drop=True)
    # only the 2:1 chains about y (both senses) are within half-way to the separatrix
    assert sorted(zip(near.q.values, near.axis.values, strict=True)) == [(2, 2), (2, 2)]
    # the Birkhoff polynomial at I* = 0.43 truncated at degree 8: 0.55 % from the torus
    np.testing.assert_allclose(near.nf_half_width, near.torus_half_width, rtol=1e-2)
    assert np.all(np.abs(near.nf_half_width / near.torus_half_width - 1) > 1e-4)
    assert nf.nf_half_width.attrs["equation"] == "(N5)"


def test_resonances_command_without_order_writes_no_normal_form(tmp_path, capsys):
    out = tmp_path / "res.nc"
    assert main(["resonances", "--body", "hess", "--A", "3", "--B", "1", "--C", "2",
                 "--mu", "0.001", "--energy", "1", "--max-order", "3",
                 "--out", str(out)]) == 0
    assert "normal form" not in capsys.readouterr().out
    assert not (tmp_path / "res-normal-form.nc").exists()


@pytest.mark.parametrize("order, message", [("5", "--order must be 0"), ("2", "--order must be 0"),
                                            ("18", "--order"), ("x", "--order")])
def test_resonances_command_refuses_a_bad_order(tmp_path, capsys, order, message):
    with pytest.raises(SystemExit) as info:
        main(["resonances", "--order", order, "--out", str(tmp_path / "r.nc")])
    assert info.value.code != 0
    err = capsys.readouterr().err
    assert "Traceback" not in err and message in err
    assert not list(tmp_path.iterdir())


def test_resonances_order_mu_writes_the_chains_to_third_order(tmp_path, capsys):
    """--order-mu 3: each chain of sign +1 to orders 1, 2 and 3 in mu (island_prediction),
    the table printed and *-order-mu.nc written; the 3:1 chain about axis 1 of
    Hess(3, 1, 2) at mu = 1e-3 has its stable point at -1.1707e-4 (measured -1.1712e-4,
    first order -1.1567e-4) and its half-width at order 3 within 1e-4 of the measured
    2.560541e-3 (benchmarks/RESONANCE_ORDERS.md: +5.9e-5; order 1 +4.2e-4); --order-mu 4
    is refused by name."""
    out = tmp_path / "res.nc"
    assert main(["resonances", "--body", "hess", "--A", "3", "--B", "1", "--C", "2",
                 "--mu", "0.001", "--energy", "1", "--max-order", "4", "--order-mu", "3",
                 "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "chains to order 3 in mu" in text and "res-order-mu.nc" in text
    ds = xr.open_dataset(tmp_path / "res-order-mu.nc")
    row = ds.where((ds.label == "3:1") & (ds.axis == 1), drop=True).isel(chain=0)
    assert float(row.stable_s.sel(order_mu=2)) == pytest.approx(-1.1712e-4, rel=2e-3)
    assert float(row.stable_s_error.sel(order_mu=2)) < float(row.stable_s_error.sel(order_mu=1))
    assert list(ds.order_mu.values) == [1, 2, 3]
    measured = 2.560541e-3
    error = {k: abs(float(row.half_width.sel(order_mu=k)) / measured - 1) for k in (1, 3)}
    assert error[3] < 1e-4 < error[1]
    with pytest.raises(SystemExit) as exc:
        main(["resonances", "--body", "hess", "--A", "3", "--B", "1", "--C", "2",
              "--mu", "0.001", "--energy", "1", "--order-mu", "4",
              "--out", str(tmp_path / "four.nc")])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "--order-mu" in err and "[0, 3]" in err and "Traceback" not in err
    with pytest.raises(SystemExit) as exc:
        main(["resonances", "--body", "hess", "--A", "3", "--B", "1", "--C", "2",
              "--mu", "0", "--energy", "1", "--order-mu", "1", "--out", str(tmp_path / "z.nc")])
    assert exc.value.code != 0
    err = capsys.readouterr().err
    assert "--order-mu needs mu > 0" in err and "Traceback" not in err
    assert not (tmp_path / "z.nc").exists()


def test_resonances_degree_writes_the_normal_forms_at_the_moved_centres(tmp_path, capsys):
    """--degree 5: the Birkhoff normal form of the section map at the level's centres
    moved by mu (periodic_orbit_normal_form); on Hess(3, 1, 2) the rotation about x is a
    1:1 resonance (W = 1 at the centre), named and skipped; about y omega0 = 0.4227491,
    tau_1 = 0.17657 at mu = 1e-2."""
    out = tmp_path / "res.nc"
    assert main(["resonances", "--body", "hess", "--A", "3", "--B", "1", "--C", "2",
                 "--mu", "0.01", "--energy", "1", "--max-order", "3", "--degree", "5",
                 "--engine", "numba", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "normal forms of the section map" in text and "res-twist.nc" in text
    assert "not taken: axis 1" in text
    ds = xr.open_dataset(tmp_path / "res-twist.nc")
    assert ds.centre.values.tolist() == [2]
    assert float(ds.rotation.sel(centre=2)) == pytest.approx(0.4227491, abs=1e-7)
    assert float(ds.twist.sel(centre=2, order=1)) == pytest.approx(0.17657, rel=1e-4)
    with pytest.raises(SystemExit) as exc:
        main(["resonances", "--degree", "2", "--out", str(tmp_path / "z.nc")])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "--degree must be 0" in err and "Traceback" not in err
    assert not (tmp_path / "z.nc").exists()
