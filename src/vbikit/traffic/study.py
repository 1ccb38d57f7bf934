"""A traffic stream over a bridge: every event simulated, stored and resumable like a study.

``traffic_study`` cuts the stream of [`VehicleRecord`][vbikit.traffic.VehicleRecord] into
events ([`partition`][vbikit.traffic.partition]) and returns a ``TrafficStudy``, a job of
the study machinery ([`vbikit.study.run.run_study`][vbikit.study.run_study]: batches of events on local processes or
a Dask cluster, each finished batch stored at once, a killed run resumed where it stopped).

Each event is one several-vehicle crossing ([`Crossing`][vbikit.solve.Crossing] with its
vehicles): the bridge, tire, road class, crossing options and response point of a base
scenario; vehicle i enters at its record's time minus the event's first entry; its lateral
offset is the record's, or the centre of its lane.  Every event gets its own random road,
seeded by ``derive_seed(seed, event index)`` (a measured road is the same for every event), so
a result depends only on the stream, the base scenario and the seed.  The bridge starts every
event at rest.

The dataset (xarray, NetCDF): per event (dimension ``event``) its first vehicle, vehicle count,
multiple presence, gross weight, static and dynamic peaks and impact factors at the response
point; per vehicle (dimension ``vehicle``) its record and event, gross weight, smallest wheel
force and contact loss; the stream's statistics as attributes (``stream_statistics``).
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import logging
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Optional, Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit._files import input_digests, shared_name, shared_spec
from vbikit.analysis.checks import Flag, airborne_wheels, unconverged_dataset_flags
from vbikit.analysis.population_start import start_attrs, start_flags
from vbikit.analysis.plan import ResponsePlan
from vbikit.analysis.response import reduce_crossing
from vbikit.bridge.base import GirderDeck
from vbikit.outputs import OUTPUTS, QUALITY_OUTPUTS, base_resolve, outputs, select_outputs
from vbikit.scenario.build import BuiltScenario, build, build_right_road, build_road, with_scenario_road
from vbikit.scenario.schema import Scenario, ScenarioError, input_paths, parse_scenario
from vbikit.solve import Crossing, VehicleMotion, simulate
from vbikit.solve.run_in import (RUN_IN_CLEARANCE, START_OUTPUTS, lengthened_run_in, least_run_in_approach,
                                 population_run_in, run_in_problem, settling, start_settling)
from vbikit.study.compute import point_names, stack_outputs
from vbikit.study.shipping import reduce_once
from vbikit.study.spec import StudyError, derive_seed
from vbikit.traffic.accuracy import governing_step_check
from vbikit.traffic.base import BASE_SECTIONS, base_scenario, template_data  # noqa: F401 (base_scenario: re-exported)
from vbikit.traffic.events import Event, partition
from vbikit.traffic.records import VehicleRecord
from vbikit.vehicle.axles import axle_truck
from vbikit.vehicle.model import Vehicle
from vbikit.vehicle.presets import VEHICLE_PRESETS

log = logging.getLogger(__name__)


#: per-event outputs beside the catalogue's (vbikit.outputs): name -> (units, description, stored dtype)
EVENT_EXTRAS: dict[str, tuple[str, str, type]] = {
    "road_seed": ("1", "seed of the event's random road (derive_seed(seed, event)); -1 for a measured or smooth road",
                  np.int64),
    "airborne_wheels": ("1", "1 if a wheel was airborne on the bridge for more than 5 % of its time there (the single "
                             "run's airborne_wheels rule): the event's impact factors are dominated by point-contact "
                             "impacts, not design values", np.int64),
    "run_in": ("m", "road the event's sprung vehicles drove alone, from rest, before the run started "
                    "(crossing.run_in: vbikit.solve.run_in; the stream's own, longer where its vehicles needed more to "
                    "settle (run_in_adaptive), or the part of it the road holds; NaN for moving forces, which have "
                    "no vibration to build up)", np.float64),
    **{name: (unit, meaning, np.float64) for name, (unit, meaning) in START_OUTPUTS.items()},
}
#: per-event extras that need no simulation (a function of the event's crossing, ``start_transient_left``): a part
#: written before they were stored is still used, and they are computed for its events when the dataset is assembled
COMPUTED_EXTRAS = tuple(START_OUTPUTS)
#: the catalogue's outputs every stream reduces, whatever it asks for: its statistics
#: (``stream_statistics``) and figure read them, the resume check reads the step counts, the dataset's
#: flags read the events' quality (``vbikit.outputs.QUALITY_OUTPUTS``)
STREAM_OUTPUTS = ("impact_factor", "max_dynamic_displacement", "max_static_displacement", "n_steps", *QUALITY_OUTPUTS)
#: per-vehicle outputs
VEHICLE_OUTPUTS: dict[str, tuple[str, str]] = {
    "vehicle_min_wheel_force": ("N", "the vehicle's smallest wheel force in its event"),
    "vehicle_contact_loss": ("1", "1 if a tire of the vehicle lost contact in its event"),
}


#: events planned by the budget check for each of its size measures (``TrafficStudy.check_budget``)
BUDGET_CANDIDATES = 3


def default_lanes(bridge) -> tuple[float, ...]:
    """Lane centres y [m] when the records give lane numbers: [substitute] two lanes at ∓ deck
    width / 4 (lane 1 at y < 0: on the right of +x traffic) on a deck; one line at y = 0 on a
    beam (no width)."""
    width = bridge.deck_width if isinstance(bridge, GirderDeck) else None
    if width is None:
        return (0.0,)
    return (-float(width) / 4.0, float(width) / 4.0)


def _vehicle(record: VehicleRecord) -> Vehicle:
    if record.model == "axles":
        return axle_truck(record.axle_loads, record.axle_spacings)
    return VEHICLE_PRESETS[record.model].build()


@dataclass(frozen=True)
class TrafficStudy:
    """A stream and what to run it on (build with ``traffic_study``).

    ``records``: the stream; ``base``: the base scenario's sections (``BASE_SECTIONS``);
    ``base_dir``: where its relative paths point (not part of the job's identity, ``to_json``: the files
    it reads are, by their content, ``input_sha256``); ``lanes``: lane centres y [m] (lane n at
    ``lanes[n - 1]``); ``seed``: the road seeds' source; ``batch_size``: events per batch;
    ``events``: the vehicles of each event (indices into ``records``), ``event_start`` and
    ``event_end`` [s] their first entry and last exit (``partition``'s); ``source``: the records' name (reports and errors; the dataset's ``records`` attribute: as given,
    an absolute path by its name only, ``vbikit._files.shared_name``); ``outputs``: the catalogue's outputs to
    reduce and store (``STREAM_OUTPUTS`` always among them; None: all).
    """

    records: tuple[VehicleRecord, ...]
    base: dict
    base_dir: str
    lanes: tuple[float, ...]
    seed: int
    batch_size: int
    events: tuple[tuple[int, ...], ...]
    event_start: tuple[float, ...]
    name: str = ""
    source: str = ""
    _digest: str = field(default="", repr=False)
    outputs: Optional[tuple[str, ...]] = None
    #: each event's last exit [s] (``partition``'s ``Event.end``) and each record's vehicle size in the
    #: budget's memory terms (3 n_dof + 2 n_wheels, ``vbikit.solve.budget.estimate_run``): the budget
    #: check's candidates
    event_end: tuple[float, ...] = ()
    vehicle_size: tuple[int, ...] = ()
    #: the budget of one event's run (``vbikit.solve.budget.Limits``; None: the defaults); not part of the
    #: job's identity (``to_json``): a resumed stream may be given another
    limits: Any = field(default=None, repr=False, compare=False)
    #: the SHA-256 of each file the base scenario reads (``vbikit.scenario.schema.INPUT_FILE_KEYS``: a
    #: bridge's modes_file, a measured road), by key: ``traffic_study``'s (key, digest) pairs
    input_sha256: tuple[tuple[str, str], ...] = field(default=(), repr=False)

    #: sent to workers as bytes made once, rebuilt once per worker (``vbikit.study.shipping``)
    __reduce__ = reduce_once

    # ------------------------------------------------------------ the job protocol of run_study
    @property
    def size(self) -> int:
        """Number of events."""
        return len(self.events)

    def batches(self) -> list[tuple[int, ...]]:
        """Event indices of each batch."""
        return [tuple(range(k, min(k + self.batch_size, self.size))) for k in range(0, self.size, self.batch_size)]

    @property
    def output_names(self) -> Optional[tuple[str, ...]]:
        """The catalogue's outputs each event reduces, in catalogue order (None: all of them)."""
        return None if self.outputs is None else tuple(o.name for o in outputs(names=self.outputs))

    def to_json(self) -> str:
        """Canonical text of the job (the resume check, and the dataset's ``study`` attribute): base
        scenario, lanes, seed, batch size, the SHA-256 of the records and of every file the base scenario
        reads (``input_sha256``; absent when it reads none) and the outputs (when not all).  No folder: the
        inputs are identified by their content, so a moved project folder still resumes and a changed
        modes or profile file does not; an absolute path in the base is stored by its file name
        (``vbikit._files.shared_spec``), so a shared dataset does not carry the machine's folders."""
        return self._identity(earlier=False)

    def earlier_json(self) -> tuple[str, ...]:
        """The job's identity as a dataset written before 2026-12-06 holds it (the base scenario's folder,
        ``base_dir``, in place of its files' content): such a finished dataset is still recognised
        (``vbikit.study.run``), as it was then."""
        return (self._identity(earlier=True),)

    def _identity(self, earlier: bool) -> str:
        where = {"base": self.base, "base_dir": self.base_dir} if earlier else \
            {"base": shared_spec(self.base), **({"input_sha256": dict(self.input_sha256)} if self.input_sha256 else {})}
        ctx = self.context()  # (the population's run-in, which the base does not hold: a stream at rest is not this one)
        settled = {} if earlier or not ctx.settled else {"population_run_in": float(ctx.template.crossing.run_in)}
        return json.dumps({"kind": "vbikit traffic", "name": self.name, **where, **settled,
                           "lanes": list(self.lanes), "seed": self.seed, "batch_size": self.batch_size,
                           "records_sha256": self._digest, "n_records": len(self.records),
                           **({"outputs": list(self.output_names)} if self.outputs is not None else {})},
                          sort_keys=True)

    def run_batch(self, batch: tuple[int, ...], threads: int = 1) -> dict[str, NDArray]:
        """Simulate the events ``batch``; arrays per event (the catalogue's outputs, [`vbikit.outputs`][vbikit.outputs],
        per response point where they are per point — those of ``output_names``; ``EVENT_EXTRAS``;
        ``event``) and per vehicle of those events (``VEHICLE_OUTPUTS``, ``vehicle``)."""
        rows, vehicle_rows = [], []
        for e in batch:
            row, per_vehicle = self.run_event(e)
            rows.append(row)
            vehicle_rows += per_vehicle
        out = stack_outputs(rows, self.output_names) | {k: np.array([r[1][k] for r in rows], float) for k in EVENT_EXTRAS}
        out["event"] = np.array(batch, np.int64)
        out["vehicle"] = np.array([i for e in batch for i in self.events[e]], np.int64)
        for k in VEHICLE_OUTPUTS:
            out[k] = np.array([r[k] for r in vehicle_rows], float)
        return out

    def part_problem(self, part, batch: tuple[int, ...]) -> Optional[str]:
        """Why a stored part cannot be used for ``batch`` (None if it can)."""
        from vbikit.study.run import output_problem

        if not np.array_equal(part["event"], np.array(batch, np.int64)):
            return "its events are not those of this batch"
        members = [i for e in batch for i in self.events[e]]
        if not np.array_equal(part["vehicle"], np.array(members, np.int64)):
            return "its vehicles are not those of its events"
        problem = output_problem(part, len(batch), len(self.point_names or [None]), self.output_names)
        if problem:
            return problem
        for name in EVENT_EXTRAS:
            if name not in part:
                if name in COMPUTED_EXTRAS:
                    continue  # (computed when the dataset is assembled)
                return f"it has no {name} (written by an earlier version)"
            if part[name].shape != (len(batch),):
                return f"{name} has the wrong shape"
        for name in VEHICLE_OUTPUTS:
            if part[name].shape != (len(members),):
                return f"{name} has the wrong shape"
        if not np.all(np.isfinite(part["n_steps"])) or np.any(part["n_steps"] < 1):
            return "its step counts are not valid"
        return run_in_problem(part["run_in"], [self.crossing(int(e), road=False).run_in for e in batch])

    def assemble(self, parts: Path):
        """The stream's Dataset from the finished parts."""
        from vbikit.study.run import part_output
        from vbikit.study.storage import load_part, part_checksums

        n_e, n_v = self.size, len(self.records)
        n_points = len(self.point_names or [None])
        ev = {o.name: np.full((n_e, n_points) if o.scope == "point" else n_e, np.nan)
              for o in outputs(names=self.output_names)}
        ev |= {k: np.full(n_e, np.nan) for k in EVENT_EXTRAS}
        veh = {k: np.full(n_v, np.nan) for k in VEHICLE_OUTPUTS}
        sums = part_checksums(parts)
        for k in range(len(self.batches())):
            part = load_part(parts, k, sums)
            if any(name not in part for name in COMPUTED_EXTRAS):  # (a part written before they were stored)
                ctx = self.context()  # (judged with the run-in each event ran with)
                computed = np.array([ctx.start_settling(self.crossing(int(e), road=False), float(r))
                                     for e, r in zip(part["event"], part["run_in"])], float)
                part = {**part, **dict(zip(COMPUTED_EXTRAS, computed.reshape(-1, 2).T))}
            for name in ev:
                ev[name][part["event"]] = part_output(part, name, n_points) if name in OUTPUTS else part[name]
            for name in VEHICLE_OUTPUTS:
                veh[name][part["vehicle"]] = part[name]
        return self.dataset(ev, veh)

    # ------------------------------------------------------------ one event
    def context(self) -> "EventContext":
        """Bridge, tire, roads and response point of the base scenario (built once per process)."""
        key = self.__dict__.get("_context_key")
        if key is None:  # (the job is immutable: its key is written once)
            key = json.dumps([self.base, self.base_dir], sort_keys=True)
            object.__setattr__(self, "_context_key", key)
        if key not in _CONTEXTS:
            _CONTEXTS.clear()
            _CONTEXTS[key] = EventContext.of(self.base, self.base_dir)
        return _CONTEXTS[key]

    def crossing(self, e: int, road: bool = True) -> Crossing:
        """The several-vehicle crossing of event ``e`` (without ``road``: before its road is made,
        ``EventContext.bare_crossing``)."""
        ctx = self.context()
        motions = []
        t0 = self.event_start[e]
        for i in self.events[e]:
            r = self.records[i]
            y = r.lateral_offset if r.lateral_offset is not None else self.lanes[r.lane - 1]
            motions.append(VehicleMotion(_vehicle(r), speed=r.speed, direction=r.direction, entry_time=r.time - t0,
                                         lateral_offset=y))
        return ctx.crossing(tuple(motions), self.road_seed(e)) if road else ctx.bare_crossing(tuple(motions))

    def check_budget(self) -> None:
        """The runs of the stream's largest events planned against ``limits`` before any event is
        simulated; above them a ``StudyError`` naming the event's first record (was: the events before it
        simulated, then the budget's refusal naming no record).  A run's steps grow with its length (from
        its start, ``Crossing.start_time``: the latest time every vehicle is ``approach`` before its entry,
        to its last exit, ``partition``'s end) and, where the road sets the step, its top speed; its memory
        with those and its vehicles' sizes: the events first by each of those products
        (``BUDGET_CANDIDATES`` each, longest first) are planned, the others are smaller on every count."""
        from vbikit.solve.budget import BudgetError
        from vbikit.solve.plan import plan_run

        if len(self.event_end) != self.size or len(self.vehicle_size) != len(self.records):
            raise StudyError("a TrafficStudy's event ends and vehicle sizes come from traffic_study(): build it with that")
        approach = self.context().template.crossing.approach
        length = np.array([self.event_end[e] - min(self.records[i].time - approach / self.records[i].speed
                                                   for i in self.events[e]) for e in range(self.size)])
        top_speed = np.array([max(self.records[i].speed for i in ev) for ev in self.events])
        size = np.array([sum(self.vehicle_size[i] for i in ev) for ev in self.events])
        ranked = []
        for key in (length, length * top_speed, length * size, length * top_speed * size):
            ranked += [int(e) for e in np.argsort(-key, kind="stable")[:BUDGET_CANDIDATES]]
        for e in sorted(dict.fromkeys(ranked), key=lambda e: -length[e]):
            try:
                plan_run(self.crossing(e), self.limits)
            except (BudgetError, ValueError) as err:  # (above the budget; a road shorter than the event)
                r = self.records[self.events[e][0]]
                where = f"{self.source or 'records'}:{r.line}" if r.line else f"record {r.id or '?'}"
                what = "is above the budget of one event" if isinstance(err, BudgetError) else "cannot run"
                raise StudyError(f"{where}: an event of the stream ({len(self.events[e])} vehicle(s) from this record "
                                 f"on) {what}: {err}") from None

    def road_seed(self, e: int) -> int:
        """Seed of event ``e``'s random road (−1 if the base road is not random; the last event's kept:
        ``run_event`` asks for it twice)."""
        last = self.__dict__.get("_last_road_seed")
        if last is not None and last[0] == e:
            return last[1]
        seed = derive_seed(self.seed, e) if self.context().random_road else -1
        object.__setattr__(self, "_last_road_seed", (e, seed))  # (the job is immutable: a function of e)
        return seed

    @property
    def point_names(self) -> list[str] | None:
        """Names of the base scenario's [[response.points]] (None for the [response] shorthand)."""
        return point_names(self.base)

    def run_event(self, e: int) -> tuple[tuple[list[dict], dict], list[dict[str, float]]]:
        """Simulate event ``e``: its outputs (per response point, per event) and those of each of its vehicles."""
        result = simulate(self.crossing(e), limits=self.limits)
        points, row = reduce_crossing(result, self.context().plan, names=self.output_names)
        row["road_seed"] = float(self.road_seed(e))
        row["airborne_wheels"] = float(bool(airborne_wheels(result)))
        crossing = result.crossing
        row["run_in"] = float(crossing.run_in) if any(m.vehicle.n_dof for m in crossing.vehicles) else math.nan
        row["start_transient_left"], row["start_settling_run_in"] = start_settling(crossing)
        forces = result.wheel_forces
        offsets = result.crossing.vehicle.wheel_offsets
        per_vehicle = []
        for j in range(len(self.events[e])):
            f = forces[:, offsets[j]:offsets[j + 1]]
            per_vehicle.append({"vehicle_min_wheel_force": float(f.min()), "vehicle_contact_loss": float(np.any(f <= 0.0))})
        return (points, row), per_vehicle

    # ------------------------------------------------------------ the dataset
    def dataset(self, ev: dict[str, NDArray], veh: dict[str, NDArray]):
        import xarray as xr

        from vbikit._version import __version__

        recs = self.records
        n_veh = np.array([len(m) for m in self.events], np.int64)
        vehicle_event = np.empty(len(recs), np.int64)
        for e, members in enumerate(self.events):
            vehicle_event[list(members)] = e
        gross = np.array([_gross(r) for r in recs])
        event_gross = np.array([gross[list(m)].sum() for m in self.events])
        variables: dict[str, Any] = {}
        from vbikit.study.run import output_variables

        names = self.point_names
        variables |= output_variables(ev, ["event"], names, self.output_names)
        for name, (units, desc, dtype) in EVENT_EXTRAS.items():
            variables[name] = ("event", ev[name].astype(dtype), {"units": units, "long_name": desc})
        variables["event_start"] = ("event", np.array(self.event_start), {"units": "s", "long_name": "first entry of the event's vehicles (record time; on a skew deck the earliest record time minus reach / speed, when a wheel can first touch the deck's oblique end)"})
        variables["n_vehicles"] = ("event", n_veh, {"units": "1", "long_name": "vehicles in the event"})
        variables["multiple_presence"] = ("event", (n_veh > 1).astype(np.int8), {"units": "1", "long_name": "1 if several vehicles were on the bridge together"})
        variables["event_gross_weight"] = ("event", event_gross, {"units": "N", "long_name": "sum of the event's vehicles' weights"})
        variables["first_vehicle"] = ("event", np.array([m[0] for m in self.events], np.int64), {"long_name": "index of the event's first vehicle"})
        vehicle_vars = {
            "vehicle_event": (vehicle_event, "1", "the vehicle's event"),
            "vehicle_time": (np.array([r.time for r in recs]), "s", "record time (front axle at its entry support)"),
            "vehicle_lane": (np.array([r.lane if r.lane is not None else 0 for r in recs], np.int64), "1", "lane (0: lateral offset given)"),
            "vehicle_lateral_offset": (np.array([r.lateral_offset if r.lateral_offset is not None else self.lanes[r.lane - 1]
                                                 for r in recs]), "m", "centreline y from the deck centreline"),
            "vehicle_direction": (np.array([1 if r.direction == "+x" else -1 for r in recs], np.int8), "1", "+1 drives +x, -1 drives -x"),
            "vehicle_speed": (np.array([r.speed for r in recs]), "m s-1", "speed"),
            "vehicle_gross_weight": (gross, "N", "gross weight (sum of the static axle loads)"),
            "vehicle_n_axles": (np.array([len(r.axle_loads) for r in recs], np.int64), "1", "number of axles (0: a preset vehicle)"),
        }
        for name, (arr, units, desc) in vehicle_vars.items():
            variables[name] = ("vehicle", arr, {"units": units, "long_name": desc})
        for name, (units, desc) in VEHICLE_OUTPUTS.items():
            arr = veh[name].astype(np.int8) if name == "vehicle_contact_loss" else veh[name]
            variables[name] = ("vehicle", arr, {"units": units, "long_name": desc})
        coords = {"event": np.arange(self.size), "vehicle": np.arange(len(recs)),
                  **({"point": np.array(names, dtype=object)} if names is not None else {}),
                  "vehicle_id": ("vehicle", np.array([r.id or f"line{r.line}" for r in recs], dtype=object))}
        ds = xr.Dataset(variables, coords=coords)
        stats = stream_statistics(ds)
        first = ds.isel(point=0) if "point" in ds.dims else ds
        impact = {name: first[name].values for name in first.data_vars if str(name).endswith("impact_factor")}
        step_attrs, step_flags = governing_step_check(self, stats, impact)
        start = self.context().template.crossing  # (where its events start their vehicles: approach, run_in)
        started = start_attrs(start.approach, start.run_in, ev["run_in"], self.context().least_approach,
                              ev["start_transient_left"], ev["start_settling_run_in"], adaptive=self.context().lengthens)
        ds.attrs = {
            "title": self.name or "vbikit traffic stream",
            "study": self.to_json(),
            "records": shared_name(self.source),  # (as given; an absolute path by its name only)
            "vbikit_version": __version__,
            "Conventions": "CF-1.8",
            **{k: (json.dumps(v) if isinstance(v, (list, dict)) else v) for k, v in stats.items()},
            **step_attrs,
            **started,
            **self.flag_attrs(ev["max_static_displacement"], airborne_dataset_flags(ev["airborne_wheels"]) + step_flags
                              + open_interval_flags(stats)
                              + unconverged_dataset_flags(ev["unconverged_steps"], "event")
                              + start_flags(started, total=self.size)),
        }
        return ds

    @property
    def settles_vehicles(self) -> bool:
        """Whether the events drive their vehicles a run-in first (``crossing.run_in`` > 0: the compiled run-in
        loops, ``vbikit.study.run.batch_kernels``)."""
        return self.context().template.crossing.run_in > 0.0

    def flag_attrs(self, static_peaks: NDArray, flags: Sequence[Flag] = ()) -> dict[str, str]:
        """The dataset's ``warnings`` and ``flag_codes`` (``vbikit.analysis.checks.dataset_flag_attrs``)
        of ``flags`` (airborne wheels, ``airborne_dataset_flags``; the governing events' step check,
        ``vbikit.traffic.accuracy``) and of an event's
        static deflection peak ``static_peaks`` (events, points) [m] implausible for the bridge's
        longest span (``implausible_deflection_dataset_flags``), and ``flags``: their records as JSON
        (``vbikit.analysis.checks.add_flags``: code, message, output, subject, value, threshold), which
        ``traffic-summary.json`` gives as every summary does; none when there is nothing to say."""
        from vbikit.analysis.checks import dataset_flag_attrs, implausible_deflection_dataset_flags

        span = max(self.context().template.crossing.bridge.span_lengths)
        spans = np.full(static_peaks.shape[0], float(span))
        return dataset_flag_attrs(implausible_deflection_dataset_flags(static_peaks, spans, self.point_names, "event")
                                  + list(flags))


def open_interval_flags(stats: dict[str, Any], confidence: float = 0.95) -> list[Flag]:
    """``interval_not_bounded`` for each IM statistic of ``stream_statistics`` with an end of its confidence interval
    that its events cannot bound (NaN, the estimate finite): said in words in the dataset, the summary and the report
    (a trial's 12-event stream gave im_q95_ci_upper NaN with no word outside the CLI's "?").  The values an end needs:
    a mean's Student-t interval 2; the order-statistic interval of the p quantile at ``confidence`` needs an order
    statistic beyond it with the binomial tail ≥ (1 + confidence) / 2, n ≥ ln((1 − c)/2) / ln p (upper end) or
    / ln(1 − p) (lower end): 72 for the 95 % quantile's upper end."""
    counts = {"im_mean": stats["n_events"] - stats["n_events_without_impact_factor"],
              "im_q95": stats["n_events"] - stats["n_events_without_impact_factor"]}
    counts |= {f"{k}_loaded": n - stats["n_small_static_events"] for k, n in counts.items()}
    tail = math.log((1.0 - confidence) / 2.0)
    flags = []
    for name, n in counts.items():
        if not math.isfinite(float(stats.get(name, math.nan))):
            continue
        for end in ("lower", "upper"):
            if math.isfinite(float(stats.get(f"{name}_ci_{end}", math.nan))):
                continue
            p = 0.95 if "q95" in name else None
            need = 2 if p is None else math.ceil(tail / math.log(p if end == "upper" else 1.0 - p))
            flags.append(Flag("interval_not_bounded",
                              f"{name}: its {n} events cannot bound the {end} end of its {100 * confidence:g} % confidence "
                              f"interval (about {need} are needed): {name} = {float(stats[name]):.4f} is an estimate "
                              "without a stated accuracy at that end; run a longer stream",
                              output=name, value=float(n), threshold=float(need)))
    return flags


def airborne_dataset_flags(airborne: NDArray) -> list[Flag]:
    """The single run's ``airborne_wheels`` rule over a stream's events (``airborne``: 1 for an event
    with a wheel airborne on the bridge for more than ``AIRBORNE_FRACTION`` of its time there): one
    flag counting them, their impact factors not design values; none when no event is."""
    from vbikit.analysis.checks import AIRBORNE_FRACTION

    flagged = np.flatnonzero(np.asarray(airborne, float) > 0.0)
    if not flagged.size:
        return []
    return [Flag("airborne_wheels",
                 f"{flagged.size} of {len(airborne)} events had a wheel airborne on the bridge for more than "
                 f"{AIRBORNE_FRACTION:.0%} of its time there (event variable airborne_wheels; first: event "
                 f"{int(flagged[0])}): their impact factors are dominated by the vehicles leaving and landing on the "
                 "road (point-contact impacts), so they are not design values, nor are the stream's statistics that "
                 "include them; the road is beyond the model's intended range", output="impact_factor",
                 subject=f"{flagged.size} events", threshold=AIRBORNE_FRACTION)]  # (value: a wheel's time share; not stored)


def _gross(record: VehicleRecord) -> float:
    return record.gross_weight if record.model == "axles" else float(_vehicle(record).total_weight)


def _interval_ends(name: str, interval) -> dict[str, float]:
    """The ends of ``name``'s confidence interval as the statistics' entries ``name_ci_lower``, ``name_ci_upper``
    (``name`` itself is the interval's estimate: the three from one sample)."""
    return {f"{name}_ci_lower": interval.lower, f"{name}_ci_upper": interval.upper}


def stream_statistics(ds) -> dict[str, Any]:
    """The stream's statistics from its dataset: event counts, the IM distribution (mean,
    standard deviation, 5/50/95/99 % quantiles, histogram), and the dynamic amplification of the
    event with the largest static effect (its R_dyn / R_st) and of the largest dynamic effect
    (the largest R_dyn of the stream over the largest R_st of the stream: the ratio of the
    governing total to the governing static load effect); at the first response point.  The governing
    events are those of the largest magnitudes; their deflections (``governing_static_deflection``,
    ``governing_dynamic_deflection`` [m]) keep the dataset's sign (z up: a downward deflection is negative,
    as every output of vbikit).

    An event without an impact factor there (NaN: no usable static reference) is left out of every IM
    statistic and counted, ``n_events_without_impact_factor``.  An event whose static peak there is below
    ``SMALL_STATIC_FRACTION`` (20 %) of the stream's largest (a light vehicle, or one in a far lane of a
    deck) has an IM resting on a small static reference, not a design value
    (``vbikit.analysis.checks.small_static``): ``n_small_static_events`` counts them (of the events with an
    IM), and ``im_mean_loaded`` / ``im_q95_loaded`` are the mean and 95 % quantile of the others — the
    ``n_events - n_events_without_impact_factor - n_small_static_events`` events that load the point.

    The means and 95 % quantiles are the estimates of their 95 % confidence intervals over those events
    (``…_ci_lower``, ``…_ci_upper``; ``vbikit.analysis.sample_intervals``: Student's t for a mean,
    order statistics for a quantile; NaN where the events cannot bound it), estimate and interval from
    the same sample: how well this many events fix each, the roads and trucks being random."""
    from vbikit.analysis.checks import SMALL_STATIC_FRACTION, small_static
    from vbikit.analysis.sample_intervals import mean_interval, quantile_interval

    if "point" in ds.dims:
        ds = ds.isel(point=0)
    im_events = np.asarray(ds["impact_factor"].values, float)
    dyn_signed = np.asarray(ds["max_dynamic_displacement"].values, float)
    st_signed = np.asarray(ds["max_static_displacement"].values, float)
    dyn, st = np.abs(dyn_signed), np.abs(st_signed)
    mp_events = np.asarray(ds["multiple_presence"].values, bool)
    # the governing events among those with a static peak (argmax would take a NaN's index)
    i_st = int(np.nanargmax(st)) if np.isfinite(st).any() else 0
    i_dyn = int(np.nanargmax(dyn)) if np.isfinite(dyn).any() else 0
    usable = np.isfinite(im_events)  # the events with an impact factor: the sample of every IM statistic
    im, mp = im_events[usable], mp_events[usable]
    loaded = ~np.array(small_static(st), bool)[usable]
    low, high = (float(im.min()), float(im.max())) if im.size else (0.0, 0.0)
    # bins of 0.05 (or wider), their edges rounded to the 12th decimal: 0.05, not linspace's 0.05000000000000002
    edges = np.round(np.linspace(min(-0.1, float(np.floor(low * 20) / 20)), max(1.0, float(np.ceil(high * 20) / 20)), 23), 12)
    counts, _ = np.histogram(im, edges)
    q = np.quantile(im, [0.05, 0.5, 0.99]) if im.size else np.full(3, math.nan)
    mean, q95 = mean_interval(im), quantile_interval(im, 0.95)
    mean_loaded, q95_loaded = mean_interval(im[loaded]), quantile_interval(im[loaded], 0.95)
    return {
        "n_events": int(im_events.size), "n_vehicles_total": int(ds.sizes["vehicle"]),
        "n_multiple_presence_events": int(mp_events.sum()),
        "n_events_without_impact_factor": int((~usable).sum()),
        "im_mean": mean.estimate, "im_std": float(im.std()) if im.size else math.nan,
        "im_q05": float(q[0]), "im_q50": float(q[1]), "im_q95": q95.estimate, "im_q99": float(q[2]),
        "im_mean_single": float(im[~mp].mean()) if (~mp).any() else math.nan,
        "im_mean_multiple": float(im[mp].mean()) if mp.any() else math.nan,
        "im_histogram_edges": [float(x) for x in edges], "im_histogram_counts": [int(c) for c in counts],
        "small_static_fraction": SMALL_STATIC_FRACTION, "n_small_static_events": int((~loaded).sum()),
        "im_mean_loaded": mean_loaded.estimate, "im_q95_loaded": q95_loaded.estimate,
        **_interval_ends("im_mean", mean), **_interval_ends("im_q95", q95),
        **_interval_ends("im_mean_loaded", mean_loaded), **_interval_ends("im_q95_loaded", q95_loaded),
        "governing_static_event": i_st,
        "governing_static_deflection": float(st_signed[i_st]),
        "governing_static_amplification": float(dyn[i_st] / st[i_st]),
        "governing_dynamic_event": i_dyn,
        "governing_dynamic_deflection": float(dyn_signed[i_dyn]),
        "governing_dynamic_amplification": float(dyn[i_dyn] / st[i_st]),
        "n_airborne_events": int(np.sum(np.asarray(ds["airborne_wheels"].values) > 0)) if "airborne_wheels" in ds else 0,
    }


@dataclass
class EventContext:
    """What every event of a stream shares (built once per process): the base scenario's crossing
    to put vehicles on (``template``), the scenario, its response plan and its road (``road(seed)``:
    the event's random road, or the fixed one).  ``EventContext.of(base, base_dir)`` builds it from
    a traffic base scenario; lifetime runs use it too.  A base scenario without ``crossing.run_in`` gets the
    population's (``settled``: ``vbikit.solve.run_in.population_run_in``, the trucks start as if they had
    driven ``SETTLED_APPROACH`` of the road) or, on a rough road, longer for an event whose vehicles need more to
    keep at most ``SETTLED_TRANSIENT_LEFT`` of their start transient (``settling``: a lighter damped vehicle), shortened
    on an event that would reach beyond the road (``road_range``, ``fit_run_in``; a run-in the base scenario gives
    is fitted alike, and not lengthened); ``run_in = 0`` there starts them at rest."""

    template: "_Template"
    scenario: Scenario
    plan: ResponsePlan
    random_road: bool
    _fixed_road: tuple = (None, None)
    #: whether the run-in is the population's (fitted to the road per event), not the base scenario's
    settled: bool = False
    #: x [m] of the first and last road stations an event may read (None: a smooth road, no end)
    road_range: Optional[tuple[float, float]] = None
    #: the shortest approach [m] with which a run-in can start (every contact point off the deck:
    #: ``RUN_IN_CLEARANCE`` beyond the deck's ends)
    least_approach: float = 0.0
    #: whether the two wheel lines read their own profiles (the road's ``road_right``: ``road_groups``)
    two_lines: bool = False

    @classmethod
    def of(cls, base: dict, base_dir: str) -> "EventContext":
        from vbikit.road.psd import random_road_range
        from vbikit.scenario.build import road_psd

        scenario = parse_scenario(template_data(base), base_dir)
        built: BuiltScenario = build(scenario)
        road = scenario.road
        random_road = road.profile_file is None and road.road_class != "none"
        crossing = built.crossing
        settled = "run_in" not in base.get("crossing", {})
        overhang = crossing.bridge.deck_overhang
        least_approach = least_run_in_approach(overhang)
        if settled:  # a population starts its trucks settled (population_run_in)
            crossing = dataclasses.replace(crossing, run_in=population_run_in(crossing.approach, overhang))
        elif crossing.run_in > 0 and crossing.approach < least_approach:
            raise ScenarioError(f"crossing.run_in = {crossing.run_in:g} m needs every contact point off the deck at the "
                                f"start: give crossing.approach >= {least_approach:g} m (the deck reaches "
                                f"{overhang:g} m beyond its supports; {RUN_IN_CLEARANCE:g} m for the tire patches), got "
                                f"{crossing.approach:g} m")
        fixed = [p for p in (built.crossing.road, built.crossing.road_right) if p is not None]
        road_range = (random_road_range(road_psd(road), road.spacing, road.length) if random_road else
                      (max(p.x[0] for p in fixed), min(p.x[-1] for p in fixed)) if fixed and road.profile_file else None)
        ctx = cls(_Template(dataclasses.replace(crossing, road=None, road_right=None)), scenario, built.plan,
                  random_road, settled=settled, road_range=road_range, least_approach=least_approach,
                  two_lines=built.crossing.road_right is not None)
        if not random_road:
            ctx._fixed_road = (built.crossing.road, built.crossing.road_right)
        return ctx

    def road(self, seed: int) -> tuple:
        if not self.random_road:
            return self._fixed_road
        spec = self.scenario.road.model_copy(update={"seed": int(seed)})
        left = build_road(spec, self.scenario)
        return left, build_right_road(spec, self.scenario, left)

    def crossing(self, motions: tuple[VehicleMotion, ...], seed: int) -> Crossing:
        """The vehicles ``motions`` on the template's bridge and the road of ``seed`` (a random road
        only over the range their contact points touch: the same road there as ``road(seed)``), with the
        run-in fitted to that road (``fit_run_in``): the population's, or longer for vehicles that need more
        (``settled_run_in``)."""
        bare = self.bare_crossing(motions)
        if not self.random_road:
            return dataclasses.replace(bare, road=self._fixed_road[0], road_right=self._fixed_road[1])
        return with_scenario_road(bare, self.scenario.road, self.scenario, seed)

    def bare_crossing(self, motions: tuple[VehicleMotion, ...]) -> Crossing:
        """The vehicles ``motions`` on the template's bridge with their run-in as ``crossing`` gives it (the
        population's or longer, ``settled_run_in``, fitted to the road, ``fit_run_in``), before any road is made."""
        bare = self.settled_run_in(self.template.with_vehicles(motions, None, None))
        if bare.run_in > 0 and self.road_range is not None:
            bare = fit_run_in(bare, self.road_range)
        return bare

    @property
    def rough(self) -> bool:
        """Whether the events' road is rough (random, or a measured profile): their vehicles have a start to settle."""
        return self.random_road or self._fixed_road[0] is not None

    @property
    def lengthens(self) -> bool:
        """Whether an event's run-in is lengthened for vehicles that need more (``settled_run_in``): the population's
        own run-in (not the base scenario's), a rough road, and an approach a run-in can start from."""
        return self.settled and self.rough and self.template.crossing.approach >= self.least_approach

    def start_settling(self, bare: Crossing, run_in: float = math.nan) -> tuple[float, float]:
        """``vbikit.solve.run_in.start_settling`` of an event's vehicles ``bare`` (no road needed: the events'
        own, ``rough``, ``two_lines``), judged with the run-in ``run_in`` [m] it ran with when given (a part
        written before the check was stored)."""
        crossing = dataclasses.replace(bare, run_in=float(run_in)) if math.isfinite(run_in) else bare
        return settling(crossing, self.two_lines) if self.rough else start_settling(crossing)

    def settled_run_in(self, bare: Crossing) -> Crossing:
        """``bare`` (an event's vehicles, no road yet) with the population's run-in lengthened, on a rough road, to
        the one with which each of its sprung vehicles keeps at most ``SETTLED_TRANSIENT_LEFT`` of its start transient
        at the bridge (``vbikit.solve.run_in.settling``, rounded up to the metre, at most ``MAX_RUN_IN``): the
        population's ``SETTLED_APPROACH`` was checked with stock trucks, and a lighter damped vehicle needs more.
        ``bare`` itself for a run-in the base scenario gives, an approach too short for one, a smooth road, moving
        forces, or vehicles that need no more (``lengthens``, ``vbikit.solve.run_in.lengthened_run_in``); a vehicle
        with an undamped mode the road excites never settles (left out of the run-in its event's other vehicles get:
        ``start_unsettled`` names it).  An approach of 100 m or more, for which the population's own run-in is 0, is
        lengthened alike."""
        if not self.lengthens:
            return bare
        run_in = lengthened_run_in(bare.run_in, settling(bare, self.two_lines, settleable=True)[1])
        return bare if run_in == bare.run_in else dataclasses.replace(bare, run_in=run_in)


#: road [m] a fitted run-in leaves between the road it reads and the road's first or last station (the
#: random road's window reaches a few steps beyond the points; ``fit_run_in``)
RUN_IN_ROAD_MARGIN = 1.0


def fit_run_in(crossing: Crossing, road_range: tuple[float, float]) -> Crossing:
    """``crossing`` with the longest run-in, up to its own, whose road (``Crossing.road_extent``) lies within
    ``road_range`` = (x_first, x_last) [m] less ``RUN_IN_ROAD_MARGIN`` (by bisection, to 0.01 m, on the
    short side): a population's run-in on an event that would drive beyond a short road (``road.length``
    of a random road, a measured profile's ends).  ``crossing`` itself when its run-in fits; without a run-in
    when the road does not hold the event without one either (the road's refusal then names it)."""
    lo, hi = road_range[0] + RUN_IN_ROAD_MARGIN, road_range[1] - RUN_IN_ROAD_MARGIN

    def fits(run_in: float) -> bool:
        shorter = crossing if run_in == crossing.run_in else dataclasses.replace(crossing, run_in=run_in)
        first, last = shorter.road_extent()  # (the crossing's own is kept: the road's window reads it again)
        return first >= lo and last <= hi

    if fits(crossing.run_in):
        return crossing
    if not fits(0.0):
        return dataclasses.replace(crossing, run_in=0.0)
    short, long_ = 0.0, crossing.run_in
    while long_ - short > 0.01:
        mid = 0.5 * (short + long_)
        short, long_ = (mid, long_) if fits(mid) else (short, mid)
    return dataclasses.replace(crossing, run_in=short)


@dataclass(frozen=True)
class _Template:
    """The base scenario's crossing (its bridge, tire and options) to put vehicles on."""

    crossing: Crossing

    def with_vehicles(self, motions: tuple[VehicleMotion, ...], road, road_right) -> Crossing:
        c = self.crossing
        return Crossing(c.bridge, vehicles=motions, tire=c.tire, road=road, road_right=road_right,
                        speed=max(m.speed for m in motions), approach=c.approach, run_in=c.run_in,
                        free_vibration=c.free_vibration,
                        dt=c.dt, integrator=c.integrator, loss_of_contact=c.loss_of_contact, resolve=c.resolve)


_CONTEXTS: dict[str, EventContext] = {}


def traffic_study(records: Sequence[VehicleRecord], base: dict, base_dir: str = ".", lanes: Optional[Sequence[float]] = None,
                  seed: int = 0, batch_size: int = 16, name: str = "", source: str = "",
                  outputs: Optional[Sequence[str]] = None, limits: Any = None) -> TrafficStudy:
    """Validate the stream against the base scenario and cut it into events (see the module
    docstring).  ``outputs``: the catalogue's outputs to reduce and store ([`vbikit.outputs`][vbikit.outputs];
    ``STREAM_OUTPUTS`` are added; None: all) — the responses and load effects no asked output reads
    are not computed.  ``limits``: the budget of one event's run (``vbikit.solve.budget.Limits``; None: the
    defaults), checked on the largest events before any is simulated (``TrafficStudy.check_budget``).
    Errors name the record's line."""
    selected = None
    if outputs is not None:
        try:
            asked = select_outputs(outputs, "outputs")
        except ValueError as err:
            raise StudyError(str(err)) from None
        selected = tuple(dict.fromkeys(STREAM_OUTPUTS + asked))
    if not records:
        raise StudyError(f"{source or 'records'}: the stream holds no vehicles")
    if batch_size < 1:
        raise StudyError(f"batch_size must be >= 1, got {batch_size}")
    try:
        resolve = base_resolve(base, selected)
    except ValueError as err:
        raise StudyError(str(err)) from None
    crossing_table = base.get("crossing") if isinstance(base.get("crossing"), dict) else {}
    if "resolve" not in crossing_table and resolve != "effects":  # only deflections asked: their step (as a study's)
        base = {**base, "crossing": {**crossing_table, "resolve": resolve}}
    ctx = EventContext.of(base, base_dir)
    bridge = ctx.template.crossing.bridge
    lanes = tuple(float(y) for y in (lanes if lanes is not None else default_lanes(bridge)))
    width = bridge.deck_width if isinstance(bridge, GirderDeck) else None
    lengths, sizes = [], []
    for r in records:
        where = f"{source or 'records'}:{r.line}" if r.line else f"record {r.id or '?'}"
        if r.lateral_offset is None and not 1 <= (r.lane or 0) <= len(lanes):
            raise StudyError(f"{where}: lane {r.lane} has no centre (lanes at y = {', '.join(f'{y:g}' for y in lanes)} m; "
                             "give --lanes or a lateral_offset column)")
        try:
            vehicle = _vehicle(r)
            sizes.append(3 * vehicle.n_dof + 2 * len(vehicle.wheels))
        except ValueError as err:
            raise StudyError(f"{where}: {err}") from None
        lengths.append(vehicle.length)
        if width is not None:  # wheels on the deck (their y mirrored when the vehicle drives -x)
            y = r.lateral_offset if r.lateral_offset is not None else lanes[r.lane - 1]
            sign = 1.0 if r.direction == "+x" else -1.0
            edge = max(abs(y + sign * w.lateral) for w in vehicle.wheels)
            if not edge <= width / 2:
                source_of_y = "lateral_offset" if r.lateral_offset is not None else f"lane {r.lane}"
                raise StudyError(f"{where}: {source_of_y} at y = {y:g} m puts wheels at y = {edge:.4g} m from the "
                                 f"centreline, off the {width:g} m wide deck")
    events: list[Event] = partition([r.time for r in records], [r.speed for r in records], lengths, bridge.span,
                                    bridge.deck_overhang)
    digest = hashlib.sha256(json.dumps([[r.id, r.time, r.lane, r.lateral_offset, r.direction, r.speed, r.model,
                                         list(r.axle_loads), list(r.axle_spacings)] for r in records]).encode()).hexdigest()
    job = TrafficStudy(tuple(records), dict(base), str(base_dir), lanes, int(seed), int(batch_size),
                       tuple(e.vehicles for e in events), tuple(e.start for e in events), name, source, digest,
                       outputs=selected, event_end=tuple(e.end for e in events), vehicle_size=tuple(sizes),
                       limits=limits, input_sha256=tuple(input_digests(input_paths(base, base_dir)).items()))
    job.check_budget()
    return job
