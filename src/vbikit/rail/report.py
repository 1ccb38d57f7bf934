"""The outcome of a railway sweep in words and numbers: the pass/fail checks (``check``), the text
report (``format_report``) and the JSON summary (``summary``) of a ``rail.nc`` dataset."""
from __future__ import annotations

import math
from typing import Any, Optional

import numpy as np

from vbikit.analysis.checks import Flag, add_flags, flag_line, has_flag, unconverged_dataset_flags
from vbikit.outputs import report_unit
from vbikit.rail.refine import PEAK_TOLERANCE, refinement_verdict

#: flag codes that make a sweep not the EN 1991-2 check as run (the report's result line says so)
STANDARD_CODES = ("hslm_range", "hslm_incomplete", "too_few_modes")
#: the checks whose governing peak is refined over speed and states its grid error, with their names in the report
GRID_CHECKS = {"acceleration": "deck acceleration", "moment": "midspan moment", "shear": "shear at the supports",
               "deflection": "midspan deflection"}


def kmh(speed: float) -> str:
    """A speed [m/s] in km/h as every railway text writes it (report, flag messages): to 0.1 km/h,
    without the unit ("250.6"; the refinement's finest steps are below that, and the speed's
    figure beyond it is not a design quantity)."""
    return f"{3.6 * float(speed):.1f}"


def speed_words(speed: float) -> str:
    """A speed [m/s] with its unit, ``kmh``'s number: "250.6 km/h"."""
    return f"{kmh(speed)} km/h"


def _effect_words(value: float, si_unit: str) -> str:
    """A moment or shear [SI] in the report's unit (``vbikit.outputs.report_unit``): "5561 kN m"."""
    unit, k = report_unit(si_unit)
    return f"{value * k:.4g} {unit}"


def check(ds) -> dict[str, Any]:
    """The pass/fail summary: governing train, speed and quantity of every check (the acceleration
    with its speed grid's error, ``vbikit.rail.refine.grid_error``), and ``flags`` (records,
    ``vbikit.analysis.checks.Flag``) with their messages under ``warnings`` (``add_flags``): an HSLM
    train outside its range of application (``codes.hslm_range_flags``), fewer modes than required,
    and a governing acceleration peak whose refinement did not converge (``speed_grid_flags``); a
    PASS with an ``hslm_range`` or ``too_few_modes`` flag is not the standard's check."""
    from vbikit.rail.codes import hslm_range_flags

    acc = ds["max_deck_acceleration"]
    i, j = np.unravel_index(int(np.nanargmax(acc.values)), acc.shape)
    limit = float(ds["acceleration_limit"])
    peak = grid_peak = float(acc.values[i, j])
    speed = float(ds.speed.values[j])
    train = str(ds.train.values[i])
    refined = ds["peak_acceleration_refined"].values
    bound = ds["peak_refinement_bound"].values
    change = ds["peak_last_change"].values if "peak_last_change" in ds else np.full(bound.shape, np.nan)
    halvings = ds["peak_halvings"].values if "peak_halvings" in ds else np.full(bound.shape, np.nan)
    governing_bound = governing_change = governing_halvings = math.nan
    if refined.size and np.any(np.isfinite(refined)):
        a, b = np.unravel_index(int(np.nanargmax(refined)), refined.shape)
        if refined[a, b] >= peak:
            peak, speed, train = float(refined[a, b]), float(ds["peak_speed_refined"].values[a, b]), str(ds.train.values[a])
            governing_bound, governing_change = float(bound[a, b]), float(change[a, b])
            h = float(halvings[a, b])
            governing_halvings = int(h) if math.isfinite(h) else math.nan
    finite = bound[np.isfinite(bound)]
    tolerance = float(ds.attrs.get("peak_tolerance", PEAK_TOLERANCE))
    out: dict[str, Any] = {"acceleration": {
        "peak": peak, "limit": limit, "train": train, "speed": speed,
        "passes": bool(peak <= limit), "ratio": peak / limit, "grid_peak": grid_peak,
        "grid_error": (peak - grid_peak) / peak if peak > 0 else 0.0, "refinement_change": governing_change,
        "refinement_bound": governing_bound, "refinement_halvings": governing_halvings,
        "largest_refinement_bound": float(finite.max()) if finite.size else math.nan,
        # the governing peak at the sweep's highest speed: the response may still rise beyond it
        "at_top_speed": bool(speed >= float(ds.speed.values.max()) * (1 - 1e-12)),
        # … or at its lowest: the response may still rise below it (a resonance just under the sweep)
        "at_bottom_speed": bool(speed <= float(ds.speed.values.min()) * (1 + 1e-12)),
        **refinement_verdict(change, bound, tolerance)}}
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
    out["deflection"] = {"phi_dyn": float(phid[a, b]), "train": str(ds.train.values[a]), "speed": float(ds.speed.values[b]),
                         "grid_phi_dyn": float(phid[a, b]), "grid_error": math.nan, "refinement_change": math.nan,
                         "refinement_bound": math.nan}  # refined by ``refine_design_checks``
    a = ds.attrs
    if "moment_max_Nm" in a:
        out["moment_envelope"] = {k: a[k] for k in ("moment_max_Nm", "moment_max_position_m", "moment_max_train",
                                                   "moment_max_speed_m_s", "moment_max_over_midspan", "static_moment_max_Nm",
                                                   "static_moment_max_position_m", "static_moment_max_train",
                                                   "static_moment_max_over_midspan")}
    for kind in GRID_CHECKS:  # the governing peaks' own: ``vbikit.rail.run.time_sampling_checks``
        out[kind].update({"time_sampling_change": math.nan, "time_sampling_bound": math.nan} | sampling_extremes(ds, kind))
    out["passes"] = out["acceleration"]["passes"]
    names = [str(n) for n in ds.train.values if not str(n).endswith(" (coupled)")]
    add_flags(out, hslm_range_flags(float(a["span_m"]), names) + modes_flags(ds)
              + speed_grid_flags(out, ("acceleration",), tolerance) + unconverged_flags(ds))
    return out


def unconverged_flags(ds) -> list[Flag]:
    """The ``contact_not_converged`` flag of a sweep whose coupled cars had steps whose contact forces
    did not converge (the dataset's ``unconverged_steps``, per train and speed; absent in sweeps
    written before it)."""
    if "unconverged_steps" not in ds:
        return []
    counts = ds["unconverged_steps"]
    describe = (lambda i: f"{ds.train.values[i[0]]} at {speed_words(float(ds.speed.values[i[1]]))}")
    return unconverged_dataset_flags(counts.values, "run", describe)


def modes_flags(ds) -> list[Flag]:
    """The ``too_few_modes`` flag of a sweep that retained fewer modes than EN 1990 A2.4.4.2.1 requires
    (every mode up to max(30 Hz, 1.5 n0, n3); the dataset's ``modes_required``)."""
    a = ds.attrs
    required, kept = int(a.get("modes_required", 0)), int(a["n_modes"])
    if required <= kept:
        return []
    return [Flag("too_few_modes", f"{kept} modes retained, but the {required} modes up to {a['frequency_limit_hz']:.1f} Hz "
                 "are required (EN 1990 A2.4.4.2.1): raise bridge.n_modes", value=float(kept), threshold=float(required))]


def speed_grid_flags(checks: dict[str, Any], kinds: tuple[str, ...], tolerance: float = PEAK_TOLERANCE) -> list[Flag]:
    """A ``speed_grid_error`` flag for every check of ``kinds`` whose governing peak was refined
    (``vbikit.rail.refine.grid_error``) but still changes with the speed step: its change over the
    last halving or the bound of its remaining error not below ``tolerance`` (relative; the
    refinement's own stopping rule, so a flagged peak is one that stopped after ``MAX_HALVINGS``)."""
    out = []
    for kind in kinds:
        c = checks.get(kind, {})
        change, bound = c.get("refinement_change", math.nan), c.get("refinement_bound", math.nan)
        if not (math.isfinite(change) and math.isfinite(bound)) or max(change, bound) < tolerance:
            continue
        out.append(Flag("speed_grid_error", f"the governing {GRID_CHECKS[kind]} peak ({c['train']} at "
                        f"{speed_words(c['speed'])}) is not converged over speed: after its refinement it still changed "
                        f"by {100 * change:.2f} % over the last halving of the speed step, error bound {100 * bound:.2f} % "
                        f"(tolerance {100 * tolerance:g} %); the stated value may be low: use a finer speeds.step or "
                        "fine_step around it", output=kind, subject=str(c["train"]), value=max(change, bound),
                        threshold=tolerance))
    return out


#: a governing peak whose time sampling changed it, or whose remaining time-sampling error may reach, this much
#: (relative) is flagged ``time_sampling_error``
TIME_SAMPLING_TOLERANCE = PEAK_TOLERANCE
#: each check's peak output in the dataset (``vbikit.rail.run.time_sampling_variables``: its ``*_sampling_*``) and
#: the peaks they qualify, for the largest over the sweep
_SAMPLING_OUTPUTS = {"acceleration": ("deck_acceleration", "deck_acceleration_at_points"), "moment": ("moment", "max_moment"),
                     "shear": ("shear", "max_shear"), "deflection": ("deflection", "max_deflection")}


def sampling_extremes(ds, kind: str) -> dict[str, float]:
    """The largest time-sampling change and bound over every train, speed (and point) of check
    ``kind``'s peak output, each as a share of the sweep's largest peak of that output (change × peak /
    largest peak: what it could move the check's value; a small peak's own relative bound can be
    larger): ``largest_time_sampling_change``, ``largest_time_sampling_bound``; NaN where none is
    estimated (coupled cars, a dataset written before them)."""
    name, peaks = _SAMPLING_OUTPUTS[kind]
    out: dict[str, Any] = {}
    for what in ("change", "bound"):
        key = f"{name}_sampling_{what}"
        value, where = math.nan, None
        if key in ds:
            peak = np.asarray(ds[peaks].values, float)
            moved = np.asarray(ds[key].values, float) * peak
            top = float(np.nanmax(peak)) if np.any(np.isfinite(peak)) else 0.0
            if np.any(np.isfinite(moved)) and top > 0:
                at = np.unravel_index(int(np.nanargmax(moved)), moved.shape)
                value = float(moved[at]) / top
                where = {"train": str(ds.train.values[at[0]]), "speed_m_s": float(ds.speed.values[at[1]])}
        out[f"largest_time_sampling_{what}"] = value
        if what == "bound":
            out["largest_time_sampling_bound_at"] = where  # the train and speed of that peak
    return out


def time_sampling_flags(checks: dict[str, Any], kinds: tuple[str, ...] = tuple(GRID_CHECKS),
                        tolerance: float = TIME_SAMPLING_TOLERANCE) -> list[Flag]:
    """A ``time_sampling_error`` flag for every check of ``kinds`` whose peaks depend on the time step:
    its governing peak's largest value read at a time sample or at an axle's passage (the one-sided
    limits there) more than ``tolerance`` (relative) below the peak taken between the samples
    (``time_sampling_change``: what a vertex added) or the estimated bound of that peak's remaining
    error (``time_sampling_bound``) at or above it, or else a peak of the sweep whose bound reaches
    ``tolerance`` of the largest peak (``largest_time_sampling_bound``, ``sampling_extremes``: it may lie
    that much higher and govern)."""
    out = []
    for kind in kinds:
        c = checks.get(kind, {})
        change, bound = c.get("time_sampling_change", math.nan), c.get("time_sampling_bound", math.nan)
        if math.isfinite(change) and math.isfinite(bound) and max(change, bound) >= tolerance:
            out.append(Flag("time_sampling_error", f"the governing {GRID_CHECKS[kind]} peak ({c['train']} at "
                            f"{speed_words(c['speed'])}) depends on the time step: {sampling_words(change, bound)} "
                            f"(tolerance {100 * tolerance:g} %); the stated value may be off by that much: raise "
                            "run.steps_per_period", output=kind, subject=str(c["train"]),
                            value=max(change, bound), threshold=tolerance))
            continue
        worst, at = c.get("largest_time_sampling_bound", math.nan), c.get("largest_time_sampling_bound_at")
        if math.isfinite(worst) and worst >= tolerance and at is not None:
            out.append(Flag("time_sampling_error", f"a {GRID_CHECKS[kind]} peak of the sweep ({at['train']} at "
                            f"{speed_words(at['speed_m_s'])}) depends on the time step: the peak between its samples may "
                            f"lie up to {100 * worst:.2f} % of the largest {GRID_CHECKS[kind]} peak off its stated value "
                            f"(tolerance {100 * tolerance:g} %), so the check may be low by that much: raise "
                            "run.steps_per_period", output=kind, subject=at["train"], value=worst,
                            threshold=tolerance))
    return out


def sampling_words(change: float, bound: float, digits: int = 2) -> str:
    """A peak's time sampling in words: "its largest time sample is 0.12 % below the peak taken between
    the samples, which may be off by up to 0.01 %", or, where no vertex moved it (``change`` 0: a sample,
    or the one-sided limit where an axle enters, leaves or passes the section), "it is read at a time
    sample or at an axle's passage (the limit beside the jump or kink), off by up to 0.53 %"."""
    if change == 0.0:
        return (f"it is read at a time sample or at an axle's passage (the limit beside the jump or kink), off by up "
                f"to {100 * bound:.{digits}f} %")
    return (f"its largest time sample is {100 * change:.{digits}f} % below the peak taken between the samples, "
            f"which may be off by up to {100 * bound:.{digits}f} %")


def _time_sampling_line(checks: dict[str, Any], dx: float, tolerance: float) -> str:
    """The report's one statement of the time sampling's error: for every check's governing peak how
    far its largest time sample lies below the peak taken between the samples and the bound of the
    remaining error (or, where it is read at a sample or at an axle's passage, that bound alone), and over the sweep the largest of each as a share of the largest peak (``sampling_extremes``;
    ``!`` where ``time_sampling_error`` flags it)."""
    parts = []
    for kind, name in GRID_CHECKS.items():
        c = checks.get(kind, {})
        change, bound = c.get("time_sampling_change", math.nan), c.get("time_sampling_bound", math.nan)
        if not (math.isfinite(change) and math.isfinite(bound)):
            parts.append(f"{name} not estimated (coupled cars govern it: sampled peaks)")
            continue
        mark = " !" if has_flag(checks, "time_sampling_error", output=kind) else ""
        own = (f"read at a sample or an axle's passage, off by up to {100 * bound:.3f} %" if change == 0.0 else
               f"largest sample {100 * change:.3f} % low, remaining error up to {100 * bound:.3f} %")
        worst = ""
        if math.isfinite(c.get("largest_time_sampling_bound", math.nan)):
            worst = (f"; over the sweep up to {100 * c['largest_time_sampling_change']:.3f} % and "
                     f"{100 * c['largest_time_sampling_bound']:.3f} % of the largest peak")
        parts.append(f"{name} {own}{worst}{mark}")
    return (f"time sampling error of the governing peaks (each taken between the samples, every {1e3 * dx:.1f} mm of "
            f"travel, as the vertex of a parabola through the largest samples, the one-sided limits read where an axle "
            f"enters, leaves or passes the section; flagged at {100 * tolerance:g} %): " + "; ".join(parts)
            + "; not in these bounds: the loads' linear hold over each step (docs/railway.md, Verification: 1e-5 … 2e-4 "
            "of a peak in its cases)")


def damping_extra(attrs) -> str:
    """The report's words on the additional damping Δζ (EN 1991-2 Eq. 6.13) in the damping shown."""
    dz = float(attrs.get("additional_damping_ratio", 0.0))
    if dz > 0:
        return f", with additional damping Δζ = {100 * dz:.3f} % (EN 1991-2:2003 Eq. 6.13)"
    if str(attrs.get("damping_source", "")).startswith("EN") and float(attrs.get("span_m", 0.0)) >= 30.0:
        return ", no additional damping: EN 1991-2:2003 Eq. 6.13 adds Δζ below 30 m only"
    return ""


def format_report(ds, checks: dict[str, Any]) -> str:
    """The text report of a sweep."""
    a = ds.attrs
    acc = checks["acceleration"]
    lines = [
        "vbikit railway dynamic check (EN 1991-2:2003 + AC 6.4.6, EN 1990:2002/A1:2005 A2.4.4.2.1)",
        f"bridge: simply supported span {a['span_m']:g} m, n0 = {a['first_frequency_hz']:.3f} Hz, {a['n_modes']} modes "
        f"(up to {float(ds['frequency'].values[-1]):.1f} Hz; required max(30 Hz, 1.5 n0, n3) = {a['frequency_limit_hz']:.1f} Hz), "
        f"damping {100 * a['damping_ratio']:.3f} % ({a['damping_source']}, {a['deck']}{damping_extra(a)})",
        f"trains: {', '.join(map(str, ds.train.values))}; {ds.speed.size} speeds {kmh(ds.speed.values.min())} … "
        f"{speed_words(ds.speed.values.max())}",
    ]
    lines += [flag_line(w) for w in checks.get("warnings", [])]
    lines += [
        "",
        f"deck acceleration: peak {acc['peak']:.3f} m/s² ({acc['train']} at {speed_words(acc['speed'])}) against "
        f"{acc['limit']:g} m/s² ({a['track']} track): {'PASS' if acc['passes'] else 'FAIL'} ({100 * acc['ratio']:.0f} % of the limit)"
        + ("; the peak is at the sweep's highest speed, where the response is still rising: it would be higher "
           "just above the sweep (resonance speeds listed below)" if acc.get("at_top_speed") else "")
        + ("; the peak is at the sweep's lowest speed, where the response is still rising towards lower speeds: it "
           "would be higher just below the sweep (resonance speeds listed below)" if acc.get("at_bottom_speed") else ""),
    ]
    pts = acc.get("points")
    if pts:
        lines.append(f"  read at x = {pts['x_dense']:.2f} m of {pts['n_dense']} deck points at that train and speed; the "
                     f"sweep's {pts['n_read']} points read {pts['read']:.3f} m/s² there (x = {pts['x_read']:.2f} m, "
                     f"{100 * pts['error']:.2f} % lower)")
    for kind in ("moment", "shear"):
        c = checks[kind]
        si, where = ("N m", "midspan") if kind == "moment" else ("N", "supports")
        lines.append(f"{kind} at the {where}: (1 + phi'dyn + phi''/2) x train = {_effect_words(c['dynamic_design'], si)} "
                     f"({c['train']} at {speed_words(c['speed'])}, phi'dyn = {c['phi_dyn']:.3f}, phi'' = "
                     f"{c['phi_irregularity']:.3f}) vs Phi x alpha x LM71 = {_effect_words(c['lm71_design'], si)} (Phi = "
                     f"{a['dynamic_factor_Phi']:.3f}, alpha = {a['classification_factor']:g}): {c['governs']} governs")
    if "moment_envelope" in checks:
        e = checks["moment_envelope"]
        # the dynamic peak (1 + phi'dyn) x train of every section, compared with the same at midspan (not with
        # the midspan line's design value, which adds phi''/2)
        mid, mid_static = float(np.nanmax(ds["max_moment"].values)), float(np.nanmax(ds["static_moment"].values))
        lines.append(f"moment along the span: largest {_effect_words(e['moment_max_Nm'], 'N m')} at x = "
                     f"{e['moment_max_position_m']:.3f} m ({e['moment_max_train']} at {speed_words(e['moment_max_speed_m_s'])}), "
                     f"{100 * (e['moment_max_over_midspan'] - 1):+.2f} % against the largest at midspan "
                     f"{_effect_words(mid, 'N m')} (dynamic peaks (1 + phi'dyn) x train, without phi''/2); static "
                     f"{_effect_words(e['static_moment_max_Nm'], 'N m')} at x = {e['static_moment_max_position_m']:.3f} m "
                     f"({e['static_moment_max_train']}), {100 * (e['static_moment_max_over_midspan'] - 1):+.2f} % against "
                     f"midspan {_effect_words(mid_static, 'N m')}")
    d = checks["deflection"]
    lines.append(f"deflection: largest phi'dyn {d['phi_dyn']:.3f} ({d['train']} at {speed_words(d['speed'])})")
    lines.append(_grid_error_line(checks, float(acc.get("tolerance", PEAK_TOLERANCE))))
    if "time_sampling_change" in acc:
        lines.append(_time_sampling_line(checks, float(a["dx_m"]),
                                         float(a.get("time_sampling_tolerance", TIME_SAMPLING_TOLERANCE))))
    lines += ["", "resonance speeds v_i = n0 D / i [km/h] (i the order; D the coach length, HSLM-B's force spacing d or "
              "the dominant repeated axle spacing):"]
    lo, hi = float(ds.speed.values.min()), float(ds.speed.values.max())
    for k, (name, row) in enumerate(zip(ds.train.values, ds["resonance_speed"].values)):
        if not np.any(np.isfinite(row)):
            lines.append(f"  {name}: none (no repeated axle spacing)")
            continue
        d = float(ds["excitation_wavelength"].values[k])
        parts = [f"i = {i + 1}: {kmh(v)}" + ("" if lo * (1 - 1e-12) <= v <= hi * (1 + 1e-12) else
                                                  " (above the sweep)" if v > hi else " (below the sweep)")
                 for i, v in enumerate(row) if np.isfinite(v)]
        lines.append(f"  {name} (D = {d:.3f} m, {ds['wavelength_source'].values[k]}): " + ", ".join(parts))
    for k, name in enumerate(ds.train.values):  # the bogies' axle spacings d: v = n0 d / i, those in the sweep
        inside = [(d, i, v) for d, i, v in bogie_resonance_list(ds, k) if lo * (1 - 1e-12) <= v <= hi * (1 + 1e-12)]
        if inside:
            lines.append(f"  {name}, axle spacing within a bogie (v = n0 d / i, in the sweep): " + "; ".join(
                f"d = {d:g} m: " + ", ".join(f"i = {i}: {kmh(v)}" for dd, i, v in inside if dd == d)
                for d in sorted({d for d, _, _ in inside})))
    near = governing_resonance(ds, acc["train"], acc["speed"])
    if near:
        lines.append(f"governing peak ({acc['train']}, {speed_words(acc['speed'])}) nearest the resonance "
                     f"{near['resonance']} at {speed_words(near['speed_m_s'])} ({100 * near['offset']:+.1f} %)")
    lines += ["", f"result: {'PASS' if checks['passes'] else 'FAIL'} (governing: {acc['train']}, "
              f"{speed_words(acc['speed'])}, deck acceleration)"
              + (f"; {len(checks['warnings'])} WARNING(s) above" if checks.get("warnings") else "")
              + (": not the EN 1991-2 check as run" if any(has_flag(checks, c) for c in STANDARD_CODES) else "")]
    return "\n".join(lines) + "\n"


def bogie_resonance_list(ds, k: int) -> list[tuple[float, int, float]]:
    """(d [m], i, v [m/s]) of train ``k``'s resonances n0 d / i of its axle spacings within a bogie
    (``bogie_resonance_speed``; none for a dataset without them)."""
    if "bogie_resonance_speed" not in ds:
        return []
    d = ds["bogie_axle_spacing"].values[k]
    v = ds["bogie_resonance_speed"].values[k]
    return [(float(d[j]), i + 1, float(v[j, i])) for j in range(d.size) if np.isfinite(d[j]) for i in range(v.shape[1])]


#: a governing peak farther than this (relative) from every resonance of the first mode is compared with
#: the higher modes' resonances too (``higher_mode_resonances``): a long span's peak can be a higher mode's
NEAR_RESONANCE = 0.05

#: the highest order i of n0 D / i the governing peak is compared with (orders down to 0.9 × the sweep's
#: lowest speed, at most this many: a short span's coach-length resonances in the sweep are high orders)
MAX_RESONANCE_ORDER = 60


def governing_resonance(ds, train: str, speed: float) -> Optional[dict[str, Any]]:
    """The resonance of ``train`` (coach length / wavelength D by order i = 1 … down to 0.9 × the sweep's
    lowest speed, at most ``MAX_RESONANCE_ORDER``, and the axle spacings within a bogie) nearest to
    ``speed`` [m/s] (the governing peak's): its label, speed and relative offset of the peak from it;
    None when the train has none."""
    from vbikit.rail.sweep import nearest_resonance

    names = [str(n) for n in ds.train.values]
    if train not in names:
        return None
    k = names.index(train)
    d = float(ds["excitation_wavelength"].values[k])
    v1 = float(ds["resonance_speed"].values[k][0])  # n0 D: the orders i are v1 / i, the stored ones and higher
    lo = float(ds.speed.values.min())
    orders = max(len(ds["resonance_speed"].values[k]), int(v1 / (0.9 * lo)) if math.isfinite(v1) and lo > 0 else 0)
    cands = [(f"n0 D / {i} (D = {d:.3f} m, {ds['wavelength_source'].values[k]})", v1 / i)
             for i in range(1, min(orders, MAX_RESONANCE_ORDER) + 1)] if math.isfinite(v1) else []
    bogies = [(f"n0 d / {i} (axle spacing within a bogie d = {dd:g} m)", v) for dd, i, v in bogie_resonance_list(ds, k)]
    # a coach order at a bogie resonance's speed (D a multiple of d: HSLM-A4's D / 7 = d) is that bogie resonance
    cands = [c for c in cands if not any(abs(c[1] / b[1] - 1.0) < 1e-6 for b in bogies)] + bogies
    near = nearest_resonance(float(speed), cands)
    if near is None:
        return None
    if abs(float(speed) / near[1] - 1.0) > NEAR_RESONANCE:  # not the first mode's: a higher mode's, when nearer
        higher = nearest_resonance(float(speed), higher_mode_resonances(ds, k))
        if higher is not None and abs(float(speed) / higher[1] - 1.0) < abs(float(speed) / near[1] - 1.0):
            near = higher
    return {"resonance": near[0], "speed_m_s": near[1], "speed_kmh": 3.6 * near[1], "offset": float(speed) / near[1] - 1.0}


def higher_mode_resonances(ds, k: int) -> list[tuple[str, float]]:
    """(label, v [m/s]) of train ``k``'s resonances of the second and higher retained modes, n_j D / i
    and n_j d / i for the orders i stored (``resonance_speed``; the same rule as the first mode's,
    EN 1991-2 6.4.6, with that mode's frequency n_j from ``frequency``); empty without them."""
    if "frequency" not in ds:
        return []
    freqs = [float(f) for f in np.atleast_1d(ds["frequency"].values)]
    d = float(ds["excitation_wavelength"].values[k])
    orders = len(ds["resonance_speed"].values[k])
    spacings = sorted({dd for dd, _, _ in bogie_resonance_list(ds, k)})
    out = []
    for j, f in enumerate(freqs[1:], start=2):
        if math.isfinite(d):
            out += [(f"n{j} D / {i} (mode {j}, {f:.3f} Hz; D = {d:.3f} m, {ds['wavelength_source'].values[k]})",
                     f * d / i) for i in range(1, orders + 1)]
        out += [(f"n{j} d / {i} (mode {j}, {f:.3f} Hz; axle spacing within a bogie d = {dd:g} m)", f * dd / i)
                for dd in spacings for i in range(1, orders + 1)]
    return out


#: each check's governed quantity as its grid value is written: (key of the grid value, SI unit; None: a factor)
_GRID_VALUES = {"acceleration": ("grid_peak", "m/s²"), "moment": ("grid_design", "N m"), "shear": ("grid_design", "N"),
                "deflection": ("grid_phi_dyn", None)}


def _grid_value(kind: str, c: dict[str, Any]) -> str:
    """What the sweep's grid alone gave for check ``kind``: "3.308 m/s²", "5537 kN m", "phi'dyn 1.206"
    ("" when the check does not have it)."""
    key, unit = _GRID_VALUES[kind]
    value = c.get(key, math.nan)
    if value is None or not math.isfinite(value):
        return ""
    if unit is None:
        return f"phi'dyn {value:.3f}"
    return f"{value:.3f} {unit}" if unit == "m/s²" else _effect_words(value, unit)


def _grid_error_line(checks: dict[str, Any], tolerance: float) -> str:
    """The report's one statement of the speed grid's error: for every check's governing peak
    (``GRID_CHECKS``) the halvings of the speed step made around it, what the sweep's grid alone gave
    and missed, the change over the last halving (only after more than one: after one it is what the
    grid missed) and the error bound, and for the acceleration the largest bound over every train's
    refined peaks; ``!`` where ``speed_grid_error`` flags it."""
    parts = []
    for kind, name in GRID_CHECKS.items():
        c = checks.get(kind, {})
        if not math.isfinite(c.get("refinement_bound", math.nan)):
            parts.append(f"{name} not refined (coupled cars govern it)")
            continue
        mark = " !" if has_flag(checks, "speed_grid_error", output=kind) else ""
        parts.append(f"{name} {_refinement_words(c, _grid_value(kind, c), _all_peaks_words(kind, c))}{mark}")
    return (f"speed grid error of the governing peaks (the speed step halved around each until the last halving "
            f"changed it by less than {100 * tolerance:g} % and its error bound was below that): " + "; ".join(parts))


def _all_peaks_words(kind: str, c: dict[str, Any]) -> str:
    """The acceleration check's bound over every train's refined peaks and its verdict ("" for the
    other checks, which refine their governing peak only)."""
    if kind != "acceleration" or not math.isfinite(c.get("largest_refinement_bound", math.nan)):
        return ""
    verdict = ("every peak within the tolerance" if c.get("refinement_converged")
               else "some peaks not within the tolerance after the most halvings")
    return f"; of all trains' refined peaks at most {100 * c['largest_refinement_bound']:.3f} %: {verdict}"


def _refinement_words(c: dict[str, Any], grid_value: str = "", beyond: str = "") -> str:
    """'after 1 halving the sweep's grid (5537 kN m) 0.12 % low (error bound 0.010 %)' (one halving:
    its change is what the grid missed, said once), 'after 3 halvings the sweep's grid 1.20 % low,
    the last halving changed it 0.040 % (error bound 0.010 %)'; a dataset without the count: the
    grid's shortfall (``grid_error``: (refined − grid) / refined), the last change and the bound.
    ``grid_value``: what the grid gave, in brackets after "grid"; ``beyond``: words after the bound,
    inside its bracket."""
    n = c.get("refinement_halvings", math.nan)
    given = f" ({grid_value})" if grid_value else ""
    grid = f"the sweep's grid{given} {100 * c['grid_error']:.2f} % low"
    bound = f"(error bound {100 * c['refinement_bound']:.3f} %{beyond})"
    last = f"the last halving changed it {100 * c['refinement_change']:.3f} %"
    if n is None or not math.isfinite(n):
        return f"{grid}, {last} {bound}"
    if int(n) == 1:
        return f"after 1 halving {grid} {bound}"
    return f"after {int(n)} halvings {grid}, {last} {bound}"


_SAMPLING_UNITS = {"time_sampling_change": "1", "time_sampling_bound": "1", "largest_time_sampling_change": "1",
                   "largest_time_sampling_bound": "1"}
#: the unit of every number of a check (``check``), written beside it in ``rail-summary.json``
CHECK_UNITS: dict[str, dict[str, str]] = {
    "acceleration": {"peak": "m s-2", "limit": "m s-2", "speed": "m s-1", "ratio": "1", "grid_peak": "m s-2",
                     "grid_error": "1", "refinement_change": "1", "refinement_bound": "1", "largest_refinement_bound": "1",
                     "tolerance": "1", "refinement_halvings": "1", **_SAMPLING_UNITS},
    "moment": {"dynamic_design": "N m", "lm71_design": "N m", "grid_design": "N m", "speed": "m s-1", "phi_dyn": "1",
               "phi_irregularity": "1", "ratio": "1", "grid_error": "1", "refinement_change": "1", "refinement_bound": "1",
               "tolerance": "1", "refinement_halvings": "1", **_SAMPLING_UNITS},
    "shear": {"dynamic_design": "N", "lm71_design": "N", "grid_design": "N", "speed": "m s-1", "phi_dyn": "1",
              "phi_irregularity": "1", "ratio": "1", "grid_error": "1", "refinement_change": "1", "refinement_bound": "1",
              "tolerance": "1", "refinement_halvings": "1", **_SAMPLING_UNITS},
    "deflection": {"phi_dyn": "1", "grid_phi_dyn": "1", "speed": "m s-1", "grid_error": "1", "refinement_change": "1",
                   "refinement_bound": "1", "tolerance": "1", "refinement_halvings": "1", **_SAMPLING_UNITS},
}


def summary(ds, checks: dict[str, Any]) -> dict[str, Any]:
    """The JSON summary (``rail-summary.json``): the checks (with the speed grid's error bound and the
    moment envelope along the span), every train's resonance speeds by order i and its refined
    acceleration peaks, ``flags`` (records) and their messages ``warnings`` (``check``); speeds in m/s and km/h, moments in N m, NaN as null; every check with the units of
    its numbers (``CHECK_UNITS``)."""
    def clean(x):
        if isinstance(x, dict):
            return {k: clean(v) for k, v in x.items()}
        if isinstance(x, (list, tuple)):
            return [clean(v) for v in x]
        if isinstance(x, (float, np.floating)):
            return float(x) if math.isfinite(float(x)) else None
        if isinstance(x, np.integer):
            return int(x)
        if isinstance(x, np.bool_):
            return bool(x)
        return x

    trains = {}
    lo, hi = float(ds.speed.values.min()), float(ds.speed.values.max())
    for k, name in enumerate(map(str, ds.train.values)):
        row = ds["resonance_speed"].values[k]
        trains[name] = {
            "wavelength_m": float(ds["excitation_wavelength"].values[k]), "wavelength_source": str(ds["wavelength_source"].values[k]),
            "resonances": [{"order": i + 1, "speed_m_s": float(v), "speed_kmh": 3.6 * float(v),
                            "in_sweep": bool(ds["resonance_in_sweep"].values[k, i])} for i, v in enumerate(row)],
            "bogie_resonances": [{"axle_spacing_m": d, "order": i, "speed_m_s": v, "speed_kmh": 3.6 * v,
                                  "in_sweep": bool(lo * (1 - 1e-12) <= v <= hi * (1 + 1e-12))}
                                 for d, i, v in bogie_resonance_list(ds, k)],
            "acceleration_peaks": [{"grid_m_s2": float(ds["peak_acceleration_grid"].values[k, j]),
                                    "refined_m_s2": float(ds["peak_acceleration_refined"].values[k, j]),
                                    "speed_kmh": 3.6 * float(ds["peak_speed_refined"].values[k, j]),
                                    "error_bound": float(ds["peak_refinement_bound"].values[k, j])}
                                   for j in range(ds.peak.size) if np.isfinite(ds["peak_acceleration_refined"].values[k, j])]}
    warnings = list(checks.get("warnings", []))  # at the top, as in every summary of vbikit
    flags = list(checks.get("flags", []))
    checks = {k: (v | {"units": {n: u for n, u in CHECK_UNITS[k].items() if n in v}} if k in CHECK_UNITS else v)
              for k, v in checks.items() if k not in ("warnings", "flags")}
    acc = checks.get("acceleration", {})
    near = governing_resonance(ds, acc["train"], acc["speed"]) if "train" in acc else None
    return clean({"vbikit_version": str(ds.attrs.get("vbikit_version", "")), "checks": checks, "warnings": warnings, "flags": flags, "trains": trains, "governing_resonance": near,
                  "peak_refinement": ds.attrs.get("peak_refinement", ""), "time_sampling": ds.attrs.get("time_sampling", ""),
                  "moment_envelope_method": ds.attrs.get("moment_envelope_method", "")})
