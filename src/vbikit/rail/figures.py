"""Figures of a railway sweep (matplotlib, imported only when a figure is drawn)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from vbikit._files import save_figure


def plot_acceleration_envelopes(ds, path: str | Path, title: str = "") -> Path:
    """Peak deck acceleration [m/s²] against speed [km/h] for every train, the EN 1990 limit and
    each train's resonance speeds n0 D / i (ticks in the train's colour at the top)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 5), constrained_layout=True)
    v = ds["speed_kmh"].values
    top = 0.0
    colours = plt.get_cmap("tab10" if ds.train.size <= 10 else "tab20")
    for k, name in enumerate(ds.train.values):
        y = ds["max_deck_acceleration"].values[k]
        (line,) = ax.plot(v, y, lw=1.2, label=str(name), color=colours(k % colours.N))
        top = max(top, float(np.nanmax(y)))
        for r in ds["resonance_speed"].values[k]:
            if np.isfinite(r) and v.min() <= 3.6 * r <= v.max():
                ax.plot([3.6 * r], [1.0], marker="v", color=line.get_color(), ms=5, transform=ax.get_xaxis_transform(),
                        clip_on=False)
    limit = float(ds["acceleration_limit"])
    ax.axhline(limit, color="tab:red", ls="--", lw=1.2, label=f"limit {limit:g} m/s² ({ds.attrs.get('track', '')})")
    ax.set_xlabel("speed [km/h]")
    ax.set_ylabel("peak deck acceleration [m/s²]")
    ax.set_ylim(0, max(top, limit) * 1.1)
    ax.set_xlim(v.min(), v.max())
    ax.set_title(title or f"span {ds.attrs.get('span_m', 0):g} m, n0 = {ds.attrs.get('first_frequency_hz', 0):.2f} Hz, "
                 f"ζ = {100 * ds.attrs.get('damping_ratio', 0):.2f} % (▼ resonance speeds n0 D / i)", fontsize="medium")
    ax.legend(fontsize="x-small", ncol=2)
    ax.grid(alpha=0.3)
    out = save_figure(fig, path, dpi=120)
    return out
