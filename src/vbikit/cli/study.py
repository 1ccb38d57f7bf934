"""``vbikit study …``: run or check a study file, or the paper's studies.  Heavy modules are
imported inside the commands (start-up stays fast)."""
from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any, Callable, Optional

import typer

from vbikit.cli.guard import (
    STATE,
    budget_option,
    guard,
    input_file_argument,
    limits,
    out_dir_option,
    out_file_option,
    progress_option,
    say,
    say_json,
    scheduler_option,
    use_json,
    warn,
    workers_option,
)

app = typer.Typer(no_args_is_help=True, pretty_exceptions_enable=False, rich_markup_mode=None,
                  help="Parameter studies: run a study file, or the paper's studies (Figs. 5–8, 10, 11).")


class _Bar:
    """tqdm progress bar over crossings (done / total, rate, ETA)."""

    def __init__(self, label: str, enabled: bool = True, unit: str = "crossing") -> None:
        self.label, self.enabled, self.bar, self.unit = label, enabled, None, unit
        #: (done, total) of the run's first report: what it found finished and usable before it started
        self.first: Optional[tuple[int, int]] = None

    def __call__(self, done: int, total: int) -> None:
        if self.first is None:
            self.first = (done, total)
        if not self.enabled:
            return
        if self.bar is None:
            from tqdm import tqdm

            self.bar = tqdm(total=total, initial=done, desc=self.label, unit=self.unit, dynamic_ncols=True)
        else:
            self.bar.update(done - self.bar.n)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def run_job(study: Any, out: Path, workers: Optional[int], scheduler: Optional[str], progress: bool,
            unit: str = "crossing", option: str = "--out", step_check: Optional[dict] = None) -> Any:
    """Run (or resume) ``study`` (or another job of [`run_study`][vbikit.study.run_study]) with a progress bar;
    ``step_check``: the base crossing's, stored with a study's dataset (``run_study``'s)."""
    from vbikit.study.run import run_study

    bar = _Bar(study.name or out.stem, progress and not STATE["quiet"], unit)  # `vbikit -q study …`: no bar
    t0, finished_before = time.perf_counter(), Path(out).is_file()  # (a run on another study's file is refused)
    from vbikit.cli.guard import say_resumed
    from vbikit.study.storage import parts_dir

    try:
        ds = guard(lambda: run_study(study, out, workers=workers, scheduler=scheduler, progress=bar, step_check=step_check))
    except KeyboardInterrupt:
        bar.close()
        typer.echo(f"\ninterrupted: finished batches are kept in {out}.parts; run the same command again to resume",
                   err=True)
        raise typer.Exit(code=130) from None
    bar.close()
    elapsed = time.perf_counter() - t0
    if finished_before:
        say(f"{study.size} {unit}s: {out} already holds this finished run, read as it is (nothing run; "
            f"delete it, or give another {option}, to run again)")
    else:
        say(f"{study.size} {unit}s -> {out} ({elapsed:.1f} s)")
        done, total = bar.first or (0, 0)
        say_resumed(f"{done:,} of {total:,} {unit}s" if 0 < done else "", parts_dir(Path(out)))
    return ds


def warn_dataset(ds: Any) -> None:
    """Print a study's or stream's dataset warnings (its ``warnings`` attribute: the checks over every
    crossing, ``vbikit.analysis.checks.dataset_flag_attrs``) on stderr, as one line (not with ``-q``)."""
    if ds.attrs.get("warnings"):
        warn([str(ds.attrs["warnings"])])


_YES = typer.Option(False, "--yes", help="Run a study of more than 1e6 crossings (refused without it).")
_YES_VALIDATE = typer.Option(False, "--yes", help="Accept a study of more than 1e6 crossings, as `study run --yes` "
                             "would (without it, such a study fails the check).")
_MAX_MEMORY = budget_option("--max-memory", "memory of each batch", "4GiB")
_MAX_STEPS = budget_option("--max-steps", "time steps of each crossing", "5e6")


#: a study check prints at most this many of its warnings (then "… and N more")
MOST_WARNINGS = 10


def _check(study: Any, yes: bool, max_memory: Optional[str], max_steps: Optional[float], label: str = "",
           file: Optional[Path] = None, announce: bool = True, step_check: bool = False) -> Any:
    """Every check the run makes before it starts (vbikit.study.check); prints the warnings on stderr,
    and with ``announce`` (a run: before it starts, as progress) the size first, on stderr too; a
    user error names ``file``, the study file; ``step_check``: the base crossing's too (``study run`` states it)."""
    from vbikit.study.check import check_study

    budget = limits(max_memory, max_steps)
    if announce and not STATE["quiet"]:  # (progress, as the bars: -q prints errors only)
        typer.echo(f"{label or study.name or 'study'}: {study_size(study)}", err=True)
    result = guard(lambda: check_study(study, budget, confirmed=yes, step_check=step_check), file=file)
    warn(result.warnings, most=MOST_WARNINGS)
    return result


#: ``study run --json``'s help: the summary is not a file's (the study writes its dataset only)
STUDY_JSON_HELP = ("Print the study's summary as JSON on standard output (the impact factors by axis value with "
                   "their standard errors, the base crossing's step check, the flags); every other line goes to "
                   "standard error.")


#: the values of a swept axis whose mean impact factor ``study run`` prints (the others: in the dataset)
AXIS_VALUES_SHOWN = 12

_WORKERS = workers_option()
_SCHEDULER = scheduler_option()
_PROGRESS = progress_option()


@app.command("run")
def run_cmd(
    study_file: Path = input_file_argument("STUDY.toml", "Study file", "studies.md"),
    out: Path = out_file_option("--out", "Result dataset (NetCDF, .nc).", ...),
    workers: Optional[int] = _WORKERS,
    scheduler: Optional[str] = _SCHEDULER,
    progress: bool = _PROGRESS,
    yes: bool = _YES,
    max_memory: Optional[str] = _MAX_MEMORY,
    max_steps: Optional[float] = _MAX_STEPS,
    as_json: bool = typer.Option(False, "--json", help=STUDY_JSON_HELP),
) -> None:
    """Run (or resume) a study and write its dataset."""
    from vbikit._files import not_an_input
    from vbikit.study.spec import load_study
    from vbikit.study.summary import study_summary

    use_json(as_json)
    guard(lambda: not_an_input(out, "--out", [study_file]))  # (was refused as "not this study's dataset: delete it")

    study = guard(lambda: load_study(study_file), file=study_file)
    checked = _check(study, yes, max_memory, max_steps, file=study_file, step_check=True)
    ds = run_job(study, out, workers, scheduler, progress, step_check=checked.step_check)
    warn_dataset(ds)
    summary = study_summary(ds, checked.step_check)  # (the text and --json read the same numbers, computed once)
    _say_results(summary)
    say_json(summary)


def _say_results(summary: dict) -> None:
    """The study's impact factors by axis value and its step check (``study_summary``'s), in lines (``say``: standard
    error under --json)."""
    if not summary["impact_factor"]:  # the study's outputs key left it out, or a PEM study's
        say(f"outputs stored: {', '.join(summary['outputs'])}")
        return
    from vbikit.cli.render import print_negative_note

    for row in summary["impact_factor"]:  # (per response point where there are several)
        label = f" at {row['point']}" if "point" in row else ""
        say(f"impact factor over all crossings{label}: mean {row['mean']:.4f}, min {row['min']:.4f}, max {row['max']:.4f}")
        axes = row["axes"]  # each swept axis's values, the mean over the others and the road samples
        for axis in axes:
            shown = ", ".join(f"{v} {m:.4f}" + ("" if math.isnan(se) else f" ± {se:.4f}") for v, m, se in
                              list(zip(axis["values"], axis["means"], axis["standard_error"]))[:AXIS_VALUES_SHOWN])
            more = len(axis["values"]) - AXIS_VALUES_SHOWN
            say(f"  mean by {axis['key']}: {shown}" + (f", … ({more} more in the dataset)" if more > 0 else ""))
            if not math.isnan(axis["difference_error"][-1]):  # the comparison the study makes: paired over the same roads
                diffs = ", ".join(f"{v} {d:+.4f} ± {e:.4f}" for v, d, e in list(zip(
                    axis["values"], axis["difference"], axis["difference_error"]))[1:AXIS_VALUES_SHOWN])
                say(f"    difference from {axis['values'][0]}: {diffs}")
        if any(not math.isnan(se) for axis in axes for se in axis["standard_error"]):
            say("  (± the standard error over the road samples; a difference's paired over the same roads)")
        elif axes:  # one road per cell: the means carry a sampling error the study cannot state
            say("  (one road profile per value: no standard error; a \"road.seed\" = { samples = N } "
                "axis, N ≥ 2, gives one)")
    say_step_check(summary["step_check"])
    print_negative_note(min(row["min"] for row in summary["impact_factor"]) < 0)


def say_step_check(check: Optional[dict]) -> None:
    """How good the study's time step is, in a line: the base crossing's half-step check (``StudyCheck.step_check``),
    the one crossing the study checks (a trial found a study's impact factors printed with no word of it)."""
    from vbikit.scenario.step_check import DT_GIVEN_WORDS, step_check_words

    if check is None:
        say(f"step check of the base crossing: {DT_GIVEN_WORDS}")
        return
    line = f"step check of the base crossing (the other cells are not checked): {step_check_words(check, True)}"
    if check["largest_change"] is not None and check["dt"] * 2 < check["study_dt"] * (1 - 1e-9):
        line += (f" — of a step finer than the {check['study_dt']:.3g} s the study's crossings run at (see the "
                 "warning)")  # (the base's run halved its step more than once for its load effects)
    say(line)


@app.command("validate")
def validate_cmd(
    study_file: Path = input_file_argument("STUDY.toml", "Study file", "studies.md"),
    yes: bool = _YES_VALIDATE,
    max_memory: Optional[str] = _MAX_MEMORY,
    max_steps: Optional[float] = _MAX_STEPS,
) -> None:
    """Check a study file without running it: every check `vbikit study run` makes before it starts
    (every axis value in the schema, the size, and each distinct set-up's time step, stability and budgets)."""
    from vbikit.study.spec import load_study

    study = guard(lambda: load_study(study_file), file=study_file)
    result = _check(study, yes, max_memory, max_steps, file=study_file, announce=False)
    typer.echo(f"{study_file}: ok — {checked_summary(study, result)}")


def checked_summary(study: Any, result: Any) -> str:
    """The summary of a checked study (``vbikit study validate`` and ``vbikit validate``): its size by
    axis, batches, the set-ups checked, their largest step count and memory a batch."""
    from vbikit.solve.budget import human

    return (f"{study_size(study)}; {result.checked} set-ups checked, "
            f"up to {result.max_steps} steps and ≈ {human(result.max_memory)} a batch")


def study_size(study: Any) -> str:
    """A study's size: "N crossings (key (n) × …) in B batches" (the run's announcement, ``checked_summary``)."""
    dims = " × ".join(f"{a.key} ({len(a.values)})" for a in study.axes) or "no axes"
    from vbikit._words import counted

    return f"{counted(study.size, 'crossing')} ({dims}) in {counted(study.n_batches, 'batch', 'batches')}"


def _paper(*figs: str) -> Callable[..., None]:
    """The command that runs the paper studies ``figs`` one after another (the local worker
    processes are shared between them)."""
    def command(
        out_dir: Path = out_dir_option("Where to write the dataset and figure."),
        samples: int = typer.Option(20, "--samples", min=1, help="Road profiles per point (the paper: 20)."),
        workers: Optional[int] = _WORKERS,
        scheduler: Optional[str] = _SCHEDULER,
        progress: bool = _PROGRESS,
        dump: bool = typer.Option(False, "--print-spec", help="Print the study as its dataset's `study` attribute "
                                  "holds it (JSON; resolve, when present, is derived from its outputs, not a key of a "
                                  "study file) and exit."),
        beam: bool = typer.Option(False, "--beam", help="Use the beam stand-ins (whole section) instead of the 3D "
                                                        "bridges at Girder 4."),
        method: str = typer.Option("monte-carlo", "--method", help="monte-carlo (the paper's: --samples roads a "
                                   "point) or pem (the impact factor's distribution by pseudo-excitation, docs/random.md)."),
        yes: bool = _YES,
    ) -> None:
        from vbikit.study.figures import plot_paper_figure
        from vbikit.study.paper import paper_study

        studies = [guard(lambda fig=fig: paper_study(fig, samples, beam, method=method)) for fig in figs]
        if dump:
            for study in studies:
                typer.echo(study.to_json())
            return
        for study in studies:
            _check(study, yes, None, None)
        suffix = ("-beam" if beam else "") + ("-pem" if method == "pem" else "" if samples == 20 else f"-{samples}samples")
        for fig, study in zip(figs, studies):
            out = out_dir / f"paper-{fig}{suffix}.nc"
            ds = run_job(study, out, workers, scheduler, progress)
            warn_dataset(ds)
            png = guard(lambda: plot_paper_figure(ds, fig, out.with_suffix(".png")))
            typer.echo(f"wrote {png}")  # (its dataset: run_job's line "N crossings -> PATH")

    from vbikit.study.paper import FIGURES

    command.__doc__ = (f"{FIGURES[figs[0]]['title']} (dataset + figure)." if len(figs) == 1 else
                       "All the paper's studies (Figs. 5-8, 10, 11), one after another: datasets + figures.")
    return command


PAPER_FIGS = ("fig5", "fig6", "fig7", "fig8", "fig10", "fig11")


def _short_help(*figs: str) -> str:
    """The one-line summary ``vbikit study --help`` shows (given whole: the default first sentence
    would end at the "." of "Fig.")."""
    from vbikit.study.paper import FIGURES

    return (f"Paper {FIGURES[figs[0]]['title']}." if len(figs) == 1 else
            "All six paper studies (Figs. 5–8, 10, 11), one after another.")


for _fig in PAPER_FIGS:
    app.command(f"paper-{_fig}", short_help=_short_help(_fig))(_paper(_fig))
app.command("paper-all", short_help=_short_help(*PAPER_FIGS))(_paper(*PAPER_FIGS))
