"""``vbikit run``, ``cite``, ``demo`` and ``compare-tires``: the commands on one
scenario file.  Heavy modules are imported inside the commands (start-up stays fast)."""
from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from vbikit.cli.execute import execute, grouped_warnings
from vbikit.cli.guard import (
    MAX_MEMORY,
    MAX_STEPS,
    figure_file_option,
    guard,
    limits,
    out_dir_option,
    out_file_option,
    say,
    use_json,
    warn,
)
from vbikit.cli.render import json_text, outputs, write_text


def run(
    scenario: Path = typer.Argument(..., metavar="SCENARIO.toml", help="TOML scenario file."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object (the summary) on stdout."),
    out: Optional[Path] = out_file_option("--out", "Write time histories to this CSV file."),
    plot: Optional[Path] = figure_file_option("Write a figure (PNG/PDF/SVG) of the response."),
    summary_path: Optional[Path] = out_file_option("--summary", "Write the JSON summary to this file."),
    max_memory: Optional[str] = MAX_MEMORY,
    max_steps: Optional[float] = MAX_STEPS,
    out_dir: Optional[Path] = out_dir_option("Write all three (SCENARIO.csv, SCENARIO.png, SCENARIO.json) into this "
                                             "folder.", default=None),
    random_: bool = typer.Option(False, "--random", help="The random road without sampling: mean ± σ histories "
                                 "and impact-factor quantiles by pseudo-excitation (docs/random.md)."),
) -> None:
    """Simulate one crossing described by a scenario file (writes files only when asked)."""
    from vbikit.scenario import load_scenario

    # the option each output comes from, named in its errors (``--out-dir`` for the ones it names)
    option = {key: key if path is not None or out_dir is None else "--out-dir"
              for key, path in (("--out", out), ("--plot", plot), ("--summary", summary_path))}
    if out_dir is not None:
        stem = scenario.stem
        out, plot, summary_path = (out or out_dir / f"{stem}.csv", plot or out_dir / f"{stem}.png",
                                   summary_path or out_dir / f"{stem}.json")
    from vbikit._files import distinct_outputs, not_an_input

    inputs, spec = [scenario], None  # and the files it reads (a road profile, a modes file): an output must replace none
    if any(path is not None for path in (out, plot, summary_path)):
        spec = guard(lambda: load_scenario(scenario), file=scenario)  # (read once: the run below takes it)
        inputs += spec.input_files()
    for key, path in (("--out", out), ("--plot", plot), ("--summary", summary_path)):
        if path is not None:
            guard(lambda key=key, path=path: not_an_input(path, option[key], inputs))
    guard(lambda: distinct_outputs({"--out": out, "--plot": plot, "--summary": summary_path}))
    budget = limits(max_memory, max_steps)
    if random_:
        from vbikit.cli.random_run import run_random

        return run_random(scenario, budget, as_json, summary_path, plot, out)
    outputs(execute(lambda: spec if spec is not None else load_scenario(scenario), budget, file=scenario), as_json, out,
            plot, summary_path)


def cite(
    scenario: Path = typer.Argument(..., metavar="SCENARIO.toml", help="TOML scenario file."),
    bibtex: bool = typer.Option(False, "--bibtex", help="Print BibTeX entries instead of citations."),
) -> None:
    """Print the publications behind the models a scenario uses (docs/references.md has them all)."""
    from vbikit.references import bibtex as to_bibtex
    from vbikit.scenario import load_scenario
    from vbikit.scenario.cite import scenario_models, scenario_references

    from vbikit.cli.validate import check_kind

    check_kind(scenario, "cite", ("scenario",))
    spec = guard(lambda: load_scenario(scenario), file=scenario)
    refs = scenario_references(spec)
    if bibtex:
        typer.echo(to_bibtex(refs), nl=False)
        return
    typer.echo(f"{scenario}: models {', '.join(scenario_models(spec))}")
    for r in refs:
        typer.echo(f"  [{r.key}] {r.text()}")


def demo(
    out_dir: Path = out_dir_option("Where to write the figure and the JSON summary."),
    as_json: bool = typer.Option(False, "--json", help="Print the JSON summary instead of the text report."),
) -> None:
    """HS20-44 truck over the 16.76 m beam (Bridge 2 stand-in), ISO class C road, multipoint tires, 75 km/h."""
    from vbikit.scenario import demo_scenario_text, scenario_from_toml

    run_ = execute(lambda: scenario_from_toml(demo_scenario_text(), source="demo.toml"))
    outputs(run_, as_json, None, out_dir / "demo.png", out_dir / "demo.json")


def _n_points(n_points: int) -> int:
    """``--n-points`` checked by the multi-point tire's own parameters (its ``tire.n_points`` range), as
    the option's error (was a traceback above 100: the tire table is built from it after the scenario)."""
    from pydantic import ValidationError

    from vbikit._validation import bound_message
    from vbikit.contact.registry import tire_model, tire_parameters
    from vbikit.errors import OptionError

    try:
        tire_parameters("multipoint", {"n_points": n_points})
    except ValidationError as err:
        field = tire_model("multipoint").Parameters.model_fields["n_points"]
        raise OptionError(f"--n-points: {bound_message(err.errors()[0], field) or err.errors()[0]['msg']}") from None
    return n_points


def compare_tires(
    scenario: Path = typer.Argument(..., metavar="SCENARIO.toml", help="TOML scenario file (its [tire] section is replaced by each model)."),
    out_dir: Path = out_dir_option("Where to write the figure and the table."),
    n_points: Optional[int] = typer.Option(None, "--n-points", help="Points of the multi-point tire (tire.n_points, "
                                           "1 … 100); default: the scenario's tire.n_points where its tire is "
                                           "multipoint, else 6."),
    as_json: bool = typer.Option(False, "--json", help="Print the table as JSON."),
    max_memory: Optional[str] = MAX_MEMORY,
    max_steps: Optional[float] = MAX_STEPS,
) -> None:
    """Run one crossing with each tire model (point, multipoint, disk, rigid disk); figure like the
    paper's Fig. 9 and a table of peaks and impact factors."""
    import time

    from vbikit.analysis.response import summary_units
    from vbikit.outputs import OUTPUTS, cf_unit
    from vbikit.plot import plot_tire_comparison
    from vbikit.scenario import load_scenario
    from vbikit.solve.compile_notice import announced_kernels

    use_json(as_json)
    if n_points is not None:
        guard(lambda: _n_points(n_points))
    budget = limits(max_memory, max_steps)
    base = guard(lambda: load_scenario(scenario), file=scenario)
    if n_points is None:  # (the file's own multi-point tire, as every other key of the file is its own)
        n_points = int(getattr(base.tire, "n_points", None) or 6) if base.tire.model == "multipoint" else 6
    # model name (the [tire] model, the JSON's key, --tires' word) -> its label in the text, figure and warnings
    models = {
        "point": ("point", {"model": "point"}),
        "multipoint": (f"multipoint (n = {n_points})", {"model": "multipoint", "n_points": n_points}),
        "disk": ("disk", {"model": "disk"}),
        "rigid-disk": ("rigid disk", {"model": "rigid-disk"}),
    }
    from vbikit.cli.render import acceleration_in_doubt, impact_doubts

    from vbikit.scenario.pipeline import run_planned
    from vbikit.scenario.preflight import preflight

    plans = {}
    for name, (_, tire) in models.items():  # every model checked (budgets, steps) before any of them runs
        spec = base.model_copy(update={"tire": base.tire.model_copy(update=tire)})
        spec._base_dir = base.base_dir
        plans[name] = guard(lambda spec=spec: preflight(spec, budget), file=scenario)
    responses, table, warnings, marks = {}, {}, {}, {}
    for name, plan in plans.items():
        label, tire = models[name]
        t0, compiled_before = time.perf_counter(), announced_kernels()
        run_ = guard(lambda plan=plan: run_planned(plan, budget), file=scenario)
        s = run_.summary
        warnings[label] = (s["warnings"], s["flags"])
        marks[label] = (*impact_doubts(s), acceleration_in_doubt(s, 0))
        responses[label] = run_.response
        table[name] = {
            "label": label, "tire": tire,
            "max_dynamic_displacement": s["max_dynamic_displacement"],
            "max_static_displacement": s["max_static_displacement"],
            "impact_factor": s["impact_factor"],
            "max_dynamic_strain": s["max_dynamic_strain"],
            "strain_impact_factor": s["strain_impact_factor"],
            "max_abs_acceleration": s["max_abs_acceleration"],
            "min_tire_force": min(s["min_wheel_force"].values()),
            "contact_lost": any(v["lost"] for v in s["contact_loss"].values()),
            "seconds": time.perf_counter() - t0,
            # the kernels numba compiled for the first time in this run (their compilation is in "seconds")
            "compiled_kernels": sorted(announced_kernels() - compiled_before),
            "warnings": s["warnings"],  # every one, as its run gave it (stderr: one line per distinct warning)
            "flags": s["flags"],  # (the codes scripts read, vbikit.analysis.checks)
            "response_x": s["response_x"], "response_y": s["response_y"],
            # how good the run's numbers are: its step, and its half-step check (None: not run, a given crossing.dt)
            "dt": s["dt"], "step_check": s.get("step_check"),
        }
        # every number's unit, as vbikit run's JSON spells it (the two keys of this table only: theirs)
        table[name]["units"] = {k: v for k, v in summary_units(table[name]).items() if v} | {
            "min_tire_force": cf_unit(OUTPUTS["min_tire_force"].unit), "seconds": "s"}
    warn(grouped_warnings(warnings, "tire", kept=f", each in {out_dir / 'compare-tires.json'}"))
    fig = guard(lambda: plot_tire_comparison(responses, out_dir / "compare-tires.png", base.name))
    guard(lambda: write_text(out_dir / "compare-tires.json", json_text(table, indent=2) + "\n"))
    written = (fig, out_dir / "compare-tires.json")
    if as_json:  # (the files said on standard error, as every command with --json says them)
        for path in written:
            say(f"wrote {path}")
        typer.echo(json_text(table))
        return
    if base.name:
        typer.echo(base.name)
    from vbikit.outputs import report_unit

    (mm, to_mm), (kn, to_kn) = report_unit("m"), report_unit("N")
    typer.echo(f"  {'tire model':<20} {f'u_max [{mm}]':>10} {'IM [-]':>7} {'ε_max [µε]':>11} {'IM_ε [-]':>8} "
               f"{'|a|max [m/s²]':>13} {f'F_min [{kn}]':>10} {'run time [s]':>12}")
    for row in table.values():
        label = row["label"]
        im, strain, acceleration = ("!" if m else " " for m in marks[label])  # (as vbikit run marks them)
        typer.echo(f"  {label:<20} {row['max_dynamic_displacement'] * to_mm:10.4f} {row['impact_factor']:7.4f}{im}"
                   f"{row['max_dynamic_strain'] * 1e6:11.3f} {row['strain_impact_factor']:8.4f}{strain}"
                   f"{row['max_abs_acceleration']:13.4f}{acceleration}"
                   f"{row['min_tire_force'] * to_kn:10.2f} {row['seconds']:12.2f}" + (" *" if row["compiled_kernels"] else ""))
    from vbikit.scenario.step_check import DT_GIVEN_WORDS, step_check_words

    for row in table.values():  # each run's step check, in vbikit run's words
        c = row["step_check"]
        typer.echo(f"  step check, {row['label']}: {step_check_words(c, True) if c else DT_GIVEN_WORDS}")
    if any(any(m) for m in marks.values()):
        typer.echo("  ! a flag of that model's run puts the value in doubt, as vbikit run marks it: see its warning above")
    if any(row["compiled_kernels"] for row in table.values()):
        typer.echo("  * its run time [s] (wall clock) includes numba's first compilation of a kernel, once a machine; "
                   "later runs take a fraction of it (`vbikit compile` compiles every kernel in advance)")
    from vbikit.cli.render import print_negative_note

    print_negative_note(any(row[k] < 0 for row in table.values() for k in ("impact_factor", "strain_impact_factor")))
    for path in written:  # one line a file, as every command that writes files says them
        say(f"wrote {path}")
