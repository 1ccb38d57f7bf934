"""The text report of a drive-by dataset: identification error by speed, road class and noise,
and the damage indicator against the true frequency shift."""
from __future__ import annotations

import numpy as np


def report_text(ds) -> str:
    """A plain-text summary of a drive-by Dataset (``vbikit.driveby.study.dataset``)."""
    err = 100 * np.asarray(ds["frequency_error"].values, float)
    lines = [f"{ds.attrs.get('title', 'drive-by')}: {ds.sizes['case']} cases, sensor rate {ds.attrs['sampling_rate']:g} Hz",
             f"anti-alias filter: {ds.attrs['sampling_filter']}",
             f"identification: method {ds.attrs['identification_method']}, sensor {ds.attrs['identification_sensor']}",
             "", "case  speed[m/s] road seed severity noise   f_true[Hz] f_ident[Hz] error[%] resolution[Hz]"]
    for i in range(ds.sizes["case"]):
        lines.append(f"{i:4d}  {float(ds['speed'][i]):9.2f} {str(ds['road_class'].values[i]):>4} {int(ds['road_seed'][i]):4d} "
                     f"{float(ds['damage_severity'][i]):8.3f} {float(ds['noise_rms'][i]):6.3g} "
                     f"{float(ds['bridge_frequency_hz'][i]):11.4f} {float(ds['identified_frequency_hz'][i]):11.4f} "
                     f"{err[i]:8.2f} {float(ds['resolution_hz'][i]):10.3f}")
    lines += ["", f"identification error: mean |e| {np.mean(np.abs(err)):.2f} %, max |e| {np.max(np.abs(err)):.2f} %"]
    for key in ("speed", "road_class", "noise_rms"):
        values = ds[key].values
        groups = sorted(set(values.tolist()), key=str)
        if len(groups) > 1:
            lines.append(f"  by {key}: " + ", ".join(
                f"{g}: {np.mean(np.abs(err[values == g])):.2f} %" for g in groups))
    shift = np.asarray(ds["identified_frequency_shift"].values, float)
    true = np.asarray(ds["bridge_frequency_shift"].values, float)
    damaged = np.isfinite(shift) & (np.asarray(ds["damage_severity"].values) > 0)
    if damaged.any():
        lines += ["", "damage indicator (frequency shift against the healthy case of the same speed, road and noise):"]
        for i in np.flatnonzero(damaged):
            lines.append(f"  case {i}: severity {float(ds['damage_severity'][i]):.2f} at x = {float(ds['damage_position'][i]):g} m: "
                         f"identified {100 * shift[i]:+.2f} %, true {100 * true[i]:+.2f} % "
                         f"(resolution {100 * float(ds['resolution_hz'][i] / ds['bridge_frequency_hz'][i]):.1f} % of f)"
                         + (f"; mode-shape MAC {float(ds['mode_shape_mac'][i]):.4f}, largest curvature change at "
                            f"x = {float(ds['curvature_change_x'][i]):.3g} m" if np.isfinite(float(ds['mode_shape_mac'][i])) else ""))
    lines.append("")
    lines.append("Spectral resolution is 1 / T for a record of T seconds (T = span / speed on the deck); zero-padding "
                 "interpolates the spectrum, it does not resolve peaks closer than 1 / T.")
    return "\n".join(lines) + "\n"
