#!/usr/bin/env python3
"""Compare the two readings of the paper's good / average / poor roads on the Fig. 6 study.

    vbikit study paper-fig6 --out-dir out
    vbikit study run examples/studies/fig6_roughness_reading.toml --out out/fig6-huang-wang.nc
    python tools/roughness_readings.py out/paper-fig6.nc out/fig6-huang-wang.nc

Prints, for each reading, the mean IM per class (over n, speeds and the 20 profiles), the
checks of the paper's claims that Fig. 6 bears on (docs/reproduction.md) and the share of
crossings in which a tire loses contact.  Both datasets use the same seeds, so the two readings
are paired profile by profile (the Huang–Wang profiles are the ISO ones scaled by a constant).
"""
from __future__ import annotations

import sys

import numpy as np
import xarray as xr


def summarise(ds: xr.Dataset, class_dim: str, labels: list[str]) -> None:
    im = ds["impact_factor"]
    print(f"  class: {' / '.join(labels)}")
    mean = im.mean(["tire_n_points", "crossing_speed_kmh", "sample"]).values
    print("  mean IM (all n, speeds, profiles): " + " / ".join(f"{v:.3f}" for v in mean))
    n6 = im.sel(tire_n_points=6).mean("sample")
    print("  mean IM, n = 6, 45 / 75 / 105 km/h:")
    for k, lab in enumerate(labels):
        print(f"    {lab:8s} " + "  ".join(f"{v:.3f}" for v in n6.isel({class_dim: k}).values))
    gap = (im.sel(tire_n_points=1) - im.sel(tire_n_points=6))
    gap_mean = gap.mean("sample")
    print("  claim 1, IM(n=1) − IM(n=6), range over speeds: " + " / ".join(
        f"{float(gap_mean.isel({class_dim: k}).min()):+.3f} … {float(gap_mean.isel({class_dim: k}).max()):+.3f}"
        for k in range(len(labels))) + f"; paired IM(1) > IM(6): {float((gap > 0).mean()) * 100:.0f} %")
    m = im.mean("sample")
    ordered = bool(np.all(np.diff(m.transpose(..., class_dim).values, axis=-1) > 0))
    print(f"  claim 2, IM grows with roughness for every n and speed: {ordered}")
    conv = abs(m - m.sel(tire_n_points=9))
    print(f"  claim 3, max |IM(n) − IM(9)|: n = 3…5 {float(conv.sel(tire_n_points=[3, 4, 5]).max()):.3f}, "
          f"n = 6…8 {float(conv.sel(tire_n_points=[6, 7, 8]).max()):.3f}")
    by_speed = m.mean("tire_n_points")
    lowest = [int(by_speed.isel({class_dim: k}).argmin(dim="crossing_speed_kmh")) for k in range(len(labels))]
    print("  claim 4, speed with the lowest mean IM per class: " + " / ".join(
        str(int(ds["crossing_speed_kmh"].values[i])) for i in lowest) + " km/h")
    lost = (ds["min_tire_force"] <= 0).mean(["tire_n_points", "crossing_speed_kmh", "sample"]).values
    print("  a tire loses contact in: " + " / ".join(f"{v * 100:.0f} %" for v in lost) + " of the crossings")


def main(iso_path: str, hw_path: str) -> None:
    iso, hw = xr.open_dataset(iso_path), xr.open_dataset(hw_path)
    print("ISO 8608 B / C / D at the geometric means (n0 = 0.1 cycle/m: 64 / 256 / 1024 × 1e-6 m³/cycle):")
    summarise(iso, "road_class", ["good", "average", "poor"])
    print("Huang–Wang reading (n0 = 1/(2π) cycle/m: 5 / 20 / 80 × 1e-6 m³/cycle):")
    summarise(hw, "road_phi0", ["good", "average", "poor"])
    ratio = hw["impact_factor"].values / iso["impact_factor"].transpose(*hw["impact_factor"].dims[:2], "road_class",
                                                                       "sample").values
    print("paired IM ratio Huang–Wang / ISO, median per class: " + " / ".join(
        f"{np.median(ratio[:, :, k, :]):.2f}" for k in range(3)))


if __name__ == "__main__":
    main(*sys.argv[1:3])
