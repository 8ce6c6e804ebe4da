"""Matplotlib figures of andoyer datasets; they take datasets and compute nothing."""

from andoyer.plot.section import plot_section as plot_section
from andoyer.plot.section import save_figure as save_figure

__all__ = ["plot_section", "save_figure"]
