"""Running one scenario for the command line: ``execute`` is the only place that does.

``execute(load, limits) -> Report`` checks, runs and reports one scenario through the library's
run pipeline (``vbikit.scenario.pipeline``, the same path as [`vbikit.run`][vbikit.scenario.run]); its
``summary`` is the dict ``vbikit run --json`` prints.  Every scenario command (run, demo,
compare-tires) calls it.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, Callable

from vbikit.cli.guard import guard, warn

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.scenario.report import Report


def execute(load: Callable[[], Any], limits: Any = None, label: str = "", print_warnings: bool = True,
            file: Any = None) -> "Report":
    """Check (``load()`` returns a Scenario; every check of ``vbikit.scenario.preflight.preflight``),
    run and report it (``vbikit.scenario.pipeline.run_planned``); user errors exit with code 2,
    the summary's warnings go to stderr, each prefixed with ``label`` when one of several runs;
    ``print_warnings=False``: the caller prints them (``compare-tires``: a warning every run shares
    once, ``shared_warnings``); ``file``: the scenario file, named in a user error (``guard``)."""
    from vbikit.scenario.pipeline import run_planned
    from vbikit.scenario.preflight import preflight

    report = guard(lambda: run_planned(preflight(load(), limits), limits), file=file)
    if print_warnings:
        warn([f"{label}: {w}" if label else w for w in report.summary["warnings"]])
    return report


def shared_warnings(by_run: dict[str, list[str]]) -> list[str]:
    """The warnings of several runs (by label) as printed once: every warning all runs share, once and
    unprefixed, first (in the first run's order); then each run's own, prefixed with its label."""
    runs = list(by_run.values())
    common = [w for w in (runs[0] if runs else []) if all(w in ws for ws in runs[1:])]
    return common + [f"{label}: {w}" for label, ws in by_run.items() for w in ws if w not in common]
