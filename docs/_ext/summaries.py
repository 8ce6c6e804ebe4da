"""Sphinx extension: API summaries are not cut at the abbreviations of the docstrings.

autosummary takes a docstring's first sentence as its summary and ends a sentence at a
period followed by a space, except after a few abbreviations (``e.g.``, ``i.e.``, ...).
The docstrings cite the paper ("the Hamiltonian of Eq. (16)", "Fig. 3 redrawn"), so
without the paper's abbreviations a summary stopped at "Eq.".
"""

from __future__ import annotations

from typing import Any

#: Abbreviations after which a period does not end the summary sentence.
ABBREVIATIONS = ("Eq.", "Eqs.", "Fig.", "Figs.", "Ref.", "Refs.", "Sec.", "No.", "cf.",
                 "resp.", "E.g.", "I.e.")


def setup(app: Any) -> dict[str, Any]:
    """Extend autosummary's list of abbreviations (a module constant it reads per call)."""
    from sphinx.ext import autosummary

    known = tuple(autosummary.WELL_KNOWN_ABBREVIATIONS)
    autosummary.WELL_KNOWN_ABBREVIATIONS = known + tuple(  # type: ignore[misc]
        a for a in ABBREVIATIONS if a not in known)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
