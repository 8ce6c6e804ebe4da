"""Moved to :mod:`andoyer.analysis.splitting.periodic`; this path works for one release.

Importing it warns (``DeprecationWarning``) and gives the module itself, so names,
monkeypatches and ``isinstance`` checks are those of the new module.
"""

import importlib
import sys
import warnings

warnings.warn("andoyer.analysis.periodic moved to andoyer.analysis.splitting.periodic; "
              "the old path works for one release", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = importlib.import_module("andoyer.analysis.splitting.periodic")
