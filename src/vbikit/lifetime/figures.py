"""Figures of a lifetime run (matplotlib imported only inside the drawing functions).

* ``lifetime-gumbel.png``: per load effect the block maxima, static and total, on Gumbel
  probability paper (reduced variate y = −ln(−ln p), Gringorten plotting positions), the fitted
  distributions and the return levels of the return periods with their confidence intervals
  (delta method), a top axis of return periods in years;
* ``lifetime-adr.png``: the ratio total / static of the return levels against the return period,
  with the per-event IM statistics and the AASHTO LRFD allowance;
* ``lifetime-fatigue.png``: per detail the static stress-range histogram and the damage per day;
* ``lifetime-traffic.png`` (``traffic_figure``): fitted against recorded distributions.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from vbikit._files import save_figure


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _level(y: np.ndarray, loc: float, scale: float, shape: float) -> np.ndarray:
    """Block-maximum quantile at reduced variate y (GEV in Coles's sign; Gumbel when ξ = 0)."""
    if abs(shape) < 1e-12:
        return loc + scale * y
    return loc + scale / shape * (np.exp(shape * y) - 1.0)  # (−ln p)^(−ξ) = e^{ξ y}


def write_figures(ds, out_dir: str | Path) -> list[Path]:
    """The run's figures into ``out_dir`` (module docstring); returns their paths."""
    out_dir = Path(out_dir)
    paths = [gumbel_figure(ds, out_dir / "lifetime-gumbel.png"), adr_figure(ds, out_dir / "lifetime-adr.png")]
    if ds.sizes.get("detail", 0):
        paths.append(fatigue_figure(ds, out_dir / "lifetime-fatigue.png"))
    return paths


def gumbel_figure(ds, path: Path) -> Path:
    from vbikit.extremes import plotting_positions

    plt = _plt()
    names = list(ds["load_effect"].values)
    n = len(names)
    fig, axes = plt.subplots(1, n, figsize=(4.2 * n, 3.8), constrained_layout=True, squeeze=False)
    week = ds.attrs["block"] == "week"
    per_year = ds.attrs["days_per_year"] / (7 if week else 1)
    periods = ds["return_period"].values
    ci = _ci_label(ds)
    for j, (ax, name) in enumerate(zip(axes[0], names)):
        s = float(ds["effect_sign"][j])
        unit = str(ds["load_effect_units"].values[j])
        for which, color in (("static", "C0"), ("total", "C3")):
            block = ds[f"weekly_max_{which}" if week else f"daily_max_{which}"].values[:, j] * s
            pp = plotting_positions(block, blocks_per_year=per_year)
            ax.plot(pp.reduced_variate, pp.values, "o", ms=3, color=color, label=f"{which} {'weekly' if week else 'daily'} maxima")
            p_top = 1 - 1 / (per_year * periods.max())
            y = np.linspace(min(pp.reduced_variate.min(), -1.5), -math.log(-math.log(p_top)), 200)
            ax.plot(y, _level(y, float(ds[f"fit_{which}_location"][j]), float(ds[f"fit_{which}_scale"][j]),
                              float(ds[f"fit_{which}_shape"][j])), "-", color=color, lw=1, label=f"{which} {ds.attrs['distribution']} fit")
            levels = ds[f"return_level_{which}"].values[j] * s
            bounds = np.sort(np.stack([ds[f"return_level_{which}_lower"].values[j] * s,
                                       ds[f"return_level_{which}_upper"].values[j] * s]), axis=0)
            yt = -np.log(-np.log(1 - 1 / (per_year * periods)))
            shown = np.isfinite(bounds).all(axis=0)  # an interval that could not be computed is not drawn
            ax.errorbar(yt[shown], levels[shown], yerr=np.abs(bounds[:, shown] - levels[shown]), fmt="D", color=color,
                        mfc="none", ms=6, capsize=3, lw=1, label=f"{which} return levels, {ci} interval")
            ax.plot(yt[~shown], levels[~shown], "D", color=color, mfc="none", ms=6)
            for t, yy, lv in zip(periods, yt, levels):
                if which == "total":
                    ax.annotate(f"{t:g} yr", (yy, lv), textcoords="offset points", xytext=(-12, 6), fontsize=7)
        ax.set_xlabel("Gumbel reduced variate −ln(−ln p)")
        _return_period_axis(ax, per_year)
        ax.set_ylabel(f"{'−' if s < 0 else ''}{name} [{unit}]")
        ax.set_title(f"{name}: ADR = {float(ds['assessment_dynamic_ratio'][j]):.3f}", fontsize=9)
        ax.legend(fontsize=6, loc="upper left")
    return save_figure(fig, path, dpi=120)


def _return_period_axis(ax, per_year: float) -> None:
    """A top axis of return periods T [years] on Gumbel paper: T = 1/(n (1 − p)) with p = exp(−e^−y)
    and n blocks per year (docs/lifetime.md, "Probability paper")."""
    lo, hi = ax.get_xlim()
    marks = np.array([1.0, 10.0, 100.0, 1000.0, 10000.0])
    marks = marks[marks * per_year > 1.0]  # T n = 1 is p = 0, y = −∞
    y = -np.log(-np.log(1.0 - 1.0 / (marks * per_year)))
    keep = (y >= lo) & (y <= hi)
    top = ax.secondary_xaxis("top", functions=(lambda v: v, lambda v: v))
    top.set_xticks(y[keep])
    top.set_xticklabels([f"{m:g}" for m in marks[keep]], fontsize=7)
    top.set_xlabel("return period [years]", fontsize=8)


def _ci_label(ds) -> str:
    """The confidence level of the return-level intervals as the dataset states it ("95 %")."""
    level = ds.attrs.get("ci")
    return f"{100 * float(level):g} %" if level is not None else "confidence"


def adr_figure(ds, path: Path) -> Path:
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5.5, 3.8), constrained_layout=True)
    periods = ds["return_period"].values
    for j, name in enumerate(ds["load_effect"].values):
        line, = ax.semilogx(periods, ds["adr_by_period"].values[j], "o-", label=f"{name} ADR")
        ax.axhline(1 + float(ds["im_mean"][j]), color=line.get_color(), ls=":", lw=1,
                   label=f"{name} 1 + mean event IM")
    ax.axhline(1 + float(ds["code_allowance"].values[0, 0]), color="k", ls="--", lw=1,
               label=f"1 + AASHTO LRFD IM ({float(ds['code_allowance'].values[0, 0]):.2f})")
    ax.set_xlabel("return period [years]")
    ax.set_ylabel("total / static return level")
    ax.legend(fontsize=6)
    return save_figure(fig, path, dpi=120)


def fatigue_figure(ds, path: Path) -> Path:
    plt = _plt()
    details = list(ds["detail"].values)
    fig, axes = plt.subplots(2, len(details), figsize=(4.5 * len(details), 6), constrained_layout=True, squeeze=False)
    edges = ds["stress_range_bin"].values / 1e6
    width = edges[1] - edges[0] if edges.size > 1 else 1.0
    for j, name in enumerate(details):
        h = ds["stress_range_histogram"].values[j]
        a = axes[0, j]
        a.bar(edges, h, width=width, align="edge")
        a.set_yscale("log")
        a.set_xlabel("stress range [MPa]")
        a.set_ylabel("cycles (static history)")
        a.set_title(f"{name} ({ds['detail_category'].values[j]}): D = {float(ds['fatigue_damage'][j]):.3g}, "
                    f"dyn/stat {float(ds['dynamic_damage_ratio'][j]):.3f}", fontsize=8)
        b = axes[1, j]
        b.plot(ds["day"].values, ds["damage_per_day_static"].values[:, j], ".-", label="static, each day alone")
        b.axhline(float(ds["fatigue_damage"][j]) / ds.sizes["day"], color="C3", ls="--",
                  label="mean per day, static + dynamic")
        b.set_xlabel("day")
        b.set_ylabel("Miner damage per day")
        b.legend(fontsize=7)
    return save_figure(fig, path, dpi=120)


def traffic_figure(model, path: str | Path) -> Path:
    """Fitted against recorded: GVW per class (histogram and mixture density), flow per hour per
    lane, speeds per lane, headways per lane (the generator's, one simulated day, against the records')."""
    plt = _plt()
    recs = model.records
    sim = model.day(0, seed=0)
    classes = model.classes
    fig, axes = plt.subplots(2, max(2, len(classes)), figsize=(4 * max(2, len(classes)), 7), constrained_layout=True,
                             squeeze=False)
    for k, c in enumerate(classes):
        a = axes[0, k]
        g = np.array([r.gross_weight for r in recs if len(r.axle_loads) == c.n_axles]) / 1e3
        gs = np.array([r.gross_weight for r in sim if len(r.axle_loads) == c.n_axles]) / 1e3
        bins = np.linspace(0, max(g.max(), gs.max() if gs.size else 0) * 1.1, 30)
        a.hist(g, bins=bins, density=True, alpha=0.5, label="records")
        a.hist(gs, bins=bins, density=True, histtype="step", label="generated (day 0)")
        x = np.linspace(bins[0], bins[-1], 200)
        a.plot(x, c.gvw.pdf(x * 1e3) * 1e3, "k-", lw=1, label=f"{len(c.gvw.weights)}-normal mixture")
        a.set_xlabel(f"GVW [kN], {c.n_axles} axles ({100 * c.share:.0f} %)")
        a.legend(fontsize=6)
    a = axes[1, 0]
    for ln in model.lanes:
        a.step(np.arange(24), ln.hourly_flow, where="post", label=f"lane {ln.lane} fitted")
        t = np.array([r.time for r in sim if r.lane == ln.lane])
        a.plot(np.arange(24) + 0.5, np.bincount((t // 3600).astype(int) % 24, minlength=24), ".",
               label=f"lane {ln.lane} generated")
    a.set_xlabel("hour of the day")
    a.set_ylabel("trucks / h")
    a.legend(fontsize=6)
    a = axes[1, 1]
    for ln in model.lanes:
        v = np.array([recs[i].speed for i in ln.records]) * 3.6
        vs = np.array([r.speed for r in sim if r.lane == ln.lane]) * 3.6
        a.hist(v, bins=20, density=True, alpha=0.4, label=f"lane {ln.lane} records")
        a.hist(vs, bins=20, density=True, histtype="step", label=f"lane {ln.lane} generated")
    a.set_xlabel("speed [km/h]")
    a.legend(fontsize=6)
    if axes.shape[1] > 2:
        a = axes[1, 2]
        for ln in model.lanes:
            h = np.diff(sorted(recs[i].time for i in ln.records))
            hs = np.diff([r.time for r in sim if r.lane == ln.lane])
            bins = np.linspace(0, np.quantile(np.r_[h, hs], 0.98), 30)
            a.hist(h, bins=bins, density=True, alpha=0.4, label=f"lane {ln.lane} records")
            a.hist(hs, bins=bins, density=True, histtype="step", label=f"lane {ln.lane} generated")
        a.set_xlabel("headway [s]")
        a.legend(fontsize=6)
    return save_figure(fig, Path(path), dpi=120)
