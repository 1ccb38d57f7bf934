"""Figures of a traffic stream (matplotlib, imported only when a figure is drawn)."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from vbikit._files import save_figure
from vbikit.analysis.codes import aashto_lrfd
from vbikit.plot.styles import CODE_STYLES

#: the small-static events' look in both panels (their IMs are not design values)
SMALL_STATIC_STYLE = {"color": "0.6", "marker": "x"}


def small_static_label(fraction: float) -> str:
    """The legend entry of the events whose static peak is below ``fraction`` of the stream's largest."""
    return f"IM not meaningful: static peak < {fraction:.0%} of the largest"


def stream_figure(ds):
    """The figure of ``plot_stream`` (returned, not saved)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from vbikit.analysis.checks import SMALL_STATIC_FRACTION, small_static_mask

    if "point" in ds.dims:
        ds = ds.isel(point=0)
    im = ds["impact_factor"].values
    mp = ds["multiple_presence"].values.astype(bool)
    st = -ds["max_static_displacement"].values * 1e3
    dyn = -ds["max_dynamic_displacement"].values * 1e3
    # the stream statistics' rule (vbikit.traffic.study.stream_statistics): IMs on small static references
    fraction = float(ds.attrs.get("small_static_fraction", SMALL_STATIC_FRACTION))
    small = small_static_mask(st, fraction=fraction)
    one, several = ~mp & ~small, mp & ~small
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    edges = np.array(json.loads(ds.attrs["im_histogram_edges"]))
    groups, labels, colors = [im[one], im[several]], ["one vehicle", "several vehicles"], ["C0", "C1"]
    if small.any():
        groups.append(im[small])
        labels.append(small_static_label(fraction))
        colors.append(SMALL_STATIC_STYLE["color"])
    a.hist(groups, bins=edges, stacked=True, label=labels, color=colors)
    mean = float(ds.attrs["im_mean"])
    if small.any() and np.isfinite(float(ds.attrs.get("im_mean_loaded", np.nan))):
        loaded = float(ds.attrs["im_mean_loaded"])
        a.axvline(loaded, color="k", ls="--", lw=1, label=f"mean, events loading the point {loaded:.3f}")
        a.axvline(mean, color="0.5", ls=":", lw=1, label=f"mean, all events {mean:.3f}")
    else:
        a.axvline(mean, color="k", ls="--", lw=1, label=f"mean {mean:.3f}")
    lrfd = CODE_STYLES["aashto_lrfd"]
    a.axvline(aashto_lrfd(), color=lrfd.color, ls=lrfd.linestyle, lw=1, label=f"{lrfd.label} IM = {aashto_lrfd():.2f}")
    a.set_xlabel("impact factor IM of the event")
    a.set_ylabel("events")
    a.set_ylim(0, a.get_ylim()[1] * 1.7)  # room for the legend above the bars
    a.legend(fontsize="x-small", loc="upper right")
    b.scatter(st[one], dyn[one], s=6, color="C0", label="one vehicle")
    b.scatter(st[several], dyn[several], s=6, color="C1", label="several vehicles")
    if small.any():
        b.scatter(st[small], dyn[small], s=14, lw=0.8, label=small_static_label(fraction), **SMALL_STATIC_STYLE)
    top = max(st.max(), dyn.max()) * 1.05
    b.plot([0, top], [0, top], "k-", lw=0.8, label="dynamic = static")
    for key, marker in (("governing_static_event", "s"), ("governing_dynamic_event", "^")):
        e = int(ds.attrs[key])
        b.plot(st[e], dyn[e], marker, mfc="none", mec="k", ms=10, label=key.replace("_", " "))
    b.set_xlabel("static peak deflection [mm]")
    b.set_ylabel("dynamic peak deflection [mm]")
    b.legend(fontsize="x-small", loc="lower right")  # (below the diagonal: few events)
    return fig


def plot_stream(ds, path: str | Path, title: str = "") -> Path:
    """Two panels: the distribution of the events' impact factors (single vehicles and multiple
    presence stacked), and each event's dynamic against its static peak deflection [mm] with the
    governing events marked; at the first response point when the stream has several.  The events
    whose static peak is below ``small_static_fraction`` of the stream's largest (their IMs rest on
    small static references, ``vbikit.analysis.checks.small_static_mask``: not design values) are
    drawn apart in both panels, grey, with their own legend entry."""
    fig = stream_figure(ds)
    fig.suptitle(title or f"{ds.attrs.get('n_events')} events, {ds.attrs.get('n_multiple_presence_events')} with "
                 f"several vehicles; amplification of the governing static event "
                 f"{float(ds.attrs['governing_static_amplification']):.3f}")
    path = Path(path)
    save_figure(fig, path, dpi=120)
    return path
