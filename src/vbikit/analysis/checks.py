"""Warnings about runs that may not mean what the user thinks: inputs outside the usual range of the
models and results that carry a caveat.  Each check returns plain sentences (the CLI prints them
on stderr and lists them under ``warnings`` in the JSON summary); none stops a run.

Thresholds (documented in docs/scenario.md):

* speed outside 5–150 km/h (a speed in km/h typed as ``speed`` [m/s] reads 3.6 times too fast),
  or outside the vehicle's own usual range (``Vehicle.usual_speed_kmh``: trains 5–420 km/h);
* road elevation (profile plus defects) over 0.1 m anywhere the wheels go (a profile in mm read as m);
* a response point within 2 % of the span from a support (static response near zero, IM meaningless);
* a step given by the user that is coarser than the integrator's automatic step, and bridge
  modes that the automatic step resolves (at least 5 steps a period, f·dt ≤ 0.2) but the user's
  step does not (``step_warnings``);
* wheels that lost contact (which, where first, for how long); and, when any wheel was airborne on
  the bridge for more than ``AIRBORNE_FRACTION`` (5 %) of its own time on the bridge, one warning
  that the run's impact factors are dominated by the wheels leaving and landing on the road
  (``airborne_warnings``; the text report marks the IM with ``!``).  5 % is a hop, not a graze: on
  Bridge 2 (16.76 m at 75 km/h, 0.80 s on the deck) it is 0.04 s in the air, about half the
  HS20-44's slowest axle-hop period (10.8 Hz: 0.093 s); an ISO class-F road keeps the front axle up for 0.55 s (68 %);
* a static strain peak of the modes (modal superposition of curvatures, which converges slowly
  under a moving load) more than ``STRAIN_MODE_TOLERANCE`` (1 %) away from the exact static strain
  c/EI times the static moment of the full stiffness (the moment's mode-acceleration static part),
  where the bridge offers the moment at the point (``strain_convergence_warnings``): the Yang–Yau
  beam with 10 modes reads 20.32 µε for the exact 21.18 µε (−4.0 %), with 50 modes 21.01 µε (−0.8 %);
* an impact factor whose static reference is small: a static peak below ``SMALL_STATIC_FRACTION``
  (20 %) of the largest static peak of the same quantity on the bridge (a lightly loaded girder, a
  point near a support; ``small_static`` / ``small_static_warnings``; for moments, shears and
  reactions each kind against its own largest, ``effect_static_warnings``).  IM = ΔR/R_st divides the
  dynamic increment ΔR, which the deck's vibration spreads over every girder, by that small R_st:
  on the paper's 3D Bridge 2 under HS20-44 Girder 1 carries 0.28 mm of the governing 2.79 mm
  (10 %) and reads IM = 1.35 against 0.22.  Such an IM is not a design value.

A negative impact factor (the dynamic peak below the static one) is physical, not a warning: the
reports print ``NEGATIVE_IM_NOTE`` beside it.
"""
from __future__ import annotations

from dataclasses import replace
from typing import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from vbikit.bridge.girder_deck import OBLIQUE_MESH_ADVISED_SKEW
from vbikit.solve.crossing import Crossing
from vbikit.solve.result import CrossingResult
from vbikit.solve.timestep import choose_time_step

#: usual range of vehicle speeds [km/h]
SPEED_RANGE_KMH = (5.0, 150.0)
#: largest usual road elevation [m] (profile plus defects)
MAX_ROAD_FEATURE = 0.1
#: a response point closer than this fraction of the span to a support is flagged
SUPPORT_MARGIN = 0.02
#: fewest steps per period of a bridge mode the step should give
STEPS_PER_PERIOD = 5.0
#: an impact factor whose static peak is below this fraction of the largest static peak of the same
#: quantity on the bridge (every girder and response point of the run) is flagged (module docstring)
SMALL_STATIC_FRACTION = 0.2
#: a wheel airborne on the bridge for more than this fraction of its time there flags the run's IMs (module docstring)
AIRBORNE_FRACTION = 0.05
#: how the airborne-wheels warning starts (the text report looks for it to mark the IM)
AIRBORNE_WARNING_START = "impact factors dominated by airborne wheels"
#: largest relative error of the modes' static strain peak against the exact one before it is flagged
STRAIN_MODE_TOLERANCE = 0.01
#: how the strain-convergence warning starts (the text report looks for it to mark the strain IM)
STRAIN_WARNING_START = "strain not converged in the modes"
#: what a negative impact factor means, in words (the reports print it once where one occurs)
NEGATIVE_IM_NOTE = ("an IM below 0 means the dynamic peak stayed below the static one: the vehicle's bounce and the "
                    "deck's vibration were out of phase with the load's arrival at the section (the wheels unloading "
                    "there); physical, not an error")


def input_warnings(crossing: Crossing, dt: float, response_x: float | None = None,
                   response_y: float | None = None) -> list[str]:
    """Warnings about the inputs of ``crossing`` run with step ``dt`` [s] and read at ``response_x`` [m]."""
    out: list[str] = []
    t_end = crossing.exit_time()
    if crossing.single:  # at the start and when the last axle has left
        speeds = [("crossing.speed", "speed", (crossing.speed, float(crossing.vehicles[0].velocity(t_end))),
                   crossing.vehicles[0].vehicle)]
    else:  # each vehicle at its entry and when the last one has left
        speeds = [(f"vehicles[{i + 1}].speed", f"vehicle {i + 1}'s speed", (m.speed, float(m.velocity(t_end))), m.vehicle)
                  for i, m in enumerate(crossing.vehicles)]
    for key, label, (v0, v1), vehicle in speeds:
        lo, hi = vehicle.usual_speed_kmh or SPEED_RANGE_KMH
        for what, v in ((label, v0 * 3.6), (f"{label} when the last axle leaves the bridge", v1 * 3.6)):
            if not lo <= v <= hi:
                out.append(f"{key}: {what} {v:.4g} km/h ({v / 3.6:.4g} m/s) is outside the usual "
                           f"{lo:g}–{hi:g} km/h; check the unit (speed is in m/s, speed_kmh in km/h)")
                break
    x_lo, x_hi = crossing.road_extent()
    for side, road in (("", crossing.road), (" (right wheel line)", crossing.road_right)):
        if road is None:
            continue
        lo, hi = np.searchsorted(road.x, x_lo, side="left"), np.searchsorted(road.x, x_hi, side="right")
        z = road.z[lo:hi] if hi > lo else road.z  # the stations x_lo ≤ x ≤ x_hi (x increasing)
        peak = float(np.max(np.abs(z))) if z.size else 0.0
        if peak > MAX_ROAD_FEATURE:
            out.append(f"road: the {road_origin(road.label)}{side} reaches {peak:.3g} m where the wheels go (more than "
                       f"{MAX_ROAD_FEATURE} m); {road_advice(road.label)}")
    skew = float(crossing.bridge.skew)
    if abs(skew) > OBLIQUE_MESH_ADVISED_SKEW:
        out.append(f"bridge.deck.skew = {skew:g}°: the grillage's transverse members run along the skew (oblique mesh), "
                   f"which grillage practice keeps to skews up to {OBLIQUE_MESH_ADVISED_SKEW:g}° (ospgrillage's meshing rules); expect "
                   "transverse load sharing near the obtuse corners to be less accurate")
    out += point_warnings(crossing, response_x, response_y)
    if crossing.dt is not None:
        out += step_warnings(crossing, float(crossing.dt))
    return out


def road_origin(label: str) -> str:
    """The road named by its profile's label (``vbikit.scenario.build.build_road``: "class F, seed 1",
    "measured f.csv", either with " + <defect> at <x> m" appended): "random class-F road (seed 1)",
    "measured profile (f.csv)", "road (…)" otherwise."""
    base = label.split(" + ")[0]
    if base.startswith("class ") and ", seed " in base:
        cls, seed = base[len("class "):].split(", seed ", 1)
        seed = seed.split(",")[0]  # (a right wheel line's label goes on: ", right line (coherence …)")
        return f"random class-{cls} road (seed {seed}{', with defects' if ' + ' in label else ''})"
    if base.startswith("measured "):
        return f"measured profile ({base[len('measured '):]}{', with defects' if ' + ' in label else ''})"
    return f"road ({label})" if label else "road profile"


def road_advice(label: str) -> str:
    """What to check for a road elevation over ``MAX_ROAD_FEATURE``, by the profile's origin (``road_origin``)."""
    checks = []
    if label.startswith("measured "):
        checks.append("the profile file's unit (elevations are in metres)")
    if " + " in label:
        checks.append("the defect sizes (metres)")
    if ", seed " in label.split(" + ")[0]:
        checks.append("the road class: a random road this rough lies beyond the range the vehicle and tire models "
                      "are meant for (wheels leave the road)")
    return "check " + ("; ".join(checks) or "the profile's unit (elevations are in metres)")


def point_warnings(crossing: Crossing, x: float | None = None, y: float | None = None) -> list[str]:
    """A response point (x, y) [m] at or next to a support (within ``SUPPORT_MARGIN`` of the
    span, along the span from the point's own support line on a skew deck)."""
    bridge = crossing.bridge
    span = bridge.span
    y = bridge.default_response_y if y is None else float(y)
    x = bridge.default_x_at(y) if x is None else float(x)
    xi = float(bridge.span_coordinate(x, y))
    if min(xi, span - xi) < SUPPORT_MARGIN * span:
        return [f"response.x = {x:g} m is at or next to a support (span {span:g} m): the static response there is "
                "near zero and the impact factor is not meaningful"]
    return []


def step_warnings(crossing: Crossing, dt: float) -> list[str]:
    """Warnings about a user's step ``dt`` [s], judged against the integrator's own automatic step
    ([`vbikit.solve.timestep.choose_time_step`][vbikit.solve.choose_time_step] without a dt — the one rule per integrator):
    a coarser step, and bridge modes the automatic step resolves (≥ 5 steps a period) but ``dt``
    does not.  An integrator whose automatic step leaves modes unresolved (one that integrates
    the modes exactly) gets no mode warning."""
    auto = choose_time_step(replace(crossing, dt=None))
    out = []
    if dt > auto * (1 + 1e-9):
        out.append(f"crossing.dt = {dt:.3g} s is coarser than the automatic step {auto:.3g} s of this crossing "
                   f"({crossing.integrator}); results lose accuracy — leave dt out for the automatic step")
    f = crossing.bridge.frequencies_hz
    unresolved = f[(f * dt > 1.0 / STEPS_PER_PERIOD) & (f * auto <= 1.0 / STEPS_PER_PERIOD)]
    if unresolved.size:
        out.append(f"crossing.dt = {dt:.3g} s resolves modes up to {1 / (STEPS_PER_PERIOD * dt):.4g} Hz "
                   f"({STEPS_PER_PERIOD:g} steps a period): {unresolved.size} of {f.size} bridge modes "
                   f"({unresolved.min():.4g}–{unresolved.max():.4g} Hz) are not resolved; use a smaller dt or fewer modes")
    return out


def contact_warnings(result: CrossingResult) -> list[str]:
    """One warning per wheel whose tire lost contact: where first (wheel x [m]), when, for how long —
    on the bridge (the deck's x extent) when it lost contact there, else that it did so only before
    or after the bridge."""
    out = []
    forces, dt = result.wheel_forces, result.dt
    x_wheel = result.wheel_positions()
    for w, wheel in enumerate(result.crossing.vehicle.wheels):
        if wheel.stiffness <= 0:
            continue
        off = forces[:, w] <= 0.0
        if not off.any():
            continue
        x0, x1 = result.crossing.bridge.deck_extent
        on = (x_wheel[:, w] >= x0) & (x_wheel[:, w] <= x1)
        if (off & on).any():  # where it matters: on the deck
            i = int(np.argmax(off & on))
            away = float((off & ~on).sum() * dt)
            out.append(f"wheel {wheel.name} lost contact with the road on the bridge: first at x = "
                       f"{float(x_wheel[i, w]):.3f} m (t = {float(result.time[i]):.4f} s), for "
                       f"{float((off & on).sum() * dt):.4f} s on the bridge"
                       + (f" (and {away:.4f} s off it)" if away > 0 else ""))
            continue
        i = int(np.argmax(off))
        where = ("before the bridge" if (x_wheel[off, w] < x0).all() else
                 "after the bridge" if (x_wheel[off, w] > x1).all() else "before and after the bridge")
        out.append(f"wheel {wheel.name} lost contact with the road only {where} (x from {x0:g} to {x1:g} m): "
                   f"first at x = {float(x_wheel[i, w]):.3f} m (t = {float(result.time[i]):.4f} s), "
                   f"for {float(off.sum() * dt):.4f} s in all")
    return out


def airborne_wheels(result: CrossingResult, fraction: float = AIRBORNE_FRACTION) -> list[tuple[str, float, float]]:
    """The wheels airborne (tire force ≤ 0) on the bridge (the deck's x extent) for more than
    ``fraction`` of their own time on it: (wheel name, time airborne there [s], that fraction)."""
    out = []
    x_wheel, forces, dt = result.wheel_positions(), result.wheel_forces, result.dt
    x0, x1 = result.crossing.bridge.deck_extent
    for w, wheel in enumerate(result.crossing.vehicle.wheels):
        if wheel.stiffness <= 0:
            continue
        on = (x_wheel[:, w] >= x0) & (x_wheel[:, w] <= x1)
        n_on = int(on.sum())
        share = int(((forces[:, w] <= 0.0) & on).sum()) / n_on if n_on else 0.0
        if share > fraction:
            out.append((wheel.name, share * n_on * dt, share))
    return out


def airborne_warnings(result: CrossingResult) -> list[str]:
    """One warning when wheels were airborne on the bridge for a significant time (``airborne_wheels``):
    the impact factors are dominated by point-contact impacts, not design values."""
    wheels = airborne_wheels(result)
    if not wheels:
        return []
    k = int(np.argmax([s for _, _, s in wheels]))
    name, t, share = wheels[k]
    return [f"{AIRBORNE_WARNING_START}: {len(wheels)} wheel{'s' if len(wheels) > 1 else ''} left the road on the bridge "
            f"for more than {AIRBORNE_FRACTION:.0%} of their time on it (longest: {name}, {t:.3g} s, {share:.0%}); "
            "the impact factors are dominated by the vehicle leaving and landing on the road (point-contact impacts), "
            "so they are not design values; the road is beyond the model's intended range"]


def impact_dominated(warnings: Sequence[str]) -> bool:
    """Whether a run's ``warnings`` hold the airborne-wheels warning (``airborne_warnings``)."""
    return any(w.startswith(AIRBORNE_WARNING_START) for w in warnings)


def strain_convergence_warnings(modal_static_peak: float, exact_static_peak: float | None, n_modes: int,
                                where: str = "") -> list[str]:
    """A warning when the static strain peak of the modes ``modal_static_peak`` differs from the exact
    one ``exact_static_peak`` (None: not known; nothing) by more than ``STRAIN_MODE_TOLERANCE``: the
    strain and its IM (ε_dyn / ε_st − 1) are not converged in the ``n_modes`` modes."""
    if exact_static_peak is None or not exact_static_peak:
        return []
    err = (float(modal_static_peak) - float(exact_static_peak)) / abs(float(exact_static_peak))
    if abs(err) <= STRAIN_MODE_TOLERANCE:
        return []
    return [f"{STRAIN_WARNING_START}{f' at {where}' if where else ''}: the static strain peak of the {n_modes} modes, "
            f"{float(modal_static_peak) * 1e6:.4g} µε, is {err:+.1%} off the exact {float(exact_static_peak) * 1e6:.4g} µε "
            f"(c/EI times the static moment of the full stiffness; flagged beyond {STRAIN_MODE_TOLERANCE:.0%}): strain "
            "sums the modes' curvatures, which converge slowly near a moving load, so the strain and the strain IM "
            "are not reliable; use more modes (bridge.n_modes) or the moment's IM"]


def strain_unconverged(warnings: Sequence[str]) -> bool:
    """Whether a run's ``warnings`` hold the strain-convergence warning (``strain_convergence_warnings``)."""
    return any(w.startswith(STRAIN_WARNING_START) for w in warnings)


def small_static_mask(static_peaks: ArrayLike, axis: int = -1, fraction: float = SMALL_STATIC_FRACTION
                      ) -> NDArray[np.bool_]:
    """Whether each static peak (signed) of ``static_peaks`` is below ``fraction`` of the largest |R_st|
    along ``axis`` (the peaks of one quantity across the bridge, or across a stream's events; NaN is
    never small, nor the largest) — the impact factors resting on it are flagged.  The one rule."""
    st = np.abs(np.asarray(static_peaks, float))
    top = np.nanmax(st, axis=axis, keepdims=True, initial=0.0)
    return st < fraction * top


def small_static(static_peaks: Sequence[float], fraction: float = SMALL_STATIC_FRACTION) -> list[bool]:
    """``small_static_mask`` of a list of peaks, as a list."""
    return small_static_mask(static_peaks, fraction=fraction).tolist()


def small_static_warnings(labels: Sequence[str], static_peaks: Sequence[float], impact_factors: Sequence[float],
                          strain_impact_factors: Sequence[float] | None = None) -> list[str]:
    """One warning per deflection impact factor in ``impact_factors`` whose static peak deflection
    [m] in ``static_peaks`` (same order, ``labels`` naming each: "Girder 1", "point p2") is small
    (``small_static``): the IM (and the strain IM beside it when given), the static peak, its share
    of the largest and why it is not a design value."""
    flags = small_static(static_peaks)
    if not any(flags):
        return []
    k = int(np.argmax(np.abs(np.asarray(static_peaks, float))))
    top = abs(float(static_peaks[k]))
    strain = [None] * len(flags) if strain_impact_factors is None else list(strain_impact_factors)
    return [f"{label}: IM = {im:.3g}{'' if e is None else f' (strain IM {e:.3g})'} rests on a static deflection of "
            f"{abs(float(st)) * 1e3:.3g} mm, {abs(float(st)) / top:.0%} of the largest on the bridge "
            f"({top * 1e3:.3g} mm, {labels[k]}; "
            f"flagged below {SMALL_STATIC_FRACTION:.0%}): a lightly loaded section, where a small dynamic increment "
            "divided by a small static response gives a large IM; unreliable as a design value — use the most "
            "loaded girder's or point's IM"
            for label, st, im, e, flag in zip(labels, static_peaks, impact_factors, strain, flags) if flag]


def effect_static_warnings(effects: Sequence[tuple[str, str, str, float, float]]) -> list[str]:
    """The small-static rule (``small_static``) for load effects: ``effects`` as (kind, label, units,
    static peak, impact factor), each kind (moment, shear, reaction) judged against the largest static
    peak of its own kind among them (a moment of Girder 1 against that of Girder 4, never against a
    shear); one warning per flagged effect, as ``small_static_warnings`` words it for deflections."""
    out = []
    for kind in dict.fromkeys(k for k, *_ in effects):
        same = [e for e in effects if e[0] == kind]
        if len(same) < 2:
            continue
        peaks = [abs(float(e[3])) for e in same]
        k = int(np.argmax(peaks))
        out += [f"{label}: IM = {im:.3g} rests on a static {kind} of {abs(float(st)):.4g} {units}, "
                f"{abs(float(st)) / peaks[k]:.0%} of the largest {kind} of the run's load effects "
                f"({peaks[k]:.4g} {units}, {same[k][1]}; flagged below {SMALL_STATIC_FRACTION:.0%}): a lightly loaded "
                "section, where a small dynamic increment divided by a small static response gives a large IM; "
                "unreliable as a design value"
                for (_, label, units, st, im), flag in zip(same, small_static(peaks)) if flag]
    return out


def small_static_dataset_warnings(names: Sequence[str], static_peaks: np.ndarray) -> list[str]:
    """Warnings for a dataset of many crossings: ``static_peaks`` (..., n_points) the static peak
    deflections of the points ``names`` in every crossing; one sentence per point whose impact
    factor rests on a small static reference (``small_static`` across the points of a crossing)
    in some of the crossings, with how many."""
    st = np.asarray(static_peaks, float)
    flags = small_static_mask(st.reshape(-1, st.shape[-1]), axis=1)
    return [f"point {name}: its impact_factor rests on a static deflection under {SMALL_STATIC_FRACTION:.0%} of "
            f"the largest of the points in {int(k)} of {flags.shape[0]} crossings (a lightly loaded section); "
            "unreliable there as a design value"
            for name, k in zip(names, flags.sum(axis=0)) if k]


def run_warnings(result: CrossingResult, response_x: float | None = None, response_y: float | None = None) -> list[str]:
    """Every warning about a finished crossing: its inputs, its contact losses and wheels airborne long
    enough to dominate the impact factors."""
    return (input_warnings(result.crossing, result.dt, response_x, response_y) + contact_warnings(result)
            + airborne_warnings(result))
