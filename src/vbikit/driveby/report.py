"""The text report of a drive-by dataset: identification error by speed, road class and noise,
and the damage indicator against the true frequency shift."""
from __future__ import annotations

import numpy as np

from vbikit.analysis.checks import add_flags, dataset_flags, flag_line
from vbikit.driveby.identify import CURVATURE_LOCATION_CAVEAT
from vbikit.driveby.quality import MIN_PASSES, unconverged_pass_flags


#: the most distinct values of a label the report groups the errors by
MAX_GROUPS = 20


class _Columns:
    """The Dataset's variables as numpy arrays, each read once (indexing an xarray variable per
    case costs ~0.1 ms: seconds for a dataset of thousands of passes)."""

    def __init__(self, ds):
        self._ds, self._cache = ds, {}

    def __getitem__(self, name: str) -> np.ndarray:
        if name not in self._cache:
            self._cache[name] = np.asarray(self._ds[name].values)
        return self._cache[name]


def multipass_lines(ds) -> list[str]:
    """One line per bridge (damage state): the multi-pass estimate with its spread, how many passes
    agree, and the multi-pass damage indicator against the healthy bridge."""
    c = _Columns(ds)
    lines = ["multi-pass estimate per bridge (median and interquartile range of the reliable passes; passes that "
             "agree: within their resolution 1/T of the median):"]
    seen = set()
    for i in range(ds.sizes["case"]):
        key = (float(c["damage_severity"][i]), float(np.nan_to_num(c["damage_position"][i])))
        if key in seen:
            continue
        seen.add(key)
        name = "healthy" if key[0] == 0 else f"severity {key[0]:.2f} from x = {key[1]:g} m"
        n, n_rel, n_agree = (int(c[k][i]) for k in ("multipass_n_passes", "multipass_n_reliable", "multipass_n_agree"))
        med = float(c["multipass_frequency_hz"][i])
        if not np.isfinite(med):
            lines.append(f"  {name}: no reliable pass of {n}: no estimate")
            continue
        verdict = ("confirmed" if n_agree >= MIN_PASSES else
                   f"NOT confirmed: fewer than {MIN_PASSES} reliable passes agree")
        shift = float(c["multipass_frequency_shift"][i])
        lines.append(f"  {name}: {med:.4f} Hz (IQR {float(c['multipass_q25_hz'][i]):.4f}–{float(c['multipass_q75_hz'][i]):.4f} Hz, "
                     f"mean {float(c['multipass_mean_hz'][i]):.4f} ± {_spread(float(c['multipass_std_hz'][i]))}), "
                     f"{n_rel} of {n} passes pass the single-pass checks, {n_agree} of them agree: {verdict}"
                     + (f"; shift against the healthy bridge {100 * shift:+.2f} % (true {100 * float(c['bridge_frequency_shift'][i]):+.2f} %)"
                        if key[0] > 0 and np.isfinite(shift) else ""))
    return lines


def _sensor_unit(ds) -> str:
    """", unit" of the identification sensor's record (the dataset's ``sensor_units`` coordinate); "" for a dataset
    without it."""
    ident = str(ds.attrs.get("identification_sensor", ""))
    if "sensor_units" not in ds.coords or "sensor" not in ds.coords:
        return ""
    from vbikit.outputs import csv_unit

    # (the coordinate's CF spelling, as the report writes units: m/s^2)
    units = dict(zip((str(s) for s in ds["sensor"].values), (csv_unit(str(u)) for u in ds["sensor_units"].values)))
    return f", {units[ident]}" if units.get(ident) else ""


def _spread(std: float) -> str:
    """The passes' standard deviation [Hz] in words: "n/a (one pass)" when one reliable pass gives none."""
    return f"{std:.4f} Hz" if np.isfinite(std) else "n/a (one reliable pass)"


def summary(ds) -> dict:
    """The results an engineer reads, as plain data for ``driveby-summary.json``: per case the
    identified frequency [Hz] with its resolution, label, reliability and reason in words, and the
    damage indicator or why it is not given; per bridge the multi-pass estimate [Hz]."""
    c = _Columns(ds)

    def num(name, i):
        v = float(c[name][i])
        return v if np.isfinite(v) else None

    cases = []
    for i in range(ds.sizes["case"]):
        cases.append({
            "case": i, "speed_m_s": num("speed", i), "road_class": str(c["road_class"][i]),
            **({"vehicle": str(ds["fleet"].values[int(c["vehicle"][i])])} if "vehicle" in ds and int(c["vehicle"][i]) >= 0
               else {}),
            "road_seed": int(c["road_seed"][i]), "damage_severity": num("damage_severity", i),
            "identified_frequency_hz": num("identified_frequency_hz", i), "resolution_hz": num("resolution_hz", i),
            "label": str(c["identified_frequency_label"][i]),
            "reliable": bool(c["identified_frequency_reliable"][i]),
            "reason": str(c["identified_frequency_reason"][i]) or "passed every check",
            "peak_snr_db": num("peak_snr_db", i), "true_frequency_hz": num("bridge_frequency_hz", i),
            "frequency_shift": num("identified_frequency_shift", i),
            "frequency_shift_note": str(c["frequency_shift_reason"][i]) or "given",
        })
    bridges = {}
    for i in range(ds.sizes["case"]):
        sev = float(c["damage_severity"][i])
        key = "healthy" if sev == 0 else f"severity {sev:g} from x = {float(c['damage_position'][i]):g} m"
        if key in bridges:
            continue
        n_agree = int(c["multipass_n_agree"][i])
        bridges[key] = {"median_hz": num("multipass_frequency_hz", i), "q25_hz": num("multipass_q25_hz", i),
                        "q75_hz": num("multipass_q75_hz", i), "mean_hz": num("multipass_mean_hz", i),
                        "std_hz": num("multipass_std_hz", i), "passes": int(c["multipass_n_passes"][i]),
                        "reliable_passes": int(c["multipass_n_reliable"][i]), "agreeing_passes": n_agree,
                        "verdict": "confirmed" if n_agree >= MIN_PASSES else
                                   f"not confirmed: fewer than {MIN_PASSES} reliable passes agree",
                        "frequency_shift": num("multipass_frequency_shift", i) if sev > 0 else None}
    out: dict = {}
    if "unconverged_steps" in ds:  # the dataset's flags as records, at the top as in every summary of vbikit
        add_flags(out, unconverged_pass_flags(ds["unconverged_steps"].values))
    return out | {"title": ds.attrs.get("title", "drive-by"), "vbikit_version": str(ds.attrs.get("vbikit_version", "")),
                  "cases": cases, "bridges": bridges,
            "note": "a reliable pass is accurate to about its resolution 1/T on a rough road, far better on a smooth "
                    "one; unreliable passes are left out of the damage indicators and the multi-pass estimates "
                    "(docs/driveby.md, How accurate is this)"}


def fleet_lines(ds) -> list[str]:
    """One line naming the fleet's vehicles and their passes (none without a fleet)."""
    if "vehicle" not in ds or int(np.min(ds["vehicle"].values, initial=0)) < 0:
        return []
    vehicle = np.asarray(ds["vehicle"].values)
    names = [str(n) for n in ds["fleet"].values]
    return ["fleet (label vehicle): " + ", ".join(f"{k} {name}: {int(np.sum(vehicle == k))} passes"
                                                  for k, name in enumerate(names))]


def report_text(ds) -> str:
    """A plain-text summary of a drive-by Dataset (``vbikit.driveby.study.dataset``)."""
    c = _Columns(ds)
    err = 100 * np.asarray(c["frequency_error"], float)
    lines = [f"{ds.attrs.get('title', 'drive-by')}: {ds.sizes['case']} cases, sensor rate {ds.attrs['sampling_rate']:g} Hz",
             f"anti-alias filter: {ds.attrs['sampling_filter']}",
             f"identification: method {ds.attrs['identification_method']}, sensor {ds.attrs['identification_sensor']}",
             *fleet_lines(ds),
             *[flag_line(w) for w in dataset_flags(ds.attrs)[1]],  # (one line a message, from the records)
             "", "case  speed[m/s] road seed severity noise   f_true[Hz] f_ident[Hz] error[%] resolution[Hz] "
                 "label      SNR[dB] reliable",
             f"      (noise: the standard deviation added to the {ds.attrs['identification_sensor']} sensor's record, "
             f"in its unit{_sensor_unit(ds)})"]
    reliable = np.asarray(c["identified_frequency_reliable"], bool)
    # the noise column: the standard deviation added to the identification sensor's record (noise_std), also
    # where its noise is given as an SNR (noise_rms then 0)
    sensors = [str(x) for x in ds["sensor"].values] if "sensor" in ds.coords else []
    ident = str(ds.attrs.get("identification_sensor", ""))
    noise = (np.asarray(c["noise_std"], float)[:, sensors.index(ident)] if "noise_std" in ds and ident in sensors
             else np.asarray(c["noise_rms"], float))
    for i in range(ds.sizes["case"]):
        lines.append(f"{i:4d}  {float(c['speed'][i]):9.2f} {str(c['road_class'][i]):>4} {int(c['road_seed'][i]):4d} "
                     f"{float(c['damage_severity'][i]):8.3f} {float(noise[i]):6.3g} "
                     f"{float(c['bridge_frequency_hz'][i]):11.4f} {float(c['identified_frequency_hz'][i]):11.4f} "
                     f"{err[i]:8.2f} {float(c['resolution_hz'][i]):10.3f}     "
                     f"{str(c['identified_frequency_label'][i]):<10} {float(c['peak_snr_db'][i]):6.1f}  "
                     f"{'yes' if reliable[i] else 'NO'}")
    lines += ["", "unreliable identifications (excluded from the damage indicators and the multi-pass estimates):"]
    lines += [f"  case {i}: {float(c['identified_frequency_hz'][i]):.4g} Hz: {c['identified_frequency_reason'][i]}"
              for i in np.flatnonzero(~reliable)] or ["  none"]
    lines += ["", "identification error of the reliable cases: " + (
        f"mean |e| {np.mean(np.abs(err[reliable])):.2f} %, max |e| {np.max(np.abs(err[reliable])):.2f} %"
        if reliable.any() else "no reliable case"),
        f"identification error of all cases: mean |e| {np.mean(np.abs(err)):.2f} %, max |e| {np.max(np.abs(err)):.2f} %"]
    for key in ("speed", "road_class", "noise_rms", "vehicle"):
        if key not in ds:
            continue
        values = c[key]
        groups = sorted(set(values.tolist()), key=lambda g: (isinstance(g, str), g if not isinstance(g, str) else 0, str(g)))
        unit = str(ds[key].attrs.get("units", "")) if key in ds else ""
        unit = f" [{unit}]" if unit not in ("", "1", "-") else ""
        if 1 < len(groups) <= MAX_GROUPS:  # drawn values (one per pass) form no groups
            lines.append(f"  all cases by {key}{unit} (mean |e|): " + ", ".join(
                f"{g}: {np.mean(np.abs(err[values == g])):.2f} %" for g in groups))
    lines += ["", *multipass_lines(ds)]
    shift = np.asarray(c["identified_frequency_shift"], float)
    true = np.asarray(c["bridge_frequency_shift"], float)
    damaged = np.asarray(c["damage_severity"]) > 0
    curvature = False
    if damaged.any():
        lines += ["", "damage indicator (frequency shift against the healthy case of the same speed, road and noise):"]
        for i in np.flatnonzero(damaged):
            head = f"  case {i}: severity {float(c['damage_severity'][i]):.2f} from x = {float(c['damage_position'][i]):g} m: "
            if not np.isfinite(shift[i]):
                truth = f"true {100 * true[i]:+.2f} %" if np.isfinite(true[i]) else "true shift not known (no healthy case)"
                lines.append(head + f"not given ({c['frequency_shift_reason'][i]}); {truth}")
                continue
            lines.append(head + f"identified {100 * shift[i]:+.2f} %, true {100 * true[i]:+.2f} % "
                         f"(resolution {100 * float(c['resolution_hz'][i] / c['bridge_frequency_hz'][i]):.1f} % of f)"
                         + (f"; mode-shape MAC {float(c['mode_shape_mac'][i]):.4f}, largest curvature change at "
                            f"x = {float(c['curvature_change_x'][i]):.3g} m (*)" if np.isfinite(float(c['mode_shape_mac'][i])) else ""))
            curvature |= bool(np.isfinite(float(c["mode_shape_mac"][i])))
        if curvature:
            lines.append(f"  (*) the largest curvature change's position is {CURVATURE_LOCATION_CAVEAT}")
    lines.append("")
    lines.append("A reliable pass is accurate to about its resolution 1 / T on a rough road and far better on a smooth "
                 "one (docs/driveby.md, How accurate is this): on rough roads use the multi-pass median.")
    lines.append("Spectral resolution is 1 / T for a record of T seconds (T = span / speed on the deck); zero-padding "
                 "interpolates the spectrum, it does not resolve peaks closer than 1 / T.")
    return "\n".join(lines) + "\n"


def write_report(ds, out_dir) -> str:
    """Write ``driveby-report.txt`` and ``driveby-summary.json`` into ``out_dir``; returns the report's text."""
    from pathlib import Path

    from vbikit._files import json_text, write_text
    from vbikit.driveby.spec import REPORT_FILE, SUMMARY_FILE

    text = report_text(ds)
    write_text(Path(out_dir) / REPORT_FILE, text)
    write_text(Path(out_dir) / SUMMARY_FILE, json_text(summary(ds), indent=1) + "\n")
    return text
