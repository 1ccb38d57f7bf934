"""``vbikit driveby``: an instrumented vehicle over healthy and damaged bridges, swept into a
labelled dataset (docs/driveby.md)."""
from __future__ import annotations

import time
from pathlib import Path
from typing import Optional

import typer

from vbikit.cli.guard import (
    STATE,
    budget_option,
    figures_option,
    finishing,
    guard,
    input_file_argument,
    json_option,
    out_dir_option,
    progress_option,
    say,
    say_summary_file,
    scheduler_option,
    steps_option,
    use_json,
    workers_option,
)


def driveby_cmd(
    file: Path = input_file_argument("DRIVEBY.toml", "Drive-by file", "driveby.md"),
    out_dir: Path = out_dir_option("Folder for driveby.nc (and driveby.zarr), driveby-report.txt, driveby-summary.json and the figures."),
    workers: Optional[int] = workers_option(),
    scheduler: Optional[str] = scheduler_option(),
    max_steps: Optional[float] = budget_option("--max-steps", "integration steps of the whole sweep", "2e7",
                                               "max_steps"),
    figures: bool = figures_option(),
    progress: bool = progress_option(),
    as_json: bool = json_option(),
) -> None:
    """Simulate an instrumented vehicle over the sweep's bridges, identify the bridge frequency and
    damage indicators, and write a labelled dataset (resumable, processes or Dask)."""
    import dataclasses

    from vbikit.cli.study import run_job, warn_dataset
    from vbikit.driveby.spec import DATASET_FILE, REPORT_FILE, SUMMARY_FILE, ZARR_FILE, load_driveby
    from vbikit.driveby.study import DriveByStudy, check_cases

    use_json(as_json)
    if max_steps is not None:
        max_steps = steps_option(max_steps)
    spec = guard(lambda: load_driveby(file), file=file)
    if max_steps is not None:
        spec = dataclasses.replace(spec, max_steps=float(max_steps))
    steps = guard(lambda: check_cases(spec), file=file)
    if not STATE["quiet"]:  # (-q: errors only)
        typer.echo(f"{file}: {max(1, len(spec.cases))} cases, about {steps:.3g} integration steps", err=True)
    from vbikit._files import output_names

    guard(lambda: output_names(out_dir, (DATASET_FILE,)).mkdir(parents=True, exist_ok=True))
    started = time.time()
    ds = run_job(DriveByStudy(spec), out_dir / DATASET_FILE, workers, scheduler, progress, unit="case",
                 option="--out-dir")
    warn_dataset(ds)

    def finish() -> None:
        from vbikit.cli.guard import say_written
        from vbikit.driveby.study import write_outputs

        say(write_outputs(spec, ds, out_dir, figures))
        say_written(out_dir, (DATASET_FILE, ZARR_FILE, REPORT_FILE, SUMMARY_FILE, "driveby-*.png"), started)
        say_summary_file(out_dir / SUMMARY_FILE)

    with finishing(out_dir / DATASET_FILE):  # (a Ctrl-C from here on: the dataset is complete, said so)
        guard(finish)
