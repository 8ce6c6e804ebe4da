"""Moved to :mod:`andoyer.analysis.hess.hess_periods`; this path works for one release.

Importing it warns (``DeprecationWarning``) and gives the module itself, so names,
monkeypatches and ``isinstance`` checks are those of the new module.
"""

import importlib
import sys
import warnings

warnings.warn("andoyer.analysis.hess_periods moved to andoyer.analysis.hess.hess_periods; "
              "the old path works for one release", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = importlib.import_module("andoyer.analysis.hess.hess_periods")
