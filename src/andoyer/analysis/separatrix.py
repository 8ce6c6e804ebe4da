"""Moved to :mod:`andoyer.analysis.unperturbed.separatrix`; this path works for one release.

Importing it warns (``DeprecationWarning``) and gives the module itself, so names,
monkeypatches and ``isinstance`` checks are those of the new module.
"""

import importlib
import sys
import warnings

warnings.warn("andoyer.analysis.separatrix moved to andoyer.analysis.unperturbed.separatrix; "
              "the old path works for one release", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = importlib.import_module("andoyer.analysis.unperturbed.separatrix")
