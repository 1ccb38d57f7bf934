"""Figures (matplotlib is imported only when a figure is drawn); the axis labels of dataset units
(``labels``) and the one style table of the design-code lines (``styles``)."""
from vbikit.plot.compare import plot_tire_comparison
from vbikit.plot.crossing import plot_crossing
from vbikit.plot.labels import axis_label, unit_label
from vbikit.plot.styles import CODE_STYLES, CodeStyle, code_line

__all__ = ["CODE_STYLES", "CodeStyle", "axis_label", "code_line", "plot_crossing", "plot_tire_comparison", "unit_label"]
