"""``vbikit traffic``: a stream of vehicle records over a bridge, run like a study."""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Optional

import typer

from vbikit.cli.guard import (
    DEFAULT_OUT_DIR,
    STATE,
    budget_option,
    check_out_dir,
    figures_option,
    finishing,
    figure_file_option,
    guard,
    input_file_argument,
    json_option,
    limits,
    out_dir_option,
    out_file_option,
    progress_option,
    say_json,
    say_summary_file,
    scheduler_option,
    use_json,
    warn,
    workers_option,
)
from vbikit.cli.guard import say as say_line
from vbikit.cli.study import run_job, warn_dataset
from vbikit.errors import OptionError


def _lanes(text: str) -> list[float]:
    """``--lanes 1.8,-1.8`` → [1.8, -1.8] [m]."""
    try:
        lanes = [float(v) for v in text.split(",")]
    except ValueError:
        raise OptionError(f"--lanes: not a comma-separated list of numbers: {text!r}") from None
    from vbikit._limits import MAX_LATERAL_OFFSET  # (a vehicle centreline's bound, as a scenario's lateral_offset)

    if not all(math.isfinite(y) and abs(y) <= MAX_LATERAL_OFFSET for y in lanes):
        raise OptionError(f"--lanes: lane centres must be finite numbers within ±{MAX_LATERAL_OFFSET:g} m, got {text!r}")
    return lanes


def traffic_cmd(
    records: Path = input_file_argument("RECORDS.csv", "Vehicle records", "traffic.md"),
    bridge: str = typer.Option(..., "--bridge", help="A bridge preset, or a scenario file (bridge, tire, road, crossing, response)."),
    out: Optional[Path] = out_file_option("--out", "The dataset only (NetCDF, .nc); or give --out-dir."),
    out_dir: Optional[Path] = out_dir_option("Folder for traffic.nc, traffic-report.txt, traffic-summary.json and "
                                             "traffic-im.png (finished batches in traffic.nc.parts); instead of --out; "
                                             "default vbikit-out when --out is not given.", default=None),
    lanes: Optional[str] = typer.Option(None, "--lanes", help="Lane centres y [m], comma-separated (lane 1 first); "
                                        "default: two lanes at ∓ deck width/4 on a deck, one lane at y = 0 on a beam "
                                        "(records with lane 2 on a beam need --lanes)."),
    road: Optional[str] = typer.Option(None, "--road", help="Road class (A…H, good/average/poor, none) instead of the scenario's."),
    seed: int = typer.Option(0, "--seed", min=0, help="Seed of the events' random roads."),
    batch_size: int = typer.Option(16, "--batch-size", min=1, help="Events per stored batch."),
    workers: Optional[int] = workers_option(),
    scheduler: Optional[str] = scheduler_option(),
    plot: Optional[Path] = figure_file_option("Write a figure of the IM distribution and the peaks."),
    progress: bool = progress_option(),
    figures: bool = figures_option(),
    outputs: Optional[str] = typer.Option(None, "--outputs", help="The outputs to reduce and store, comma-separated "
                                          "(docs/results.md; default all; the stream statistics' impact_factor, "
                                          "max_dynamic_displacement, max_static_displacement and n_steps always)."),
    max_vehicles: Optional[int] = typer.Option(None, "--max-vehicles", min=1, help="The most vehicle records read "
                                               "(default 100000; a larger file is refused before it is parsed)."),
    max_memory: Optional[str] = budget_option("--max-memory", "memory of each event's run", "4GiB"),
    max_steps: Optional[float] = budget_option("--max-steps", "time steps of each event's run", "5e6"),
    as_json: bool = json_option(),
) -> None:
    """Simulate a traffic stream: every event (vehicles on the bridge together) as one coupled run;
    resumable and parallel like a study.  --out-dir DIR writes the dataset, the report, the summary and the
    figure into DIR, as lifetime, driveby and rail do; --out FILE.nc the dataset only."""
    from vbikit._files import not_an_input, output_names
    from vbikit.traffic.summary import DATASET_FILE, FIGURE_FILE, REPORT_FILE, SUMMARY_FILE, WORK_FOLDER

    use_json(as_json)
    if out is not None and out_dir is not None:
        guard(lambda: _one_output())
    if out is None and out_dir is None:  # the folder every command writes into by default
        out_dir = check_out_dir(DEFAULT_OUT_DIR)
    if out_dir is not None:
        guard(lambda: output_names(out_dir, (DATASET_FILE, REPORT_FILE, SUMMARY_FILE, FIGURE_FILE), (WORK_FOLDER,)))
    dataset = out if out is not None else out_dir / DATASET_FILE
    option = "--out" if out is not None else "--out-dir"
    guard(lambda: not_an_input(dataset, option, [records, Path(bridge)]))  # (a base scenario may be a preset's name)
    lane_y = None if lanes is None else guard(lambda: _lanes(lanes))  # (an option's error at once, before the imports)
    budget = limits(max_memory, max_steps)
    from vbikit.traffic.records import MAX_RECORDS, read_records

    recs = guard(lambda: read_records(records, max_vehicles or MAX_RECORDS), file=records)  # (before the model's imports)
    from vbikit.traffic.study import base_scenario, traffic_study

    base, base_dir = guard(lambda: base_scenario(bridge), file=bridge)
    if road is not None:
        from vbikit.scenario.schema import ROAD_CLASSES

        classes = [c for c in ROAD_CLASSES if c != "psd"]  # (a PSD needs its parameters: a scenario's [road])
        if road not in classes:
            raise typer.BadParameter(f"unknown road class {road!r}; allowed: {', '.join(classes)}", param_hint="'--road'")
        base = {**base, "road": {**base.get("road", {}), "class": road}}
    from vbikit.scenario.schema import parse_scenario
    from vbikit.traffic.base import dropped_section_warnings, template_data

    warn(dropped_section_warnings(guard(lambda: parse_scenario(template_data(base), base_dir), file=bridge).response))
    names = None if outputs is None else [n.strip() for n in outputs.split(",") if n.strip()]
    job = guard(lambda: traffic_study(recs, base, base_dir, lane_y, seed, batch_size, name=records.stem,
                                      source=str(records), outputs=names, limits=budget))
    n_mp = sum(len(e) > 1 for e in job.events)
    if not STATE["quiet"]:  # (-q: errors only)
        typer.echo(f"{records.name}: {len(recs)} vehicles in {job.size} events ({n_mp} with several vehicles), "
                   f"lanes at y = {', '.join(f'{y:g}' for y in job.lanes)} m", err=True)
    if out_dir is not None:
        guard(lambda: out_dir.mkdir(parents=True, exist_ok=True))
    ds = run_job(job, dataset, workers, scheduler, progress, unit="event", option=option)
    with finishing(dataset):  # (a Ctrl-C from here on: the dataset is complete, said so)
        report: list[str] = []  # the lines below, on stdout (stderr with --json) and (--out-dir) in traffic-report.txt

        def say(line: str) -> None:
            say_line(line)
            report.append(line)

        warn_dataset(ds)
        from vbikit.analysis.population_start import start_words

        say(start_words(dict(ds.attrs)))
        from vbikit.analysis.checks import dataset_has_flag
        from vbikit.analysis.sample_intervals import stored_interval_text

        a = dict(ds.attrs)
        if "n_events_without_impact_factor" not in a:
            # a dataset written before 2026-12-06: its IM statistics were NaN when an event had no IM, and its count of
            # small static references took such events in; they are read again from its events as they are now
            # computed (its governing events kept: its half-step check is of them)
            from vbikit.traffic.study import stream_statistics

            a |= {k: v for k, v in stream_statistics(ds).items() if not k.startswith("governing_")}
        first = ds.isel(point=0) if "point" in ds.dims else ds  # the statistics are of the first response point
        implausible, airborne = dataset_has_flag(a, "implausible_deflection"), dataset_has_flag(a, "airborne_wheels")
        doubt = "!" if implausible or airborne else ""
        n_small = int(a["n_small_static_events"])
        n_without = int(a["n_events_without_impact_factor"])
        small_words = ("the other event's IM rests" if n_small == 1 else f"the other {n_small} events' IMs rest") + \
            " on small static references (light vehicles, far lanes): not design values"
        ci = {name: stored_interval_text(a, name) for name in ("im_mean", "im_q95", "im_mean_loaded", "im_q95_loaded")}
        say(f"deflection impact factors at {_first_point_words(job.context().plan.points[0])} (the stream's "
                   "statistics are of this point)")
        if n_small:  # the design values first: the events that load the point
            say(f"impact factor of the events loading the point ({job.size - n_without - n_small} of {job.size}, static peak "
                       f"≥ {float(a['small_static_fraction']):.0%} of the stream's largest): mean "
                       f"{ci['im_mean_loaded']}{doubt}, 95th percentile {ci['im_q95_loaded']}")
        every = f"all events with one at the point ({job.size - n_without} of {job.size})" if n_without else "all events"
        loads = "" if n_small else " (each loads the point)" if n_without else " (every event loads the point)"
        if n_without < job.size:
            say(f"impact factor of {every}{loads}: mean {ci['im_mean']}{doubt}, "
                       f"95th percentile {ci['im_q95']}, max {float(first['impact_factor'].max()):.4f}; mean of the events "
                       f"with {_group_mean('one vehicle', a['im_mean_single'])}, {_group_mean('several', a['im_mean_multiple'])}"
                       + (f"; {small_words}" if n_small else ""))
        else:  # (not "mean n/a, max nan" of "all events with one at the point (0 of 2) (each loads the point)")
            say(f"impact factor: no event has one at the point ({job.size} of {job.size} without a usable static "
                       "reference): no IM statistics")
        if 0 < n_without < job.size:
            say(f"  ({n_without} event{'' if n_without == 1 else 's'} without an impact factor at the point (NaN: "
                       "no usable static reference) left out of these statistics)")
        if n_without < job.size and any("?" in ci[n] for n in ("im_mean", "im_q95") + (("im_mean_loaded", "im_q95_loaded") if n_small else ())):
            say("  (95 % CI: of the statistic over this stream's events; ?: too few events to bound that end)")
        if implausible:
            say("! not meaningful: implausible static deflections (a likely unit mistake in the bridge) — see the "
                       "warning; no statistic of this stream is a result")
        if airborne:
            say(f"! not design values: {int(a['n_airborne_events'])} of {job.size} events had wheels airborne on the "
                       "bridge (event variable airborne_wheels) — see the warning; the road is beyond the model's range")

        from vbikit.outputs import report_unit

        unit, to_unit = report_unit("m")

        def event(name: str, peak: str) -> str:  # the dataset's event index (from 0), its signed peak and when it starts
            e = int(a[f"governing_{name}_event"])
            return (f"{float(first[peak].values[e]) * to_unit:.3f} {unit}, event {e} (starts at "
                    f"t = {float(ds['event_start'].values[e]):.1f} s)")

        say(f"largest static deflection: {event('static', 'max_static_displacement')}, dynamic amplification "
            f"{a['governing_static_amplification']:.4f}; largest dynamic deflection: "
            f"{event('dynamic', 'max_dynamic_displacement')}, {a['governing_dynamic_amplification']:.4f} × the largest "
            "static one (at the first point; events: the dataset's index, from 0)")
        step = dataset_has_flag(a, "stream_step_sensitive")
        changes = {int(a[f"governing_{w}_event"]): float(a[f"governing_{w}_half_step_im_change"]) for w in ("static", "dynamic")}
        say(f"{'!' if step else ''}the governing event{'s' if len(changes) > 1 else ''} at half the time step: IM changes by "
                   + ", ".join(f"{c:+.1e} (event {e})" if math.isfinite(c) else f"not checked (event {e}: above the budget)"
                               for e, c in changes.items())
                   + f" (absolute, the deflection IM at the first point; flagged above {float(a['half_step_tolerance']):g})")
        others = [(abs(c), name, int(a[f"governing_{w}_event"]), c) for w in ("static", "dynamic")
                  for name, c in json.loads(a[f"governing_{w}_half_step_changes"]).items()
                  if name != "impact_factor" and math.isfinite(c)]
        if others:
            _, name, event, change = max(others)
            say(f"{'!' if step else ''}  their other impact factors: the largest change {change:+.1e} ({name}, event {event})")
        if plot is not None:
            from vbikit.plot.traffic import plot_stream

            guard(lambda: plot_stream(ds, plot))
            say_line(f"figure {plot}")
        if out_dir is not None:
            guard(lambda: _write_folder(ds, out_dir, report, figures))
            say_summary_file(out_dir / SUMMARY_FILE)
        else:  # (--out: the dataset only; the summary's object all the same)
            from vbikit.traffic.summary import summary

            say_json(guard(lambda: summary(ds, dataset.name)))


def _one_output() -> None:
    """--out and --out-dir are the two forms of the stream's outputs: at most one is given."""
    raise OptionError("--out or --out-dir: give one, not both (--out FILE.nc: the dataset only; --out-dir DIR: the "
                      "dataset, report, summary and figure; neither: --out-dir vbikit-out)")


def _write_folder(ds, out_dir: Path, report: list[str], figures: bool) -> None:
    """--out-dir: the report, the summary and (``figures``) the figure next to the dataset; says what it wrote."""
    from vbikit._files import json_text, write_text
    from vbikit.traffic.summary import DATASET_FILE, FIGURE_FILE, REPORT_FILE, SUMMARY_FILE, summary

    files = [out_dir / DATASET_FILE,  # (written by the run: said with the others, as every folder command says them)
             write_text(out_dir / REPORT_FILE, "\n".join(report) + "\n"),
             write_text(out_dir / SUMMARY_FILE, json_text(summary(ds), indent=1) + "\n")]
    if figures:
        from vbikit.plot.traffic import plot_stream

        files.append(plot_stream(ds, out_dir / FIGURE_FILE))
    for path in files:
        say_line(f"wrote {path}")


def _first_point_words(point) -> str:
    """The base scenario's first response point as its file gives it: ``girder 4, midspan of the first span`` (x and y where
    given; the defaults named)."""
    where = [f"point {point.name}"] if point.name else []
    if point.girder is not None:
        where.append(f"girder {point.girder}")
    elif point.y is not None:
        where.append(f"y = {point.y:g} m")
    where.append("midspan of the first span" if point.x is None else f"x = {point.x:g} m")
    return ", ".join(where)


def _group_mean(label: str, mean: float) -> str:
    """``label`` and the mean IM of its events, or that the stream has none (its mean is NaN)."""
    import math

    return f"{label} {mean:.4f}" if math.isfinite(float(mean)) else f"{label}: no such event"
