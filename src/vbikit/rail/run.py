"""``run_rail``: a RAIL.toml (or its dict, or a ``RailSpec``) → speed sweeps of every train, the
EN 1991-2 / EN 1990 checks, ``rail.nc``, a text report and the acceleration-envelope figure.

Checks (``vbikit.rail.codes`` for the rules and their clauses):

* peak deck acceleration, the largest over every train, speed and deck point (a simply supported
  span read at ``run.points`` equally spaced points), against 3.5 m/s² (ballasted) or 5 m/s²
  (direct fastening);
* φ'dyn = max|y_dyn| / max|y_stat| − 1 of midspan deflection, midspan moment and shear at the
  entry support, per train and speed (static: the same train at crawl speed; deflection within the
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

from vbikit.errors import VbikitError
from vbikit.rail import codes
from vbikit.rail.spec import RailSpec, RailSpecError, load_rail_spec, parse_rail_spec
from vbikit.rail.sweep import KMH, SweepSetup, coupled_envelopes, speed_grid, sweep_moving_forces, train_resonances
from vbikit.vehicle.trains import Train, get_train, read_train_table

log = logging.getLogger(__name__)

#: resonance orders i of v_i = n0 D / i marked and refined
RESONANCE_ORDERS = 4


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


def _scenario_bridge(spec: RailSpec, base_dir: Path):
    """The [bridge] of a scenario file: one span, square supports; its damping_ratio and n_modes
    unless given there (then Table 6.6 + Δζ and the frequency range decide them)."""
    from vbikit._toml import read_toml
    from vbikit.scenario.build import build_bridge as build_scenario_bridge
    from vbikit.scenario.schema import parse_bridge
    from vbikit.scenario.section import ScenarioError

    b = spec.bridge
    path = Path(b.scenario) if Path(b.scenario).is_absolute() else base_dir / b.scenario
    data = read_toml(path, RailSpecError, "scenario file")
    table = dict(data.get("bridge") or {})
    if not table:
        raise RailSpecError(f"bridge.scenario: {path.name} has no [bridge] table")
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


def plan_rail(source: Any) -> RailPlan:
    """Every check of a railway sweep before it runs (the spec, the bridge, the train tables, the
    work budgets ``run.budget`` and ``coupled.max_steps``): what ``run_rail`` and ``vbikit validate``
    do first."""
    from vbikit.solve.moving_loads import default_dx, filter_steps

    spec, base_dir = _spec(source)
    bridge, f_limit, required = build_bridge(spec, base_dir)
    originals = load_trains(spec, base_dir)  # with their cars, for coupled models
    trains = originals
    if spec.trains.sleeper_spacing is not None:
        from vbikit.vehicle.trains import rail_distributed

        trains = [rail_distributed(t, spec.trains.sleeper_spacing) for t in originals]
    n0 = float(bridge.frequencies_hz[0])
    v_min, v_max = spec.speeds.min * KMH, spec.speeds.top * KMH
    res = {t.name: (lambda r: r[r >= v_min])(train_resonances(t, n0, v_max, RESONANCE_ORDERS)) for t in trains}
    all_res = np.concatenate([r for r in res.values()] + [np.zeros(0)])
    fine = spec.speeds.fine_step * KMH if spec.speeds.fine_step else None
    speeds = speed_grid(v_min, v_max, spec.speeds.step * KMH, all_res, fine, spec.speeds.fine_width * KMH)
    span = float(bridge.span)
    points = np.unique(np.append(np.linspace(0.0, span, spec.run.points + 2)[1:-1], 0.5 * span))  # midspan always
    effects = (("moment", 0.5 * span), ("shear", 0.0))
    dx = default_dx(bridge, float(speeds.min()), spec.run.steps_per_period)
    fv = 1.0 / n0
    work = filter_steps(bridge, [t.length for t in trains], speeds, dx, fv)
    if work > spec.run.budget:
        raise RailBudgetError(f"run.budget: the sweep needs {work:.3g} filter steps ({len(trains)} trains × {speeds.size} "
                              f"speeds × {bridge.omega.size} modes), above the budget {spec.run.budget:.3g}; raise "
                              "run.budget or use fewer trains, speeds or a coarser step")
    coupled = [t for t in originals if t.cars] if spec.coupled.enabled else []
    if spec.coupled.enabled and not coupled:
        raise RailSpecError("coupled.enabled: none of the trains has car data (masses and suspensions): use a preset "
                            "such as 'ice3', or disable coupled")
    coupled_steps = sum(float(np.sum((span + 10.0 + t.length) / dx + fv * speeds / dx))  # Σ over speeds
                        for t in coupled) if coupled else 0.0
    if coupled_steps > spec.coupled.max_steps:
        raise RailBudgetError(f"coupled.max_steps: the coupled cars need {coupled_steps:.3g} time steps ({len(coupled)} "
                              f"trains × {speeds.size} speeds), above {spec.coupled.max_steps:.3g}; raise coupled.max_steps "
                              "or use fewer speeds")
    if span < 7.0 and any(t.name.startswith("HSLM-A") for t in trains):
        log.warning("span %.3g m < 7 m: EN 1991-2 Annex E uses HSLM-B for simply supported spans below 7 m", span)
    y = float(bridge.default_lateral_offset)  # the track's axis; the deck is read on it
    setup = SweepSetup(bridge, points, effects, dx, fv, spec.run.budget, y)
    return RailPlan(spec, bridge, f_limit, required, originals, trains, res, speeds, points, effects, setup, coupled)


def run_rail(source: Any, out_dir: str | Path | None = None, workers: Optional[int] = None,
             figures: bool = True, progress: Optional[Callable[[int, int], None]] = None) -> RailResult:
    """Run a railway sweep (module docstring).  ``source``: a RAIL.toml path, its dict or a
    ``RailSpec``; ``out_dir``: where ``rail.nc``, ``rail-report.txt`` and ``rail-acceleration.png``
    go (None: nothing written); ``workers`` overrides ``run.workers``; ``progress(done, total)``
    after every group of trains (as many as workers) swept."""
    t0 = time.perf_counter()
    p = plan_rail(source)
    spec, bridge, f_limit, required, originals, trains, res, speeds, points, setup, coupled = (
        p.spec, p.bridge, p.f_limit, p.required, p.originals, p.trains, p.resonances, p.speeds, p.points, p.setup,
        p.coupled)
    n0 = float(bridge.frequencies_hz[0])
    log.info("sweeping %d trains × %d speeds, %d modes (%.1f … %.1f Hz), Δx = %.4f m", len(trains), speeds.size,
             bridge.omega.size, n0, bridge.frequencies_hz[-1], setup.dx)
    from vbikit.solve.moving_loads import _peaks
    from vbikit.solve.simulate import announce_compile

    n_workers = workers or spec.run.workers
    announce_compile(_peaks, "each worker process" if n_workers > 1 and len(trains) > 1 else "")
    envs = []
    group = len(trains) if progress is None else max(1, n_workers)
    for start in range(0, len(trains), group):
        envs += sweep_moving_forces(setup, trains[start:start + group], speeds, n_workers)
        if progress is not None:
            progress(min(start + group, len(trains)), len(trains))
    names = [t.name for t in trains]
    if coupled:
        for t in coupled:
            if t.cars:
                log.info("coupled cars: %s over %d speeds", t.name, speeds.size)
                envs.append(coupled_envelopes(setup, t, speeds, spec.coupled.irregularity, spec.coupled.seed,
                                              spec.coupled.contact))
                names.append(f"{t.name} (coupled)")
                res[names[-1]] = res[trains[originals.index(t)].name]
    ds = assemble(spec, bridge, names, speeds, points, envs, res, f_limit)
    ds.attrs["modes_required"] = required
    checks = check(ds)
    report = format_report(ds, checks)
    result = RailResult(ds, checks, report, seconds=time.perf_counter() - t0)
    ds.attrs["run_seconds"] = result.seconds
    if out_dir is not None:
        result.files = write_outputs(result, Path(out_dir), figures)
    return result


def assemble(spec: RailSpec, bridge, names, speeds, points, envs, res, f_limit):
    """The NetCDF dataset of a sweep (every variable with units and long_name)."""
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
        "max_shear": var(("train", "speed"), dyn_eff[:, :, 1], "N", "peak shear at the entry support (mode acceleration)"),
        "static_shear": var(("train",), st_eff[:, 1], "N", "peak static shear at the entry support"),
        "phi_dyn_deflection": var(("train", "speed"), disp_pts[:, :, mid] / st_disp[:, None] - 1, "1", "phi'dyn of midspan deflection"),
        "phi_dyn_moment": var(("train", "speed"), dyn_eff[:, :, 0] / st_eff[:, :1] - 1, "1", "phi'dyn of midspan moment"),
        "phi_dyn_shear": var(("train", "speed"), dyn_eff[:, :, 1] / st_eff[:, 1:2] - 1, "1", "phi'dyn of shear at the entry support"),
        "phi_irregularity": var(("speed",), phi_irr, "1", "phi'' of EN 1991-2 Annex C"),
        "resonance_speed": var(("train", "order"), res_arr, "m s-1", "resonance speed n0 D / i"),
        "acceleration_limit": var((), limit, "m s-2", f"EN 1990 A2.4.4.2.1 limit, {b.track} track"),
        "lm71_moment": var((), phi_lm * lm_m, "N m", "Phi x alpha x LM71 midspan moment"),
        "lm71_shear": var((), phi_lm * lm_v, "N", "Phi x alpha x LM71 shear at the entry support"),
        "frequency": var(("mode",), bridge.frequencies_hz, "Hz", "natural frequency"),
    }
    coords = {
        "train": ("train", np.array(names, dtype=object)),
        "speed": ("speed", speeds, {"units": "m s-1", "long_name": "train speed"}),
        "speed_kmh": ("speed", speeds * 3.6, {"units": "km h-1", "long_name": "train speed"}),
        "point": ("point", points, {"units": "m", "long_name": "x of the deck point from the entry support"}),
        "order": ("order", orders, {"units": "1", "long_name": "resonance order i"}),
        "mode": ("mode", np.arange(1, bridge.omega.size + 1), {"units": "1", "long_name": "mode number"}),
    }
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update({
        "title": "vbikit railway speed sweep", "span_m": span,
        **({"EI_Nm2": b.EI, "mass_per_length_kg_m": b.mass_per_length} if b.scenario is None else {}),
        "bridge_model": type(bridge).__name__ + (f" from {b.scenario}" if b.scenario else ""),
        "damping_ratio": float(bridge.damping_ratios[0]), "deck": b.deck, "track": b.track,
        "damping_source": "given (bridge.damping)" if b.damping is not None else "EN 1991-2 Table 6.6",
        "additional_damping": int(b.additional_damping and b.damping is None), "first_frequency_hz": n0,
        "frequency_limit_hz": f_limit, "n_modes": int(bridge.omega.size), "dynamic_factor_Phi": phi_lm,
        "maintenance": b.maintenance, "classification_factor": alpha, "lm71_moment_static": lm_m,
        "lm71_shear_static": lm_v, "dx_m": float(envs[0].dx) if envs else math.nan,
        "method": "moving forces, exact modal stepping (vbikit.solve.moving_loads); load effects by mode acceleration",
    })
    return ds


def check(ds) -> dict[str, Any]:
    """The pass/fail summary: governing train, speed and quantity of every check."""
    acc = ds["max_deck_acceleration"]
    i, j = np.unravel_index(int(np.nanargmax(acc.values)), acc.shape)
    limit = float(ds["acceleration_limit"])
    peak = float(acc.values[i, j])
    out: dict[str, Any] = {"acceleration": {
        "peak": peak, "limit": limit, "train": str(ds.train.values[i]), "speed": float(ds.speed.values[j]),
        "passes": bool(peak <= limit), "ratio": peak / limit}}
    irr = ds["phi_irregularity"].values
    for kind in ("moment", "shear"):
        dyn = ds[f"max_{kind}"].values + 0.5 * irr[None, :] * ds[f"static_{kind}"].values[:, None]
        a, b = np.unravel_index(int(np.nanargmax(dyn)), dyn.shape)
        lm = float(ds[f"lm71_{kind}"])
        phi = float(ds[f"phi_dyn_{kind}"].values[a, b])
        out[kind] = {"dynamic_design": float(dyn[a, b]), "lm71_design": lm, "train": str(ds.train.values[a]),
                     "speed": float(ds.speed.values[b]), "phi_dyn": phi, "phi_irregularity": float(irr[b]),
                     "governs": "dynamic analysis" if dyn[a, b] > lm else "Phi x LM71", "ratio": float(dyn[a, b] / lm)}
    phid = ds["phi_dyn_deflection"].values
    a, b = np.unravel_index(int(np.nanargmax(phid)), phid.shape)
    out["deflection"] = {"phi_dyn": float(phid[a, b]), "train": str(ds.train.values[a]), "speed": float(ds.speed.values[b])}
    out["passes"] = out["acceleration"]["passes"]
    return out


def format_report(ds, checks: dict[str, Any]) -> str:
    """The text report of a sweep."""
    a = ds.attrs
    acc = checks["acceleration"]
    lines = [
        "vbikit railway dynamic check (EN 1991-2 6.4.6, EN 1990 A2.4.4.2.1)",
        f"bridge: simply supported span {a['span_m']:g} m, n0 = {a['first_frequency_hz']:.3f} Hz, {a['n_modes']} modes "
        f"(up to {float(ds['frequency'].values[-1]):.1f} Hz; required max(30 Hz, 1.5 n0, n3) = {a['frequency_limit_hz']:.1f} Hz), "
        f"damping {100 * a['damping_ratio']:.3f} % ({a['damping_source']}, {a['deck']}"
        f"{', with additional damping' if a['additional_damping'] else ''})",
        f"trains: {', '.join(map(str, ds.train.values))}; {ds.speed.size} speeds {float(ds.speed_kmh.min()):.0f} … "
        f"{float(ds.speed_kmh.max()):.0f} km/h",
    ]
    if a.get("modes_required", 0) > a["n_modes"]:
        lines.append(f"WARNING: {a['n_modes']} modes retained, but the {a['modes_required']} modes up to "
                     f"{a['frequency_limit_hz']:.1f} Hz are required (EN 1990 A2.4.4.2.1): raise bridge.n_modes")
    lines += [
        "",
        f"deck acceleration: peak {acc['peak']:.3f} m/s² ({acc['train']} at {3.6 * acc['speed']:.1f} km/h) against "
        f"{acc['limit']:g} m/s² ({a['track']} track): {'PASS' if acc['passes'] else 'FAIL'} ({100 * acc['ratio']:.0f} % of the limit)",
    ]
    for kind in ("moment", "shear"):
        c = checks[kind]
        lines.append(f"{kind}: (1 + phi'dyn + phi''/2) x train = {c['dynamic_design']:.4g} ({c['train']} at "
                     f"{3.6 * c['speed']:.1f} km/h, phi'dyn = {c['phi_dyn']:.3f}, phi'' = {c['phi_irregularity']:.3f}) "
                     f"vs Phi x alpha x LM71 = {c['lm71_design']:.4g} (Phi = {a['dynamic_factor_Phi']:.3f}, alpha = "
                     f"{a['classification_factor']:g}): {c['governs']} governs")
    d = checks["deflection"]
    lines.append(f"deflection: largest phi'dyn {d['phi_dyn']:.3f} ({d['train']} at {3.6 * d['speed']:.1f} km/h)")
    lines += ["", "resonance speeds v = n0 D / i [km/h]:"]
    for name, row in zip(ds.train.values, ds["resonance_speed"].values):
        r = row[np.isfinite(row)]
        if r.size:
            lines.append(f"  {name}: " + ", ".join(f"{3.6 * v:.1f}" for v in r))
    lines += ["", f"result: {'PASS' if checks['passes'] else 'FAIL'} (governing: {acc['train']}, "
              f"{3.6 * acc['speed']:.1f} km/h, deck acceleration)"]
    return "\n".join(lines) + "\n"


def write_outputs(result: RailResult, out_dir: Path, figures: bool = True) -> list[Path]:
    """``rail.nc``, ``rail-report.txt`` and (``figures``) ``rail-acceleration.png`` in ``out_dir``."""
    from vbikit._files import atomic_write, write_text

    out_dir.mkdir(parents=True, exist_ok=True)
    ds = result.dataset.copy()
    ds["train"] = ds["train"].astype(str)
    files = [atomic_write(out_dir / "rail.nc", lambda tmp: ds.to_netcdf(tmp, engine="netcdf4")),
             write_text(out_dir / "rail-report.txt", result.report)]
    if figures:
        from vbikit.rail.figures import plot_acceleration_envelopes

        files.append(plot_acceleration_envelopes(result.dataset, out_dir / "rail-acceleration.png"))
    return files
