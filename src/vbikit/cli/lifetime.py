"""``vbikit lifetime``: years of traffic over a bridge → characteristic static and total load
effects, the assessment dynamic ratio and fatigue damage (``vbikit.lifetime``)."""
from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Optional

import typer

from vbikit._words import duration_words
from vbikit.cli.guard import (
    STATE,
    budget_option,
    budget_value,
    figures_option,
    guard,
    input_file_argument,
    json_option,
    memory_option,
    out_dir_option,
    progress_option,
    say,
    say_summary_file,
    scheduler_option,
    use_json,
    workers_option,
)


class _Bars:
    """One tqdm bar per stage: the static pass in days (with trucks/s), each dynamic round in events
    (events/s) with the fraction of the run's events simulated dynamically so far."""

    def __init__(self, enabled: bool) -> None:
        self.enabled, self.bar, self.stage = enabled, None, None
        #: per stage, (done, total) of its first report: what the run found finished and usable of it (a stage run
        #: again from the start reports less than before, and starts its record afresh)
        self.first: dict[str, tuple[int, int]] = {}
        self._last: dict[str, int] = {}

    def resumed(self) -> str:
        """The stages the run found finished (or partly) before it started, in words ("" for none)."""
        from vbikit._words import counted

        whole = sum(1 for d, t in self.first.values() if t and d >= t)
        part = sum(1 for d, t in self.first.values() if 0 < d < t)
        of = f"{part} more" if whole else counted(part, "stage")
        parts = f"{'part' if part == 1 else 'parts'} of {of}" if part else ""
        return " and ".join(filter(None, [counted(whole, "stage") if whole else "", parts]))

    def __call__(self, stage: str, done: int, total: int, info: dict) -> None:
        if stage not in self.first or done < self._last.get(stage, 0):
            self.first[stage] = (done, total)
        self._last[stage] = done
        if not self.enabled:
            return
        if stage != self.stage:
            self.close()
            from tqdm import tqdm

            unit = "day" if stage.startswith("static") else "event"
            self.bar = tqdm(total=total, initial=done, desc=stage, unit=unit, dynamic_ncols=True)
            self.stage = stage
        else:
            self.bar.update(done - self.bar.n)
        rate = self.bar.format_dict.get("rate")
        if "trucks_per_day" in info and rate:
            self.bar.set_postfix_str(f"{rate * info['trucks_per_day']:,.0f} trucks/s", refresh=False)
        if info.get("events"):
            hours = info.get("estimate_hours", math.nan)
            estimate = f"; estimated {duration_words(hours)}" if math.isfinite(hours) else ""
            self.bar.set_postfix_str(f"dynamic {100 * info['dynamic'] / info['events']:.2f} % of "
                                     f"{info['events']:,} events{estimate}", refresh=False)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
            self.bar = None


def lifetime_cmd(
    spec: Path = input_file_argument("LIFETIME.toml", "Lifetime file", "lifetime.md"),
    out_dir: Path = out_dir_option("Folder for lifetime.nc, report.txt, summary.json and the figures (finished batches in work/)."),
    workers: Optional[int] = workers_option(),
    scheduler: Optional[str] = scheduler_option(),
    figures: bool = figures_option(),
    progress: bool = progress_option(),
    as_json: bool = json_option(),
    max_memory: Optional[str] = budget_option("--max-memory", "memory of the whole run", "4GiB"),
    budget_hours: Optional[float] = budget_option("--budget-hours", "estimated hours of the whole run", "2",
                                                  "budget_hours"),
) -> None:
    """Lifetime load effects with dynamics: traffic for days or years from a records file, every
    event's static peak by influence lines, coupled dynamics for the events that can govern each
    day (and a random sample for fatigue), extreme-value fits and return levels, ADR, fatigue
    damage.  An interrupted run started again resumes (finished batches in OUT_DIR/work)."""
    from vbikit._words import counted
    from vbikit.lifetime.run import DATASET_FILE, REPORT_FILE, SUMMARY_FILE, WORK_FOLDER, run_lifetime

    use_json(as_json)
    memory = None if max_memory is None else memory_option(max_memory)
    if budget_hours is not None:
        from vbikit.lifetime.spec import MAX_BUDGET_HOURS

        budget_hours = budget_value(budget_hours, "--budget-hours", MAX_BUDGET_HOURS)
    bars = _Bars(progress and not STATE["quiet"])
    t0, started = time.perf_counter(), time.time()
    from vbikit.cli.guard import say_resumed

    try:
        ds = guard(lambda: run_lifetime(spec, out_dir, workers=workers, scheduler=scheduler, progress=bars,
                                        figures=figures, max_memory=memory,
                                        budget_hours=budget_hours), file=spec)
    except KeyboardInterrupt:
        bars.close()
        typer.echo(f"\ninterrupted: finished batches are kept in {out_dir / WORK_FOLDER}; run the same command again "
                   "to resume", err=True)
        raise typer.Exit(code=130) from None
    bars.close()
    a = ds.attrs
    say((out_dir / REPORT_FILE).read_text())
    from vbikit.cli.guard import say_written

    say_written(out_dir, (DATASET_FILE, REPORT_FILE, SUMMARY_FILE, "lifetime-*.png"), started)
    say(f"{counted(int(a['n_events']), 'event', thousands=True)}, {a['n_dynamic_events']:,} dynamic ({100 * a['fraction_dynamic']:.2f} %) "
        f"-> {out_dir / DATASET_FILE} ({time.perf_counter() - t0:.1f} s)")
    say_resumed(bars.resumed(), out_dir / WORK_FOLDER)
    say_summary_file(out_dir / SUMMARY_FILE)
