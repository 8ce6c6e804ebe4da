"""``andoyer last-torus``: the residues written and printed; bad input ends in one line,
exit 2, never a traceback."""

import numpy as np
import pytest
import xarray as xr

from andoyer import RigidBody
from andoyer.analysis.resonance import last_torus
from andoyer.cli import main


def test_last_torus_command_writes_the_residues(tmp_path, capsys):
    out = tmp_path / "torus.nc"
    assert main(["last-torus", "--body", "hess", "--A", "3", "--B", "1", "--C", "2",
                 "--mu", "0.002", "--energy", "1", "--head", "2", "--axis", "2",
                 "--n-convergents", "2", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "2/5" in text and "3/8" in text and "mu_c not found (no --mu-range)" in text
    ds = xr.open_dataset(out)
    ref = last_torus(RigidBody.hess(3.0, 1.0, 2.0, mu=0.002), 1.0, head=(2,), axis=2,
                     n_convergents=2, progress=False)
    np.testing.assert_allclose(ds.residue_elliptic, ref.residue_elliptic, rtol=1e-6)
    assert ds.attrs["head"] == "2" and ds.residue_elliptic.attrs["equation"] == "(G4)"


@pytest.mark.parametrize("argv, message", [
    (["--head", "x"], "--head"),
    (["--head", "1"], "head"),
    (["--axis", "3"], "--axis"),
    (["--mu-range", "0.1", "0.01"], "mu_range"),
    (["--mu", "0"], "mu > 0"),
    (["--body", "general", "--A", "3", "--B", "1", "--C", "2", "--mu", "0.01", "--r", "0.6",
      "0.48", "0.64"], "e3 = 0"),
])
def test_last_torus_command_refuses_bad_input(tmp_path, capsys, argv, message):
    with pytest.raises(SystemExit) as info:
        main(["last-torus", *argv, "--out", str(tmp_path / "t.nc")])
    assert info.value.code == 2
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if line.strip()]
    assert "Traceback" not in err and message in lines[-1]
    if not lines[0].startswith("usage:"):      # past the parser: the one line of the error
        assert len(lines) == 1
