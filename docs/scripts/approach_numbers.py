"""How much a traffic event's impact factor depends on where its trucks start: the numbers of
docs/traffic.md's "Start from rest and the approach", stored in docs/figures/approach-numbers.json.

    python docs/scripts/approach_numbers.py                # about a minute on 2 cores
    python docs/scripts/approach_numbers.py --transients   # only the start transients and the lighter damped vehicle

Every run starts its vehicles at rest in static equilibrium ``crossing.approach`` before the bridge
(docs/theory.md, "Start and end of a crossing"); a truck that has driven on a rough road for long
carries a stationary vibration instead.  The start's transient decays with the truck's slowest
mode the road excites (σ_min ≈ 0.7–0.8 s⁻¹ for the stream's trucks), so it has not died out after a short approach.  Here
the same one-truck events (the first ``N`` of ``benchmarks/bench_traffic.py``'s stream: Bridge 2,
10 modes, point tires, 2 % damping, the stream's truck mix at 80 ± 8 and 75 ± 8 km/h), each on its
own road of the given ISO class, are run with the default approach (10 m) and with long ones
(100 m; 200 m for the convergence), the road being the same realisation (a longer approach reads
further back on it).  Reported per class: the mean, standard deviation and 95th percentile of the
deflection IM at Girder 4 midspan for each approach, the paired differences (mean with its
standard error, root mean square), the runs' mean steps, and the share of its start transient the truck keeps at
the bridge entry, exp(−σ_min · approach / v), averaged over the events (``start_transient_left``); then
(``run_in``) the same class B events started 10 m before the bridge after a 90 m run-in
(``crossing.run_in``) against the 100 m approach run coupled all the way; then (``settling``) how far they
must have driven: run-ins giving 25, 50, 100 and 200 m in all, each against 200 m (``SETTLED_APPROACH``); and
(``settling_spans``) whether that holds on other bridges: simply supported beams of 15, 30, 40 and 60 m whose first
frequencies (7, 2.2, 1.6 and 1.2 Hz) lie above, on and below the trucks' slowest modes the road excites (2.1–2.3
Hz), on class B (and the 40 m beam on class C), 50, 100 and 200 m in all against 400 m; and (``checked_transients``,
``transient_effect``) the share of its start transient each of those trucks kept and how an event's IM error grows
with it.
"""
from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
NUMBERS = ROOT / "docs" / "figures" / "approach-numbers.json"
#: (road class, events, approaches [m]) of the study
CASES = (("B", 300, (10.0, 100.0, 200.0)), ("C", 200, (10.0, 100.0)))
#: the road [m] driven before the bridge in all (the 10 m approach plus a run-in) whose settling is compared
SETTLING_TOTALS = (25.0, 50.0, 100.0, 200.0)
#: (span [m], first frequency [Hz], road class) of the beams of ``settling_spans``: 15 m above the trucks' slowest
#: modes the road excites (2.1–2.3 Hz), 30 m on them, 40 and 60 m below; 15,000 kg/m, EI from f1 (Eq. of a simply
#: supported beam, f1 = π/(2L²) √(EI/m)), 6 modes, 2 % damping
SPAN_CASES = ((15.0, 7.0, "B"), (30.0, 2.2, "B"), (40.0, 1.6, "B"), (60.0, 1.2, "B"), (40.0, 1.6, "C"))
#: the road [m] driven in all on the beams, the last the reference
SPAN_TOTALS = (50.0, 100.0, 200.0, 400.0)
#: one-truck events per beam case
SPAN_EVENTS = 100


def _base(road_class: str, approach: float, run_in: float = 0.0) -> dict:
    return {"bridge": {"model": "paper-bridge-2", "n_modes": 10}, "tire": {"model": "point"},
            "road": {"class": road_class, "spacing": 0.01}, "crossing": {"approach": approach, "run_in": run_in}}


def _beam(span: float, f1: float, road_class: str, total: float) -> dict:
    """The base scenario of a ``SPAN_CASES`` beam, its trucks started 10 m before it after ``total`` − 10 m of run-in."""
    mass = 15000.0
    stiffness = (f1 * 2.0 * span**2 / math.pi) ** 2 * mass  # f1 = π/(2L²) √(EI/m)
    return {"bridge": {"model": "beam", "span": span, "EI": stiffness, "mass_per_length": mass, "n_modes": 6},
            "tire": {"model": "point"}, "road": {"class": road_class, "spacing": 0.01, "length": 3000.0},
            "crossing": {"approach": 10.0, "run_in": total - 10.0}}  # (a long road: on the 60 m beam 15 trucks meet)


def _events(road_class: str, n: int, approach: float, run_in: float = 0.0,
            base: dict | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The deflection IMs of the stream's first ``n`` one-truck events, each truck's start transient
    left at its entry (exp(−σ_min (approach + run-in) / v), ``start_transient_left``) and each run's steps;
    ``base``: another base scenario (a beam: both lanes on its axis, more of the stream's trucks: more of them
    meet on a long beam)."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_traffic import _stream

    from vbikit.solve.run_in import start_transient_left
    from vbikit.traffic.study import traffic_study

    job = traffic_study(_stream((3 if base is None else 8) * n, 600.0), base or _base(road_class, approach, run_in), batch_size=16,
                        **({} if base is None else {"lanes": [0.0, 0.0]}))
    events = [e for e in range(job.size) if len(job.events[e]) == 1][:n]
    if len(events) < n:
        raise SystemExit(f"the stream has only {len(events)} one-truck events")
    im, left, steps = [], [], []
    for e in events:
        (points, row), _ = job.run_event(e)
        im.append(points[0]["impact_factor"])
        steps.append(row["n_steps"])
        left.append(start_transient_left(job.crossing(e)))  # exp(−σ_min (approach + run-in) / v)
    return np.array(im), np.array(left), np.array(steps, float)


def _stats(im: np.ndarray) -> dict:
    return {"mean": round(float(im.mean()), 4), "std": round(float(im.std(ddof=1)), 4),
            "q95": round(float(np.quantile(im, 0.95)), 4)}


def _paired(a: np.ndarray, b: np.ndarray) -> dict:
    d = b - a
    return {"mean": round(float(d.mean()), 4), "se": round(float(d.std(ddof=1) / math.sqrt(d.size)), 4),
            "rms": round(float(np.sqrt(np.mean(d**2))), 4)}


def _small_differences(a: np.ndarray, b: np.ndarray) -> dict:
    """``_paired`` to two significant digits (differences far below the rounding of ``_paired``), and the largest."""
    d = b - a
    two = lambda x: float(f"{x:.2g}")  # noqa: E731
    return {"mean": two(d.mean()), "se": two(d.std(ddof=1) / math.sqrt(d.size)), "rms": two(np.sqrt(np.mean(d**2))),
            "max": two(np.max(np.abs(d)))}


def compute() -> dict:
    out = {}
    for road_class, n, approaches in CASES:
        runs = {a: _events(road_class, n, a) for a in approaches}
        short, long_ = approaches[0], approaches[1]
        case = {"events": n, "approaches_m": list(approaches),
                "im": {f"{a:g}": _stats(runs[a][0]) for a in approaches},
                "start_transient_left": {f"{a:g}": round(float(runs[a][1].mean()), 3) for a in approaches},
                "mean_steps": {f"{a:g}": round(float(runs[a][2].mean())) for a in approaches},
                f"{long_:g}_minus_{short:g}": _paired(runs[short][0], runs[long_][0])}
        if len(approaches) > 2:
            case[f"{approaches[2]:g}_minus_{long_:g}"] = _paired(runs[long_][0], runs[approaches[2]][0])
        out[road_class] = case
    # the run-in (crossing.run_in, vbikit.solve.run_in): the default 10 m approach after 90 m driven alone, against
    # the 100 m approach run coupled all the way (the same events and roads)
    road_class, n, _ = CASES[0]
    im, _, steps = _events(road_class, n, 10.0, 90.0)
    reference = _events(road_class, n, 100.0)[0]
    out["run_in"] = {"road_class": road_class, "events": n, "approach_m": 10.0, "run_in_m": 90.0, "im": _stats(im),
                     "mean_steps": round(float(steps.mean())), "minus_100": _small_differences(reference, im)}
    # how far the trucks must have driven (approach + run-in, SETTLED_APPROACH): the 10 m approach after run-ins of
    # 15, 40, 90 and 190 m (25 … 200 m in all), each against the 200 m one, on the same events and roads
    runs = {total: _events(road_class, n, 10.0, total - 10.0) for total in SETTLING_TOTALS}
    settled = {total: run[0] for total, run in runs.items()}
    longest = settled[SETTLING_TOTALS[-1]]
    out["transient_effect"] = transient_effect({t: runs[t][1] for t in SETTLING_TOTALS[:-1]},
                                               {t: settled[t] - longest for t in SETTLING_TOTALS[:-1]})
    out["settling"] = {"road_class": road_class, "events": n, "approach_m": 10.0, "totals_m": list(SETTLING_TOTALS),
                       "mean": {f"{t:g}": round(float(settled[t].mean()), 4) for t in SETTLING_TOTALS},
                       f"minus_{SETTLING_TOTALS[-1]:g}": {f"{t:g}": _small_differences(longest, settled[t])
                                                           for t in SETTLING_TOTALS[:-1]}}
    # the same on beams below, on and above the trucks' slowest modes: 50, 100, 200 m in all against 400 m
    cases = []
    for span, f1, cls in SPAN_CASES:
        ims = {t: _events(cls, SPAN_EVENTS, 10.0, t - 10.0, _beam(span, f1, cls, t))[0] for t in SPAN_TOTALS}
        ref = ims[SPAN_TOTALS[-1]]
        cases.append({"span_m": span, "f1_hz": f1, "road_class": cls, "events": SPAN_EVENTS,
                                      "mean": round(float(ref.mean()), 4),
                                      f"minus_{SPAN_TOTALS[-1]:g}": {f"{t:g}": _small_differences(ref, ims[t])
                                                                      for t in SPAN_TOTALS[:-1]}})
    out["settling_spans"] = {"slowest_truck_mode_hz": _slowest_modes(), "cases": cases}
    out["checked_transients"] = checked_transients()
    out["lighter_damped"] = lighter_damped()
    return out


#: the preset of ``lighter_damped``: its slowest road-excited mode decays slower than every checked truck's
LIGHTER_PRESET = "two-axle"


def lighter_damped(n: int = 100) -> dict:
    """A vehicle outside the checked range (``LIGHTER_PRESET`` in place of each record's truck, the stream's times,
    lanes and speeds; Bridge 2, class B, a 3 km road): the first ``n`` one-vehicle events after 100 m in all (the 10
    m approach after the population's 90 m run-in) against 400 m — the share of its start transient each keeps
    at 100 m and the IM error, to set beside ``transient_effect``'s bins for the same share."""
    import dataclasses

    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_traffic import _stream

    from vbikit.solve.run_in import start_transient_left
    from vbikit.traffic.study import traffic_study

    records = [dataclasses.replace(r, model=LIGHTER_PRESET, axle_loads=(), axle_spacings=()) for r in _stream(3 * n, 600.0)]
    runs = {}
    for total in (100.0, 400.0):
        base = {**_base("B", 10.0, total - 10.0), "road": {"class": "B", "spacing": 0.01, "length": 3000.0}}
        job = traffic_study(records, base, batch_size=16)
        events = [e for e in range(job.size) if len(job.events[e]) == 1][:n]
        runs[total] = (np.array([job.run_event(e)[0][0][0]["impact_factor"] for e in events]),
                       np.array([start_transient_left(job.crossing(e)) for e in events]))
    left = runs[100.0][1]
    return {"preset": LIGHTER_PRESET, "events": n, "left_at_100_m": {"mean": round(float(left.mean()), 3),
                                                                      "min": round(float(left.min()), 3),
                                                                      "max": round(float(left.max()), 3)},
            "minus_400": _small_differences(runs[400.0][0], runs[100.0][0])}


#: the bins of the share of its start transient a truck keeps at the bridge (``transient_effect``)
TRANSIENT_BINS = (0.0, 0.035, 0.07, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 1.0)


def transient_effect(left: dict, error: dict) -> dict:
    """How an event's IM error depends on the share of its start transient its truck keeps at the bridge: the
    ``settling`` runs (25, 50 and 100 m in all; ``left``: each event's exp(−σ_min D / v), ``error``: its IM minus the
    200 m start's), pooled and binned by the share kept (``TRANSIENT_BINS``): events, root mean square and largest
    |error| per bin."""
    kept = np.concatenate([left[t] for t in left])
    err = np.abs(np.concatenate([error[t] for t in left]))
    bins = []
    for lo, hi in zip(TRANSIENT_BINS[:-1], TRANSIENT_BINS[1:]):
        m = (kept >= lo) & (kept < hi)
        if m.any():
            bins.append({"left": [lo, hi], "events": int(m.sum()), "rms": round(float(np.sqrt(np.mean(err[m] ** 2))), 4),
                         "max": round(float(err[m].max()), 4)})
    return {"totals_m": [float(t) for t in left], "bins": bins}


def checked_transients() -> dict:
    """The start transients of the trucks ``SETTLED_APPROACH`` was checked with (no simulation): of every one-truck
    event above that drove 100 m in all — the class B and C events on Bridge 2 and those of each beam of
    ``SPAN_CASES`` — the share of the start's transient its truck keeps at the bridge as the flag reads it
    (``vbikit.solve.run_in.start_transient_left``: exp(−σ_min · 100 m / v), σ_min the slowest decay rate of the modes
    the road excites) and that σ_min: the range a population's ``start_unsettled`` flag stays within
    (``vbikit.solve.run_in.SETTLED_TRANSIENT_LEFT``)."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_traffic import _stream

    from vbikit.solve.run_in import SETTLED_APPROACH, start_transient_left
    from vbikit.traffic.study import traffic_study

    jobs = [(traffic_study(_stream(3 * n, 600.0), _base(cls, 10.0, SETTLED_APPROACH - 10.0), batch_size=16), n)
            for cls, n, _ in CASES]
    jobs += [(traffic_study(_stream(8 * SPAN_EVENTS, 600.0), _beam(span, f1, cls, SETTLED_APPROACH), batch_size=16,
                            lanes=[0.0, 0.0]), SPAN_EVENTS) for span, f1, cls in SPAN_CASES]
    rates, left = [], []
    for job, n in jobs:
        for e in [e for e in range(job.size) if len(job.events[e]) == 1][:n]:
            left.append(start_transient_left(job.crossing(e)))
            rates.append(-math.log(left[-1]) * job.records[job.events[e][0]].speed / SETTLED_APPROACH)
    return {"events": len(left), "slowest_decay_rate_per_s": [round(min(rates), 3), round(max(rates), 3)],
            "transient_left_at_100_m": {"mean": round(float(np.mean(left)), 3), "max": round(max(left), 4)}}


def _slowest_modes() -> list[float]:
    """The lowest and highest undamped frequency [Hz] of the stream's trucks' slowest decaying mode that the road
    excites (``Vehicle.slowest_mode``, the wheels grouped by axle: one profile under both wheel lines) over its
    first 800 trucks."""
    from bench_traffic import _stream

    from vbikit.solve.run_in import road_groups
    from vbikit.traffic.study import _vehicle

    slowest = []
    for record in _stream(800, 600.0):
        truck = _vehicle(record)
        mode = truck.slowest_mode(road_groups(truck))
        if mode is not None:  # (a truck whose modes the road does not reach has none)
            slowest.append(abs(mode) / (2 * math.pi))
    return [round(min(slowest), 2), round(max(slowest), 2)]


def main() -> None:
    if "--transients" in sys.argv[1:]:  # only the start transients and the lighter damped vehicle (seconds)
        numbers = json.loads(NUMBERS.read_text()) | {"checked_transients": checked_transients(),
                                                     "lighter_damped": lighter_damped()}
    else:
        numbers = compute()
    NUMBERS.write_text(json.dumps(numbers, indent=1) + "\n")
    print(json.dumps(numbers, indent=1))


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT / "src"))
    main()
