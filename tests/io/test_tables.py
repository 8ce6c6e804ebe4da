"""Plain-text tables of fixed points, equilibria and the paper check."""

from __future__ import annotations

import pytest

from andoyer import RigidBody, paper_check
from andoyer.analysis.unperturbed.equilibria import euler_poisson_equilibria
from andoyer.analysis.unperturbed.fixed_points import hess_fixed_points
from andoyer.io.tables import format_table


def test_fixed_point_and_equilibrium_tables(paper_body: RigidBody) -> None:
    fps = hess_fixed_points(paper_body, 1.0)
    eq = euler_poisson_equilibria(paper_body)
    text = format_table(fps)
    assert "(2 phi0, J2/2)" in text and "centre" in text and "+-0.0995859195" in text
    assert "saddle-saddle" in format_table(eq)


def test_paper_check_table() -> None:
    rows = paper_check(n=20)
    text = format_table(rows)
    assert text.splitlines()[-1].startswith(f"{len(rows)} formulas:")
    assert "misprint" in text and "corrected:" in text


def test_anything_else_is_refused() -> None:
    with pytest.raises(TypeError, match="format_table"):
        format_table(3.0)  # type: ignore[arg-type]
