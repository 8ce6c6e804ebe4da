"""The report's item of the last torus (issue 37, item 3): Greene's residues of the golden
torus's convergents, mu_c below the overlap estimate, the prose reading the run."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from andoyer.report.paper import build_paper


@pytest.mark.slow
def test_last_torus_item_reports_the_critical_mu(tmp_path: Path) -> None:
    index, done = build_paper(tmp_path / "paper", quick=True, only=["last-torus"],
                              progress=False, jobs=1)
    (_, result, _), = done
    n = result.numbers
    # quick: the convergents 2/5, 3/8 (mu_c(q) = 0.01115, 0.00829; converged 0.00904)
    assert 0.007 < n["mu_critical"] < 0.012
    assert n["mu_overlap"] == pytest.approx(0.029937, rel=1e-3)
    assert 0.2 < n["mu_ratio"] < 0.5
    trend = result.values["trend"]
    assert trend[0.5][-1] < trend[0.5][0] and trend[2.0][-1] > trend[2.0][0] > 0.25
    html = index.read_text(encoding="utf-8")
    assert f"{n['mu_critical']:.6g}" in html and f"{n['mu_overlap']:.4g}" in html
    assert math.isfinite(n["mu_critical_error"])
    assert (tmp_path / "paper" / "last-torus.png").exists()
