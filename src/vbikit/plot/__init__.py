"""Figures (matplotlib is imported only when a figure is drawn)."""
from vbikit.plot.compare import plot_tire_comparison
from vbikit.plot.crossing import plot_crossing

__all__ = ["plot_crossing", "plot_tire_comparison"]
