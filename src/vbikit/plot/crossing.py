"""Figures of one crossing (matplotlib, imported only when a figure is drawn)."""
from __future__ import annotations

from pathlib import Path
from typing import Sequence

from vbikit._files import save_figure
from vbikit.analysis.response import PointResponse
from vbikit.solve.result import CrossingResult

#: the most wheels named in the tire-force legend (more: the lines are drawn unnamed)
MAX_LEGEND_WHEELS = 12


def _outside(ax, **kwargs) -> None:
    """A legend right of the panel: it covers neither the curves nor a neighbouring panel
    (constrained layout makes room for it)."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, fontsize="small", **kwargs)


def plot_crossing(result: CrossingResult, response: PointResponse | Sequence[PointResponse], path: str | Path,
                  title: str = "", metadata: dict[str, str] | None = None, names: Sequence[str] | None = None) -> Path:
    """Four panels against time: deck displacement (dynamic and static) [mm], bottom-fibre strain
    [µε] and deck acceleration [m/s²] at every response point in ``response`` (one point or a
    sequence: one colour each, static references dashed; ``names`` label them, default ``p1``,
    ``p2``, …), and the tire forces [kN].  Legends sit right of their panels.  ``metadata``: text
    entries stored in the file (``savefig(metadata=…)``, e.g. PNG ``Description``)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    points = [response] if isinstance(response, PointResponse) else list(response)
    labels = [f"p{i}" for i in range(1, len(points) + 1)] if names is None else [str(n) for n in names]
    several = len(points) > 1
    fig, axes = plt.subplots(4, 1, figsize=(9.5, 9), sharex=True,
                             constrained_layout=True)
    for k, (p, label) in enumerate(zip(points, labels)):
        colour = f"C{k % 10}"
        name = f"{label} (x = {p.x:.2f} m)" if several else "dynamic"
        axes[0].plot(p.time, p.displacement * 1e3, color=colour, label=name)
        axes[0].plot(p.time, p.static_displacement * 1e3, "--", color=colour if several else "C1",
                     label=None if several else "static")
        axes[1].plot(p.time, p.strain * 1e6, color=colour)
        axes[1].plot(p.time, p.static_strain * 1e6, "--", color=colour if several else "C1")
        axes[2].plot(p.time, p.acceleration, color=colour, lw=0.9 if several else 1.5)
    axes[0].set_ylabel("displacement [mm]")
    axes[1].set_ylabel("strain [µε]")
    axes[2].set_ylabel("acceleration [m/s²]")
    if several:
        axes[0].plot([], [], "k--", label="static (dashed)")
        ims = ", ".join(f"{label} {p.displacement_impact.impact_factor:.3f}" for p, label in zip(points, labels))
        axes[0].set_title(title or f"response at {len(points)} points;  IM: {ims}")
    else:
        p = points[0]
        axes[0].set_title(title or f"response at x = {p.x:.2f} m, y = {p.y:.2f} m;  "
                                   f"IM = {p.displacement_impact.impact_factor:.3f}")
    _outside(axes[0])
    wheels = result.crossing.vehicle.wheels
    for wheel, force in zip(wheels, result.wheel_forces.T):
        axes[3].plot(result.time, force / 1e3, lw=0.8, label=wheel.name)
    axes[3].set_ylabel("tire force [kN]")
    axes[3].set_xlabel("time [s]")
    if 0 < len(wheels) <= MAX_LEGEND_WHEELS:
        _outside(axes[3], ncol=1 if len(wheels) <= 8 else 2)
    for ax in axes:
        ax.grid(alpha=0.3)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    save_figure(fig, path, dpi=120, **({"metadata": metadata} if metadata else {}))
    return path
