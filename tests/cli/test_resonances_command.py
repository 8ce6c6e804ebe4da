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
