"""``run_rail``: a RAIL.toml (or its dict, or a ``RailSpec``) → speed sweeps of every train, the
EN 1991-2 / EN 1990 checks, ``rail.nc``, a text report and the acceleration-envelope figure.

Checks (``vbikit.rail.codes`` for the rules and their clauses):

* peak deck acceleration, the largest over every train, speed and deck point (a simply supported
  span read at ``run.points`` equally spaced points), against 3.5 m/s² (ballasted) or 5 m/s²
  (direct fastening);
* φ'dyn = max|y_dyn| / max|y_stat| − 1 of midspan deflection, midspan moment and shear at the
  supports (the larger of the entry's and the exit's), per train and speed (static: the same train at crawl speed; deflection within the
  retained modes, moment and shear with the full static influence line);
* (1 + φ'dyn + φ''/2) × the train's static effect — the largest over trains and speeds — against
  Φ × α × LM71 (Φ2 or Φ3 with L_Φ = the span, EN 1991-2 Table 6.2 for a simply supported main
  girder): the larger governs the design (EN 1991-2 6.4.6).  LM71 alone; SW/0 is not
  considered (it does not govern a single simply supported span).
"""
from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Optional

import numpy as np

from vbikit import __version__
from vbikit._files import shared_name
from vbikit.errors import VbikitError
from vbikit.rail import codes
from vbikit.rail.spec import RailSpec, RailSpecError, load_rail_spec, parse_rail_spec
from vbikit.rail.envelope import TRAVEL_STEPS, moment_envelope_near, moment_sections, static_envelope, stations_words
from vbikit.analysis.checks import add_flags, summary_flag_attrs
from vbikit.outputs import OUTPUTS, cf_unit
from vbikit.rail.refine import MAX_HALVINGS, MAX_PEAKS, PEAK_TOLERANCE, grid_error, refine_peaks, refinement_verdict
from vbikit.rail.report import (TIME_SAMPLING_TOLERANCE, check, format_report, speed_grid_flags, summary,
                               time_sampling_flags)
from vbikit.rail.sweep import (KMH, SweepSetup, bogie_resonances, coupled_envelopes, excitation_wavelength, speed_grid,
                               sweep_moving_forces, train_resonances)
from vbikit.vehicle.trains import Train, get_train, hslm_b, read_train_table

log = logging.getLogger(__name__)

#: resonance orders i of v_i = n0 D / i marked and refined
RESONANCE_ORDERS = 4
#: the moment envelope along the span is swept at the sections j L / MOMENT_SECTIONS (j = 0 … n, the supports
#: included: a restrained end's hogging moment) and every interior support (``moment_sections``)
MOMENT_SECTIONS = 16


class RailBudgetError(VbikitError):
    """The sweep would exceed its work budget (``run.budget``)."""

    message_names_key = True


@dataclass
class RailResult:
    """The outcome of ``run_rail``: the dataset, the check summary (``checks``), the report text,
    the files written and the run time [s]."""

    dataset: Any
    checks: dict[str, Any]
    report: str
    files: list[Path] = field(default_factory=list)
    seconds: float = 0.0


def build_bridge(spec: RailSpec, base_dir: Path = Path(".")):
    """The bridge — the beam of [bridge] or the [bridge] of a scenario file — with every mode up to
    max(30 Hz, 1.5 n0, n3) (at least 3; or ``n_modes``) and the damping of Table 6.6 (+ Δζ) or the
    given one; the required frequency [Hz] and the number of modes up to it."""
    b = spec.bridge
    if b.scenario is not None:
        return _scenario_bridge(spec, base_dir)
    from vbikit.bridge.beam import EulerBernoulliBeam

    zeta = b.damping if b.damping is not None else codes.code_damping(b.deck, b.span, b.additional_damping)
    probe = EulerBernoulliBeam(b.span, b.EI, b.mass_per_length, zeta, n_modes=50)
    f = probe.frequencies_hz
    required = int(np.sum(f <= codes.frequency_limit(f) * (1 + 1e-12)))
    n = b.n_modes or max(3, required)
    return EulerBernoulliBeam(b.span, b.EI, b.mass_per_length, zeta, n_modes=n), codes.frequency_limit(f), required


#: modes of the probe model that finds how many modes the frequency range needs (scenario bridges)
PROBE_MODES = 30


def _scenario_table(spec: RailSpec, base_dir: Path) -> tuple[Path, dict[str, Any]]:
    """The path and the [bridge] table of the scenario file of ``bridge.scenario``."""
    from vbikit._toml import read_toml

    b = spec.bridge
    path = Path(b.scenario) if Path(b.scenario).is_absolute() else base_dir / b.scenario
    data = read_toml(path, RailSpecError, "scenario file")
    table = dict(data.get("bridge") or {})
    if not table:
        raise RailSpecError(f"bridge.scenario: {path.name} has no [bridge] table")
    return path, table


def damping_origin(spec: RailSpec, span: float, base_dir: Path = Path(".")) -> tuple[str, float]:
    """Where the bridge's damping ratio comes from, in words, and the Δζ [-] of EN 1991-2 Eq. 6.13 it
    includes: ``bridge.damping``, a scenario's own ``damping_ratio`` (neither adds Δζ), or Table 6.6
    (+ Δζ with ``additional_damping``, 0 from a span of 30 m)."""
    b = spec.bridge
    if b.damping is not None:
        return "given (bridge.damping)", 0.0
    if b.scenario is not None:
        path, table = _scenario_table(spec, base_dir)
        if "damping_ratio" in table:
            return f"given (damping_ratio of the [bridge] of {path.name})", 0.0
    return "EN 1991-2:2003 Table 6.6", codes.additional_damping(span) if b.additional_damping else 0.0


def _scenario_bridge(spec: RailSpec, base_dir: Path):
    """The [bridge] of a scenario file: one span, square supports; its damping_ratio and n_modes
    unless given there (then Table 6.6 + Δζ and the frequency range decide them)."""
    from vbikit.scenario.build import build_bridge as build_scenario_bridge
    from vbikit.scenario.schema import parse_bridge
    from vbikit.scenario.section import ScenarioError

    b = spec.bridge
    path, table = _scenario_table(spec, base_dir)
    where = path.parent

    def make(overrides: dict[str, Any]):
        try:
            return build_scenario_bridge(parse_bridge({**table, **overrides}), where)
        except (ScenarioError, ValueError) as err:
            raise RailSpecError(f"bridge.scenario: {path.name}: {err}") from None

    probe = make({"n_modes": PROBE_MODES} if "n_modes" not in table else {})
    from vbikit.bridge.base import HasLoadEffects

    if not isinstance(probe, HasLoadEffects):
        raise RailSpecError(f"bridge.scenario: the {type(probe).__name__} of {path.name} has no load effects (moments, "
                            "shears), which the checks need; use a beam, continuous-beam or slab-on-girder bridge")
    if len(probe.span_lengths) != 1 or probe.skew_tan:
        raise RailSpecError(f"bridge.scenario: {path.name} is a bridge of {len(probe.span_lengths)} spans"
                            f"{' with skew supports' if probe.skew_tan else ''}; the railway checks take one simply "
                            "supported span with square supports")
    span = float(probe.span)
    over: dict[str, Any] = {}
    if "damping_ratio" not in table:
        over["damping_ratio"] = b.damping if b.damping is not None else codes.code_damping(b.deck, span, b.additional_damping)
    elif b.damping is not None:
        raise RailSpecError("bridge.damping: the scenario's [bridge] gives its own damping_ratio; give one of them")
    f = probe.frequencies_hz
    limit = codes.frequency_limit(f)
    required = int(np.sum(f <= limit * (1 + 1e-12)))
    if "n_modes" not in table:
        over["n_modes"] = b.n_modes or max(3, required)
    return make(over), limit, required


def load_trains(spec: RailSpec, base_dir: Path) -> list[Train]:
    trains = [get_train(name) for name in spec.trains.presets]
    trains += [hslm_b(b.n, b.d) for b in spec.trains.hslm_b]
    for i, table in enumerate(spec.trains.tables):
        path = Path(table) if Path(table).is_absolute() else base_dir / table
        try:
            trains.append(read_train_table(path))
        except VbikitError as err:
            raise RailSpecError(f"trains.tables[{i + 1}]: {err}") from None
    names = [t.name for t in trains]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise RailSpecError(f"trains: train names must differ, repeated: {', '.join(sorted(dup))}")
    return trains


def _spec(source: Any) -> tuple[RailSpec, Path]:
    if isinstance(source, RailSpec):
        return source, Path(".")
    if isinstance(source, dict):
        return parse_rail_spec(source), Path(".")
    path = Path(source)
    return load_rail_spec(path), path.parent


@dataclass
class RailPlan:
    """A checked railway sweep before any computation (``plan_rail``): the spec, the bridge, the
    trains (``originals`` with their cars; ``trains`` as swept), the speeds and the sweep setup."""

    spec: RailSpec
    bridge: Any
    f_limit: float
    required: int
    originals: list
    trains: list
    resonances: dict
    speeds: Any
    points: Any
    effects: tuple
    setup: Any
    coupled: list
    waves: dict
    sections: Any
    warnings: list = field(default_factory=list)  # the sweep's limits of the standard (codes.hslm_range_warnings)
    damping: Optional[tuple] = None  # where the damping comes from, in words, and its Δζ (damping_origin)


def bogie_resonance_speeds(trains: list, n0: float) -> np.ndarray:
    """Every train's resonance speeds n0 d / i [m/s] of its axle spacings within a bogie
    (``bogie_resonances``, orders 1 … ``RESONANCE_ORDERS``), the family that governs a short span:
    the speed grid samples each and one fine step either side (``speed_grid``'s ``bracketed``), and the
    peak refinement climbs from there.  Not a fine band as around n0 D / i: on a 5 m span under
    HSLM-A1 … A10 (100 … 360 km/h, 4 km/h steps, 0.5 km/h within ± 5 km/h) bands around the nine
    n0 d / i in the sweep took 241 speeds instead of 66 and 2.2 times the CPU time, for the same
    governing peak (11.278 m/s²), the bogie's few axles giving a broad peak."""
    return np.unique(np.array([v for t in trains for _, _, v in bogie_resonances(t, n0, RESONANCE_ORDERS)], float))


def plan_rail(source: Any, budget: Optional[float] = None, coupled_max_steps: Optional[float] = None) -> RailPlan:
    """Every check of a railway sweep before it runs (the spec, the bridge, the train tables, the
    work budgets ``run.budget`` and ``coupled.max_steps``, or ``budget`` / ``coupled_max_steps`` given instead:
    ``vbikit rail --max-steps`` / ``--max-coupled-steps``): what ``run_rail`` and ``vbikit validate`` do first."""
    from vbikit._words import raise_budget
    from vbikit.rail.spec import MAX_BUDGET, MAX_COUPLED_STEPS, with_budgets
    from vbikit.solve.moving_loads import default_dx, filter_steps

    spec, base_dir = _spec(source)
    spec = with_budgets(spec, budget, coupled_max_steps)
    bridge, f_limit, required = build_bridge(spec, base_dir)
    originals = load_trains(spec, base_dir)  # with their cars, for coupled models
    trains = originals
    if spec.trains.sleeper_spacing is not None:
        from vbikit.vehicle.trains import rail_distributed

        trains = [rail_distributed(t, spec.trains.sleeper_spacing) for t in originals]
    n0 = float(bridge.frequencies_hz[0])
    v_min, v_max = spec.speeds.min * KMH, spec.speeds.top * KMH
    # the resonance wavelength D from the axles as given: the rail's distribution (P/4, P/2, P/4 at ±a) adds
    # spacings D − a, D + a that also repeat, and the finite train's spectrum is larger at one of them
    # (an ICE 3 table with a = 0.6 m: 24.175 m for the car length 24.775 m)
    res = {t.name: train_resonances(o, n0, RESONANCE_ORDERS) for t, o in zip(trains, originals)}
    waves = {t.name: excitation_wavelength(o) for t, o in zip(trains, originals)}
    all_res = np.concatenate([r[np.isfinite(r)] for r in res.values()] + [np.zeros(0)])
    fine = spec.speeds.fine_step * KMH if spec.speeds.fine_step else None
    speeds = speed_grid(v_min, v_max, spec.speeds.step * KMH, all_res, fine, spec.speeds.fine_width * KMH,
                        bogie_resonance_speeds(trains, n0))
    span = float(bridge.span)
    points = np.unique(np.append(np.linspace(0.0, span, spec.run.points + 2)[1:-1], 0.5 * span))  # midspan always
    sections = moment_sections(span, MOMENT_SECTIONS, np.asarray(bridge.support_x, float))
    # the shear at both supports: the exit's (the last effect) is the larger at a resonance (HSLM-A1 on the
    # example's span at n0 D / 2: 815 kN against the entry's 750 kN), the check takes the larger of the two
    effects = (("moment", 0.5 * span), ("shear", 0.0), *(("moment", float(x)) for x in sections if abs(x - 0.5 * span) > 1e-9 * span),
               ("shear", span))
    dx = default_dx(bridge, float(speeds.min()), spec.run.steps_per_period)
    fv = 1.0 / n0
    refine = np.full(2 * MAX_HALVINGS * MAX_PEAKS, float(speeds.max()))  # the most peak-refinement speeds per train
    work = filter_steps(bridge, [t.length for t in trains], np.concatenate([speeds, refine]), dx, fv)
    if work > spec.run.budget:
        raise RailBudgetError(f"run.budget: the sweep needs up to {work:.3g} filter steps ({len(trains)} trains × {speeds.size} "
                              f"speeds and up to {refine.size} refinement speeds × {bridge.omega.size} modes), above the "
                              f"budget {spec.run.budget:.3g}; "
                              f"{raise_budget('run.budget', '--max-steps', MAX_BUDGET)}, or use fewer trains, speeds or "
                              "a coarser step")
    coupled = [t for t in originals if t.cars] if spec.coupled.enabled else []
    if spec.coupled.enabled and not coupled:
        raise RailSpecError("coupled.enabled: none of the trains has car data (masses and suspensions): use a preset "
                            "such as 'ice3', or disable coupled")
    coupled_steps = sum(float(np.sum((span + 10.0 + t.length) / dx + fv * speeds / dx))  # Σ over speeds
                        for t in coupled) if coupled else 0.0
    if coupled_steps > spec.coupled.max_steps:
        raise RailBudgetError(f"coupled.max_steps: the coupled cars need {coupled_steps:.3g} time steps ({len(coupled)} "
                              f"trains × {speeds.size} speeds), above the budget {spec.coupled.max_steps:.3g}; "
                              f"{raise_budget('coupled.max_steps', '--max-coupled-steps', MAX_COUPLED_STEPS)}, or use "
                              "fewer speeds")
    warnings = codes.hslm_range_warnings(span, [t.name for t in trains])  # as swept (check() names them so)
    for w in warnings:
        log.warning("%s", w)
    y = float(bridge.default_lateral_offset)  # the track's axis; the deck is read on it
    setup = SweepSetup(bridge, points, effects, dx, fv, spec.run.budget, y)
    return RailPlan(spec, bridge, f_limit, required, originals, trains, res, speeds, points, effects, setup, coupled,
                    waves, sections, warnings, damping_origin(spec, float(bridge.span), base_dir))


#: the files a railway run writes in its output folder: checked before the sweep (``_files.output_names``)
#: and written under these names (``write_outputs``)
DATASET_FILE, REPORT_FILE, SUMMARY_FILE, FIGURE_FILE = ("rail.nc", "rail-report.txt", "rail-summary.json",
                                                        "rail-acceleration.png")


def run_rail(source: Any, out_dir: str | Path | None = None, workers: Optional[int] = None,
             figures: bool = True, progress: Optional[Callable[[int, int], None]] = None,
             scheduler: Optional[str] = None, budget: Optional[float] = None,
             coupled_max_steps: Optional[float] = None) -> RailResult:
    """Run a railway sweep (module docstring).  ``source``: a RAIL.toml path, its dict or a
    ``RailSpec``; ``out_dir``: where ``rail.nc``, ``rail-report.txt`` and ``rail-acceleration.png``
    go, with ``rail-summary.json`` (None: nothing written); ``workers`` overrides ``run.workers`` (default: all cores); ``progress(done, total)``
    after every group of trains (as many as workers) swept; ``scheduler``: a Dask scheduler's
    address, the trains swept there (one task a train) instead of on local processes; ``budget`` /
    ``coupled_max_steps``: the work budgets instead of the file's ``run.budget`` / ``coupled.max_steps`` (``plan_rail``)."""
    from vbikit._validation import checked_workers

    workers = checked_workers(workers, error=RailSpecError)  # (0 read as "the file's": refused, as --workers 0 is)
    t0 = time.perf_counter()
    if out_dir is not None:  # (before the sweep: not after it, when writing)
        from vbikit._files import output_names
        from vbikit.rail.checkpoint import WORK

        output_names(out_dir, (DATASET_FILE, REPORT_FILE, SUMMARY_FILE, FIGURE_FILE), (str(WORK),))
    p = plan_rail(source, budget, coupled_max_steps)
    spec, bridge, f_limit, required, originals, trains, res, speeds, points, setup, coupled = (
        p.spec, p.bridge, p.f_limit, p.required, p.originals, p.trains, p.resonances, p.speeds, p.points, p.setup,
        p.coupled)
    waves, sections, y = p.waves, p.sections, float(bridge.default_lateral_offset)
    bogies = {t.name: t.bogie_axle_spacings for t in trains}  # their resonances n0 d / i: assemble, report
    n0 = float(bridge.frequencies_hz[0])
    log.info("sweeping %d trains × %d speeds, %d modes (%.1f … %.1f Hz), Δx = %.4f m", len(trains), speeds.size,
             bridge.omega.size, n0, bridge.frequencies_hz[-1], setup.dx)
    from vbikit.solve.moving_loads import _peaks
    from vbikit.solve.compile_notice import announce_compile

    from vbikit._validation import default_workers

    n_workers = workers or spec.run.workers or default_workers()
    announce_compile(_peaks, "each worker process" if n_workers > 1 and len(trains) > 1 else "")
    stored = _Stored(spec, setup, speeds, out_dir)
    swept = [stored.load(t) for t in trains]
    todo = [i for i, s in enumerate(swept) if s is None]
    if len(todo) < len(trains):
        log.info("resuming: %d of %d trains read from %s", len(trains) - len(todo), len(trains), stored.work)
    if progress is not None:  # (what was finished before, read: the first report)
        progress(len(trains) - len(todo), len(trains))
    group = max(1, n_workers) if (progress is not None or stored.work is not None) else max(1, len(todo))
    for start in range(0, len(todo), group):
        idx = todo[start:start + group]
        for i, result in zip(idx, sweep_moving_forces(setup, [trains[i] for i in idx], speeds, n_workers, scheduler)):
            swept[i] = result
            stored.save(trains[i], *result)  # a finished train is never lost (kill -9, Ctrl-C)
        if progress is not None:
            progress(len(trains) - len(todo) + min(start + group, len(todo)), len(trains))
    envs, refined = [e for e, _ in swept], [r for _, r in swept]
    names = [t.name for t in trains]
    statics = [static_envelope(bridge, "moment", sections, t.axle_positions, t.axle_loads, y) for t in trains]
    if coupled:
        for t in coupled:
            if t.cars:
                log.info("coupled cars: %s over %d speeds", t.name, speeds.size)
                env = stored.load(t, "coupled")
                if env is None:
                    env = (coupled_envelopes(setup, t, speeds, spec.coupled.irregularity, spec.coupled.seed,
                                             spec.coupled.contact), None)
                    stored.save(t, *env, kind="coupled")
                envs.append(env[0])
                names.append(f"{t.name} (coupled)")
                res[names[-1]] = res[trains[originals.index(t)].name]
                waves[names[-1]] = waves[trains[originals.index(t)].name]
                bogies[names[-1]] = bogies[trains[originals.index(t)].name]
                refined.append(None)
                statics.append(statics[originals.index(t)])
    ds = assemble(spec, bridge, names, speeds, points, envs, res, f_limit, waves=waves, refined=refined,
                  sections=sections, statics=statics, bogies=bogies,
                  damping=p.damping)
    ds.attrs.update(moment_envelope_summary(ds, setup, {t.name: t for t in trains}))
    ds.attrs["modes_required"] = required
    ds.attrs["code_warnings"] = "\n".join(p.warnings)  # one a line (check: checks["warnings"])
    checks = check(ds)
    refine_points(checks, setup, {t.name: t for t in trains})
    refine_design_checks(ds, checks, setup, {t.name: t for t in trains})
    time_sampling_checks(checks, setup, {t.name: t for t in trains})
    ds.attrs.update(summary_flag_attrs(checks))  # (the checks' flag records and warnings, as every dataset's)
    report = format_report(ds, checks)
    result = RailResult(ds, checks, report, seconds=time.perf_counter() - t0)
    ds.attrs["run_seconds"] = result.seconds
    if out_dir is not None:
        result.files = write_outputs(result, Path(out_dir), figures)
        stored.clear()  # everything is in rail.nc now
    return result


class _Stored:
    """The finished trains of this sweep under ``out_dir/rail.parts`` (``vbikit.rail.checkpoint``);
    nothing stored when ``out_dir`` is None."""

    def __init__(self, spec: RailSpec, setup: SweepSetup, speeds, out_dir) -> None:
        from vbikit.rail.checkpoint import WORK

        self.spec_json, self.setup, self.speeds = spec.model_dump_json(), setup, speeds
        self.work = None if out_dir is None else Path(out_dir) / WORK

    def _key(self, train, kind: str) -> str:
        from vbikit.rail.checkpoint import train_key

        return train_key(self.spec_json, self.setup, train, self.speeds, kind)

    def load(self, train, kind: str = "forces"):
        from vbikit.rail.checkpoint import load

        return None if self.work is None else load(self.work, self._key(train, kind))

    def save(self, train, env, refined, kind: str = "forces") -> None:
        from vbikit.rail.checkpoint import save

        if self.work is not None:
            save(self.work, self._key(train, kind), env, refined)

    def clear(self) -> None:
        if self.work is None:
            return
        for path in self.work.glob("*.npz"):
            path.unlink(missing_ok=True)
        try:
            self.work.rmdir()  # only when empty
        except OSError:
            pass


#: how every dynamic peak of a moving-force sweep is taken between the time samples (dataset attribute)
TIME_SAMPLING_METHOD = (
    "every dynamic peak (deck acceleration and deflection, moment, shear) taken between the time samples h = dx / v: "
    "the vertex of the parabola through each local maximum of the sampled history and its two neighbours, except "
    "where an axle enters or leaves the deck or passes the effect's section or a support within those two steps "
    "(the history kinks or jumps there: the sample stands), and the one-sided limits at each such passage (the loads "
    "and static effects exact, the modal state by cubic Hermite interpolation); *_sampling_change: how far the "
    "largest sample or limit fell below the peak (what a vertex added); *_sampling_bound: the estimated bound of "
    "the remaining error (a vertex: the three-point interpolation's remainder h^3 max|y'''|/(9 sqrt 3), y''' from "
    "the third differences; a one-sided limit: the Hermite interpolation's remainder; a sample next to a kink: "
    "how far the one-sided limits there, extrapolated from either side, lie above it); coupled cars: sampled "
    "peaks, NaN")


def time_sampling_variables(samp: dict[str, np.ndarray], mid: int, col: np.ndarray) -> dict[str, Any]:
    """The dataset's time-sampling variables of every peak output (``TIME_SAMPLING_METHOD``) from the
    envelopes' fields stacked over trains (``samp``: acceleration / displacement / effect × change / bound,
    each (train, speed, n)); ``mid`` the midspan point, ``col`` the effect of each moment section."""
    import xarray as xr

    change_words = ("relative amount by which the largest time sample or one-sided limit at an axle's passage falls "
                    "below the peak {} taken between the samples")
    bound_words = "estimated bound of the relative error the time sampling leaves in the peak {}"
    outputs = {"deck_acceleration": (("train", "speed", "point"), "acceleration", slice(None), "deck acceleration at each point"),
               "deflection": (("train", "speed"), "displacement", mid, "midspan deflection"),
               "moment": (("train", "speed"), "effect", 0, "midspan bending moment"),
               "shear": (("train", "speed"), "effect", 1, "shear at the supports"),
               "moment_along": (("train", "speed", "section"), "effect", col, "bending moment at each section")}
    out = {}
    for name, (dims, source, index, words) in outputs.items():
        for kind, text in (("change", change_words), ("bound", bound_words)):
            values = samp[f"{source}_{kind}"][:, :, index]
            out[f"{name}_sampling_{kind}"] = xr.Variable(dims, values, {"units": "1", "long_name": text.format(words)})
    return out


def support_shears(dyn_eff: np.ndarray, st_eff: np.ndarray, samp: dict[str, np.ndarray], sections,
                   span: float) -> tuple[np.ndarray, np.ndarray]:
    """The shear at the supports from the sweep's effects 1 (entry) and the last (exit, when swept: one
    more than the midspan moment, the shear and the moments off midspan): column 1 of ``dyn_eff``,
    ``st_eff`` and the effect's sampling fields in ``samp`` becomes the larger of the two (in place);
    returns the exit's dynamic (train, speed) and static (train) peaks (NaN when not swept)."""
    n_sec = 0 if sections is None else sum(abs(float(x) - 0.5 * span) > 1e-9 * span for x in sections)
    if dyn_eff.shape[2] != 3 + n_sec:  # no exit shear swept
        return np.full(dyn_eff.shape[:2], np.nan), np.full(st_eff.shape[0], np.nan)
    exit_dyn, exit_st = dyn_eff[:, :, -1].copy(), st_eff[:, -1].copy()
    wins = exit_dyn > dyn_eff[:, :, 1]
    for key in ("effect_change", "effect_bound"):
        samp[key][:, :, 1] = np.where(wins, samp[key][:, :, -1], samp[key][:, :, 1])
    dyn_eff[:, :, 1] = np.maximum(dyn_eff[:, :, 1], exit_dyn)
    st_eff[:, 1] = np.maximum(st_eff[:, 1], exit_st)
    return exit_dyn, exit_st


def assemble(spec: RailSpec, bridge, names, speeds, points, envs, res, f_limit, waves=None, refined=None, sections=None,
             statics=None, bogies=None, damping=None):
    """The NetCDF dataset of a sweep (every variable with units and long_name): ``res`` the resonance
    speeds of every train by order, ``waves`` their (D [m], source), ``bogies`` their axle spacings
    within a bogie [m] (``Train.bogie_axle_spacings``; resonances n0 d / i), ``refined`` the ``RefinedPeaks``
    of every train (None: not refined), ``sections`` the sections x [m] of the moment envelope (the
    sweep's effects 2 … are its moments off midspan) and ``statics`` every train's exact static
    moment envelope there; ``damping`` (words, Δζ) where the damping comes from (``damping_origin``;
    None: from ``spec`` alone, a scenario's own damping_ratio not seen)."""
    import xarray as xr

    b = spec.bridge
    n0 = float(bridge.frequencies_hz[0])
    span = float(bridge.span)

    def var(dims, values, units, long_name):
        return xr.Variable(dims, np.asarray(values, float), {"units": units, "long_name": long_name})

    acc_pts = np.stack([e.max_acceleration for e in envs])
    disp_pts = np.stack([e.max_displacement for e in envs])
    mid = int(np.argmin(np.abs(points - 0.5 * span)))
    dyn_eff = np.stack([e.max_effect for e in envs])
    st_eff = np.stack([e.static_effect for e in envs])
    st_disp = np.stack([e.static_displacement for e in envs])[:, mid]
    orders = np.arange(1, RESONANCE_ORDERS + 1)
    res_arr = np.full((len(names), orders.size), np.nan)
    for i, n in enumerate(names):
        r = res.get(n, np.zeros(0))
        res_arr[i, :r.size] = r
    v_lo, v_hi = float(speeds.min()), float(speeds.max())
    in_sweep = np.where(np.isfinite(res_arr), (res_arr >= v_lo * (1 - 1e-12)) & (res_arr <= v_hi * (1 + 1e-12)), False)
    waves, bogies = waves or {}, bogies or {}
    n_bogie = max([len(bogies.get(n, ())) for n in names] + [1])  # at least one (NaN) entry: no zero-length dimension
    bogie_d = np.full((len(names), n_bogie), np.nan)
    for i, n in enumerate(names):
        bogie_d[i, :len(bogies.get(n, ()))] = bogies.get(n, ())
    bogie_res = n0 * bogie_d[:, :, None] / orders[None, None, :]
    wave = np.array([(waves.get(n) or (None, ""))[0] or np.nan for n in names], float)
    wave_src = np.array([(waves.get(n) or (None, "none"))[1] for n in names], dtype=object)
    sections = np.zeros(0) if sections is None else np.asarray(sections, float)
    n_sec = sections.size
    others = [j for j, x in enumerate(sections) if abs(x - 0.5 * span) > 1e-9 * span]
    col = np.array([0 if abs(x - 0.5 * span) <= 1e-9 * span else 2 + others.index(j) for j, x in enumerate(sections)], int)
    along = dyn_eff[:, :, col] if n_sec else np.zeros((len(names), speeds.size, 0))
    st_along = np.stack(statics) if statics is not None and n_sec else np.zeros((len(names), n_sec))
    if n_sec and np.any(np.abs(sections - 0.5 * span) <= 1e-9 * span):
        st_eff[:, 0] = st_along[:, int(np.argmin(np.abs(sections - 0.5 * span)))]  # the exact static peak at midspan
    def sampling(name: str, n: int) -> np.ndarray:  # (train, speed, n): NaN where not estimated (coupled cars)
        return np.stack([np.full((speeds.size, n), np.nan) if getattr(e, name, None) is None
                         else np.asarray(getattr(e, name), float) for e in envs])

    samp = {f"{what}_{kind}": sampling(f"{what}_sampling_{kind}", n)
            for what, n in (("acceleration", points.size), ("displacement", points.size), ("effect", dyn_eff.shape[2]))
            for kind in ("change", "bound")}
    shear_exit, static_shear_exit = support_shears(dyn_eff, st_eff, samp, sections, span)
    peaks = [r for r in (refined or []) if r is not None]
    n_pk = max([r.speed.size for r in peaks] + [0])
    pk = {key: np.full((len(names), n_pk), np.nan) for key in ("grid_speed", "grid_value", "speed", "value", "bound", "last_change", "step",
                                                         "halvings")}
    for i, r in enumerate(refined or []):
        if r is not None:
            for key in pk:
                pk[key][i, :r.speed.size] = getattr(r, key)
    phi_lm = codes.DYNAMIC_FACTORS[b.maintenance](span)
    alpha = b.classification_factor
    y = float(bridge.default_lateral_offset)
    lm_m = codes.lm71_peak(bridge.load_effect("moment", 0.5 * span).influence, span, alpha, y=y)
    lm_v = codes.lm71_peak(bridge.load_effect("shear", 0.0).influence, span, alpha, y=y)
    phi_irr = np.array([codes.phi_irregularity(float(v), span, n0) for v in speeds])
    limit = codes.ACCELERATION_LIMITS[b.track]
    data = {
        "max_deck_acceleration": var(("train", "speed"), acc_pts.max(axis=2), "m s-2",
                                     "peak vertical deck acceleration over the deck points"),
        "deck_acceleration_at_points": var(("train", "speed", "point"), acc_pts, "m s-2", "peak vertical deck acceleration at each point"),
        "max_deflection": var(("train", "speed"), disp_pts[:, :, mid], "m", "peak midspan deflection (absolute)"),
        "static_deflection": var(("train",), st_disp, "m", "peak static midspan deflection (retained modes)"),
        "max_moment": var(("train", "speed"), dyn_eff[:, :, 0], "N m", "peak midspan bending moment (mode acceleration)"),
        "static_moment": var(("train",), st_eff[:, 0], "N m", "peak static midspan bending moment"),
        "max_shear": var(("train", "speed"), dyn_eff[:, :, 1], "N",
                         "peak shear at the supports, the larger of the entry's and the exit's (mode acceleration)"),
        "static_shear": var(("train",), st_eff[:, 1], "N", "peak static shear at the supports (the larger of the two)"),
        "max_shear_exit": var(("train", "speed"), shear_exit, "N", "peak shear at the exit support (mode acceleration)"),
        "static_shear_exit": var(("train",), static_shear_exit, "N", "peak static shear at the exit support"),
        "phi_dyn_deflection": var(("train", "speed"), disp_pts[:, :, mid] / st_disp[:, None] - 1, "1", "phi'dyn of midspan deflection"),
        "phi_dyn_moment": var(("train", "speed"), dyn_eff[:, :, 0] / st_eff[:, :1] - 1, "1", "phi'dyn of midspan moment"),
        "phi_dyn_shear": var(("train", "speed"), dyn_eff[:, :, 1] / st_eff[:, 1:2] - 1, "1", "phi'dyn of shear at the supports"),
        "phi_irregularity": var(("speed",), phi_irr, "1", "phi'' of EN 1991-2 Annex C"),
        "resonance_speed": var(("train", "order"), res_arr, "m s-1",
                               "resonance speed n0 D / i (every order i, inside the sweep or not: resonance_in_sweep)"),
        "resonance_in_sweep": var(("train", "order"), in_sweep.astype(float), "1",
                                  "1 where the resonance speed n0 D / i lies within the swept speeds, 0 outside"),
        "excitation_wavelength": var(("train",), wave, "m", "D of the resonance speeds n0 D / i (wavelength_source)"),
        "bogie_axle_spacing": var(("train", "bogie"), bogie_d, "m",
                                  "the train's axle spacings within a bogie d (NaN: none, or fewer than the most of any train)"),
        "bogie_resonance_speed": var(("train", "bogie", "order"), bogie_res, "m s-1",
                                     "resonance speed n0 d / i of each axle spacing within a bogie d (every order i)"),
        "max_moment_along": var(("train", "speed", "section"), along, "N m", "peak bending moment at each section (mode acceleration)"),
        "static_moment_along": var(("train", "section"), st_along, "N m",
                                   "peak static bending moment at each section (exact on a piecewise-linear influence line: an "
                                   "axle on a breakpoint; a curved line also sampled every L/400 of travel)"),
        **time_sampling_variables(samp, mid, col if n_sec else np.zeros(0, int)),
        "peak_acceleration_grid": var(("train", "peak"), pk["grid_value"], "m s-2", "acceleration peak on the sweep's speed grid"),
        "peak_speed_grid": var(("train", "peak"), pk["grid_speed"], "m s-1", "speed of the acceleration peak on the sweep's grid"),
        "peak_acceleration_refined": var(("train", "peak"), pk["value"], "m s-2",
                                         "acceleration peak after halving the speed step around it (NaN: not refined)"),
        "peak_speed_refined": var(("train", "peak"), pk["speed"], "m s-1", "speed of the refined acceleration peak"),
        "peak_grid_error": var(("train", "peak"), (pk["value"] - pk["grid_value"]) / pk["value"], "1",
                               "relative amount by which the sweep's grid misses the refined peak"),
        "peak_refinement_bound": var(("train", "peak"), pk["bound"], "1",
                                     "bound of the refined peak's remaining grid error (relative; a quadratic peak between its samples)"),
        "peak_last_change": var(("train", "peak"), pk["last_change"], "1",
                                "relative change of the refined peak over its last halving of the speed step"),
        "peak_speed_step": var(("train", "peak"), pk["step"], "m s-1", "final half-step of the speed around the refined peak"),
        "peak_halvings": var(("train", "peak"), pk["halvings"], "1", "halvings of the speed step made around the refined peak (NaN: not refined)"),
        "acceleration_limit": var((), limit, "m s-2", f"EN 1990 A2.4.4.2.1 limit, {b.track} track"),
        "lm71_moment": var((), phi_lm * lm_m, "N m", "Phi x alpha x LM71 midspan moment"),
        "lm71_shear": var((), phi_lm * lm_v, "N", "Phi x alpha x LM71 shear at a support"),
        "frequency": var(("mode",), bridge.frequencies_hz, "Hz", "natural frequency"),
        "unconverged_steps": var(("train", "speed"), np.stack([np.zeros(speeds.size) if e.unconverged_steps is None
                                                               else e.unconverged_steps for e in envs]),
                                 cf_unit(OUTPUTS["unconverged_steps"].unit),
                                 f"coupled cars: {OUTPUTS['unconverged_steps'].long_name} (moving forces: 0)"),
    }
    coords = {
        "train": ("train", np.array(names, dtype=object)),
        "speed": ("speed", speeds, {"units": "m s-1", "long_name": "train speed"}),
        "speed_kmh": ("speed", speeds * 3.6, {"units": "km h-1", "long_name": "train speed"}),
        "point": ("point", points, {"units": "m", "long_name": "x of the deck point from the entry support"}),
        "order": ("order", orders, {"units": "1", "long_name": "resonance order i"}),
        "bogie": ("bogie", np.arange(1, n_bogie + 1), {"units": "1", "long_name": "axle spacing within a bogie (ascending)"}),
        "mode": ("mode", np.arange(1, bridge.omega.size + 1), {"units": "1", "long_name": "mode number"}),
        "section": ("section", sections, {"units": "m", "long_name": "x of the moment section from the entry support",
                                          "stations": stations_words(MOMENT_SECTIONS)}),
        "peak": ("peak", np.arange(1, n_pk + 1), {"units": "1", "long_name": "refined acceleration peak (by speed)"}),
        "wavelength_source": ("train", wave_src, {"long_name": "where the resonance wavelength D comes from"}),
    }
    ds = xr.Dataset(data, coords=coords)
    if damping is None and b.scenario is None:
        damping = damping_origin(spec, span)
    damping_words, delta_zeta = damping if damping is not None else ("unknown (a scenario's [bridge])", math.nan)
    ds.attrs.update({
        "title": "vbikit railway speed sweep", "vbikit_version": __version__, "span_m": span,
        **({"EI_Nm2": b.EI, "mass_per_length_kg_m": b.mass_per_length} if b.scenario is None else {}),
        # (the scenario file as given, an absolute path by its name only: a shared dataset names no folder)
        "bridge_model": type(bridge).__name__ + (f" from {shared_name(b.scenario)}" if b.scenario else ""),
        "damping_ratio": float(bridge.damping_ratios[0]), "deck": b.deck, "track": b.track,
        "damping_source": damping_words, "additional_damping": int(bool(delta_zeta > 0)),
        "additional_damping_ratio": delta_zeta, "first_frequency_hz": n0,
        "frequency_limit_hz": f_limit, "n_modes": int(bridge.omega.size), "dynamic_factor_Phi": phi_lm,
        "maintenance": b.maintenance, "classification_factor": alpha, "lm71_moment_static": lm_m,
        "lm71_shear_static": lm_v, "dx_m": float(envs[0].dx) if envs else math.nan,
        "method": "moving forces, exact modal stepping (vbikit.solve.moving_loads); load effects by mode acceleration",
        "peak_tolerance": PEAK_TOLERANCE, "time_sampling_tolerance": TIME_SAMPLING_TOLERANCE,
        "time_sampling": TIME_SAMPLING_METHOD,
        "peak_refinement": (f"each acceleration peak (local maxima of at least half the train's largest, up to four per train) "
                            f"refined by halving the speed step around it until both the change over a halving and the "
                            f"bound of the remaining error (a quadratic peak between its samples) are below "
                            f"{100 * PEAK_TOLERANCE:g} %; coupled cars not refined"),
    })
    return ds


#: deck points, equally spaced between the supports, on which the governing acceleration is read again
#: (``refine_points``), beside the sweep's own ``[run] points``
DENSE_POINTS = 99


def refine_points(checks: dict[str, Any], setup: SweepSetup, trains: dict[str, Train]) -> None:
    """The governing deck acceleration read again at its train and speed on ``DENSE_POINTS`` equally
    spaced points plus the sweep's own (one moving-load run): the sweep reads the deck at ``[run]
    points`` only, and the envelope max_t |ẅ(x, t)| can peak between them (its higher modes' antisymmetric
    parts give it a corner at midspan, not a rounded top: off midspan by 1.2 m of a 60 m span, 0.3 %
    above the midspan reading).  The check's peak becomes the larger reading, with ``points`` (the
    sweep's largest reading in the same run, the dense one, their x and the points' error
    (dense − read) / dense) in ``checks["acceleration"]``; the pass and the ratio follow (the speed
    grid's error stays the speed refinement's, at the sweep's points)."""
    from vbikit.solve.moving_loads import moving_load_sweep

    acc = checks["acceleration"]
    train = trains.get(acc["train"])
    acc["points"] = None
    if train is None:  # coupled cars: read at the sweep's points only
        return
    span = float(setup.bridge.span)
    dense = np.unique(np.concatenate([np.linspace(0.0, span, DENSE_POINTS + 2)[1:-1], setup.points]))
    env = moving_load_sweep(setup.bridge, train.axle_positions, train.axle_loads, np.array([acc["speed"]]), dense, (),
                            dx=setup.dx, free_vibration=setup.free_vibration, y=setup.y, max_steps=setup.max_steps)
    a = env.max_acceleration[0]
    own = np.flatnonzero(np.isin(dense, setup.points))
    k_read, k_dense = int(own[np.argmax(a[own])]), int(np.argmax(a))
    read, best = float(a[k_read]), float(a[k_dense])
    acc["points"] = {"n_read": int(setup.points.size), "n_dense": int(dense.size), "read": read, "dense": best,
                     "x_read": float(dense[k_read]), "x_dense": float(dense[k_dense]),
                     "error": (best - read) / best if best > 0 else 0.0}
    acc["time_sampling_change"] = float(env.acceleration_sampling_change[0, k_dense])  # of the peak read (below)
    acc["time_sampling_bound"] = float(env.acceleration_sampling_bound[0, k_dense])
    if best > acc["peak"]:
        acc["peak"] = best
        acc["passes"], acc["ratio"] = bool(best <= acc["limit"]), best / acc["limit"]
    checks["passes"] = acc["passes"]


def refine_design_checks(ds, checks: dict[str, Any], setup: SweepSetup, trains: dict[str, Train]) -> None:
    """Refine the governing peak of the moment, shear and deflection checks over speed as the
    acceleration peaks are (``refine_peaks`` at the governing train's grid speed, whatever resonance
    it belongs to): the design value (the deflection's φ'dyn) becomes the larger of the grid's and
    the refined one, with the speed grid's error (``grid_error``: what the grid missed, the change
    over the last halving, the bound; ``checks[kind]``), and a ``speed_grid_error`` flag where the
    refinement did not converge (``speed_grid_flags``)."""
    speeds = ds.speed.values
    span = float(ds.attrs["span_m"])
    tolerance = float(ds.attrs.get("peak_tolerance", PEAK_TOLERANCE))
    for kind in ("moment", "shear", "deflection"):
        c = checks[kind]
        deflection = kind == "deflection"
        c.update({"grid_phi_dyn" if deflection else "grid_design": c["phi_dyn" if deflection else "dynamic_design"],
                  "grid_error": math.nan, "refinement_change": math.nan, "refinement_bound": math.nan,
                  "refinement_halvings": math.nan} | refinement_verdict(math.nan, math.nan, tolerance))
        train = trains.get(c["train"])
        if train is None:  # coupled cars: not refined
            continue
        j = int(np.argmin(np.abs(speeds - c["speed"])))
        curve = ds["max_deflection" if deflection else f"max_{kind}"].sel(train=c["train"]).values
        static = float(ds[f"static_{kind}"].sel(train=c["train"]))
        r = refine_peaks(_peak_evaluator(setup, train, kind, span), speeds, curve, tolerance=tolerance, indices=[j])
        v = float(r.speed[0])
        c.update(grid_error(r) | refinement_verdict(r.last_change, r.bound, tolerance))
        if deflection:
            if float(r.value[0]) > float(r.grid_value[0]):
                c.update(phi_dyn=float(r.value[0]) / static - 1.0, speed=v)
            continue
        irr = codes.phi_irregularity(v, span, float(ds.attrs["first_frequency_hz"]))
        design = float(r.value[0]) + 0.5 * irr * static
        if design > c["dynamic_design"]:
            c.update(dynamic_design=design, speed=v, phi_dyn=float(r.value[0]) / static - 1.0, phi_irregularity=irr)
        c["grid_error"] = (c["dynamic_design"] - c["grid_design"]) / c["dynamic_design"]  # of the design value
        c["governs"] = "dynamic analysis" if c["dynamic_design"] > c["lm71_design"] else "Phi x LM71"
        c["ratio"] = c["dynamic_design"] / c["lm71_design"]
    add_flags(checks, speed_grid_flags(checks, ("moment", "shear", "deflection"), tolerance))


def _peak_evaluator(setup: SweepSetup, train: Train, kind: str, span: float) -> Callable:
    """speeds [m/s] → the train's peak of ``kind`` at each (the midspan moment or the shear at the
    supports [N m, N]: the sweep's effects 0, and 1 with the last; the midspan deflection [m])."""
    run = _peak_sweep(setup, train, kind, span)
    return lambda v: run(v)[0]


def _peak_sweep(setup: SweepSetup, train: Train, kind: str, span: float) -> Callable:
    """speeds [m/s] → (peak, its time-sampling change, its time-sampling bound) of ``kind`` at each
    (``_peak_evaluator``)."""
    from vbikit.solve.moving_loads import moving_load_sweep

    if kind == "deflection":
        mid = int(np.argmin(np.abs(setup.points - 0.5 * span)))
        points, effects = setup.points[mid:mid + 1], ()
    else:
        e = ("moment", "shear").index(kind)
        points, effects = setup.points[:1], setup.effects[e:e + 1]
        if kind == "shear" and setup.effect_specs[-1] == ("shear", span):  # the exit's too: the larger counts
            effects = (*effects, setup.effects[-1])

    def evaluate(v):
        env = moving_load_sweep(setup.bridge, train.axle_positions, train.axle_loads, v, points, effects, dx=setup.dx,
                                free_vibration=setup.free_vibration, y=setup.y, max_steps=setup.max_steps)
        if kind == "deflection":
            return env.max_displacement[:, 0], env.displacement_sampling_change[:, 0], env.displacement_sampling_bound[:, 0]
        k = np.argmax(env.max_effect, axis=1)  # the larger of the entry's and the exit's shear (one effect else)
        rows = np.arange(k.size)
        return env.max_effect[rows, k], env.effect_sampling_change[rows, k], env.effect_sampling_bound[rows, k]

    return evaluate


def time_sampling_checks(checks: dict[str, Any], setup: SweepSetup, trains: dict[str, Train]) -> None:
    """Each check's governing peak with its time sampling (``TIME_SAMPLING_METHOD``): for the moment,
    shear and deflection one crossing at the governing train and (refined) speed gives
    ``time_sampling_change`` and ``time_sampling_bound`` (the acceleration's come from
    ``refine_points``' reading), NaN where coupled cars govern; then a ``time_sampling_error`` flag
    where either reaches the tolerance (``time_sampling_flags``)."""
    span = float(setup.bridge.span)
    for kind in ("moment", "shear", "deflection"):
        c = checks[kind]
        train = trains.get(c["train"])
        if train is None:
            continue
        _, change, bound = _peak_sweep(setup, train, kind, span)(np.array([c["speed"]]))
        c["time_sampling_change"], c["time_sampling_bound"] = float(change[0]), float(bound[0])
    add_flags(checks, time_sampling_flags(checks))


#: sections [per span] of the fine static envelope and of the dynamic one around the swept maximum
FINE_SECTIONS = 400
NEAR_SECTIONS = 81


def moment_envelope_summary(ds, setup: SweepSetup, trains: dict[str, Train]) -> dict[str, Any]:
    """The largest moment along the span, dynamic (over trains, speeds and the swept sections, then
    placed between the sections by one crossing at the governing speed, ``moment_envelope_near``) and
    static (the exact envelope ``static_envelope`` on L / FINE_SECTIONS), with their positions and
    their ratios to the same maxima at midspan (dataset attrs)."""
    span = float(ds.attrs["span_m"])
    along = ds["max_moment_along"].values
    if along.shape[-1] == 0:
        return {}
    t, v, j = np.unravel_index(int(np.nanargmax(along)), along.shape)
    name = str(ds.train.values[t])
    x_sec = float(ds.section.values[j])
    best, where = float(along[t, v, j]), x_sec
    h = float(np.min(np.diff(ds.section.values))) if ds.section.size > 1 else span
    if name in trains:
        xs, env = moment_envelope_near(setup, trains[name], float(ds.speed.values[v]), max(x_sec - h, 1e-6 * span),
                                       min(x_sec + h, span * (1 - 1e-6)), NEAR_SECTIONS)
        k = int(np.argmax(env))
        if env[k] > best:
            best, where = float(env[k]), float(xs[k])
    mid = float(np.nanmax(ds["max_moment"].values))
    st = ds["static_moment_along"].values
    ts = int(np.unravel_index(int(np.nanargmax(st)), st.shape)[0])
    sname = str(ds.train.values[ts])
    base = sname.removesuffix(" (coupled)")
    fine = moment_sections(span, FINE_SECTIONS, np.asarray(setup.bridge.support_x, float))
    tr = trains.get(base)
    st_fine = (static_envelope(setup.bridge, "moment", fine, tr.axle_positions, tr.axle_loads, setup.y)
               if tr is not None else st[ts])
    fine = fine if tr is not None else ds.section.values
    ks = int(np.flatnonzero(st_fine >= st_fine.max() * (1 - 1e-12))[0])  # ties (mirror positions): the first
    st_mid = float(np.nanmax(ds["static_moment"].values))
    return {"moment_max_Nm": best, "moment_max_position_m": where, "moment_max_train": name,
            "moment_max_speed_m_s": float(ds.speed.values[v]), "moment_max_over_midspan": best / mid if mid > 0 else math.nan,
            "static_moment_max_Nm": float(st_fine[ks]), "static_moment_max_position_m": float(fine[ks]),
            "static_moment_max_train": sname,
            "static_moment_max_over_midspan": float(st_fine[ks]) / st_mid if st_mid > 0 else math.nan,
            "moment_envelope_method": (f"dynamic: {ds.section.size} sections swept ({stations_words(MOMENT_SECTIONS)}), "
                                       f"the largest placed on {NEAR_SECTIONS} sections around it at the governing speed; "
                                       f"static on L/{FINE_SECTIONS} (the supports included): "
                                       f"exact on a piecewise-linear influence line (an axle on a breakpoint), on a "
                                       f"curved one (restrained ends, a girder of a deck) also every L/{TRAVEL_STEPS} "
                                       f"of travel")}


def write_outputs(result: RailResult, out_dir: Path, figures: bool = True) -> list[Path]:
    """``rail.nc``, ``rail-report.txt``, ``rail-summary.json`` and (``figures``) ``rail-acceleration.png``
    in ``out_dir``."""
    import json

    from vbikit._files import atomic_write, write_text

    out_dir.mkdir(parents=True, exist_ok=True)
    ds = result.dataset.copy()
    ds["train"] = ds["train"].astype(str)
    ds["wavelength_source"] = ds["wavelength_source"].astype(str)
    files = [atomic_write(out_dir / DATASET_FILE, lambda tmp: ds.to_netcdf(tmp, engine="netcdf4")),
             write_text(out_dir / REPORT_FILE, result.report),
             write_text(out_dir / SUMMARY_FILE, json.dumps(summary(result.dataset, result.checks), indent=1, ensure_ascii=False) + "\n")]
    if figures:
        from vbikit.rail.figures import plot_acceleration_envelopes

        files.append(plot_acceleration_envelopes(result.dataset, out_dir / FIGURE_FILE))
    return files
