"""The text report of a drive-by dataset: identification error by speed, road class and noise,
and the damage indicator against the true frequency shift."""
from __future__ import annotations

import numpy as np

from vbikit.driveby.quality import MIN_PASSES


def multipass_lines(ds) -> list[str]:
    """One line per bridge (damage state): the multi-pass estimate with its spread, how many passes
    agree, and the multi-pass damage indicator against the healthy bridge."""
    lines = ["multi-pass estimate per bridge (median and interquartile range of the reliable passes; passes that "
             "agree: within their resolution 1/T of the median):"]
    seen = set()
    for i in range(ds.sizes["case"]):
        key = (float(ds["damage_severity"][i]), float(np.nan_to_num(ds["damage_position"][i])))
        if key in seen:
            continue
        seen.add(key)
        name = "healthy" if key[0] == 0 else f"severity {key[0]:.2f} at x = {key[1]:g} m"
        n, n_rel, n_agree = (int(ds[k][i]) for k in ("multipass_n_passes", "multipass_n_reliable", "multipass_n_agree"))
        med = float(ds["multipass_frequency_hz"][i])
        if not np.isfinite(med):
            lines.append(f"  {name}: no reliable pass of {n}: no estimate")
            continue
        verdict = ("confirmed" if n_agree >= MIN_PASSES else
                   f"NOT confirmed: fewer than {MIN_PASSES} reliable passes agree")
        shift = float(ds["multipass_frequency_shift"][i])
        lines.append(f"  {name}: {med:.4f} Hz (IQR {float(ds['multipass_q25_hz'][i]):.4f}–{float(ds['multipass_q75_hz'][i]):.4f} Hz, "
                     f"mean {float(ds['multipass_mean_hz'][i]):.4f} ± {float(ds['multipass_std_hz'][i]):.4f} Hz), "
                     f"{n_rel} of {n} passes pass the single-pass checks, {n_agree} of them agree: {verdict}"
                     + (f"; shift against the healthy bridge {100 * shift:+.2f} % (true {100 * float(ds['bridge_frequency_shift'][i]):+.2f} %)"
                        if key[0] > 0 and np.isfinite(shift) else ""))
    return lines


def report_text(ds) -> str:
    """A plain-text summary of a drive-by Dataset (``vbikit.driveby.study.dataset``)."""
    err = 100 * np.asarray(ds["frequency_error"].values, float)
    lines = [f"{ds.attrs.get('title', 'drive-by')}: {ds.sizes['case']} cases, sensor rate {ds.attrs['sampling_rate']:g} Hz",
             f"anti-alias filter: {ds.attrs['sampling_filter']}",
             f"identification: method {ds.attrs['identification_method']}, sensor {ds.attrs['identification_sensor']}",
             "", "case  speed[m/s] road seed severity noise   f_true[Hz] f_ident[Hz] error[%] resolution[Hz] "
                 "label      SNR[dB] reliable"]
    reliable = np.asarray(ds["identified_frequency_reliable"].values, bool)
    for i in range(ds.sizes["case"]):
        lines.append(f"{i:4d}  {float(ds['speed'][i]):9.2f} {str(ds['road_class'].values[i]):>4} {int(ds['road_seed'][i]):4d} "
                     f"{float(ds['damage_severity'][i]):8.3f} {float(ds['noise_rms'][i]):6.3g} "
                     f"{float(ds['bridge_frequency_hz'][i]):11.4f} {float(ds['identified_frequency_hz'][i]):11.4f} "
                     f"{err[i]:8.2f} {float(ds['resolution_hz'][i]):10.3f}     "
                     f"{str(ds['identified_frequency_label'].values[i]):<10} {float(ds['peak_snr_db'][i]):6.1f}  "
                     f"{'yes' if reliable[i] else 'NO'}")
    lines += ["", "unreliable identifications (excluded from the damage indicators and the multi-pass estimates):"]
    lines += [f"  case {i}: {float(ds['identified_frequency_hz'][i]):.4g} Hz: {ds['identified_frequency_reason'].values[i]}"
              for i in np.flatnonzero(~reliable)] or ["  none"]
    lines += ["", f"identification error of the reliable cases: " + (
        f"mean |e| {np.mean(np.abs(err[reliable])):.2f} %, max |e| {np.max(np.abs(err[reliable])):.2f} %"
        if reliable.any() else "no reliable case"),
        f"identification error of all cases: mean |e| {np.mean(np.abs(err)):.2f} %, max |e| {np.max(np.abs(err)):.2f} %"]
    for key in ("speed", "road_class", "noise_rms"):
        values = ds[key].values
        groups = sorted(set(values.tolist()), key=str)
        if len(groups) > 1:
            lines.append(f"  by {key}: " + ", ".join(
                f"{g}: {np.mean(np.abs(err[values == g])):.2f} %" for g in groups))
    lines += ["", *multipass_lines(ds)]
    shift = np.asarray(ds["identified_frequency_shift"].values, float)
    true = np.asarray(ds["bridge_frequency_shift"].values, float)
    damaged = np.asarray(ds["damage_severity"].values) > 0
    if damaged.any():
        lines += ["", "damage indicator (frequency shift against the healthy case of the same speed, road and noise):"]
        for i in np.flatnonzero(damaged):
            head = f"  case {i}: severity {float(ds['damage_severity'][i]):.2f} at x = {float(ds['damage_position'][i]):g} m: "
            if not np.isfinite(shift[i]):
                lines.append(head + f"not given ({ds['frequency_shift_reason'].values[i]}); true {100 * true[i]:+.2f} %")
                continue
            lines.append(head + f"identified {100 * shift[i]:+.2f} %, true {100 * true[i]:+.2f} % "
                         f"(resolution {100 * float(ds['resolution_hz'][i] / ds['bridge_frequency_hz'][i]):.1f} % of f)"
                         + (f"; mode-shape MAC {float(ds['mode_shape_mac'][i]):.4f}, largest curvature change at "
                            f"x = {float(ds['curvature_change_x'][i]):.3g} m" if np.isfinite(float(ds['mode_shape_mac'][i])) else ""))
    lines.append("")
    lines.append("Spectral resolution is 1 / T for a record of T seconds (T = span / speed on the deck); zero-padding "
                 "interpolates the spectrum, it does not resolve peaks closer than 1 / T.")
    return "\n".join(lines) + "\n"
