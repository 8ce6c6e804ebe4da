"""The report's item of the body in space (issue 27, item 5): the Hess branch of the
heteroclinic cycle joins P+ and P- in space, the attitude checks hold, the prose reads
the run's numbers."""

from __future__ import annotations

from pathlib import Path

from andoyer.report.paper import build_paper


def test_space_item_reports_the_cycle_from_the_run(tmp_path: Path) -> None:
    index, done = build_paper(tmp_path / "paper", quick=True, only=["space"],
                              engine="numba", progress=False, jobs=1)
    (_, result, _), = done
    n = result.numbers
    assert n["hess_branch_start"] > 1 - 1e-4 and n["hess_branch_end"] < -1 + 1e-4
    assert n["orthogonality"] <= 1e-13 and n["vertical_momentum"] <= 1e-11
    assert n["hess_relation"] <= 1e-9
    html = index.read_text(encoding="utf-8")
    assert f"{n['hess_branch_end']:.6f}" in html and "numba" in html
    assert (tmp_path / "paper" / "space.png").exists()
