"""Tire-model comparison figure, laid out like the paper's Fig. 9."""
from __future__ import annotations

from pathlib import Path

from vbikit._files import save_figure
from vbikit.analysis.response import PointResponse


def plot_tire_comparison(responses: dict[str, PointResponse], path: str | Path, title: str = "") -> Path:
    """Three panels against time, one line per tire model: (a) vertical displacement [mm],
    (b) longitudinal bottom-fibre strain [µε], (c) vertical acceleration [m/s²]."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 1, figsize=(8, 8), sharex=True, constrained_layout=True)
    for name, r in responses.items():
        axes[0].plot(r.time, r.displacement * 1e3, lw=1, label=name)
        axes[1].plot(r.time, r.strain * 1e6, lw=1, label=name)
        axes[2].plot(r.time, r.acceleration, lw=0.8, label=name)
    labels = ("(a) vertical displacement [mm]", "(b) longitudinal strain [µε]", "(c) vertical acceleration [m/s²]")
    for ax, label in zip(axes, labels):
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize="small")
    axes[-1].set_xlabel("time [s]")
    if title:
        axes[0].set_title(title, fontsize="medium")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    save_figure(fig, path, dpi=120)
    return path
