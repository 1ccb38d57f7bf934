"""Outputs of a field comparison: one figure per loading case (like the paper's Figs. 17–18),
``field-metrics.json`` and ``field-metrics.csv``; ``run_field`` ties the workflow together."""
from __future__ import annotations

import csv
import logging
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from vbikit._files import atomic_write, inside, json_safe, json_text, save_figure, shared_name, write_text
from vbikit.field.io import FieldSpec, load_field_toml
from vbikit.field.workflow import Calibration, CaseComparison, calibrate, check_field, compare_case
from vbikit.solve.budget import Limits

log = logging.getLogger(__name__)

_SCALE = {"displacement": (1e3, "displacement [mm]"), "acceleration": (1.0, "acceleration [m/s²]"),
          "strain": (1e6, "strain [µε]")}
_ORDER = {"displacement": 0, "acceleration": 1, "strain": 2}


def plot_case(cmp: CaseComparison, path: str | Path, title: str = "") -> Path:
    """One panel per channel (displacement, acceleration, strain first), measured (processed) vs each tire model."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    chans = sorted(cmp.case.channels, key=lambda c: (_ORDER[c.quantity], c.girder))
    fig, axes = plt.subplots(len(chans), 1, figsize=(8, 2.6 * len(chans)), sharex=True, constrained_layout=True,
                             squeeze=False)
    for ax, ch, letter in zip(axes[:, 0], chans, "abcdefghijklmnopqrstuvwxyz"):
        f, label = _SCALE[ch.quantity]
        ax.plot(cmp.time, cmp.measured[ch.name] * f, color="k", lw=1.0, label="measured")
        for tire, sims in cmp.simulated.items():
            ax.plot(cmp.time, sims[ch.name] * f, lw=0.9, label=f"{tire} tire")
        ax.set_ylabel(f"({letter}) {label}")
        ax.set_title(f"{ch.name}: girder {ch.girder}, x = {ch.x:g} m", fontsize="small")
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize="small")
    axes[-1, 0].set_xlabel(f"time on the simulation clock [s] (front axle at the span entry at {cmp.t_entry:.3f} s)")
    note = f"low-pass {cmp.lowpass_hz:g} Hz" if cmp.lowpass_hz else "no low-pass"
    fig.suptitle(f"{title} — {cmp.case.name} ({note})" if title else f"{cmp.case.name} ({note})", fontsize="medium")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    save_figure(fig, path, dpi=110)
    return path


def metrics_rows(cmps: list[CaseComparison], label: str = "nominal") -> list[dict[str, Any]]:
    """Flat rows (one per model, case, tire, channel) for the CSV table."""
    rows = []
    for c in cmps:
        for tire, chans in c.metrics.items():
            for name, m in chans.items():
                row = {"model": label, "case": c.case.name, "tire": tire, "channel": name}
                row.update({k: v for k, v in m.items() if k != "psd_bands"})
                for b in m["psd_bands"]:
                    lo, hi = b["band_hz"]
                    row[f"psd_amplitude_ratio_{lo:g}-{hi:g}Hz"] = b["amplitude_ratio"]
                rows.append(row)
    return rows


@dataclass
class FieldRun:
    """Everything ``vbikit field`` produced."""

    spec: FieldSpec
    comparisons: list[CaseComparison]
    figures: list[Path]
    json_path: Path
    csv_path: Path
    calibration: Calibration | None = None
    calibrated: list[CaseComparison] | None = None
    table: dict[str, Any] | None = None


def run_field(path: str | Path, out_dir: str | Path, tires: list[str], do_calibrate: bool = False,
              calibration_tire: str | None = None, limits: Limits | None = None) -> FieldRun:
    """Load FIELD.toml, compare every case with every tire model, optionally calibrate, write outputs; every
    run checked against ``limits`` (the memory and step budgets; None: the defaults) before any runs."""
    spec = load_field_toml(path)
    check_field(spec, tires, limits)
    out = Path(out_dir)
    cmps = [compare_case(spec, case, tires, limits=limits) for case in spec.cases]
    figures = [plot_case(c, inside(out, f"field-{c.case.name}.png"), spec.name) for c in cmps]
    table: dict[str, Any] = {"name": spec.name, "field_file": shared_name(spec.path), "bridge": spec.bridge, "truck": spec.truck,
                             "speed_m_s": spec.speed, "stiffness_factor": spec.stiffness_factor,
                             "damping_ratio": spec.damping_ratio, "tires": tires,
                             "cases": [c.table() for c in cmps]}
    rows = metrics_rows(cmps)
    cal = calibrated = None
    if do_calibrate:
        tire = calibration_tire or tires[-1]
        cal = calibrate(spec, [replace(c) for c in cmps], tire=tire, limits=limits)
        table["calibration"] = cal.as_dict()
        calibrated = [compare_case(spec, case, tires, cal.stiffness_factor, cal.damping_ratio, limits) for case in spec.cases]
        figures += [plot_case(c, inside(out, f"field-{c.case.name}-calibrated.png"),
                              f"{spec.name}, calibrated f = {cal.stiffness_factor:.4f}, ζ = {cal.damping_ratio:.4f}")
                    for c in calibrated]
        table["calibrated_cases"] = [c.table() for c in calibrated]
        rows += metrics_rows(calibrated, "calibrated")
    out.mkdir(parents=True, exist_ok=True)
    json_path = out / "field-metrics.json"
    table, nonfinite = json_safe(table)
    if nonfinite:
        table["warnings"] = [f"{key} is not a finite number (written as null)" for key in nonfinite]
        for text in table["warnings"]:
            log.warning(text)
    write_text(json_path, json_text(table, indent=2) + "\n")
    csv_path = out / "field-metrics.csv"
    keys: list[str] = []
    for r in rows:
        keys += [k for k in r if k not in keys]

    def write_csv(tmp: Path) -> None:
        with tmp.open("w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=keys)
            w.writeheader()
            w.writerows(rows)

    atomic_write(csv_path, write_csv)
    log.info("field comparison written to %s", out)
    return FieldRun(spec, cmps, figures, json_path, csv_path, cal, calibrated, table)
