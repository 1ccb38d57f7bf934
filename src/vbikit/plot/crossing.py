"""Figures of one crossing (matplotlib, imported only when a figure is drawn)."""
from __future__ import annotations

from pathlib import Path

from vbikit._files import save_figure
from vbikit.analysis.response import PointResponse
from vbikit.solve.result import CrossingResult


def plot_crossing(result: CrossingResult, response: PointResponse, path: str | Path, title: str = "",
                  metadata: dict[str, str] | None = None) -> Path:
    """Four panels against time: deck displacement (dynamic and static) [mm], bottom-fibre strain
    [µε], deck acceleration [m/s²] at the response point, and the tire forces [kN]. ``metadata``:
    text entries stored in the file (``savefig(metadata=…)``, e.g. PNG ``Description``)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = response.time
    fig, axes = plt.subplots(4, 1, figsize=(8, 9), sharex=True, constrained_layout=True)
    im = response.displacement_impact
    axes[0].plot(t, response.displacement * 1e3, label="dynamic")
    axes[0].plot(t, response.static_displacement * 1e3, "--", label="static")
    axes[0].set_ylabel("displacement [mm]")
    axes[0].legend(loc="lower right")
    axes[0].set_title(title or f"response at x = {response.x:.2f} m, y = {response.y:.2f} m;  IM = {im.impact_factor:.3f}")
    axes[1].plot(t, response.strain * 1e6, label="dynamic")
    axes[1].plot(t, response.static_strain * 1e6, "--", label="static")
    axes[1].set_ylabel("strain [µε]")
    axes[2].plot(t, response.acceleration)
    axes[2].set_ylabel("acceleration [m/s²]")
    for wheel, force in zip(result.crossing.vehicle.wheels, result.wheel_forces.T):
        axes[3].plot(t, force / 1e3, lw=0.8, label=wheel.name)
    axes[3].set_ylabel("tire force [kN]")
    axes[3].set_xlabel("time [s]")
    if len(result.crossing.vehicle.wheels) <= 8:
        axes[3].legend(fontsize="small", ncol=3)
    for ax in axes:
        ax.grid(alpha=0.3)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    save_figure(fig, path, dpi=120, **({"metadata": metadata} if metadata else {}))
    return path
