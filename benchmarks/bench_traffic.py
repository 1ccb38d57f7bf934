"""A synthetic stream of 5,000 trucks over Bridge 2 (3D deck, two lanes, both directions) with
``vbikit traffic``'s machinery, against the same trucks simulated one at a time, in one run.

    python benchmarks/bench_traffic.py                       # 5000 trucks, 2 workers
    python benchmarks/bench_traffic.py --trucks 1000 --baseline 100
    python benchmarks/bench_traffic.py --spacing 0.05        # road sampled every 0.05 m
    python benchmarks/bench_traffic.py --outputs impact_factor   # only the outputs the statistics need

1. the stream: ``synthetic_stream`` (seed 2026), lane 1 +x and lane 2 −x, ``--flow`` trucks/h
   per lane, speeds 80 ± 8 and 75 ± 8 km/h, the documented truck mix (docs/traffic.md);
2. warm-up: a 20-truck stream through the same path (numba cache load, worker start-up),
   reported separately;
3. the stream with ``traffic_study`` + ``run_study`` (``--workers`` processes, batches of 16
   events): events (vehicles on the bridge together, simulated as one coupled run each), wall
   time, events/s and trucks/s; and its CPU time (this process's ``time.process_time`` and the
   workers' ``resource.getrusage(RUSAGE_CHILDREN)`` once they have ended, their start-up
   included) per event, with the events/s that CPU time allows on ``--workers`` idle cores — on
   a shared machine the wall time follows the other jobs' load, the CPU time hardly;
4. one-at-a-time: the first ``--baseline`` trucks, each alone on the bridge (one Crossing with
   one vehicle on the same bridge object, ``simulate``, the displacement IM), on the same number
   of processes: trucks/s, and the time the whole stream would take that way;
5. by event size (``--by-size N``, default 300; 0: skip): the stream's first N events in this
   process, each run once as the workers run it (``TrafficStudy.run_event``), thread CPU time of
   the whole event and of its step loop (the default's lean kernel, and ``kernels.implicit`` where the lean
   kernel hands over), grouped by the number of trucks on the bridge together: how much of the
   stream's cost the several-truck events are; and the share of their runs a truck spends between
   ``crossing.approach`` before its entry and its exit (weighted by its DOFs): the part of a
   several-truck run that integrates trucks far from the bridge is the rest.

Base scenario: ``paper-bridge-2`` (10 modes, 2 % damping), point tires, ISO class B road with a
new seed per event, ``--spacing`` m road samples (the scenario default is 0.01 m), response at
Girder 4 midspan; the trucks settled by the population's run-in (``--run-in 0``: at rest).  Writes only temporary datasets (deleted) and numba's cache.
"""
from __future__ import annotations

import argparse
import os
import resource
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _args import benchmark_args  # noqa: E402


def _base(spacing: float, run_in: float | None = None) -> dict:
    """The stream's base scenario; ``run_in`` [m]: its ``crossing.run_in`` (None: none given, the population's
    run-in, 100 m less the approach: the trucks start settled)."""
    return {"bridge": {"model": "paper-bridge-2", "n_modes": 10}, "tire": {"model": "point"},
            "road": {"class": "B", "spacing": spacing}, **({} if run_in is None else {"crossing": {"run_in": run_in}})}


def _stream(n: int, flow: float, seed: int = 2026):
    from vbikit.traffic import LaneTraffic, synthetic_stream

    return synthetic_stream([LaneTraffic(1, "+x", flow, 80, 8), LaneTraffic(2, "-x", flow, 75, 8)], n, seed=seed)


def _alone(args):
    """Trucks ``indices`` of the stream, each alone on the bridge (its own single-vehicle event)."""
    job, indices = args
    from vbikit.analysis import point_response
    from vbikit.solve import simulate
    from vbikit.traffic.study import EventContext  # noqa: F401  (the job's cached base: bridge built once)

    ctx = job.context()
    out = []
    for i in indices:
        r = job.records[i]
        from vbikit.solve import VehicleMotion
        from vbikit.traffic.study import _vehicle

        road, road_right = ctx.road(job.road_seed(0))
        crossing = ctx.template.with_vehicles(
            (VehicleMotion(_vehicle(r), r.speed, direction=r.direction, lateral_offset=job.lanes[r.lane - 1]),),
            road, road_right)
        result = simulate(crossing)
        out.append(point_response(result, None, float(crossing.bridge.girder_y[3])).displacement_impact.impact_factor)
    return out


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--trucks", type=int, default=5000)
    p.add_argument("--flow", type=float, default=600.0, help="trucks per hour and lane (default 600)")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--baseline", type=int, default=200, help="trucks run one at a time (default 200; 0: skip)")
    p.add_argument("--spacing", type=float, default=0.01, help="road sample spacing [m] (default 0.01, the scenario default)")
    p.add_argument("--outputs", default=None, help="outputs to reduce, comma-separated (default: the whole catalogue)")
    p.add_argument("--by-size", type=int, default=300, help="events timed in this process by trucks per event (default 300; 0: skip)")
    p.add_argument("--run-in", type=float, default=None,
                   help="crossing.run_in of the base scenario [m] (default: none given, the population's: the trucks "
                        "start settled; 0: at rest, as before 2026-12-06)")
    args = benchmark_args(__doc__, "unused (one timed run)", p)

    from vbikit.study.run import run_study, shutdown_workers
    from vbikit.traffic.study import traffic_study

    base = _base(args.spacing, args.run_in)
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        warm = traffic_study(_stream(20, args.flow, seed=1), base, batch_size=4)
        run_study(warm, Path(tmp) / "warm.nc", workers=args.workers)
        t_warm = time.perf_counter() - t0
        shutdown_workers()  # the warm-up's workers end here: their CPU time is not the stream's
        kids0 = resource.getrusage(resource.RUSAGE_CHILDREN)

        records = _stream(args.trucks, args.flow)
        t0 = time.perf_counter()
        job = traffic_study(records, base, batch_size=16,
                            **({} if args.outputs is None else {"outputs": args.outputs.split(",")}))
        t_setup = time.perf_counter() - t0
        t0, p0 = time.perf_counter(), time.process_time()
        ds = run_study(job, Path(tmp) / "stream.nc", workers=args.workers)
        t_stream, p_stream = time.perf_counter() - t0, time.process_time() - p0
        shutdown_workers()
        kids1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu_workers = (kids1.ru_utime + kids1.ru_stime) - (kids0.ru_utime + kids0.ru_stime)

    n_b = min(max(args.baseline, 0), len(records))
    t_alone = 0.0
    if n_b:
        chunks = [list(range(k, n_b, args.workers)) for k in range(args.workers)]
        with ProcessPoolExecutor(args.workers) as pool:
            list(pool.map(_alone, [(job, c[:2]) for c in chunks]))  # warm the pool (imports, numba cache)
            t0 = time.perf_counter()
            list(pool.map(_alone, [(job, c) for c in chunks]))
            t_alone = time.perf_counter() - t0

    n_ev = job.size
    n_mp = int(ds["multiple_presence"].sum())
    a = ds.attrs
    print(f"stream: {len(records)} trucks, flow {args.flow:g} /h per lane, road spacing {args.spacing} m, "
          f"{args.workers} workers, {os.cpu_count()} cores, outputs: {args.outputs or 'all'}")
    print(f"  warm-up (numba cache, workers) {t_warm:.1f} s; stream set-up (validation, events) {t_setup:.1f} s")
    print(f"  {n_ev} events ({n_mp} with several trucks, up to {int(ds['n_vehicles'].max())}), "
          f"{int(ds['n_steps'].mean())} steps a event on average")
    print(f"  stream: {t_stream:.1f} s = {n_ev / t_stream:.1f} events/s = {len(records) / t_stream:.1f} trucks/s "
          f"(target: under 180 s)")
    cpu = p_stream + cpu_workers
    print(f"  stream CPU: this process {p_stream:.1f} s + workers {cpu_workers:.1f} s = {cpu / n_ev * 1e3:.1f} ms an event "
          f"-> {n_ev / (cpu / args.workers):.0f} events/s on {args.workers} idle cores")
    if n_b:
        print(f"  one at a time ({n_b} trucks): {t_alone:.1f} s = {n_b / t_alone:.1f} trucks/s -> the whole stream "
              f"{len(records) / (n_b / t_alone):.0f} s")
    print(f"  IM: mean {a['im_mean']:.4f} (one truck {a['im_mean_single']:.4f}, several {a['im_mean_multiple']:.4f}), "
          f"95 % {a['im_q95']:.4f}; governing static event amplification {a['governing_static_amplification']:.4f}")
    if args.by_size > 0:
        _by_size(job, min(args.by_size, n_ev))


def _by_size(job, n: int) -> None:
    """Thread CPU time of the first ``n`` events (each run once) and of their step loops, by trucks per event."""
    from bench_per_crossing import _kernel_clock

    spent = _kernel_clock()
    job.run_event(0)  # this process's first event: bridge, tables and compiled kernels loaded
    rows: dict[int, list[tuple[float, float]]] = {}
    for e in range(1, n):
        k0, t0 = spent[0], time.thread_time()
        job.run_event(e)
        rows.setdefault(len(job.events[e]), []).append((time.thread_time() - t0, spent[0] - k0))
    total = sum(w for r in rows.values() for w, _ in r)
    print(f"  by trucks per event, events 1–{n - 1} in this process (thread CPU, each event run once):")
    for size in sorted(rows):
        whole = [w for w, _ in rows[size]]
        loop = [k for _, k in rows[size]]
        print(f"    {size} truck(s): {len(whole)} events, {1e3 * sum(whole) / len(whole):.2f} ms an event "
              f"(step loop {1e3 * sum(loop) / len(loop):.2f} ms), {100 * sum(whole) / total:.0f} % of the time")
    print(f"    all: {1e3 * total / (n - 1):.2f} ms an event")
    shares = _presence(job, range(1, n))
    print("    share of the run a truck is between its approach (crossing.approach before its entry) and its "
          "exit, weighted by its DOFs: " + ", ".join(f"{size} truck(s) {100 * shares[size]:.0f} %" for size in sorted(shares)))


def _presence(job, events) -> dict[int, float]:
    """Per number of trucks in an event: the mean over those events of the share of the run's time each
    truck spends between ``crossing.approach`` before its entry and the exit of its last axle, weighted by
    its DOFs (1 for one truck): how much of a several-truck run integrates trucks far from the bridge."""
    import numpy as np

    from vbikit.solve.plan import plan_run

    out: dict[int, list[float]] = {}
    for e in events:
        crossing = job.crossing(e)
        grid = plan_run(crossing).grid
        t0 = crossing.start_time
        t1 = t0 + grid.n_steps * grid.dt
        weighted = 0.0
        for i, m in enumerate(crossing.vehicles):
            exit_time = m.time_at(crossing.leaving_distance(np.flatnonzero(crossing.point_vehicle == i), m.sign))
            inside = min(exit_time, t1) - max(m.time_at(-crossing.approach), t0)
            weighted += max(inside, 0.0) / (t1 - t0) * m.vehicle.n_dof
        out.setdefault(len(crossing.vehicles), []).append(weighted / crossing.vehicle.n_dof)
    return {size: float(np.mean(v)) for size, v in out.items()}


if __name__ == "__main__":
    main()
