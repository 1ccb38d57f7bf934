"""Figures of study datasets laid out like the paper's Figs. 5–8 and 10–11."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from vbikit._files import save_figure
from vbikit.study.paper import AASHTO_LRFD_IM, AASHTO_STANDARD_IM, CLASS_NAMES, FIGURES

BEAM_NOTE = ("vbikit beam stand-in for the paper's slab-on-girder bridge: impact factors of the whole "
             "cross-section's midspan deflection, not of Girder 4")
GIRDER_NOTE = "vbikit 3D slab-on-girder grillage (10 modes): impact factors of the midspan deflection of Girder 4"



def _reference_lines(ax, bridge: str) -> None:
    ax.axhline(AASHTO_LRFD_IM, color="k", ls="--", lw=0.8, label=f"AASHTO LRFD IM = {AASHTO_LRFD_IM}")
    std = AASHTO_STANDARD_IM.get(bridge)
    if std is not None:
        ax.axhline(std, color="k", ls=":", lw=0.8, label=f"AASHTO Standard 50/(L+125) = {std}")


def plot_paper_figure(ds, fig: str, path: str | Path, variable: str = "impact_factor") -> Path:
    """Mean (markers + line) and ±1 standard deviation (band) over the road samples of
    ``variable``; one panel per road class.  Figs. 5–8: IM vs number of points, one line per
    speed; Figs. 10–11: IM vs speed [km/h], one line per tire model."""
    import matplotlib

    matplotlib.use("Agg")
    import json

    import matplotlib.pyplot as plt

    spec = FIGURES[fig]
    bridge = json.loads(ds.attrs["study"])["base"]["bridge"]["model"]
    note = BEAM_NOTE if bridge.endswith("-beam") else GIRDER_NOTE
    mean = ds[variable].mean("sample")
    std = ds[variable].std("sample", ddof=1) if ds.sizes["sample"] > 1 else 0 * mean
    classes = [str(c) for c in ds["road_class"].values]
    figure, axes = plt.subplots(1, len(classes), figsize=(4.2 * len(classes), 4.2), sharey=True,
                                constrained_layout=True)
    axes = np.atleast_1d(axes)
    if spec["kind"] == "points":
        x, line_dim, xlabel = ds["tire_n_points"].values, "crossing_speed_kmh", "number of points n"
        labels = {v: f"{v:g} km/h" for v in ds[line_dim].values}
    else:
        x, line_dim, xlabel = ds["crossing_speed_kmh"].values, "tire_model", "speed [km/h]"
        labels = {"point": "single-point", "multipoint": "multipoint (n = 6)", "disk": "disk"}
    for ax, cls in zip(axes, classes):
        for value in ds[line_dim].values:
            m = mean.sel({"road_class": cls, line_dim: value}).values
            s = np.asarray(std.sel({"road_class": cls, line_dim: value}).values)
            line, = ax.plot(x, m, "o-", ms=4, label=labels.get(value, str(value)))
            ax.fill_between(x, m - s, m + s, color=line.get_color(), alpha=0.12, lw=0)
        _reference_lines(ax, bridge)
        ax.set_title(f"{CLASS_NAMES.get(cls, cls)} road", fontsize="medium")
        ax.set_xlabel(xlabel)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("impact factor IM (mean ± 1 s.d. over samples)" if variable == "impact_factor" else variable)
    axes[0].legend(fontsize="small")
    n = ds.sizes["sample"]
    figure.suptitle(f"{spec['title']} — vbikit, {n} road profiles per point\n{note}", fontsize="small")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    save_figure(figure, path, dpi=120)
    plt.close(figure)
    return path
