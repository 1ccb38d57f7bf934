"""``vbikit field``: measured crossings against the simulated ones (docs/field.md)."""
from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from vbikit.cli.guard import MAX_MEMORY, MAX_STEPS, guard, limits, option, out_dir_option


def _shown(unit: str) -> tuple[float, str]:
    """How the metrics table shows a channel's SI unit: (factor, unit) — a strain ("-") in µε, an
    acceleration as m/s², the rest as every text report does (``vbikit.outputs.report_unit``: a
    displacement in mm)."""
    from vbikit.outputs import report_unit

    if unit == "-":
        return 1e6, "µε"
    if unit == "m/s^2":
        return 1.0, "m/s²"
    shown, factor = report_unit(unit)
    return factor, shown


def field_(
    field_file: Path = typer.Argument(..., metavar="FIELD.toml", help="FIELD.toml describing the measured crossings (docs/field.md)."),
    out_dir: Path = out_dir_option("Where to write the figures and the metrics tables."),
    tires: str = typer.Option("point,multipoint", "--tires", help="Comma-separated tire models: point, multipoint, disk, rigid-disk."),
    calibrate: bool = typer.Option(False, "--calibrate", help="Fit a stiffness factor and damping ratio (least squares)."),
    max_memory: Optional[str] = MAX_MEMORY,
    max_steps: Optional[float] = MAX_STEPS,
) -> None:
    """Compare measured bridge responses with the simulated crossing per tire model; optionally calibrate."""
    from vbikit.field.report import run_field
    from vbikit.field.workflow import parse_tires
    from vbikit.outputs import QUANTITIES

    names = guard(lambda: option(parse_tires, tires))
    budget = limits(max_memory, max_steps)
    run_ = guard(lambda: run_field(field_file, out_dir, names, calibrate, limits=budget), file=field_file)
    typer.echo(run_.spec.name)
    for label, cmps in (("nominal model", run_.comparisons), ("calibrated model", run_.calibrated or [])):
        for c in cmps:
            typer.echo(f"  [{label}] {c.case.name}: time shift {c.shift:+.4f} s (trigger {c.t_entry - c.shift:.4f} s), "
                       f"low-pass {c.lowpass_hz or 'none'} Hz")
            units = {ch.name: QUANTITIES[ch.quantity].unit for ch in c.case.channels if ch.quantity in QUANTITIES}
            for ch, d in c.drift.items():
                scale, unit = _shown(units.get(ch, ""))
                typer.echo(f"    {ch}: removed offset {d.offset * scale:+.4g} {unit}, drift {d.drift * scale:+.4g} "
                           f"{unit} per s ({d.method})")
            typer.echo(f"    {'tire':<11} {'channel':<16} {'peak err [%]':>12} {'RMS err':>18} {'nRMS [-]':>8} "
                       f"{'corr [-]':>8}")
            for tire, chans in c.metrics.items():
                for name, m in chans.items():
                    scale, unit = _shown(units.get(name, ""))
                    rms = f"{m['rms_error'] * scale:.4g} {unit}".rstrip()
                    typer.echo(f"    {tire:<11} {name:<16} {m['peak_error'] * 100:+12.3f} {rms:>18} "
                               f"{m['normalised_rms_error']:8.4f} {m['correlation']:8.4f}")
    cal = run_.calibration
    if cal is not None:
        typer.echo(f"  calibration ({cal.tire} tire, {cal.evaluations} runs, {cal.seconds:.1f} s): stiffness factor "
                   f"{cal.stiffness_factor:.5f} ± {cal.stiffness_factor_std:.2g}, damping ratio {cal.damping_ratio:.5f} "
                   f"± {cal.damping_ratio_std:.2g} (1σ, correlation {cal.correlation:+.2f})")
    for path in (*run_.figures, run_.json_path, run_.csv_path):  # one line a file, as every command that writes files
        typer.echo(f"wrote {path}")
