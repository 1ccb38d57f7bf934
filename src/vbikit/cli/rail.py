"""``vbikit rail``: speed sweeps of HSLM and real trains over a railway span with the EN 1991-2 /
EN 1990 dynamic checks."""
from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from vbikit.cli.guard import (
    STATE,
    budget_option,
    budget_value,
    figures_option,
    guard,
    input_file_argument,
    json_option,
    out_dir_option,
    progress_option,
    scheduler_option,
    say,
    say_summary_file,
    use_json,
    workers_option,
)


def rail_cmd(
    spec: Path = input_file_argument("RAIL.toml", "Railway file", "railway.md"),
    out_dir: Path = out_dir_option("Folder for rail.nc, rail-report.txt, rail-summary.json and rail-acceleration.png."),
    workers: Optional[int] = workers_option("run.workers"),
    scheduler: Optional[str] = scheduler_option(),
    figures: bool = figures_option(),
    progress: bool = progress_option(),
    as_json: bool = json_option(),
    max_steps: Optional[float] = budget_option("--max-steps", "filter steps of the whole moving-force sweep", "4e9",
                                               "run.budget"),
    max_coupled_steps: Optional[float] = budget_option("--max-coupled-steps", "time steps of the coupled cars over "
                                                       "the whole sweep", "2e6", "coupled.max_steps"),
) -> None:
    """Sweep every train over every speed: envelopes of deck acceleration, deflection, moment and
    shear, phi'dyn, resonance speeds and the pass/fail report.  An interrupted sweep started again
    resumes (finished trains in OUT_DIR/rail.parts).  The trains are swept on local processes
    (--workers) or on a Dask cluster (--scheduler)."""
    from vbikit.rail.run import SUMMARY_FILE, run_rail
    from vbikit.rail.spec import MAX_BUDGET, MAX_COUPLED_STEPS

    use_json(as_json)
    budget = None if max_steps is None else budget_value(max_steps, "--max-steps", MAX_BUDGET)
    coupled_steps = (None if max_coupled_steps is None
                     else budget_value(max_coupled_steps, "--max-coupled-steps", MAX_COUPLED_STEPS))

    bar = None

    def report(done: int, total: int) -> None:
        nonlocal bar
        if not first:
            first.append((done, total))
        if not (progress and not STATE["quiet"]):
            return
        if bar is None:
            from tqdm import tqdm

            bar = tqdm(total=total, desc="rail sweep", unit="train", dynamic_ncols=True)
        bar.update(done - bar.n)

    from vbikit.cli.guard import say_resumed

    first: list[tuple[int, int]] = []  # (the run's first report: the trains it read, finished before)
    try:
        result = guard(lambda: run_rail(spec, out_dir, workers=workers, figures=figures,
                                        progress=report,
                                        scheduler=scheduler, budget=budget, coupled_max_steps=coupled_steps),
                       file=spec)
    except KeyboardInterrupt:
        typer.echo(f"\ninterrupted: finished trains are kept in {out_dir / 'rail.parts'}; run the same command "
                   "again to resume", err=True)
        raise typer.Exit(code=130) from None
    finally:
        if bar is not None:
            bar.close()
    say(result.report, nl=False)
    for f in result.files:  # results, on stdout as every command's (stderr with --json; progress and warnings: stderr)
        say(f"wrote {f}")
    say(f"{result.dataset.train.size} trains × {result.dataset.speed.size} speeds in {result.seconds:.1f} s")
    say_summary_file(out_dir / SUMMARY_FILE)
    done, total = first[0] if first else (0, 0)
    say_resumed(f"{done} of {total} trains" if done else "", out_dir / "rail.parts")
