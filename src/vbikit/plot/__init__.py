"""Figures."""
from vbikit.plot.crossing import plot_crossing

__all__ = ["plot_crossing"]
