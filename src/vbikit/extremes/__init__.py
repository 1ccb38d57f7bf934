"""Extreme values of load effects: block maxima (GEV, Gumbel) and peaks over threshold (GPD)
fitted with scipy.stats, return levels with confidence intervals, probability-paper positions
and named characteristic return periods.

Parameters use Coles's (2001) sign of the shape ξ (ξ > 0 heavy tail); scipy's
``genextreme`` uses c = −ξ — see ``ExtremeFit.scipy_c``.  Values keep the unit of the data.
"""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.extremes.errors import ExtremesError
    from vbikit.extremes.figures import plot_gumbel
    from vbikit.extremes.fits import BLOCK_DISTRIBUTIONS, MIN_SAMPLE, ExtremeFit, fit_block_maxima, fit_peaks_over_threshold
    from vbikit.extremes.plotting_positions import POSITIONS, PlottingPositions, plotting_positions
    from vbikit.extremes.presets import RETURN_PERIODS, ReturnPeriod, exceedance_return_period, return_period
    from vbikit.extremes.paired import LevelRatio, level_ratio
    from vbikit.extremes.return_levels import CI_METHODS, return_level, return_levels

__all__ = [
    "BLOCK_DISTRIBUTIONS",
    "CI_METHODS",
    "ExtremeFit",
    "ExtremesError",
    "LevelRatio",
    "MIN_SAMPLE",
    "POSITIONS",
    "PlottingPositions",
    "RETURN_PERIODS",
    "ReturnPeriod",
    "exceedance_return_period",
    "fit_block_maxima",
    "fit_peaks_over_threshold",
    "level_ratio",
    "plot_gumbel",
    "plotting_positions",
    "return_level",
    "return_levels",
    "return_period",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.extremes.errors": ["ExtremesError"],
    "vbikit.extremes.figures": ["plot_gumbel"],
    "vbikit.extremes.fits": ["BLOCK_DISTRIBUTIONS", "ExtremeFit", "MIN_SAMPLE", "fit_block_maxima",
                             "fit_peaks_over_threshold"],
    "vbikit.extremes.paired": ["LevelRatio", "level_ratio"],
    "vbikit.extremes.plotting_positions": ["POSITIONS", "PlottingPositions", "plotting_positions"],
    "vbikit.extremes.presets": ["RETURN_PERIODS", "ReturnPeriod", "exceedance_return_period", "return_period"],
    "vbikit.extremes.return_levels": ["CI_METHODS", "return_level", "return_levels"],
})
