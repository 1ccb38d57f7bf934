"""The two jobs of a lifetime run for the study runner (``vbikit.study.run.run_study``: batches on
local processes or a Dask cluster, every finished batch stored, a killed run resumed).

* ``StaticJob``: work items are days.  Each day's traffic is drawn (``TrafficModel.day``), cut
  into events, and every event's exact static peak of every load effect computed
  (``vbikit.lifetime.influence``, ``vbikit.lifetime.peaks``); for every fatigue detail the day's
  stress history (the turning points of the events' static histories in time order, zero
  between events — the bridge is empty) is
  rainflow counted (``vbikit.fatigue.RainflowCounter``): the day's closed cycles (their Miner
  damage and histogram) and its residual, which ``vbikit.lifetime.fatigue_results`` joins
  across days exactly.
* ``DynamicJob``: work items are events (day, index in the day), simulated with the coupled
  engine as in ``vbikit.traffic.study``: the event's vehicles as axle trucks, each event on its
  own random road seeded ``derive_seed(seed, day · 2²⁰ + index)``.  Per event: the dynamic and
  static peak of every load effect (dynamic: mode acceleration for moments, shears and
  reactions; the modal deflection) and, per fatigue detail, the Miner damage of the event's
  dynamic and static stress histories counted alone.
"""
from __future__ import annotations

import bisect
import dataclasses
import hashlib
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

import numpy as np
from numpy.typing import NDArray

from vbikit.lifetime.influence import event_static
from vbikit.lifetime.setup import Setup, build_setup, day_events
from vbikit.lifetime.traffic import TrafficModel
from vbikit.study.shipping import reduce_once

def moving_forces(loads, spacings):
    """A truck as moving constant forces: each axle load split over two wheels at ± the
    half-track (``vbikit.lifetime.influence.HALF_TRACK``), no degrees of freedom."""
    from vbikit.lifetime.influence import HALF_TRACK
    from vbikit.vehicle.builder import VehicleBuilder

    vb = VehicleBuilder("moving-forces")
    s = 0.0
    for a, p in enumerate(loads):
        s += spacings[a - 1] if a else 0.0
        for side, y in (("left", HALF_TRACK), ("right", -HALF_TRACK)):
            vb.wheel(f"axle{a + 1}_{side}", {}, s, y, 0.0, 0.0, fixed_load=0.5 * float(p))
    return vb.build("moving axle forces", {})


def _axle_truck(loads, spacings):
    """``vbikit.vehicle.axle_truck`` with its defaults; a load split it cannot build (a tractor that
    cannot carry the semitrailer, an axle lighter than its default unsprung mass — generated or
    recorded traffic has such trucks) is built as a rigid truck, then with every unsprung mass at
    most 40 % of its axle's load.  The static axle loads stay exact in every case."""
    from vbikit.vehicle.axles import axle_truck

    try:
        return axle_truck(loads, spacings)
    except ValueError:
        pass
    try:
        return axle_truck(loads, spacings, tractor_groups=0)
    except ValueError:
        unsprung = [min(700.0 if a == 0 else 1100.0, 0.4 * p / 9.80665) for a, p in enumerate(loads)]
        return axle_truck(loads, spacings, tractor_groups=0, unsprung_masses=unsprung)


#: how a dynamic event's trucks are modelled (spec key ``vehicle_model``)
VEHICLE_MODELS = {"axle-truck": _axle_truck, "moving-forces": moving_forces}

#: [substitute] the fewest batches a dynamic round whose records are all stored is cut into: enough
#: for 2–8 workers to finish together (a week's round of 130 events was 7 day batches: 4 on one of
#: 2 workers, 3 on the other)
MIN_DYNAMIC_BATCHES = 16

#: events of a day are numbered below this (global event id = day · EVENT_STRIDE + index)
EVENT_STRIDE = 2**20


def _joined_parts(parts: Path, n_batches: int, complete=None) -> dict[str, NDArray]:
    """Every array of the finished parts (checked against their checksums), the batches' joined
    along their first axis in batch order (the runner's bookkeeping left out); ``complete``: called
    with each part's arrays first, to add what a part written by an earlier version lacks."""
    from vbikit.study.storage import load_part, part_checksums

    sums = part_checksums(parts)
    data: dict[str, list] = {}
    for k in range(n_batches):
        part = load_part(parts, k, sums)
        if complete is not None:
            part = complete(part)
        for name in part:
            if name not in ("batch_index", "spec_checksum"):
                data.setdefault(name, []).append(np.asarray(part[name]))
    return {k: np.concatenate(v, axis=0) for k, v in data.items()}


@dataclass(frozen=True)
class Detail:
    """A fatigue detail as the workers need it: its line index, stress per unit [Pa], S-N curve name, γ_Mf,
    bin [Pa] and the size-effect reduction k_s of an EN category (the curve of k_s·Δσ_C)."""

    name: str
    line: int
    factor: float
    curve: str
    gamma_mf: float
    bin: float
    size_factor: float = 1.0

    @property
    def label(self) -> str:
        """The curve as reports name it: the category, and with a size reduction k_s the reduced one
        ("EN 36 × k_s 0.5 = 18 MPa")."""
        if self.size_factor == 1.0 or not self.curve.upper().startswith("EN"):
            return self.curve
        from vbikit.fatigue import curve_name

        category = float(curve_name(self.curve).split()[1])
        return f"{self.curve} × k_s {self.size_factor:g} = {category * self.size_factor:.4g} MPa"

    @property
    def limit_name(self) -> str:
        """The name of the curve's constant-amplitude fatigue limit: EN 1993-1-9's Δσ_D, AASHTO's (ΔF)_TH."""
        return "Δσ_D" if self.curve.upper().startswith("EN") else "(ΔF)_TH"

    def sn(self):
        from vbikit.fatigue import curve_name, en1993_curve, sn_curve

        if not self.curve.upper().startswith("EN"):
            return sn_curve(self.curve)
        if self.size_factor == 1.0:
            return sn_curve(self.curve, self.gamma_mf)
        return en1993_curve(self.size_factor * float(curve_name(self.curve).split()[1]), self.gamma_mf)


def _digest(model: TrafficModel) -> str:
    return hashlib.sha256(repr(model).encode()).hexdigest()


#: days of traffic kept per process (a dynamic round revisits the days in order)
DAY_CACHE = 16
_DAYS: dict[tuple[str, int, int], tuple[list, list]] = {}


def day_traffic(model: TrafficModel, digest: str, setup: Setup, day: int, seed: int) -> tuple[list, list]:
    """(records, events) of ``day`` (the last few kept per process)."""
    key = (digest, int(day), int(seed))
    if key not in _DAYS:
        if len(_DAYS) >= DAY_CACHE:
            _DAYS.pop(next(iter(_DAYS)))
        records = model.day(day, seed)
        _DAYS[key] = (records, day_events(setup, records))
    return _DAYS[key]


@dataclass(frozen=True)
class StaticJob:
    """Every day's static pass (module docstring)."""

    model: TrafficModel
    setup_key: str
    n_days: int
    seed: int
    ds: float
    details: tuple[Detail, ...]
    days_per_batch: int = 1
    sample_fraction: float = 0.0
    store_top: int = 256
    name: str = "lifetime static pass"
    _digest: str = field(default="", repr=False)

    #: sent to workers as bytes made once, rebuilt once per worker (``vbikit.study.shipping``)
    __reduce__ = reduce_once

    @property
    def size(self) -> int:
        return self.n_days

    def batches(self) -> list[tuple[int, ...]]:
        k = self.days_per_batch
        return [tuple(range(d, min(d + k, self.n_days))) for d in range(0, self.n_days, k)]

    def to_json(self) -> str:
        return json.dumps({"kind": "vbikit lifetime static", "setup": self.setup_key, "traffic": self._digest,
                           "n_days": self.n_days, "seed": self.seed, "ds": self.ds, "peaks": "exact both directions",
                           "fatigue_top": "exact", "days_per_batch": self.days_per_batch,
                           "sample_fraction": self.sample_fraction, "store_top": self.store_top, "details": [d.__dict__ for d in self.details]}, sort_keys=True)

    def run_batch(self, batch: tuple[int, ...], threads: int = 1) -> dict[str, NDArray]:
        from vbikit.fatigue import RainflowCounter, miner_damage

        setup = build_setup(self.setup_key)
        curves = [d.sn() for d in self.details]
        out: dict[str, list] = {k: [] for k in ("ev_day", "ev_index", "ev_start", "ev_n_vehicles", "ev_gross_weight",
                                               "ev_static", "ev_static_opposite", "day", "day_trucks", "day_events",
                                               "day_damage_closed",
                                               "day_damage_alone", "day_max_range", "res_day", "res_detail", "res_value",
                                               "hist_day", "hist_detail", "hist_bin", "hist_count", "ev_sample",
                                               "rec_event", "rec_time", "rec_speed", "rec_lane", "rec_direction",
                                               "rec_n_axles", "rec_loads", "rec_spacings")}
        for day in batch:
            records, events = day_traffic(self.model, self._digest, setup, day, self.seed)
            statics = event_static(records, events, setup.lines, setup.span, setup.lanes, setup.pattern, self.ds,
                                   setup.tables, keep_histories=bool(self.details))
            n = len(events)
            gross = np.array([r.gross_weight for r in records])
            out["ev_day"].append(np.full(n, day, np.int64))
            out["ev_index"].append(np.arange(n, dtype=np.int64))
            out["ev_start"].append(np.array([records[m[0]].time for m in events]))
            out["ev_n_vehicles"].append(np.array([len(m) for m in events], np.int64))
            out["ev_gross_weight"].append(np.array([gross[list(m)].sum() for m in events]))
            out["ev_static"].append(statics.peaks.reshape(n, len(setup.lines)))
            out["ev_static_opposite"].append(statics.opposite.reshape(n, len(setup.lines)))
            # the random sample (each event with probability sample_fraction) and the records of the events the
            # dynamics may need (the sample and the store_top largest static peaks of each effect), so that the
            # dynamic rounds need not draw the day's traffic again
            sample = np.random.default_rng([int(self.seed), int(day), 0x66617469]).random(n) < self.sample_fraction
            out["ev_sample"].append(sample.astype(np.int8))
            keep = set(np.flatnonzero(sample).tolist())
            for j, line in enumerate(setup.lines):
                keep |= set(np.argsort(-line.sign * statics.peaks[:, j])[: self.store_top].tolist())
            for e in sorted(keep):
                for i in events[e]:
                    r = records[i]
                    out["rec_event"].append(np.array([day * EVENT_STRIDE + e], np.int64))
                    out["rec_time"].append(np.array([r.time]))
                    out["rec_speed"].append(np.array([r.speed]))
                    out["rec_lane"].append(np.array([r.lane], np.int64))
                    out["rec_direction"].append(np.array([1 if r.direction == "+x" else -1], np.int64))
                    out["rec_n_axles"].append(np.array([len(r.axle_loads)], np.int64))
                    out["rec_loads"].append(np.asarray(r.axle_loads, float))
                    out["rec_spacings"].append(np.asarray(r.axle_spacings, float))
            out["day"].append(np.array([day], np.int64))
            out["day_trucks"].append(np.array([len(records)], np.int64))
            out["day_events"].append(np.array([n], np.int64))
            closed, alone, top = [], [], []
            for j, (det, curve) in enumerate(zip(self.details, curves)):
                hist = statics.histories[det.line] * det.factor
                counter = RainflowCounter()
                # the events' histories in time order, each from 0 to 0 (the bridge is empty between events)
                if hist.size:
                    counter.feed(hist)
                state = counter.state
                closed.append(miner_damage(state.ranges, state.counts, curve, whole_spectrum=False) if state.ranges.size else 0.0)
                top.append(float(state.ranges.max()) if state.ranges.size else 0.0)  # exact, for the limit rule
                cyc = counter.finish()
                alone.append(miner_damage([c[0] for c in cyc], [c[1] for c in cyc], curve, whole_spectrum=False) if cyc else 0.0)
                out["res_day"].append(np.full(state.residual.size, day, np.int64))
                out["res_detail"].append(np.full(state.residual.size, j, np.int64))
                out["res_value"].append(state.residual)
                if state.ranges.size:
                    keys = np.floor(state.ranges / det.bin).astype(np.int64)
                    uk, inv = np.unique(keys, return_inverse=True)
                    cnt = np.bincount(inv, weights=state.counts)
                    out["hist_day"].append(np.full(uk.size, day, np.int64))
                    out["hist_detail"].append(np.full(uk.size, j, np.int64))
                    out["hist_bin"].append(uk)
                    out["hist_count"].append(cnt)
            out["day_damage_closed"].append(np.array(closed, float).reshape(1, len(self.details)))
            out["day_damage_alone"].append(np.array(alone, float).reshape(1, len(self.details)))
            out["day_max_range"].append(np.array(top, float).reshape(1, len(self.details)))
        res: dict[str, NDArray] = {}
        for k, v in out.items():
            if k in ("ev_static", "ev_static_opposite"):
                res[k] = np.concatenate(v, axis=0) if v else np.zeros((0, len(setup.lines)))
            elif k.startswith("day_damage") or k == "day_max_range":
                res[k] = np.concatenate(v, axis=0) if v else np.zeros((0, len(self.details)))
            else:
                ints = k in ("hist_bin", "ev_sample", "rec_event", "rec_lane", "rec_direction", "rec_n_axles") or \
                    k.endswith(("day", "detail"))
                res[k] = np.concatenate(v) if v else np.zeros(0, np.int64 if ints else float)
        return res

    def part_problem(self, part, batch: tuple[int, ...]) -> Optional[str]:
        for k in ("day", "ev_static", "ev_static_opposite", "day_damage_closed", "day_max_range", "res_value", "hist_count"):
            if k not in part:
                return f"it holds no {k}"
        if not np.array_equal(part["day"], np.array(batch, np.int64)):
            return "its days are not those of this batch"
        if not np.all(np.isfinite(part["ev_static"])):
            return "its static peaks are not finite"
        return None

    def assemble(self, parts: Path):
        import xarray as xr

        cat = _joined_parts(parts, len(self.batches()))
        ds = xr.Dataset({
            **{k: ("event", cat[k]) for k in ("ev_day", "ev_index", "ev_start", "ev_n_vehicles", "ev_gross_weight",
                                              "ev_sample")},
            **{k: ("rec", cat[k]) for k in ("rec_event", "rec_time", "rec_speed", "rec_lane", "rec_direction",
                                            "rec_n_axles")},
            "rec_loads": ("rec_axle", cat["rec_loads"]),
            "rec_spacings": ("rec_spacing", cat["rec_spacings"]),
            "ev_static": (("event", "line"), cat["ev_static"]),
            "ev_static_opposite": (("event", "line"), cat["ev_static_opposite"]),
            **{k: ("day", cat[k]) for k in ("day_trucks", "day_events")},
            **{k: (("day", "detail"), cat[k]) for k in ("day_damage_closed", "day_damage_alone", "day_max_range")},
            **{k: ("res", cat[k]) for k in ("res_day", "res_detail", "res_value")},
            **{k: ("hist", cat[k]) for k in ("hist_day", "hist_detail", "hist_bin", "hist_count")},
        }, coords={"day": cat["day"]}, attrs={"study": self.to_json()})
        return ds


@dataclass(frozen=True)
class DynamicJob:
    """Coupled dynamics of chosen events (module docstring); ``items``: global event ids, sorted."""

    model: TrafficModel
    setup_key: str
    seed: int
    items: tuple[int, ...]
    details: tuple[Detail, ...]
    batch_size: int = 8
    vehicle_model: str = "axle-truck"
    #: the records of each item's vehicles when the static pass stored them (else None: drawn again)
    event_records: tuple = field(default=(), repr=False, compare=False)
    #: the time step is the automatic one (``vbikit.solve.choose_time_step``) times this (0.5: the
    #: half-step re-run of the governing events)
    step_factor: float = 1.0
    name: str = "lifetime dynamics"
    _digest: str = field(default="", repr=False)

    #: sent to workers as bytes made once, rebuilt once per worker (``vbikit.study.shipping``)
    __reduce__ = reduce_once

    @property
    def size(self) -> int:
        return len(self.items)

    def batches(self) -> list[tuple[int, ...]]:
        """Up to ``batch_size`` events of one day each (a worker draws a day's traffic once per batch);
        when every event's records are stored (no day to draw), the events in order in equal batches
        of at most ``batch_size``, at least ``MIN_DYNAMIC_BATCHES`` of them (a round of a short run
        spread over every worker, not one batch per day)."""
        out: list[tuple[int, ...]] = []
        items = np.asarray(self.items, np.int64)
        if items.size and len(self.event_records) == items.size and all(r is not None for r in self.event_records):
            n_batches = max(-(-items.size // self.batch_size), min(items.size, MIN_DYNAMIC_BATCHES))
            return [tuple(part.tolist()) for part in np.array_split(items, n_batches)]
        days = items // EVENT_STRIDE
        for d in np.unique(days):
            of_day = items[days == d].tolist()
            out += [tuple(of_day[k:k + self.batch_size]) for k in range(0, len(of_day), self.batch_size)]
        return out

    def to_json(self) -> str:
        """The job's identity (the resume check); with the run-in its events start their trucks from (the
        population's when the base scenario gives none: work written before it, at rest, is not taken for it)."""
        run_in = float(build_setup(self.setup_key).context.template.crossing.run_in)
        return json.dumps({"kind": "vbikit lifetime dynamics", "setup": self.setup_key, "traffic": self._digest,
                           "seed": self.seed, "batch_size": self.batch_size, "vehicle_model": self.vehicle_model, "details": [d.__dict__ for d in self.details],
                           "run_in": run_in,
                           "items_sha256": hashlib.sha256(np.asarray(self.items, np.int64).tobytes()).hexdigest(),
                           "n_items": self.size, **({"step_factor": self.step_factor} if self.step_factor != 1.0 else {})},
                          sort_keys=True)

    @property
    def settles_vehicles(self) -> bool:
        """Whether the events drive their trucks a run-in first (sprung trucks, ``crossing.run_in`` > 0: the
        compiled run-in loops, ``vbikit.study.run.batch_kernels``)."""
        return self.vehicle_model == "axle-truck" and build_setup(self.setup_key).context.template.crossing.run_in > 0.0

    def crossing(self, g: int, road: bool = True):
        """The coupled crossing of global event ``g`` and its day's records (without ``road``: the crossing before
        its road is made, ``EventContext.bare_crossing``)."""
        from vbikit.solve import VehicleMotion
        from vbikit.study.spec import derive_seed
        setup = build_setup(self.setup_key)
        day, k = divmod(int(g), EVENT_STRIDE)
        stored = self.event_records[bisect.bisect_left(self.items, int(g))] if self.event_records else None
        if stored is not None:
            records, members = stored, tuple(range(len(stored)))
        else:
            records, events = day_traffic(self.model, self._digest, setup, day, self.seed)
            members = events[k]
        ctx = setup.context
        t0 = records[members[0]].time
        motions = []
        for i in members:
            r = records[i]
            y = r.lateral_offset if r.lateral_offset is not None else setup.lanes[r.lane - 1]
            motions.append(VehicleMotion(VEHICLE_MODELS[self.vehicle_model](r.axle_loads, r.axle_spacings), speed=r.speed, direction=r.direction,
                                         entry_time=r.time - t0, lateral_offset=y))
        crossing = ctx.crossing(tuple(motions), derive_seed(self.seed, int(g))) if road else \
            ctx.bare_crossing(tuple(motions))
        return crossing, records, members, t0

    def run_event(self, g: int) -> dict[str, NDArray]:
        from vbikit.analysis.effects import load_effect_responses
        from vbikit.analysis.response import point_response
        from vbikit.fatigue import miner_damage, rainflow, reversals
        from vbikit.lifetime.peaks import knot_limits
        from vbikit.solve import choose_time_step, simulate
        from vbikit.solve.run_in import start_settling

        setup = build_setup(self.setup_key)
        crossing, _, _, _ = self.crossing(g)
        if self.step_factor != 1.0:
            crossing = dataclasses.replace(crossing, dt=choose_time_step(crossing) * self.step_factor)
        result = simulate(crossing)
        dyn, st = [], []
        effect_at = [j for j, line in enumerate(setup.lines) if line.kind != "deflection"]
        responses = load_effect_responses(result, [setup.lines[j].effect for j in effect_at], check_step=False)
        # the total and static at the instants a wheel crosses the lines' jumps and kinks too (all
        # lines of the run at once: they share the run's state at their instants)
        limits = dict(zip(effect_at, knot_limits(result, [setup.lines[j].effect for j in effect_at],
                                                 [setup.tables[j] for j in effect_at],
                                                 [resp.dynamic for resp in responses], [resp.static for resp in responses])))
        for j, line in enumerate(setup.lines):
            if line.kind == "deflection":
                resp = point_response(result, line.x, line.y)
                dyn.append(resp.displacement)
                st.append(resp.static_displacement)
            else:
                _, h_dyn, h_st = limits[j]
                dyn.append(h_dyn)
                st.append(h_st)
        out = {"dyn_peak": np.array([s.sign * np.max(s.sign * d) for s, d in zip(setup.lines, dyn)]),
               "run_static_peak": np.array([s.sign * np.max(s.sign * h) for s, h in zip(setup.lines, st)])}
        d_dyn, d_st, top = [], [], []
        for det in self.details:
            curve = det.sn()
            for hist, acc in ((dyn[det.line], d_dyn), (st[det.line], d_st)):
                # the counting sees only the reversals (ASTM E1049-85 §5.4.4): reduced to them by numpy
                # first, the counter's own pass in Python runs over tens of points, not thousands
                cyc = rainflow(reversals(np.concatenate([[0.0], hist * det.factor, [0.0]])))
                acc.append(miner_damage([c[0] for c in cyc], [c[1] for c in cyc], curve, whole_spectrum=False) if cyc else 0.0)
                if acc is d_dyn:
                    top.append(max((c[0] for c in cyc), default=0.0))
        out["damage_dynamic"] = np.array(d_dyn)
        out["damage_static"] = np.array(d_st)
        out["max_range_dynamic"] = np.array(top)  # largest stress range of the dynamic history [Pa]
        # the road the event's trucks drove alone before the run (crossing.run_in: the population's, fitted to the
        # road; NaN for moving forces, which have nothing to settle)
        out["run_in"] = np.array(crossing.run_in if any(m.vehicle.n_dof for m in crossing.vehicles) else np.nan)
        left, needed = start_settling(crossing)  # (NaN for moving forces)
        out["start_transient_left"], out["start_settling_run_in"] = np.array(left), np.array(needed)
        out["n_steps"] = np.array(result.n_steps, float)
        out["unconverged_steps"] = np.array(result.unconverged_steps, float)  # (CrossingResult.unconverged_steps)
        return out

    def _with_start_settling(self, part: dict) -> dict:
        """A part's arrays with the start's settling of its events (``start_settling``) where it was written before
        they were stored: no simulation needed."""
        if "start_settling_run_in" in part:
            return part
        left, needed = self.start_settling(part["event_id"], part["run_in"])
        return {**part, "start_transient_left": left, "start_settling_run_in": needed}

    def start_settling(self, events, run_ins) -> tuple[NDArray, NDArray]:
        """``vbikit.solve.run_in.start_settling`` of each global event of ``events`` (its crossing only: no
        simulation), for events whose runs were stored before it was, judged with the run-in each ran with
        (``run_ins`` [m]; ``EventContext.start_settling``): (shares kept, run-ins needed [m])."""
        ctx = build_setup(self.setup_key).context
        both = np.array([ctx.start_settling(self.crossing(int(g), road=False)[0], float(r))
                         for g, r in zip(events, run_ins)], float).reshape(-1, 2)
        return both[:, 0], both[:, 1]

    def run_in_problem(self, events, run_ins) -> Optional[str]:
        """Whether stored runs of ``events`` ran with another run-in (``run_ins`` [m]) than this version gives them
        (``vbikit.solve.run_in.run_in_problem``): they are then run again."""
        from vbikit.solve.run_in import run_in_problem

        return run_in_problem(run_ins, [self.crossing(int(g), road=False)[0].run_in for g in events])

    def run_batch(self, batch: tuple[int, ...], threads: int = 1) -> dict[str, NDArray]:
        rows = [self.run_event(g) for g in batch]
        out = {k: np.stack([r[k] for r in rows]) for k in rows[0]}
        out["event_id"] = np.array(batch, np.int64)
        return out

    def part_problem(self, part, batch: tuple[int, ...]) -> Optional[str]:
        if "event_id" not in part or not np.array_equal(part["event_id"], np.array(batch, np.int64)):
            return "its events are not those of this batch"
        for k in ("dyn_peak", "run_static_peak", "damage_dynamic", "damage_static", "max_range_dynamic",
                  "unconverged_steps"):
            if k not in part or part[k].shape[0] != len(batch) or not np.all(np.isfinite(part[k])):
                return f"{k} is missing or not finite"
        if "run_in" not in part or part["run_in"].shape[0] != len(batch):
            return "it has no run_in (written by an earlier version)"
        return self.run_in_problem(batch, part["run_in"])

    def assemble(self, parts: Path):
        import xarray as xr

        cat = _joined_parts(parts, len(self.batches()), self._with_start_settling)
        return xr.Dataset({
            "dyn_peak": (("event", "line"), cat["dyn_peak"]),
            "run_static_peak": (("event", "line"), cat["run_static_peak"]),
            "damage_dynamic": (("event", "detail"), cat["damage_dynamic"].reshape(len(cat["event_id"]), -1)),
            "damage_static": (("event", "detail"), cat["damage_static"].reshape(len(cat["event_id"]), -1)),
            "max_range_dynamic": (("event", "detail"), cat["max_range_dynamic"].reshape(len(cat["event_id"]), -1)),
            "n_steps": ("event", cat["n_steps"]),
            "unconverged_steps": ("event", cat["unconverged_steps"]),
            "run_in": ("event", cat["run_in"]),
            "start_transient_left": ("event", cat["start_transient_left"]),
            "start_settling_run_in": ("event", cat["start_settling_run_in"]),
        }, coords={"event": cat["event_id"]}, attrs={"study": self.to_json()})
