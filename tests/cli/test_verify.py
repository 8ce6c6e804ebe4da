"""``andoyer verify`` refuses what is not a certificate, with one line and exit 2."""

from __future__ import annotations

import pytest

from andoyer.cli import main


def _fails(argv):
    with pytest.raises(SystemExit) as info:
        main(argv)
    return info.value.code


def test_verify_refuses_foreign_json(tmp_path, capsys):
    path = tmp_path / "other.json"
    path.write_text('{"hello": 1}')
    assert _fails(["verify", str(path)]) == 2
    assert "not an andoyer certificate" in capsys.readouterr().err
    assert _fails(["verify", str(tmp_path / "none.json")]) == 2
    assert "no such file" in capsys.readouterr().err
