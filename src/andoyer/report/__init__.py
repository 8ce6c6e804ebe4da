"""Reports built from the analysis and plot layers: ``andoyer paper``."""
