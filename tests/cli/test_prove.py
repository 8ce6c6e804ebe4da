"""``andoyer prove`` writes a certificate that ``andoyer verify`` accepts."""

from __future__ import annotations

import json

import pytest

from andoyer.cli import main
from andoyer.outputs import release_all


def _fails(argv):
    with pytest.raises(SystemExit) as info:
        main(argv)
    return info.value.code


def test_prove_then_verify(tmp_path, capsys):
    out = tmp_path / "cert.json"
    assert main(["prove", "--epsilon", "0.1", "--branch", "theta1=0", "--digits", "12",
                 "--out", str(out)]) == 0
    release_all()
    assert "two simple zeros" in capsys.readouterr().out
    cert = json.loads(out.read_text())
    assert cert["body"]["epsilon"] == "0.1" and cert["branch"] == "theta1=0"
    assert main(["verify", str(out)]) == 0
    assert "verified" in capsys.readouterr().out
    cert["body"]["A"] = "2.4"
    out.write_text(json.dumps(cert))
    assert _fails(["verify", str(out)]) == 2
    err = capsys.readouterr().err
    assert "altered" in err and len(err.strip().splitlines()) == 1


def test_prove_checks_its_output_first(tmp_path, capsys):
    assert _fails(["prove", "--out", str(tmp_path / "c.txt")]) == 2
    assert "must name a .json file" in capsys.readouterr().err


def test_transversal_kind_needs_mu_and_melnikov_refuses_it(tmp_path, capsys):
    assert _fails(["prove", "--kind", "transversal", "--out", str(tmp_path / "c.json")]) == 2
    assert "needs --mu" in capsys.readouterr().err
    assert _fails(["prove", "--mu", "0.05", "--out", str(tmp_path / "c.json")]) == 2
    assert "--kind transversal" in capsys.readouterr().err


@pytest.mark.slow
def test_prove_transversal_then_verify(tmp_path, capsys):
    out = tmp_path / "theorem.json"
    assert main(["prove", "--kind", "transversal", "--B", "1.0", "--C", "1.6",
                 "--epsilon", "0.1", "--mu", "0.05", "--out", str(out)]) == 0
    release_all()
    assert "intersect transversally" in capsys.readouterr().out
    assert main(["verify", str(out)]) == 0
    assert "every box recomputed" in capsys.readouterr().out
    cert = json.loads(out.read_text())
    cert["boxes"]["angle"] = "[-0.0037 +/- 1e-3]"
    out.write_text(json.dumps(cert))
    assert _fails(["verify", str(out)]) == 2
    err = capsys.readouterr().err
    assert "altered" in err and len(err.strip().splitlines()) == 1
