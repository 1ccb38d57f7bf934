"""Field verification: simulate a measured crossing, align and clean the record, compare, calibrate.

Pipeline per loading case ([`compare_case`][vbikit.field.compare_case]):

1. read the response CSV ([`read_response_csv`][vbikit.field.read_response_csv]) and check it against the
   case's channel table (missing channels, unit mismatches, sampling rate);
2. simulate the crossing with each tire model on the bridge preset (optionally scaled by a
   stiffness factor, see [`ScaledBridge`][vbikit.field.ScaledBridge]) with the measured wheel-track profiles;
3. align the record in time: ``trigger`` (t_sim = t_meas − t_trig + approach / speed) or
   ``xcorr`` (cross-correlation of the first displacement — else strain — channel with the
   first tire model's simulation);
4. optional zero-phase low-pass of record *and* simulation at the same cut-off (recorded);
5. remove offset and linear drift from acceleration channels: ``quiet`` fits a line to the
   samples where the bridge is at rest (before the front axle reaches the span, and the last
   ``quiet_tail`` seconds of the record); ``model`` fits it to measured − simulated;
6. resample the record onto the simulation time base (cubic spline) and compute the metrics of
   ``vbikit.field.metrics`` on the overlap.

[`calibrate`][vbikit.field.calibrate] fits a stiffness factor f (every ωᵢ → √f ωᵢ, mode shapes unchanged: uniform
scaling of E) and one modal damping ratio ζ by ``scipy.optimize.least_squares``.  Residuals are
taken at the *measured* sample instants (the simulation, interpolated there), each channel
divided by its measured RMS; the covariance is s² (JᵀJ)⁻¹ with s² = Σr² / (m − n) (Gauss–Newton
linearisation at the optimum), multiplied by f_s / (2 f_c) when a low-pass at f_c was applied to a
record sampled at f_s (the residuals are then correlated; see docs/field.md).
"""
from __future__ import annotations

import logging
import time as _time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import CubicSpline
from scipy.optimize import least_squares

from vbikit.bridge.base import GirderDeck, ModalBridge
from vbikit.bridge.presets import BRIDGE_PRESETS
from vbikit.bridge.scaled import ScaledBridge
from vbikit.bridge.series import SpanSeries
from vbikit.contact.registry import TIRE_MODELS
from vbikit.contact.tires import TireModel
from vbikit.field.io import (
    CaseSpec,
    FieldFileError,
    FieldSpec,
    MeasuredRecord,
    check_case_record,
    read_response_csv,
)
from vbikit.field.metrics import channel_metrics
from vbikit.field.signal import (
    DriftFit,
    lowpass,
    model_drift,
    quiet_drift,
    resample,
    xcorr_shift,
)
from vbikit.road.measured import read_profile_csv
from vbikit.road.profile import RoadProfile
from vbikit.scenario.build import build_bridge, build_tire
from vbikit.scenario.preflight import check_steps
from vbikit.scenario.schema import TireSpec, parse_bridge
from vbikit.solve import Crossing, CrossingResult, simulate
from vbikit.solve.budget import Limits, check_bridge
from vbikit.vehicle.presets import VEHICLE_PRESETS

log = logging.getLogger(__name__)

#: the tire models a field comparison can use: every registered model, with its defaults
FIELD_TIRES = TIRE_MODELS


def field_tire(name: str) -> TireModel:
    """The tire model ``name`` with the defaults of a scenario's [tire] (built as a scenario builds it)."""
    return build_tire(TireSpec(model=name))


def parse_tires(text: str) -> list[str]:
    """``"point,multipoint"`` → ["point", "multipoint"]; unknown names raise a ValueError naming --tires."""
    names = [t.strip() for t in text.split(",") if t.strip()]
    bad = [t for t in names if t not in FIELD_TIRES]
    if not names or bad:
        raise ValueError(f"--tires: unknown tire model {bad[0] if bad else text!r}; allowed: {', '.join(FIELD_TIRES)}")
    return names


def base_bridge(spec: FieldSpec) -> ModalBridge:
    """The bridge preset of a field test (with ``[bridge.deck]`` overrides on slab-on-girder presets),
    validated and built as a scenario's [bridge]."""
    if spec.bridge not in BRIDGE_PRESETS:
        raise FieldFileError(f"{spec.path}: bridge {spec.bridge!r} is not a preset; allowed: {', '.join(BRIDGE_PRESETS)}")
    table: dict[str, Any] = {"model": spec.bridge, "n_modes": spec.n_modes, "damping_ratio": spec.damping_ratio}
    if spec.bridge_overrides:
        table["deck"] = dict(spec.bridge_overrides)
    try:
        return build_bridge(parse_bridge(table))
    except (TypeError, ValueError) as err:
        raise FieldFileError(f"{spec.path}: {err}") from None


def sensor_y(bridge: ModalBridge, girder: int, where: str) -> float:
    """y [m] of a girder's centre line (Girder 1 at the most negative y); a beam model has y = 0."""
    base = bridge.base if isinstance(bridge, ScaledBridge) else bridge
    if not isinstance(base, GirderDeck):
        return 0.0
    gy = base.girder_y
    if not 1 <= girder <= len(gy):
        raise FieldFileError(f"{where}: girder {girder} does not exist (the bridge has {len(gy)} girders)")
    return float(gy[girder - 1])


Profiles = tuple[RoadProfile | None, RoadProfile | None]


def _check_truck(spec: FieldSpec) -> None:
    if spec.truck not in VEHICLE_PRESETS:
        raise FieldFileError(f"{spec.path}: truck {spec.truck!r} is not a preset; allowed: {', '.join(VEHICLE_PRESETS)}")


def case_profiles(case: CaseSpec) -> Profiles:
    """The case's measured wheel-track profiles (left, right) read from their CSV files (None where
    the case gives none); a bad file raises ``RoadFileError`` naming it and the line."""
    return (read_profile_csv(case.profile_left) if case.profile_left else None,
            read_profile_csv(case.profile_right) if case.profile_right else None)


def _checked_profiles(spec: FieldSpec, case: CaseSpec) -> Profiles:
    """``case_profiles`` after the truck check ``case_crossing`` makes first (the same errors in the same
    order, for callers that read a case's profiles once for every tire model)."""
    _check_truck(spec)
    return case_profiles(case)


def case_crossing(spec: FieldSpec, case: CaseSpec, tire: TireModel, bridge: ModalBridge, dt: float | None = None,
                  profiles: Profiles | None = None) -> Crossing:
    """The simulated crossing of one loading case (vehicle enters in static equilibrium ``approach``
    before the span, or settled by its ``run_in`` on the road behind); ``profiles``: the case's profiles as ``case_profiles`` reads them (read here
    when None; a caller simulating one case several times reads them once)."""
    _check_truck(spec)
    left, right = case_profiles(case) if profiles is None else profiles
    offset = tested_span_offset(bridge)
    if offset:  # a series of spans: x of the files is from the tested span's entry, the crossing's from the first span's
        if spec.approach < offset:
            raise FieldFileError(f"{spec.path}: approach = {spec.approach} m is shorter than the spans before the tested "
                                 f"one ({offset} m): the truck must start before the first span")
        left, right = (None if p is None else RoadProfile(p.x + offset, p.z, p.label, p.resolution) for p in (left, right))
    return Crossing(bridge, VEHICLE_PRESETS[spec.truck].build(), tire, left, speed=case.speed or spec.speed,
                    approach=spec.approach - offset, free_vibration=spec.free_vibration, lateral_offset=case.lateral_offset,
                    dt=dt if dt is not None else spec.dt, road_right=right, run_in=spec.run_in)


def tested_span_offset(bridge: ModalBridge) -> float:
    """x [m] of the tested span's entry in the bridge model: 0, or the spans before it in a
    ``SpanSeries`` (channel x, ``approach`` and profiles are measured from
    the tested span's entry, as in the field)."""
    base = bridge.base if isinstance(bridge, ScaledBridge) else bridge
    return float(base.instrumented_offset) if isinstance(base, SpanSeries) else 0.0


def simulated_channels(result: CrossingResult, case: CaseSpec, where: str) -> dict[str, NDArray[np.float64]]:
    """Simulated history of each channel of ``case`` (SI units) at its (x, girder)."""
    br = result.crossing.bridge
    offset = tested_span_offset(br)
    length = br.span - offset
    out = {}
    for ch in case.channels:
        y = sensor_y(br, ch.girder, where)
        xi = float(br.span_coordinate(ch.x + offset, y)) - offset  # along its girder (a skew deck's lines are shifted)
        if not 0.0 <= xi <= length:
            extra = "" if xi == ch.x else f" (x − y tan θ = {xi:.6g} m along its girder)"
            raise FieldFileError(f"{where}: channel {ch.name!r}: x = {ch.x} m is outside the span 0 … {length} m{extra}")
        out[ch.name] = {"displacement": result.displacement, "acceleration": result.acceleration,
                        "strain": result.strain}[ch.quantity](ch.x + offset, y)
    return out


@dataclass
class CaseComparison:
    """Result of [`compare_case`][vbikit.field.compare_case]; histories on the simulation time base ``time`` (overlap only)."""

    case: CaseSpec
    time: NDArray[np.float64]
    shift: float
    t_entry: float
    measured: dict[str, NDArray[np.float64]]
    simulated: dict[str, dict[str, NDArray[np.float64]]]
    metrics: dict[str, dict[str, dict[str, Any]]]
    drift: dict[str, DriftFit]
    lowpass_hz: float | None
    record: MeasuredRecord
    dt: float
    timings: dict[str, float] = field(default_factory=dict)

    def table(self) -> dict[str, Any]:
        """JSON-ready summary: alignment, drift fits, cut-off, metrics per tire and channel, and each channel's SI
        unit in CF spelling (``channel_units``: the unit of its peaks, ``rms_error`` and drift ``offset``; the drift
        per second of that unit per s; ``peak_error``, ``normalised_rms_error`` and ``correlation`` are fractions)."""
        from vbikit.outputs import QUANTITIES, cf_unit

        return {
            "case": self.case.name,
            "align": self.case.align,
            "time_shift_s": self.shift,
            "trigger_time_s": self.t_entry - self.shift,
            "lowpass_hz": self.lowpass_hz,
            "record_sampling_rate_hz": self.record.sampling_rate,
            "simulation_dt_s": self.dt,
            "drift": {k: {"offset": d.offset, "drift_per_s": d.drift, "t_ref_s": d.t_ref, "method": d.method,
                          "samples": d.samples} for k, d in self.drift.items()},
            "metrics": self.metrics,
            "channel_units": {ch.name: cf_unit(QUANTITIES[ch.quantity].unit) for ch in self.case.channels
                              if ch.quantity in QUANTITIES},
            "seconds": self.timings,
        }


def _lp(x: NDArray[np.float64], fs: float, cutoff: float | None) -> NDArray[np.float64]:
    return x if cutoff is None else lowpass(x, fs, cutoff)


def align_shift(spec: FieldSpec, case: CaseSpec, record: MeasuredRecord, t_sim: NDArray[np.float64],
                sim: dict[str, NDArray[np.float64]]) -> float:
    """Shift s = t_sim − t_meas [s] from the trigger or by cross-correlation (see module docstring)."""
    t_entry = spec.approach / (case.speed or spec.speed)
    if case.align == "trigger":
        return t_entry - float(case.trigger_time)
    ref = next((c for c in case.channels if c.quantity == "displacement"),
               next((c for c in case.channels if c.quantity == "strain"), case.channels[0]))
    max_shift = float(record.time[-1] - record.time[0] + t_sim[-1])
    s = xcorr_shift(t_sim, sim[ref.name], record.time, record.channels[ref.name], max_shift)
    log.info("case %s: cross-correlation on %s gives a shift of %.4f s", case.name, ref.name, s)
    return s


def check_field(spec: FieldSpec, tires: list[str], limits: Limits | None = None) -> None:
    """Every check a field comparison makes before it simulates: the bridge's size, and per case and
    tire model the checks of a scenario's run (``check_steps``: at
    least ten steps, the step rule and stability, the memory and step budgets)."""
    bridge = base_bridge(spec)
    check_bridge(bridge, limits)
    for case in spec.cases:  # every record against its case first (cheap), before any simulation
        check_case_record(case, read_response_csv(case.responses), spec.path, spec.lowpass_hz)
    for case in spec.cases:
        profiles: Profiles | None = None
        for name in tires:
            try:
                tire = field_tire(name)
                profiles = _checked_profiles(spec, case) if profiles is None else profiles
                check_steps(case_crossing(spec, case, tire, bridge, spec.dt, profiles), limits)
            except FieldFileError:
                raise
            except (ValueError, RuntimeError, ArithmeticError, np.linalg.LinAlgError) as err:
                raise FieldFileError(f"{spec.path}: case {case.name!r}, {name} tire: {err}") from None


def compare_case(spec: FieldSpec, case: CaseSpec, tires: list[str], stiffness_factor: float | None = None,
                 damping_ratio: float | None = None, limits: Limits | None = None) -> CaseComparison:
    """Run the whole pipeline of the module docstring for one loading case (each run within ``limits``, the
    memory and step budgets; None: the defaults)."""
    t0 = _time.perf_counter()
    record = read_response_csv(case.responses)
    check_case_record(case, record, spec.path, spec.lowpass_hz)
    bridge = ScaledBridge(base_bridge(spec), spec.stiffness_factor if stiffness_factor is None else stiffness_factor,
                          damping_ratio)
    where = f"{spec.path} case {case.name!r}"
    sims: dict[str, dict[str, NDArray[np.float64]]] = {}
    t_sim = np.zeros(0)
    dt = spec.dt
    profiles: Profiles | None = None
    for name in tires:
        tire = field_tire(name)
        profiles = _checked_profiles(spec, case) if profiles is None else profiles
        res = simulate(case_crossing(spec, case, tire, bridge, dt, profiles), limits=limits)
        dt = res.dt  # every tire model on the same time step …
        t_sim = res.time if t_sim.size == 0 or res.time.size < t_sim.size else t_sim
        sims[name] = simulated_channels(res, case, where)
    sims = {k: {c: v[: t_sim.size] for c, v in s.items()} for k, s in sims.items()}  # … and the shortest duration
    t_run = _time.perf_counter() - t0
    fs_sim = 1.0 / dt
    shift = align_shift(spec, case, record, t_sim, sims[tires[0]])
    t_entry = spec.approach / (case.speed or spec.speed)
    t_meas = record.time + shift
    fs = record.sampling_rate
    cut = spec.lowpass_hz
    if fs > 0.8 * fs_sim and (cut is None or cut > 0.4 * fs_sim):
        cut = 0.4 * fs_sim  # anti-aliasing before the record is resampled onto the coarser simulation base
        log.warning("case %s: record sampled at %.4g Hz, faster than the simulation (%.4g Hz): low-pass at %.4g Hz",
                    case.name, fs, fs_sim, cut)
    meas = {k: _lp(v, fs, cut) for k, v in record.channels.items()}
    sims = {tn: {k: _lp(v, fs_sim, cut) for k, v in s.items()} for tn, s in sims.items()}
    drift: dict[str, DriftFit] = {}
    for ch in case.channels:
        if ch.quantity != "acceleration" or spec.drift == "none":
            continue
        if spec.drift == "quiet":
            quiet = (t_meas < t_entry) | (t_meas > t_meas[-1] - spec.quiet_tail)
            fit = quiet_drift(t_meas, meas[ch.name], quiet, t_entry)
        else:
            fit = model_drift(t_meas, meas[ch.name], resample(t_sim, sims[tires[0]][ch.name], t_meas), t_entry)
        meas[ch.name] = meas[ch.name] - (fit.offset + fit.drift * (t_meas - t_entry))
        drift[ch.name] = fit
        log.info("case %s: %s offset %.4g, drift %.4g /s (%s)", case.name, ch.name, fit.offset, fit.drift, fit.method)
    inside = (t_sim >= t_meas[0]) & (t_sim <= t_meas[-1])
    if inside.sum() < 16:
        raise FieldFileError(f"case {case.name!r}: the aligned record (t = {t_meas[0]:.3f} … {t_meas[-1]:.3f} s on the "
                         f"simulation clock) hardly overlaps the simulation (0 … {t_sim[-1]:.3f} s); check trigger_time")
    t = t_sim[inside]
    measured = {ch.name: resample(t_meas, meas[ch.name], t) for ch in case.channels}
    simulated = {tn: {ch.name: s[ch.name][inside] for ch in case.channels} for tn, s in sims.items()}
    metrics = {tn: {ch.name: {"quantity": ch.quantity, "girder": ch.girder, "x": ch.x,
                              **channel_metrics(measured[ch.name], simulated[tn][ch.name], fs_sim, spec.bands)}
                    for ch in case.channels} for tn in tires}
    return CaseComparison(case, t, shift, t_entry, measured, simulated, metrics, drift, cut, record, dt,
                          {"simulation_s": t_run, "total_s": _time.perf_counter() - t0})


@dataclass(frozen=True)
class Calibration:
    """Fitted stiffness factor and damping ratio with 1-σ uncertainties from s² (JᵀJ)⁻¹."""

    stiffness_factor: float
    stiffness_factor_std: float
    damping_ratio: float
    damping_ratio_std: float
    correlation: float
    residual_rms: float
    n_residuals: int
    evaluations: int
    tire: str
    seconds: float

    def as_dict(self) -> dict[str, Any]:
        return dict(self.__dict__)


def calibrate(spec: FieldSpec, comparisons: list[CaseComparison], tire: str = "multipoint",
              x0: tuple[float, float] | None = None, max_nfev: int = 30, limits: Limits | None = None) -> Calibration:
    """Least-squares fit of (stiffness factor, damping ratio) to the aligned, cleaned records.

    Uses the time shift, drift fits and low-pass of each [`CaseComparison`][vbikit.field.CaseComparison] (made with the
    starting model) and the same simulation time step.  Each residual evaluation simulates every
    case once (within ``limits``, the memory and step budgets; None: the defaults).  See the module docstring
    for the residual weighting and the covariance.
    """
    t0 = _time.perf_counter()
    base = base_bridge(spec)
    prepared = []
    for cmp in comparisons:
        case = cmp.case
        t_meas = cmp.record.time + cmp.shift
        fs = cmp.record.sampling_rate
        chans = {}
        for ch in case.channels:
            m = _lp(cmp.record.channels[ch.name], fs, cmp.lowpass_hz)
            if ch.name in cmp.drift:
                d = cmp.drift[ch.name]
                m = m - (d.offset + d.drift * (t_meas - d.t_ref))
            chans[ch.name] = m
        prepared.append((cmp, t_meas, chans, case_profiles(case)))  # the profiles read once, not per evaluation
    x_start = np.array(x0 if x0 is not None else (spec.stiffness_factor, spec.damping_ratio), float)
    nfev = [0]

    def residuals(p: NDArray[np.float64]) -> NDArray[np.float64]:
        nfev[0] += 1
        bridge = ScaledBridge(base, float(p[0]), float(p[1]))
        out = []
        for cmp, t_meas, chans, profiles in prepared:
            res = simulate(case_crossing(spec, cmp.case, field_tire(tire), bridge, cmp.dt, profiles), limits=limits)
            sim = simulated_channels(res, cmp.case, str(spec.path))
            ok = (t_meas >= res.time[0]) & (t_meas <= res.time[-1])
            for ch in cmp.case.channels:
                s = _lp(sim[ch.name], 1.0 / res.dt, cmp.lowpass_hz)
                s_at = CubicSpline(res.time, s)(t_meas[ok])
                m = chans[ch.name][ok]
                out.append((s_at - m) / np.sqrt(np.mean(m**2)))
        r = np.concatenate(out)
        log.info("calibration: f = %.5f, zeta = %.5f, rms residual %.4g", p[0], p[1], np.sqrt(np.mean(r**2)))
        return r

    sol = least_squares(residuals, x_start, bounds=([0.2, 0.0], [5.0, 0.3]), diff_step=1e-4, x_scale=[1.0, 0.01],
                        max_nfev=max_nfev)
    m, n = sol.fun.size, sol.x.size
    s2 = 2.0 * sol.cost / (m - n)
    cov = s2 * np.linalg.pinv(sol.jac.T @ sol.jac)
    # low-passed residuals are correlated: band-limited white noise of bandwidth f_c sampled at f_s has
    # about 2 f_c / f_s independent values per sample, so the covariance grows by f_s / (2 f_c)
    inflation = max((max(1.0, c.record.sampling_rate / (2.0 * c.lowpass_hz)) if c.lowpass_hz else 1.0)
                    for c in comparisons)
    cov *= inflation
    std = np.sqrt(np.diag(cov))
    corr = float(cov[0, 1] / (std[0] * std[1])) if std.all() else float("nan")
    return Calibration(float(sol.x[0]), float(std[0]), float(sol.x[1]), float(std[1]), corr,
                       float(np.sqrt(np.mean(sol.fun**2))), int(m), nfev[0], tire, _time.perf_counter() - t0)
