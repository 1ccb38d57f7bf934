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


def execute(load: Callable[[], Any], limits: Any = None, label: str = "", file: Any = None) -> "Report":
    """Check (``load()`` returns a Scenario; every check of ``vbikit.scenario.preflight.preflight``),
    run and report it (``vbikit.scenario.pipeline.run_planned``); user errors exit with code 2,
    the summary's warnings go to stderr, each prefixed with ``label`` when one of several runs;
    ``file``: the scenario file, named in a user error (``guard``).  (``compare-tires`` checks its four
    runs before any of them and prints one line per distinct warning, ``grouped_warnings``.)"""
    from vbikit.scenario.pipeline import run_planned
    from vbikit.scenario.preflight import preflight

    report = guard(lambda: run_planned(preflight(load(), limits), limits), file=file)
    warn([f"{label}: {w}" if label else w for w in report.summary["warnings"]])
    return report


def _severity(flag: dict[str, Any]) -> float:
    """How far a flag is past its threshold, larger worse (``Flag.value`` against ``Flag.threshold``:
    a value flagged for being small, such as ``small_static``'s share, is the worse the smaller)."""
    value, threshold = flag.get("value"), flag.get("threshold")
    if value is None:
        return 0.0
    size = abs(float(value))
    return -size if threshold is not None and size < abs(float(threshold)) else size


def grouped_warnings(by_run: dict[str, tuple[list[str], list[dict[str, Any]]]], what: str = "tire",
                     kept: str = "") -> list[str]:
    """The warnings of several runs of one scenario (``label -> (summary["warnings"], summary["flags"])``),
    one line per distinct warning.  Distinct: a flag's code and its subject, wheels taken together
    (``contact_loss`` of every wheel is one warning), or a warning's text when no flag gives it.  A
    warning every run gives once in the same words is printed once, unprefixed, first; one in the
    same words from some runs with their labels (``tire point, rigid disk: …``); any other the worst
    of its instances (``_severity``) with its run's label and a count, ``tire rigid disk: … (×12 over
    the tire models: point 4, rigid disk 8; the worst shown{kept})``, ``kept`` saying where every
    instance is; in the order they first occur."""
    groups: dict[tuple[str, ...], list[tuple[str, str, dict[str, Any]]]] = {}
    for label, (warnings, flags) in by_run.items():
        by_message = {f["message"]: f for f in flags}
        for text in warnings:
            flag = by_message.get(text, {})
            key = ("flag", flag["code"], "" if flag.get("wheel") else str(flag.get("subject"))) if flag else ("text", text)
            groups.setdefault(key, []).append((label, text, flag))
    shared, lines = [], []
    for found in groups.values():
        labels = [label for label, _, _ in found]
        names = list(dict.fromkeys(labels))
        if len({text for _, text, _ in found}) == 1:  # the same words
            if len(found) == len(by_run) and set(labels) == set(by_run):
                shared.append(found[0][1])  # every run's, once
            else:
                lines.append(f"{what} {', '.join(names)}: {found[0][1]}" + ("" if len(found) == len(names) else
                                                                          f" (×{len(found)})"))
        else:
            label, text, _ = max(found, key=lambda item: _severity(item[2]))  # the first of the worst
            counts = ", ".join(f"{name} {labels.count(name)}" for name in names)
            lines.append(f"{what} {label}: {text} (×{len(found)} over the {what} models: {counts}; the worst "
                         f"shown{kept})")
    return shared + lines
