"""``vbikit run SCENARIO --random``: the crossing on its random road without sampling (mean ± σ
and the impact factor's distribution by pseudo-excitation)."""
from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from vbikit.cli.guard import guard, warn
from vbikit.cli.render import json_text, write_text


def run_random(scenario: Path, budget, as_json: bool, summary_path: Optional[Path], plot: Optional[Path] = None,
               out: Optional[Path] = None) -> None:
    """Run the random-vibration analysis and print its summary (text, or JSON with ``--json``);
    ``plot``: the figure of the mean and its ±kσ envelopes (``vbikit.random.figure``); ``out``: CSV
    of the mean and σ histories of the deck responses at every point."""
    from vbikit.scenario.pipeline import run_random as run

    rr = guard(lambda: run(scenario, limits=budget), file=scenario)
    s = rr.summary
    if plot is not None:
        from vbikit.random.figure import plot_random

        guard(lambda: plot_random(rr, plot, title=s.get("name", "")))
    if out is not None:
        def table() -> None:
            from vbikit.outputs import csv_unit

            ds = rr.dataset()
            deck = ds[[v for v in ds.data_vars if "point" in ds[v].dims]].drop_vars(["x", "y"])
            frame = deck.to_dataframe()
            # every column headed "name [unit]", as vbikit run's CSV (its unit spelling)
            frame.columns = [f"{c} [{csv_unit(str(ds[c].attrs.get('units', '-')))}]" for c in frame.columns]
            frame.index = frame.index.set_names([f"time [{csv_unit(str(ds['time'].attrs.get('units', 's')))}]", "point"])
            write_text(out, frame.to_csv())

        guard(table)
    if summary_path is not None:
        guard(lambda: write_text(summary_path, json_text(s, indent=2) + "\n"))
    if as_json:
        typer.echo(json_text(s))
        return
    if s.get("name"):
        typer.echo(s["name"])
    typer.echo(f"  method: {s['method']}")
    typer.echo("  values: mean ± standard deviation over the road's realisations")
    from vbikit.outputs import report_unit

    (mm, to_mm), (kn, to_kn) = report_unit("m"), report_unit("N")
    from vbikit.analysis.checks import has_flag
    from vbikit.random.response import point_label

    every = "!" if any(has_flag(s, code) for code in DOUBT_EVERY_IM) else ""  # (every IM statistic in doubt)
    for p in s["points"]:  # (a point's IM on a small static reference: that point's)
        mark = every or ("!" if has_flag(s, "small_static", subject=point_label(p)) else "")
        typer.echo(f"  {point_label(p)}")
        typer.echo(f"    peak displacement  {p['displacement_peak_mean'] * to_mm:9.4f} ± "
                   f"{p['displacement_peak_std'] * to_mm:.4f} {mm}  (static {p['static_peak'] * to_mm:.4f} {mm})")
        _impact_lines(p, mark)
        typer.echo(f"    σ max: displacement {p['displacement_std_max'] * to_mm:.4f} {mm}, acceleration "
                   f"{p['acceleration_std_max']:.4f} m/s², strain {p['strain_std_max'] * 1e6:.3f} µε")
    for e in s.get("effects", []):
        u, k = report_unit(e["units"])  # kN m, kN
        typer.echo(f"  {e['kind']} {e['name']} ({e['method']})")
        typer.echo(f"    peak {e['peak_mean'] * k:12.5g} ± {e['peak_std'] * k:.4g} {u}  (static {e['static_peak'] * k:.5g} {u}), "
                   f"σ max {e['std_max'] * k:.4g} {u}")
        _impact_lines(e, every)
    forces = s.get("wheel_force_std_max", {})
    if forces:
        typer.echo(f"  σ max wheel force [{kn}]: " + ", ".join(f"{w} {v * to_kn:.2f}" for w, v in forces.items()))
    acc = {k: v for k, v in s.get("vehicle_acceleration_std_max", {}).items() if v > 1e-9}
    if acc:
        typer.echo("  σ max vehicle acceleration [m/s², rad/s²]: " + ", ".join(f"{k} {v:.3g}" for k, v in acc.items()))
    typer.echo(f"  lift-off probability (largest at one instant): {s['lift_off_probability']:.3g}")
    from vbikit.cli.render import start_line

    start_line(s)
    refined = s.get("grid_refinements", 0)
    typer.echo(f"  wavenumber lines: {s['n_lines']}, grid check {s['grid_change']:.2%} (σ on every second line "
               f"against every line)" + (f", the default grid's cells halved {refined} time(s) for it" if refined else "")
               + f"; run time {s['seconds']:.1f} s")
    typer.echo(f"  quality: {s['quality']}")
    from vbikit.cli.render import print_negative_note

    print_negative_note(any(v < 0 for e in [*s["points"], *s.get("effects", [])]
                            for v in (e["impact_factor_mean"], *e["impact_factor_quantiles"].values())))
    warn(s["warnings"])
    if every:
        typer.echo("  ! the impact-factor statistics are not design values here — see the warning")


#: the flag codes of a random run (``vbikit.random.response.QUALITY_RULES``) that put every impact-factor statistic in
#: doubt: the linear theory fails where a tire lifts off; a coarse wavenumber grid's σ is off
DOUBT_EVERY_IM = frozenset({"lift_off", "coarse_grid"})


def _impact_lines(e: dict, mark: str) -> None:
    """A point's or load effect's impact-factor statistics: mean ± standard deviation with the mean's sampling error
    (over the Gaussian histories drawn) and the quantiles, ``mark`` ("!": in doubt) beside the numbers."""
    from vbikit.cli.render import im_text

    q = ", ".join(f"{float(k):.0%}: {im_text(v)}{mark}" for k, v in e["impact_factor_quantiles"].items())
    typer.echo(f"    impact factor      {im_text(e['impact_factor_mean']):>9}{mark} ± {e['impact_factor_std']:.4f}   quantiles {q}")
    if "impact_factor_sampling_error" in e:
        typer.echo(f"    {'':<18} (the mean's sampling error ±{e['impact_factor_sampling_error']:.4f}, "
                   f"{e['impact_factor_samples']:,} Gaussian histories)")
