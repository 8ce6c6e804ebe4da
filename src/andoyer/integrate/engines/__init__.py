"""Integration engines behind one seam (:mod:`andoyer.integrate.engines.base`)."""
