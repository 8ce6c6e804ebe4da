"""The command line covers the API's analyses: frequencies (NAFF), single-orbit chaos
indicators, near-Hess bodies (--epsilon) for every command that takes a body; each
command prints its own usage on its own errors."""

import argparse

import numpy as np
import pytest
import xarray as xr

from andoyer import RigidBody
from andoyer.cli import build_parser, main
from andoyer.cli._common import body_from_args

STATE = ["--andoyer", "0.3,0,0.3,1,0", "--engine", "numba"]


def _commands():
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return parser, sub.choices


def test_every_command_that_takes_a_body_takes_epsilon():
    parser, commands = _commands()
    with_body = [n for n, p in commands.items()
                 if any("--body" in a.option_strings for a in p._actions)]
    assert {"section", "orbit", "chaos-map", "explore", "manifolds", "frequencies",
            "indicators"} <= set(with_body)
    for name in with_body:
        args = parser.parse_args([name, "--epsilon", "0.1", "--mu", "0.02"])
        body = body_from_args(args)
        want = RigidBody.near_hess(2.5, 2.0, 2.2, 0.02, 0.1)
        assert body.hess_epsilon == pytest.approx(0.1, abs=1e-14), name
        np.testing.assert_allclose(body.r, want.r, rtol=0, atol=1e-15)
        assert body.mu == 0.02
        args = parser.parse_args([name, "--body", "hess", "--A", "3", "--B", "1", "--C", "2",
                                  "--epsilon", "-0.2"])
        assert body_from_args(args).hess_epsilon == pytest.approx(-0.2, abs=1e-14)
        assert body_from_args(parser.parse_args([name])).is_hess


def test_epsilon_is_refused_for_bodies_that_are_not_hess(capsys):
    with pytest.raises(SystemExit) as info:
        main(["orbit", *STATE, "--body", "lagrange", "--A", "2", "--C", "1", "--mu", "1",
              "--epsilon", "0.1", "--t-end", "1"])
    assert info.value.code == 2
    assert "--body lagrange does not take --epsilon" in capsys.readouterr().err


def test_indicators_command(tmp_path, capsys):
    from andoyer.analysis.chaos.lyapunov import indicators

    out = tmp_path / "ind.nc"
    assert main(["indicators", *STATE, "--t-end", "100", "--n-times", "11",
                 "--out", str(out)]) == 0
    assert "MEGNO" in capsys.readouterr().out
    ds = xr.open_dataset(out)
    assert (tmp_path / "ind.png").read_bytes()[:4] == b"\x89PNG"
    ref = indicators(RigidBody.paper(), [0.3, 0, 0.3, 1, 0], 100.0, n_times=11,
                     chart="andoyer", engine="numba")
    np.testing.assert_array_equal(ds.megno.values, ref.megno.values)
    for v in ("fli", "megno", "mle"):
        assert ds[v].attrs["long_name"]


def test_frequencies_command_one_orbit(tmp_path, capsys):
    out = tmp_path / "f.nc"
    assert main(["frequencies", *STATE, "--t-end", "1500", "--n-samples", "4097",
                 "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "frequency_ratio = omega_g/omega_l" in text and "rotation_number_g_section" in text
    ds = xr.open_dataset(out)
    o = ds.isel(orbit=0)
    assert float(o.frequency_ratio * o.rotation_number_g_section) == pytest.approx(1.0)
    assert 7.0 < float(o.frequency_ratio) < 9.0      # the paper's body: about 8
    assert "section" in ds.rotation_number_g_section.attrs["long_name"]
    # Like every command's figure, the PNG beside the NetCDF (issue 29).
    assert (tmp_path / "f.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f"wrote {out} and {tmp_path / 'f.png'}" in text


def test_frequencies_command_map(tmp_path):
    out = tmp_path / "fm.nc"
    assert main(["frequencies", "--engine", "numba", "--n-orbits", "4", "--t-end", "300",
                 "--n-samples", "1025", "--out", str(out)]) == 0
    ds = xr.open_dataset(out)
    assert ds.sizes["orbit"] >= 3 and "log10_drift" in ds
    assert (tmp_path / "fm.png").read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize("argv, usage, hint", [
    (["scan", "x.toml", "--out", "s.zarr"], "usage: andoyer scan", "did you mean --store?"),
    (["section", "--crosings", "4"], "usage: andoyer section", "did you mean --n-crossings?"),
    (["frequencies", "--n-crossing", "4"], "usage: andoyer frequencies", ""),
])
def test_each_command_prints_its_own_usage(capsys, argv, usage, hint):
    with pytest.raises(SystemExit) as info:
        main(argv)
    err = capsys.readouterr().err
    assert info.value.code == 2
    assert err.startswith(usage) and "usage: andoyer [-h]" not in err
    assert f"andoyer {argv[0]}: error: unrecognized arguments" in err and hint in err


@pytest.mark.parametrize("command", ["section", "frequencies", "chaos-map"])
def test_level_commands_check_the_level_before_work_naming_the_flag(tmp_path, capsys,
                                                                    command):
    """The commands that seed a section plane take their body, section and level through
    one helper (cli._common.inputs_from_args): an energy level beyond what the integrators
    take is refused naming --energy, before anything is integrated or compiled."""
    with pytest.raises(SystemExit) as info:
        main([command, "--energy", "1e300", "--out", str(tmp_path / "x.nc")])
    err = capsys.readouterr().err
    assert info.value.code == 2
    assert f"andoyer {command}: error: --energy = 1e+300: the energy level reaches" in err
    assert "compiled" not in err and not (tmp_path / "x.nc").exists()
