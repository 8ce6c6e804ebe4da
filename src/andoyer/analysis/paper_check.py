"""Moved to :mod:`andoyer.analysis.paper.paper_check`; this path works for one release.

Importing it warns (``DeprecationWarning``) and gives the module itself, so names,
monkeypatches and ``isinstance`` checks are those of the new module.
"""

import importlib
import sys
import warnings

warnings.warn("andoyer.analysis.paper_check moved to andoyer.analysis.paper.paper_check; "
              "the old path works for one release", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = importlib.import_module("andoyer.analysis.paper.paper_check")
