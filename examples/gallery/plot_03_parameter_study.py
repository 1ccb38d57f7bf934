"""A parameter study: impact factor against speed, with code allowances.

A study sweeps a base scenario over axes; here the HS20-44 on the Bridge 2 beam, single-point
against multi-point tires, five speeds and eight random class C roads (the same eight for every
speed and tire, so differences are not sampling noise). The result is an xarray Dataset with one
dimension per axis; the mean over the samples is drawn with AASHTO's allowances
(LRFD IM = 0.33; Standard Specifications 50/(L + 125) with L in ft).
"""
import os
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from vbikit.plot.labels import axis_label
from vbikit.plot.styles import code_line
from vbikit.study import parse_study, run_study

OUT = Path(os.environ.get("VBIKIT_GALLERY_OUT", "vbikit-out"))

study = parse_study({
    "name": "IM against speed, Bridge 2 beam",
    "seed": 2024,
    "base": {
        "bridge": {"model": "paper-bridge-2-beam", "n_modes": 6},
        "vehicle": {"model": "hs20-44"},
        "tire": {"model": "multipoint"},
        "road": {"class": "C", "length": 300},
        "crossing": {"speed_kmh": 75},
    },
    "axes": {
        "tire.n_points": [1, 6],
        "crossing.speed_kmh": [30, 50, 70, 90, 110],
        "road.seed": {"samples": 8},
    },
})
with tempfile.TemporaryDirectory() as tmp:
    ds = run_study(study, Path(tmp) / "speed.nc", workers=1)

mean, std = ds["impact_factor"].mean("sample"), ds["impact_factor"].std("sample")
speed = ds["crossing_speed_kmh"]
fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
for n, label in ((1, "single-point"), (6, "multi-point, n = 6")):
    ax.errorbar(speed, mean.sel(tire_n_points=n), std.sel(tire_n_points=n), capsize=3, marker="o", label=label)
span_ft = 16.76 / 0.3048
code_line(ax, "aashto_lrfd", 0.33)
code_line(ax, "aashto_standard", min(50 / (span_ft + 125), 0.3))
ax.set(xlabel=axis_label(speed, "speed"), ylabel="impact factor IM [-]",
       title="HS20-44 on the 16.76 m beam, ISO C: mean ± std over 8 roads")
ax.legend(fontsize=8)
OUT.mkdir(parents=True, exist_ok=True)
fig.savefig(OUT / "parameter_study.png", dpi=110)
print(mean.round(4).values)
