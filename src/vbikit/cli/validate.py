"""``vbikit validate FILE``: every check a command makes before it computes, for every input kind.

The kind is told by the file (``KINDS``, or ``--kind``): a TOML file by its tables (``[[load_effects]]``
lifetime, ``[[sensors]]``/``[sampling]`` drive-by, ``[trains]`` railway, ``[axes]`` study,
``[[case]]`` field, a [bridge] and only the sections a traffic base scenario takes (``BASE_SECTIONS``: no [vehicle] or
[[vehicles]]) a traffic base scenario, else a scenario), a CSV file by its first line (``# vbikit-modes`` a mode file,
a ``time [s]`` … ``direction`` header a records file, ``time [s], <channel> [unit]`` a measured
response, ``x [m], elevation [m]`` a road profile, else a train table).  Each kind runs the checks
of its command (``CHECKS``), no simulation, and prints one line ``FILE: ok — <kind>: <summary>``.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any, Callable, Optional

import typer

from vbikit.cli.guard import MAX_MEMORY, MAX_STEPS, guard, limits, memory_option, warn

#: the input kinds: name -> what it is (the command that reads it)
KINDS: dict[str, str] = {
    "scenario": "a scenario (vbikit run)",
    "traffic-base": "a traffic base scenario (vbikit traffic --bridge: no vehicles, the records give them)",
    "study": "a study (vbikit study run)",
    "lifetime": "a lifetime file (vbikit lifetime)", "driveby": "a drive-by file (vbikit driveby)",
    "rail": "a railway file (vbikit rail)", "field": "a field file (vbikit field)",
    "records": "a vehicle records CSV (vbikit traffic, lifetime [traffic].records)",
    "train": "a train table CSV (rail [trains].tables)", "modes": "a mode file (bridge.model = \"modes-file\")",
    "response": "a measured response CSV (vbikit field [[case]].responses)",
    "profile": "a measured road profile CSV (road.profile_file)",
}


#: ``detect``'s answer for a CSV whose first line names no kind: read as a train table, which a
#: refusal then says (``validate``)
TRAIN_GUESSED = "train (guessed)"


def detect(path: Path) -> str:
    """The kind of the input file ``path`` (module docstring); reads it through the safe reader."""
    from vbikit._files import read_text
    from vbikit.errors import OptionError

    if path.suffix.lower() != ".toml":
        text = read_text(path, OptionError, "input file")
        first = next((ln.strip() for ln in text.splitlines() if ln.strip()), "")
        if first.lstrip("#").strip().startswith("vbikit-modes"):
            return "modes"
        header = next((ln.lower() for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")), "")
        cells = [c.strip() for c in header.split(",")]
        if "time" in header and "direction" in header:
            return "records"
        if cells[0].startswith("time [") and len(cells) > 1:
            return "response"
        if cells[0].startswith("x [") or "elevation" in header:
            return "profile"
        return "train" if cells[0].startswith("position") else TRAIN_GUESSED
    from vbikit._toml import read_toml

    data = read_toml(path, OptionError, "input file")
    if "load_effects" in data or "fatigue" in data:
        return "lifetime"
    if any(k in data for k in ("sensors", "sampling", "identification", "sweep")):
        return "driveby"
    if "trains" in data or "speeds" in data:
        return "rail"
    if "axes" in data:
        return "study"
    if "case" in data or "signal" in data:
        return "field"
    from vbikit.traffic.base import BASE_SECTIONS

    if "bridge" in data and all(k in BASE_SECTIONS for k in data):  # no [vehicle] or [[vehicles]]: the records give them
        return "traffic-base"
    return "scenario"


def check_kind(path: Path, command: str, accepted: tuple[str, ...]) -> None:
    """Refuse (exit 2) an input file of another kind than ``accepted`` (``detect``), naming its kind and the
    command that reads it: ``vbikit cite`` and ``bridge`` on a railway or lifetime file listed its keys as
    unknown to a scenario, as if the file were bad.  A file that cannot be read or parsed is left to the
    command's own reader, whose error names the problem."""
    from vbikit.errors import OptionError, VbikitError

    if Path(path).suffix.lower() != ".toml":  # (a scenario by another name, or a CSV: left to the reader, as before)
        return
    try:
        kind = detect(path)
    except (VbikitError, OSError):
        return
    if kind in accepted or kind not in KINDS:
        return

    def refuse() -> None:
        names = [KINDS[k].split(" (")[0] for k in accepted]
        takes = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]
        raise OptionError(f"{path}: vbikit {command} takes {takes}; this file is {KINDS[kind]} "
                          f"(`vbikit validate {path}` checks it)")

    guard(refuse)


def _scenario(path: Path, budget: Any) -> str:
    from vbikit.scenario import load_scenario
    from vbikit.scenario.preflight import preflight
    from vbikit.solve.budget import human

    from vbikit.scenario.step_check import effect_step_warnings

    plan = preflight(load_scenario(path), budget)
    steps = effect_step_warnings(plan.scenario, plan.built.crossing, plan.built.plan.load_effects, plan.run, budget)
    warn(plan.warnings + [w for w in steps if w not in plan.warnings])
    est = plan.estimate
    return f"{est.n_steps} steps of {est.dt:.3e} s ({plan.built.crossing.integrator}), ≈ {human(est.memory)}"


def _traffic_base(path: Path, budget: Any) -> str:
    """The checks of ``vbikit traffic --bridge FILE`` before it reads the events: its sections
    (``base_scenario``) and the event template it builds from them (``template_data``, as
    ``vbikit.traffic.study.EventContext.of``: bridge, tire, road, response points), without loading
    the kernels."""
    from vbikit.scenario.build import build
    from vbikit.scenario.schema import parse_scenario
    from vbikit.traffic.base import base_scenario, dropped_section_warnings, template_data

    base, base_dir = base_scenario(str(path))
    scenario = parse_scenario(template_data(base), base_dir)
    warn(dropped_section_warnings(scenario.response))
    bridge = build(scenario, budget).crossing.bridge
    road = "one road for every event" if scenario.road.profile_file is not None or scenario.road.road_class == "none" \
        else "a random road per event"
    return f"{type(bridge).__name__}, {bridge.omega.size} modes (n0 = {bridge.frequencies_hz[0]:.3g} Hz), {road}"


def _study(path: Path, budget: Any) -> str:
    from vbikit.cli.study import MOST_WARNINGS, checked_summary
    from vbikit.study.check import check_study
    from vbikit.study.spec import load_study

    study = load_study(path)
    result = check_study(study, budget, confirmed=False)
    warn(result.warnings, most=MOST_WARNINGS)
    return checked_summary(study, result)


def _lifetime(path: Path, budget: Any) -> str:
    from vbikit._words import duration_words
    from vbikit.lifetime.run import prepare
    from vbikit.lifetime.spec import read_lifetime

    spec, folder = read_lifetime(path)
    prep = prepare(spec, folder, workers=1, max_memory=budget.max_memory)
    return (f"{spec.n_days:,} days, {prep.model.trucks_per_day:,.0f} trucks a day, {len(prep.setup.lines)} load "
            f"effect(s), {len(prep.details)} fatigue detail(s); estimated {duration_words(prep.estimate_hours)} on one worker")


def _driveby(path: Path, budget: Any) -> str:
    from vbikit.driveby.spec import load_driveby
    from vbikit.driveby.study import check_cases

    spec = load_driveby(path)
    steps = check_cases(spec)
    return f"{max(1, len(spec.cases)):,} cases, about {steps:.3g} integration steps (budget {spec.max_steps:.3g})"


def _rail(path: Path, budget: Any) -> str:
    from vbikit.rail.run import plan_rail

    plan = plan_rail(path)
    return (f"{len(plan.trains)} trains × {plan.speeds.size} speeds, {plan.bridge.omega.size} modes "
            f"(n0 = {plan.bridge.frequencies_hz[0]:.3g} Hz)")


def _field(path: Path, budget: Any) -> str:
    from vbikit.field.io import load_field_toml
    from vbikit.field.workflow import check_field

    spec = load_field_toml(path)
    check_field(spec, ["point"], budget)
    return f"{len(spec.cases)} case(s)"


def _file(module: str, reader: str, summary: Callable[[Any], str]) -> Callable[[Path, Any], str]:
    """The check of a data file: its reader (``module.reader(path)``, through the safe reader) and a summary."""
    def check(path: Path, budget: Any) -> str:
        import importlib

        return summary(getattr(importlib.import_module(module), reader)(path))

    return check


#: the checks of each kind: kind -> check(path, Limits) -> summary
CHECKS: dict[str, Callable[[Path, Any], str]] = {
    "scenario": _scenario, "traffic-base": _traffic_base, "study": _study, "lifetime": _lifetime, "driveby": _driveby, "rail": _rail,
    "field": _field,
    "records": _file("vbikit.traffic.records", "read_records",
                     lambda r: f"{len(r):,} vehicle records in lane(s) {', '.join(map(str, sorted({v.lane for v in r})))} "
                               "(each lane needs a centre on the bridge, --lanes or vbikit traffic's default ones: "
                               "checked when it runs)"),
    "train": _file("vbikit.vehicle.trains", "read_train_table",
                   lambda t: f"{t.axle_positions.size} axles over {t.length:g} m"),
    "modes": _file("vbikit.bridge.modefile", "modes_from_file", lambda b: f"{b.omega.size} modes, span {b.span:g} m"),
    "response": _file("vbikit.field.io", "read_response_csv",
                      lambda r: f"{len(r.channels)} channel(s), {r.time.size:,} samples"),
    "profile": _file("vbikit.road.measured", "read_profile_csv", lambda p: f"{p.x.size:,} stations"),
}


def validate(
    file: Path = typer.Argument(..., metavar="FILE", help="An input file of any kind: scenario, study, lifetime, drive-by, railway or "
                                          "field TOML; records, train table, mode file, measured response or road "
                                          "profile CSV."),
    kind: Optional[str] = typer.Option(None, "--kind", help=f"The file's kind if not told by it: {', '.join(KINDS)}."),
    max_memory: Optional[str] = MAX_MEMORY,
    max_steps: Optional[float] = MAX_STEPS,
) -> None:
    """Check an input file without running it: every check its command makes before it computes
    (files, parameters, positions on the bridge, time step and stability, memory and step budgets)."""
    from vbikit.errors import OptionError

    if kind is not None and kind not in KINDS:
        guard(lambda: (_ for _ in ()).throw(OptionError(f"--kind: {kind!r}; allowed: {', '.join(KINDS)}")))
    budget = limits(max_memory, max_steps)
    if max_memory is not None:
        memory_option(max_memory)
    detected = kind or guard(lambda: detect(file), file=file)
    found = "train" if detected == TRAIN_GUESSED else detected

    def check() -> str:
        from vbikit.errors import VbikitError

        try:
            return CHECKS[found](file, budget)
        except VbikitError as err:
            if detected == TRAIN_GUESSED:  # the fallback guess: say so, and how to name the kind
                raise OptionError(f"{err} (its first line names no other kind of CSV, so it was read as a train "
                                  f"table; if it is another kind, give --kind: {', '.join(KINDS)})") from None
            raise

    summary = guard(check, file=file)
    if kind is None and found == "traffic-base":  # told by a missing [vehicle]: say so, in case it was forgotten
        summary += " (no [vehicle] or [[vehicles]]: checked as a traffic base; `vbikit run` needs one)"
    typer.echo(f"{file}: ok — {summary}" if found == "scenario" else f"{file}: ok — {KINDS[found]}: {summary}")
