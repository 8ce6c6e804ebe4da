"""Reports built from the analysis and plot layers: ``andoyer paper``.

Importing this package loads nothing heavy (the command line reads
:data:`DEFAULT_OUT` to build ``andoyer --help``); :mod:`andoyer.report.paper` does the work.
"""

__all__ = ["DEFAULT_OUT"]

#: Folder ``andoyer paper`` writes into by default.
DEFAULT_OUT = "andoyer-paper"
