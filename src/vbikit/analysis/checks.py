"""Warnings about runs that may not mean what the user thinks: inputs outside the usual range of the
models and results that carry a caveat.  Each check returns [`Flag`][vbikit.analysis.checks.Flag]
records: a stable ``code`` (``FLAG_CODES``, the one list; docs/results.md's table is generated from
it), what it is about (the output, girder, point, wheel), the measured ``value`` and its
``threshold``, and the engineer-readable ``message``.  A summary carries them under ``flags`` and
their messages under ``warnings`` (``flag_fields``, ``add_flags``: one truth; the CLI prints the
messages on stderr); the text report decides its ``!`` marks from the codes (``has_flag``), never
from the words.  None stops a run.

Thresholds (documented in docs/scenario.md):

* speed outside 5–150 km/h (a speed in km/h typed as ``speed`` [m/s] reads 3.6 times too fast),
  or outside the vehicle's own usual range (``Vehicle.usual_speed_kmh``: trains 5–420 km/h);
* road elevation (profile plus defects) over 0.1 m anywhere the wheels go (a profile in mm read as m);
* a response point within 2 % of the span from a support (static response near zero, IM meaningless);
* a step given by the user that is coarser than the integrator's automatic step, and bridge
  modes that the automatic step resolves (at least 5 steps a period, f·dt ≤ 0.2) but the user's
  step does not (``step_flags``; its message counts and lists every mode the step leaves unresolved);
* a random road (``RoadProfile.origin`` of kind "random"): its IMs are one realisation's
  (``realisation_flags``, code ``one_realisation``; single crossings only);
* wheels that lost contact (which, where first, for how long); and, when any wheel was airborne on
  the bridge for more than ``AIRBORNE_FRACTION`` (5 %) of its own time on the bridge (its own
  track's stretch of the deck, ``wheel_track_ends``: on a skew deck shorter than the deck's x range), one warning
  that the run's impact factors are dominated by the wheels leaving and landing on the road
  (``airborne_flags``; code ``airborne_wheels``; the text report marks the IM with ``!``).  5 % is a hop, not a graze: on
  Bridge 2 (16.76 m at 75 km/h, 0.80 s on the deck) it is 0.04 s in the air, about half the
  HS20-44's slowest axle-hop period (10.8 Hz: 0.093 s); an ISO class-F road keeps the front axle up for 0.55 s (68 %);
* a static strain peak of the modes (modal superposition of curvatures, which converges slowly
  under a moving load) more than ``STRAIN_MODE_TOLERANCE`` (1 %) away from the exact static strain
  c/EI times the static moment of the full stiffness (the moment's mode-acceleration static part),
  where the bridge offers the moment at the point (``strain_convergence_flags``, code ``strain_not_converged``;
  simply supported and continuous beams; on a girder deck's grid the exact strain is that of the full
  stiffness's static solution: ``vbikit.analysis.response.exact_static_strain_peak``): the Yang–Yau
  beam with 10 modes reads 20.32 µε for the exact 21.18 µε (−4.0 %), with 50 modes 21.01 µε (−0.8 %);
* an impact factor whose static reference is small: a static peak below ``SMALL_STATIC_FRACTION``
  (20 %) of the largest static peak of the same quantity on the bridge (a lightly loaded girder, a
  point near a support; ``small_static`` / ``small_static_flags``, code ``small_static``; for moments, shears and
  reactions each kind against its own largest, ``effect_static_flags``).  IM = ΔR/R_st divides the
  dynamic increment ΔR, which the deck's vibration spreads over every girder, by that small R_st:
  on the paper's 3D Bridge 2 under HS20-44 Girder 1 carries 0.28 mm of the governing 2.79 mm
  (10 %) and reads IM = 1.35 against 0.22.  Such an IM is not a design value;
* a static deflection peak (at any response point or girder) above ``IMPLAUSIBLE_DEFLECTION_FRACTION``
  (1/100) of the longest span (``implausible_deflection_flags``, code ``implausible_deflection``): highway
  bridges are designed to live-load deflections of L/800 to L/300 (AASHTO LRFD 2.5.2.6.2: L/800, L/1000
  with pedestrians; Eurocode practice about L/300 to L/600), so L/100 under one vehicle lies far beyond
  any real bridge and almost always means a unit mistake in the stiffness or mass (EI in kN m² instead
  of N m² reads deflections 1000 times too large: a 4.5 m static deflection on a 20 m span).  Study
  and traffic datasets apply the same rule to every crossing or event
  (``implausible_deflection_dataset_flags``; the threshold and the words are these), their
  ``warnings`` and ``flag_codes`` attributes from ``dataset_flag_attrs``.

* railway sweeps (``vbikit.rail``, docs/railway.md): an HSLM train outside its range of application
  (``hslm_range``), fewer modes than EN 1990 A2.4.4.2.1 requires (``too_few_modes``), and a governing
  peak still changing with the speed step after its refinement (``speed_grid_error``, tolerance
  ``vbikit.rail.refine.PEAK_TOLERANCE``, 0.5 %), and a governing peak that depends on the time step
  (``time_sampling_error``, tolerance ``vbikit.rail.report.TIME_SAMPLING_TOLERANCE``, 0.5 %).

A negative impact factor (the dynamic peak below the static one) is physical, not a warning: the
reports print ``NEGATIVE_IM_NOTE`` beside it.
"""
from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, replace
from typing import Any, Callable, Iterable, Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from vbikit._limits import MAX_RUN_IN
from vbikit._words import counted
from vbikit.bridge.girder_deck import OBLIQUE_MESH_ADVISED_SKEW
from vbikit.road.profile import RoadProfile
from vbikit.solve.crossing import Crossing
from vbikit.solve.result import CrossingResult
from vbikit.solve.run_in import SETTLED_APPROACH, SETTLED_TRANSIENT_LEFT
from vbikit.solve.timestep import choose_time_step
from vbikit.outputs import report_unit

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
#: largest relative error of the modes' static strain peak against the exact one before it is flagged
STRAIN_MODE_TOLERANCE = 0.01
#: a static deflection peak above this fraction of the longest span is not plausible for a bridge (module docstring)
IMPLAUSIBLE_DEFLECTION_FRACTION = 0.01
#: the one mark of a doubt in every report and printed result: right after a value a flag puts in doubt, and at the
#: start of a line that states a flag's message (``flag_line``); ``vbikit run``, ``traffic``, ``lifetime``, ``rail``
#: and ``driveby`` alike (before 2026-12-08 the railway and drive-by reports wrote "WARNING:", the lifetime's "FLAG")
FLAG_MARK = "!"


def flag_line(message: str) -> str:
    """A report's line stating a flag's ``message``: ``FLAG_MARK``, a space, the message."""
    return f"{FLAG_MARK} {message}"


#: what a negative impact factor means, in words (the reports print it once where one occurs)
NEGATIVE_IM_NOTE = ("an IM below 0 means the dynamic peak stayed below the static one: the deck's vibration (and a "
                    "sprung vehicle's bounce, the wheels unloading there) was out of phase with the load's arrival at "
                    "the section; physical, not an error")


#: every flag code and what it means, with what its ``value`` and ``threshold`` hold (SI units): the one
#: list (``Flag`` refuses any other code; docs/results.md's table is generated from it)
FLAG_CODES: dict[str, str] = {
    "speed_range": "a vehicle speed outside the usual range (``SPEED_RANGE_KMH``, or the vehicle's own); value: the "
                   "speed [m/s], threshold: the bound it crosses [m/s]",
    "road_elevation": "road elevation (profile plus defects) over ``MAX_ROAD_FEATURE`` where the wheels go; value: the "
                      "largest absolute elevation [m], threshold: 0.1 m",
    "oblique_mesh": "a skew beyond the grillage's advised oblique mesh; value: the skew [°], threshold [°]",
    "point_near_support": "a response point at or next to a support; value: its distance from the nearer support / "
                          "the span, threshold: ``SUPPORT_MARGIN`` (0.02)",
    "coarse_step": "a given crossing.dt coarser than the integrator's automatic step; value: dt [s], threshold: the "
                   "automatic step [s]",
    "deflection_step": 'a run for deflections only (crossing.resolve = "deflections") at a step coarser than the '
                       "automatic step for every result: its accelerations, strains, moments, shears and reactions are "
                       "not within the step's accuracy bound; value: the step [s], threshold: the step for every "
                       "result [s]",
    "unresolved_modes": "bridge modes the given step does not resolve (fewer than 5 steps a period) but the automatic "
                        "step does (the message counts and lists every mode the step does not resolve); value: the "
                        "highest frequency of those the automatic step resolves [Hz], threshold: 1 / (5 dt) [Hz]",
    "contact_loss": "a wheel lost contact with the road; wheel; value: its time off the road on the bridge [s] (0 "
                    "when only before or after it)",
    "wheel_force_step": "implicit integrators: a wheel's tire force read over a step where the road's slope changes "
                        "within it (a bump's edge): its peak can differ from the force at the instant by up to the "
                        "tire dashpots' c × (cell slope − step secant) × v; output: max_wheel_force; wheel: the "
                        "largest; value: that bound / the wheel's peak force, threshold: ``WHEEL_FORCE_STEP`` (0.05)",
    "airborne_wheels": "the impact factors are dominated by wheels leaving the road: a wheel airborne on the bridge for "
                       "more than ``AIRBORNE_FRACTION`` of its own time there; output: impact_factor; wheel: the "
                       "longest; value: its airborne share, threshold: 0.05",
    "strain_not_converged": "the static strain of the modes differs from the exact static strain; output: "
                            "strain_impact_factor; point; value: the relative error, threshold: "
                            "``STRAIN_MODE_TOLERANCE`` (0.01)",
    "small_static": "an impact factor resting on a small static reference; output: impact_factor (deflection) or "
                    "moment / shear / reaction; girder or point; value: the static peak's share of the largest, "
                    "threshold: ``SMALL_STATIC_FRACTION`` (0.2)",
    "defect_outside": "a road defect (partly) outside the approach and the bridge, where no wheel meets it",
    "heavy_axle": "an axle load far beyond legal limits; value: the axle load [N], threshold [N]",
    "effect_step": "the step does not resolve a load effect (``vbikit.analysis.effect_step``); output: moment / "
                   "shear / reaction; value: the run's step [s], threshold: the step that resolves it [s]",
    "step_not_converged": "impact factors or peak deck accelerations still changing when the step was last halved "
                          "(the step check); output: the quantity that changed most; value: its change (of a peak "
                          "acceleration relative to its value), threshold: the tolerance",
    "non_finite": "an output that is not a finite number (written as null); output: its key",
    "contact_not_converged": "implicit integrators: steps whose end-of-step contact forces did not settle to their "
                             "tolerance within the iteration limit (the run went on with the last iterate); output: "
                             "unconverged_steps (lifetime: \"total return levels\", subject: the load effect); value: "
                             "their number (in a dataset or a lifetime: in the worst crossing, event or drive-by "
                             "pass), threshold: 0",
    "lift_off": "random run: a tire lifts off with a probability above the linear theory's limit; value: the "
                "probability, threshold: the limit",
    "sagging_over_pier": "a moment over an interior support whose largest static value is sagging (a soft "
                         "support); output: moment; value: the hogging extreme's share of it, threshold: "
                         "``SMALL_STATIC_FRACTION`` (0.2; above it the hogging extreme is reported too)",
    "coarse_grid": "random run: the wavenumber grid is coarse; value: the change of σ between every and every "
                   "second line, threshold: the limit",
    "one_realisation": "the road is one realisation of a random road (a class or PSD with a seed): the impact factors "
                       "are those of that realisation and scatter between seeds; output: impact_factor; value: the "
                       "seed",
    "implausible_deflection": "a static deflection peak larger than a bridge under traffic can plausibly show (a unit "
                              "mistake in the bridge's stiffness or mass); output: impact_factor; girder or point: "
                              "the largest; value: its static peak / the longest span, threshold: "
                              "``IMPLAUSIBLE_DEFLECTION_FRACTION`` (0.01)",
    "ignored_input": "an input the model has no use for (response.y or crossing.lateral_offset on a beam, which has "
                     "no lateral dimension); subject: the key; value: the value given",
    # lifetime (vbikit.lifetime.report; per load effect, subject: the effect's name; units of a level: the effect's,
    # N m, N or m: load_effect_units)
    "characteristic_not_estimable": "lifetime: the block maxima could not be fitted (all equal, too few), the "
                                    "characteristic value is missing; output: \"characteristic static value\" or "
                                    "\"characteristic total value\"",
    "characteristic_above_static_bound": "lifetime: the characteristic static value exceeds the largest static effect "
                                         "the traffic model can produce (bootstrap traffic); output: "
                                         "\"characteristic static value\"; value: the characteristic static value, threshold: "
                                         "static_upper_bound (the effect's unit, signed like it)",
    "opposite_direction_unreported": "lifetime: a load effect governed by the sign of its influence line's largest "
                                     "ordinate (direction = \"auto\") while the other direction may govern, which "
                                     "the run does not report: its traffic reached a larger static value the other "
                                     "way, or the other sign's part of the line has the larger area (long or several "
                                     "vehicles load it more that way); output: \"characteristic static value\"; "
                                     "value: the run's largest static value the other way over the reported way's "
                                     "where that is above 1, else the area ratio, threshold: ``OPPOSITE_AREA_LIMIT`` (1)",
    "negative_shape": "lifetime: a fitted shape ξ (GEV of the block maxima or GPD of the exceedances) strongly "
                      "negative, a bounded tail fitted from little data; output: \"static return levels\" or "
                      "\"total return levels\"; value: the lower of the two shapes, threshold: xi_strongly_negative (−0.3)",
    "wide_interval": "lifetime: a return level whose confidence interval is wider than the level (or reaches across "
                     "zero); output: \"static return levels\" or \"total return levels\"; value: the largest interval width "
                     "over the level's magnitude of those flagged, threshold: ``WIDE_INTERVAL`` (1)",
    "bm_pot_disagree": "lifetime: block maxima and peaks over threshold disagree beyond their confidence intervals "
                       "(the intervals do not overlap); output: \"static return levels\" or \"total return levels\"; value: "
                       "the largest gap between the two intervals (a method without one: its value) over the periods "
                       "flagged (the effect's unit), threshold: 0",
    "adr_indistinguishable_from_one": "lifetime: the ADR's confidence interval contains 1; output: \"ADR\"; value: the "
                                      "interval's bound on the far side of 1 (the lower bound for an ADR ≥ 1, else "
                                      "the upper), threshold: 1",
    "adr_above_event_bound": "lifetime: the ADR is above 1 + the largest amplification any day's total maximum can "
                             "have over its static one (the screening bound A used, or the effect's simulated events' "
                             "larger R_dyn/R_st − 1): the two fits extrapolate apart beyond what the events allow; output: "
                             "\"characteristic total value\" (the report marks it and the ADR); value: the ADR, "
                             "threshold: that bound",
    "static_reference_short": "lifetime: the coupled runs' static reference misses the exact static peak (the daily "
                              "maxima of the total and the ADR biased low); output: \"ADR\"; value: the largest relative "
                              "shortfall (run_static_shortfall), threshold: half_step_tolerance (0.01)",
    "start_from_rest": "traffic and lifetime: the events start their vehicles at rest crossing.approach + crossing.run_in "
                       "before the bridge (the shortest run-in of any event: a base scenario's run_in = 0, a road too "
                       "short for the population's), less than ``SETTLED_APPROACH`` (100 m): they enter before their body "
                       "vibration has built up, so the impact factors and dynamic peaks come out low (docs/traffic.md); "
                       "output: impact_factor; value: approach + run-in [m], threshold: ``SETTLED_APPROACH``",
    "start_unsettled": "traffic and lifetime: events with a sprung vehicle that keeps more than "
                       "``SETTLED_TRANSIENT_LEFT`` (0.07) of its start transient when it reaches "
                       "the bridge (exp(−σ_min t): a lighter damped vehicle than the trucks the settled start was "
                       "checked with, or less road before the bridge), so their impact factors and dynamic peaks may "
                       "come out low (docs/traffic.md); output: impact_factor; value: the largest share kept, threshold: "
                       "``SETTLED_TRANSIENT_LEFT``",
    "stream_step_sensitive": "traffic: a governing event's impact factors (deflection, strain, load effects) change at "
                             "half the time step; output: the one that moved most; subject: the event; value: its "
                             "IM_half − IM_run, threshold: ``STEP_TOLERANCE`` (5e-3, on its magnitude)",
    "interval_not_bounded": "traffic: an end of a statistic's 95 % confidence interval that the stream's events cannot "
                            "bound (an order-statistic interval of a quantile needs enough values beyond it; a mean's "
                            "Student-t interval two values): the statistic is an estimate without a stated accuracy at "
                            "that end; output: the statistic; value: the values it rests on, threshold: the values that "
                            "end needs",
    "governing_step_sensitive": "lifetime: a governing event's total peak changes at half the time step; output: "
                                "\"governing static event\" or \"governing total event\"; value: the relative change R_half / R_run − 1, "
                                "threshold: half_step_tolerance (0.01, on its magnitude)",
    "hslm_range": "railway sweep: an HSLM train outside its range of application (EN 1991-2:2003 6.4.6.1.1(5), Annex "
                  "E: HSLM-B on simply supported spans below 7 m, HSLM-A otherwise), so its check is not the EN 1991-2 "
                  "one; subject: the trains; value: the span [m], threshold: ``HSLM_B_MAX_SPAN`` (7 m)",
    "hslm_incomplete": "railway sweep: some of the ten HSLM-A trains, not all, on a span of 7 m or more: EN 1991-2:2003 "
                       "6.4.6.1.1 and Annex E check a span with HSLM-A1 … A10 together, so a PASS covers only the "
                       "trains run; subject: the HSLM-A trains run; value: how many, threshold: 10",
    "too_few_modes": "railway sweep: fewer modes retained than EN 1990 A2.4.4.2.1 requires (every mode up to max(30 Hz, "
                     "1.5 n0, n3)); value: the modes retained, threshold: the modes required",
    "speed_grid_error": "railway sweep: the governing peak of a check still changes with the speed step after its "
                        "refinement (``vbikit.rail.refine``: the step halved around it at most ``MAX_HALVINGS`` times); "
                        "output: acceleration, moment, shear or deflection; value: the larger of its relative change "
                        "over the last halving and the bound of its remaining error, threshold: ``PEAK_TOLERANCE`` "
                        "(0.005)",
    "time_sampling_error": "railway sweep: the peaks of a check depend on the time step h = dx / v "
                           "(``vbikit.solve.moving_loads``: peaks taken between the samples); output: acceleration, "
                           "moment, shear or deflection; value: the governing peak's larger of how far its largest time "
                           "sample or one-sided limit at an axle's passage lies below the peak taken between the samples and the estimated bound of its "
                           "remaining error (relative), or else the largest such bound of a peak of the sweep as a share "
                           "of the largest peak; threshold: ``TIME_SAMPLING_TOLERANCE`` (0.005)",
}


@dataclass(frozen=True)
class Flag:
    """One finding of a check, as data.

    Parameters
    ----------
    code : str
        What was found, stable (``FLAG_CODES``).
    message : str
        The engineer-readable sentence (the summary's ``warnings``, stderr).
    output : str, optional
        The summary key the finding puts in doubt ("impact_factor", "strain_impact_factor",
        "moment", …) or names (a non-finite output); a lifetime finding's, what it puts in doubt
        in words ("static return levels", "ADR": ``vbikit.lifetime.report.FLAG_OUTPUTS``).
    subject : str, optional
        What it is about, in words ("Girder 1", "point p2", the moment's section, an input key).
    girder : int, optional
        The girder (1-based) it is about.
    point : str, optional
        The response point (by name) it is about.
    wheel : str, optional
        The wheel (by name) it is about.
    value, threshold : float, optional
        The measured value and the limit it passed (units: ``FLAG_CODES``).
    """

    code: str
    message: str
    output: str | None = None
    subject: str | None = None
    girder: int | None = None
    point: str | None = None
    wheel: str | None = None
    value: float | None = None
    threshold: float | None = None

    def __post_init__(self) -> None:
        _check_code(self.code)

    def as_dict(self) -> dict[str, Any]:
        """The JSON-ready record (every field, None as null; a value or threshold that is not finite,
        e.g. an unbounded step, as None too)."""
        out = asdict(self)
        for key in ("value", "threshold"):
            if out[key] is not None:
                out[key] = float(out[key]) if np.isfinite(out[key]) else None
        return out


def messages(flags: Iterable[Flag]) -> list[str]:
    """The flags' messages, in order, each once."""
    return list(dict.fromkeys(f.message for f in flags))


def flag_fields(flags: Iterable[Flag]) -> dict[str, list]:
    """A summary's ``flags`` (JSON records) and ``warnings`` (their messages) from ``flags``, each
    message once (the first flag with it kept)."""
    out: dict[str, list] = {"warnings": [], "flags": []}
    add_flags(out, flags)
    return out


#: codes that put every result of a run in doubt (a likely input mistake): listed first in ``flags`` and
#: ``warnings``, so that the cause leads and the symptoms (contact losses, airborne wheels) follow
LEADING_CODES = ("implausible_deflection",)


def add_flags(summary: dict[str, Any], flags: Iterable[Flag]) -> None:
    """Append ``flags`` to ``summary``'s ``flags`` and their messages to its ``warnings`` (the one
    way a summary gets a warning), skipping a message it holds already; a flag of ``LEADING_CODES``
    goes before the others."""
    texts, records = summary.setdefault("warnings", []), summary.setdefault("flags", [])
    for f in flags:
        if f.message not in texts:
            at = 0 if f.code in LEADING_CODES else len(records)
            records.insert(at, f.as_dict())
            texts.insert(at, f.message)


def _check_code(code: str) -> None:
    """ValueError unless ``code`` is one of ``FLAG_CODES``."""
    if code not in FLAG_CODES:
        raise ValueError(f"flag code {code!r} is not one of {', '.join(FLAG_CODES)}")


def find_flag(summary: Mapping[str, Any], code: str, **match: object) -> dict[str, Any] | None:
    """The first flag record of ``summary`` with ``code`` whose fields equal ``match`` (e.g. girder=1),
    or None."""
    _check_code(code)
    return next((f for f in summary.get("flags", ())
                 if f.get("code") == code and all(f.get(k) == v for k, v in match.items())), None)


def has_flag(summary: Mapping[str, Any], code: str, **match: object) -> bool:
    """Whether ``summary`` carries a flag of ``code`` whose fields equal ``match`` (``find_flag``)."""
    return find_flag(summary, code, **match) is not None


def input_flags(crossing: Crossing, dt: float, response_x: float | None = None,
                response_y: float | None = None) -> list[Flag]:
    """Flags about the inputs of ``crossing`` run with step ``dt`` [s] and read at ``response_x`` [m]."""
    out: list[Flag] = []
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
                out.append(Flag("speed_range", f"{key}: {what} {v:.4g} km/h ({v / 3.6:.4g} m/s) is outside the usual "
                                f"{lo:g}–{hi:g} km/h; check the unit (speed is in m/s, speed_kmh in km/h)",
                                subject=key, value=v / 3.6, threshold=(lo if v < lo else hi) / 3.6))
                break
    x_lo, x_hi = crossing.road_extent()
    for side, road in (("", crossing.road), (" (right wheel line)", crossing.road_right)):
        if road is None:
            continue
        lo, hi = np.searchsorted(road.x, x_lo, side="left"), np.searchsorted(road.x, x_hi, side="right")
        z = road.z[lo:hi] if hi > lo else road.z  # the stations x_lo ≤ x ≤ x_hi (x increasing)
        peak = float(np.max(np.abs(z))) if z.size else 0.0
        if peak > MAX_ROAD_FEATURE:
            out.append(Flag("road_elevation", f"road: the {road_origin(road)}{side} reaches {peak:.3g} m where the "
                            f"wheels go (more than {MAX_ROAD_FEATURE} m); {road_advice(road)}",
                            subject="road" + side, value=peak, threshold=MAX_ROAD_FEATURE))
    skew = float(crossing.bridge.skew)
    if abs(skew) > OBLIQUE_MESH_ADVISED_SKEW:
        out.append(Flag("oblique_mesh", f"bridge.deck.skew = {skew:g}°: the grillage's transverse members run along the "
                        f"skew (oblique mesh), which grillage practice keeps to skews up to {OBLIQUE_MESH_ADVISED_SKEW:g}° "
                        "(ospgrillage's meshing rules); expect transverse load sharing near the obtuse corners to be "
                        "less accurate", subject="bridge.deck.skew", value=skew, threshold=OBLIQUE_MESH_ADVISED_SKEW))
    out += point_flags(crossing, response_x, response_y)
    if crossing.dt is not None:
        out += step_flags(crossing, float(crossing.dt))
    return out


def road_origin(road: RoadProfile) -> str:
    """The road named by its origin (``RoadProfile.origin``, set where the profile is made: a scenario's
    [road], a profile file, ``with_defects``): "random class-F road (seed 1)", "measured profile
    (f.csv)", either with ", with defects"; "road (<label>)" for a profile of unknown origin."""
    o = road.origin
    defects = ", with defects" if o is not None and o.defects else ""
    if o is not None and o.kind == "random":
        what = f"random class-{o.road_class} road" if o.road_class else "random road"
        return f"{what} (seed {o.seed}{defects})"
    if o is not None and o.kind == "measured":
        return f"measured profile ({o.file}{defects})"
    return f"road ({road.label})" if road.label else "road profile"


def road_advice(road: RoadProfile) -> str:
    """What to check for a road elevation over ``MAX_ROAD_FEATURE``, by the profile's origin (``road_origin``)."""
    o = road.origin
    checks = []
    if o is not None and o.kind == "measured":
        checks.append("the profile file's unit (elevations are in metres)")
    if o is not None and o.defects:
        checks.append("the defect sizes (metres)")
    if o is not None and o.kind == "random":
        checks.append("the road class: a random road this rough lies beyond the range the vehicle and tire models "
                      "are meant for (wheels leave the road)")
    return "check " + ("; ".join(checks) or "the profile's unit (elevations are in metres)")


def point_flags(crossing: Crossing, x: float | None = None, y: float | None = None,
                name: str | None = None) -> list[Flag]:
    """A response point (x, y) [m] (``name``: the point's name) at or next to a support (within
    ``SUPPORT_MARGIN`` of the span, along the span from the point's own support line on a skew deck)."""
    bridge = crossing.bridge
    span = bridge.span
    y = bridge.default_response_y if y is None else float(y)
    x = bridge.default_x_at(y) if x is None else float(x)
    xi = float(bridge.span_coordinate(x, y))
    if min(xi, span - xi) < SUPPORT_MARGIN * span:
        return [Flag("point_near_support", f"response.x = {x:g} m is at or next to a support (span {span:g} m): the "
                     "static response there is near zero and the impact factor is not meaningful",
                     output="impact_factor", subject=f"x = {x:g} m, y = {y:g} m", point=name,
                     value=min(xi, span - xi) / span, threshold=SUPPORT_MARGIN)]
    return []


def step_flags(crossing: Crossing, dt: float) -> list[Flag]:
    """Flags about a user's step ``dt`` [s], judged against the integrator's own automatic step
    ([`vbikit.solve.timestep.choose_time_step`][vbikit.solve.choose_time_step] without a dt — the one rule per integrator):
    a coarser step, and bridge modes the automatic step resolves (≥ 5 steps a period) but ``dt``
    does not.  An integrator whose automatic step leaves modes unresolved (one that integrates
    the modes exactly) gets no mode flag."""
    auto = choose_time_step(replace(crossing, dt=None))
    out = []
    if dt > auto * (1 + 1e-9):
        out.append(Flag("coarse_step", f"crossing.dt = {dt:.3g} s is coarser than the automatic step {auto:.3g} s of this "
                        f"crossing ({crossing.integrator}); results lose accuracy — leave dt out for the automatic step",
                        output="impact_factor", subject="crossing.dt", value=dt, threshold=auto))
    f = np.asarray(crossing.bridge.frequencies_hz, float)
    limit = 1.0 / STEPS_PER_PERIOD
    unresolved = np.flatnonzero(f * dt > limit)  # every mode the step does not resolve
    lost = np.flatnonzero((f * dt > limit) & (f * auto <= limit))  # ... of them, those the automatic step resolves
    if lost.size:
        also = "" if lost.size == unresolved.size else (
            f"; the automatic step {auto:.3g} s resolves {_modes(lost, f)} of them")
        out.append(Flag("unresolved_modes", f"crossing.dt = {dt:.3g} s resolves modes up to {1 / (STEPS_PER_PERIOD * dt):.4g} Hz "
                        f"({STEPS_PER_PERIOD:g} steps a period): {unresolved.size} of {f.size} bridge modes, "
                        f"{_modes(unresolved, f)}, are not resolved{also}; use a smaller dt or fewer modes",
                        output="impact_factor", subject="crossing.dt", value=float(f[lost].max()),
                        threshold=1 / (STEPS_PER_PERIOD * dt)))
    return out


def resolve_flags(crossing: Crossing, dt: float) -> list[Flag]:
    """A run for deflections only (``Crossing.resolve`` = "deflections") at a step ``dt`` [s] (automatic or
    given) coarser than the automatic step for every result: its other results are flagged."""
    if crossing.resolve == "effects":
        return []
    full = choose_time_step(replace(crossing, resolve="effects", dt=None))
    if dt <= full * (1 + 1e-9):
        return []
    which = "automatic step" if crossing.dt is None else "step"
    return [Flag("deflection_step", f'crossing.resolve = "{crossing.resolve}": the {which} {dt:.3g} s resolves the '
                 "deck's deflections and the tire forces; its accelerations (the vehicles' too), strains, moments, "
                 f"shears and reactions are not within the step's accuracy bound (the step for them: {full:.3g} s) — "
                 "leave crossing.resolve out for them", subject="crossing.resolve", value=float(dt), threshold=float(full))]


def _modes(index: NDArray[np.intp], f: NDArray[np.float64]) -> str:
    """Modes by number (1-based, runs joined: "modes 1–4, 7") and their frequency range [Hz]."""
    runs: list[list[int]] = []
    for i in (int(k) + 1 for k in index):
        if runs and i == runs[-1][1] + 1:
            runs[-1][1] = i
        else:
            runs.append([i, i])
    numbers = ", ".join(f"{a}" if a == b else f"{a}–{b}" for a, b in runs)
    word = "mode" if index.size == 1 else "modes"
    hz = f"{f[index].min():.4g} Hz" if index.size == 1 else f"{f[index].min():.4g}–{f[index].max():.4g} Hz"
    return f"{word} {numbers} ({hz})"


def wheel_track_ends(result: CrossingResult) -> NDArray[np.float64]:
    """(n_wheels, 2): x [m] where each wheel's own track enters and leaves the deck, the support lines
    at the wheel's deck y (the lateral y of its contact points, ``Crossing.point_kinematics``): ξ = 0
    and ξ = span with ξ = ``bridge.span_coordinate(x, y)``, i.e. x = y·tan θ and span + y·tan θ on a
    skew deck — a stretch as long as the span, shorter than the deck's full x range
    (``deck_extent``), which holds every track's ends."""
    crossing = result.crossing
    bridge = crossing.bridge
    _, _, y_points = crossing.point_kinematics()
    wheel = np.asarray(crossing.contact.wheel, np.int64)
    n_w = len(crossing.vehicle.wheels)
    y = np.bincount(wheel, weights=y_points, minlength=n_w) / np.maximum(np.bincount(wheel, minlength=n_w), 1)
    start = -np.asarray(bridge.span_coordinate(np.zeros(n_w), y), float)
    return np.stack([start, start + float(bridge.span)], axis=1)


def wheels_on_deck(result: CrossingResult, x: NDArray[np.float64] | None = None,
                   ends: NDArray[np.float64] | None = None) -> NDArray[np.bool_]:
    """Whether each wheel centre is on its own track's stretch of the deck at each time, (n_t, n_wheels)
    (``wheel_track_ends``); ``x``: the wheel positions, ``ends``: the track ends, if already made."""
    x = result.wheel_positions() if x is None else x
    ends = wheel_track_ends(result) if ends is None else ends
    return (x >= ends[None, :, 0]) & (x <= ends[None, :, 1])


def contact_flags(result: CrossingResult) -> list[Flag]:
    """One flag per wheel whose tire lost contact: where first (wheel x [m]), when, for how long —
    on the bridge (its own track on the deck, ``wheels_on_deck``) when it lost contact there, else
    that it did so only before or after the bridge."""
    out = []
    forces, dt = result.wheel_forces, result.dt
    x_wheel = result.wheel_positions()
    ends: NDArray[np.float64] | None = None  # (made for the first wheel that lost contact)
    on_deck: NDArray[np.bool_] | None = None
    for w, wheel in enumerate(result.crossing.vehicle.wheels):
        if wheel.stiffness <= 0:
            continue
        off = forces[:, w] <= 0.0
        if not off.any():
            continue
        if ends is None:
            ends = wheel_track_ends(result)
            on_deck = wheels_on_deck(result, x_wheel, ends)
        on = on_deck[:, w]
        if (off & on).any():  # where it matters: on the deck
            i = int(np.argmax(off & on))
            away = float((off & ~on).sum() * dt)
            t_on = float((off & on).sum() * dt)
            out.append(Flag("contact_loss", f"wheel {wheel.name} lost contact with the road on the bridge: first at x = "
                            f"{float(x_wheel[i, w]):.3f} m (t = {float(result.time[i]):.4f} s), for "
                            f"{t_on:.4f} s on the bridge" + (f" (and {away:.4f} s off it)" if away > 0 else ""),
                            subject=f"wheel {wheel.name}", wheel=wheel.name, value=t_on))
            continue
        i = int(np.argmax(off))
        lo, hi = map(float, ends[w])
        where = ("before the bridge" if (x_wheel[off, w] < lo).all() else
                 "after the bridge" if (x_wheel[off, w] > hi).all() else "before and after the bridge")
        out.append(Flag("contact_loss", f"wheel {wheel.name} lost contact with the road only {where} (its track on the deck: "
                        f"x from {round(lo, 3) + 0.0:.3f} to {round(hi, 3) + 0.0:.3f} m): first at x = {float(x_wheel[i, w]):.3f} m (t = {float(result.time[i]):.4f} s), "
                        f"for {float(off.sum() * dt):.4f} s in all", subject=f"wheel {wheel.name}", wheel=wheel.name,
                        value=0.0))
    return out


#: a wheel's step-read share of its peak tire force above which ``wheel_force_step`` flags the peak
#: (``wheel_force_step_bound``: 0.2 % on the demo's class C road, 73 % on examples/field's 38.1 mm bump)
WHEEL_FORCE_STEP = 0.05


def wheel_force_step_bound(result: CrossingResult) -> NDArray[np.float64]:
    """Per wheel, an estimate [N] of how far its peak tire force as the implicit integrators store it
    can be from the force at the instant: the largest over the stored steps t_n, and over the instants
    t of the step around each (|t − t_n| ≤ dt/2), of |Σ_p c_p (ṙ_cell(t) − ṙ_n)| — the tire dashpots'
    road term at the instant (v × the slope of the road cell the point is on then, as RK4 reads it)
    against the one the step reads (the road's secant over the half steps around t_n,
    ``vbikit.solve.kernels``, "the road rate"), the wheel's own motion frozen over the step.  The road
    is piecewise linear, so the instants are taken every half of its finest station spacing (every
    cell a point crosses within the step is read).  Zeros for an integrator that reads the cell's slope.
    On examples/field's wood bump (point tires) RK4's peak-force shortfall is 0.82–1.14 times it at
    steps of 1–3 cm of road (272 kN against 273 kN at the automatic step; tests/unit/test_wheel_force_step.py)."""
    from vbikit.solve.integrators import get_integrator

    crossing, data = result.crossing, result.kernel_data
    n_w = data.n_wheels if data is not None else 0
    span = get_integrator(crossing.integrator).road_rate_span(result.integration_dt)
    if n_w == 0 or span <= 0.0 or (crossing.road is None and crossing.road_right is None):
        return np.zeros(n_w)
    pts = data.points
    travel, speed = crossing.travel(result.time), crossing.travel_speed(result.time)  # (n_t, n_vehicles)
    x = pts.origin + pts.direction * travel[:, pts.vehicle]  # (n_t, n_points), as ``point_positions``
    vx = pts.direction * speed[:, pts.vehicle]
    by_wheel = np.zeros((pts.wheel.size, n_w))
    by_wheel[np.arange(pts.wheel.size), pts.wheel] = pts.damping
    # the points' road lines as the kernels read them (``road_data``: line 1 is the right profile, or the left)
    lines = [(profile, np.minimum(pts.line, 1) == line) for line, profile in
             enumerate((crossing.road, crossing.road if crossing.road_right is None else crossing.road_right))]
    # with the rates the step reads there (ṙ_n per point)
    lines = [(profile, on, profile.run_rates(x[:, on], vx[:, on], span)) for profile, on in lines
             if profile is not None and on.any()]
    reach = float(np.abs(vx).max()) * result.integration_dt / 2  # the road a point covers in half a step [m]
    finest = min(float(np.diff(profile.x).min()) for profile, _, _ in lines)
    n_instants = int(min(_MAX_STEP_INSTANTS, max(2, math.ceil(2 * reach / (0.5 * finest)))))
    bound = np.zeros(n_w)
    for s in np.linspace(-1.0, 1.0, n_instants + 1):  # t − t_n = s dt/2
        gap = np.zeros_like(x)  # ṙ_cell(t) − ṙ_n per point
        for profile, on, step_rate in lines:
            gap[:, on] = vx[:, on] * profile.evaluate(x[:, on] + s * vx[:, on] * (result.integration_dt / 2))[1] \
                - step_rate
        bound = np.maximum(bound, np.abs(gap @ by_wheel).max(axis=0))
    return bound


#: most instants a step ``wheel_force_step_bound`` reads the road at (a step of 64 half stations)
_MAX_STEP_INSTANTS = 64


def wheel_force_step_flags(result: CrossingResult) -> list[Flag]:
    """One flag when a wheel's peak tire force may be off by more than ``WHEEL_FORCE_STEP`` of it because
    the implicit integrators read the road rate over a step (``wheel_force_step_bound``): over a road
    feature about a step long the stored forces are the step's, not the instant's.  The bridge's
    response is not concerned (its loads over a step are the step's).  Not checked on generated
    random roads without defects (``RoadProfile.band_limited``), whose 1 cm cells move a
    peak by ≈ 0.2 % (the demo's class C road: 0.21 kN of 108 kN; ``tests/unit/test_wheel_force_step.py``)
    and whose check would cost about half of a run's own time; measured profiles, defects and arrays
    are checked."""
    crossing = result.crossing
    roads = [r for r in (crossing.road, crossing.road_right) if r is not None]
    if all(r.band_limited for r in roads):
        return []
    peak = np.maximum(np.abs(result.wheel_forces).max(axis=0), 1e-300)
    bound = wheel_force_step_bound(result)
    if not bound.size:
        return []
    share = bound / peak
    w = int(np.argmax(share))
    if share[w] <= WHEEL_FORCE_STEP:
        return []
    name = result.crossing.vehicle.wheels[w].name
    unit, factor = report_unit("N")
    kn = float(bound[w]) * factor
    return [Flag("wheel_force_step",
                 f"tire forces over a road feature about a step long (a bump's edge): the implicit integrator reads the "
                 f"road's rate over each step, so a wheel's peak tire force can differ from the force at the instant by "
                 f"about {kn:.4g} {unit} (wheel {name}, {share[w]:.0%} of its peak); the bridge's response is not "
                 f"concerned; read peak tire forces (max_wheel_force) from a run with integrator = \"rk4\"",
                 output="max_wheel_force", subject=f"wheel {name}", wheel=name, value=float(share[w]),
                 threshold=WHEEL_FORCE_STEP)]


def airborne_wheels(result: CrossingResult, fraction: float = AIRBORNE_FRACTION) -> list[tuple[str, float, float]]:
    """The wheels airborne (tire force ≤ 0) on the bridge for more than ``fraction`` of their own time
    on it (each on its own track's stretch of the deck, ``wheels_on_deck``): (wheel name, time
    airborne there [s], that fraction).  A run whose every tire force stays positive has none (the
    deck stretches are not computed: a population's events ask this of every run)."""
    out: list[tuple[str, float, float]] = []
    forces, dt = result.wheel_forces, result.dt
    if not np.any(forces <= 0.0):
        return out
    on_deck = wheels_on_deck(result)
    for w, wheel in enumerate(result.crossing.vehicle.wheels):
        if wheel.stiffness <= 0:
            continue
        on = on_deck[:, w]
        n_on = int(on.sum())
        share = int(((forces[:, w] <= 0.0) & on).sum()) / n_on if n_on else 0.0
        if share > fraction:
            out.append((wheel.name, share * n_on * dt, share))
    return out


def airborne_flags(result: CrossingResult) -> list[Flag]:
    """One flag when wheels were airborne on the bridge for a significant time (``airborne_wheels``):
    the impact factors are dominated by point-contact impacts, not design values."""
    wheels = airborne_wheels(result)
    if not wheels:
        return []
    k = int(np.argmax([s for _, _, s in wheels]))
    name, t, share = wheels[k]
    return [Flag("airborne_wheels",
                 f"impact factors dominated by airborne wheels: {len(wheels)} wheel{'s' if len(wheels) > 1 else ''} left "
                 f"the road on the bridge for more than {AIRBORNE_FRACTION:.0%} of their time on it (longest: {name}, "
                 f"{t:.3g} s, {share:.0%}); the impact factors are dominated by the vehicle leaving and landing on the "
                 "road (point-contact impacts), so they are not design values; the road (or, with an implausible "
                 "deflection, the bridge's stiffness) is beyond the model's intended range", output="impact_factor",
                 subject=f"wheel {name}", wheel=name, value=share, threshold=AIRBORNE_FRACTION)]


#: what a girder deck's ``strain_not_converged`` advises instead of more modes: the substitute to sign with
DECK_STRAIN_ADVICE = ("on a girder deck the modes' strain converges slowly and not monotonically (more modes can move it "
                      "further off before hundreds of modes bring it in), so sign with the girder's moment IM at this "
                      "section (response.moment), not the deflection IM: the strain follows the girder's bending moment, "
                      "and a moment's IM is the one applied in moment (strength) design, a deflection's only in "
                      "serviceability checks")


def strain_mode_error(modal_static_peak: float, exact_static_peak: float | None) -> float:
    """The relative error of the modes' static strain peak against the exact one, (modal − exact) / |exact|
    (NaN where the exact peak is not known or zero): what ``strain_convergence_flags`` and
    ``strain_mode_dataset_flags`` judge against ``STRAIN_MODE_TOLERANCE``."""
    if exact_static_peak is None or not exact_static_peak:
        return math.nan
    return (float(modal_static_peak) - float(exact_static_peak)) / abs(float(exact_static_peak))


def strain_convergence_flags(modal_static_peak: float, exact_static_peak: float | None, n_modes: int,
                             where: str = "", point: str | None = None, deck: bool = False) -> list[Flag]:
    """A flag when the static strain peak of the modes ``modal_static_peak`` differs from the exact
    one ``exact_static_peak`` (None: not known; nothing) by more than ``STRAIN_MODE_TOLERANCE``: the
    strain and its IM (ε_dyn / ε_st − 1) are not converged in the ``n_modes`` modes (``where``: the
    point in words, ``point``: its name).  ``deck``: a girder deck's grid, whose exact strain is that
    of the full stiffness's static solution and whose modes converge to it slowly and not
    monotonically (``vbikit.analysis.response.exact_static_strain_peak``): the advice names that, and
    which substitute to sign with (``DECK_STRAIN_ADVICE``)."""
    err = strain_mode_error(modal_static_peak, exact_static_peak)
    if math.isnan(err) or abs(err) <= STRAIN_MODE_TOLERANCE:
        return []
    reference, advice = (
        ("the strain of the grid's full-stiffness static solution", DECK_STRAIN_ADVICE) if deck else
        ("c/EI times the static moment of the full stiffness", "use more modes (bridge.n_modes) or the moment's IM"))
    return [Flag("strain_not_converged",
                 f"strain not converged in the modes{f' at {where}' if where else ''}: the static strain peak of the "
                 f"{n_modes} modes, {float(modal_static_peak) * 1e6:.4g} µε, is {err:+.1%} off the exact "
                 f"{float(exact_static_peak) * 1e6:.4g} µε ({reference}; flagged beyond {STRAIN_MODE_TOLERANCE:.0%}): "
                 "strain sums the modes' curvatures, which converge slowly near a moving load, so the strain and the "
                 f"strain IM are not reliable; {advice}", output="strain_impact_factor", subject=where or None,
                 point=point, value=err, threshold=STRAIN_MODE_TOLERANCE)]


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


def small_static_flags(labels: Sequence[str], static_peaks: Sequence[float], impact_factors: Sequence[float],
                       strain_impact_factors: Sequence[float] | None = None,
                       girders: Sequence[int | None] | None = None, points: Sequence[str | None] | None = None,
                       output: str = "impact_factor") -> list[Flag]:
    """One flag per deflection impact factor in ``impact_factors`` whose static peak deflection
    [m] in ``static_peaks`` (same order, ``labels`` naming each: "Girder 1", "point p2"; ``girders``,
    ``points``: each one's girder number and point name, None where not one; ``output``: the summary key
    of the impact factors) is small
    (``small_static``): the IM (and the strain IM beside it when given), the static peak, its share
    of the largest and why it is not a design value."""
    flags = small_static(static_peaks)
    if not any(flags):
        return []
    k = int(np.argmax(np.abs(np.asarray(static_peaks, float))))
    top = abs(float(static_peaks[k]))
    n = len(flags)
    strain = [None] * n if strain_impact_factors is None else list(strain_impact_factors)
    girders = [None] * n if girders is None else list(girders)
    points = [None] * n if points is None else list(points)
    return [Flag("small_static",
                 f"{label}: IM = {im:.3g}{'' if e is None else f' (strain IM {e:.3g})'} rests on a static deflection of "
                 f"{abs(float(st)) * 1e3:.3g} mm, {abs(float(st)) / top:.0%} of the largest on the bridge "
                 f"({top * 1e3:.3g} mm, {labels[k]}; "
                 f"flagged below {SMALL_STATIC_FRACTION:.0%}): a lightly loaded section, where a small dynamic increment "
                 "divided by a small static response gives a large IM; unreliable as a design value — use the most "
                 "loaded girder's or point's IM", output=output, subject=label, girder=g, point=p,
                 value=abs(float(st)) / top, threshold=SMALL_STATIC_FRACTION)
            for label, st, im, e, g, p, flag in zip(labels, static_peaks, impact_factors, strain, girders, points, flags)
            if flag]


#: what an implausible static deflection asks the user to check (the single run's and the populations' words)
IMPLAUSIBLE_DEFLECTION_ADVICE = ("check the units of the bridge's stiffness (EI in N m², E in Pa, I in m⁴) and mass "
                                 "(kg/m)")


def implausible_deflection_share(static_peak: ArrayLike, span: ArrayLike) -> NDArray[np.float64]:
    """|static deflection peak| [m] / the longest span [m], elementwise: the measure that
    ``implausible_deflection_flags`` and ``implausible_deflection_dataset_flags`` compare with
    ``IMPLAUSIBLE_DEFLECTION_FRACTION`` (NaN stays NaN)."""
    return np.abs(np.asarray(static_peak, float)) / np.asarray(span, float)


def _implausible_words(peak: float, span: float, fraction: float) -> str:
    """"static deflection 4.5 m on a 20 m span (L/4.44) is not plausible …: check the units …" — the
    one wording of an implausible deflection (``implausible_deflection_flags`` and the datasets')."""
    share = float(implausible_deflection_share(peak, span))
    return (f"static deflection {abs(float(peak)):.3g} m on a {float(span):g} m span (L/{1 / share:.3g}) is not "
            f"plausible for a bridge under this load (flagged above L/{1 / fraction:g}; highway bridges are designed "
            f"to L/800–L/300): {IMPLAUSIBLE_DEFLECTION_ADVICE}")


def implausible_deflection_flags(span: float, static_peaks: Sequence[tuple[str, float, int | None, str | None]],
                                 fraction: float = IMPLAUSIBLE_DEFLECTION_FRACTION) -> list[Flag]:
    """One flag for the run when the largest static deflection peak [m] among ``static_peaks`` (label:
    "point p1", "Girder 2"; peak [m]; girder number or None; point name or None) exceeds ``fraction``
    of ``span`` [m] (the longest span): no bridge under a vehicle deflects that much, so the bridge's
    stiffness or mass is most likely in the wrong unit (module docstring)."""
    if not static_peaks:
        return []
    label, peak, girder, point = max(static_peaks, key=lambda s: abs(float(s[1])))
    share = float(implausible_deflection_share(peak, span))
    if not share > fraction:
        return []
    return [Flag("implausible_deflection",
                 f"{label}: {_implausible_words(peak, span, fraction)}; every result of this run depends on them",
                 output="impact_factor", subject=label, girder=girder, point=point, value=share, threshold=fraction)]


def implausible_deflection_dataset_flags(static_peaks: ArrayLike, spans: ArrayLike, names: Sequence[str] | None = None,
                                         unit: str = "crossing",
                                         describe: Callable[[tuple[int, ...]], str] | None = None,
                                         fraction: float = IMPLAUSIBLE_DEFLECTION_FRACTION) -> list[Flag]:
    """The implausible-deflection rule (``implausible_deflection_flags``) for a dataset of many
    crossings (a study's grid, a traffic stream's events): ``static_peaks`` (..., n_points) the
    static deflection peaks [m] of the response points ``names`` in every crossing (``names`` None:
    one unnamed point, and ``static_peaks`` may have the shape of ``spans``), ``spans`` (...) each
    crossing's longest span [m] (NaN: not known, not judged); ``unit``: what a crossing is called
    ("crossing", "event"); ``describe``: the words naming a crossing by its index into ``spans``
    (default: "crossing 12", the flat index).  One flag when any crossing's largest peak exceeds
    ``fraction`` of its span: how many crossings, the largest as L/n, where, and the units to check;
    value: that largest share of the span."""
    st = np.asarray(static_peaks, float)
    spans = np.asarray(spans, float)
    if st.shape == spans.shape:
        st = st[..., None]
    flat = st.reshape(-1, st.shape[-1])
    share = implausible_deflection_share(flat, spans.reshape(-1, 1))
    per_crossing = np.max(np.where(np.isnan(share), -np.inf, share), axis=1, initial=-np.inf)
    flagged = per_crossing > fraction
    if not flagged.any():
        return []
    k = int(np.argmax(per_crossing))
    p = int(np.nanargmax(share[k]))
    point = None if names is None else str(names[p])
    where = f"point {point}" if point is not None else "the response point"
    crossing = describe(tuple(int(i) for i in np.unravel_index(k, spans.shape))) if describe else f"{unit} {k}"
    return [Flag("implausible_deflection",
                 f"implausible static deflection in {int(flagged.sum())} of {flagged.size} {unit}s; the largest, at "
                 f"{where} in {crossing}: {_implausible_words(flat[k, p], spans.reshape(-1)[k], fraction)}; every "
                 f"result of those {unit}s depends on them", output="impact_factor", subject=where, point=point,
                 value=float(per_crossing[k]), threshold=fraction)]


#: where a population's remedies put their crossing keys (a traffic stream's base scenario; a lifetime file
#: passes its own [crossing] table)
BASE_SCENARIO = "the base scenario"
#: the remedy for a run-in the road cut short (``start_from_rest_flags``, ``start_unsettled_flags``)
LONGER_ROAD = "give a longer road.length (a random road) or a measured profile reaching further before the bridge"


def start_from_rest_flags(approach: float, settled: float = SETTLED_APPROACH, output: str = "impact_factor",
                          subject: str = "crossing.approach", shortened: int = 0,
                          least_approach: float = 0.0, where: str = BASE_SCENARIO) -> list[Flag]:
    """A population's events (traffic streams, a lifetime's dynamic events) start their vehicles at rest in
    static equilibrium ``approach`` [m] before the bridge (``crossing.approach`` + ``crossing.run_in``, the
    road they drive before it alone: ``vbikit.solve.run_in``; the shortest over the events): below
    ``settled`` they enter it before the start's transient has died out, calmer than trucks that have driven
    on the road for long, and the impact factors come out low (one flag about ``output``, ``subject``; none
    from ``settled`` on).  ``shortened``: events whose run-in the road cut short (a population's run-in fitted
    to a short road), named in the words with the remedy; ``least_approach`` [m]: the approach a run-in needs
    (every contact point off the deck at the start, ``vbikit.solve.run_in.RUN_IN_CLEARANCE``) when the given
    one is shorter — then the remedy is to lengthen it; ``where``: the table the remedy's keys are in."""
    if not approach < settled:
        return []
    if approach < least_approach:
        remedy = (f"for design values give crossing.approach >= {least_approach:g} m (a run-in needs every contact "
                  "point off the deck at the start), and a population's run-in then settles them")
    elif shortened:
        remedy = (f"the road was too short for the whole run-in on {counted(shortened, 'event')}: for design values "
                  f"{LONGER_ROAD}")
    else:
        remedy = (f"for design values let them drive {settled:g} m: crossing.run_in = {max(settled - approach, 0.0):g} "
                  f"in {where} (the vehicles alone on the road, no coupled steps: cheaper than a longer approach)")
    return [Flag("start_from_rest",
                 f"the events start their vehicles at rest {approach:g} m before the bridge (crossing.approach + "
                 "crossing.run_in): they enter it before their body vibration has built up, so the impact factors and "
                 f"dynamic peaks come out low (docs/traffic.md, \"Start from rest and the approach\"); {remedy}",
                 output=output, subject=subject, value=float(approach), threshold=float(settled))]


def start_unsettled_flags(events: int, worst: float, settling: float, total: int, output: str = "impact_factor",
                          subject: str = "crossing.approach", limit: float = SETTLED_TRANSIENT_LEFT,
                          run_in: float = math.nan, shortened: int = 0, where: str = BASE_SCENARIO,
                          adaptive: bool = False) -> list[Flag]:
    """A population's ``events`` (of ``total``; 0: not said) with a sprung vehicle that keeps more than ``limit`` of
    its start transient at the bridge (``vbikit.solve.run_in.start_settling``; ``worst`` the largest share kept,
    ``settling`` [m] the run-in with which every vehicle would keep at most ``limit``, the events with an undamped
    vehicle left out, NaN when not known; ``run_in`` [m] the population's run-in, ``shortened`` the events whose
    run-in the road cut short): outside the range the settled start was checked in, their impact factors may come
    out low (one flag about ``output``, ``subject``, naming that run-in — or the road, when the population's run-in
    is already as long and the road cut events short; none when no event keeps more); ``where``: the table the
    remedy's keys are in (``BASE_SCENARIO``, or a lifetime file's); ``adaptive``: the population already gave each
    event the run-in its vehicles need (``run_in_adaptive``), so what is left is the road that cut it short, a run-in
    beyond the longest allowed, or an undamped vehicle."""
    if events <= 0 or not worst > limit:
        return []
    remedies = []
    if worst >= 1.0 - 1e-9:
        remedies.append("a vehicle with an undamped mode the road excites never settles: give its suspension or tires "
                        "damping")
    if adaptive and math.isfinite(settling):
        if shortened:
            remedies.append(f"the population lengthens each event's run-in to what its vehicles need, but the road cut "
                            f"it short on {counted(shortened, 'event')}: {LONGER_ROAD}")
        elif math.ceil(settling) > MAX_RUN_IN:
            remedies.append(f"their vehicles need a run-in of {math.ceil(settling):g} m, more than the longest "
                            f"allowed ({MAX_RUN_IN:g} m): give them more damping or a longer crossing.approach, or "
                            "read their impact factors as low")
    elif math.isfinite(settling) and not math.ceil(settling) <= run_in:
        whom = "the population's other vehicles" if remedies else "every vehicle of the population"
        remedies.append(f"give crossing.run_in = {math.ceil(settling):g} m in {where} (crossing.approach as "
                        f"it is; the road must hold it: road.length), which settles {whom} to the limit")
    elif math.isfinite(settling) and shortened:
        remedies.append(f"crossing.run_in is long enough ({math.ceil(settling):g} m would do), but the road cut it "
                        f"short on {counted(shortened, 'event')}: {LONGER_ROAD}")
    if not remedies:
        remedies.append(f"drive them further before the bridge (crossing.run_in in {where})")
    remedy = "; ".join(remedies)
    of = f" of {total}" if total > 0 else ""
    return [Flag("start_unsettled",
                 f"{counted(events, 'event')}{of} {'has' if events == 1 else 'have'} a sprung vehicle that keeps "
                 f"{worst:.1%} of its start transient when it reaches the bridge (its slowest mode the road excites, "
                 f"exp(−σ_min t)), more than the {limit:.1%} the trucks the settled start was checked with kept at most "
                 "(docs/traffic.md, \"Start from rest and the approach\"): a lighter damped vehicle, or less road before "
                 f"the bridge, so those impact factors and dynamic peaks may come out low; {remedy}",
                 output=output, subject=subject, value=float(worst), threshold=float(limit))]


def join_codes(codes: Iterable[str]) -> str:
    """Flag codes as every dataset stores them (the attribute ``flag_codes``): comma-separated, each
    once, in order of first appearance ("implausible_deflection,small_static"; "" for none) — the
    one format, ``dataset_has_flag`` reads it."""
    return ",".join(dict.fromkeys(codes))


def dataset_flag_attrs(flags: Sequence[Flag]) -> dict[str, str]:
    """A population dataset's attributes from its ``flags`` (``summary_flag_attrs`` of the summary ``add_flags``
    makes of them: a flag of ``LEADING_CODES`` first): ``warnings``, every message joined by "; ", ``flag_codes``,
    the codes, comma-separated, each once, and ``flags``, the records as JSON; none when there is nothing to say."""
    summary: dict[str, Any] = {}
    add_flags(summary, flags)
    return summary_flag_attrs(summary)


def summary_flag_attrs(summary: Mapping[str, Any]) -> dict[str, str]:
    """The dataset attributes of a summary's flags (its ``flags`` records and ``warnings``, ``add_flags``'s):
    ``flag_attrs`` of them — what a run's, a random run's, a railway sweep's and every population dataset carry."""
    records = summary.get("flags", [])
    return flag_attrs(summary.get("warnings", []), [f["code"] for f in records], records)


def flag_attrs(texts: Sequence[str], codes: Iterable[str], records: Sequence[Mapping[str, Any]] = ()) -> dict[str, str]:
    """A dataset's ``warnings`` (the messages, "; "-joined), ``flag_codes`` (``join_codes``) and ``flags`` (the
    ``records``, ``Flag.as_dict``'s, as JSON: what the summaries give, ``dataset_flags``) attributes, none when there
    is nothing to say: the one format of every population dataset (``dataset_flag_attrs``; the railway sweep's from
    its checks' records)."""
    codes = list(codes)
    return ({"warnings": "; ".join(texts)} if texts else {}) | ({"flag_codes": join_codes(codes)} if codes else {}) | \
        ({"flags": json.dumps(list(records), default=_plain)} if records else {})


def _plain(value: Any) -> Any:
    """A numpy scalar in a flag record as the Python number JSON writes (``json.dumps``' ``default``)."""
    if hasattr(value, "item"):
        return value.item()
    raise TypeError(f"a flag record holds a {type(value).__name__}, which JSON does not write")


def add_dataset_flags(attrs: Mapping[str, Any], flags: Sequence[Flag]) -> dict[str, Any]:
    """A dataset's attributes ``attrs`` with ``flags`` added after the ones it carries (``flag_attrs``'s three
    attributes; a message it holds already is not repeated)."""
    records, texts = dataset_flags(attrs)
    codes = dataset_flag_codes(attrs)
    legacy = f"; {texts[0]}; " if texts and not records else None  # (a dataset written before the records)

    def known(message: str) -> bool:  # (one of the joined messages of a dataset without records)
        return message in texts or (legacy is not None and f"; {message}; " in legacy)

    new = [f for f in flags if not known(f.message)]
    if not new:
        return dict(attrs)
    if legacy is not None:  # its joined messages kept as one record
        records = [{"code": None, "message": texts[0]}]
    joined = [str(attrs["warnings"])] if attrs.get("warnings") else []  # (as stored: messages may hold "; ")
    return {**attrs, **flag_attrs(joined + [f.message for f in new], codes + [f.code for f in new],
                                  records + [f.as_dict() for f in new])}


def dataset_flags(attrs: Mapping[str, Any]) -> tuple[list[dict[str, Any]], list[str]]:
    """The flag records a population dataset's attributes carry (``flag_attrs``' ``flags``) and their messages, as
    every summary gives them (``flags``, ``warnings``); for a dataset written before the records were stored, none
    and its "; "-joined ``warnings`` as one message."""
    records = json.loads(attrs["flags"]) if attrs.get("flags") else []
    if records:
        return records, [str(r["message"]) for r in records]
    return [], [str(attrs["warnings"])] if attrs.get("warnings") else []


def dataset_flag_codes(attrs: Mapping[str, Any]) -> list[str]:
    """The flag codes a dataset's attributes carry (``flag_codes``, ``join_codes``' format), in their order."""
    return [c for c in str(attrs.get("flag_codes", "")).split(",") if c]


def dataset_has_flag(attrs: Mapping[str, Any], code: str) -> bool:
    """Whether a population dataset's attributes (``dataset_flag_attrs``: ``flag_codes``,
    comma-separated, ``join_codes``; a lifetime dataset's alike) carry ``code``."""
    _check_code(code)
    return code in dataset_flag_codes(attrs)


def effect_static_flags(effects: Sequence[tuple[str, str, str, float, float]]) -> list[Flag]:
    """The small-static rule (``small_static``) for load effects: ``effects`` as (kind, label, units,
    static peak, impact factor), each kind (moment, shear, reaction) judged against the largest static
    peak of its own kind among them (a moment of Girder 1 against that of Girder 4, never against a
    shear); one flag per flagged effect, as ``small_static_flags`` words it for deflections."""
    out = []
    for kind in dict.fromkeys(k for k, *_ in effects):
        same = [e for e in effects if e[0] == kind]
        if len(same) < 2:
            continue
        peaks = [abs(float(e[3])) for e in same]
        k = int(np.argmax(peaks))
        out += [Flag("small_static",
                     f"{label}: IM = {im:.3g} rests on a static {kind} of {abs(float(st)):.4g} {units}, "
                     f"{abs(float(st)) / peaks[k]:.0%} of the largest {kind} of the run's load effects "
                     f"({peaks[k]:.4g} {units}, {same[k][1]}; flagged below {SMALL_STATIC_FRACTION:.0%}): a lightly "
                     "loaded section, where a small dynamic increment divided by a small static response gives a "
                     "large IM; unreliable as a design value", output=kind, subject=label,
                     value=abs(float(st)) / peaks[k], threshold=SMALL_STATIC_FRACTION)
                for (_, label, units, st, im), flag in zip(same, small_static(peaks)) if flag]
    return out


def small_static_dataset_flags(names: Sequence[str], static_peaks: np.ndarray) -> list[Flag]:
    """The flags of a dataset of many crossings (its attributes, not a summary): ``static_peaks`` (..., n_points)
    the static peak deflections of the points ``names`` in every crossing; one ``small_static`` flag per point
    whose impact factor rests on a small static reference (``small_static`` across the points of a crossing) in
    some of the crossings, with how many (``point`` its name, ``value`` the smallest share of the largest static
    peak it had, ``threshold`` ``SMALL_STATIC_FRACTION``)."""
    st = np.asarray(static_peaks, float).reshape(-1, np.shape(static_peaks)[-1])
    flags = small_static_mask(st, axis=1)
    largest = np.nanmax(np.abs(st), axis=1, keepdims=True, initial=0.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        share = np.where(flags, np.abs(st) / largest, np.inf)  # (a NaN peak elsewhere in the crossing: not the largest)
    return [Flag("small_static", f"point {name}: its impact_factor rests on a static deflection under "
                 f"{SMALL_STATIC_FRACTION:.0%} of the largest of the points in {int(k)} of {flags.shape[0]} crossings "
                 "(a lightly loaded section); unreliable there as a design value", output="impact_factor",
                 point=str(name), value=float(np.min(share[:, j])), threshold=SMALL_STATIC_FRACTION)
            for j, (name, k) in enumerate(zip(names, flags.sum(axis=0))) if k]


def realisation_flags(crossing: Crossing) -> list[Flag]:
    """One flag when the crossing's road is a random realisation (``RoadProfile.origin`` of kind
    "random": an ISO 8608 / paper class or a PSD, with its seed; with or without defects): its impact
    factors are those of that one road and scatter between seeds (their mean and σ: ``vbikit run
    --random``, docs/random.md), so they are not the road class's IM.
    Smooth roads, measured profiles and defects alone are deterministic: no flag.  A single-crossing
    check only (``run_flags``): a random run (PEM) or a study over seeds is the remedy, not the case."""
    road = crossing.road
    o = road.origin if road is not None else None
    if o is None or o.kind != "random" or not np.any(road.z):  # a PSD of level 0 is a smooth road
        return []
    return [Flag("one_realisation",
                 f"one road realisation: the impact factors are those of one realisation of the {road_origin(road)}; "
                 f"another seed of the same road gives another road and other impact factors (they scatter between "
                 f"realisations), so this IM alone is not the road class's value; for the mean, σ and quantiles over "
                 f"realisations run `vbikit run --random` on the scenario, or a study over seeds "
                 f"(\"road.seed\" = {{ samples = N }})", output="impact_factor",
                 subject="road.seed", value=None if o.seed is None else float(o.seed))]


#: what a ``contact_not_converged`` flag advises
UNCONVERGED_ADVICE = ("the states after those steps carry a contact-force error above the tolerance; run again with a "
                      "shorter crossing.dt (a stiff, heavily damped tire on a light wheel needs one), or check with "
                      "integrator = \"rk4\", which does not iterate")


def convergence_flags(result: CrossingResult) -> list[Flag]:
    """One flag when the implicit integrator's contact forces did not settle in some steps
    (``CrossingResult.unconverged_steps``)."""
    n = int(result.unconverged_steps)
    if n <= 0:
        return []
    dt = result.integration_dt or result.dt
    steps = max(int(round((float(result.time[-1]) - float(result.time[0])) / dt)), 1)
    return [Flag("contact_not_converged",
                 f"the contact forces did not converge in {n} of the run's {steps} time steps: {UNCONVERGED_ADVICE}",
                 output="unconverged_steps", value=float(n), threshold=0.0)]


def strain_mode_dataset_flags(errors: ArrayLike, names: Sequence[str] | None = None,
                              describe: Callable[[tuple[int, ...]], str] | None = None) -> list[Flag]:
    """``strain_convergence_flags``' rule over a study's crossings: ``errors`` (..., points) each crossing's relative
    error of the modes' static strain peak against the exact one per response point (NaN: not known;
    ``names``: the points' names, None for the one [response] point); one ``strain_not_converged`` flag when any is
    beyond ``STRAIN_MODE_TOLERANCE``: how many crossings, the worst, its point and crossing (``describe``)."""
    e = np.asarray(errors, float)
    bad = np.abs(np.nan_to_num(e, nan=0.0)) > STRAIN_MODE_TOLERANCE
    if not bad.any():
        return []
    k = int(np.argmax(np.abs(np.nan_to_num(e, nan=0.0))))
    index = tuple(int(i) for i in np.unravel_index(k, e.shape))
    point = None if names is None else str(names[index[-1]])
    crossing = describe(index[:-1]) if describe else f"crossing {k // e.shape[-1]}"
    n_bad, n = int(bad.any(axis=-1).sum()), int(np.prod(e.shape[:-1], dtype=np.int64))
    where = f" at point {point}" if point else ""
    return [Flag("strain_not_converged",
                 f"strain not converged in the modes in {n_bad} of {counted(n, 'crossing', thousands=True)}: the static "
                 f"strain peak of the modes is up to {float(e.reshape(-1)[k]):+.1%} off the exact one{where} "
                 f"({crossing}; flagged beyond {STRAIN_MODE_TOLERANCE:.0%}): those crossings' strain and strain IM "
                 "are not reliable; use more modes (bridge.n_modes) or the moment's IM (vbikit run of such a crossing "
                 "says more)", output="strain_impact_factor", point=point, value=float(e.reshape(-1)[k]),
                 threshold=STRAIN_MODE_TOLERANCE)]


def unconverged_dataset_flags(counts: ArrayLike, unit: str = "crossing",
                              describe: Callable[[tuple[int, ...]], str] | None = None,
                              plural: str | None = None) -> list[Flag]:
    """The ``contact_not_converged`` rule over a dataset of many crossings (a study's grid, a traffic
    stream's events, a drive-by sweep's passes): ``counts`` (...) each crossing's ``unconverged_steps``
    (NaN: not known); one flag when any is above 0: how many crossings, the worst and its count
    (``describe``: the words naming a crossing by its index into ``counts``; default "crossing 12",
    the flat index; ``unit`` / ``plural`` the noun, ``plural`` where adding "s" is wrong)."""
    c = np.nan_to_num(np.asarray(counts, float), nan=0.0)
    flagged = c > 0.0
    if not flagged.any():
        return []
    k = int(np.argmax(c))
    index = tuple(int(i) for i in np.unravel_index(k, c.shape))
    worst = describe(index) if describe else f"{unit} {k}"
    return [unconverged_runs_flag(int(flagged.sum()), counted(c.size, unit, plural), float(c.reshape(-1)[k]), worst,
                                  variable="unconverged_steps", output="unconverged_steps")]


def unconverged_runs_flag(flagged: int, total: str, most: float, worst: str, variable: str | None = None,
                          output: str = "unconverged_steps", subject: str | None = None) -> Flag:
    """The ``contact_not_converged`` flag of many runs, in one wording: ``flagged`` runs of ``total``
    (their count and noun, "40 coupled runs") had steps whose contact forces did not converge, the
    most ``most`` steps in ``worst`` (the words naming that run); ``variable``: the dataset variable
    holding each run's count, if there is one."""
    where = f"variable {variable}; " if variable else ""
    return Flag("contact_not_converged",
                f"the contact forces did not converge in some time steps of {flagged} of {total} ({where}the most: "
                f"{counted(int(most), 'step')} in {worst}): {UNCONVERGED_ADVICE}", output=output, subject=subject,
                value=float(most), threshold=0.0)


def run_flags(result: CrossingResult, response_x: float | None = None, response_y: float | None = None) -> list[Flag]:
    """Every flag about a finished crossing: its inputs, its contact losses, wheels airborne long
    enough to dominate the impact factors, steps whose contact forces did not converge
    (``convergence_flags``) and a random road's one realisation (``realisation_flags``)."""
    return (input_flags(result.crossing, result.dt, response_x, response_y)
            + resolve_flags(result.crossing, float(result.integration_dt or result.dt)) + contact_flags(result)
            + airborne_flags(result) + wheel_force_step_flags(result) + convergence_flags(result)
            + realisation_flags(result.crossing))
