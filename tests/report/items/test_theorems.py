"""The report's item of the proofs: both certificates written and verified, the proved
angle holds the measured one, the prose reads the run's statement."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from andoyer.report.paper import build_paper


@pytest.mark.slow
def test_proof_item_writes_verified_certificates(tmp_path: Path) -> None:
    from andoyer.analysis.splitting.certificate import verify_certificate

    index, done = build_paper(tmp_path / "paper", quick=True, only=["proof"],
                              engine="numba", progress=False, jobs=1)
    (_, result, _), = done
    n = result.numbers
    assert abs(n["angle_measured"] - n["angle_proved"]) <= n["angle_radius"]
    assert n["angle_radius"] < 1e-4 and n["melnikov_digits"] > 19
    html = index.read_text(encoding="utf-8")
    assert "intersect transversally" in html and "inside" in html
    cert = json.loads((tmp_path / "paper" / "proof-transversal.json").read_text())
    assert verify_certificate(cert)["angle"] == cert["boxes"]["angle"]
