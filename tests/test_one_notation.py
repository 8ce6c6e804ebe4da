"""One notation, the reader's: ``I`` is the inertia tensor, so the angular velocity is
``omega = I^-1 G`` and the Hamiltonian ``H = (G, I^-1 G)/2 + mu (r, gamma)`` (Eq. (1)),
in the README, the report, the docs and the docstrings alike. The other form
(``(G, I G)``, ``omega = I G``: ``I`` standing for the inverse) reads as a wrong formula to
anyone who learnt rigid-body dynamics, so no tracked text may write it."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: ``I G`` / ``IG`` as a product (not ``SIGTERM``, ``CONFIG``, ``I^-1 G``, ``I, G``), and
#: its LaTeX spellings ``\mathbf I \mathbf G``, ``I G`` in math.
OTHER_FORM = re.compile(
    r"(?<![\w^⁻\-])I ?G\b(?![\w.]*\()"      # (G, I G), omega = I G, R I G, (0, IG)
    r"|\\{1,2}mathbf ?\{?I\}? ?\\{1,2}mathbf ?\{?G"  # \mathbf I \mathbf G (docstrings: \\mathbf)
    r"|\(G, ?I ?G\)")
SUFFIXES = {".py", ".md", ".j2", ".html", ".rst", ".txt", ".toml", ".cff", ".css"}


def tracked_texts() -> list[Path]:
    try:
        out = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True,
                             check=True).stdout.split()
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("not a git checkout")
    here = Path(__file__).resolve()
    return [ROOT / f for f in out if Path(f).suffix in SUFFIXES and (ROOT / f) != here
            and (ROOT / f).is_file()]


def other_forms(text: str) -> list[str]:
    """The lines of ``text`` that write ``I G`` for ``I^-1 G``."""
    return [line.strip() for line in text.splitlines() if OTHER_FORM.search(line)]


def test_the_pattern_finds_the_other_form() -> None:
    for bad in ("H = ½ (G, I G) + μ (r, γ)", "H = (G, IG)/2", "omega = I G",
                "dq/dt = q (x) (0, I G)/2", r"\mathbf I \mathbf G", r"\\mathbf I\\mathbf G",
                "dG/dt = G x I G"):
        assert other_forms(bad), bad
    for good in ("H = ½ (G, I⁻¹G) + μ (r, γ)", "omega = I^-1 G", r"\mathbf I^{-1} \mathbf G",
                 "SIGTERM", "CONFIG.toml", "self.energy(I, G)", "I^{-1} G"):
        assert not other_forms(good), good


def test_no_text_writes_I_G_for_the_inverse() -> None:
    found = {str(p.relative_to(ROOT)): lines for p in tracked_texts()
             if (lines := other_forms(p.read_text(errors="replace")))}
    assert not found, f"write I^-1 G (I the inertia tensor): {found}"
