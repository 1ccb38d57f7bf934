"""Figure of a random crossing: the mean history and its ±kσ envelopes at the headline point, with
Monte-Carlo sample histories over them when given."""
from __future__ import annotations

from pathlib import Path
from typing import Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit._files import save_figure
from vbikit.random.response import RandomResponse


def plot_random(rr: RandomResponse, path: str | Path, samples: Sequence[NDArray[np.float64]] = (),
                k: tuple[float, ...] = (1.0, 2.0, 3.0), title: str = "") -> Path:
    """Mid-span (headline point) displacement [mm]: mean (the smooth crossing), mean ± kσ bands
    (PEM) and the displacement histories ``samples`` [m] (Monte-Carlo crossings on the same time
    grid) in grey; the deck acceleration's σ below.  Returns the written file."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = rr.pem.time
    n = min(t.size, rr.points[0].displacement.size)
    mean = rr.points[0].displacement[:n] * 1e3
    std = rr.pem.std("displacement")[:n, 0] * 1e3
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    for s in samples:
        ax.plot(t[:n], np.asarray(s)[:n] * 1e3, color="0.75", lw=0.5)
    for j, kk in enumerate(sorted(k, reverse=True)):
        ax.fill_between(t[:n], mean - kk * std, mean + kk * std, alpha=0.15 + 0.1 * j, color="C0", lw=0,
                        label=f"mean ± {kk:g}σ")
    ax.plot(t[:n], mean, color="k", lw=1.2, label="mean (smooth road)")
    ax.plot(t[:n], rr.points[0].static_displacement[:n] * 1e3, "k--", lw=0.8, label="static")
    ax.set_ylabel("displacement [mm]")
    ax.legend(loc="lower left", fontsize=8)
    if title:
        ax.set_title(title, fontsize=9)
    ax2.plot(t[:n], rr.pem.std("acceleration")[:n, 0], color="C3")
    ax2.set_ylabel("σ acceleration [m/s²]")
    ax2.set_xlabel("time [s]")
    fig.tight_layout()
    return save_figure(fig, path, dpi=120)
