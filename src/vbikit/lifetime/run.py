"""A lifetime run: traffic for days or years, static screening, dynamics where it matters,
extremes and fatigue → one NetCDF dataset (``lifetime.nc``), figures and a text report.

``run_lifetime(spec, out_dir)``:

1. validates everything before any computation (``prepare``: the records, the traffic fit, the
   bridge and its load effects, the S-N curves, the duration against the fits' minimum sample,
   the estimated run time against ``budget_hours``);
2. the static pass (``vbikit.lifetime.jobs.StaticJob``) over every day;
3. dynamics (``DynamicJob``) in rounds: the largest static event of every day and effect plus a
   seeded random sample of events (fatigue, IM statistics), then the events the screening rule
   keeps (``vbikit.lifetime.screening``), then again if an amplification above A was seen;
4. extremes and fatigue (``vbikit.lifetime.results``).

Every stage runs on the study runner (local processes or ``scheduler = "tcp://…"``) with its
finished batches stored under ``out_dir/work``: an interrupted run started again resumes.
"""
from __future__ import annotations

import json
import logging
import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Optional

import numpy as np
from numpy.typing import NDArray

from vbikit._files import shared_name
from vbikit._words import counted, duration_words
from vbikit.lifetime.jobs import EVENT_STRIDE, Detail, DynamicJob, StaticJob, _digest
from vbikit.lifetime.screening import (CHECK_FRACTION, block_dynamic_max, candidates, expected_dynamic_events,
                                       heavy_amplifications, rescreen_bound, top_events)
from vbikit.lifetime.spec import LifetimeError, LifetimeFile, base_sections, parse_lifetime, read_lifetime

log = logging.getLogger(__name__)

#: [substitute] planning costs of the run-time estimate on one core: the static pass per truck and load effect [s],
#: one dynamic event [s] (with its share of the rounds' work); measured 2026-12-07 on one worker over a week of
#: 4,000 trucks a day with point tires (``benchmarks/bench_lifetime.py``, and ``--deck``): 4.0e-5 s and 0.021–0.030 s
#: on the 4-mode beam of ``paper-bridge-2-beam``, 1.45e-4 s and 0.024–0.025 s on the 10-mode deck of
#: ``paper-bridge-2``; the static cost 1.4× the deck's, the event's the upper end (docs/lifetime.md, "Run time and
#: memory")
STATIC_SECONDS_PER_TRUCK = 2e-4
DYNAMIC_SECONDS_PER_EVENT = 0.03
#: events per day and effect the screening is expected to keep, for the estimate before the static pass (measured:
#: 19 on the 4-mode beam, 111 on the 10-mode deck, 4,000 trucks a day, A = 0.6, class B); once the static pass is
#: done its peaks give the count (``vbikit.lifetime.screening.expected_dynamic_events``)
SCREENED_PER_DAY = 20
#: screening: events per block and effect taken in one round (``vbikit.lifetime.screening``)
PER_ROUND = 3
#: most re-screenings after an amplification above the bound was seen
MAX_RESCREENS = 4

def bytes_per_event(n_effects: int) -> float:
    """Bytes per event at the run's peak: the stored static pass (five per-event columns of 8 bytes
    and one of 1, the static peaks: 8 per effect) twice (the parts and their concatenation), and
    five float arrays per effect while the dataset is built (``vbikit.lifetime.results``)."""
    return 2 * (41 + 8 * n_effects) + 5 * 8 * n_effects


#: the fewest events the random dynamic sample may expect (a standard error needs two)
MIN_SAMPLE_EVENTS = 2

#: progress(stage, done, total, info): after every finished batch; info: "events" (of the run, once the
#: static pass is done), "dynamic" (events simulated so far), "trucks_per_day"
Progress = Callable[[str, int, int, dict], None]


@dataclass
class Prepared:
    """A validated lifetime run (``prepare``)."""

    spec: LifetimeFile
    base_dir: Path
    model: Any
    setup_key: str
    setup: Any
    details: tuple[Detail, ...]
    estimate_hours: float
    info: dict = field(default_factory=dict)
    #: the workers the run-time estimates divide by (``prepare``'s ``workers``; not given: all cores, as the run)
    cores: int = 1

    @property
    def n_days(self) -> int:
        return self.spec.n_days

    def static_job(self) -> StaticJob:
        return StaticJob(self.model, self.setup_key, self.n_days, self.spec.seed, self.spec.ds, self.details,
                         self.spec.days_per_batch, self.spec.fatigue.dynamic_sample if self.details else 0.0,
                         _digest=_digest(self.model))

    def dynamic_job(self, items, records: Optional[dict] = None, step_factor: float = 1.0) -> DynamicJob:
        """The dynamics of global events ``items``; ``records``: stored vehicle records by global id;
        ``step_factor``: times the automatic time step."""
        items = tuple(sorted(int(i) for i in items))
        stored = tuple(records.get(i) for i in items) if records else ()
        return DynamicJob(self.model, self.setup_key, self.spec.seed, items, self.details, self.spec.batch_size,
                          self.spec.vehicle_model, stored, step_factor, _digest=_digest(self.model))


def memory_estimate(n_events: float, n_effects: int) -> float:
    """Bytes the run's per-event arrays need at their peak (``bytes_per_event``)."""
    return float(n_events) * bytes_per_event(max(1, n_effects))


def prepare(spec: LifetimeFile | dict, base_dir: str | Path = ".", workers: Optional[int] = None,
            max_memory: Optional[float] = None, budget_hours: Optional[float] = None) -> Prepared:
    """Validate a lifetime run (module docstring, step 1); LifetimeError naming the key.  The run's
    memory (``memory_estimate``, at most one event a truck) is refused above ``max_memory`` [bytes]
    (default ``vbikit.solve.budget.DEFAULT_MAX_MEMORY``; ``vbikit lifetime --max-memory``), its estimated hours above
    ``budget_hours`` (default the file's ``budget_hours``; ``vbikit lifetime --budget-hours``)."""
    from vbikit.extremes import MIN_SAMPLE
    from vbikit.lifetime.setup import build_setup, check_lanes, setup_key
    from vbikit.lifetime.traffic import fit_traffic
    from vbikit.traffic.records import RecordsError, read_records

    if isinstance(spec, dict):
        spec = parse_lifetime(spec)
    if budget_hours is not None:
        spec = spec.model_copy(update={"budget_hours": float(budget_hours)})
    base_dir = Path(base_dir)
    records_path = base_dir / spec.traffic.records
    try:
        records = read_records(records_path)
    except RecordsError as err:
        raise LifetimeError(f"traffic.records: {err}") from None
    if not records:
        raise LifetimeError(f"traffic.records: {records_path.name} holds no vehicle records (a header only); "
                            "the traffic model is fitted to them")
    try:
        model = fit_traffic(records, spec.traffic.mode, spec.traffic.components)
    except ValueError as err:
        raise LifetimeError(f"traffic.records: {records_path.name}: {err}") from None
    if spec.traffic.trucks_per_day is not None:
        factor = spec.traffic.trucks_per_day / model.trucks_per_day
        top = model.max_scale()
        if factor > top * (1 + 1e-9):
            raise LifetimeError(
                f"traffic.trucks_per_day: {spec.traffic.trucks_per_day:g} trucks a day would ask the busiest hour of "
                f"{records_path.name}'s profile for more trucks than its lanes' smallest recorded headways allow "
                f"(lane by lane, at most 3600/h_min an hour, with the congested share of the headways); the "
                f"generator would fall short of it; at most {math.floor(model.trucks_per_day * top):,} trucks a day")
        model = model.scaled(factor)
    if spec.traffic.speed_kmh is not None:
        model = model.with_speed(spec.traffic.speed_kmh / 3.6)
    base, scenario_dir = base_sections(spec, base_dir)  # (a base file's paths point into its own folder)
    effects = [e.model_dump() for e in spec.load_effects]
    n_lanes = max(ln.lane for ln in model.lanes)
    key = setup_key(base, str(scenario_dir), effects, spec.traffic.lanes, n_lanes, spec.dx)
    try:
        setup = build_setup(key)
        check_lanes(setup, [ln.lane for ln in model.lanes])
    except ValueError as err:
        raise LifetimeError(f"{err}") from None
    names = [ln.name for ln in setup.lines]
    details = []
    for i, d in enumerate(spec.fatigue.details):
        where = f"fatigue.details[{i + 1}]"
        if d.effect not in names:
            raise LifetimeError(f"{where}.effect: {d.effect!r} is not a load effect; allowed: {', '.join(names)}")
        det = Detail(d.name, names.index(d.effect), d.factor, d.category, d.gamma_mf, spec.fatigue.histogram_bin,
                     d.size_factor)
        try:
            det.sn()
        except Exception as err:  # FatigueError: unknown category
            raise LifetimeError(f"{where}.category: {err}") from None
        details.append(det)
    n_blocks = spec.n_days // (7 if spec.block == "week" else 1)
    need = MIN_SAMPLE[spec.distribution]
    if n_blocks < need:
        raise LifetimeError(f"days: {spec.n_days} day(s) give {n_blocks} {'daily' if spec.block == 'day' else 'weekly'} maxima; a {spec.distribution} "
                            f"fit needs at least {need} ({_block_advice(spec.block, spec.distribution, need)})")
    if spec.block == "week" and spec.n_days % 7:
        raise LifetimeError(_partial_week_message(spec))
    trucks = model.trucks_per_day * spec.n_days
    events = trucks  # at most one event a truck
    sampled = spec.fatigue.dynamic_sample * events
    if details and sampled < MIN_SAMPLE_EVENTS:
        raise LifetimeError(f"fatigue.dynamic_sample: {spec.fatigue.dynamic_sample:g} of about {events:,.0f} events samples "
                            f"{sampled:.3g} event(s); the fatigue damage ratio and its standard error need at least "
                            f"{MIN_SAMPLE_EVENTS} (raise dynamic_sample or the duration)")
    dyn = spec.n_days * len(names) * (1 + SCREENED_PER_DAY) + spec.fatigue.dynamic_sample * events * (1 if details else 0)
    from vbikit._validation import default_workers
    from vbikit._words import raise_budget
    from vbikit.lifetime.spec import MAX_BUDGET_HOURS

    cores = max(1, workers or default_workers())  # (as the run: ``run_study``'s default, all cores)
    hours = (trucks * STATIC_SECONDS_PER_TRUCK * max(1, len(names)) + dyn * DYNAMIC_SECONDS_PER_EVENT) / cores / 3600
    if hours > spec.budget_hours:
        raise LifetimeError(f"budget_hours: the run is estimated at {_estimate(hours)} on {cores} worker(s) "
                            f"({trucks:,.0f} trucks, about {dyn:,.0f} dynamic events), above budget_hours = "
                            f"{spec.budget_hours:g} h; "
                            f"{raise_budget('budget_hours', '--budget-hours', MAX_BUDGET_HOURS)} to run it")
    from vbikit.solve.budget import DEFAULT_MAX_MEMORY, human

    limit = DEFAULT_MAX_MEMORY if max_memory is None else float(max_memory)
    memory = memory_estimate(events, len(names))
    if memory > limit:
        raise LifetimeError(f"days: the run is estimated to need {human(memory)} of memory ({events:,.0f} events × "
                            f"{len(names)} load effect(s)), above the memory budget {human(limit)}; raise it with "
                            "--max-memory (vbikit lifetime) or max_memory= (run_lifetime), or simulate fewer days")
    return Prepared(spec, base_dir, model, key, setup, tuple(details), hours,
                    {"n_records": len(records), "records": shared_name(spec.traffic.records)},  # (as the file gives it)
                    cores)


def global_ids(static) -> NDArray[np.int64]:
    """Every event's global id (day · ``EVENT_STRIDE`` + its index that day) of the static pass ``static``."""
    return static["ev_day"].values * EVENT_STRIDE + static["ev_index"].values


def dynamics_estimate(prep: Prepared, static, done: NDArray[np.bool_] | None = None,
                      amplification: float | None = None) -> tuple[float, int]:
    """(hours, events) the dynamics still to run are estimated at once the static pass ``static`` is done: the events
    the screening is expected to simulate (``expected_dynamic_events``, from the static peaks, with the bound
    ``amplification``, default the file's A), less those ``done`` marks (a mask over the static pass's events: their
    dynamics are done), at ``DYNAMIC_SECONDS_PER_EVENT`` on ``prep.cores`` workers."""
    signs = np.array([ln.sign for ln in prep.setup.lines])
    sample = np.flatnonzero(static["ev_sample"].values).astype(np.int64)
    bound = prep.spec.amplification if amplification is None else float(amplification)
    expected = expected_dynamic_events(static["ev_static"].values, signs, static["ev_day"].values, prep.n_days, bound,
                                       sample)
    if done is not None and np.any(done):
        expected = expected[~np.asarray(done, bool)[expected]]
    return expected.size * DYNAMIC_SECONDS_PER_EVENT / prep.cores / 3600, int(expected.size)


def finished_dynamics(work: Path) -> NDArray[np.int64]:
    """The global ids of the events whose dynamics the finished rounds under ``work`` hold (``dynamic-<r>.nc``)."""
    import xarray as xr

    ids = [np.zeros(0, np.int64)]
    for path in sorted(work.glob("dynamic-*.nc")):
        if path.is_file() and _round_of(path) > 0:
            with xr.open_dataset(path) as ds:
                ids.append(np.asarray(ds["event"].values, np.int64))
    return np.unique(np.concatenate(ids))


def check_dynamics_budget(prep: Prepared, static, work: Path) -> float:
    """Refuse the dynamics when, estimated from the static pass (``dynamics_estimate``; the events of the finished
    rounds under ``work`` left out), they would take longer than ``budget_hours``: the estimate before the run
    (``prepare``) cannot know how many events the screening keeps (19 a day and effect on the example's beam, 111 on
    its deck); the static pass it ran is kept, and the same command resumes from it.  Returns the estimate [h]."""
    hours, events = dynamics_estimate(prep, static, np.isin(global_ids(static), finished_dynamics(work)))
    log.info("dynamics estimated at %.3g h on %d worker(s) (about %d events the screening keeps)", hours, prep.cores,
             events)
    _refuse_above_budget(prep, hours, events, "after the static pass the dynamics are estimated at",
                         "the screening keeps, from the static peaks")
    return hours


def check_rescreen_budget(prep: Prepared, static, bound: float, given: float, amplified: float,
                          done: NDArray[np.bool_]) -> float:
    """Refuse the dynamics left when the amplification check raised the screening bound (``given`` → ``bound``, an
    event amplified by ``amplified``) and the events the new bound keeps (``dynamics_estimate`` with A = ``bound``,
    those ``done`` marks left out: simulated so far, or held by a finished round of a resumed run) would take longer
    than ``budget_hours``: a raised A can keep many times the events the first estimate counted (the example's week:
    20 % of its events instead of 2 %).  The rounds run so far are kept, and the same command resumes from them.
    Returns the estimate [h]."""
    hours, events = dynamics_estimate(prep, static, done, bound)
    log.info("screening bound raised to A = %.3f: the dynamics left estimated at %.3g h on %d worker(s) (about %d "
             "events)", bound, hours, prep.cores, events)
    _refuse_above_budget(prep, hours, events, f"an event's dynamic increment (IM) {amplified:.3f} exceeded the "
                         f"screening bound A = {given:.3f}, and with A raised to {bound:.3f} the dynamics left are "
                         "estimated at", "more the screening keeps")
    return hours


def _estimate(hours: float) -> str:
    """A run-time estimate in words and in budget_hours' unit: "40 s (0.011 h)", "3.5 h"."""
    words = duration_words(hours)
    return words if words.endswith(" h") else f"{words} ({hours:.2g} h)"


def _refuse_above_budget(prep: Prepared, hours: float, events: int, what: str, whose: str) -> None:
    """The one refusal of dynamics estimated at ``hours`` (``events`` of them) above ``budget_hours``: "budget_hours:
    ``what`` H h on N worker(s) (about E events ``whose``), above budget_hours = B h; raise …"."""
    if hours <= prep.spec.budget_hours:
        return
    from vbikit._words import raise_budget
    from vbikit.lifetime.spec import MAX_BUDGET_HOURS

    raise LifetimeError(f"budget_hours: {what} {_estimate(hours)} on {prep.cores} worker(s) (about "
                        f"{counted(events, 'event', thousands=True)} {whose}), above budget_hours = "
                        f"{prep.spec.budget_hours:g} h; {raise_budget('budget_hours', '--budget-hours', MAX_BUDGET_HOURS)}"
                        ", or run on more workers, to run them")


def _partial_week_message(spec: LifetimeFile) -> str:
    """Weekly blocks over ``days`` that are not whole weeks: the days left over would be simulated and
    then left out of the block maxima (the fit takes whole weeks), silently, their largest event
    too; refused with the whole-week durations either side (``years`` are taken as the whole weeks in
    them, ``LifetimeFile.n_days``)."""
    n, left = spec.n_days, spec.n_days % 7
    lo, hi = n - left, n - left + 7
    return (f"days: {n} days are {n // 7} whole weeks and {left} day(s); block = \"week\" fits the maxima of whole "
            f"weeks, so the last {left} simulated day(s) would be left out of the block maxima, their largest events "
            f"too: give days = {lo} or {hi}, or block = \"day\"")


def _block_advice(block: str, distribution: str, need: int) -> str:
    """What to change when the run has too few block maxima for its fit: only settings other than
    those in use (``MIN_SAMPLE``: the fewest maxima of each distribution)."""
    from vbikit.extremes import MIN_SAMPLE

    days = need * (7 if block == "week" else 1)
    advice = [f"raise days to at least {days}"]
    if block == "week":
        advice.append(f"or block = \"day\" (then days >= {need})")
    if distribution != "gumbel" and MIN_SAMPLE["gumbel"] < need:
        advice.append(f"or distribution = \"gumbel\" (needs {MIN_SAMPLE['gumbel']} maxima)")
    return ", ".join(advice)


def _run(job, path: Path, workers, scheduler, progress: Optional[Progress], stage: str, info: Optional[dict] = None):
    from vbikit.study.run import StudyError, run_study

    def report(done: int, total: int) -> None:
        if progress:
            extra = dict(info or {})
            if "dynamic" in extra:
                extra["dynamic"] += done
            progress(stage, done, total, extra)

    try:
        return run_study(job, path, workers=workers, scheduler=scheduler, progress=report)
    except StudyError as err:
        if "is not this study's finished dataset" not in str(err):
            raise
        work = path.parent  # (a work file of another lifetime run: name the output folder, not the file)
        raise LifetimeError(f"{work.parent} holds work this run cannot use ({path}: another lifetime run's, or an "
                            f"earlier version's): delete {work} or write to another output folder") from None


#: the files a lifetime run writes in its output folder, and the folder of its finished work (resumed by the
#: next run): checked before any computation (``_files.output_names``) and written under these names
DATASET_FILE, SUMMARY_FILE, REPORT_FILE = "lifetime.nc", "summary.json", "report.txt"
WORK_FOLDER = "work"


def run_lifetime(spec: LifetimeFile | dict | str | Path, out_dir: str | Path, base_dir: str | Path | None = None,
                 workers: Optional[int] = None, scheduler: Optional[str] = None,
                 progress: Optional[Progress] = None, figures: bool = True, max_memory: Optional[float] = None,
                 budget_hours: Optional[float] = None):
    """Run (or resume) a lifetime analysis and write ``out_dir/lifetime.nc`` (+ figures, report.txt,
    summary.json).

    ``spec``: a lifetime TOML path, a parsed dict or a ``LifetimeFile``; ``base_dir``: where its
    relative paths point (default: the file's folder, else "."); ``workers`` / ``scheduler``: as
    ``vbikit.study.run_study``; ``progress(stage, done, total)`` after every finished batch;
    ``max_memory``: the memory budget [bytes], ``budget_hours``: the time budget instead of the file's (``prepare``).
    A failure after finished simulations says in a note (``resume_note``; the CLI prints it) that they are kept
    under ``out_dir/work`` and that the same call resumes.
    Returns the dataset."""
    from vbikit._validation import checked_workers

    workers = checked_workers(workers, error=LifetimeError)
    if isinstance(spec, (str, Path)):
        spec, folder = read_lifetime(spec)
        base_dir = folder if base_dir is None else base_dir
    from vbikit._files import output_names

    out_dir = output_names(out_dir, (DATASET_FILE, SUMMARY_FILE, REPORT_FILE), (WORK_FOLDER,))  # (before any computation)
    prep = prepare(spec, base_dir if base_dir is not None else ".", workers, max_memory, budget_hours)
    work = out_dir / WORK_FOLDER
    work.mkdir(parents=True, exist_ok=True)
    try:
        return _simulate_and_write(prep, out_dir, work, workers, scheduler, progress, figures)
    except Exception as err:  # a user error, a full disk, a bug: the finished work stands
        note = resume_note(work)
        # (a study's failed write says so itself; an error about the stored work — a stage file that is
        # not this run's — would only recur on resuming from it)
        if note and "to resume" not in str(err) and str(work) not in str(err):
            err.add_note(note)
        raise


def _stages_after(work: Path, r: int) -> list[Path]:
    """The stored stages that follow dynamics round ``r`` (later rounds and the half-step check), files or parts."""
    later = [p for p in work.glob("dynamic-*.nc*") if _round_of(p) > r]
    return later + list(work.glob("half-step.nc*"))


def _round_of(path: Path) -> int:
    """The round number of a stage file or parts folder ``dynamic-<r>.nc[.parts]`` (-1 for another name)."""
    digits = path.name.removeprefix("dynamic-").split(".", 1)[0]
    return int(digits) if digits.isdigit() else -1


def _remove_stage(path: Path) -> None:
    """A stored stage's file or parts folder removed."""
    import shutil

    if path.is_dir():
        shutil.rmtree(path)
    elif path.exists():
        path.unlink()


def resume_note(work: Path) -> str:
    """What a failed run leaves, in words, when ``work`` holds finished stages (``<stage>.nc``) or batches
    (``<stage>.nc.parts/batch-*.npz``) that the same command resumes from; "" when it holds none."""
    stages = sorted(p.stem for p in work.glob("*.nc") if p.is_file())
    batches = sum(1 for _ in work.glob("*.nc.parts/batch-*.npz"))
    if not stages and not batches:
        return ""
    done = ", ".join(filter(None, [f"stage(s) {', '.join(stages)}" if stages else "",
                                   f"{batches} batch(es) of an unfinished stage" if batches else ""]))
    return (f"the finished simulations are kept in {work} ({done}): fix the cause and run the same command "
            "again to resume; they are not simulated again")


def _simulate_and_write(prep: Prepared, out_dir: Path, work: Path, workers, scheduler, progress, figures: bool):
    """``run_lifetime`` after ``prepare``: every stage (stored under ``work``), the dataset and the files."""
    from vbikit._files import atomic_write, write_text
    from vbikit.lifetime.report import effect_flag_codes, flag_codes, summary, text_report
    from vbikit.lifetime.results import build_dataset

    t0 = time.perf_counter()
    static = _run(prep.static_job(), work / "static.nc", workers, scheduler, progress, "static pass",
                  {"trucks_per_day": prep.model.trucks_per_day})
    t_static = time.perf_counter() - t0
    estimate = check_dynamics_budget(prep, static, work)
    dyn, rounds, bound = _dynamics(prep, static, work, workers, scheduler, progress, estimate)
    _governing(prep, static, dyn, work, workers, scheduler, progress)
    t_total = time.perf_counter() - t0
    ds = build_dataset(prep, static, dyn, rounds, bound, {"time_static_s": t_static, "time_total_s": t_total})
    from vbikit.study.run import _to_netcdf

    facts = summary(ds)
    # (the summary reads neither: the stored file's summary is the same)
    ds.attrs["flag_codes"] = flag_codes(facts)
    ds["load_effect_flag_codes"] = ("load_effect", np.array(effect_flag_codes(facts), dtype=object),
                                    {"long_name": "the codes of each load effect's flags in summary.json, comma-separated "
                                                  "(vbikit.analysis.checks.FLAG_CODES)"})
    atomic_write(out_dir / DATASET_FILE, lambda tmp: _to_netcdf(ds, tmp))
    write_text(out_dir / SUMMARY_FILE, json.dumps(facts, indent=1, allow_nan=False) + "\n")
    write_text(out_dir / REPORT_FILE, text_report(facts))
    if figures:
        from vbikit.lifetime.figures import traffic_figure, write_figures

        write_figures(ds, out_dir)
        traffic_figure(prep.model, out_dir / "lifetime-traffic.png")
    return ds


def _dynamics(prep: Prepared, static, work: Path, workers, scheduler, progress, estimate: float = math.nan):
    """Rounds of dynamics (module docstring); returns the per-event dynamic results (dict by
    global id), the rounds' log and the final amplification bound.  ``estimate``: the hours the dynamics were
    estimated at (``check_dynamics_budget``; the progress reports carry it, and a raised screening bound's
    ``check_rescreen_budget``)."""
    spec = prep.spec
    day = static["ev_day"].values
    gid = global_ids(static)
    results: dict[int, dict[str, np.ndarray]] = {}

    stored = stored_records(static)

    done = [0]
    estimated = [estimate]

    def simulate(new: np.ndarray, r: int) -> np.ndarray:
        job = prep.dynamic_job(gid[new], stored)
        path = work / f"dynamic-{r}.nc"
        finished = path.is_file()  # (a round read back, not run now: its run-ins are those of the version that ran it)
        ds = _run(job, path, workers, scheduler, progress, f"dynamics round {r}",
                  {"events": int(gid.size), "dynamic": done[0], "estimate_hours": estimated[0]})
        again = job.run_in_problem(ds["event"].values, ds["run_in"].values) if finished and "run_in" in ds else None
        if again:  # (a round finished by an earlier version that gave its events other run-ins: run again)
            log.info("dynamics round %d: %s; running it again, and the stages after it", r, again)
            for later in _stages_after(work, r):  # (the next rounds' events and the half-step check follow from
                _remove_stage(later)             # this round's peaks: theirs would no longer be this run's)
            path.unlink()
            ds = _run(job, path, workers, scheduler, progress, f"dynamics round {r}",
                      {"events": int(gid.size), "dynamic": done[0], "estimate_hours": estimated[0]})
        done[0] += int(new.size)
        # (a round finished before the start's settling was stored: computed from the events' crossings)
        left, needed = (ds["start_transient_left"].values, ds["start_settling_run_in"].values) \
            if "start_settling_run_in" in ds else job.start_settling(
                ds["event"].values, ds["run_in"].values if "run_in" in ds else np.zeros(ds["event"].size))  # (at rest)
        for k, g in enumerate(ds["event"].values):
            results[int(g)] = {v: ds[v].values[k] for v in ("dyn_peak", "run_static_peak", "damage_dynamic",
                                                             "damage_static", "max_range_dynamic", "unconverged_steps",
                                                             "run_in") if v in ds}
            results[int(g)]["start_transient_left"] = float(left[k])
            results[int(g)]["start_settling_run_in"] = float(needed[k])
        return np.stack([results[int(g)]["dyn_peak"] for g in gid[new]])

    sample = np.flatnonzero(static["ev_sample"].values).astype(np.int64)
    signs = np.array([ln.sign for ln in prep.setup.lines])

    def rescreened(bound: float, given: float, amplified: float, simulated: np.ndarray) -> None:
        done = np.isin(gid, finished_dynamics(work)) | simulated  # (a resumed run's later rounds are done already)
        estimated[0] = check_rescreen_budget(prep, static, bound, given, amplified, done)

    simulated, _, rounds, bound = screen(static["ev_static"].values, signs, day, prep.n_days, spec.amplification,
                                         simulate, sample, on_rescreen=rescreened)
    return {"gid": gid, "simulated": simulated, "results": results, "sample": sample, "records": stored}, rounds, bound


def _governing(prep: Prepared, static, dyn: dict, work: Path, workers, scheduler, progress) -> None:
    """The governing events (``vbikit.lifetime.governing``): their vehicles and their re-run at half
    the time step, added to ``dyn`` as "governing" (event indices), "vehicles" and "half_step" (by
    global id)."""
    from vbikit.lifetime.governing import event_vehicles, governing_events

    signs = np.array([ln.sign for ln in prep.setup.lines])
    total = _dyn_matrix(dyn["results"], dyn["gid"], dyn["simulated"], signs.size)
    gov = governing_events(static["ev_static"].values, total, signs, dyn["simulated"])
    items = np.unique(dyn["gid"][gov[gov >= 0]])
    ds = _run(prep.dynamic_job(items, dyn["records"], step_factor=0.5), work / "half-step.nc", workers, scheduler,
              progress, "governing events at half step")
    dyn["governing"] = gov
    dyn["half_step"] = {int(g): {v: ds[v].values[k] for v in ("dyn_peak", "run_static_peak")}
                        for k, g in enumerate(ds["event"].values)}
    dyn["vehicles"] = {int(g): event_vehicles(prep, dyn["records"], int(g)) for g in items}


def screen(static: np.ndarray, signs: np.ndarray, block: np.ndarray, n_blocks: int, amplification: float,
           simulate: Callable[[np.ndarray, int], np.ndarray], extra: np.ndarray = np.zeros(0, np.int64),
           per_round: int = PER_ROUND,
           on_rescreen: Optional[Callable[[float, float, float, np.ndarray], None]] = None
           ) -> tuple[np.ndarray, np.ndarray, list, float]:
    """The screening of ``vbikit.lifetime.screening`` around a simulator: ``simulate(indices,
    round)`` returns the dynamic peaks (n, n_effects) of those events.  Round 1: the largest static
    event of every block and effect, and ``extra`` (the random sample); then rounds of
    per_round · 2^(k−1) events per block and effect (round k + 1) kept by the rule, until none is left; then the
    amplification check on the simulated events whose static peak is at least ``CHECK_FRACTION``
    of their block's largest (re-screening with A = 1.25 × the largest amplification seen there,
    at most ``MAX_RESCREENS`` times); before each re-screening ``on_rescreen(new bound, bound, largest
    amplification, simulated mask)`` when given (it may raise: the run's budget, ``check_rescreen_budget``).
    Returns (simulated mask, dynamic peaks (NaN where not simulated), rounds, the bound used)."""
    n, m = static.shape
    dyn = np.full((n, m), np.nan)
    simulated = np.zeros(n, bool)
    rounds: list[dict] = []

    def run(select: np.ndarray, r: int) -> None:
        new = np.setdiff1d(select, np.flatnonzero(simulated))
        if new.size:
            dyn[new] = simulate(new, r)
            simulated[new] = True
        rounds.append({"round": r, "new_events": int(new.size), "simulated": int(simulated.sum())})

    run(np.union1d(top_events(static, signs, block), extra), 1)
    bound = float(amplification)
    r, rescreens = 1, 0
    while True:
        threshold = block_dynamic_max(dyn, signs, block, simulated, n_blocks)
        # rounds grow geometrically (per_round, 2·per_round, 4·per_round, …): few rounds when a block keeps many
        todo = candidates(static, signs, block, threshold, bound, simulated, per_round * 2 ** max(0, r - 1))
        if todo.size:
            r += 1
            run(todo, r)
            continue
        amp = heavy_amplifications(dyn, static, signs, block, n_blocks, simulated, CHECK_FRACTION)
        new_bound = rescreen_bound(amp.ravel(), bound)
        if new_bound <= bound or rescreens >= MAX_RESCREENS:
            break
        log.warning("an event's dynamic increment (IM) %.3f exceeds the screening bound A = %.3f: screening again "
                    "with A = %.3f", np.nanmax(amp), bound, new_bound)
        if on_rescreen is not None:  # (e.g. the run's budget for the events the new bound keeps: it may refuse)
            on_rescreen(new_bound, bound, float(np.nanmax(amp)), simulated.copy())
        rounds[-1]["rescreen_to"] = new_bound
        bound, rescreens = new_bound, rescreens + 1
    return simulated, dyn, rounds, bound


def _dyn_matrix(results, gid, simulated, n_lines) -> np.ndarray:
    out = np.full((gid.size, n_lines), np.nan)
    for k in np.flatnonzero(simulated):
        out[k] = results[int(gid[k])]["dyn_peak"]
    return out


def stored_records(static) -> dict[int, tuple]:
    """The vehicle records the static pass stored, by global event id (``StaticJob``)."""
    from vbikit.traffic.records import VehicleRecord

    ev = static["rec_event"].values
    n_ax = static["rec_n_axles"].values
    loads, spacings = static["rec_loads"].values, static["rec_spacings"].values
    la = np.concatenate([[0], np.cumsum(n_ax)])
    sa = np.concatenate([[0], np.cumsum(np.maximum(n_ax - 1, 0))])
    time, speed = static["rec_time"].values, static["rec_speed"].values
    lane, direction = static["rec_lane"].values, static["rec_direction"].values
    out: dict[int, list] = {}
    for k in range(ev.size):
        out.setdefault(int(ev[k]), []).append(VehicleRecord(
            float(time[k]), "+x" if direction[k] > 0 else "-x", float(speed[k]), tuple(map(float, loads[la[k]:la[k + 1]])),
            tuple(map(float, spacings[sa[k]:sa[k + 1]])), lane=int(lane[k])))
    return {g: tuple(v) for g, v in out.items()}
