"""A crossing on a random road without sampling: the mean history (the smooth-road crossing), the
standard deviation history of every response by pseudo-excitation (``vbikit.random.pem``), and
the design numbers that follow: the distribution of the peak deflection and of the impact factor
at each response point (peaks of Gaussian histories with PEM's covariance; the Poisson up-crossing
estimate of ``vbikit.random.peaks`` as a cross-check), the same for every load effect of the plan
(moment, shear, reaction), and the probability of lift-off.

Load effects, by the plan's ``load_effect_method`` (``vbikit.analysis.effects``), the ordinary
run's: mean (the smooth crossing's R), static reference and random part of one model.

* Mode superposition, R(t) = Σ_i r_i ξ_i(t) (r_i = ``LoadEffect.modal``): its pseudo response is
  Σ_i r_i ξ̃_i — a deck probe whose "mode shape" is r (``Probes.shapes`` row); static reference
  Σ_i r_i ξ_st,i (``vbikit.analysis.impact.static_modal_history``): the retained modes only.
* Mode acceleration (the default), R(t) = −Σ_p I(x_p) β_p f_w(t) − Σ_i r_i (ξ̈_i + 2ζ_iω_i ξ̇_i)/ω_i²
  = Σ_i r_i ξ_i − Σ_i r_i p_i/ω_i² − Σ_w c_w(t) f_w(t), with p_i = ξ̈_i + 2ζ_iω_i ξ̇_i + ω_i² ξ_i the modal
  load and c_w(t) = Σ_{p∈w} I(x_p(t)) β_p: linear in the state [ξ; ξ̇; p; F_w], so its pseudo
  response is the time-invariant part (a ``Probes.state_rows`` row) minus Σ_w c_w(t) F̃_w(t) (the
  wheels' pseudo forces, state rows too), combined per line (``_combine_acceleration``).  Its
  static reference is −Σ_p I(x_p) β_p P_w, every mode's static part included: the ordinary run's.
  A shear or reaction near a support, whose truncated modes' static part is large (30 % of the
  entry shear of the 3D Bridge 2 with 20 modes), needs it.
"""
from __future__ import annotations

import dataclasses
import logging
import time as _time
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np
from numpy.typing import NDArray

from vbikit.analysis.checks import Flag, flag_fields, small_static_flags, summary_flag_attrs
from vbikit.analysis.effects import LoadEffectResponse, load_effect_responses
from vbikit.analysis.impact import static_direction, static_modal_history
from vbikit.analysis.plan import ResponsePlan
from vbikit.analysis.response import PointResponse, plan_responses
from vbikit.outputs import QUANTITIES, cf_unit
from vbikit.random.lines import Lines, default_lines
from vbikit.random.peaks import exceedance_probability, peak_distribution
from vbikit.random.pem import PEMResult, Probes, PseudoRoad, pseudo_excitation

#: the pseudo-excitation integrator random runs use (``pseudo_excitation``'s default)
PEM_METHOD = "exact"
from vbikit.solve.crossing import Crossing
from vbikit.solve.result import CrossingResult
from vbikit.solve.run_in import START_OUTPUTS, start_settling
from vbikit.solve.simulate import simulate

log = logging.getLogger(__name__)

#: Gaussian histories sampled for the peak statistics (one matrix product each 256)
SAMPLES = 4000
#: the quantiles of the impact factor reported by default
QUANTILES = (0.5, 0.9, 0.95)
#: lift-off probability above which the linear theory is not trusted (the user is sent to Monte Carlo)
LIFT_OFF_LIMIT = 1e-3
#: how good the numbers are, in words (validated in tests/random_vibration; docs/random.md)
QUALITY = ("σ histories exact for the linear system up to the wavenumber grid (grid_change, checked in this run) and the "
           "time step (not checked in this run; on the demo the exact and Newmark paths, whose step errors differ, "
           "agree within 0.34 % of the peak σ, docs/random.md); they match 1,000 Monte-Carlo crossings within sampling error. Impact-factor "
           "statistics from the peaks of Gaussian histories with exactly that covariance (sampling error stated); "
           "the Poisson up-crossing quantiles (impact_factor_quantiles_crossings) are a cross-check that runs low "
           "below the 90 % quantile")
#: grid check (σ on every line vs every second line) above which the answer is flagged
GRID_LIMIT = 0.02
#: a run on the default grid whose check is above ``GRID_LIMIT`` runs again on a grid with every cell halved
#: (``vbikit.random.lines.default_lines``), at most this many times (254 → 506 → 1,009 lines over ISO 8608's
#: band; a 30 m beam under HS20-44 at 80 km/h: 4.75 % on 254 lines, 0.48 % on 506, test_pem_grid_refinement.py);
#: the flag is raised only if the check is still above the limit after them
GRID_REFINEMENTS = 2

#: the run's quality rules, each (flag code, the value's key in the summary and in a PEM study's cells,
#: its limit, the finding in words with the value, what to do): ``quality_flags``, and over a PEM
#: study's cells ``vbikit.study.pem.pem_dataset_flags``
QUALITY_RULES = (
    ("lift_off", "lift_off_probability", LIFT_OFF_LIMIT,
     "a tire lifts off with probability {value:.2g} at some instant (> {limit:g})",
     "the linear theory does not hold there, so the impact-factor statistics are not design values; use Monte Carlo "
     "(several road seeds, tires that can lift)"),
    ("coarse_grid", "grid_change", GRID_LIMIT,
     "the wavenumber grid is coarse: σ changes by {value:.1%} between every and every second line (> {limit:.0%})",
     "the σ histories and the statistics built on them may be off by about as much; refine the grid from Python "
     "(lines=vbikit.random.default_lines(n_min, n_max, refinement) with a refinement above the run's "
     "grid_refinements) or check the run with Monte Carlo crossings over road seeds"),
)


def point_label(entry: dict[str, Any]) -> str:
    """A response point of a random run's summary in words, "point x = 8.380 m, y = 2.130 m": its flags' subject
    and its report line (``vbikit run --random``)."""
    return f"point x = {entry['x']:.3f} m, y = {entry['y']:.3f} m"


def quality_flags(values: dict[str, float]) -> list[Flag]:
    """The ``QUALITY_RULES`` flags of one run from its ``values`` (by the rules' keys)."""
    out = []
    for code, key, limit, finding, advice in QUALITY_RULES:
        value = float(values[key])
        if value > limit:
            out.append(Flag(code, finding.format(value=value, limit=limit) + (f": {advice}" if advice else ""),
                            value=value, threshold=limit))
    return out


def _every_channel(n_points: int, effects: list[LoadEffectResponse]) -> list[int]:
    """Every deck channel: the points, then the load effects."""
    return list(range(n_points + len(effects)))


def _study_channels(n_points: int, effects: list[LoadEffectResponse]) -> list[int]:
    """What a PEM study stores (``vbikit.study.pem.PEM_OUTPUTS``): the headline point (channel 0) and
    the first bending moment of the plan, if any."""
    first = next((k for k, e in enumerate(effects) if e.effect.kind == "moment"), None)
    return [0] + ([] if first is None else [n_points + first])


#: which deck channels get peak and impact-factor statistics (``random_response(peaks=...)``): name ->
#: (the channels' rule, with the Poisson up-crossing cross-check or not).  "all": every point and
#: effect, with the cross-check (``vbikit run --random``); "study": what a PEM study stores, no
#: cross-check.  σ histories, the grid check and the lift-off probability are computed for every
#: channel either way.
PEAKS: dict[str, tuple[Callable[[int, list[LoadEffectResponse]], list[int]], bool]] = {
    "all": (_every_channel, True), "study": (_study_channels, False)}


@dataclass
class RandomResponse:
    """The random crossing: ``mean`` (the smooth-road crossing), its ``points`` (mean and static
    histories per response point), ``effects`` (mean and static histories of the plan's load
    effects, mode superposition), ``pem`` (variances: the deck channels hold the points, then the
    effects), ``summary`` (JSON-ready numbers)."""

    mean: CrossingResult
    points: list[PointResponse]
    pem: PEMResult
    summary: dict[str, Any]
    effects: list[LoadEffectResponse] = dataclasses.field(default_factory=list)

    def effect_std(self, k: int) -> NDArray[np.float64]:
        """σ(t) of load effect ``k`` (its unit: N m or N)."""
        return self.pem.std("displacement")[:, len(self.points) + k]

    def dataset(self):
        """xarray Dataset: ``mean`` and ``std`` of the deck displacement, velocity, acceleration and
        bottom-fibre strain over (time, point), of every load effect (``<name>_mean``, ``<name>_std``,
        ``<name>_static`` over time, e.g. ``moment_x8.38``), of the vehicle DOFs' accelerations over
        (time, dof) and of the contact forces over (time, wheel) — named as ``CrossingResult.to_xarray``
        names them (points by the summary's names, the plan's: ``p1``, ``p2``, … or their own; ``contact_force``;
        the DOFs' units by ``vehicle_dof_units``), with ``_mean`` and ``_std``."""
        import xarray as xr

        from vbikit.solve.result import deck_point_coords, vehicle_dof_coords, vehicle_dof_units

        t = self.pem.time
        n = min(t.size, self.mean.time.size)
        pts = np.arange(len(self.points))
        data: dict[str, Any] = {}
        for q in ("displacement", "velocity", "acceleration", "strain"):
            unit = cf_unit(QUANTITIES[q].unit)  # (the catalogue's unit, in the datasets' CF spelling)
            data[f"{q}_mean"] = (("time", "point"), np.stack([getattr(p, q)[:n] for p in self.points], axis=1),
                                 {"units": unit, "long_name": f"mean deck {q} (smooth-road crossing)"})
            data[f"{q}_std"] = (("time", "point"), self.pem.std(q)[:n, :pts.size], {"units": unit,
                                                                         "long_name": f"standard deviation of the deck {q} (pseudo-excitation)"})
        for k, e in enumerate(self.effects):
            unit = e.effect.units
            data[f"{e.name}_mean"] = ("time", e.dynamic[:n], {"units": unit, "long_name": f"mean {e.effect.label} "
                                                                                         f"(smooth road, {e.method})"})
            data[f"{e.name}_std"] = ("time", self.effect_std(k)[:n], {"units": unit, "long_name": f"standard deviation of "
                                                                                              f"the {e.effect.label}"})
            data[f"{e.name}_static"] = ("time", e.static[:n], {"units": unit})
        vehicle = self.mean.crossing.vehicle
        dof_units = vehicle_dof_units(vehicle.dof_names, acceleration=True)
        data["vehicle_acceleration_mean"] = (("time", "dof"), self.mean.q_ddot[:n],
                                             {**dof_units, "long_name": "mean vehicle DOF acceleration (smooth-road crossing)"})
        data["vehicle_acceleration_std"] = (("time", "dof"), self.pem.std("vehicle_acceleration")[:n],
                                            {**dof_units, "long_name": "standard deviation of the vehicle DOF acceleration"})
        wheels = [w.name for w in vehicle.wheels]
        data["contact_force_mean"] = (("time", "wheel"), self.mean.wheel_forces[:n],
                                      {"units": "N", "long_name": "mean tire force, compression positive (smooth-road crossing)"})
        data["contact_force_std"] = (("time", "wheel"), self.pem.std("wheel_force")[:n],
                                     {"units": "N", "long_name": "standard deviation of the tire force"})
        s = self.summary
        attrs = {"method": s["method"], "grid_change": s["grid_change"], "n_lines": s["n_lines"],
                 "lift_off_probability": s["lift_off_probability"],
                 **summary_flag_attrs(s)}
        names = [str(p["name"]) for p in s["points"]]  # (the summary's: one entry a point, in order)
        coords = deck_point_coords(t[:n], names, [p.x for p in self.points], [p.y for p in self.points])
        return xr.Dataset(data, coords={**coords, "wheel": wheels, **vehicle_dof_coords(vehicle.dof_names)}, attrs=attrs)


def random_response(crossing: Crossing, plan: ResponsePlan, road: PseudoRoad, dt: float, *,
                    quantiles: tuple[float, ...] = QUANTILES, lines: Lines | None = None, substeps: int | None = None,
                    samples: int = SAMPLES, data=None, peaks: str = "all") -> RandomResponse:
    """Mean, σ and impact-factor distribution of ``crossing`` on the random ``road`` at the points of
    ``plan``, on the time grid of step ``dt`` [s] (the engine's step for the sampled road);
    ``substeps`` integrator steps an output step (None: ``pseudo_excitation``'s default for its
    method, one exact step, so that PEM and Monte Carlo step the same discrete system).

    The impact factor at a point is IM = (P − R_st)/R_st with P the peak of the dynamic response in
    the static peak's direction and R_st the static peak (``vbikit.analysis.impact``).  P's
    distribution: the peaks of ``samples`` histories of the Gaussian process with PEM's covariance
    (``PEMResult.sample_displacement``: exact for the linear system, with a sampling error stated
    in the summary), and as a cross-check by Poisson up-crossings (``peak_distribution``).  The
    same for every load effect of ``plan`` (``summary["effects"]``; mode superposition, module
    docstring), with its static reference R_st from the static modal history.  ``peaks`` (``PEAKS``):
    "all" (default) every point and effect with the up-crossing cross-check; "study" only what a
    PEM study stores (the headline point and the first bending moment, no cross-check; the other
    effects' entries then hold σ only), the same numbers for those."""
    return random_responses(crossing, plan, [road], dt, quantiles=quantiles, lines=lines, substeps=substeps,
                            samples=samples, data=data, peaks=peaks)[0]


def level_factor(road: PseudoRoad, base: PseudoRoad) -> float | None:
    """G_road(n) / G_base(n) [-] if ``road`` is ``base`` at another level (the same band, exponent,
    n0 and wheel-line coherence, another φ(n0): e.g. ISO 8608 classes, 4× apart), else None; 1 for
    ``base`` itself (whatever its spectrum: a zero level, a spectrum without ``phi0``)."""
    if road is base or road == base:
        return 1.0
    if (road.coherence, road.two_lines) != (base.coherence, base.two_lines) or type(road.psd) is not type(base.psd) \
            or "phi0" not in {f.name for f in dataclasses.fields(base.psd)} or not base.psd.phi0 > 0:
        return None
    if dataclasses.replace(road.psd, phi0=base.psd.phi0) != base.psd:
        return None
    return float(road.psd.phi0 / base.psd.phi0)


def random_responses(crossing: Crossing, plan: ResponsePlan, roads: list[PseudoRoad], dt: float, *,
                     quantiles: tuple[float, ...] = QUANTILES, lines: Lines | None = None, substeps: int | None = None,
                     samples: int = SAMPLES, data=None, peaks: str = "all") -> list[RandomResponse]:
    """``random_response`` of ``crossing`` on each road of ``roads``, which differ only in level
    (``level_factor``: the PSD G times a factor f_r): the system is linear in the road, so every
    pseudo response is the first road's times √f_r, every variance its variance times f_r — one
    pseudo-excitation and one set of sampled Gaussian histories (the same random numbers, scaled)
    serve them all; the smooth crossing (the mean) is the same.  The numbers equal
    ``random_response`` road by road (bit for bit when √f_r is a power of two, as between ISO
    classes; else to round-off)."""
    if int(samples) != samples or samples < 100:
        raise ValueError(f"samples must be an integer >= 100, got {samples!r}")
    if peaks not in PEAKS:
        raise ValueError(f"peaks must be one of {', '.join(PEAKS)}, got {peaks!r}")
    if not roads:
        raise ValueError("roads: give at least one road")
    road = roads[0]
    factors = [level_factor(r, road) for r in roads]
    if any(f is None for f in factors):
        raise ValueError("roads must differ only in their PSD's level phi0 (the same band, exponent, n0 and coherence)")
    which, crossings = PEAKS[peaks]
    started = _time.perf_counter()
    smooth = simulate(dataclasses.replace(crossing, road=None, road_right=None, dt=dt))
    xi_st = static_modal_history(smooth)
    points = plan_responses(smooth, plan, xi_st)
    method = plan.load_effect_method
    effects = load_effect_responses(smooth, plan.load_effects, method, xi_st)
    xs, ys = [p.x for p in points], [p.y for p in points]
    shapes, strains = np.atleast_2d(crossing.bridge.mode_shapes(xs, ys)), np.atleast_2d(crossing.bridge.strain_shapes(xs, ys))
    rows = None
    if effects and method == "mode-superposition":  # a deck probe whose "shape" is r_i (module docstring)
        modal = np.stack([e.effect.modal for e in effects])
        shapes, strains = np.vstack([shapes, modal]), np.vstack([strains, np.zeros_like(modal)])
    elif effects:  # mode acceleration: state rows (module docstring)
        rows = _acceleration_rows(crossing, effects)
    n_pt = len(points)
    refinement = 0
    while True:  # the default grid refined while its check is above the limit (``GRID_REFINEMENTS``)
        grid_lines = lines if lines is not None else default_lines(road.psd.n_min, road.psd.n_max, refinement)
        pem = pseudo_excitation(crossing, road, Probes(shapes, strains, rows), dt, lines=grid_lines,
                                substeps=substeps, method=PEM_METHOD, data=data, keep_lines=True)
        n = min(pem.time.size, smooth.time.size)
        if rows is not None:
            _combine_acceleration(pem, smooth, effects, n_pt, road.line_factors().shape[0], n)
        grid = _run_grid_change(pem, n_pt, len(effects))
        if lines is not None or grid <= GRID_LIMIT or refinement == GRID_REFINEMENTS:
            break
        refinement += 1
        log.info("random run: the grid check is %.1f%% on %d lines (> %.0f%%); again with every cell halved",
                 100 * grid, grid_lines.size, 100 * GRID_LIMIT)
    # every deck channel (points, then effects): mean, its rate and the static reference
    mean = np.stack([p.displacement[:n] for p in points] + [e.dynamic[:n] for e in effects], axis=1)
    rate = np.stack([p.velocity[:n] for p in points] + [_effect_rate(smooth, e, n) for e in effects], axis=1)
    static = np.stack([p.static_displacement[:n] for p in points] + [e.static[:n] for e in effects], axis=1)
    chosen = which(n_pt, effects)
    scales = [float(np.sqrt(f)) for f in factors]
    sampled_all = _sampled_peaks(pem, mean, static, n, samples, chosen, scales)
    base = pem
    out = []
    for road, f, sampled in zip(roads, factors, sampled_all):
        pem = base if f == 1.0 else base.scaled(f)
        out.append(RandomResponse(smooth, points, pem, _reduce(
            crossing, plan, road, smooth, points, effects, pem, n, mean, rate, static, chosen, sampled, quantiles,
            crossings, samples, started, grid, refinement), effects))
    return out


def _reduce(crossing, plan, road, smooth, points, effects, pem, n, mean, rate, static, chosen, sampled, quantiles,
            crossings, samples, started, grid, refinement) -> dict[str, Any]:
    """The summary of one road (``random_responses``): statistics of the ``chosen`` deck channels
    from their ``sampled`` peaks, σ of every channel, lift-off, the grid check ``grid`` after ``refinement``
    halvings of the default grid's cells, and warnings."""
    n_pt = len(points)
    col = {j: c for c, j in enumerate(chosen)}

    def stats(j):
        if j not in col:
            return {}
        return _peak_entry(pem, j, n, mean[:, j], static[:, j], rate[:, j], quantiles, sampled[:, col[j]], crossings)

    entries = []
    for j, (p, name) in enumerate(zip(points, plan.point_names)):  # (named as the dataset's ``point`` and vbikit run)
        if j not in col:  # a further point of a study: σ only
            entries.append({"name": name, "x": p.x, "y": p.y,
                            "displacement_std_max": float(pem.std("displacement")[:n, j].max())})
            continue
        entry = {"name": name, "x": p.x, "y": p.y, **stats(j)}
        entry["displacement_peak_mean"] = entry.pop("peak_mean")
        entry["displacement_peak_std"] = entry.pop("peak_std")
        entries.append(entry | {"displacement_std_max": float(pem.std("displacement")[:n, j].max()),
                                "acceleration_std_max": float(pem.std("acceleration")[:n, j].max()),
                                "strain_std_max": float(pem.std("strain")[:n, j].max())})
    effect_entries = []
    for k, e in enumerate(effects):
        j = n_pt + k
        entry = {"name": e.name, "kind": e.effect.kind, "x": e.effect.x, "units": e.effect.units,
                 "method": plan.load_effect_method, **stats(j), "std_max": float(pem.std("displacement")[:n, j].max())}
        effect_entries.append(entry)
    wheel_std = pem.std("wheel_force")[:n]
    lift = {w.name: exceedance_probability(smooth.wheel_forces[:n, k], wheel_std[:, k])
            for k, w in enumerate(crossing.vehicle.wheels)}
    p_lift = max(lift.values(), default=0.0)
    flags = quality_flags({"lift_off_probability": p_lift, "grid_change": grid})
    if len(entries) > 1 and all("static_peak" in e for e in entries):  # a point's mean IM on a small static
        # reference (vbikit.analysis.checks); peaks="study" has no statistics of the further points
        flags += small_static_flags([point_label(e) for e in entries],
                                    [e["static_peak"] for e in entries],
                                    [e["impact_factor_mean"] for e in entries], output="impact_factor_mean")
    head = entries[0]
    vehicle = crossing.vehicle
    summary: dict[str, Any] = {
        "method": "pseudo-excitation (%s integrator, %d step(s) an output step); peaks of %d Gaussian histories "
                  "with its covariance%s"
                  % (PEM_METHOD, pem.substeps, samples,
                     " (cross-check: Poisson up-crossings with Vanmarcke's correction)" if crossings else ""),
        **{k: head[k] for k in ("impact_factor_mean", "impact_factor_std", "impact_factor_quantiles",
                                "impact_factor_sampling_error", "impact_factor_quantiles_crossings",
                                "displacement_peak_mean", "displacement_peak_std", "static_peak", "std_at_peak")
           if k in head},
        "lift_off_probability": p_lift,
        "lift_off_probability_by_wheel": lift,
        "run_in": float(crossing.run_in),
        **{k: v for k, v in zip(START_OUTPUTS, start_settling(crossing)) if not np.isnan(v)},  # (NaN: moving forces)
        "wheel_force_std_max": {w.name: float(wheel_std[:, k].max()) for k, w in enumerate(vehicle.wheels)},
        "vehicle_acceleration_std_max": dict(zip(vehicle.dof_names,
                                                 map(float, pem.std("vehicle_acceleration")[:n].max(axis=0)))),
        "grid_change": grid,
        "grid_refinements": refinement,
        "n_lines": pem.lines.size * road.line_factors().shape[0],
        "quality": QUALITY,
        "points": entries,
        "effects": effect_entries,
        **flag_fields(flags),
        "dt": float(pem.time[1] - pem.time[0]) if pem.time.size > 1 else float("nan"),
        "seconds": _time.perf_counter() - started,
    }
    # every top-level number's unit, in the CF spelling of every JSON summary (as vbikit run's ``units``)
    summary["units"] = {k: u for k, u in SUMMARY_UNITS.items() if k in summary}
    from vbikit.solve.result import dof_acceleration_unit

    summary["units"]["vehicle_acceleration_std_max"] = {d: dof_acceleration_unit(d) for d in vehicle.dof_names}
    return summary


#: the units of a random run's top-level numbers (``units`` of its summary; the points' and load effects' entries
#: carry those of their own kind: a displacement in m, a load effect in its ``units``)
SUMMARY_UNITS = {"impact_factor_mean": "1", "impact_factor_std": "1", "impact_factor_quantiles": "1",
                 "impact_factor_sampling_error": "1", "impact_factor_quantiles_crossings": "1",
                 "displacement_peak_mean": "m", "displacement_peak_std": "m", "static_peak": "m", "std_at_peak": "m",
                 "lift_off_probability": "1", "lift_off_probability_by_wheel": "1", "run_in": "m",
                 **{k: unit for k, (unit, _) in START_OUTPUTS.items()}, "wheel_force_std_max": "N",
                 "grid_change": "1", "grid_refinements": "1", "n_lines": "1", "dt": "s", "seconds": "s"}


def _acceleration_rows(crossing: Crossing, effects: list[LoadEffectResponse]) -> NDArray[np.float64]:
    """``Probes.state_rows`` of load effects by mode acceleration (module docstring): per effect
    [r; 0; −r/ω²; 0] on [ξ; ξ̇; p; F_w] (Σ r_i ξ_i − Σ r_i p_i/ω_i² = −Σ r_i (ξ̈_i + 2ζ_iω_i ξ̇_i)/ω_i²), then
    one row per wheel picking its contact force F_w."""
    omega = crossing.bridge.omega
    n_m, n_w = omega.size, len(crossing.vehicle.wheels)
    rows = np.zeros((len(effects) + n_w, 3 * n_m + n_w))
    for k, e in enumerate(effects):
        rows[k, :n_m] = e.effect.modal
        rows[k, 2 * n_m:3 * n_m] = -e.effect.modal / omega**2
    rows[len(effects):, 3 * n_m:] = np.eye(n_w)
    return rows


def _combine_acceleration(pem: PEMResult, smooth: CrossingResult, effects: list[LoadEffectResponse], n_pt: int,
                          n_sets: int, n: int) -> None:
    """Complete the mode-acceleration load effects' pseudo responses in ``pem`` (in place) and drop
    the wheel-force channels that served them: ỹ_e(t) = [Σ r ξ̃ − Σ r p̃/ω²](t) − Σ_w c_ew(t) F̃_w(t) with
    c_ew(t) = Σ_{p∈w} I_e(x_p(t), y_p) β_p (the influence at the wheel's contact points, spread by
    their static shares: ``vbikit.analysis.effects``, the engine's rule), per line; then the
    effects' variances (every line and the grid check's every second line), and their rate ẏ̃_e
    by central differences in time (``numpy.gradient``: relative error (ω dt)²/6, 3e-4 for a
    7 Hz mode at 1 ms) for Cov(y, ẏ) and λ₁ of the up-crossing cross-check."""
    from vbikit.analysis.effects import contact_influence_table

    n_e = len(effects)
    crossing = smooth.crossing
    cp = crossing.contact
    n_w = len(crossing.vehicle.wheels)
    table = contact_influence_table(smooth, [e.effect for e in effects])
    pts = table.points
    share = np.zeros((pts.size, n_w))
    share[np.arange(pts.size), cp.wheel[pts]] = cp.weight[pts]
    coef = table.sums(share)[:, :, :n]  # (n_w, n_e, n_t)
    kept = pem.lines_displacement  # (n_t, channels, 2 L')
    eff, wheels = slice(n_pt, n_pt + n_e), slice(n_pt + n_e, n_pt + n_e + n_w)
    y = kept[:n, eff] - np.einsum("wet,twc->tec", coef, kept[:n, wheels])
    y_rate = np.gradient(y, float(pem.time[1] - pem.time[0]), axis=0)  # the uniform output grid
    coarse_w = np.repeat(np.tile(pem.lines.coarse_weights(), n_sets), 2)
    for name, z in (("displacement", y), ("velocity", y_rate)):
        z2 = z * z
        pem.var[name][:n, eff] = z2.sum(axis=2)
        pem.coarse[name][:n, eff] = z2 @ coarse_w
    pem.cov_dv[:n, eff] = (y * y_rate).sum(axis=2)
    modulus = lambda z: np.hypot(z[..., 0::2], z[..., 1::2])  # noqa: E731  |ỹ_k| of the [Re, Im] pairs
    pem.lambda1[:n, eff] = (modulus(y) * modulus(y_rate)).sum(axis=2)
    kept[:n, eff] = y
    keep = np.r_[0:n_pt + n_e]
    pem.time = pem.time[:n]
    deck = ("displacement", "velocity", "acceleration", "strain")
    for d in (pem.var, pem.coarse):
        for name in d:
            d[name] = d[name][:n, keep] if name in deck else d[name][:n]
    pem.cov_dv, pem.lambda1 = pem.cov_dv[:n, keep], pem.lambda1[:n, keep]
    pem.lines_displacement = np.ascontiguousarray(kept[:n, keep])


def _effect_rate(smooth: CrossingResult, e: LoadEffectResponse, n: int) -> NDArray[np.float64]:
    """dR/dt of a load effect's mean history: Σ r_i ξ̇_i by mode superposition; by mode acceleration
    central differences of R (``_combine_acceleration``)."""
    if e.method == "mode-superposition":
        return smooth.xi_dot[:n] @ e.effect.modal
    return np.gradient(e.dynamic[:n], smooth.time[:n])


def _run_grid_change(pem: PEMResult, n_points: int, n_effects: int) -> float:
    """The run's grid check: the largest ``_grid_change`` of the points' displacement and acceleration, the
    wheel forces and each load effect (one unit at a time)."""
    return max(_grid_change(pem, "displacement", slice(0, n_points)),
               _grid_change(pem, "acceleration", slice(0, n_points)), pem.grid_change("wheel_force"),
               *(_grid_change(pem, "displacement", slice(j, j + 1)) for j in range(n_points, n_points + n_effects)))


def _grid_change(pem: PEMResult, name: str, cols: slice) -> float:
    """``PEMResult.grid_change`` of the channels ``cols`` of ``name`` only (one unit at a time)."""
    s, c = np.sqrt(pem.var[name][:, cols]), np.sqrt(np.maximum(pem.coarse[name][:, cols], 0.0))
    top = float(s.max(initial=0.0))
    return float(np.abs(s - c).max(initial=0.0) / top) if top > 0 else 0.0


def _sampled_peaks(pem: PEMResult, mean: NDArray[np.float64], static: NDArray[np.float64], n: int,
                   samples: int, channels: list[int], scales: list[float]) -> list[NDArray[np.float64]]:
    """Per factor a of ``scales``: (samples, len(channels)), the peak of each sampled history of the
    deck channels ``channels`` with its random part times a (``mean`` (n_t, all channels), the
    smooth crossing's) in its static peak's direction."""
    sign = np.array([static_direction(static[:, j]) for j in channels])
    signed = mean[:, channels] * sign
    out: list[list[NDArray[np.float64]]] = [[] for _ in scales]
    for y in pem._sample_blocks(samples, channels=channels):  # (n_t, channels, m): the maximum over time runs over contiguous rows
        y = y[:n]
        for k, a in enumerate(scales):
            z = y * a if a != 1.0 else y.copy() if k < len(scales) - 1 else y
            z *= sign[:, None]
            z += signed[:, :, None]
            out[k].append(z.max(axis=0).T)
    return [np.concatenate(o, axis=0) for o in out]


def _peak_entry(pem: PEMResult, j: int, n: int, mean_signed: NDArray[np.float64], static: NDArray[np.float64],
                rate_signed: NDArray[np.float64], quantiles, peaks: NDArray[np.float64],
                crossings: bool = True) -> dict[str, Any]:
    """Peak and impact-factor statistics of deck channel ``j`` (a point's displacement or a load
    effect) from its smooth-road ``mean_signed``, ``rate_signed``, ``static`` histories (signed as
    the response) and its sampled ``peaks`` (in the static peak's direction); ``crossings``: with the
    Poisson up-crossing quantiles (``impact_factor_quantiles_crossings``)."""
    sign = static_direction(static)
    r_st = float(np.max(sign * static))
    mean, rate = sign * mean_signed, sign * rate_signed
    std, rate_std = pem.std("displacement")[:n, j], pem.std("velocity")[:n, j]
    ok = r_st > 0
    im = (peaks - r_st) / r_st if ok else np.full(peaks.size, np.nan)
    cross = lambda b: (b - r_st) / r_st if ok else float("nan")  # noqa: E731
    i_peak = int(np.argmax(mean))
    out = {"impact_factor_mean": float(im.mean()), "impact_factor_std": float(im.std(ddof=1)),
           "impact_factor_quantiles": {f"{q:g}": float(np.quantile(im, q)) for q in quantiles},
           "impact_factor_sampling_error": float(im.std(ddof=1) / np.sqrt(im.size)),
           "impact_factor_samples": int(im.size)}
    if crossings:
        dist = peak_distribution(pem.time[:n], mean, std, rate, rate_std, pem.cov_dv[:n, j], pem.lambda1[:n, j])
        out["impact_factor_quantiles_crossings"] = {f"{q:g}": cross(dist.quantile(q)) for q in quantiles}
    return out | {"peak_mean": sign * float(peaks.mean()), "peak_std": float(peaks.std(ddof=1)),
                  "static_peak": sign * r_st, "std_at_peak": float(std[i_peak]),
                  "impact_factor_smooth": cross(float(mean.max()))}
