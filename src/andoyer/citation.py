"""How to cite andoyer and the paper it implements (as REBOUND's ``sim.cite()``).

The same facts as ``CITATION.cff`` at the repository root; a test keeps the two in step.
"""

from __future__ import annotations

from andoyer._version import __version__
from andoyer.validation import checks_arguments, choice

__all__ = ["cite", "TOOL_BIBTEX", "PAPER_BIBTEX"]

#: The software record; ``{version}`` is filled with the installed version.
TOOL_BIBTEX = """@software{{andoyer,
  title   = {{andoyer: the heavy rigid body (Hess gyroscope) in Andoyer--Deprit variables}},
  author  = {{{{andoyer developers}}}},
  version = {{{version}}},
  license = {{MIT}},
  note    = {{Python library and command-line tool}}
}}"""

#: The paper the tool implements and checks. The copy we work from names no journal,
#: volume or year, so none is invented here.
PAPER_BIBTEX = """@article{kyrychenko_hess_andoyer_deprit,
  author  = {Kyrychenko, V. V.},
  title   = {Andoyer--Deprit variables use to the {Hess} gyroscope phase trajectories
             exploring},
  note    = {Aircraft Control Systems Department, National Aviation University, Kyiv,
             Ukraine; journal, volume and year not given in the copy implemented here}
}"""


@checks_arguments
def cite(what: str = "all") -> str:
    """BibTeX for the tool and for the paper it implements.

    Parameters
    ----------
    what : {"all", "tool", "paper"}
        Which entries to return.

    Returns
    -------
    str
        One or two BibTeX entries, separated by a blank line.

    Examples
    --------
    >>> import andoyer
    >>> print(andoyer.cite("paper").splitlines()[0])
    @article{kyrychenko_hess_andoyer_deprit,
    >>> "@software{andoyer," in andoyer.cite()
    True
    """
    what = choice("what", what, ("all", "tool", "paper"))
    entries = {"tool": TOOL_BIBTEX.format(version=__version__), "paper": PAPER_BIBTEX}
    if what == "all":
        return "\n\n".join(entries.values()) + "\n"
    return entries[what] + "\n"
