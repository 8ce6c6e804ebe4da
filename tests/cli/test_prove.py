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
