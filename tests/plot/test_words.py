"""Labels in words and symbols (``andoyer.plot.words``): what the report's figures print
for the names the code uses."""

from __future__ import annotations

import pytest

from andoyer.analysis.unperturbed.separatrix import BRANCHES
from andoyer.plot.words import body_words, branch_words, number_words, symbol_words


def test_every_branch_reads_as_an_equation_in_symbols() -> None:
    words = [branch_words(b) for b in BRANCHES]
    assert words == [r"$\theta_1 = 0$", r"$\theta_1 = 4\varphi_0$"]
    assert all("=" not in w.replace(" = ", "") for w in words)


@pytest.mark.parametrize("x, text", [(0.01, "0.01"), (1e-3, "$10^{-3}$"),
                                     (2e-4, r"$2 \times 10^{-4}$"), (0.0, "0"), (1.0, "1")])
def test_numbers_as_a_paper_prints_them(x: float, text: str) -> None:
    assert number_words(x) == text


def test_a_body_in_words() -> None:
    assert body_words(3.0, 1.0, 2.0, 1e-3) == \
        r"Hess body $(A, B, C) = (3, 1, 2)$, $\mu$ = $10^{-3}$"
    assert symbol_words("mu=0.5") == r"$\mu = 0.5$"
