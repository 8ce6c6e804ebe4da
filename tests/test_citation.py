"""andoyer.cite() and CITATION.cff say the same thing."""

from pathlib import Path

import pytest

import andoyer
from andoyer.citation import cite

ROOT = Path(__file__).resolve().parents[1]


def test_cite_gives_both_entries_with_the_installed_version():
    text = andoyer.cite()
    assert text.count("@") == 2
    assert "@software{andoyer," in text and "@article{kyrychenko" in text
    assert f"version = {{{andoyer.__version__}}}" in text


def test_cite_one_entry_and_bad_argument():
    assert cite("tool").count("@") == 1
    assert "Kyrychenko" in cite("paper")
    with pytest.raises(ValueError, match="what must be"):
        cite("both")


def test_citation_cff_matches():
    cff = (ROOT / "CITATION.cff").read_text()
    pyproject = (ROOT / "pyproject.toml").read_text()
    version = next(line.split('"')[1] for line in pyproject.splitlines()
                   if line.startswith("version"))
    assert f"version: {version}" in cff
    assert "Kyrychenko" in cff
