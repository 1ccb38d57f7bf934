"""Figures of a traffic stream (matplotlib, imported only when a figure is drawn)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from vbikit._files import save_figure
from vbikit.analysis.codes import aashto_lrfd
from vbikit.plot.styles import CODE_STYLES


def plot_stream(ds, path: str | Path, title: str = "") -> Path:
    """Two panels: the distribution of the events' impact factors (single vehicles and multiple
    presence stacked), and each event's dynamic against its static peak deflection [mm] with the
    governing events marked; at the first response point when the stream has several."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if "point" in ds.dims:
        ds = ds.isel(point=0)
    im = ds["impact_factor"].values
    mp = ds["multiple_presence"].values.astype(bool)
    st = -ds["max_static_displacement"].values * 1e3
    dyn = -ds["max_dynamic_displacement"].values * 1e3
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    edges = np.array(__import__("json").loads(ds.attrs["im_histogram_edges"]))
    a.hist([im[~mp], im[mp]], bins=edges, stacked=True, label=["one vehicle", "several vehicles"])
    a.axvline(float(ds.attrs["im_mean"]), color="k", ls="--", lw=1, label=f"mean {float(ds.attrs['im_mean']):.3f}")
    lrfd = CODE_STYLES["aashto_lrfd"]
    a.axvline(aashto_lrfd(), color=lrfd.color, ls=lrfd.linestyle, lw=1, label=f"{lrfd.label} IM = {aashto_lrfd():.2f}")
    a.set_xlabel("impact factor IM of the event")
    a.set_ylabel("events")
    a.legend(fontsize="small")
    b.scatter(st[~mp], dyn[~mp], s=6, label="one vehicle")
    b.scatter(st[mp], dyn[mp], s=6, label="several vehicles")
    top = max(st.max(), dyn.max()) * 1.05
    b.plot([0, top], [0, top], "k-", lw=0.8, label="dynamic = static")
    for key, marker in (("governing_static_event", "s"), ("governing_dynamic_event", "^")):
        e = int(ds.attrs[key])
        b.plot(st[e], dyn[e], marker, mfc="none", mec="k", ms=10, label=key.replace("_", " "))
    b.set_xlabel("static peak deflection [mm]")
    b.set_ylabel("dynamic peak deflection [mm]")
    b.legend(fontsize="small")
    fig.suptitle(title or f"{ds.attrs.get('n_events')} events, {ds.attrs.get('n_multiple_presence_events')} with "
                 f"several vehicles; amplification of the governing static event "
                 f"{float(ds.attrs['governing_static_amplification']):.3f}")
    path = Path(path)
    save_figure(fig, path, dpi=120)
    return path
