"""Figures of study datasets laid out like the paper's Figs. 5–8 and 10–11, with the design-code
allowances of the study's bridge and vehicle as reference lines (AASHTO LRFD and Standard, CSA S6,
OHBDC 1983, JTG D60-2015; ``vbikit.analysis.codes``)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from vbikit._files import save_figure
from vbikit.study.paper import CLASS_NAMES, FIGURES

BEAM_NOTE = ("vbikit beam stand-in for the paper's slab-on-girder bridge: impact factors of the whole "
             "cross-section's midspan deflection, not of Girder 4")
GIRDER_NOTE = "vbikit 3D slab-on-girder grillage (10 modes): impact factors of the midspan deflection of Girder 4"



def design_code_lines(base: dict) -> dict[str, float]:
    """The design-code allowances (``vbikit.analysis.codes.code_allowances``) of a study's base
    scenario: loaded length = the span of the response point, f₁ of the bridge model, the axles of
    the vehicle (the first of ``[[vehicles]]``) on that span at once (CSA S6, ``axles_on_span``)."""
    from vbikit.analysis.codes import axles_on_span, code_allowances
    from vbikit.analysis.effects import loaded_length
    from vbikit.scenario import build, parse_scenario

    built = build(parse_scenario(base))
    bridge = built.crossing.bridge
    vehicle = built.crossing.vehicles[0].vehicle
    loaded = loaded_length(bridge, built.response_x, built.response_y)
    return code_allowances(loaded, float(bridge.frequencies_hz[0]),
                           axles_on_span([w.offset for w in vehicle.wheels], loaded))


def _reference_lines(ax, codes: dict[str, float]) -> None:
    from vbikit.plot.styles import code_line  # one style table for every figure's code lines

    for key, value in codes.items():
        code_line(ax, key, value)


def plot_paper_figure(ds, fig: str, path: str | Path, variable: str = "impact_factor") -> Path:
    """Mean (markers + line) and ±1 standard deviation (band) over the road samples of
    ``variable`` (a ``method = "pem"`` study: its stored ``<variable>_mean`` and ``_std`` over the
    random road); one panel per road class.  Figs. 5–8: IM vs number of points, one line per
    speed; Figs. 10–11: IM vs speed [km/h], one line per tire model."""
    import matplotlib

    matplotlib.use("Agg")
    import json

    import matplotlib.pyplot as plt

    spec = FIGURES[fig]
    base = json.loads(ds.attrs["study"])["base"]
    bridge = base["bridge"]["model"]
    note = BEAM_NOTE if bridge.endswith("-beam") else GIRDER_NOTE
    codes = design_code_lines(base)
    pem = ds.attrs.get("method") == "pem"  # a study with method = "pem": the distribution is stored (vbikit.study.pem)
    if pem:
        mean, std = ds[f"{variable}_mean"], ds[f"{variable}_std"]
    else:
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
        _reference_lines(ax, codes)
        ax.set_title(f"{CLASS_NAMES.get(cls, cls)} road", fontsize="medium")
        ax.set_xlabel(xlabel)
        ax.grid(alpha=0.3)
    over = "the random road (PEM)" if pem else "samples"
    axes[0].set_ylabel(f"impact factor IM (mean ± 1 s.d. over {over})" if variable == "impact_factor" else variable)
    axes[0].legend(fontsize="small")
    roads = "pseudo-excitation (no sampled roads)" if pem else f"{ds.sizes['sample']} road profiles per point"
    figure.suptitle(f"{spec['title']} — vbikit, {roads}\n{note}", fontsize="small")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    save_figure(figure, path, dpi=120)
    return path
