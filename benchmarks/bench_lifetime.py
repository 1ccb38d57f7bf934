"""Lifetime run with screening + dynamics: ``--days`` of two-lane traffic (≈ 2,000 trucks a day
per lane) over the example bridge, against dynamics on every event, in one run.

    python benchmarks/bench_lifetime.py --days 365             # the year (target ≤ 30 min, ≤ 2 GB on 2 cores)
    python benchmarks/bench_lifetime.py --days 30              # a month; the year extrapolated
    python benchmarks/bench_lifetime.py --days 7 --baseline 100

1. traffic: the example's generator (examples/lifetime: fitted to its day of records) scaled to
   ``--trucks-per-day`` (default 4,000: two lanes × 2,000), seeded;
2. bridge: ``paper-bridge-2-beam`` (4 modes), point tires, ISO class B roads (each dynamic event
   its own), trucks as 3D axle-truck multibodies; effects: midspan moment, midspan deflection,
   entry reaction; one fatigue detail (EN 36) with ``--sample`` of the events simulated for the
   dynamic damage ratio; A = 0.6;
3. ``run_lifetime`` on ``--workers`` local processes: wall time, peak memory of this process and
   of its workers (resource.getrusage, ru_maxrss), events, fraction simulated dynamically,
   events/s of the static pass and of the whole run; its CPU time (this process's
   ``time.process_time`` and the workers' ``RUSAGE_CHILDREN`` once they have ended) and the year
   extrapolated from it on ``--workers`` idle cores (CPU / workers × 365 / days: on a shared
   machine the wall time follows the other jobs' load, the CPU time hardly);
4. baseline: ``--baseline`` events of day 0 simulated one by one in this process (dynamics on
   every event): events/s, and the time dynamics on every event of the run would take on the
   same workers — the ratio against the screened run.

Writes into a temporary folder (deleted) and numba's cache.
"""
from __future__ import annotations

import argparse
import json
import resource
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _args import benchmark_args  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def spec(days: int, trucks: float, sample: float, deck: bool = False) -> dict:
    if deck:  # (the 10-mode 3D deck of paper-bridge-2: the screening keeps more events, docs/lifetime.md)
        out = spec(days, trucks, sample)
        out["bridge"] = {"model": "paper-bridge-2", "n_modes": 10}
        out["load_effects"] = out["load_effects"][:2]
        return out
    return {"name": "benchmark", "seed": 2026, "days": days, "amplification": 0.6, "budget_hours": 100,
            "traffic": {"records": str(ROOT / "examples" / "lifetime" / "wim.csv"), "trucks_per_day": trucks},
            "bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "tire": {"model": "point"},
            "road": {"class": "B"}, "crossing": {"approach": 10},
            "load_effects": [{"kind": "moment", "x": 8.38, "name": "M_mid"}, {"kind": "deflection", "name": "w_mid"},
                             {"kind": "reaction", "support": 0, "name": "R_entry"}],
            "fatigue": {"dynamic_sample": sample,
                        "details": [{"name": "flange", "effect": "M_mid", "section_modulus": 0.05, "category": "EN 36"}]}}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--days", type=int, default=30)
    p.add_argument("--trucks-per-day", type=float, default=4000.0)
    p.add_argument("--sample", type=float, default=0.001, help="fraction of events simulated for fatigue")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--baseline", type=int, default=60, help="events of day 0 simulated one by one")
    p.add_argument("--deck", action="store_true", help="the 10-mode 3D deck of paper-bridge-2 (M_mid, w_mid) instead of the beam")
    p.add_argument("--json", type=Path, default=None, help="also write the numbers to this JSON file")
    args = benchmark_args(__doc__, "unused (one run)", p)

    import xarray as xr

    from vbikit.lifetime.run import dynamics_estimate, prepare, run_lifetime

    s = spec(args.days, args.trucks_per_day, args.sample, args.deck)
    with tempfile.TemporaryDirectory(prefix="vbikit-bench-lifetime-") as tmp:
        t0, p0 = time.perf_counter(), time.process_time()
        ds = run_lifetime(s, Path(tmp) / "out", workers=args.workers, figures=False)
        wall, cpu_self = time.perf_counter() - t0, time.process_time() - p0
        estimate = prepare(s, ".", workers=args.workers)
        with xr.open_dataset(Path(tmp) / "out" / "work" / "static.nc") as static:
            after_hours, after_events = dynamics_estimate(estimate, static.load())
    from vbikit.study import shutdown_workers

    shutdown_workers()  # the workers' CPU time and peak memory count once they have ended (RUSAGE_CHILDREN)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = cpu_self + kids.ru_utime + kids.ru_stime
    a = ds.attrs
    # baseline: dynamics on every event, measured on day 0's first events, one process
    prep = prepare(s, ".")
    job = prep.static_job()
    day0 = job.run_batch((0,))
    gid = (day0["ev_day"] * 2**20 + day0["ev_index"])[: max(1, args.baseline)]
    dyn = prep.dynamic_job(gid)
    dyn.run_event(int(gid[0]))  # warm-up (numba cache, the day's traffic)
    t1 = time.perf_counter()
    for g in gid:
        dyn.run_event(int(g))
    per_event = (time.perf_counter() - t1) / len(gid)
    every = per_event * a["n_events"] / args.workers
    me = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    kids = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    out = {
        "date": time.strftime("%Y-%m-%d"), "days": args.days, "workers": args.workers,
        "trucks": a["n_trucks"], "events": a["n_events"], "dynamic_events": a["n_dynamic_events"],
        "fraction_dynamic": a["fraction_dynamic"], "sample_events": a["n_sample_events"],
        "wall_s": wall, "estimate_before_s": estimate.estimate_hours * 3600,
        "estimate_after_static_s": after_hours * 3600, "estimate_after_static_events": after_events,
        "static_pass_s": a["time_static_s"], "static_events_per_s": a["events_per_second_static"],
        "events_per_s_overall": a["n_events"] / wall, "peak_rss_coordinator_MB": me, "peak_rss_worker_MB": kids,
        "baseline_dynamic_s_per_event_one_core": per_event, "every_event_estimate_s": every,
        "speedup_vs_every_event": every / wall, "year_extrapolated_s": wall * 365 / args.days,
        "cpu_s": cpu, "year_extrapolated_cpu_s_idle_cores": cpu / args.workers * 365 / args.days,
        "adr": dict(zip(map(str, ds["load_effect"].values), map(float, ds["assessment_dynamic_ratio"].values))),
    }
    print(json.dumps(out, indent=1))
    if args.json:
        args.json.write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
