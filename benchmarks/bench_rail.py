"""Ten HSLM-A trains × 200 speeds over a 20 m simply supported span with the fast moving-force
solver (``vbikit.solve.moving_loads`` through ``vbikit.rail.sweep``), against the same crossings one
at a time through ``vbikit.solve.simulate`` with a moving-force vehicle, in one run.

    python benchmarks/bench_rail.py                 # 2 workers, 40 baseline crossings
    python benchmarks/bench_rail.py --workers 1 --baseline 100

Bridge: span 20 m, EI = 7.9e10 N m², m = 25 t/m (n0 = 7.0 Hz), ζ = 1.3 % (Table 6.6 prestressed
concrete + Δζ), every mode up to max(30 Hz, 1.5 n0, n3) and at least 3 (here 3: 7.0, 28.0, 63.0 Hz —
n3 = 63 Hz governs).  Speeds: 200 from 100 to 420 km/h.  Response: peak acceleration at 9 deck
points, deflection, midspan moment and support shear (mode acceleration).  Both paths use the same
step (Δx / v with the sweep's Δx); the baseline runs the first ``--baseline`` (train, speed) pairs of
the sweep (spread over trains and speeds) and scales to 2000 crossings.
"""
from __future__ import annotations

import argparse
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _args import benchmark_args  # noqa: E402


def _beam():
    from vbikit.bridge.beam import EulerBernoulliBeam
    from vbikit.rail.codes import code_damping, frequency_limit

    span, EI, m = 20.0, 7.9e10, 25000.0
    zeta = code_damping("prestressed-concrete", span)
    probe = EulerBernoulliBeam(span, EI, m, zeta, n_modes=20)
    f = probe.frequencies_hz
    n = max(3, int((f <= frequency_limit(f) * (1 + 1e-12)).sum()))
    return EulerBernoulliBeam(span, EI, m, zeta, n_modes=n)


def _one(args):
    """One crossing through simulate: a moving-force vehicle with every axle of the train."""
    import numpy as np

    from vbikit.solve import Crossing, simulate
    from vbikit.vehicle.trains import hslm_a, train_vehicle

    k, v, dx, fv = args
    beam, train = _beam(), hslm_a(k)
    r = simulate(Crossing(beam, train_vehicle(train), speed=v, approach=0.0, dt=dx / v, free_vibration=fv))
    phi = beam.mode_shapes(np.linspace(0, 20, 11)[1:-1])
    return float(np.abs(r.xi_ddot @ phi.T).max())


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--baseline", type=int, default=40, help="crossings run one at a time through simulate")
    args = benchmark_args(__doc__, "repeats of the sweep (the fastest is reported)", p)
    import numpy as np

    from vbikit.rail.sweep import SweepSetup, sweep_moving_forces
    from vbikit.vehicle.trains import hslm_a
    from vbikit.solve.moving_loads import default_dx

    beam = _beam()
    trains = [hslm_a(k) for k in range(1, 11)]
    speeds = np.linspace(100, 420, 200) / 3.6
    dx = default_dx(beam, float(speeds.min()))
    fv = 1.0 / float(beam.frequencies_hz[0])
    setup = SweepSetup(beam, np.linspace(0, 20, 11)[1:-1], (("moment", 10.0), ("shear", 0.0)), dx, fv, 1e12)
    print(f"bridge: {beam.omega.size} modes {', '.join(f'{f:.1f}' for f in beam.frequencies_hz)} Hz, ζ = "
          f"{100 * beam.damping_ratio:.3f} %, Δx = {dx:.4f} m; {len(trains)} trains × {speeds.size} speeds")
    t0 = time.perf_counter()
    sweep_moving_forces(setup, trains[:1], speeds[:5], 1)  # warm-up: imports, scipy
    print(f"warm-up {time.perf_counter() - t0:.2f} s")
    best = float("inf")
    for _ in range(max(1, args.repeat)):
        t0 = time.perf_counter()
        envs = [env for env, _ in sweep_moving_forces(setup, trains, speeds, args.workers)]  # (envelopes, refined peaks)
        best = min(best, time.perf_counter() - t0)
    n = len(trains) * speeds.size
    print(f"fast sweep (with the peak refinement): {best:.2f} s for {n} crossings on {args.workers} workers "
          f"({1e3 * best / n:.2f} ms per crossing)")

    pairs = [(1 + (i % 10), float(speeds[(i * 37) % speeds.size])) for i in range(args.baseline)]
    jobs = [(k, v, dx, fv) for k, v in pairs]
    _one(jobs[0])  # warm-up (numba cache load)
    t0 = time.perf_counter()
    if args.workers > 1:
        with ProcessPoolExecutor(args.workers) as pool:
            peaks = list(pool.map(_one, jobs))
    else:
        peaks = [_one(j) for j in jobs]
    t_base = time.perf_counter() - t0
    per = t_base / len(jobs)
    print(f"simulate one at a time: {t_base:.2f} s for {len(jobs)} crossings ({1e3 * per:.1f} ms each on "
          f"{args.workers} workers) → {per * n:.0f} s for the whole sweep; ratio {per * n / best:.0f}×")
    worst = 0.0
    for (k, v), peak in zip(pairs, peaks):
        j = int(np.argmin(np.abs(speeds - v)))
        e = envs[k - 1]
        # simulate's peak is its largest sample: against the sweep's largest value read (its peak between the samples
        # less what a vertex moved it, ``acceleration_sampling_change``: a sample, or a one-sided limit at an axle's
        # passage, which may lie a little above simulate's samples)
        sampled = e.max_acceleration[j] * (1.0 - e.acceleration_sampling_change[j])
        worst = max(worst, abs(sampled.max() / peak - 1))
    print(f"largest relative difference of the sampled peak acceleration, fast vs simulate: {worst:.2e}")
    change = max(float(np.max(e.acceleration_sampling_change)) for e in envs)
    bound = max(float(np.max(e.acceleration_sampling_bound)) for e in envs)
    print(f"peaks between the time samples: the largest samples or limits up to {100 * change:.3f} % low, remaining error "
          f"bound up to {100 * bound:.3f} % (any train, speed and point)")


if __name__ == "__main__":
    main()
