"""Moved to :mod:`andoyer.analysis.unperturbed.euler_poinsot`; this path works for one release.

Importing it warns (``DeprecationWarning``) and gives the module itself, so names,
monkeypatches and ``isinstance`` checks are those of the new module.
"""

import importlib
import sys
import warnings

warnings.warn("andoyer.analysis.euler_poinsot moved to andoyer.analysis.unperturbed.euler_poinsot; "
              "the old path works for one release", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = importlib.import_module("andoyer.analysis.unperturbed.euler_poinsot")
