"""Probability-paper (Gumbel) plot of a fitted extreme-value model (matplotlib, imported only
when a figure is drawn)."""
from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from vbikit._files import save_figure
from vbikit.extremes.errors import ExtremesError
from vbikit.extremes.fits import ExtremeFit
from vbikit.extremes.plotting_positions import plotting_positions
from vbikit.extremes.return_levels import _check_periods, return_levels


def plot_gumbel(fit: ExtremeFit, path: str | Path, periods: Any = (75.0, 100.0, 1000.0), ci: float = 0.95,
                unit: str = "", method: str = "gringorten", title: str = "") -> Path:
    """Gumbel plot: the sample on probability paper, the fitted distribution and the return levels.

    The x axis is the Gumbel reduced variate y = −ln(−ln p) of the non-exceedance probability p of
    one block maximum (or of one exceedance, for a POT fit); a Gumbel sample lies on a straight
    line.  Points: the sample at its plotting positions (``method``).  Line: the fitted quantile
    function.  Markers with bars: the return levels of ``periods`` (years) with their ``ci``
    delta-method intervals, at p = 1 − 1/(T n).  The top axis gives return periods in years.

    Parameters
    ----------
    fit : ExtremeFit
        The fitted model.
    path : str or Path
        PNG file to write (atomically).
    periods : sequence of float
        Return periods to mark, years.
    ci : float
        Confidence level of the bars.
    unit : str
        Unit of the data, for the axis label.
    method : str
        Plotting-position formula (see ``plotting_positions``).
    title : str
        Figure title (default: the distribution and its parameters).

    Returns
    -------
    Path
        The file written.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from vbikit.plot.labels import unit_label

    t = _check_periods(fit, periods, "periods")
    n = fit.events_per_year
    if np.any(t * n <= 1.0):  # p = 1 − 1/(T n) = 0 has no place on the Gumbel axis (y = −∞)
        raise ExtremesError(f"periods: a return period of {t[t * n <= 1.0][0]:g} years is at p = 0 on the plot; "
                            f"mark periods longer than 1/{n:g} year")
    pos = plotting_positions(fit.sample, method, blocks_per_year=n)
    level, lo, hi = return_levels(fit, t, ci=ci)
    p_t = 1.0 - 1.0 / (t * n)
    y_t = -np.log(-np.log(p_t))
    y = np.linspace(min(pos.reduced_variate.min(), -1.5), max(y_t.max(), pos.reduced_variate.max()) + 0.5, 300)
    p = np.exp(-np.exp(-y))
    fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
    ax.plot(pos.reduced_variate, pos.values, "o", ms=3, mfc="none", label=f"sample ({method} positions)")
    ax.plot(y, fit.frozen().ppf(p), "-", lw=1.2, label=f"fitted {fit.distribution.upper()}")
    ax.errorbar(y_t, level, yerr=[level - lo, hi - level], fmt="s", ms=5, capsize=3,
                label=f"return levels, {ci:.0%} interval")
    for k, (yt, lv, tt) in enumerate(zip(y_t, level, t)):
        ax.annotate(f"{tt:g} yr", (yt, lv), textcoords="offset points", xytext=(-8, 8 if k % 2 else -14),
                    ha="right", fontsize="small")
    what = "block maximum" if fit.distribution != "gpd" else "exceedance"
    ax.set_xlabel(f"Gumbel reduced variate −ln(−ln p)   (p: probability of one {what} not exceeded)")
    ax.set_ylabel(f"value [{unit_label(unit)}]" if unit else "value")
    top = ax.secondary_xaxis("top", functions=(lambda v: v, lambda v: v))
    marks = np.array([1.0, 10.0, 100.0, 1000.0])
    marks = marks[marks * n > 1.0]  # T n = 1 is p = 0, y = −∞
    top.set_xticks(-np.log(-np.log(1.0 - 1.0 / (marks * n))))
    top.set_xticklabels([f"{m:g}" for m in marks])
    top.set_xlabel("return period [years]")
    ax.legend(fontsize="small", loc="upper left")
    ax.set_title(title or ", ".join(f"{k} = {v:.4g}" for k, v in fit.params.items()), fontsize="medium")
    path = Path(path)
    save_figure(fig, path, dpi=120)
    return path


__all__ = ["plot_gumbel"]
