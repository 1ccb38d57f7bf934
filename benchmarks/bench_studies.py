"""The paper's whole numerical program (Figs. 5–8, 10, 11: 6 × 1440 = 8640 crossings) and the
speed-up of the batched solver over one-at-a-time crossings, measured in the same run.

    python benchmarks/bench_studies.py                    # whole program, 20 profiles, all cores
    python benchmarks/bench_studies.py --samples 5        # a quarter of it (extrapolated × 20/5)
    python benchmarks/bench_studies.py --baseline-samples 2 --workers 2

1. warm-up: one small study (numba compilation / cache load, reported separately);
2. the program with ``vbikit.study.run_study`` (batches of crossings sharing their set-up,
   ``--workers`` processes), total time and crossings per second, with the library's default
   integrator (exact modal stepping, which the paper studies use) and again with RK4, the paper's
   integrator (``--no-rk4`` skips it): the ratio and the largest IM difference, per crossing and in the
   figures' means over the profiles;
3. one-at-a-time on the same ``--workers`` processes: the program's first
   ``--baseline-samples`` profiles of every point (the same mix of bridges, tires and speeds),
   each crossing on its own (build the scenario, ``simulate``, ``point_response``, both impact
   factors — what a user loop over ``vbikit run`` does), one process pool for all; its
   crossings/s against the batched program's crossings/s is the program-level speed-up;
4. solver level, one process, no pools: the batch of Fig. 6 (n = 6, 75 km/h) that starts with a
   class C road (28 roads: batches hold 32 crossings, classes B–D × 20 seeds) through
   ``run_batch`` (shared set-up, roads as lanes of one kernel call) against the same crossings
   one at a time, and the batch split over 2 threads.

The studies of step 2 run one after another in this process, so they share the worker
processes (``run_study`` keeps them for the session), as the six paper commands do when run
from one Python session; step 3 uses its own pool.

Writes nothing but temporary datasets (deleted) and numba's cache.
"""
from __future__ import annotations

import argparse
import itertools
import os
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

FIGS = ("fig5", "fig6", "fig7", "fig8", "fig10", "fig11")


def _one_crossing(args):
    """One crossing the one-at-a-time way; returns its displacement IM."""
    from vbikit.analysis import point_response
    from vbikit.scenario import build, parse_scenario
    from vbikit.solve import simulate

    study, idx = args
    built = build(parse_scenario(study.scenario_dict(idx)))
    resp = point_response(simulate(built.crossing), built.response_x, built.response_y)
    return resp.displacement_impact.impact_factor, resp.strain_impact.impact_factor


def _batched(studies, workers, tmp, keep=None):
    from vbikit.study import run_study

    t0 = time.perf_counter()
    for k, study in enumerate(studies):
        ds = run_study(study, Path(tmp) / f"{k}-{time.time_ns()}.nc", workers=workers)
        if keep is not None:
            keep.append(ds["impact_factor"].load())
    return time.perf_counter() - t0


def _one_at_a_time(studies, workers):
    jobs = [(s, idx) for s in studies for idx in itertools.product(*(range(n) for n in s.shape))]
    t0 = time.perf_counter()
    with ProcessPoolExecutor(max_workers=workers) as pool:
        list(pool.map(_one_crossing, jobs, chunksize=8))
    return time.perf_counter() - t0, len(jobs)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--samples", type=int, default=20, help="road profiles per point in the program (paper: 20)")
    ap.add_argument("--baseline-samples", type=int, default=2, help="profiles per point for the speed-up comparison")
    ap.add_argument("--workers", type=int, default=os.cpu_count(), help="worker processes")
    ap.add_argument("--beam", action="store_true", help="beam stand-ins instead of the 3D bridges (Girder 4)")
    ap.add_argument("--no-rk4", action="store_true", help="skip the same program with RK4 (the ratio)")
    args = ap.parse_args()

    from vbikit.study.paper import paper_study

    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        _batched([paper_study("fig11", 1, args.beam)], 1, tmp)  # compiles / loads every kernel incl. disk tires
        print(f"warm-up (numba compile or cache load, 1 small study): {time.perf_counter() - t0:.1f} s")

        studies = [paper_study(f, args.samples, args.beam, integrator="exact") for f in FIGS]
        n = sum(s.size for s in studies)
        per_fig = {}
        ims: list = []
        t_all = time.perf_counter()
        for f, s in zip(FIGS, studies):
            per_fig[f] = _batched([s], args.workers, tmp, ims)
        total = time.perf_counter() - t_all
        scale = 20 / args.samples
        print(f"paper program, {args.samples} profiles per point: {n} crossings on {args.workers} workers "
              f"in {total:.1f} s = {n / total:.1f} crossings/s")
        print("  per figure: " + ", ".join(f"{f} {t:.1f} s" for f, t in per_fig.items()))
        if args.samples != 20:
            print(f"  extrapolated to the whole program (8640 crossings): {total * scale:.0f} s")
        print("  integrator: exact (the library default)")

        if not args.no_rk4:
            rk4 = [paper_study(f, args.samples, args.beam, integrator="rk4") for f in FIGS]  # the paper's integrator
            ims_rk4: list = []
            t_rk4 = sum(_batched([s], args.workers, tmp, ims_rk4) for s in rk4)
            diff = max(float(abs(a - b).max()) for a, b in zip(ims, ims_rk4))
            seed_axis = "sample"  # the road.seed axis of the datasets
            fig_diff = max(float(abs(a.mean(seed_axis) - b.mean(seed_axis)).max()) for a, b in zip(ims, ims_rk4))
            print(f"the same program with RK4 (the paper's integrator): {t_rk4:.1f} s = {n / t_rk4:.1f} crossings/s -> default {t_rk4 / total:.1f}x "
                  f"faster; IM differences: largest {diff:.1e} per crossing, {fig_diff:.1e} in the figures' means "
                  f"over the {args.samples} profiles")

        small = [paper_study(f, args.baseline_samples, args.beam) for f in FIGS]
        t_single, m = _one_at_a_time(small, args.workers)
        print(f"one-at-a-time, first {args.baseline_samples} profiles of every point ({m} crossings, "
              f"{args.workers} workers): {t_single:.1f} s = {m / t_single:.1f} crossings/s; "
              f"program-level speed-up of the batched runner: {(n / total) / (m / t_single):.2f}x")

        from vbikit.study.compute import run_batch

        s6 = paper_study("fig6", 20, args.beam)
        batch = next(b for b in s6.batches() if s6.scenario_dict(b[0])["tire"]["n_points"] == 6
                     and s6.scenario_dict(b[0])["crossing"]["speed_kmh"] == 75
                     and s6.scenario_dict(b[0])["road"]["class"] == "C")
        run_batch(s6, batch[:2])
        run_batch(s6, batch[:2], threads=2)
        t0 = time.perf_counter()
        run_batch(s6, batch)
        t_b = time.perf_counter() - t0
        t0 = time.perf_counter()
        for idx in batch:
            _one_crossing((s6, idx))
        t_s = time.perf_counter() - t0
        t0 = time.perf_counter()
        run_batch(s6, batch, threads=2)
        t_t = time.perf_counter() - t0
        print(f"solver level, one process, {len(batch)} roads (Fig. 6, n = 6, 75 km/h, class C): batched "
              f"{t_b:.2f} s, one-at-a-time {t_s:.2f} s, speed-up {t_s / t_b:.2f}x; batched on 2 threads {t_t:.2f} s")


if __name__ == "__main__":
    main()
